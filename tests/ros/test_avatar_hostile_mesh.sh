#!/usr/bin/env bash
# avatar_node given a hostile ~mesh (issue 14): a FIFO (opening it would block for
# ever), an OFF declaring billions of vertices, and 67 bytes of OFF that make
# assimp 5.2 abort inside its importer. The node has no body yet, so each ends it
# at start with exit 1 and one error naming the file -- no hang, no crash, no
# memory bomb. Usage: test_avatar_hostile_mesh.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
exe=$(find "$bld/devel/lib/skin_sim" -name avatar_node -type f | head -n 1)
[ -x "$exe" ] || { echo "FAIL: avatar_node not built"; exit 1; }
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
/usr/bin/python3 -c 'import sys, xmlrpc.client
xmlrpc.client.ServerProxy(sys.argv[1]).setParam("/test", "/robot_description", open(sys.argv[2]).read())' \
  "$ROS_MASTER_URI" "$src/urdf/mannequin.urdf"
d="$ROS_ENV_DIR/hostile"
mkdir -p "$d"
mkfifo "$d/fifo.obj"
printf 'OFF\n4000000000 3000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$d/huge.off"
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 193 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$d/abort.off"
n=0
for f in "fifo.obj:not a" huge.off:4000000000 abort.off:importer; do
  file="${f%%:*}" word="${f#*:}"
  n=$((n + 1))
  timeout 120 "$exe" __name:=avatar_hostile_$n _mesh:="$d/$file" > "$d/$file.log" 2>&1
  rc=$?
  sed 's/\x1b\[[0-9;]*m//g' "$d/$file.log" | grep -i -m1 "error" || true
  check "~mesh $file: the node ends with exit 1 (not a hang or a crash: $rc) naming the file" \
    "[ $rc -eq 1 ] && grep -q '$file' '$d/$file.log' && grep -q '$word' '$d/$file.log'"
done
exit $fail
