#!/usr/bin/env bash
# skinsim run on avatars: the built-in mannequin, a URDF with a CSV motion
# (the mannequin's own file, and the Solo robot whose links wear their own
# visual meshes), a region mask, and rigged characters nobody here made
# (Debian's assimp-testmodels, ../shared/data) animated for 100 frames with
# the walk: 0 failures; robots of URDF primitives, mixed with a Y_UP Collada mesh
# (--mesh-up-axis), joint values outside the limits (--strict-limits). Bad input:
# one clear message, exit 2, no crash.
set -u
. "$(dirname "$0")/lib.sh"   # bld, src, exe, tmp, py, check
if ! "$exe" help | grep -q -- '--asset'; then echo "skinsim built without avatars: skipped"; exit 77; fi
shared="${SS_SHARED_DIR:-$src/../shared}"
models=/usr/share/assimp/models
field() { $py -c "import json,sys; print(json.load(open('$1'))['$2'])"; }

# run <name> <args...>: must exit 0 with 0 failures (and print the summary)
run() {
  local name="$1"; shift
  "$exe" run "$@" --json "$tmp/$name.json" > "$tmp/$name.txt" 2> "$tmp/$name.err"; local rc=$?
  check "$name: exit 0" "[ $rc -eq 0 ]"
  [ $rc -eq 0 ] || { cat "$tmp/$name.err"; return; }
  cat "$tmp/$name.txt"
  check "$name: 0 failures" "[ \"\$(field '$tmp/$name.json' failures)\" = 0 ]"
  check "$name: walk did not snag" "[ \"\$(field '$tmp/$name.json' snags)\" = 0 ]"
}

run demo --avatar demo --frames 40
# the automatic weights of a large mannequin (a factor CHOLMOD would make
# supernodal, through the BLAS): the same skin for any BLAS thread count
OPENBLAS_NUM_THREADS=1 run demo19k_blas1 --avatar demo --avatar-tris 19000 --frames 2
OPENBLAS_NUM_THREADS=2 run demo19k_blas2 --avatar demo --avatar-tris 19000 --frames 2
check "demo 19k: the same bits on 1 and 2 BLAS threads" \
  "[ \"\$(field '$tmp/demo19k_blas1.json' final_hash)\" = \"\$(field '$tmp/demo19k_blas2.json' final_hash)\" ]"
run demo_region --avatar demo --frames 20 --region l_upper_arm,l_forearm,torso
check "demo_region: a part of the skin simulated" \
  "$py -c 'import json,sys; a=json.load(open(\"$tmp/demo_region.json\")); sys.exit(0 if 0 < a[\"region_faces\"] < a[\"triangles\"] else 1)'"

# a URDF with a body mesh file and a CSV motion: the mannequin's URDF over a
# PLY of its body (written by skinsim itself), weights computed automatically
"$exe" run --avatar demo --motion elbows --frames 1 --out "$tmp/ply" > /dev/null 2>&1 || true
printf 'time,l_elbow,r_elbow\n0,0,0\n0.5,1.4,-1.4\n1.0,0,0\n' > "$tmp/elbows.csv"
if [ -f "$tmp/ply/body_0001.ply" ]; then
  run urdf_mesh_csv --urdf "$src/urdf/mannequin.urdf" --mesh "$tmp/ply/body_0001.ply" \
    --motion "$tmp/elbows.csv"
  check "urdf_mesh_csv: 30 frames (the CSV's second)" "[ \"\$(field '$tmp/urdf_mesh_csv.json' frames)\" = 30 ]"
else
  check "demo body written as PLY" "false"
fi

solo="$shared/data/urdf-solo-quadruped/example-robot-data"
if [ -f "$solo/robots/solo_description/robots/solo.urdf" ]; then
  printf 'time,FL_HFE,FL_KFE,HR_HFE,HR_KFE\n0,0,0,0,0\n0.5,0.8,-1.6,-0.8,1.6\n1.0,0,0,0,0\n' > "$tmp/solo.csv"
  run solo --urdf "$solo/robots/solo_description/robots/solo.urdf" \
    --package-path "example-robot-data=$solo" --motion "$tmp/solo.csv" --frames 30
else
  echo "skip: $solo is absent (the Solo URDF)"
fi

# rigged, animated characters nobody here made: 100 frames each
assets=0
for a in "$models/X/BCN_Epileptic.X" "$models/X/Testwuson.X"; do
  if [ -f "$a" ]; then run "$(basename "$a")" --asset "$a" --frames 100; assets=$((assets + 1));
  else echo "skip: $a is absent (Debian package assimp-testmodels)"; fi
