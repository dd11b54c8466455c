#!/usr/bin/env bash
# skin_sim_node through a real master, started from launch/skin.launch (no mocks), driven
# by tests/ros/skin_probe.c:
#  - stream: 90 kinematic meshes at 30 Hz; a skin_mesh with the same stamp, frame and
#    triangles for every one, skin_stats for each, skin_marker rate-limited; latency printed;
#  - bad: every kind of bad SkinMesh is rejected and counted while the good ones around
#    it come through; a new topology_id makes a new skin;
#  - jump: time going backwards and a gap over ~max_gap each reset the skin (counted).
# Each part gets a fresh skin node. Usage: test_skin_node.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
probe="$bld/tests/ros/skin_probe"
[ -x "$probe" ] || { echo "FAIL: $probe not built"; exit 1; }
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
t0=$(ros_env_now_ms)

run_part() {
  local part="$1"; shift
  ros_env_bg "launch_$part" roslaunch "$src/launch/skin.launch" output:=screen
  local lpid=$ROS_ENV_LAST_PID
  if ! ros_env_wait_node /skin_sim 20 "$lpid"; then
    check "$part: skin node starts from skin.launch" false
    return
  fi
  "$probe" "$@" > "$ROS_ENV_DIR/probe_$part.log" 2>&1
  local rc=$?
  cat "$ROS_ENV_DIR/probe_$part.log"
  check "$part: skin_probe $* passes (exit $rc)" "[ $rc -eq 0 ]"
  ros_env_stop "$lpid"
  if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$ROS_ENV_DIR/launch_$part.log"; then
    grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$ROS_ENV_DIR/launch_$part.log" | head -30
    check "$part: no sanitizer report from the skin node" false
  fi
}

run_part stream stream 90 30
run_part bad bad
l="$ROS_ENV_DIR/launch_bad.log"
check "bad: rejections are logged, one line each (throttled), saying why" \
  "grep -q 'rejected kinematic_mesh: .*multiple of 3' '$l' && [ \$(grep -c 'rejected kinematic_mesh' '$l') -le 9 ]"
check "bad: each kind of problem is named (sizes, non-finite, topology)" "grep -q 'non-finite' '$l' && grep -q 'without a new topology_id' '$l'"
run_part jump jump
check "jump: the resets are logged" "grep -q 'skin reset' '$ROS_ENV_DIR/launch_jump.log'"

echo "test_skin_node: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit $fail
