#!/usr/bin/env bash
# avatar_node (the built-in mannequin) through a real master: good joint_states come
# back as kinematic_mesh with the same stamp and the URDF root frame; joint_states whose
# arrays disagree, with NaN, or naming only joints the robot lacks are rejected and
# counted (avatar_stats) while the node keeps running; unknown names beside known ones
# are ignored and counted. Usage: test_avatar_node.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
probe="$bld/tests/ros/skin_probe"
exe=$(find "$bld/devel/lib/skin_sim" -name avatar_node -type f | head -n 1)
[ -x "$probe" ] && [ -x "$exe" ] || { echo "FAIL: skin_probe or avatar_node not built"; exit 1; }
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
t0=$(ros_env_now_ms)

# (a long joint_states queue: this test is about rejections, not about keeping up
# on a loaded machine)
ros_env_bg avatar "$exe" _avatar:=mannequin _tris:=3000 _queue_size:=50
apid=$ROS_ENV_LAST_PID
check "avatar node starts" "ros_env_wait_node /avatar 30 $apid"
"$probe" joints > "$ROS_ENV_DIR/probe.log" 2>&1
rc=$?
cat "$ROS_ENV_DIR/probe.log"
check "skin_probe joints passes (exit $rc)" "[ $rc -eq 0 ]"
check "avatar node still running" "kill -0 $apid"
kill -INT "$apid"
for _ in $(seq 100); do kill -0 "$apid" 2> /dev/null || break; sleep 0.05; done
wait "$apid"; arc=$?
check "avatar node exits 0 on SIGINT (exit $arc)" "[ $arc -eq 0 ]"
l="$ROS_ENV_DIR/avatar.log"
check "rejections are logged with the reason" "grep -q 'rejected joint_states: arrays disagree' '$l'"
check "unknown names are logged" "grep -q 'does not have' '$l'"
if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$l"; then
  grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$l" | head -30
  check "no sanitizer report from the avatar node" false
fi

# robot_description (the mannequin's URDF, as demo.launch loads it) with a body mesh
# of its own, given as a package:// URI resolved through ~package_path: a torso-sized
# ellipsoid (OBJ) bound to the links by automatic weights
pkg="$ROS_ENV_DIR/pkgs/probe_meshes"
mkdir -p "$pkg/meshes"
echo "<package format=\"2\"><name>probe_meshes</name></package>" > "$pkg/package.xml"
/usr/bin/python3 - "$pkg/meshes/torso.obj" <<'PY'
import math, sys
nu, nv = 24, 16
lines, idx = [], {}
verts = [(0.0, 0.0, 0.35 + 0.35)]
for j in range(1, nv):
    th = math.pi * j / nv
    for i in range(nu):
        ph = 2 * math.pi * i / nu
        verts.append((0.15 * math.sin(th) * math.cos(ph), 0.15 * math.sin(th) * math.sin(ph),
                      0.35 + 0.35 * math.cos(th)))
verts.append((0.0, 0.0, 0.0))
ring = lambda j, i: 1 + (j - 1) * nu + (i % nu)
faces = []
for i in range(nu):
    faces.append((0, ring(1, i), ring(1, i + 1)))
for j in range(1, nv - 1):
    for i in range(nu):
        a, b, c, d = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
        faces += [(a, c, d), (a, d, b)]
last = len(verts) - 1
for i in range(nu):
    faces.append((ring(nv - 1, i), last, ring(nv - 1, i + 1)))
with open(sys.argv[1], "w") as f:
    for v in verts:
        f.write("v %.6f %.6f %.6f\n" % v)
    for t in faces:
        f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
PY
/usr/bin/python3 -c 'import sys, xmlrpc.client
xmlrpc.client.ServerProxy(sys.argv[1]).setParam("/test", "/robot_description", open(sys.argv[2]).read())' \
  "$ROS_MASTER_URI" "$src/urdf/mannequin.urdf"
# (other node names: the first node's private parameters stay on the master)
ros_env_bg avatar_mesh "$exe" __name:=avatar_mesh _mesh:=package://probe_meshes/meshes/torso.obj \
  _package_path:="$ROS_ENV_DIR/pkgs" _queue_size:=50
mpid=$ROS_ENV_LAST_PID
check "avatar node with robot_description and a package:// mesh starts" "ros_env_wait_node /avatar_mesh 30 $mpid"
"$probe" joints > "$ROS_ENV_DIR/probe_mesh.log" 2>&1
rc=$?
cat "$ROS_ENV_DIR/probe_mesh.log"
check "it poses that mesh for joint_states, frame pelvis (exit $rc)" "[ $rc -eq 0 ]"
check "it says which body it uses (the ellipsoid's 362 vertices)" "grep -q \"avatar 'mannequin': 362 vertices\" '$ROS_ENV_DIR/avatar_mesh.log'"
ros_env_stop "$mpid"
# a mesh that does not exist: one clear error, exit 1
timeout 60 "$exe" __name:=avatar_missing _mesh:=package://probe_meshes/meshes/missing.obj \
  _package_path:="$ROS_ENV_DIR/pkgs" \
  > "$ROS_ENV_DIR/avatar_missing.log" 2>&1
mrc=$?
check "a missing ~mesh ends the node with exit 1 and says so (exit $mrc)" \
  "[ $mrc -eq 1 ] && grep -q 'missing.obj' '$ROS_ENV_DIR/avatar_missing.log'"
echo "test_avatar_node: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit $fail
