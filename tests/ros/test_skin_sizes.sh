#!/usr/bin/env bash
# skin_sim_node sizes a kinematic_mesh before anything is allocated for it, and hands
# the memory of a large one back (through a real master; tests/ros/raw_mesh.py sends
# raw SkinMesh bytes and reads the node's /proc/PID/status):
#  - the 56-byte SkinMesh whose positions claim 0x40000002 floats (roscpp's own
#    deserialiser allocated 4 GiB for it): refused unread with one error naming the
#    field and the sizes, counted in inputs_rejected; the node stays up and answers the
#    next good mesh; its peak RSS (VmHWM) grows by less than 150 MB;
#  - a 72 MB message of valid sizes that the node reads and rejects: counted; once the
#    next good mesh is answered, its RSS is back within 40 MB of where it was before;
#  - the same message to a node started with _max_vertices:=100000: refused unread,
#    the error names ~max_vertices; peak RSS grows by less than 150 MB.
# The sanitizer build keeps freed memory in quarantine: the node runs here without it
# (ASAN_OPTIONS quarantine_size_mb=0), so that its RSS shows what the code hands back.
# SKIN_SIM_NODE=PATH runs another skin_sim_node binary.
# Usage: test_skin_sizes.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
skin=${SKIN_SIM_NODE:-$(ros_env_node_exe skin_sim_node)} || exit 1
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}quarantine_size_mb=0"
t0=$(ros_env_now_ms)
D="$ROS_ENV_DIR"
# fig NAME KEY: a figure of raw_mesh.py's `figures` line in $D/NAME.log
fig() { sed -n "s/.*figures .*\b$2=\([-0-9]*\).*/\1/p" "$D/$1.log" | head -n 1; }

# --- the 56-byte lie, then a large message read and rejected
ros_env_bg skin "$skin" _marker_rate:=0
spid=$ROS_ENV_LAST_PID
ros_env_check "skin node starts" "ros_env_wait_node /skin_sim $ROS_ENV_START_S $spid"
timeout 600 /usr/bin/python3 "$src/tests/ros/raw_mesh.py" "$spid" lie > "$D/lie.log" 2>&1
rc=$?
cat "$D/lie.log"
ros_env_check "the node answers a good mesh after the 56-byte message and after the large one (exit $rc)" "[ $rc -eq 0 ]"
ros_env_check "the node is still up" "kill -0 $spid"
hwm0=$(fig lie hwm0); hwm1=$(fig lie hwm1); rss0=$(fig lie rss0); rss2=$(fig lie rss2)
r1=$(fig lie rejected1); r2=$(fig lie rejected2)
echo "56-byte message ($(fig lie lie_bytes) bytes): VmHWM ${hwm0:-?} -> ${hwm1:-?} kB; rejected ${r1:-?}"
echo "large message ($(fig lie large_bytes) bytes): VmRSS ${rss0:-?} -> $(fig lie rss1) -> ${rss2:-?} kB (peak $(fig lie hwm2) kB); rejected ${r2:-?}"
ros_env_check "the 56-byte message's peak RSS growth < 150 MB" "[ -n '$hwm1' ] && [ \$(( ${hwm1:-0} - ${hwm0:-0} )) -lt 153600 ]"
ros_env_check "the 56-byte message counted as rejected" "[ '${r1:-0}' -ge 1 ]"
ros_env_check "its error names positions and the sizes" \
  "grep -q 'rejected kinematic_mesh unread: positions: length 1073741826 (4294967304 bytes) but only' '$D/skin.log'"
ros_env_check "the large message counted as rejected" "[ '${r2:-0}' -ge 2 ]"
ros_env_check "RSS back within 40 MB after the large message" "[ -n '$rss2' ] && [ \$(( ${rss2:-0} - ${rss0:-0} )) -lt 40960 ]"
ros_env_sigint "$spid" 20
ros_env_check_sanitizer "$D/skin.log" "no sanitizer report from the node (lie)"

# --- the large message against a smaller ~max_vertices: refused unread
ros_env_bg skin2 "$skin" _marker_rate:=0 _max_vertices:=100000 __name:=skin_sim
spid=$ROS_ENV_LAST_PID
ros_env_check "skin node (~max_vertices 100000) starts" "ros_env_wait_node /skin_sim $ROS_ENV_START_S $spid"
timeout 600 /usr/bin/python3 "$src/tests/ros/raw_mesh.py" "$spid" limit > "$D/limit.log" 2>&1
rc=$?
cat "$D/limit.log"
hwm0=$(fig limit hwm0); hwm1=$(fig limit hwm1); r1=$(fig limit rejected1)
echo "over ~max_vertices: VmHWM ${hwm0:-?} -> ${hwm1:-?} kB; rejected ${r1:-?}"
ros_env_check "the node answers a good mesh after a mesh over ~max_vertices (exit $rc)" "[ $rc -eq 0 ]"
ros_env_check "it was counted as rejected" "[ '${r1:-0}' -ge 1 ]"
ros_env_check "its error names ~max_vertices" "grep -q 'positions: .* exceed ~max_vertices = 100000' '$D/skin2.log'"
ros_env_check "peak RSS growth < 150 MB" "[ -n '$hwm1' ] && [ \$(( ${hwm1:-0} - ${hwm0:-0} )) -lt 153600 ]"
ros_env_sigint "$spid" 20
ros_env_check_sanitizer "$D/skin2.log" "no sanitizer report from the node (limit)"
echo "test_skin_sizes: $(($(ros_env_now_ms) - t0)) ms"
exit $ROS_ENV_FAIL
