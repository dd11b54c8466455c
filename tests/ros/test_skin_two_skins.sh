#!/usr/bin/env bash
# Two skin_sim_nodes in two namespaces on one body stream can be told apart (issue 13,
# point 5): /left with ~tf_prefix:=left publishes skin_mesh and skin_marker in frame
# "left/probe_frame", /right with ~frame_id:=right_skin in "right_skin"; a node with
# neither keeps the input's frame (the other tests check that). The body is
# skin_probe's waving sheet on /kinematic_mesh (remapped into both nodes).
# Usage: test_skin_two_skins.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
probe="$bld/tests/ros/skin_probe"
skin="$bld/devel/lib/skin_sim/skin_sim_node"
[ -x "$probe" ] && [ -x "$skin" ] || { echo "FAIL: $probe or $skin not built"; exit 1; }
export PATH=/usr/bin:$PATH

ros_env_bg left "$skin" __name:=skin_sim __ns:=/left kinematic_mesh:=/kinematic_mesh \
  _tf_prefix:=left
lpid=$ROS_ENV_LAST_PID
ros_env_bg right "$skin" __name:=skin_sim __ns:=/right kinematic_mesh:=/kinematic_mesh \
  _frame_id:=right_skin
rpid=$ROS_ENV_LAST_PID
ros_env_wait_node /left/skin_sim $ROS_ENV_START_S "$lpid" && ros_env_wait_node /right/skin_sim $ROS_ENV_START_S "$rpid" || {
  check "both skin nodes start" false; exit 1; }
# the probe reads /left's output (its own frame check fails there on purpose: not used)
"$probe" stream 3000 10 skin_mesh:=/left/skin_mesh skin_stats:=/left/skin_stats \
  skin_marker:=/left/skin_marker > "$ROS_ENV_DIR/probe.log" 2>&1 &
ppid=$!
for t in /left/skin_mesh /left/skin_marker /right/skin_mesh /right/skin_marker; do
  timeout 90 rostopic echo -n 1 "$t/header/frame_id" > "$ROS_ENV_DIR/frame_${t//\//_}.txt" 2>&1
  echo "$t: $(head -n 1 "$ROS_ENV_DIR/frame_${t//\//_}.txt")"
done
kill "$ppid" 2>/dev/null; wait "$ppid" 2>/dev/null
frame() { head -n 1 "$ROS_ENV_DIR/frame_${1//\//_}.txt"; }
check "/left/skin_mesh in left/probe_frame (~tf_prefix)" "[ \"\$(frame /left/skin_mesh)\" = '\"left/probe_frame\"' ]"
check "/left/skin_marker in left/probe_frame" "[ \"\$(frame /left/skin_marker)\" = '\"left/probe_frame\"' ]"
check "/right/skin_mesh in right_skin (~frame_id)" "[ \"\$(frame /right/skin_mesh)\" = '\"right_skin\"' ]"
check "/right/skin_marker in right_skin" "[ \"\$(frame /right/skin_marker)\" = '\"right_skin\"' ]"
ros_env_stop "$lpid" "$rpid"
exit $fail
