#!/usr/bin/env bash
# The one settings table (include/skin_sim/ss_settings.h, `skinsim settings`) against
# what is written by hand elsewhere: every setting is an <arg> of launch/skin.launch
# with the table's default, passed to the node as <param> of the right type, its
# comment starting with the type; demo.launch, replay.launch and robot.launch repeat no
# default that disagrees; doc/ros.md's parameter table has a row `~name` with the
# table's type and default (that table is generated: bash scripts/doc_tables.sh; its
# exact text is checked by test_doc_tables.sh), and every other argument of skin.launch
# (the node's own parameters) has a row in doc/ros.md too; and skinsim takes every flag
# with the table's range (a value just outside is refused naming the flag, the bound
# inside is taken). Fails on any disagreement.
set -u
. "$(dirname "$0")/lib.sh"   # bld, src, exe, tmp, py, check

"$exe" settings --tsv > "$tmp/table.tsv"; rc=$?
check "skinsim settings --tsv exits 0" "[ $rc -eq 0 ]"
check "the table has the settings the issue names" \
  "for n in stiffness slide tether young poisson density damping bending gravity iterations \
   substeps method solver barycenters threads; do grep -q \"^\$n	\" '$tmp/table.tsv' || exit 1; done"
"$exe" settings > "$tmp/table.txt"
check "skinsim settings (for people) lists them too" "grep -q '^poisson ' '$tmp/table.txt'"

# launch files and doc/ros.md against the table
"$py" - "$tmp/table.tsv" "$src" <<'PY' > "$tmp/cmp.txt" 2>&1
import csv, math, re, sys, xml.etree.ElementTree as ET
rows = list(csv.DictReader(open(sys.argv[1]), delimiter='\t'))
src = sys.argv[2]
bad = []
def same(a, b, rel=0.0):
    a, b = a.strip().strip('"`'), b.strip().strip('"`')
    if a == b: return True
    try:
        x = [float(t) for t in a.split()]; y = [float(t) for t in b.split()]
    except ValueError:
        return a.lower() == b.lower()
    return len(x) == len(y) and all(u == v or (rel and abs(u - v) <= rel * max(abs(u), abs(v)))
                                    for u, v in zip(x, y))
skin = open(src + '/launch/skin.launch').read()
root = ET.fromstring(skin)
args = {a.get('name'): a.get('default') for a in root.iter('arg')}
params = {p.get('name'): p for p in root.iter('param')}
comments = dict(re.findall(r'<arg name="(\w+)"[^>]*/>\s*<!--\s*([^,:]+)', skin))
for r in rows:
    n, t, d = r['name'], r['type'], r['default']
    if n not in args: bad.append('skin.launch: no <arg name="%s">' % n); continue
    if not same(args[n], d): bad.append('skin.launch: %s default %s, table %s' % (n, args[n], d))
    p = params.get(n)
    if p is None or p.get('value') != '$(arg %s)' % n:
        bad.append('skin.launch: no <param name="%s" value="$(arg %s)">' % (n, n))
    elif p.get('type') not in (None, {'int': 'int', 'double': 'double', 'bool': 'bool', 'string': 'str'}[t]):
        bad.append('skin.launch: <param %s> type="%s", table %s' % (n, p.get('type'), t))
    elif t == 'double' and p.get('type') != 'double':
        bad.append('skin.launch: <param %s> needs type="double" (a default like 1 would be an int)' % n)
    if not comments.get(n, '').strip().startswith(t):
        bad.append('skin.launch: the comment of %s does not start with its type %s' % (n, t))
for other in ('demo.launch', 'replay.launch', 'robot.launch'):
    r2 = ET.fromstring(open(src + '/launch/' + other).read())
    for a in r2.iter('arg'):
        for r in rows:
            if a.get('name') == r['name'] and a.get('default') is not None and \
               not same(a.get('default'), r['default']):
                bad.append('%s: %s default %s, table %s' % (other, r['name'], a.get('default'), r['default']))
readme = open(src + '/doc/ros.md').read()
names = {r['name'] for r in rows}
for n in args:
    if n not in names and n not in ('name', 'output') and \
       not re.search(r'^\| `~%s` \|' % re.escape(n), readme, re.M):
        bad.append('doc/ros.md: no row for ~%s (an argument of skin.launch)' % n)
