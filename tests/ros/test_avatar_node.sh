#!/usr/bin/env bash
# avatar_node (the built-in mannequin) through a real master: good joint_states come
# back as kinematic_mesh with the same stamp and the URDF root frame; joint_states whose
# arrays disagree, with NaN, or naming only joints the robot lacks are rejected and
# counted (avatar_stats) while the node keeps running; unknown names beside known ones
# are ignored and counted. Usage: test_avatar_node.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
probe="$bld/tests/ros/skin_probe"
exe=$(find "$bld/devel/lib/skin_sim" -name avatar_node -type f | head -n 1)
[ -x "$probe" ] && [ -x "$exe" ] || { echo "FAIL: skin_probe or avatar_node not built"; exit 1; }
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
t0=$(ros_env_now_ms)

ros_env_bg avatar "$exe" _avatar:=mannequin _tris:=3000
apid=$ROS_ENV_LAST_PID
check "avatar node starts" "ros_env_wait_node /avatar 30 $apid"
"$probe" joints > "$ROS_ENV_DIR/probe.log" 2>&1
rc=$?
cat "$ROS_ENV_DIR/probe.log"
check "skin_probe joints passes (exit $rc)" "[ $rc -eq 0 ]"
check "avatar node still running" "kill -0 $apid"
kill -INT "$apid"
for _ in $(seq 100); do kill -0 "$apid" 2> /dev/null || break; sleep 0.05; done
wait "$apid"; arc=$?
check "avatar node exits 0 on SIGINT (exit $arc)" "[ $arc -eq 0 ]"
l="$ROS_ENV_DIR/avatar.log"
check "rejections are logged with the reason" "grep -q 'rejected joint_states: arrays disagree' '$l'"
check "unknown names are logged" "grep -q 'does not have' '$l'"
if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$l"; then
  grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$l" | head -30
  check "no sanitizer report from the avatar node" false
fi

# a robot_description that is not the mannequin: the URDF's own frame and joints
echo "test_avatar_node: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit $fail
