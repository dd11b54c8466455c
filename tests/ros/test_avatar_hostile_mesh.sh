#!/usr/bin/env bash
# avatar_node given a hostile ~mesh (issue 14): a FIFO (opening it would block for
# ever), an OFF declaring billions of vertices, and 67 bytes of OFF that make
# assimp 5.2 abort inside its importer. The node has no body yet, so each ends it
# at start with exit 1 and one error naming the file -- no hang, no crash, no
# memory bomb. Usage: test_avatar_hostile_mesh.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
exe=$(ros_env_node_exe avatar_node) || exit 1
ros_env_set_robot_description "$src/urdf/mannequin.urdf"
d="$ROS_ENV_DIR/hostile"
ros_env_hostile_meshes "$d"
n=0
for f in "fifo.obj:not a" huge.off:4000000000 abort.off:importer; do
  file="${f%%:*}" word="${f#*:}"
  n=$((n + 1))
  timeout 120 "$exe" __name:=avatar_hostile_$n _mesh:="$d/$file" > "$d/$file.log" 2>&1
  rc=$?
  sed 's/\x1b\[[0-9;]*m//g' "$d/$file.log" | grep -i -m1 "error" || true
  ros_env_check "~mesh $file: the node ends with exit 1 (not a hang or a crash: $rc) naming the file" \
    "[ $rc -eq 1 ] && grep -q '$file' '$d/$file.log' && grep -q '$word' '$d/$file.log'"
done
exit "$ROS_ENV_FAIL"