done
fox="$shared/data/gltf-khronos-skinned/Fox/glTF-Binary/Fox.glb"
if [ -f "$fox" ]; then
  # the file says metres but holds centimetres (MANIFEST.md): scale it
  run fox_run --asset "$fox" --anim Run --asset-scale 0.01 --frames 100; assets=$((assets + 1))
else
  echo "skip: $fox is absent (../shared/data)"
fi

bad() { # bad <description> <args...>: exit 2, one line on stderr naming the problem
  local what="$1"; shift
  "$exe" "$@" > /dev/null 2> "$tmp/err"; local rc=$?
  check "$what: exit 2" "[ $rc -eq 2 ]"
  check "$what: one message" "[ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q 'skinsim: ' '$tmp/err'"
}
echo '<robot name="x"><link name="a"/><joint' > "$tmp/broken.urdf"
printf 'time,no_such_joint\n0,0\n1,1\n' > "$tmp/unknown_joint.csv"
printf 'time,l_elbow\n0,0\n1\n' > "$tmp/short_row.csv"
bad "missing URDF" run --urdf "$tmp/nope.urdf" --motion arms
bad "URDF that does not parse" run --urdf "$tmp/broken.urdf" --motion arms
bad "missing body mesh" run --urdf "$src/urdf/mannequin.urdf" --mesh "$tmp/nope.obj" --motion arms
bad "unknown joint in the motion" run --urdf "$src/urdf/mannequin.urdf" --motion "$tmp/unknown_joint.csv"
bad "short CSV row" run --urdf "$src/urdf/mannequin.urdf" --motion "$tmp/short_row.csv"
bad "unknown region link" run --avatar demo --region no_such_link --frames 1
bad "scene and avatar both" run --scene fold --avatar demo
bad "unknown avatar" run --avatar robocop
bad "missing asset" run --asset "$tmp/none.glb"
if [ -f "$models/X/BCN_Epileptic.X" ]; then
  bad "animation out of range" run --asset "$models/X/BCN_Epileptic.X" --anim 7
fi

# ---- inputs that used to run silently wrong
# a robot of primitives (box, cylinder placed by its origin, sphere) and one mixing a
# Y_UP Collada mesh with a sphere: both are bodies (they used to be refused)
cat > "$tmp/prims.urdf" <<'URDF'
<robot name='prims'>
<link name='base'><visual><origin xyz='0 0 0.05'/><geometry><box size='0.4 0.3 0.1'/></geometry></visual></link>
<link name='arm'><visual><origin xyz='0.15 0 0' rpy='0 1.5707963267948966 0'/><geometry><cylinder radius='0.04' length='0.3'/></geometry></visual></link>
<link name='ball'><visual><geometry><sphere radius='0.06'/></geometry></visual></link>
<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><origin xyz='0 0 0.2'/>
<axis xyz='0 0 1'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>
<joint name='wrist' type='fixed'><parent link='arm'/><child link='ball'/><origin xyz='0.3 0 0'/></joint>
</robot>
URDF
printf 'time,shoulder\n0,0\n1,1.5\n2,-1.5\n' > "$tmp/shoulder.csv"
printf 'shoulder,wrist\n0,0\n1,1\n' > "$tmp/notime.csv"
bad "CSV without a time column" run --urdf "$tmp/prims.urdf" --motion "$tmp/notime.csv"
check "  ... names the column" "grep -q \"first column must be 'time'.*'shoulder'\" '$tmp/err'"
# a motion ending at t = 1e308 s: its frame count was a float-to-int cast out of range
# (undefined behaviour, exit 0); now refused, naming the line and the column
printf 'time,shoulder\n0,0\n1e308,1\n' > "$tmp/endless.csv"
bad "CSV ending at 1e308 s" run --urdf "$tmp/prims.urdf" --motion "$tmp/endless.csv"
check "  ... names the line, the column and the bound" "grep -q \"endless.csv', line 3, column 1 (time): 1e+308 s is past the bound\" '$tmp/err'"
# joints forming a cycle under the root (b -> c -> b, the root's joint named last so that
# it was the one kept): ran with exit 0 on two of the three links; now refused
cat > "$tmp/cycle.urdf" <<'URDF'
<robot name='cycle'>
<link name='a'><visual><geometry><box size='0.1 0.1 0.1'/></geometry></visual></link>
<link name='b'><visual><geometry><box size='0.1 0.1 0.1'/></geometry></visual></link>
<link name='c'><visual><geometry><box size='0.1 0.1 0.1'/></geometry></visual></link>
<joint name='z1' type='revolute'><parent link='a'/><child link='b'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint>
<joint name='j2' type='fixed'><parent link='b'/><child link='c'/><origin xyz='0.2 0 0'/></joint>
<joint name='j3' type='fixed'><parent link='c'/><child link='b'/><origin xyz='0.2 0 0'/></joint>
</robot>
URDF
printf 'time,z1\n0,0\n1,0.5\n' > "$tmp/z1.csv"
bad "URDF whose joints form a cycle" run --urdf "$tmp/cycle.urdf" --motion "$tmp/z1.csv" --frames 1
check "  ... names the link and both joints" "grep -q \"link 'b' is the child of joints 'j3' and 'z1'\" '$tmp/err'"
# inputs that ran silently wrong: a duplicated joint column (one of the two silently
# won): exit 2 naming both columns; times as absolute stamps: exit 2 (the bound); times
# in milliseconds (the robot seemed to stand still): one warning; a URDF mesh in
# millimetres (a 550 m robot): one warning, as --asset gives
printf 'time,shoulder,shoulder\n0,0,1\n1,1,0\n' > "$tmp/dup.csv"
bad "CSV naming a joint twice" run --urdf "$tmp/prims.urdf" --motion "$tmp/dup.csv" --frames 1
check "  ... names both columns" "grep -q \"columns 2 and 3 both name joint 'shoulder'\" '$tmp/err'"
printf 'time,shoulder\n1764230400.0,0\n1764230400.5,1\n' > "$tmp/stamps.csv"
bad "CSV of absolute stamps" run --urdf "$tmp/prims.urdf" --motion "$tmp/stamps.csv" --frames 1
check "  ... says absolute stamps" "grep -q 'absolute stamps' '$tmp/err'"
printf 'time,shoulder\n0,0\n33,0.5\n67,1\n100,1.5\n133,1\n' > "$tmp/ms.csv"
"$exe" run --urdf "$tmp/prims.urdf" --motion "$tmp/ms.csv" --frames 1 --out "$tmp/ms_out" > /dev/null 2> "$tmp/err"; rc=$?
check "CSV in milliseconds: runs (exit $rc) with one warning naming the column and the cause" \
  "[ $rc -eq 0 ] && [ \$(grep -c 'warning' '$tmp/err') -eq 1 ] && grep -q \"ms.csv', column 1 (time): rows 33 s apart (median) over 133 s: times in milliseconds?\" '$tmp/err'"
