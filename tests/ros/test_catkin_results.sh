#!/usr/bin/env bash
# catkin's test results: `catkin_make run_tests` runs the suite through
# scripts/catkin_run_tests.sh (CMakeLists.txt, run_tests_skin_sim_ctest), and
# `catkin_test_results` must count its tests and exit non-zero when one fails.
# CTest's own JUnit file has no `errors` attribute: catkin_test_results skipped
# it, said "0 tests" and exited 0 whatever failed. Checked on a scratch CTest
# project of one passing and one failing test (seconds; the real suite's JUnit
# file is written the same way): raw CTest JUnit -> 0 tests counted (the fault);
# through the script -> "2 tests, 0 errors, 1 failures", exit 1; the passing
# test alone -> "1 tests, 0 errors, 0 failures", exit 0.
# Usage: test_catkin_results.sh BUILD_DIR [SOURCE_DIR].
set -u
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
export PATH=/usr/bin:/bin:$PATH
command -v catkin_test_results > /dev/null || { echo "skipped: catkin_test_results not installed"; exit 77; }
. "$src/tests/check.sh"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/proj" "$tmp/build"
cat > "$tmp/proj/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.16)
project(scratch NONE)
enable_testing()
add_test(NAME passes COMMAND true)
add_test(NAME fails COMMAND false)
CM
cmake -S "$tmp/proj" -B "$tmp/build" > "$tmp/cmake.log" 2>&1 || { cat "$tmp/cmake.log"; exit 1; }

# the fault: CTest's JUnit file as it comes is not counted
(cd "$tmp/build" && ctest --output-junit "$tmp/raw/r/ctest.xml" > /dev/null 2>&1)
catkin_test_results "$tmp/raw" > "$tmp/raw.txt" 2>&1; rc=$?
echo "raw CTest JUnit: $(tail -n 1 "$tmp/raw.txt") (exit $rc)"
check "raw CTest JUnit: catkin_test_results counts no test (why the script exists)" \
  "grep -q '0 tests' '$tmp/raw.txt'"

bash "$src/scripts/catkin_run_tests.sh" "$tmp/build" "$tmp/all/skin_sim/ctest-suite.xml" > "$tmp/run.log" 2>&1
rc=$?
check "catkin_run_tests.sh exits 0 with a failing test (exit $rc), as catkin's run_tests does" "[ $rc -eq 0 ]"
catkin_test_results "$tmp/all" > "$tmp/all.txt" 2>&1; rc=$?
echo "through the script: $(tail -n 1 "$tmp/all.txt") (exit $rc)"
check "catkin_test_results counts both tests and the failure, exit non-zero" \
  "[ $rc -ne 0 ] && grep -q 'Summary: 2 tests, 0 errors, 1 failures' '$tmp/all.txt'"

bash "$src/scripts/catkin_run_tests.sh" "$tmp/build" "$tmp/ok/skin_sim/ctest-suite.xml" -R '^passes$' > "$tmp/run2.log" 2>&1
catkin_test_results "$tmp/ok" > "$tmp/ok.txt" 2>&1; rc=$?
echo "passing only: $(tail -n 1 "$tmp/ok.txt") (exit $rc)"
check "all passing: counted, exit 0" "[ $rc -eq 0 ] && grep -q 'Summary: 1 tests, 0 errors, 0 failures' '$tmp/ok.txt'"
exit $fail
