#!/usr/bin/env bash
# skinsim run: the JSON summary has every field the issue names, the same
# command twice gives the same final_hash (determinism), --out writes a
# readable PLY of skin and body per frame, and bad input gets one clear
# error (exit 2, no crash).
set -u
. "$(dirname "$0")/lib.sh"   # bld, src, exe, tmp, py, check

"$exe" run --scene fold --tris 800 --frames 6 --json "$tmp/a.json" --out "$tmp/out" > /dev/null; rc=$?
check "run exits 0" "[ $rc -eq 0 ]"
for k in scene method triangles vertices anchors frames ms_per_frame_median walk_ms_per_frame_median \
         walk_share solver iterations_mean snags failures min_area_ratio max_area_ratio hug_rms \
         hug_max final_hash inverted_faces_max inside_max slide_max slide_max_m tether settle; do
  check "run JSON has $k" "grep -q '\"$k\":' '$tmp/a.json'"
done
check "run JSON: 6 frames of walk with quasi-newton, finite numbers" \
  "$py -c 'import json,sys,math; d=json.load(open(\"$tmp/a.json\")); sys.exit(0 if d[\"frames\"]==6 and d[\"method\"]==\"walk\" and d[\"solver\"]==\"quasi-newton\" and all(v is not None for v in d.values()) else 1)'"
"$exe" run --scene fold --tris 800 --frames 6 --json "$tmp/b.json" > /dev/null
check "same command twice: same final_hash" \
  "$py -c 'import json,sys; a=json.load(open(\"$tmp/a.json\")); b=json.load(open(\"$tmp/b.json\")); sys.exit(0 if a[\"final_hash\"]==b[\"final_hash\"] else 1)'"
"$exe" run --scene fold --tris 800 --frames 6 --solver newton --json "$tmp/n.json" > /dev/null; rc=$?
check "newton runs" "[ $rc -eq 0 ] && grep -q '\"solver\": \"newton\"' '$tmp/n.json'"
check "--out wrote 6 skin and 6 body frames" \
  "[ \$(ls '$tmp/out' | grep -c '^skin_.*\.ply$') -eq 6 ] && [ \$(ls '$tmp/out' | grep -c '^body_.*\.ply$') -eq 6 ]"
check "PLY frame parses: counts match the header, finite positions, each skin vertex's anchor face a body face" "$py - '$tmp/out/skin_0006.ply' '$tmp/a.json' '$tmp/out/body_0006.ply' <<'PY'
import json, math, struct, sys
def parse(path):
    data = open(path, 'rb').read()
    head, body = data.split(b'end_header\n', 1)
    lines = head.decode().splitlines()
    nv = int([l for l in lines if l.startswith('element vertex')][0].split()[2])
    nf = int([l for l in lines if l.startswith('element face')][0].split()[2])
    return lines, body, nv, nf
lines, body, nv, nf = parse(sys.argv[1])
assert 'property int anchor_face' in lines, lines
assert len(body) == nv * 16 + nf * 13, (len(body), nv, nf)
rec = [struct.unpack_from('<fffi', body, 16 * v) for v in range(nv)]
assert all(math.isfinite(c) for r in rec for c in r[:3])
d = json.load(open(sys.argv[2]))
assert nv == d['vertices'] and nf == d['triangles']
blines, bbody, bnv, bnf = parse(sys.argv[3])
assert len(bbody) == bnv * 12 + bnf * 13, (len(bbody), bnv, bnf)
assert all(0 <= r[3] < bnf for r in rec), 'anchor face out of the body'
PY"

# bench/inside_view.py reads the frames and splits the skin inside the body as the run
# measures it (the anchor faces in the skin files): the same counts and depth
"$exe" run --scene elbow --tris 1000 --frames 30 --inside-every 30 --json "$tmp/ev.json" \
  --out "$tmp/ev" > /dev/null 2>&1