printf 'v 0 0 0\nv 300 0 0\nv 0 200 0\nv 0 0 550\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$tmp/mm_tet.obj"
cat > "$tmp/mm.urdf" <<'URDF'
<robot name='mm'>
<link name='base'><visual><geometry><mesh filename='mm_tet.obj'/></geometry></visual></link>
<link name='arm'><visual><geometry><box size='0.1 0.1 0.1'/></geometry></visual></link>
<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><origin xyz='0 0 0.2'/>
<axis xyz='0 0 1'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>
</robot>
URDF
"$exe" run --urdf "$tmp/mm.urdf" --motion "$tmp/shoulder.csv" --frames 1 --out "$tmp/mm_out" > /dev/null 2> "$tmp/err"; rc=$?
check "URDF mesh in millimetres: runs (exit $rc) with one warning naming the mesh and the link" \
  "[ $rc -eq 0 ] && [ \$(grep -c 'warning' '$tmp/err') -eq 1 ] && grep -q \"mesh over 20 m across (first: '.*mm_tet.obj' of link 'base', 550 m at scale 1 1 1): a file in millimetres\" '$tmp/err'"
sed 's|filename=.mm_tet.obj./>|filename="mm_tet.obj" scale="0.001 0.001 0.001"/>|' "$tmp/mm.urdf" > "$tmp/mm_scaled.urdf"
"$exe" run --urdf "$tmp/mm_scaled.urdf" --motion "$tmp/shoulder.csv" --frames 1 --out "$tmp/mm_out2" > /dev/null 2> "$tmp/err"; rc=$?
check "the same with <mesh scale='0.001 ...'/>: exit 0, no warning" "[ $rc -eq 0 ] && ! grep -q 'warning' '$tmp/err'"
run prims --urdf "$tmp/prims.urdf" --motion "$tmp/shoulder.csv" --frames 30
check "prims: 3244 triangles at the default 2 cm edge" "[ \"\$(field '$tmp/prims.json' triangles)\" = 3244 ]"
run prims_coarse --urdf "$tmp/prims.urdf" --motion "$tmp/shoulder.csv" --frames 5 --primitive-edge 0.05
check "prims_coarse: --primitive-edge 0.05 gives fewer triangles" \
  "[ \"\$(field '$tmp/prims_coarse.json' triangles)\" -lt 2000 ]"
