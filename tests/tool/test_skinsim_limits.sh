#!/usr/bin/env bash
# skinsim run's limits on hostile mesh files (issue 14): --max-file-mb,
# --import-timeout, --import-mem-mb. Bad values get the one-line error (exit 2) of
# every flag; a limit a file breaks refuses it with one error naming the file and
# the limit (exit 2), and the same run without it works.
set -u
. "$(dirname "$0")/lib.sh"   # bld, src, exe, tmp, py, check
if ! "$exe" help | grep -q -- '--max-file-mb'; then echo "skinsim built without avatars: skipped"; exit 77; fi
bad() { # bad <description> <words wanted in the message> <args...>: exit 2, one line
  local what="$1" want="$2"; shift 2
  "$exe" "$@" > /dev/null 2> "$tmp/err"; local rc=$?
  check "$what: exit 2 ($rc), one line: $(head -c 150 "$tmp/err")" \
    "[ $rc -eq 2 ] && [ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q 'skinsim: ' '$tmp/err' && grep -q -- '$want' '$tmp/err'"
}
# a torso-sized octahedron-ish body mesh (OBJ) for the mannequin's URDF
cat > "$tmp/body.obj" <<'OBJ'
v 0 0 0.75
v 0.15 0 0.35
v 0 0.15 0.35
v -0.15 0 0.35
v 0 -0.15 0.35
v 0 0 -0.05
f 1 2 3
f 1 3 4
f 1 4 5
f 1 5 2
f 6 3 2
f 6 4 3
f 6 5 4
f 6 2 5
OBJ
urdf="$src/urdf/mannequin.urdf"
body=(run --urdf "$urdf" --mesh "$tmp/body.obj" --motion arms --frames 2)

for f in --max-file-mb --import-timeout --import-mem-mb; do
  bad "$f abc" "$f expects a number" "${body[@]}" "$f" abc
  bad "$f 0" "$f expects a number" "${body[@]}" "$f" 0
  bad "$f -5" "$f expects a number" "${body[@]}" "$f" -5
  bad "$f nan" "$f expects a number" "${body[@]}" "$f" nan
  bad "$f without a value" "$f needs a value" "${body[@]}" "$f"
  bad "$f with a built-in scene" "built-in scene reads none" run --scene fold --frames 1 "$f" 100
done
bad "--import-mem-mb 8 (under 16)" "from 16 to" "${body[@]}" --import-mem-mb 8
bad "--import-timeout 1e9" "from 0.1 to 86400" "${body[@]}" --import-timeout 1e9
bad "--max-file-mb 1e300" "from 1e-06 to" "${body[@]}" --max-file-mb 1e300

"$exe" "${body[@]}" > "$tmp/ok.txt" 2>&1; rc=$?
check "the body mesh loads with the default limits (exit $rc)" "[ $rc -eq 0 ]"
"$exe" "${body[@]}" --max-file-mb 1 --import-timeout 30 --import-mem-mb 2048 > "$tmp/ok2.txt" 2>&1; rc=$?
check "and within explicit limits (exit $rc)" "[ $rc -eq 0 ]"
# body.obj is about 130 bytes: a cap of 0.0001 MB (105 bytes) refuses it
bad "a mesh file over --max-file-mb" "body.obj. is 0.000[0-9]* MB, over the cap of 0.0001 MB: refused" \
  "${body[@]}" --max-file-mb 0.0001
bad "an asset over --max-file-mb" "over the cap of 0.0001 MB" \
  run --asset "$tmp/body.obj" --frames 1 --max-file-mb 0.0001
# the time limit: an import that cannot meet it on any machine. A 600 x 600 vertex
# grid (22 MB of OBJ) takes over 1 s to import on an idle machine here, ten times
# the 0.1 s limit (a real asset such as BCN_Epileptic.X imports in under 0.1 s on an
# idle machine, so it cannot show the limit reliably)
/usr/bin/python3 - "$tmp/big.obj" <<'PY'
import sys
n = 600
with open(sys.argv[1], "w") as f:
    for i in range(n):
        f.write("".join("v %g %g 0\n" % (i * 0.01, j * 0.01) for j in range(n)))
    for i in range(n - 1):
        for j in range(n - 1):
            a = i * n + j + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (a, a + 1, a + n + 1, a, a + n + 1, a + n))
PY
"$exe" run --asset "$tmp/big.obj" --frames 1 --import-timeout 0.1 > /dev/null 2> "$tmp/err"; rc=$?
check "--import-timeout 0.1 stops the import of a 22 MB OBJ (exit $rc): $(cat "$tmp/err")" \
  "[ $rc -eq 2 ] && [ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q 'longer than 0.1 s and was stopped' '$tmp/err'"
rm -f "$tmp/big.obj"
# the memory limit: a 200 x 200 vertex grid (2.3 MB of OBJ) needs more than 16 MB to
# import; with the default limit its import works (and the run stops later: the
# grid has no animation)
/usr/bin/python3 - "$tmp/grid.obj" <<'PY'
import sys
n = 200
with open(sys.argv[1], "w") as f:
    f.writelines("v %.5f %.5f 0\n" % (i / n, j / n) for j in range(n) for i in range(n))
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (a, a + 1, a + n + 1, a, a + n + 1, a + n))
PY
"$exe" run --asset "$tmp/grid.obj" --frames 1 --import-mem-mb 16 > /dev/null 2> "$tmp/err"; rc=$?
check "--import-mem-mb 16 makes the grid's import fail with one error, not the process (exit $rc): $(cat "$tmp/err")" \
  "[ $rc -eq 2 ] && [ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q 'grid.obj. cannot be imported' '$tmp/err'"
"$exe" run --asset "$tmp/grid.obj" --frames 1 > /dev/null 2> "$tmp/err"; rc=$?
check "with the default limit the grid imports (then: no animation; exit $rc): $(cat "$tmp/err")" \
  "[ $rc -eq 2 ] && grep -q 'has no animation' '$tmp/err'"
exit $fail
