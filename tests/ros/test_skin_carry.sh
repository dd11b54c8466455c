#!/usr/bin/env bash
# Rigid pieces carried, a separate skin, and the step budget, through the real nodes:
#  - a URDF robot whose links wear separate meshes (bench/make_robot.py quadruped: every
#    piece rigid on its link) driven by motion_node's sweep: skin_mesh equals
#    kinematic_mesh exactly (the float values received), skin_stats says every triangle
#    carried and none simulated, the create log says so;
#  - ~skin_mesh: a suit over a robot's swinging arm (the arm's mesh grown 10%) is
#    published in the file's own layout with a topology_id of its own, carried rigidly
#    with the leg (the distances between its vertices do not change while it moves);
#    one 1 m off the body is refused with one error naming the file and
#    ~skin_max_distance (no skin_mesh); a missing file stops the node at start (exit 2);
#  - ~step_budget: a budget no step can meet (10 us) on skin_probe's waving sheet lowers
#    the work to 1 substep x 1 iteration, said on skin_stats and as a WARN on
#    /diagnostics; with ~step_budget -1 the settings' 4 x 2 stay.
# Usage: test_skin_carry.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
avatar="$(ros_env_node_exe avatar_node)" || exit 1
skin="$(ros_env_node_exe skin_sim_node)" || exit 1
motion="$(ros_env_node_exe motion_node)" || exit 1
probe="$(ros_env_helper_exe skin_probe)" || exit 1
d="$ROS_ENV_DIR"
/usr/bin/python3 "$src/bench/make_robot.py" quadruped "$d/robot" > /dev/null || {
  echo "FAIL: make_robot.py"; exit 1; }
