#!/usr/bin/env bash
# One skin, whatever the mesh: URDF robots whose link meshes duplicate vertices along
# their seams (flat normals, one mesh per link) driven through avatar_node and
# skin_sim_node with joint_states (tests/ros/seam_probe.py, real nodes and master):
#  - a robot this test writes: two links, each a subdivided box with a normal per side
#    (every box edge a seam of duplicated vertices; OBJ through assimp), one revolute
#    joint swinging;
#  - the Solo quadruped of ../shared/data/urdf-solo-quadruped (package:// URIs; 8 joints
#    swinging), skipped (saying so) where that data is absent.
# For each: every skin_mesh keeps the body's layout (vertex count, triangles,
# topology_id), is finite, and every seam stays closed: the copies of one welded vertex
# are bit-identical (distance exactly 0) in every skin_mesh; the skin has as many pieces
# as the welded body; skin_marker's corners of one welded vertex share a point and a
# slide colour. Figures (pieces, seam gaps) are printed.
# SKIN_SIM_NODE=PATH runs another skin_sim_node binary (to measure an older one).
# Usage: test_skin_seams.sh BUILD_DIR [SOURCE_DIR].
set -u
. "$(dirname "$0")/ros_env.sh"
ros_env_start "$@" || exit $?
avatar=$(find "$bld/devel/lib/skin_sim" -name avatar_node -type f | head -n 1)
skin=${SKIN_SIM_NODE:-$(find "$bld/devel/lib/skin_sim" -name skin_sim_node -type f | head -n 1)}
[ -x "$avatar" ] && [ -x "$skin" ] || { echo "FAIL: avatar_node or skin_sim_node not built"; exit 1; }
secs=${SEAM_SECONDS:-8}
t0=$(ros_env_now_ms)

# run_robot NAME URDF PACKAGE_PATH: both nodes on this robot, the probe for $secs s
run_robot() {
  local name="$1" urdf="$2" pkgpath="$3"
  /usr/bin/python3 -c 'import sys, xmlrpc.client
xmlrpc.client.ServerProxy(sys.argv[1]).setParam("/test", "/robot_description", open(sys.argv[2]).read())' \
    "$ROS_MASTER_URI" "$urdf"
  ros_env_bg "avatar_$name" "$avatar" __name:="avatar_$name" _package_path:="$pkgpath" _queue_size:=5
  local apid=$ROS_ENV_LAST_PID
  ros_env_bg "skin_$name" "$skin" __name:="skin_$name" _marker_rate:=2
  local spid=$ROS_ENV_LAST_PID
  if ! ros_env_wait_node "/avatar_$name" $ROS_ENV_START_S "$apid" || ! ros_env_wait_node "/skin_$name" $ROS_ENV_START_S "$spid"; then
    check "$name: avatar_node and skin_sim_node start" false
    return
  fi
  timeout 300 /usr/bin/python3 "$src/tests/ros/seam_probe.py" "$urdf" "$secs" \
    "$ROS_ENV_DIR/$name.json" > "$ROS_ENV_DIR/probe_$name.log" 2>&1
  local rc=$?
  cat "$ROS_ENV_DIR/probe_$name.log"
  check "$name: the probe measured skin_mesh (exit $rc)" "[ $rc -eq 0 ]"
  ros_env_stop "$spid" "$apid"
  grep -h "skin created" "$ROS_ENV_DIR/skin_$name.log" | sed 's/^.*skin created/skin created/'
  if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$ROS_ENV_DIR/skin_$name.log"; then
    grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$ROS_ENV_DIR/skin_$name.log" | head -30
    check "$name: no sanitizer report from the skin node" false
  fi
  [ $rc -eq 0 ] || return
  local j="$ROS_ENV_DIR/$name.json"
  val() { /usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get(sys.argv[2], -1))' "$j" "$1"; }
  printf '%s: %s vertices (%s seam copies, %s welded), %s triangles; %s skin_mesh; pieces: body indices %s, welded body %s, skin (last) %s; max seam gap %s m (median frame %s m), at most %s seams open > 1 mm\n' \
    "$name" "$(val vertices)" "$(val seam_copies)" "$(val welded_vertices)" "$(val triangles)" \
    "$(val skin_mesh)" "$(val pieces_body_indices)" "$(val pieces_body_welded)" \
    "$(val pieces_skin_last)" "$(val max_gap_m)" "$(val median_gap_m)" "$(val max_seams_open_1mm)"
  if [ "${NO_SEAMS_OK:-0}" = 1 ]; then
    echo "note: $name as shipped has $(val seam_copies) seam copies (assimp joins vertices without normals)"
  else
    check "$name: the body has seams (duplicated vertices)" "[ $(val seam_copies) -gt 0 ]"
  fi
  check "$name: skin_mesh kept coming (>= 3: the first and two steps, even in a sanitizer build)" "[ $(val skin_mesh) -ge 3 ]"
  check "$name: every skin_mesh in the body's layout (vertices, triangles, topology_id)" "[ $(val bad_layout_skin_mesh) -eq 0 ]"
  check "$name: every skin_mesh finite" "[ $(val nonfinite_skin_mesh) -eq 0 ]"
  check "$name: every seam closed in every skin_mesh (max gap exactly 0)" "[ \"$(val max_gap_m)\" = 0.0 ]"
  check "$name: the skin is as many pieces as the welded body" "[ $(val pieces_skin_last) -eq $(val pieces_body_welded) ]"
  check "$name: skin_marker came ($(val skin_marker)) and every one is a TRIANGLE_LIST of the body's triangles, seam corners at one point in one slide colour ($(val skin_marker_ok) ok; $(val skin_marker_bad))" \
    "[ $(val skin_marker) -ge 1 ] && [ $(val skin_marker_ok) -eq $(val skin_marker) ]"
}

