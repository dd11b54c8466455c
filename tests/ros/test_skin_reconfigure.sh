#!/usr/bin/env bash
# Live tuning of skin_sim_node through dynamic_reconfigure, as a user does it: the node
# from launch/skin.launch, a waving sheet streamed by tests/ros/skin_probe.c, and
# `rosrun dynamic_reconfigure dynparam` (the Python client rqt_reconfigure uses too):
#  - dynparam get lists the table's settings with their values in force;
#  - `dynparam set /skin_sim substeps 12` while streaming: skin_stats' substeps per step
#    triple from one step on and stay so (no reset), the log says it;
#  - `dynparam set /skin_sim young 500`: taken, "refactored" in the log;
#  - a bad value (poisson 0.7, method crawl) is refused with a log line naming it, and
#    the served config, dynparam get and the parameter server keep the value in force;
#  - `dynparam set /skin_sim barycenters false` (between two streams: skin_probe sends
#    1024 meshes at most): the skin is created again on the next mesh, without its
#    barycenter anchors (the log says so, skin_stats counts one reset), output goes on.
# Usage: test_skin_reconfigure.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
probe=$(ros_env_helper_exe skin_probe) || exit 1
[ -x /usr/lib/dynamic_reconfigure/dynparam ] || [ -n "$(command -v dynparam)" ] || \
  /usr/bin/python3 -c 'import dynamic_reconfigure.client' 2>/dev/null || {
  echo "python3-dynamic-reconfigure is not installed (scripts/install_deps.sh): skipped"; exit 77; }
export PATH=/usr/bin:$PATH
dynparam() { timeout 120 rosrun dynamic_reconfigure dynparam "$@"; }
log="$ROS_ENV_DIR/launch.log"

# no step budget: the substeps checked are the settings' (a budget would lower them on a
# slow machine: the sanitizer build beside two CPU hogs)
ros_env_launch_skin launch 120 "$ROS_ENV_START_S" step_budget:=-1; started=$?
lpid=$ROS_ENV_LAST_PID
if [ "$started" -ne 0 ]; then
  ros_env_check "skin node starts from skin.launch" false
  exit 1
fi

dynparam get /skin_sim > "$ROS_ENV_DIR/get0.txt" 2>&1; rc=$?
echo "--- dynparam get /skin_sim:"; cat "$ROS_ENV_DIR/get0.txt"
ros_env_check "dynparam get /skin_sim exits 0" "[ $rc -eq 0 ]"
for k in "'slide': 20.79" "'poisson': 0.3" "'substeps': 4" "'method': 'walk'" \
         "'solver': 'quasi-newton'" "'barycenters': True" "'gravity': '0 0 0'" "'young': 50.0"; do
  ros_env_check "dynparam get shows $k" "grep -qF \"$k\" '$ROS_ENV_DIR/get0.txt'"
done

# One long stream (the waving sheet, 10 Hz) with every skin_stats recorded, while the
# settings change (each dynparam takes seconds on a loaded machine, so no fixed timing).
ros_env_bg stats_echo rostopic echo /skin_stats
epid=$ROS_ENV_LAST_PID
"$probe" stream 1000 10 > "$ROS_ENV_DIR/probe.log" 2>&1 &
ppid=$!
wait_stats() { # wait_stats N: until N skin_stats were recorded (120 s at most)
  for _ in $(seq 1200); do
    [ "$(grep -c '^substeps:' "$ROS_ENV_DIR/stats_echo.log" 2>/dev/null)" -ge "$1" ] && return 0
    sleep 0.1
  done
  return 1
}
wait_stats 20
n0=$(grep -c '^substeps:' "$ROS_ENV_DIR/stats_echo.log")
dynparam set /skin_sim substeps 12 > "$ROS_ENV_DIR/set_substeps.txt" 2>&1; rc=$?
ros_env_check "dynparam set /skin_sim substeps 12 exits 0" "[ $rc -eq 0 ]"
dynparam set /skin_sim young 500 > /dev/null 2>&1; rc=$?
ros_env_check "dynparam set /skin_sim young 500 exits 0" "[ $rc -eq 0 ]"
dynparam set /skin_sim poisson 0.7 > "$ROS_ENV_DIR/set_poisson.txt" 2>&1
dynparam set /skin_sim method crawl > "$ROS_ENV_DIR/set_method.txt" 2>&1
dynparam get /skin_sim > "$ROS_ENV_DIR/get1.txt" 2>&1
n1=$(grep -c '^substeps:' "$ROS_ENV_DIR/stats_echo.log")
# skin_probe streams 1024 meshes at most: a second stream carries the next change
kill "$ppid" 2>/dev/null; wait "$ppid" 2>/dev/null
# the node drains the meshes still queued from the first stream before the change: a
# mesh of it stepped after the change would create the skin again on the old stream,
# and the second stream, whose stamps start again from the same time, would then go
# back in time (a second reset)
quiet=0
for _ in $(seq 120); do
  a=$(grep -c '^substeps:' "$ROS_ENV_DIR/stats_echo.log"); sleep 0.5
  [ "$(grep -c '^substeps:' "$ROS_ENV_DIR/stats_echo.log")" = "$a" ] && quiet=$((quiet + 1)) || quiet=0
  [ "$quiet" -ge 4 ] && break
