#!/usr/bin/env bash
# Every launch file passes roslaunch-check (XML, args, packages and node types
# resolvable) and `roslaunch --nodes` lists the nodes it should.
# Usage: test_launch_files.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
rlc=/usr/share/roslaunch/scripts/roslaunch-check
if [ -f "$rlc" ]; then
  # one run over the folder (each run costs seconds of Python start-up)
  /usr/bin/python3 "$rlc" -i -o "$ROS_ENV_DIR/check.xml" "$src/launch" > "$ROS_ENV_DIR/check.log" 2>&1
  check "roslaunch-check launch/ ($(ls "$src"/launch/*.launch | wc -l) files)" \
    "grep -q '^passed' '$ROS_ENV_DIR/check.log'" || cat "$ROS_ENV_DIR/check.log"
else
  echo "roslaunch-check not found: skipped that part"
fi
nodes() { roslaunch --nodes "$@" 2> "$ROS_ENV_DIR/nodes.err" | tr '\n' ' '; }
check "demo.launch: motion avatar skin_sim robot_state_publisher rviz" \
  "[ \"\$(nodes '$src/launch/demo.launch')\" = '/motion /avatar /skin_sim /robot_state_publisher /rviz ' ]"
check "demo.launch rviz:=false record:=x.bag: headless, with a recorder" \
  "[ \"\$(nodes '$src/launch/demo.launch' rviz:=false record:=/tmp/x.bag)\" = '/motion /avatar /skin_sim /robot_state_publisher /record ' ]"
check "demo.launch use_gui:=true: joint_state_publisher_gui instead of the motion" \
  "nodes '$src/launch/demo.launch' use_gui:=true | grep -q '^/joint_state_publisher_gui /avatar '"
check "record.launch bag:=x.bag" "[ \"\$(nodes '$src/launch/record.launch' bag:=/tmp/x.bag)\" = '/record ' ]"
check "replay.launch bag:=x.bag: skin node and player" \
  "[ \"\$(nodes '$src/launch/replay.launch' bag:=/tmp/x.bag)\" = '/skin_sim /play ' ]"
u="$src/urdf/mannequin.urdf"
check "robot.launch urdf:=X: joint_state_publisher_gui, robot_state_publisher, avatar, skin_sim, rviz" \
  "[ \"\$(nodes '$src/launch/robot.launch' urdf:=$u)\" = '/joint_state_publisher_gui /robot_state_publisher /avatar /skin_sim /rviz ' ]"
check "robot.launch urdf:=X rviz:=false: joint_state_publisher instead of the sliders, no rviz" \
  "[ \"\$(nodes '$src/launch/robot.launch' urdf:=$u rviz:=false)\" = '/joint_state_publisher /robot_state_publisher /avatar /skin_sim ' ]"
check "robot.launch urdf:=X joints:=none: the robot's own joint_states" \
  "[ \"\$(nodes '$src/launch/robot.launch' urdf:=$u joints:=none)\" = '/robot_state_publisher /avatar /skin_sim /rviz ' ]"
check "skin.launch" "[ \"\$(nodes '$src/launch/skin.launch')\" = '/skin_sim ' ]"
exit $fail
