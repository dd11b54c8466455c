#!/usr/bin/env bash
# The rosc shim through a real master (no mocks): tests/ros/rosc_echo.c's `check`
# publishes SkinMesh, SkinStats, JointState, Marker and String messages, a second
# process (`relay`, topics remapped on its command line) sends them back, and every
# byte is compared; parameters, latching, time, rate and logging are checked too.
# Then the throttled log lines are counted in the master's rosout.log, and a rospy
# publisher (tests/ros/pub_mesh.py) checks that rosc reads messages it did not write.
# Usage: test_rosc.sh BUILD_DIR [SOURCE_DIR]. Exit 77 only if ROS is not installed.
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?

exe="$bld/tests/ros/rosc_echo"
[ -x "$exe" ] || { echo "FAIL: $exe not built"; exit 1; }
t0=$(ros_env_now_ms)

ros_env_bg relay "$exe" relay mesh_in:=mesh_a stats_in:=stats_a joints_in:=joints_a \
  marker_in:=marker_a string_in:=string_a mesh_out:=mesh_b stats_out:=stats_b \
  joints_out:=joints_b marker_out:=marker_b string_out:=string_b
relay_pid=$ROS_ENV_LAST_PID
check "relay node registers" "ros_env_wait_node /rosc_relay $ROS_ENV_START_S"

# 60 meshes of 19k-triangle size at 30 Hz through the relay (queues of 2): all come
# back in order and intact; the latency is printed, not judged
"$exe" ping 60 30 9500 > "$ROS_ENV_DIR/ping.log" 2>&1
prc=$?
cat "$ROS_ENV_DIR/ping.log"
check "30 Hz round trips of 19k-triangle-sized meshes all come back (exit $prc)" "[ $prc -eq 0 ]"

"$exe" check _p_double:=2.5 _p_int:=7 _p_str:=hello _p_bool:=true _p_int_as_double:=3.0 \
  > "$ROS_ENV_DIR/check.log" 2>&1
rc=$?
grep -E "CHECK|checks|ERROR|runtime error|Sanitizer" "$ROS_ENV_DIR/check.log" | grep -v "expected by the test" | head -40
check "rosc_echo check passes (exit $rc)" "[ $rc -eq 0 ]"

# the relay quits on the "quit" message, cleanly (a sanitizer build checks it for leaks)
for _ in $(seq 100); do kill -0 "$relay_pid" 2> /dev/null || break; sleep 0.05; done
if kill -0 "$relay_pid" 2> /dev/null; then
  check "relay exits on quit" false
else
  wait "$relay_pid"; rrc=$?
  check "relay exits 0 on quit (exit $rrc)" "[ $rrc -eq 0 ]"
fi

# /rosout got the log lines: wait for the last one, then count the throttled flood
rlog="$ROS_LOG_DIR/rosout.log"
for _ in $(seq 100); do grep -q "rosc_check done" "$rlog" 2> /dev/null && break; sleep 0.05; done
check "log lines reach /rosout" "grep -q 'rosc_check done' '$rlog'"
n=$(grep -c "\] flood [0-9]*" "$rlog" 2> /dev/null || true)
check "throttled flood (1.2 s, period 0.25 s) logged 4..7 times, got $n" "[ ${n:-0} -ge 4 ] && [ ${n:-0} -le 7 ]"
check "throttled lines say how many were held back" "grep -q 'flood [0-9]* ([0-9]* similar messages held back)' '$rlog'"
m=$(grep -c "macro flood" "$rlog" 2> /dev/null || true)
check "per-call-site throttle macro (period 0.5 s) logged 2..4 times, got $m" "[ ${m:-0} -ge 2 ] && [ ${m:-0} -le 4 ]"
check "debug lines are hidden by default" "! grep -q 'hidden debug' '$rlog'"
check "a 3000-character line arrives whole" "grep -q 'long:x\{2999\}:end' '$rlog'"
check "the caller's file, line and function show in the log" "grep -q 'rosc_echo.c:[0-9]*(check_logging)' '$rlog'"
check "relay logged at INFO" "grep -q 'relay: [0-9]* messages relayed' '$rlog'"

# a publisher that is not rosc (rospy, with the generated Python message): rosc
# receives its good message exactly and drops (and counts) the one whose frame_id
# does not fit the C struct
ros_env_bg listen "$exe" listen 1 15 mesh_in:=py_mesh
listen_pid=$ROS_ENV_LAST_PID
ros_env_bg pub_mesh /usr/bin/python3 "$src/tests/ros/pub_mesh.py" /py_mesh
pub_pid=$ROS_ENV_LAST_PID
wait "$listen_pid"; lrc=$?
check "rosc receives rospy's SkinMesh (exit $lrc)" "[ $lrc -eq 0 ]"
check "contents from rospy arrive exactly" \
  "grep -qx 'mesh frame_id=body stamp=1234.000005678 topology_id=9 positions=9 triangles=3 first=0.100000001' '$ROS_ENV_DIR/listen.log'"
check "a frame_id too long for the C view is dropped and counted" \
  "grep -qx 'received=1 dropped=1' '$ROS_ENV_DIR/listen.log'"
for _ in $(seq 400); do grep -q "dropped a message on /py_mesh" "$rlog" && break; sleep 0.05; done
check "the drop is logged (once, clearly)" \
  "[ \$(grep -c 'dropped a message on /py_mesh: frame_id too long ([0-9]* bytes, at most 255) (1 dropped so far)' '$rlog') -eq 1 ]"
ros_env_stop "$pub_pid"

# roslaunch stops nodes with SIGINT: a rosc node (renamed with __name:=) exits 0 soon
ros_env_bg relay_int "$exe" relay __name:=relay_int
int_pid=$ROS_ENV_LAST_PID
if ros_env_wait_node /relay_int $ROS_ENV_START_S "$int_pid"; then
  kill -INT "$int_pid"
  for _ in $(seq 100); do kill -0 "$int_pid" 2> /dev/null || break; sleep 0.05; done
  if kill -0 "$int_pid" 2> /dev/null; then
    check "a rosc node stops within 5 s of SIGINT" false
  else
    wait "$int_pid"; irc=$?
    check "a rosc node stops on SIGINT, exit 0 (exit $irc)" "[ $irc -eq 0 ]"
  fi
else
  check "relay renamed with __name:=relay_int registers" false
fi

echo "test_rosc: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit $fail