done
n1=$(grep -c '^substeps:' "$ROS_ENV_DIR/stats_echo.log")
dynparam set /skin_sim barycenters false > /dev/null 2>&1; rc=$?
ros_env_check "dynparam set /skin_sim barycenters false exits 0" "[ $rc -eq 0 ]"
"$probe" stream 1000 10 > "$ROS_ENV_DIR/probe2.log" 2>&1 &
ppid=$!
n2=$(grep -c '^substeps:' "$ROS_ENV_DIR/stats_echo.log")
wait_stats $((n2 + 20))
dynparam get /skin_sim > "$ROS_ENV_DIR/get2.txt" 2>&1
kill "$ppid" 2>/dev/null; wait "$ppid" 2>/dev/null
ros_env_stop "$epid"
echo "--- the node's log about it:"; grep "dynamic_reconfigure" "$log"
/usr/bin/python3 - "$ROS_ENV_DIR/stats_echo.log" "$n0" "$n1" "$n2" > "$ROS_ENV_DIR/seq.txt" <<'PY'
import sys
blocks = [b for b in open(sys.argv[1]).read().split('---') if 'substeps:' in b]
f = lambda b, k: int([l for l in b.splitlines() if l.startswith(k + ':')][0].split()[1])
sub = [f(b, 'substeps') for b in blocks]
res = [f(b, 'resets') for b in blocks]
n0, n1, n2 = (int(x) for x in sys.argv[2:5])
runs = []
for s in sub:
    if not runs or runs[-1][0] != s: runs.append([s, 0])
    runs[-1][1] += 1
print('skin_stats: %d; substeps per step (value x count; 0: a skin created, no step): %s' %
      (len(sub), ' '.join('%dx%d' % (s, c) for s, c in runs)))
print('resets before the change of barycenters %d, at the end %d' % (res[n1 - 1], res[-1]))
stepped = [r for r in runs if r[0] > 0]
merged = []
for s, c in stepped:
    if merged and merged[-1][0] == s: merged[-1][1] += c
    else: merged.append([s, c])
ok_sub = (len(merged) == 2 and merged[0][0] * 3 == merged[1][0] and n0 <= merged[0][1] <= n1)
ok_res = res[n1 - 1] == 0 and res[-1] == 1 and sub[n1:].count(0) == 1
print('SUBSTEPS_OK' if ok_sub else 'SUBSTEPS_BAD')
print('RESETS_OK' if ok_res else 'RESETS_BAD')
PY
cat "$ROS_ENV_DIR/seq.txt"
ros_env_check "substeps 12: skin_stats' substeps per step triple from one step on, never back"   "grep -q SUBSTEPS_OK '$ROS_ENV_DIR/seq.txt'"
ros_env_check "log: substeps 4 -> 12" "grep -q 'dynamic_reconfigure: substeps 4 -> 12' '$log'"
ros_env_check "log: young 50 -> 500, refactored" \
  "grep -q 'dynamic_reconfigure: young 50 -> 500' '$log' && grep -q 'refactored' '$log'"
ros_env_check "log: poisson 0.7 refused, naming it and the range" \
  "grep -q 'poisson refused: poisson must be in \[0, 0.5) (got 0.7); it stays 0.3' '$log'"
ros_env_check "log: method crawl refused, naming the choices" \
  "grep -q \"method refused: method expects walk, project, nring, got 'crawl'\" '$log'"
ros_env_check "served config keeps what is in force (poisson 0.3, method walk, young 500, substeps 12)" \
  "grep -qF \"'poisson': 0.3\" '$ROS_ENV_DIR/get1.txt' && grep -qF \"'method': 'walk'\" '$ROS_ENV_DIR/get1.txt' && grep -qF \"'young': 500.0\" '$ROS_ENV_DIR/get1.txt' && grep -qF \"'substeps': 12\" '$ROS_ENV_DIR/get1.txt'"
ros_env_check "parameter server mirrors it (rosparam get /skin_sim/young: 500.0, poisson 0.3)" \
  "[ \"\$(rosparam get /skin_sim/young)\" = 500.0 ] && [ \"\$(rosparam get /skin_sim/poisson)\" = 0.3 ]"
ros_env_check "barycenters false: no reset before, one after (the skin created again), output goes on" \
  "grep -q RESETS_OK '$ROS_ENV_DIR/seq.txt'"
ros_env_check "log: says the skin is created again, without barycenter anchors (576 for 576 vertices)" \
  "grep -q 'the skin is created again on the next kinematic_mesh' '$log' && grep -q 'skin created again with the new settings' '$log' && grep -q '576 anchors' '$log'"
ros_env_check "dynparam get: barycenters False" "grep -qF \"'barycenters': False\" '$ROS_ENV_DIR/get2.txt'"
ros_env_stop "$lpid"
ros_env_check_sanitizer "$log" "no sanitizer report from the skin node"
exit "$ROS_ENV_FAIL"