"$py" "$src/bench/inside_view.py" "$tmp/ev" 30 "$tmp/ev.png" > "$tmp/ev.txt" 2>&1
check "inside_view.py: the run's clean counts and depth at frame 30, and a picture" "$py - '$tmp/ev.json' '$tmp/ev.txt' '$tmp/ev.png' <<'PY'
import json, os, re, sys
d = json.load(open(sys.argv[1]))
t = open(sys.argv[2]).read()
m = re.search(r'inside (\d+) of \d+; clean \d+ \(deepest ([\d.]+) edges, >0.05: (\d+), >0.1: (\d+)\)', t)
assert m, t
assert d['inside_samples'] == 1 and d['inside_count_max'] > 0, d
assert int(m.group(1)) == d['inside_count_max'], (m.group(1), d['inside_count_max'])
assert abs(float(m.group(2)) - d['inside_clean_max']) < 2e-3, (m.group(2), d['inside_clean_max'])
assert (int(m.group(3)), int(m.group(4))) == (d['inside_clean_over_005_max'], d['inside_clean_over_01_max']), t
assert os.path.getsize(sys.argv[3]) > 10000
PY"

"$exe" run --scene fold --tris 300 --frames 4 --settle 0.5 --tether 3 --json "$tmp/r.json" \
  --out "$tmp/rout" > /dev/null; rc=$?
check "--settle: rest return fields, 1 s blend + 0.5 s hold = 45 frames, walk clean" \
  "[ $rc -eq 0 ] && $py -c 'import json,sys; d=json.load(open(\"$tmp/r.json\")); sys.exit(0 if d[\"settle_frames\"]==45 and d[\"rest_error_max\"]>=d[\"rest_error_rms\"]>=0 and d[\"rest_error_max_m\"]>=0 and d[\"tether\"]==3 and d[\"snags\"]==0 and d[\"failures\"]==0 else 1)'"
check "--out with --settle writes the settling frames too" "[ -s '$tmp/rout/skin_0049.ply' ]"

bad() { # bad <description> <args...>: exit 2, one line on stderr naming the problem
  local what="$1"; shift
  "$exe" "$@" > /dev/null 2> "$tmp/err"; local rc=$?
  check "$what: exit 2" "[ $rc -eq 2 ]"
  check "$what: one message" "[ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q 'skinsim: ' '$tmp/err'"
}
bad "run without scene" run
bad "run unknown solver" run --scene fold --solver magic
bad "run negative dt" run --scene fold --dt -1
bad "run slide out of range" run --scene fold --slide -1
bad "run substeps zero" run --scene fold --substeps 0
bad "run negative tether" run --scene fold --tether -1
bad "run negative settle" run --scene fold --settle -2
bad "run NaN tol" run --scene fold --tol nan
bad "run unknown scene" run --scene nowhere
bad "run unwritable out" run --scene fold --frames 1 --out /proc/no/such/dir
# --out naming a file: refused before the first step (a run of 100000 frames would not
# end within the timeout), nothing written next to it
touch "$tmp/a_file"
timeout 60 "$exe" run --scene quadruped --frames 100000 --out "$tmp/a_file" > /dev/null 2> "$tmp/err"; rc=$?
check "--out FILE: exit 2 at once" "[ $rc -eq 2 ]"
check "--out FILE: one message saying it is not a folder" \
  "[ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q \"is not a folder\" '$tmp/err'"
cat "$tmp/err"
# a run whose frames fail exits 1, says so in one line and still writes its JSON
# (no membrane under a fast twist: triangles crushed past the area-ratio bounds)
"$exe" run --scene twist --young 0 --frames 60 --json "$tmp/f.json" > /dev/null 2> "$tmp/err"; rc=$?
check "failing frames: exit 1" "[ $rc -eq 1 ]"
check "failing frames: one message counting them" \
  "[ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q 'run failed: [0-9]* of 60 frames failed' '$tmp/err'"
check "failing frames: JSON written with failures > 0" \
  "$py -c 'import json,sys; sys.exit(0 if json.load(open(\"$tmp/f.json\"))[\"failures\"] > 0 else 1)'"
cat "$tmp/err"
exit $fail
