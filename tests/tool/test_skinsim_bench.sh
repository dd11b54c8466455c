#!/usr/bin/env bash
# skinsim bench --quick into a temporary folder: every chart, both Markdown
# tables and the CSV exist; the CSV has a row for every anchor method and
# every body (built-in scenes and avatars), with error_vs_reference filled in;
# --sweeps runs and draws only the named sweeps.
# Usage: test_skinsim_bench.sh BUILD_DIR SOURCE_DIR
set -u
. "$(dirname "$0")/lib.sh"   # bld, src, exe, tmp, py, check
/usr/bin/python3 -c 'import matplotlib' 2> /dev/null ||
  { echo "SKIP: python3-matplotlib missing (scripts/install_deps.sh installs it)"; exit 77; }

# BLAS threads only slow the references' small factorisations down here
start=$(date +%s)
OPENBLAS_NUM_THREADS=1 "$exe" bench --quick --out "$tmp/out" --cache "$tmp/cache" \
  --plot-script "$src/scripts/plot_bench.py" 2> "$tmp/err"; rc=$?
echo "bench --quick: exit $rc in $(( $(date +%s) - start )) s"
check "bench --quick exits 0" "[ $rc -eq 0 ]" || tail -n 20 "$tmp/err"
check "a progress line per run on stderr" "grep -q '^\[1/' '$tmp/err'"
for f in results.csv pareto.png stability.png stability.md scaling.png breakdown.png \
         options.png options.md pareto_reference.png rest_return.png; do
  check "$f written and not empty" "[ -s '$tmp/out/$f' ]"
done
for f in pareto pareto_reference stability scaling breakdown options rest_return; do
  check "$f.png is a PNG" "head -c 8 '$tmp/out/$f.png' | od -An -c | grep -q 'P   N   G'"
done
scenes=$("$exe" scenes | awk 'NR > 1 {print $1}' | tr '\n' ' ')
check "CSV: a row per method and body, errors filled, every field of run --json" "/usr/bin/python3 - '$tmp/out/results.csv' $scenes <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
bodies = sys.argv[2:] + ['demo']
import os
if os.path.exists('/usr/share/assimp/models/X/BCN_Epileptic.X'):
    bodies.append('BCN_Epileptic.X')
methods = ['walk', 'project', 'nring1', 'nring2', 'nring4']
def label(r):
    return r['method'] + (r['nring_rings'] if r['method'] == 'nring' else '')
have = {(r['scene'], label(r)) for r in rows if r['sweep'] == 'methods'}
missing = [(b, m) for b in bodies for m in methods if (b, m) not in have]
need = ['sweep', 'scene', 'method', 'solver', 'triangles', 'frames', 'substeps', 'iterations',
        'ms_per_frame_median', 'walk_ms_per_frame_median', 'assemble_ms_per_frame_median',
        'factor_ms_per_frame_median', 'solve_ms_per_frame_median', 'snags', 'failures',
        'hug_rms', 'hug_max', 'final_hash', 'error_vs_reference', 'reference_cache_hit',
        'error_vs_truth', 'inverted_faces_max', 'inside_max', 'slide_max', 'tether',
        'rest_error_rms', 'rest_error_max', 'rest_error_max_m']
absent = [k for k in need if k not in rows[0]]
noerr = [(r['scene'], label(r)) for r in rows if r['sweep'] == 'methods' and
         (not r['error_vs_reference'] or not r['error_vs_truth'])]
# one truth per body: every method of a body has the same truth key
keys = {}
for r in rows:
    if r['sweep'] == 'methods':
        keys.setdefault(r['scene'], set()).add(r['truth_key'])
noerr += [(b, 'truth keys') for b, k in keys.items() if len(k) != 1]
noerr += [(r['scene'], 'rest') for r in rows if r['sweep'] == 'rest' and not r['rest_error_max']]
sweeps = {r['sweep'] for r in rows}
solvers = {r['solver'] for r in rows}
print('rows', len(rows), 'missing', missing, 'absent', absent, 'no error', noerr, sweeps, solvers)
ok = not missing and not absent and not noerr and solvers == {'newton', 'quasi-newton'} and \
    sweeps == {'methods', 'solvers', 'substeps', 'scaling', 'options', 'rest'}
sys.exit(0 if ok else 1)
PY"
# a run whose frames fail is kept (its row, failures > 0) and the sweep goes on; the summary
# line counts such runs, and its count matches the CSV
check "summary counts the runs with failing frames, as many as the CSV's rows" "/usr/bin/python3 - '$tmp/out/results.csv' '$tmp/err' <<'PY'
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
n = sum(1 for r in rows if int(r['failures']) > 0)
m = re.search(r'(\\d+) had failing frames', open(sys.argv[2]).read())
print('runs with failing frames: CSV', n, 'summary', m and m.group(1))
sys.exit(0 if m and int(m.group(1)) == n else 1)
PY"
check "stability.md has a row for walk on the quadruped" \
  "grep -q '^| quadruped | .* | walk |' '$tmp/out/stability.md'"

# --sweeps: only the named sweeps' rows (the options' here, from the quick run's cache), and
# only their charts
OPENBLAS_NUM_THREADS=1 "$exe" bench --quick --sweeps options --out "$tmp/opt" --cache "$tmp/cache" \
  --plot-script "$src/scripts/plot_bench.py" 2> "$tmp/err_opt"; rc=$?
check "bench --sweeps options exits 0" "[ $rc -eq 0 ]" || tail -n 20 "$tmp/err_opt"
check "--sweeps options: options rows only, every option of the quick run" "/usr/bin/python3 - '$tmp/opt/results.csv' '$tmp/out/results.csv' <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
full = [r for r in csv.DictReader(open(sys.argv[2])) if r['sweep'] == 'options']
print('rows', len(rows), {r['sweep'] for r in rows}, 'options in the full quick run', len(full))
sys.exit(0 if rows and {r['sweep'] for r in rows} == {'options'} and
         [(r['scene'], r['option']) for r in rows] == [(r['scene'], r['option']) for r in full]
         else 1)
PY"
check "--sweeps options: options.png and options.md, no other chart" \
  "[ -s '$tmp/opt/options.png' ] && [ -s '$tmp/opt/options.md' ] && [ ! -e '$tmp/opt/pareto.png' ] && [ ! -e '$tmp/opt/stability.png' ]"

bad() { # bad <description> <args...>: exit 2, one line on stderr
  local what="$1"; shift
  "$exe" "$@" > /dev/null 2> "$tmp/e"; local rc=$?
  check "$what: exit 2, one message" "[ $rc -eq 2 ] && [ \$(wc -l < '$tmp/e') -eq 1 ]"
}
bad "bench without --out" bench --quick
bad "bench unknown option" bench --out "$tmp/x" --bogus
bad "bench missing plot script" bench --out "$tmp/x" --plot-script "$tmp/none.py"
bad "bench unknown sweep" bench --out "$tmp/x" --sweeps options,bogus
bad "bench --sweeps with --truth-doubling" bench --out "$tmp/x" --sweeps options --truth-doubling 32
exit $fail
