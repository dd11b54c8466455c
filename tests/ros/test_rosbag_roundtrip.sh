#!/usr/bin/env bash
# The rosbag round trip, started from the launch files: demo.launch (headless, with
# record:=BAG) records kinematic_mesh while the mannequin moves; replay.launch then plays
# that bag twice through a fresh skin node each time, recording skin_mesh; the two
# skin_mesh streams must be identical byte for byte except header.seq (roscpp rewrites
# it), and each must hold one skin_mesh per recorded kinematic_mesh, with its stamp.
# Usage: test_rosbag_roundtrip.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
t0=$(ros_env_now_ms)
D="$ROS_ENV_DIR"
seconds=${ROUNDTRIP_SECONDS:-5}
# a sanitizer build steps the skin ~50 times slower: a shorter recording keeps the
# replays (every mesh stepped, however slowly) within the time budget
grep -q "^SKIN_SIM_SANITIZE:BOOL=ON" "$bld/CMakeCache.txt" 2> /dev/null && seconds=${ROUNDTRIP_SECONDS:-2}

# 1. the demo, recording
ros_env_bg demo roslaunch "$src/launch/demo.launch" rviz:=false tris:=3000 record:="$D/demo.bag"
dpid=$ROS_ENV_LAST_PID
check "demo.launch starts the skin node" "ros_env_wait_node /skin_sim $ROS_ENV_START_S $dpid"
check "demo.launch starts the avatar and motion nodes" "ros_env_wait_node /avatar $ROS_ENV_START_S $dpid && ros_env_wait_node /motion $ROS_ENV_START_S $dpid"
sleep "$seconds"
kill -INT "$dpid"
ros_env_stop "$dpid"
check "the demo bag was written" "[ -f '$D/demo.bag' ]"
/usr/bin/python3 "$src/scripts/skin_bag_summary.py" "$D/demo.bag" > "$D/summary.log" 2>&1
cat "$D/summary.log"
nin=$(sed -n 's/^frames in: *\([0-9]*\).*/\1/p' "$D/summary.log")
nout=$(sed -n 's/^frames out: *[0-9]* skin_mesh (\([0-9]*\) of the \([0-9]*\) since.*/\2 \1/p' "$D/summary.log")
check "the demo moved: ${nin:-0} kinematic_mesh in ${seconds} s (at least 5: the avatar's rate depends on the machine's speed)" "[ ${nin:-0} -ge 5 ]"
# shellcheck disable=SC2086
set -- $nout
check "every skin_mesh of the demo (since the recording began) carries the stamp of a kinematic_mesh (${2:-0} of ${1:-0})" \
  "[ ${1:-0} -gt 0 ] && [ ${1:-0} -eq ${2:-0} ]"
# no input lost without a word in the middle of the stream: every recorded input
# between the node's first and last answers is answered or counted by the node
# (rejected, dropped, skipped). At the ends the recorder may hear the avatar while
# the skin node's subscription is not up yet, or is already shut down: one ASan run
# had 4 of 59 inputs unanswered and none counted (where, not recorded then; the log
# now says), two more only the last.
counted=$(sed -n 's/^inputs rejected: *\([0-9]*\), dropped: \([0-9]*\), skipped: \([0-9]*\), resets.*/\1 + \2 + \3/p' "$D/summary.log")
unanswered=$(/usr/bin/python3 -c 'import sys, rosbag
kin, skin = [], set()
for topic, m, _ in rosbag.Bag(sys.argv[1]).read_messages():
    name = topic.lstrip("/")
    if name == "kinematic_mesh": kin.append(m.header.stamp.to_nsec())
    elif name == "skin_mesh": skin.add(m.header.stamp.to_nsec())
answered = [s for s in kin if s in skin]
print(sum(1 for s in kin if answered and min(answered) < s < max(answered) and s not in skin))
# for the log: where the unanswered ones are (input indices, of all recorded)
print("unanswered inputs at", [i for i, s in enumerate(kin) if s not in skin], "of", len(kin), file=sys.stderr)' \
  "$D/demo.bag" 2>> "$D/summary.log")
grep "^unanswered inputs at" "$D/summary.log" || true
check "every kinematic_mesh between the first and last answered has its skin_mesh or is counted by the node (${unanswered:-none} unanswered, counted: ${counted:-none})" \
  "[ -n '$counted' ] && [ -n '$unanswered' ] && [ ${unanswered:-0} -le \$(( $counted )) ]"

# 2. two replays through fresh skin nodes; a probe waits until the last recorded frame
#    has been stepped (a slow build steps from its queue long after the player ends)
last_ns=$(/usr/bin/python3 -c 'import sys, rosbag
print(max(m.header.stamp.to_nsec() for _, m, _ in rosbag.Bag(sys.argv[1]).read_messages(topics=["kinematic_mesh", "/kinematic_mesh"])))' "$D/demo.bag")
for k in 1 2; do
  ros_env_bg "await$k" "$bld/tests/ros/skin_probe" await "$last_ns" 120
  apid=$ROS_ENV_LAST_PID
  ros_env_bg "replay$k" roslaunch "$src/launch/replay.launch" bag:="$D/demo.bag" out:="$D/replay$k.bag" \
    delay:=1.5 marker_rate:=0 queue_size:=1000
  rpid=$ROS_ENV_LAST_PID
  done_play=0
  for _ in $(seq 900); do
    if grep -q "play-[0-9]*\] process has finished" "$D/replay$k.log" 2> /dev/null; then done_play=1; break; fi
    kill -0 "$rpid" 2> /dev/null || break
    sleep 0.1
  done
  check "replay $k: the player finished" "[ $done_play = 1 ]"
  wait "$apid"; arc=$?
  cat "$D/await$k.log"
  check "replay $k: the skin stepped the last recorded frame" "[ $arc -eq 0 ]"
  sleep 0.5   # the last skin_mesh reaches the recorder
  kill -INT "$rpid"
  ros_env_stop "$rpid"
  check "replay $k: a bag of skin_mesh was written" "[ -f '$D/replay$k.bag' ]"
done
/usr/bin/python3 "$src/tests/ros/bag_compare.py" "$D/demo.bag" "$D/replay1.bag" "$D/replay2.bag" > "$D/compare.log" 2>&1
crc=$?
cat "$D/compare.log"
check "two replays give the same skin_mesh stream, byte for byte (exit $crc)" "[ $crc -eq 0 ]"
for f in "$D"/demo.log "$D"/replay*.log; do
  if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$f"; then
    grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$f" | head -30
    check "no sanitizer report in ${f##*/}" false
  fi
done
echo "test_rosbag_roundtrip: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit $fail
