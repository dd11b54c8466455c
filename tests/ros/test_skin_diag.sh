#!/usr/bin/env bash
# skin_sim_node's health on /diagnostics and its ~reset service, through a real master,
# the node started from launch/skin.launch, driven by tests/ros/skin_probe.c:
#  - /diagnostics (read with rostopic echo, as a robot monitor would): with no input the
#    status "skin_sim: skin" is WARN "no kinematic_mesh received"; during a good 10 Hz
#    stream it has every key-value and is OK, or (a slow or busy machine) WARN/ERROR for
#    the step time or falling behind, as its own figures show (never assumed: the level
#    of a good stream depends on the machine's speed); during a stream of NaN meshes it
#    is ERROR "every input rejected";
#  - ~reset: `skin_probe reset` calls it through rosc; the next skin_mesh is the body's
#    pose and skin_stats counts the reset; then the same with `rosservice call
#    /skin_sim/reset` (the user's way).
# Usage: test_skin_diag.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
probe=$(ros_env_helper_exe skin_probe) || exit 1
export PATH=/usr/bin:$PATH

# diag NAME: the next skin_sim status on /diagnostics, into $ROS_ENV_DIR/diag_NAME.txt
diag() {
  timeout 20 rostopic echo -n 1 /diagnostics > "$ROS_ENV_DIR/diag_$1.txt" 2>&1
  echo "--- /diagnostics ($1):"
  grep -E "name:|level:|message:|key:|value:" "$ROS_ENV_DIR/diag_$1.txt" | head -34
}
level_is() { grep -q "level: $2" "$ROS_ENV_DIR/diag_$1.txt"; }
# healthy_or_slow NAME: the status of a good stream is OK "stepping normally", or WARN/ERROR for
# the machine's speed alone (a step over 80% or twice the input period, inputs dropped or
# skipped), as the status's own figures confirm; no rejection, reset or failure either way.
# The level itself depends on the speed of the machine (a busy 2-core machine under ASan:
# a 136 ms step for a 100 ms period), so no test may require OK (issue 34, item 7).
healthy_or_slow() {
  /usr/bin/python3 - "$ROS_ENV_DIR/diag_$1.txt" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
level = re.search(r'level: (\d+)', t)
msg = re.search(r'message: "([^"]*)"', t)
kv = dict(re.findall(r'key: "([^"]*)"\s*\n\s*value: "([^"]*)"', t))
if not level or not msg:
    print('no status'); sys.exit(1)
level, msg = int(level.group(1)), msg.group(1)
num = lambda k: float(kv.get(k, 'nan'))
clean = all(num(k) == 0 for k in ('inputs rejected', 'resets', 'failures'))
step, budget, period = num('step time mean (ms)'), num('step budget (ms)'), num('input period (ms)')
behind = num('inputs dropped') + num('inputs skipped') > 0
if level == 0:
    ok = msg == 'stepping normally' and not step > budget
elif level == 1:
    ok = (msg.startswith('step ') and step > budget) or ('falling behind' in msg and behind)
else:
    ok = level == 2 and 'cannot keep up' in msg and step > 2 * period
print('level %d "%s": step %.2f ms, budget %.2f ms, period %.2f ms, behind %s, clean %s -> %s'
      % (level, msg, step, budget, period, behind, clean, 'ok' if ok and clean else 'not ok'))
sys.exit(0 if ok and clean else 1)
PY
}

# 0. the judge on the status the sanitizer pass met on a busy machine (a good stream,
#    every input stepped, the step 136 ms for a 100 ms period): WARN for speed, accepted;
#    and on a status that is not the machine's speed (a reset): refused.
slow_status() { # LEVEL MESSAGE RESETS
  cat <<TXT
status:
  -
    level: $1
    name: "skin_sim: skin"
    message: "$2"
    hardware_id: "skin_sim"
    values:
      -
        key: "window (s)"
        value: "1.0"
      -
        key: "step time mean (ms)"
        value: "136.20"
      -
        key: "step time max (ms)"
        value: "171.03"
      -
        key: "input period (ms)"
        value: "100.00"
      -
        key: "step budget (ms)"
        value: "80.00"
      -
        key: "inputs received"
        value: "10"
      -
        key: "inputs processed"
        value: "7"
      -
        key: "inputs rejected"
        value: "0"
      -
        key: "inputs dropped"
        value: "0"
      -
        key: "inputs skipped"
        value: "0"
      -
        key: "resets"
        value: "$3"
      -
        key: "failures"
        value: "0"
TXT
}
slow_status 1 "step 136.2 ms over 80% of the input period 100.0 ms" 0 > "$ROS_ENV_DIR/diag_busy.txt"
slow_status 1 "skin reset 1 times" 1 > "$ROS_ENV_DIR/diag_busyreset.txt"
ros_env_check "judge: a busy machine's WARN (step 136 ms, period 100 ms) is the machine's speed" \
  "healthy_or_slow busy"
