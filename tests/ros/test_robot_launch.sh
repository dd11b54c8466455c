#!/usr/bin/env bash
# Your own robot in one command: `roslaunch skin_sim robot.launch urdf:=PATH`, headless
# (rviz:=false, so joints:=fixed: joint_state_publisher), on the Solo quadruped of
# ../shared/data/urdf-solo-quadruped (package:// URIs resolved by package_path:=) with
# frame_prefix:=solo. It must bring up robot_state_publisher, joint_state_publisher,
# avatar_node and skin_sim_node; skin_mesh must come, in frame solo/base_link (the URDF's
# root link under the prefix), with skin_stats beside it; robot_state_publisher's frames
# must carry the prefix; and scripts/skin_rviz.py must give rviz the fixed frame
# solo/base_link. Skipped (77) where the Solo's data is absent.
# Usage: test_robot_launch.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
shared="${SS_SHARED_DIR:-$src/../shared}"
erd="$shared/data/urdf-solo-quadruped/example-robot-data"
urdf="$erd/robots/solo_description/robots/solo.urdf"
[ -f "$urdf" ] || { echo "skipped: $urdf is absent (../shared/data)"; exit 77; }
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
D="$ROS_ENV_DIR"

/usr/bin/python3 "$src/scripts/skin_rviz.py" --urdf "$urdf" --config "$src/rviz/skin_sim.rviz" \
  --frame-prefix=solo --fit --print > "$D/rviz_frame.txt" 2>&1
cat "$D/rviz_frame.txt"
check "skin_rviz.py: rviz's fixed frame is the root link under the prefix (solo/base_link)" \
  "grep -qx 'fixed frame: solo/base_link' '$D/rviz_frame.txt'"
check "skin_rviz.py: the config it writes has that fixed frame and TF prefix" \
  "f=\$(sed -n 's/^config: //p' '$D/rviz_frame.txt'); grep -q 'Fixed Frame: solo/base_link' \"\$f\" && grep -q 'TF Prefix: \"solo\"' \"\$f\""

t0=$(ros_env_now_ms)
ros_env_bg robot roslaunch "$src/launch/robot.launch" urdf:="$urdf" \
  package_path:="example-robot-data=$erd" frame_prefix:=solo rviz:=false
lpid=$ROS_ENV_LAST_PID
check "robot.launch starts skin_sim_node" "ros_env_wait_node /skin_sim $ROS_ENV_START_S $lpid"
for n in /robot_state_publisher /joint_state_publisher /avatar; do
  check "robot.launch starts $n" "ros_env_wait_node $n 30 $lpid"
done
# the first skin_mesh: the Solo's body is read (assimp, in a child process) and welded first
timeout 180 rostopic echo -n 1 /skin_mesh/header/frame_id > "$D/frame.txt" 2> "$D/frame.err"
t1=$(ros_env_now_ms)
echo "first skin_mesh $(( (t1 - t0) / 1000 )) s after roslaunch; its frame_id: $(head -n 1 "$D/frame.txt")"
check "skin_mesh came, in frame solo/base_link" "grep -qxE '\"?solo/base_link\"?' '$D/frame.txt'"
timeout 60 rostopic echo -n 1 /skin_stats > "$D/stats.txt" 2>&1
check "skin_stats came" "grep -q '^total_ms:' '$D/stats.txt'"
grep -E '^(total_ms|substeps|iterations|inputs_rejected|resets|failures):' "$D/stats.txt" | tr '\n' ' '; echo
if /usr/bin/python3 -c 'import tf2_msgs.msg' 2> /dev/null; then
  timeout 30 rostopic echo -n 1 /tf_static > "$D/tf.txt" 2>&1
  grep -m 2 -E 'frame_id' "$D/tf.txt"
  check "robot_state_publisher's frames carry the prefix (solo/...)" \
    "grep -q 'frame_id: \"solo/' '$D/tf.txt' && ! grep -q 'frame_id: \"[^s]' '$D/tf.txt'"
else
  echo "note: python3-tf2-msgs absent: robot_state_publisher's frames not read"
fi
# what the nodes said (the launch log)
sed 's/\x1b\[[0-9;]*m//g' "$D/robot.log" | grep -E "avatar '|skin created|skin_sim: solver|ERROR|rejected" | head -n 8
check "no node died" "! grep -q 'process has died' '$D/robot.log'"
ros_env_sigint "$lpid" 20
check "roslaunch stops cleanly on SIGINT" "[ $? -eq 0 ]"
exit $fail