bad "built-in motion on a robot without its joints" run --urdf "$tmp/prims.urdf" --motion arms
check "  ... names the motion and the robot" "grep -q \"'arms'.*robot 'prims'\" '$tmp/err'"
bad "bad --mesh-up-axis" run --urdf "$tmp/prims.urdf" --motion "$tmp/shoulder.csv" --mesh-up-axis up
# a Y_UP Collada tetrahedron (bounding box 0.1 x 0.2 x 0.3 as the file stores it)
cp "$src/tests/data/tet_y.dae" "$tmp/tet_y.dae"
cat > "$tmp/mixed.urdf" <<'URDF'
<robot name='mixed'>
<link name='body'><visual><geometry><mesh filename='tet_y.dae'/></geometry></visual>
<visual><origin xyz='0.5 0 0'/><geometry><mesh filename='tet_y.dae'/></geometry></visual></link>
<link name='head'><visual><geometry><sphere radius='0.05'/></geometry></visual></link>
<joint name='neck' type='revolute'><parent link='body'/><child link='head'/><origin xyz='0 0 0.4'/>
<axis xyz='0 1 0'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint>
</robot>
URDF
printf 'time,neck\n0,0\n0.5,0.8\n1,0\n' > "$tmp/neck.csv"
"$exe" run --urdf "$tmp/mixed.urdf" --motion "$tmp/neck.csv" --out "$tmp/mixed_ignore" > /dev/null 2> "$tmp/err"; rc=$?
check "mixed mesh + sphere: exit 0" "[ $rc -eq 0 ]"
check "Y_UP Collada, --mesh-up-axis ignore (default): one warning naming the option" \
  "[ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q 'warning: .*Y_UP.*--mesh-up-axis file' '$tmp/err'"
cat "$tmp/err"
"$exe" run --urdf "$tmp/mixed.urdf" --motion "$tmp/neck.csv" --mesh-up-axis file --frames 1 \
  --out "$tmp/mixed_file" > /dev/null 2> "$tmp/err"; rc=$?
check "--mesh-up-axis file: exit 0, no warning" "[ $rc -eq 0 ] && [ ! -s '$tmp/err' ]"
check "the tetrahedron as written (ignore: z up to 0.3) or turned Z-up (file: y down to -0.3)" "$py - '$tmp' <<'PY'
import struct, sys
def verts(path):
    b = open(path, 'rb').read(); h = b.index(b'end_header\n') + 11
    n = int(b[:h].decode().split('element vertex ')[1].split()[0])
    return [struct.unpack_from('<3f', b, h + 12 * i) for i in range(n)]
ign, fil = verts(sys.argv[1] + '/mixed_ignore/body_0001.ply')[:4], verts(sys.argv[1] + '/mixed_file/body_0001.ply')[:4]
lo = lambda v, k: min(p[k] for p in v); hi = lambda v, k: max(p[k] for p in v)
print('ignore: z', lo(ign, 2), hi(ign, 2), ' file: y', lo(fil, 1), hi(fil, 1), 'z', hi(fil, 2))
ok = abs(hi(ign, 2) - 0.3) < 1e-6 and abs(lo(fil, 1) + 0.3) < 1e-6 and abs(hi(fil, 2) - 0.2) < 1e-6
sys.exit(0 if ok else 1)
PY"
# joint values outside the URDF limits (here in degrees): clamped with one warning naming
# the joint and its limits; --strict-limits makes it an error
printf 'time,l_elbow,r_elbow\n0,0,0\n0.5,90,45\n1,0,0\n' > "$tmp/degrees.csv"
if [ -f "$tmp/ply/body_0001.ply" ]; then
  "$exe" run --urdf "$src/urdf/mannequin.urdf" --mesh "$tmp/ply/body_0001.ply" \
    --motion "$tmp/degrees.csv" --frames 2 > /dev/null 2> "$tmp/err"; rc=$?
  check "degrees: exit 0 (clamped)" "[ $rc -eq 0 ]"
  check "degrees: one warning naming l_elbow and its limits" \
    "[ \$(wc -l < '$tmp/err') -eq 1 ] && grep -q \"warning: .*'l_elbow'.*\\[0, 2.6\\] rad (degrees?.*--strict-limits\" '$tmp/err'"
  cat "$tmp/err"
  bad "degrees with --strict-limits" run --urdf "$src/urdf/mannequin.urdf" \
    --mesh "$tmp/ply/body_0001.ply" --motion "$tmp/degrees.csv" --strict-limits
  "$exe" run --urdf "$tmp/prims.urdf" --motion "$tmp/shoulder.csv" --frames 1 --strict-limits \
    > /dev/null 2> "$tmp/err"; rc=$?
  check "motion within limits with --strict-limits: exit 0, silent" "[ $rc -eq 0 ] && [ ! -s '$tmp/err' ]"
fi
[ $assets -ge 2 ] || { echo "fewer than two real assets here: the real-asset part was skipped"; [ $fail -eq 0 ] && exit 77; }
exit $fail