ros_env_check "judge: a reset is not the machine's speed" "! healthy_or_slow busyreset"

ros_env_launch_skin launch 120; started=$?
lpid=$ROS_ENV_LAST_PID
if [ "$started" -ne 0 ]; then
  ros_env_check "skin node starts from skin.launch" false
  exit 1
fi

# 1. no input yet
diag idle
ros_env_check "idle: status named after the node, WARN, no input" \
  "grep -q 'name: \"skin_sim: skin\"' '$ROS_ENV_DIR/diag_idle.txt' && level_is idle 1 && grep -q 'no kinematic_mesh' '$ROS_ENV_DIR/diag_idle.txt'"

# 2. a good stream at 10 Hz (8 s): OK, every figure present
"$probe" stream 80 10 > "$ROS_ENV_DIR/probe_stream.log" 2>&1 &
ppid=$!
sleep 3
diag good
wait $ppid
rc=$?
tail -3 "$ROS_ENV_DIR/probe_stream.log"
ros_env_check "good: skin_probe stream passes (exit $rc)" "[ $rc -eq 0 ]"
ros_env_check "good: OK 'stepping normally', or a level the window's own figures show is the machine's speed" \
  "healthy_or_slow good"
for k in "step time mean (ms)" "step time max (ms)" "input period (ms)" "step budget (ms)" \
         "inputs received" "inputs processed" "inputs rejected" "inputs dropped" \
         "inputs skipped" "resets" "failures" "window (s)" "skin steps on more than one thread" \
         "skin steps refused (since created)" "skin steps failure (since created)" \
         "skin steps unconverged (since created)" "skin steps step_limit (since created)"; do
  ros_env_check "good: key '$k' present" "grep -qF 'key: \"$k\"' '$ROS_ENV_DIR/diag_good.txt'"
done
ros_env_check "good: the window's skin steps counted, with those on more than one thread" \
  "grep -A1 'key: \"skin steps on more than one thread\"' '$ROS_ENV_DIR/diag_good.txt' | grep -qE 'value: \"[0-9]+ of [1-9][0-9]*\"'"
ros_env_check "good: input period measured (100 ms)" \
  "grep -A1 'key: \"input period (ms)\"' '$ROS_ENV_DIR/diag_good.txt' | grep -q 'value: \"100.00\"'"

# 3. NaN meshes only (8 s at 10 Hz): ERROR, every input rejected
"$probe" badstream 8 10 > "$ROS_ENV_DIR/probe_bad.log" 2>&1 &
ppid=$!
sleep 3
diag bad
wait $ppid
rc=$?
cat "$ROS_ENV_DIR/probe_bad.log"
ros_env_check "bad: skin_probe badstream passes (exit $rc)" "[ $rc -eq 0 ]"
ros_env_check "bad: level ERROR, 'every input rejected'" "level_is bad 2 && grep -q 'every input rejected' '$ROS_ENV_DIR/diag_bad.txt'"
ros_env_stop "$lpid"

# 4. ~reset on a fresh node
ros_env_launch_skin launch_reset 120; started=$?
lpid=$ROS_ENV_LAST_PID
if [ "$started" -eq 0 ]; then
  ros_env_run probe_reset "$probe" reset; rc=$?
  ros_env_check "reset: skin_probe reset passes (exit $rc)" "[ $rc -eq 0 ]"
  ros_env_run probe_reset2 "$probe" reset "timeout 20 rosservice call /skin_sim/reset"; rc=$?
  ros_env_check "reset: with rosservice call /skin_sim/reset (exit $rc)" "[ $rc -eq 0 ]"
  ros_env_check "reset: logged" "grep -q '~reset: skin created again' '$ROS_ENV_DIR/launch_reset.log'"
  ros_env_check "reset: the second reset (rosservice) counted" \
    "[ \$(grep -c '~reset: skin created again' '$ROS_ENV_DIR/launch_reset.log') -eq 2 ]"
  ros_env_stop "$lpid"
else
  ros_env_check "reset: skin node starts" false
fi
for l in launch launch_reset; do
  ros_env_check_sanitizer "$ROS_ENV_DIR/$l.log" "$l: no sanitizer report from the skin node"
done
exit "$ROS_ENV_FAIL"
