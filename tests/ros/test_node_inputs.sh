#!/usr/bin/env bash
# Honest inputs for the nodes, through a real master:
# - a parameter of the wrong type (_substeps:=abc, _queue_size:=abc, _rate:=fast,
#   _strict_limits:=3) or out of range (_queue_size:=0, _max_split:=0) stops
#   skin_sim_node, avatar_node and motion_node at start (exit 2) with one message
#   naming the parameter and the type or range wanted; an int where a double is
#   wanted is fine;
# - motion_node refuses a built-in motion that moves no joint of robot_description;
# - avatar_node clamps joint values outside the URDF limits (here: degrees) with ONE
#   warning naming the joint and its limits, and with ~strict_limits rejects them;
# - avatar_node builds a robot of URDF primitives (box, cylinder, sphere) and a
#   Y_UP Collada mesh: one warning naming ~mesh_up_axis, none with ~mesh_up_axis:=file.
# Usage: test_node_inputs.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
lib="$bld/devel/lib/skin_sim"
skin="$lib/skin_sim_node"; avatar="$lib/avatar_node"; motion="$lib/motion_node"
[ -x "$skin" ] && [ -x "$avatar" ] && [ -x "$motion" ] || { echo "FAIL: nodes not built"; exit 1; }
t0=$(ros_env_now_ms)
D="$ROS_ENV_DIR"
# stop_int PID: SIGINT (the node logs its summary line) and wait for it
stop_int() {
  kill -INT "$1" 2> /dev/null
  for _ in $(seq 200); do kill -0 "$1" 2> /dev/null || break; sleep 0.05; done
  wait "$1" 2> /dev/null
}
set_param() { /usr/bin/python3 -c 'import sys, xmlrpc.client
xmlrpc.client.ServerProxy(sys.argv[1]).setParam("/test", sys.argv[2], sys.argv[3])' \
  "$ROS_MASTER_URI" "$1" "$2"; }

# refused <name> <pattern> <exe> <args...>: the node ends with exit 2 at once and its
# log has the pattern (each run under its own node name: private parameters stay on
# the master)
refused() {
  local name="$1" pat="$2"; shift 2
  timeout 60 "$@" __name:="$name" > "$D/$name.log" 2>&1; local rc=$?
  check "$name: refused at start (exit $rc)" "[ $rc -eq 2 ]"
  check "$name: says '$pat'" "grep -q -- \"$pat\" '$D/$name.log'"
  grep -m1 -E "ERROR|must|range|moves" "$D/$name.log" | sed 's/^/    /'
}
refused skin_substeps "~substeps must be an int, but is the string 'abc'" "$skin" _substeps:=abc
refused skin_tol_str "~tol must be a double (or an int), but is the string 'small'" "$skin" _tol:=small
refused skin_split_dbl "~max_split must be an int, but is the double 2.5" "$skin" _max_split:=2.5
refused skin_queue0 "~queue_size = 0 is out of range \[1, 1000\]" "$skin" _queue_size:=0
refused skin_split0 "~max_split = 0 is out of range \[1, 1000\]" "$skin" _max_split:=0
refused skin_bary "~barycenters must be a bool, but is the int 3" "$skin" _barycenters:=3
refused skin_color "~marker_color: 'purple' is not slide, stretch or a colour 'R G B' (each in \[0, 1\])" "$skin" _marker_color:=purple
refused skin_color_range "~marker_color: '1 2 0' is not slide" "$skin" _marker_color:="1 2 0"
refused avatar_queue "~queue_size must be an int, but is the string 'abc'" \
  "$avatar" _avatar:=mannequin _tris:=3000 _queue_size:=abc
refused avatar_queue0 "~queue_size = 0 is out of range \[1, 1000\]" \
  "$avatar" _avatar:=mannequin _tris:=3000 _queue_size:=0
refused avatar_strict "~strict_limits must be a bool, but is the int 3" \
  "$avatar" _avatar:=mannequin _strict_limits:=3
refused avatar_tris "~tris must be an int, but is the string 'many'" "$avatar" _avatar:=mannequin _tris:=many
refused avatar_up "~mesh_up_axis: 'up' is neither" "$avatar" _avatar:=mannequin _mesh_up_axis:=up
refused motion_rate "~rate must be a double (or an int), but is the string 'fast'" "$motion" _rate:=fast
refused motion_zero "~rate = 0 Hz is out of range" "$motion" _rate:=0

# an int where a double is wanted is fine: the skin node starts
ros_env_bg skin_int "$skin" __name:=skin_int _stiffness:=2000 _tol:=1
spid=$ROS_ENV_LAST_PID
check "skin_sim_node with _stiffness:=2000 (an int) starts" "ros_env_wait_node /skin_int $ROS_ENV_START_S $spid"
ros_env_stop "$spid"

# a robot of primitives with a Y_UP Collada mesh on one link
# a Y_UP Collada tetrahedron (bounding box 0.1 x 0.2 x 0.3 as the file stores it)
cp "$src/tests/data/tet_y.dae" "$D/tet_y.dae"
cat > "$D/prims.urdf" <<URDF
<robot name='prims'>
<link name='base'><visual><origin xyz='0 0 0.05'/><geometry><box size='0.4 0.3 0.1'/></geometry></visual>
<visual><geometry><mesh filename='file://$D/tet_y.dae'/></geometry></visual></link>
<link name='arm'><visual><origin xyz='0.15 0 0' rpy='0 1.5707963267948966 0'/><geometry><cylinder radius='0.04' length='0.3'/></geometry></visual></link>
<link name='ball'><visual><geometry><sphere radius='0.06'/></geometry></visual></link>
<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><origin xyz='0 0 0.2'/>
<axis xyz='0 0 1'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>
<joint name='wrist' type='fixed'><parent link='arm'/><child link='ball'/><origin xyz='0.3 0 0'/></joint>
</robot>
URDF
set_param /robot_description "$(cat "$D/prims.urdf")"
refused motion_prims "~motion 'arms' moves joints of the mannequin, and robot 'prims'" "$motion" _motion:=arms

# joint_states from a small rospy publisher: shoulder at 90 (degrees, outside [-2, 2] rad)
cat > "$D/pub.py" <<'PY'
import sys, time, rospy
from sensor_msgs.msg import JointState
from skin_sim.msg import SkinMesh, SkinStats
rospy.init_node("pub_" + sys.argv[1], anonymous=True)
got = {"meshes": 0, "rejected": 0}
def on_mesh(m): got["meshes"] += 1
def on_stats(m): got["rejected"] = m.inputs_rejected
rospy.Subscriber("kinematic_mesh", SkinMesh, on_mesh)
rospy.Subscriber("avatar_stats", SkinStats, on_stats)
pub = rospy.Publisher("joint_states", JointState, queue_size=10)
t_end = time.time() + 10
while pub.get_num_connections() == 0 and time.time() < t_end:
    time.sleep(0.05)
time.sleep(0.5)
for i in range(5):
    m = JointState(); m.header.stamp = rospy.Time.now()
    m.name = ["shoulder"]; m.position = [float(sys.argv[2])]
    pub.publish(m); time.sleep(0.1)
time.sleep(1.0)
print("meshes %d rejected %d" % (got["meshes"], got["rejected"]))
PY
for mode in ignore file; do
  ros_env_bg "avatar_$mode" "$avatar" __name:="avatar_$mode" _mesh_up_axis:=$mode _queue_size:=50
  apid=$ROS_ENV_LAST_PID
  check "avatar_node on a robot of primitives + a mesh starts (~mesh_up_axis $mode)" \
    "ros_env_wait_node /avatar_$mode $ROS_ENV_START_S $apid"
  /usr/bin/python3 "$D/pub.py" "$mode" 90 > "$D/pub_$mode.log" 2>&1
  stop_int "$apid"
  l="$D/avatar_$mode.log"
  grep -E "avatar 'prims'|WARN" "$l" | sed 's/^/    /'
  check "  it builds the body (the 3244 primitive triangles and the 4 of the mesh)" \
    "grep -q \"avatar 'prims': .* 3248 triangles\" '$l'"
  if [ $mode = ignore ]; then
    check "  one warning on the Y_UP mesh naming ~mesh_up_axis" \
      "[ \$(grep -c 'declares an up axis other than Z' '$l') -eq 1 ] && grep -q '~mesh_up_axis:=file' '$l'"
  else
    check "  no up-axis warning with ~mesh_up_axis:=file" "! grep -q 'up axis other than Z' '$l'"
  fi
  check "  5 values outside the limits: ONE warning naming the joint and its limits" \
    "[ \$(grep -c 'outside its limits' '$l') -eq 1 ] && grep -q \"joint 'shoulder' of robot 'prims' is 90 rad, outside its limits \\[-2, 2\\] rad (degrees?\" '$l'"
  cat "$D/pub_$mode.log"
  check "  and the 5 messages were posed (clamped), not rejected" \
    "grep -q 'meshes 5 rejected 0' '$D/pub_$mode.log'"
done
ros_env_bg avatar_strict_on "$avatar" __name:=avatar_strict_on _strict_limits:=true _queue_size:=50
apid=$ROS_ENV_LAST_PID
check "avatar_node with ~strict_limits starts" "ros_env_wait_node /avatar_strict_on $ROS_ENV_START_S $apid"
/usr/bin/python3 "$D/pub.py" strict 90 > "$D/pub_strict.log" 2>&1
/usr/bin/python3 "$D/pub.py" strict2 1.0 > "$D/pub_strict2.log" 2>&1
cat "$D/pub_strict.log" "$D/pub_strict2.log"
stop_int "$apid"
l="$D/avatar_strict_on.log"
grep -E "rejected|meshes out" "$l" | head -3 | sed 's/^/    /'
check "  ~strict_limits: values outside the limits rejected (naming the joint), good ones posed" \
  "grep -q \"rejected joint_states: joint 'shoulder' .*(~strict_limits)\" '$l' && grep -q 'meshes 0 rejected 0' '$D/pub_strict.log' && grep -q 'meshes 5 rejected 5' '$D/pub_strict2.log'"
for l in "$D"/*.log; do
  if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$l"; then
    grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$l" | head -30
    check "no sanitizer report in $(basename "$l")" false
  fi
done
echo "test_node_inputs: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit $fail
