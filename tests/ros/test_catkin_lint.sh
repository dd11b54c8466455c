#!/usr/bin/env bash
# catkin_lint -W2 finds no problem in the package (the notices CMakeLists.txt
# explains are silenced there with #catkin_lint: lines). The folder's name is the
# user's choice (a clone may be called anything), so PACKAGE_PATH_NAME is ignored.
# Usage: test_catkin_lint.sh BUILD_DIR [SOURCE_DIR].
set -u
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
export PATH=/usr/bin:/bin:$PATH
command -v catkin_lint > /dev/null || { echo "skipped: catkin_lint not installed (package catkin-lint)"; exit 77; }
out=$(catkin_lint -W2 --ignore PACKAGE_PATH_NAME "$src" 2>&1 | grep -v 'rosdep')
echo "$out"
if echo "$out" | grep -q 'found 0 problems'; then
  echo "ok: catkin_lint -W2: no problems"
  exit 0
fi
echo "FAIL: catkin_lint -W2 reports problems"
exit 1
