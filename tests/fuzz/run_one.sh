#!/usr/bin/env bash
# Runs one libFuzzer harness: tests/fuzz/run_one.sh BINARY SEED_DIR RUNS [SECONDS]
# RUNS executions (0: no limit) for at most SECONDS (default 60) over the seed
# corpus; inputs it finds go to a scratch folder (the seeds in the source tree
# stay as they are), a crash to FUZZ_ARTIFACTS (default: a scratch folder).
# Exit status: 0 nothing found; 1 a finding (libFuzzer's report above); 77 the
# harness was not built.
set -uo pipefail
bin="${1:?usage: run_one.sh BINARY SEED_DIR RUNS [SECONDS]}"
seeds="${2:?}"
runs="${3:?}"
secs="${4:-60}"
[ -x "$bin" ] || { echo "run_one.sh: $bin was not built"; exit 77; }
work=$(mktemp -d "${TMPDIR:-/tmp}/ss_fuzz.XXXXXX")
trap 'rm -rf "$work"' EXIT
art="${FUZZ_ARTIFACTS:-$work/artifacts}"
mkdir -p "$work/corpus" "$art"
# leaks inside assimp's and urdfdom's own importers are theirs (the harnesses
# suppress them); ours are findings.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}:allocator_may_return_null=1"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
"$bin" -runs="$runs" -max_total_time="$secs" -timeout=30 -rss_limit_mb=2560 -max_len=4096 \
  -artifact_prefix="$art/" -print_final_stats=1 "$work/corpus" "$seeds" 2>&1 |
  grep -v "^#[0-9]*	\(NEW\|REDUCE\|pulse\)" | tail -n 60
status=${PIPESTATUS[0]}
if [ "$status" -ne 0 ]; then
  echo "run_one.sh: $(basename "$bin") found a problem (exit $status); artifacts in $art:"
  ls -l "$art"
  [ -z "${FUZZ_ARTIFACTS:-}" ] && trap - EXIT && echo "(kept $work)"
  exit 1
fi
exit 0
