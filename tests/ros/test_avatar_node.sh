#!/usr/bin/env bash
# avatar_node (the built-in mannequin) through a real master: good joint_states come
# back as kinematic_mesh with the same stamp and the URDF root frame; joint_states whose
# arrays disagree, with NaN, or naming only joints the robot lacks are rejected and
# counted (avatar_stats) while the node keeps running; unknown names beside known ones
# are ignored and counted. Usage: test_avatar_node.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
probe=$(ros_env_helper_exe skin_probe) || exit 1
exe=$(ros_env_node_exe avatar_node) || exit 1
t0=$(ros_env_now_ms)

# (a long joint_states queue: this test is about rejections, not about keeping up
# on a loaded machine)
ros_env_bg avatar "$exe" _avatar:=mannequin _tris:=3000 _queue_size:=50
apid=$ROS_ENV_LAST_PID
ros_env_check "avatar node starts" "ros_env_wait_node /avatar $ROS_ENV_START_S $apid"
ros_env_run probe "$probe" joints; rc=$?
ros_env_check "skin_probe joints passes (exit $rc)" "[ $rc -eq 0 ]"
ros_env_check "avatar node still running" "kill -0 $apid"
ros_env_sigint "$apid" 5; arc=$?
ros_env_check "avatar node exits 0 on SIGINT (exit $arc)" "[ $arc -eq 0 ]"
l="$ROS_ENV_DIR/avatar.log"
ros_env_check "rejections are logged with the reason" "grep -q 'rejected joint_states: arrays disagree' '$l'"
ros_env_check "unknown names are logged" "grep -q 'does not have' '$l'"
ros_env_check_sanitizer "$l" "no sanitizer report from the avatar node"

# robot_description (the mannequin's URDF, as demo.launch loads it) with a body mesh
# of its own, given as a package:// URI resolved through ~package_path: a torso-sized
# ellipsoid (OBJ) bound to the links by automatic weights
pkg="$ROS_ENV_DIR/pkgs/probe_meshes"
mkdir -p "$pkg/meshes"
echo "<package format=\"2\"><name>probe_meshes</name></package>" > "$pkg/package.xml"
ros_env_ellipsoid_obj "$pkg/meshes/torso.obj" 24 16   # 362 vertices
ros_env_set_robot_description "$src/urdf/mannequin.urdf"
# (other node names: the first node's private parameters stay on the master)
ros_env_bg avatar_mesh "$exe" __name:=avatar_mesh _mesh:=package://probe_meshes/meshes/torso.obj \
  _package_path:="$ROS_ENV_DIR/pkgs" _queue_size:=50
mpid=$ROS_ENV_LAST_PID
ros_env_check "avatar node with robot_description and a package:// mesh starts" "ros_env_wait_node /avatar_mesh $ROS_ENV_START_S $mpid"
ros_env_run probe_mesh "$probe" joints; rc=$?
ros_env_check "it poses that mesh for joint_states, frame pelvis (exit $rc)" "[ $rc -eq 0 ]"
ros_env_check "it says which body it uses (the ellipsoid's 362 vertices)" "grep -q \"avatar 'mannequin': 362 vertices\" '$ROS_ENV_DIR/avatar_mesh.log'"
ros_env_stop "$mpid"
# a mesh that does not exist: one clear error, exit 1
timeout 60 "$exe" __name:=avatar_missing _mesh:=package://probe_meshes/meshes/missing.obj \
  _package_path:="$ROS_ENV_DIR/pkgs" \
  > "$ROS_ENV_DIR/avatar_missing.log" 2>&1
mrc=$?
ros_env_check "a missing ~mesh ends the node with exit 1 and says so (exit $mrc)" \
  "[ $mrc -eq 1 ] && grep -q 'missing.obj' '$ROS_ENV_DIR/avatar_missing.log'"
echo "test_avatar_node: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit "$ROS_ENV_FAIL"