for r in rows:
    m = re.search(r'^\| `~%s` \| [^|]*\| (\w+), ([^|]*?)\s*\|' % re.escape(r['name']), readme, re.M)
    if not m: bad.append('doc/ros.md: no row for ~%s' % r['name']); continue
    t, rest = m.group(1), m.group(2)
    if t != r['type']: bad.append('doc/ros.md: ~%s is %s, table %s' % (r['name'], t, r['type']))
    dflt = rest.strip()
    if r['unit'] and dflt.endswith(r['unit']): dflt = dflt[:-len(r['unit'])]
    # a page may round (20.79 for 30 ln 2): 1e-3 relative
    if not same(dflt, r['default'], 1e-3):
        bad.append('doc/ros.md: ~%s default "%s", table %s' % (r['name'], rest, r['default']))
    if r['unit'] and r['unit'] not in rest:
        bad.append('doc/ros.md: ~%s says no unit %s' % (r['name'], r['unit']))
print('\n'.join(bad) if bad else 'all agree (%d settings)' % len(rows))
sys.exit(1 if bad else 0)
PY
rc=$?
cat "$tmp/cmp.txt"
check "skin.launch, demo.launch, replay.launch, robot.launch and doc/ros.md agree with the table" "[ $rc -eq 0 ]"

# skinsim's flags take the table's ranges (one range per setting)
while IFS=$'\t' read -r name flag type def range unit live help; do
  [ "$name" = name ] || [ -z "$flag" ] && continue
  case "$type" in
    int|double)
      lo=$(echo "$range" | sed -E 's/^[[(]([^,]*),.*/\1/'); hi=$(echo "$range" | sed -E 's/.*, ([^])]*)[])]$/\1/')
      if [ "${range:0:1}" = "[" ] && [ "$lo" != "-inf" ]; then
        "$exe" run --scene fold --tris 300 --frames 1 "$flag" "$lo" > /dev/null 2>&1; rc=$?
        check "$flag $lo (the lower bound) is taken" "[ $rc -eq 0 ] || [ $rc -eq 1 ]"
        below=$("$py" -c "print(int($lo) - 1 if '$type' == 'int' else -1e-9 if float($lo) == 0 else float($lo) * 0.999)")
        "$exe" run --scene fold --tris 300 --frames 1 "$flag" "$below" > /dev/null 2> "$tmp/err"; rc=$?
        check "$flag $below (below the range) is refused naming it" \
          "[ $rc -eq 2 ] && grep -q -- '$flag' '$tmp/err' && grep -q -- '$name' '$tmp/err'"
      fi
      if [ "${range: -1}" = ")" ] && [ "$hi" != "inf" ]; then
        "$exe" run --scene fold --tris 300 --frames 1 "$flag" "$hi" > /dev/null 2> "$tmp/err"; rc=$?
        check "$flag $hi (the excluded upper bound) is refused" "[ $rc -eq 2 ] && grep -q -- '$name' '$tmp/err'"
      fi ;;
  esac
done < "$tmp/table.tsv"
"$exe" run --scene fold --tris 300 --frames 1 --poisson 0.4999 > /dev/null 2>&1; rc=$?
check "--poisson 0.4999 is taken (the core's [0, 0.5), no longer the CLI's own 0.499)" "[ $rc -ne 2 ]"
"$exe" run --scene fold --tris 300 --frames 1 --method crawl > /dev/null 2> "$tmp/err"; rc=$?
check "--method crawl is refused naming the choices" "[ $rc -eq 2 ] && grep -q 'walk, project, nring' '$tmp/err'"
"$exe" run --scene fold --tris 300 --frames 1 --gravity '0 0 nan' > /dev/null 2> "$tmp/err"; rc=$?
check "--gravity '0 0 nan' is refused naming gravity" "[ $rc -eq 2 ] && grep -q 'gravity' '$tmp/err'"
"$exe" help > "$tmp/help"
check "skinsim help lists every flag of the table" \
  "cut -f2 '$tmp/table.tsv' | tail -n +2 | grep -v '^$' | while read f; do grep -q -- \"\$f \" '$tmp/help' || exit 1; done"
exit $fail
