#!/usr/bin/env bash
# A node that degrades gracefully: skin_sim_node (default parameters, queue of 1) gets a
# kinematic_mesh stream faster than it can step: a 19,200-triangle tube with a seam at
# 60 Hz for OVERLOAD_SECONDS (default 20) s, with a CPU hog beside it
# (tests/ros/overload_probe.c; real node and master). Asserts: 0 resets, every
# skin_mesh finite, in the body's layout and welded (seam copies equal), the skin
# answers after every step (at least every 60 input frames plus two of its longest
# steps: a slow machine is not judged), inputs_skipped > 0 (the overload was real),
# no failures. Prints input/output rates, resets, skipped, dropped and latency (median,
# p95); asserts no wall-clock threshold. Stops by itself.
# SKIN_SIM_NODE=PATH measures another skin_sim_node binary (no assertions then).
# Usage: test_skin_overload.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
probe="$bld/tests/ros/overload_probe"
skin=${SKIN_SIM_NODE:-$(find "$bld/devel/lib/skin_sim" -name skin_sim_node -type f | head -n 1)}
[ -x "$probe" ] && [ -x "$skin" ] || { echo "FAIL: overload_probe or skin_sim_node not built"; exit 1; }
secs=${OVERLOAD_SECONDS:-20}
mode=check
[ -n "${SKIN_SIM_NODE:-}" ] && mode=measure

ros_env_bg skin "$skin" _marker_rate:=0
spid=$ROS_ENV_LAST_PID
check "skin node starts" "ros_env_wait_node /skin_sim $ROS_ENV_START_S $spid"
# a CPU hog beside the node, as on a busy robot computer (stopped at exit)
ros_env_bg hog bash -c 'while :; do :; done'
t0=$(ros_env_now_ms)
timeout $((secs + 60)) "$probe" "$secs" 60 $mode > "$ROS_ENV_DIR/probe.log" 2>&1
rc=$?
cat "$ROS_ENV_DIR/probe.log"
[ "$mode" = check ] && check "overload_probe: 0 resets, finite and welded skin, answers, overload real (exit $rc)" "[ $rc -eq 0 ]"
ros_env_stop "$ROS_ENV_LAST_PID"
# skins created (once at start, then once per reset), from the node's log: works for
# any binary (an older node's skin_stats do not reach this build's probe)
created=$(grep -c 'skin created' "$ROS_ENV_DIR/skin.log")
echo "node: skin created $created times: $((created > 0 ? created - 1 : 0)) resets"
if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$ROS_ENV_DIR/skin.log"; then
  grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$ROS_ENV_DIR/skin.log" | head -30
  check "no sanitizer report from the skin node" false
fi
[ "$mode" = check ] && check "the skin was created once: no reset (created $created times)" "[ $created -eq 1 ]"
echo "test_skin_overload: $(($(ros_env_now_ms) - t0)) ms"
exit $fail
