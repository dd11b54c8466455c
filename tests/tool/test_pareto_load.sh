#!/usr/bin/env bash
# bench/pareto.py --load: saved rows are printed, their Pareto front found and
# their chart drawn without running anything; a configuration that is beaten on
# both speed and error is left off the front, and a missing file is one clear
# error (no traceback).
# Usage: test_pareto_load.sh BUILD_DIR SOURCE_DIR
set -u
. "$(dirname "$0")/lib.sh"   # bld, src, exe, tmp, py, check
$py -c 'import matplotlib' 2> /dev/null ||
  { echo "SKIP: python3-matplotlib missing (scripts/install_deps.sh installs it)"; exit 77; }

# four configurations: 2x2 and 4x2 on the front, 3x3 beaten by 4x2 (faster and
# more accurate), 1x8 beaten by 2x2; 4x1 and 4x2 drawn side by side
cat > "$tmp/rows.json" <<'JSON'
{"tris": 19000, "frames": 20, "threads": [1], "rows": [
 {"substeps": 1, "iterations": 8, "error": 0.81, "hash": null, "cpu1": 16.6, "wall1": 16.6, "its": 8.2},
 {"substeps": 2, "iterations": 2, "error": 0.63, "hash": null, "cpu1": 14.2, "wall1": 14.2, "its": 5.1},
 {"substeps": 3, "iterations": 3, "error": 0.42, "hash": null, "cpu1": 26.5, "wall1": 26.5, "its": 9.7},
 {"substeps": 4, "iterations": 1, "error": 0.45, "hash": null, "cpu1": 26.0, "wall1": 26.0, "its": 7.2},
 {"substeps": 4, "iterations": 2, "error": 0.36, "hash": null, "cpu1": 26.2, "wall1": 26.2, "its": 9.2}]}
JSON
$py "$src/bench/pareto.py" --load "$tmp/rows.json" --png "$tmp/p.png" > "$tmp/out" 2> "$tmp/err"; rc=$?
check "--load exits 0" "[ $rc -eq 0 ]" || cat "$tmp/err"
check "a line per saved configuration" "[ \$(grep -c '^substeps' '$tmp/out') -eq 5 ]"
check "the front is 2x2, 4x1 and 4x2 (1x8 and 3x3 are beaten)" \
  "grep -qx 'Pareto front (cpu ms at 1 thread(s) vs error): 2x2, 4x1, 4x2' '$tmp/out'" || cat "$tmp/out"
check "the chart is a PNG" "head -c 8 '$tmp/p.png' | od -An -c | grep -q 'P   N   G'"
$py "$src/bench/pareto.py" --load "$tmp/none.json" > "$tmp/out2" 2> "$tmp/err2"; rc=$?
check "a missing file: exit 2, one line naming it, no traceback" \
  "[ $rc -eq 2 ] && grep -q 'none.json' '$tmp/err2' && ! grep -q Traceback '$tmp/err2' && [ \$(wc -l < '$tmp/err2') -le 2 ]" ||
  cat "$tmp/err2"
$py "$src/bench/pareto.py" > /dev/null 2> "$tmp/err3"; rc=$?
check "neither binaries nor --load: a usage error" "[ $rc -eq 2 ] && grep -q 'SKINSIM and BENCH_SIM' '$tmp/err3'"
exit $fail
