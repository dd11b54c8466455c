#!/usr/bin/env bash
# A screenshot of rviz showing the skin, under Xvfb (no display needed): runs a launch
# file of the package with rviz on a private ROS master, waits, saves the screen.
#
#   bash scripts/rviz_shot.sh OUT.png SECONDS LAUNCH [ARG:=VALUE...]
#   bash scripts/rviz_shot.sh doc/rviz_demo.png 25 demo.launch
#   bash scripts/rviz_shot.sh /tmp/solo.png 40 robot.launch urdf:=solo.urdf package_path:=...
#
# Needs a build (build/release, or BUILD=DIR) and the packages xvfb, xauth and
# imagemagick (scripts/install_deps.sh installs them).
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
out="${1:?usage: rviz_shot.sh OUT.png SECONDS LAUNCH [ARG:=VALUE...]}"
secs="${2:?seconds}"
launch="${3:?launch file}"
shift 3
src="$(cd "$(dirname "$0")/.." && pwd)"
bld="${BUILD:-$src/build/release}"
[ -f "$bld/devel/setup.bash" ] || { echo "rviz_shot.sh: no ROS build in $bld" >&2; exit 1; }
set +u
# shellcheck disable=SC1091
. "$bld/devel/setup.bash"
set -u
export PATH=/usr/bin:/bin:$PATH
work=$(mktemp -d)
export ROS_HOME="$work" ROS_HOSTNAME=127.0.0.1
unset ROS_IP ROS_NAMESPACE
port=$(/usr/bin/python3 -c 'import socket
s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()')
export ROS_MASTER_URI="http://127.0.0.1:$port"
case "$out" in /*) ;; *) out="$PWD/$out" ;; esac
xvfb-run -a -s "-screen 0 1024x768x24" bash -c '
  roslaunch -p "$1" "$2" "${@:5}" > "$3/launch.log" 2>&1 &
  pid=$!
  sleep "$4"
  import -window root "$3/shot.png"
  kill -INT "$pid"; wait "$pid"' rviz_shot "$port" "$src/launch/$launch" "$work" "$secs" "$@" || true
if [ ! -s "$work/shot.png" ]; then
  echo "rviz_shot.sh: no screenshot; the launch log ends with:" >&2
  tail -n 30 "$work/launch.log" >&2
  exit 1
fi
cp "$work/shot.png" "$out"
rm -rf "$work"
echo "rviz_shot.sh: $out"
