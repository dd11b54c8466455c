#!/usr/bin/env bash
# /diagnostics during one long step: skin_sim_node, started with 300 substeps a frame,
# no step budget and a 0.25 s diagnostic period, gets a 20,160-triangle torus (the
# skin is created) and then the torus turned a little, which it takes long to step
# (tests/ros/busy_probe.py). Asserts: at least one status arrives while that step
# runs, saying "step in progress for N s" at level WARN or ERROR; the step is
# answered; the first status after it no longer says so. No bound on the step's time
# (only generous ones on waiting).
# Usage: test_skin_busy.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
skin=$(ros_env_node_exe skin_sim_node) || exit 1
t0=$(ros_env_now_ms)
D="$ROS_ENV_DIR"
fig() { sed -n "s/.*figures .*\b$1=\([-0-9]*\).*/\1/p" "$D/probe.log" | head -n 1; }

ros_env_bg skin "$skin" _marker_rate:=0 _step_budget:=-1 _substeps:=300 _diagnostic_period:=0.25
spid=$ROS_ENV_LAST_PID
ros_env_check "skin node starts" "ros_env_wait_node /skin_sim $ROS_ENV_START_S $spid"
timeout 2000 /usr/bin/python3 "$src/tests/ros/busy_probe.py" > "$D/probe.log" 2>&1
rc=$?
cat "$D/probe.log"
ros_env_check "both meshes answered (exit $rc)" "[ $rc -eq 0 ]"
n=$(fig in_progress); level=$(fig level_max)
ros_env_check "a status arrived during the step saying 'step in progress for N s' (${n:-0})" "[ '${n:-0}' -ge 1 ]"
ros_env_check "at level WARN or ERROR (${level:-?})" "[ '${level:--1}' -ge 1 ]"
ros_env_check "the first status after the step no longer says so" \
  "grep -q 'figures .*after=\"' '$D/probe.log' && ! grep -q 'after=\"step in progress' '$D/probe.log'"
ros_env_sigint "$spid" 20
ros_env_check_sanitizer "$D/skin.log" "no sanitizer report from the node"
echo "test_skin_busy: $(($(ros_env_now_ms) - t0)) ms"
exit $ROS_ENV_FAIL
