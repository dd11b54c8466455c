# shellcheck shell=bash
# tests/tool/lib.sh: the tool tests' common start. A script run as
# `test_X.sh BUILD_DIR [SOURCE_DIR]` (CTest passes both) begins
#
#   set -u
#   . "$(dirname "$0")/lib.sh"
#
# and then has: bld (BUILD_DIR), src (SOURCE_DIR, else the tree this file is in),
# exe (the skinsim built under bld; the script exits 1 when there is none),
# tmp (a fresh temporary folder, removed at exit), py (Debian's python3), and
# check / fail from tests/check.sh.
bld="$1"
src="${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}"
# shellcheck source=../check.sh
. "$src/tests/check.sh"
py=/usr/bin/python3
# -L: in a catkin workspace BUILD/devel is a link to the workspace's devel space
exe=$(find -L "$bld" -type f -name skinsim -perm -u+x 2> /dev/null | head -n 1)
[ -x "$exe" ] || { echo "skinsim not built under $bld"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