# 1. a robot written here: two boxes with flat normals (every box edge a seam)
pkg="$ROS_ENV_DIR/pkgs/seam_robot"
mkdir -p "$pkg/meshes"
echo "<package format=\"2\"><name>seam_robot</name></package>" > "$pkg/package.xml"
/usr/bin/python3 - "$pkg/meshes" <<'PY'
import sys
def box(path, sx, sy, sz, n=6):
    """A box of n x n quads per side, a normal per side: the corners and edges of
    the box are duplicated (one copy per side), as OBJ exporters write flat shading."""
    v, vn, f = [], [], []
    sides = [((0, 1, 2), 1), ((0, 1, 2), -1), ((1, 2, 0), 1), ((1, 2, 0), -1),
             ((2, 0, 1), 1), ((2, 0, 1), -1)]
    size = (sx, sy, sz)
    for (a, b, c), s in sides:
        nrm = [0.0, 0.0, 0.0]; nrm[c] = float(s); vn.append(nrm)
        base = len(v)
        for j in range(n + 1):
            for i in range(n + 1):
                p = [0.0, 0.0, 0.0]
                p[a] = size[a] * (i / n - 0.5); p[b] = size[b] * (j / n - 0.5); p[c] = 0.5 * size[c] * s
                v.append(p)
        k = len(vn)
        for j in range(n):
            for i in range(n):
                q = [base + j * (n + 1) + i, base + j * (n + 1) + i + 1,
                     base + (j + 1) * (n + 1) + i + 1, base + (j + 1) * (n + 1) + i]
                if s < 0: q.reverse()
                f.append((q[0], q[1], q[2], k)); f.append((q[0], q[2], q[3], k))
    with open(path, "w") as o:
        for p in v: o.write("v %.6f %.6f %.6f\n" % tuple(p))
        for p in vn: o.write("vn %.1f %.1f %.1f\n" % tuple(p))
        for a, b, c, k in f: o.write("f %d//%d %d//%d %d//%d\n" % (a + 1, k, b + 1, k, c + 1, k))
