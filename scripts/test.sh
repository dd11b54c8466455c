#!/usr/bin/env bash
# The README's test command: installs what is missing, builds skin_sim twice
# (a normal build, and one with address + undefined-behaviour sanitizers) and
# runs every test through CTest in both. Exits non-zero if anything fails.
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
src="$(cd "$(dirname "$0")/.." && pwd)"
cd "$src"
bash scripts/install_deps.sh
mkdir -p build
bash scripts/build.sh build/release
bash scripts/build.sh build/asan -DSKIN_SIM_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug
status=0
echo "== tests: normal build"
(cd build/release && ctest --output-on-failure -j2) || status=1
echo "== tests: sanitizer build (address, undefined)"
(cd build/asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
   UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j2) || status=1
exit $status
