#!/usr/bin/env bash
# Runs every libFuzzer harness of tests/fuzz for as long as asked:
#   bash scripts/fuzz.sh [SECONDS] [HARNESS...]      (default 60 s each, all harnesses)
# Builds them with clang (ASan + UBSan) into build/fuzz, keeps each harness's
# growing corpus in build/fuzz/corpus/NAME (seeded from tests/fuzz/corpus/NAME)
# and crashes in build/fuzz/artifacts/NAME. Harnesses run one after the other;
# FUZZ_JOBS=N runs N at once (each with nice -n ${FUZZ_NICE:-10}: FUZZ_NICE=19 for a
# long run beside other work). Prints per harness the
# executions reached, the corpus size and what was found; exits 1 on a finding.
set -uo pipefail
export PATH=/usr/bin:/bin:$PATH
src="$(cd "$(dirname "$0")/.." && pwd)"
secs="${1:-60}"
shift || true
case "$secs" in ''|*[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$secs'" >&2; exit 2 ;; esac
command -v clang > /dev/null && command -v clang++ > /dev/null \
  || { echo "fuzz.sh: clang not found (bash scripts/install_deps.sh installs it)" >&2; exit 2; }
bld="${FUZZ_BUILD:-$src/build/fuzz}"
mkdir -p "$bld"
cmake -S "$src/tests/fuzz" -B "$bld" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DSS_SRC="$src" > "$bld/configure.log" 2>&1 || { cat "$bld/configure.log"; exit 1; }
cmake --build "$bld" -j"$(nproc)" > "$bld/build.log" 2>&1 || { tail -n 40 "$bld/build.log"; exit 1; }
if [ $# -gt 0 ]; then
  names=("$@")
else
  names=()
  for f in "$src"/tests/fuzz/fuzz_*.c; do names+=("$(basename "$f" .c)"); done
fi
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
run() {
  local n=$1
  mkdir -p "$bld/corpus/$n" "$bld/artifacts/$n"
  nice -n "${FUZZ_NICE:-10}" "$bld/$n" -max_total_time="$secs" -timeout=30 -rss_limit_mb=2560 -max_len=4096 \
    -artifact_prefix="$bld/artifacts/$n/" -print_final_stats=1 \
    "$bld/corpus/$n" "$src/tests/fuzz/corpus/$n" > "$bld/$n.log" 2>&1
  echo $? > "$bld/$n.status"
}
jobs_max="${FUZZ_JOBS:-1}"
for n in "${names[@]}"; do
  [ -x "$bld/$n" ] || { echo "fuzz.sh: $n was not built (see $bld/build.log)" >&2; continue; }
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do sleep 1; done
  echo "fuzz.sh: $n for $secs s"
  run "$n" &
done
wait
status=0
printf "%-16s %12s %10s %8s  %s\n" harness executions exec/s corpus finding
for n in "${names[@]}"; do
  [ -f "$bld/$n.status" ] || continue
  ex=$(awk '/number_of_executed_units/ {print $2}' "$bld/$n.log" | tail -n 1)
  rate=$(awk '/average_exec_per_sec/ {print $2}' "$bld/$n.log" | tail -n 1)
  cs=$(find "$bld/corpus/$n" -type f | wc -l)
  finding="none"
  if [ "$(cat "$bld/$n.status")" != 0 ]; then
    finding="$(grep -m1 -E "ERROR|Assertion|runtime error|SUMMARY" "$bld/$n.log") (log $bld/$n.log)"
    status=1
  fi
  printf "%-16s %12s %10s %8s  %s\n" "$n" "${ex:-?}" "${rate:-?}" "$cs" "$finding"
done
exit $status