box(sys.argv[1] + "/base.obj", 0.30, 0.20, 0.10)
box(sys.argv[1] + "/arm.obj", 0.40, 0.08, 0.08)
PY
cat > "$pkg/seam_robot.urdf" <<'EOF'
<?xml version="1.0"?>
<robot name="seam_robot">
  <link name="base"><visual><geometry><mesh filename="package://seam_robot/meshes/base.obj"/></geometry></visual></link>
  <link name="arm"><visual><origin xyz="0.25 0 0"/><geometry><mesh filename="package://seam_robot/meshes/arm.obj"/></geometry></visual></link>
  <joint name="swing" type="revolute">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 0.15"/><axis xyz="0 0 1"/>
    <limit lower="-1.5" upper="1.5" effort="1" velocity="10"/>
  </joint>
</robot>
EOF
run_robot seam_robot "$pkg/seam_robot.urdf" "$ROS_ENV_DIR/pkgs"

# 2. the Solo quadruped (real robot data nobody here made). Its OBJ meshes carry no
# normals, so assimp joins their vertices and the body has no seams as shipped; the
# same robot with normals split at creases over 40 degrees (what exporters write for
# hard edges: one vertex copy per smoothing group) is the seamed real robot.
solo="${SS_SHARED_DIR:-$src/../shared}/data/urdf-solo-quadruped"
solo_urdf="$solo/example-robot-data/robots/solo_description/robots/solo.urdf"
if [ -f "$solo_urdf" ]; then
  cp="$ROS_ENV_DIR/pkgs_creased/solo_creased"
  mkdir -p "$cp/meshes"
  echo "<package format=\"2\"><name>solo_creased</name></package>" > "$cp/package.xml"
  /usr/bin/python3 - "$solo_urdf" "$cp" <<'PY'
import math, os, re, sys
urdf, out = sys.argv[1], sys.argv[2]
text = open(urdf).read()
pre = "package://example-robot-data/robots/solo_description/meshes/obj/with_foot/"
src_dir = os.path.join(os.path.dirname(urdf), "..", "meshes", "obj", "with_foot")
for name in sorted(set(re.findall(re.escape(pre) + r"([\w.]+)", text))):
    v, f = [], []
    for line in open(os.path.join(src_dir, name)):
        t = line.split()
        if t and t[0] == "v": v.append(tuple(map(float, t[1:4])))
        elif t and t[0] == "f": f.append(tuple(int(x.split("/")[0]) - 1 for x in t[1:4]))
    def nrm(a):
        l = math.sqrt(sum(x * x for x in a)) or 1.0
        return tuple(x / l for x in a)
    fn = []
    for a, b, c in f:
        e1 = [v[b][i] - v[a][i] for i in range(3)]; e2 = [v[c][i] - v[a][i] for i in range(3)]
        fn.append(nrm((e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])))
    around = [[] for _ in v]
    for i, t in enumerate(f):
        for c in t: around[c].append(i)
    cos_max = math.cos(math.radians(40.0))
    corner = {}
    nv, nn = [], []
    for vi, faces in enumerate(around):
        groups = []
        for fi in faces:
            for g in groups:
                if sum(fn[fi][k] * fn[g[0]][k] for k in range(3)) > cos_max:
                    g.append(fi); break
            else:
                groups.append([fi])
        for g in groups:
            n = nrm(tuple(sum(fn[fi][k] for fi in g) for k in range(3)))
            for fi in g: corner[(fi, vi)] = len(nv)
            nv.append(v[vi]); nn.append(n)
    with open(os.path.join(out, "meshes", name), "w") as o:
        for p in nv: o.write("v %.9g %.9g %.9g\n" % p)
        for n in nn: o.write("vn %.6f %.6f %.6f\n" % n)
        for i, t in enumerate(f):
            o.write("f " + " ".join("%d//%d" % (corner[(i, c)] + 1, corner[(i, c)] + 1) for c in t) + "\n")
open(os.path.join(out, "solo_creased.urdf"), "w").write(text.replace(pre, "package://solo_creased/meshes/"))
PY
  run_robot solo_creased "$cp/solo_creased.urdf" "$ROS_ENV_DIR/pkgs_creased"
  NO_SEAMS_OK=1 run_robot solo "$solo_urdf" "$solo"
else
  echo "skipped: the Solo quadruped ($solo) is absent; only the robot written here was tested"
fi

echo "test_skin_seams: $(($(ros_env_now_ms) - t0)) ms after the master was up"
exit $fail
