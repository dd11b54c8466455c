#!/usr/bin/env bash
# skinsim run on avatars: the built-in mannequin, a URDF with a CSV motion
# (the mannequin's own file, and the Solo robot whose links wear their own
# visual meshes), a region mask, and rigged characters nobody here made
# (Debian's assimp-testmodels, ../shared/data) animated for 100 frames with
# the walk: 0 failures. Bad input: one clear message, exit 2, no crash.
set -u
bld="$1"
src="$2"
exe=$(find "$bld" -type f -name skinsim -perm -u+x | head -n 1)
[ -x "$exe" ] || { echo "skinsim not built under $bld"; exit 1; }
if ! "$exe" help | grep -q -- '--asset'; then echo "skinsim built without avatars: skipped"; exit 77; fi
shared="${SS_SHARED_DIR:-$src/../shared}"
models=/usr/share/assimp/models
fail=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
py=/usr/bin/python3
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
[ $assets -ge 2 ] || { echo "fewer than two real assets here: the real-asset part was skipped"; [ $fail -eq 0 ] && exit 77; }
exit $fail
