#!/usr/bin/env bash
# avatar_node's ~reload (issue 14): the node starts with a good body (an ellipsoid
# OBJ on the mannequin's URDF); reloads with a hostile or broken ~mesh (a FIFO, an
# OFF declaring billions of vertices, an OFF that makes assimp abort, a missing
# file, a good file over ~max_file_mb, a bad ~import_timeout or ~import_mem_mb) each fail with one
# error naming the file (or parameter) while the node keeps publishing its last
# good body (same vertex count and topology_id); a reload with another good mesh
# swaps it in (new vertex count and topology). Then the node exits 0 on SIGINT.
# Usage: test_avatar_reload.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
exe=$(find "$bld/devel/lib/skin_sim" -name avatar_node -type f | head -n 1)
[ -x "$exe" ] || { echo "FAIL: avatar_node not built"; exit 1; }
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
/usr/bin/python3 -c 'import sys, xmlrpc.client
xmlrpc.client.ServerProxy(sys.argv[1]).setParam("/test", "/robot_description", open(sys.argv[2]).read())' \
  "$ROS_MASTER_URI" "$src/urdf/mannequin.urdf"
d="$ROS_ENV_DIR/meshes"
mkdir -p "$d"
# torso-sized ellipsoids (OBJ): NU x NV segments, 2 + NU * (NV - 1) vertices
ellipsoid() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import math, sys
nu, nv = int(sys.argv[2]), int(sys.argv[3])
verts = [(0.0, 0.0, 0.7)]
for j in range(1, nv):
    th = math.pi * j / nv
    for i in range(nu):
        ph = 2 * math.pi * i / nu
        verts.append((0.15 * math.sin(th) * math.cos(ph), 0.15 * math.sin(th) * math.sin(ph),
                      0.35 + 0.35 * math.cos(th)))
verts.append((0.0, 0.0, 0.0))
ring = lambda j, i: 1 + (j - 1) * nu + (i % nu)
faces = [(0, ring(1, i), ring(1, i + 1)) for i in range(nu)]
for j in range(1, nv - 1):
    for i in range(nu):
        a, b, c, e = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
        faces += [(a, c, e), (a, e, b)]
faces += [(ring(nv - 1, i), len(verts) - 1, ring(nv - 1, i + 1)) for i in range(nu)]
with open(sys.argv[1], "w") as f:
    f.writelines("v %.6f %.6f %.6f\n" % v for v in verts)
    f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in faces)
PY
}
ellipsoid "$d/torso.obj" 24 16   # 362 vertices
ellipsoid "$d/torso2.obj" 12 8   # 86 vertices
mkfifo "$d/fifo.obj"
printf 'OFF\n4000000000 3000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$d/huge.off"
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 193 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$d/abort.off"

ros_env_bg avatar_reload "$exe" __name:=avatar_reload _mesh:="$d/torso.obj" _queue_size:=50
apid=$ROS_ENV_LAST_PID
check "avatar node starts with torso.obj" "ros_env_wait_node /avatar_reload 60 $apid"
p="$ROS_ENV_DIR/probe.log"
timeout 600 /usr/bin/python3 "$src/tests/ros/reload_probe.py" /avatar_reload \
  mesh="$d/fifo.obj" fail mesh="$d/huge.off" fail mesh="$d/abort.off" fail \
  mesh="$d/missing.obj" fail \
  mesh="$d/torso2.obj" param=max_file_mb=0.001 fail \
  param=max_file_mb=256 param=import_timeout=abc fail \
  param=import_timeout=60 ok \
  mesh="$d/torso.obj" param=import_mem_mb=8 fail \
  param=import_mem_mb=4096 ok > "$p" 2>&1
rc=$?
cat "$p"
check "every reload ends as expected (probe exit $rc)" "[ $rc -eq 0 ]"
start=$(awk '/^start:/ {print $2, $5}' "$p")
check "the first body is torso.obj's 362 vertices" "[ '${start%% *}' = 362 ]"
check "after each of the first 6 failed reloads the node still publishes the first body" \
  "[ \$(grep -c \"^reload failed: ${start%% *} vertices, topology ${start##* }\$\" '$p') -eq 6 ]"
check "after the 7th (a bad ~import_mem_mb) it still publishes the second (86 vertices)" \
  "[ \$(grep -c '^reload failed: 86 vertices' '$p') -eq 1 ]"
check "a good reload swaps in torso2.obj (86 vertices, another topology)" \
  "grep -q '^reload ok: 86 vertices' '$p' && ! grep -q '^reload ok: 86 vertices, topology ${start##* }\$' '$p'"
check "and reloading torso.obj gives the first topology again" \
  "grep -q \"^reload ok: 362 vertices, topology ${start##* }\$\" '$p'"
l="$ROS_ENV_DIR/avatar_reload.log"
sed 's/\x1b\[[0-9;]*m//g' "$l" | grep -E "ERROR|reload" | head -30
for w in "fifo.obj.*not a" "huge.off.*4000000000" "abort.off.*importer" "missing.obj" \
         "torso2.obj.*over the cap of 0.001 MB" "~import_timeout" "~import_mem_mb = 8 MB is out of range"; do
  check "the log names the problem: $w" "grep -q -- '$w' '$l'"
done
check "each failed reload says the last good body is kept" \
  "[ \$(grep -c 'still publishing the last good body' '$l') -eq 7 ]"
kill -INT "$apid"
for _ in $(seq 200); do kill -0 "$apid" 2> /dev/null || break; sleep 0.05; done
wait "$apid"; arc=$?
check "avatar node exits 0 on SIGINT (exit $arc)" "[ $arc -eq 0 ]"
if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$l"; then
  grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$l" | head -30
  check "no sanitizer report from the avatar node" false
fi
exit $fail