ros_env_set_robot_description "$d/robot/robot.urdf"
js() { /usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

# ---- the robot's own meshes, every piece rigid
ros_env_bg avatar "$avatar"
apid=$ROS_ENV_LAST_PID
ros_env_bg skin "$skin" _threads:=1
spid=$ROS_ENV_LAST_PID
ros_env_wait_node /avatar 60 "$apid" && ros_env_wait_node /skin_sim 60 "$spid" || {
  ros_env_check "avatar and skin nodes start" false; exit 1; }
ros_env_bg motion "$motion" _motion:=sweep _rate:=30
mpid=$ROS_ENV_LAST_PID
/usr/bin/python3 "$src/tests/ros/carry_probe.py" 4 "$d/robot.json" > "$d/probe_robot.log" 2>&1
cat "$d/robot.json"; echo
ros_env_check "skin_mesh came, matched to kinematic_mesh stamps" \
  "[ \"\$(js $d/robot.json 'd[\"matched\"] > 0')\" = True ]"
ros_env_check "a rigid robot's skin is its body exactly" \
  "[ \"\$(js $d/robot.json 'd[\"body_diff\"] == 0.0')\" = True ]"
ros_env_check "skin_stats: every triangle carried, none simulated" \
  "[ \"\$(js $d/robot.json 'd[\"stats\"][\"triangles_simulated\"] == 0 and d[\"stats\"][\"triangles_carried\"] > 10000')\" = True ]"
ros_env_check "the create log says what is carried" \
  "grep -q 'carried rigidly (51 of 51 pieces move with one link)' '$d/skin.log'"
ros_env_stop "$spid"

# ---- a suit over a swinging arm, from a file: a robot of two links far apart
ros_env_stop "$spid" "$mpid" "$apid"
/usr/bin/python3 - "$d" <<'PY'
import math, sys
d = sys.argv[1]
def ellipsoid(r, c, nu=24, nv=13):
    v = [(c[0], c[1], c[2] - r[2])]
    for j in range(1, nv):
        th = math.pi * j / nv
        for i in range(nu):
            ph = 2 * math.pi * i / nu
            v.append((c[0] + r[0] * math.sin(th) * math.cos(ph), c[1] + r[1] * math.sin(th) * math.sin(ph),
                      c[2] - r[2] * math.cos(th)))
    v.append((c[0], c[1], c[2] + r[2]))
    ring = lambda j, i: 1 + (j - 1) * nu + i % nu
    f = [(0, ring(1, i + 1), ring(1, i)) for i in range(nu)]
    for j in range(1, nv - 1):
        for i in range(nu):
            f += [(ring(j, i), ring(j, i + 1), ring(j + 1, i + 1)), (ring(j, i), ring(j + 1, i + 1), ring(j + 1, i))]
    f += [(ring(nv - 1, i), ring(nv - 1, i + 1), len(v) - 1) for i in range(nu)]
    return v, f
def obj(path, vf):
    with open(path, "w") as o:
        for p in vf[0]: o.write("v %.6f %.6f %.6f\n" % p)
        for t in vf[1]: o.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
obj(d + "/base.obj", ellipsoid((0.2, 0.1, 0.1), (0, 0, 0)))
obj(d + "/arm.obj", ellipsoid((0.15, 0.05, 0.05), (0, 0, 0)))
# the suit: the arm (at (0.7, 0, 0.1) at rest) grown 10%, its coordinates as written
# (no up axis turned); and the same 1 m up
obj(d + "/suit.obj", ellipsoid((0.165, 0.055, 0.055), (0.7, 0, 0.1)))
obj(d + "/far.obj", ellipsoid((0.165, 0.055, 0.055), (0.7, 0, 1.1)))
open(d + "/arm.urdf", "w").write("""<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><visual><geometry><mesh filename="file://%s/base.obj"/></geometry></visual></link>
  <link name="arm"><visual><origin xyz="0.4 0 0.1"/><geometry><mesh filename="file://%s/arm.obj"/></geometry></visual></link>
  <joint name="swing" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0.3 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
""" % (d, d))
PY
ros_env_set_robot_description "$d/arm.urdf"
ros_env_bg avatar2 "$avatar" __name:=avatar2
apid=$ROS_ENV_LAST_PID
# the skins are bound on the first kinematic_mesh: up before the motion starts (at rest)
ros_env_bg suit "$skin" __ns:=/suit kinematic_mesh:=/kinematic_mesh _threads:=1 \
  _skin_mesh:="$d/suit.obj"
spid=$ROS_ENV_LAST_PID
ros_env_bg far "$skin" __ns:=/far kinematic_mesh:=/kinematic_mesh _skin_mesh:="$d/far.obj"
fpid=$ROS_ENV_LAST_PID
ros_env_wait_node /avatar2 60 "$apid" && ros_env_wait_node /suit/skin_sim 60 "$spid" &&
  ros_env_wait_node /far/skin_sim 60 "$fpid" || { ros_env_check "the suit's nodes start" false; exit 1; }
ros_env_bg motion2 "$motion" __name:=motion2 _motion:=sweep _rate:=30
mpid=$ROS_ENV_LAST_PID
/usr/bin/python3 "$src/tests/ros/carry_probe.py" 4 "$d/suit.json" skin_mesh:=/suit/skin_mesh \
  skin_stats:=/suit/skin_stats > "$d/probe_suit.log" 2>&1
cat "$d/suit.json"; echo
ros_env_check "the suit is published in the file's layout (290 vertices)" \
  "[ \"\$(js $d/suit.json 'd.get(\"nvert\")')\" = 290 ]"
ros_env_check "with a topology_id of its own" \
  "[ \"\$(js $d/suit.json 'd.get(\"topology\") != d[\"kin_topology\"]')\" = True ]"
ros_env_check "carried with its leg: it moved, rigidly" \
  "[ \"\$(js $d/suit.json 'd[\"moved\"] > 0.01 and d[\"rigid_change\"] < 1e-5 and d[\"finite\"]')\" = True ]"
ros_env_check "skin_stats: the suit's 576 triangles carried" \
  "[ \"\$(js $d/suit.json 'd[\"stats\"][\"triangles_carried\"] == 576')\" = True ]"
ros_env_stop "$spid"

ros_env_check "a skin 1 m off the body is refused, naming the file and the bound" \
  "grep -q 'far.obj: its vertex [0-9]* is 1.* m from the body, farther than ~skin_max_distance' '$d/far.log'"
ros_env_check "... and publishes nothing" \
  "! timeout 5 rostopic echo -n 1 /far/skin_mesh/topology_id > /dev/null 2>&1"
ros_env_stop "$fpid" "$mpid" "$apid"
ros_env_run missing "$skin" __name:=missing _skin_mesh:="$d/no_such_file.obj" > /dev/null
rc=$?
ros_env_check "a missing ~skin_mesh stops the node at start (exit 2)" "[ $rc -eq 2 ]"
ros_env_check "... with one error naming it" "grep -q '~skin_mesh.*no_such_file.obj' '$d/missing.log'"

# ---- the step budget, on a deforming sheet
ros_env_bg tight "$skin" __ns:=/tight kinematic_mesh:=/sheet _step_budget:=0.00001 _threads:=1
tpid=$ROS_ENV_LAST_PID
ros_env_bg loose "$skin" __ns:=/loose kinematic_mesh:=/sheet _step_budget:=-1 _threads:=1
lpid=$ROS_ENV_LAST_PID
ros_env_wait_node /tight/skin_sim 60 "$tpid" && ros_env_wait_node /loose/skin_sim 60 "$lpid" || {
  ros_env_check "the budget nodes start" false; exit 1; }
# what both nodes say is recorded from before the stream starts to its end (rostopic
# starts slowly on a loaded machine: an echo started during the 8 s stream can miss it)
ros_env_bg diag rostopic echo /diagnostics
dpid=$ROS_ENV_LAST_PID
ros_env_bg stats_tight rostopic echo /tight/skin_stats
epids="$dpid $ROS_ENV_LAST_PID"
ros_env_bg stats_loose rostopic echo /loose/skin_stats
epids="$epids $ROS_ENV_LAST_PID"
subscribed() { # subscribed TOPIC: rostopic info lists a subscriber (120 s at most)
  for _ in $(seq 120); do
    rostopic info "$1" 2>/dev/null | sed -n '/Subscribers:/,$p' | grep -q '^ \* ' && return 0
    sleep 1
  done
  return 1
}
for t in /diagnostics /tight/skin_stats /loose/skin_stats; do subscribed "$t"; done
"$probe" stream 240 30 kinematic_mesh:=/sheet skin_mesh:=/tight/skin_mesh \
  skin_stats:=/tight/skin_stats skin_marker:=/tight/skin_marker > "$d/sheet.log" 2>&1
sleep 2
ros_env_stop $epids
last_block() { awk '/^---$/{if (b ~ /substeps:/) last = b; b = ""; next} {b = b $0 "\n"} END {if (b ~ /substeps:/) last = b; printf "%s", last}' "$1"; }
last_block "$ROS_ENV_DIR/stats_tight.log" > "$d/stats_tight.txt"
last_block "$ROS_ENV_DIR/stats_loose.log" > "$d/stats_loose.txt"
cp "$ROS_ENV_DIR/diag.log" "$d/diag.txt"
cat "$d/stats_tight.txt" | grep -E "substeps|iterations_per|step_budget"
ros_env_check "an unmeetable budget: 1 substep x 1 iteration" \
  "grep -q '^substeps: 1$' '$d/stats_tight.txt' && grep -q '^iterations_per_substep: 1$' '$d/stats_tight.txt'"
ros_env_check "... the budget on skin_stats (0.01 ms)" \
  "grep -qE '^step_budget_ms: 0\\.0(09|1)' '$d/stats_tight.txt'"
ros_env_check "... and /diagnostics warns that accuracy is traded for time" \
  "grep -q 'accuracy traded for time' '$d/diag.txt' && grep -q 'substeps x iterations in force' '$d/diag.txt'"
ros_env_check "no budget (-1): the settings' 4 x 2" \
  "grep -q '^substeps: 4$' '$d/stats_loose.txt' && grep -q '^iterations_per_substep: 2$' '$d/stats_loose.txt'"
ros_env_stop "$tpid" "$lpid"
exit $ROS_ENV_FAIL
