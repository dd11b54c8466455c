#!/usr/bin/env bash
# avatar_node's ~reload (issue 14): the node starts with a good body (an ellipsoid
# OBJ on the mannequin's URDF); reloads with a hostile or broken ~mesh (a FIFO, an
# OFF declaring billions of vertices, an OFF that makes assimp abort, a missing
# file, a good file over ~max_file_mb, a bad ~import_timeout or ~import_mem_mb) each fail with one
# error naming the file (or parameter) while the node keeps publishing its last
# good body (same vertex count and topology_id); a reload with another good mesh
# swaps it in (new vertex count and topology). Then the node exits 0 on SIGINT.
# Usage: test_avatar_reload.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
exe=$(ros_env_node_exe avatar_node) || exit 1
ros_env_set_robot_description "$src/urdf/mannequin.urdf"
d="$ROS_ENV_DIR/meshes"
mkdir -p "$d"
ros_env_ellipsoid_obj "$d/torso.obj" 24 16   # 362 vertices
ros_env_ellipsoid_obj "$d/torso2.obj" 12 8   # 86 vertices
ros_env_hostile_meshes "$d"

ros_env_bg avatar_reload "$exe" __name:=avatar_reload _mesh:="$d/torso.obj" _queue_size:=50
apid=$ROS_ENV_LAST_PID
ros_env_check "avatar node starts with torso.obj" "ros_env_wait_node /avatar_reload $ROS_ENV_START_S $apid"
p="$ROS_ENV_DIR/probe.log"
timeout 600 /usr/bin/python3 "$src/tests/ros/reload_probe.py" /avatar_reload \
  mesh="$d/fifo.obj" fail mesh="$d/huge.off" fail mesh="$d/abort.off" fail \
  mesh="$d/missing.obj" fail \
  mesh="$d/torso2.obj" param=max_file_mb=0.001 fail \
  param=max_file_mb=256 param=import_timeout=abc fail \
  param=import_timeout=60 ok \
  mesh="$d/torso.obj" param=import_mem_mb=8 fail \
  param=import_mem_mb=4096 ok > "$p" 2>&1
rc=$?
cat "$p"
ros_env_check "every reload ends as expected (probe exit $rc)" "[ $rc -eq 0 ]"
start=$(awk '/^start:/ {print $2, $5}' "$p")
ros_env_check "the first body is torso.obj's 362 vertices" "[ '${start%% *}' = 362 ]"
ros_env_check "after each of the first 6 failed reloads the node still publishes the first body" \
  "[ \$(grep -c \"^reload failed: ${start%% *} vertices, topology ${start##* }\$\" '$p') -eq 6 ]"
ros_env_check "after the 7th (a bad ~import_mem_mb) it still publishes the second (86 vertices)" \
  "[ \$(grep -c '^reload failed: 86 vertices' '$p') -eq 1 ]"
ros_env_check "a good reload swaps in torso2.obj (86 vertices, another topology)" \
  "grep -q '^reload ok: 86 vertices' '$p' && ! grep -q '^reload ok: 86 vertices, topology ${start##* }\$' '$p'"
ros_env_check "and reloading torso.obj gives the first topology again" \
  "grep -q \"^reload ok: 362 vertices, topology ${start##* }\$\" '$p'"
l="$ROS_ENV_DIR/avatar_reload.log"
sed 's/\x1b\[[0-9;]*m//g' "$l" | grep -E "ERROR|reload" | head -30
for w in "fifo.obj.*not a" "huge.off.*4000000000" "abort.off.*importer" "missing.obj" \
         "torso2.obj.*over the cap of 0.001 MB" "~import_timeout" "~import_mem_mb = 8 MB is out of range"; do
  ros_env_check "the log names the problem: $w" "grep -q -- '$w' '$l'"
done
ros_env_check "each failed reload says the last good body is kept" \
  "[ \$(grep -c 'still publishing the last good body' '$l') -eq 7 ]"
ros_env_sigint "$apid" 10; arc=$?
ros_env_check "avatar node exits 0 on SIGINT (exit $arc)" "[ $arc -eq 0 ]"
ros_env_check_sanitizer "$l" "no sanitizer report from the avatar node"
exit "$ROS_ENV_FAIL"
