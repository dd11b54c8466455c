#!/usr/bin/env bash
# skin_sim_node through a real master, started from launch/skin.launch (no mocks), driven
# by tests/ros/skin_probe.c:
#  - stream: 90 kinematic meshes at 30 Hz; a skin_mesh with the same stamp, frame and
#    triangles for every one, skin_stats for each, skin_marker rate-limited; latency printed;
#  - bad: every kind of bad SkinMesh is rejected and counted while the good ones around
#    it come through; a new topology_id makes a new skin;
#  - burst: 41 meshes back to back into the default queue of 1: the newest is stepped
#    last, every other is stepped or counted as skipped or dropped; no reset;
#  - jump: time going backwards and a gap over ~max_gap each reset the skin (counted).
# Each part gets a fresh skin node. Usage: test_skin_node.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
probe=$(ros_env_helper_exe skin_probe) || exit 1
t0=$(ros_env_now_ms)

# run_part NAME QUEUE PROBE_ARGS...: a fresh skin node (skin.launch queue_size:=QUEUE)
run_part() {
  local part="$1" queue="$2"; shift 2
  local lpid rc
  ros_env_launch_skin "launch_$part" "$queue"; rc=$?
  lpid=$ROS_ENV_LAST_PID
  if [ "$rc" -ne 0 ]; then
    ros_env_check "$part: skin node starts from skin.launch" false
    ros_env_stop "$lpid" # a node left behind would spoil the later parts
    return
  fi
  ros_env_run "probe_$part" "$probe" "$@"; rc=$?
  ros_env_check "$part: skin_probe $* passes (exit $rc)" "[ $rc -eq 0 ]"
  ros_env_stop "$lpid"
  ros_env_check_sanitizer "$ROS_ENV_DIR/launch_$part.log" "$part: no sanitizer report from the skin node"
}

# a queue long enough for the whole stream: every mesh is stepped even where the skin
# is slower than 30 Hz (sanitizer builds); the latency printed says how it kept up
run_part stream 120 stream 90 30
# the default queue of 1 under a burst: the newest is stepped, the others counted as skipped/dropped
run_part burst 1 burst 40
run_part bad 120 bad
l="$ROS_ENV_DIR/launch_bad.log"
ros_env_check "bad: rejections are logged, one line each (throttled), saying why" \
  "grep -q 'rejected kinematic_mesh: .*multiple of 3' '$l' && [ \$(grep -c 'rejected kinematic_mesh' '$l') -le 9 ]"
ros_env_check "bad: each kind of problem is named (sizes, non-finite, topology)" "grep -q 'non-finite' '$l' && grep -q 'without a new topology_id' '$l'"
run_part jump 120 jump
ros_env_check "jump: the resets are logged" "grep -q 'skin reset' '$ROS_ENV_DIR/launch_jump.log'"

echo "test_skin_node: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit "$ROS_ENV_FAIL"
