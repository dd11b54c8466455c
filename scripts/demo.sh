#!/usr/bin/env bash
# The README's main-job command: installs what is missing, builds skin_sim and runs
# the headless ROS demo on the built-in mannequin: a private ROS master on a free
# port, the scripted motion, the avatar and skin nodes and a rosbag recording, for a
# fixed time; then prints what happened (frames in and out, ms per frame, latency,
# the bag's path).
#
#   bash scripts/demo.sh                  # ROS demo, 12 s (DEMO_SECONDS=N to change)
#   bash scripts/demo.sh --offline [...] # no ROS: `skinsim compare [...]`, every scene
#                                         # with every anchor method (where projection snags)
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
src="$(cd "$(dirname "$0")/.." && pwd)"
cd "$src"
bash scripts/install_deps.sh
mkdir -p build
bash scripts/build.sh build/release > build/release.build.log 2>&1 \
  || { tail -n 40 build/release.build.log; echo "demo.sh: build failed" >&2; exit 1; }

if [ "${1:-}" = "--offline" ]; then
  shift
  exe=$(find build/release -type f -name skinsim -perm -u+x | head -n 1)
  exec "$exe" compare "$@"
fi

bld="$src/build/release"
if [ ! -f "$bld/devel/setup.bash" ]; then
  echo "demo.sh: ROS was not found by the build; run the offline demo: bash scripts/demo.sh --offline" >&2
  exit 1
fi
seconds="${DEMO_SECONDS:-12}"
out="$src/build/demo"
mkdir -p "$out"
stamp=$(date -u +%Y%m%d-%H%M%S)
bag="$out/demo-$stamp.bag"
set +u
# shellcheck disable=SC1091
. "$bld/devel/setup.bash"
set -u
export PATH=/usr/bin:/bin:$PATH
export ROS_HOME="$out/ros_home" ROS_HOSTNAME=127.0.0.1 ROSCONSOLE_STDOUT_LINE_BUFFERED=1
unset ROS_IP ROS_NAMESPACE
mkdir -p "$ROS_HOME"
port=$(/usr/bin/python3 -c 'import socket
s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()')
export ROS_MASTER_URI="http://127.0.0.1:$port"
log="$out/demo-$stamp.log"
echo "demo.sh: ROS master on port $port; mannequin, motion 'all', skin, recording for ${seconds} s"
roslaunch -p "$port" "$src/launch/demo.launch" rviz:=false record:="$bag" > "$log" 2>&1 &
launch_pid=$!
stop() { kill -INT "$launch_pid" 2> /dev/null || true; wait "$launch_pid" 2> /dev/null || true; }
trap stop EXIT
sleep "$seconds"
stop
trap - EXIT
if [ ! -f "$bag" ]; then
  echo "demo.sh: no bag was written; the launch log ($log) ends with:" >&2
  tail -n 30 "$log" >&2
  exit 1
fi
grep -E "skin created|avatar '|motion '|rejected|reset" "$log" | sed 's/\x1b\[[0-9;]*m//g' | head -n 8 || true
/usr/bin/python3 "$src/scripts/skin_bag_summary.py" "$bag"
echo "log:              $log"
echo "replay it:        roslaunch skin_sim replay.launch bag:=$bag   (after: source $bld/devel/setup.bash)"
