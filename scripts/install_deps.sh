#!/usr/bin/env bash
# Installs, with Debian 12's apt, every package skin_sim needs to build, test and
# run its demo. Idempotent: installs only what is missing. Must run as root (or
# with sudo available).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
PKGS=(
  build-essential cmake pkg-config
  ros-core-dev rosbash libroscpp-dev librosbag-dev python3-rosbag python3-rostest
  ros-std-msgs ros-sensor-msgs ros-geometry-msgs ros-visualization-msgs
  libsuitesparse-dev libopenblas0-pthread liburdfdom-dev libassimp-dev
  assimp-testmodels python3-matplotlib python3-numpy
  ros-robot-state-publisher rviz xvfb xauth imagemagick joint-state-publisher-gui
  python3-visualization-msgs catkin-tools catkin-lint
  clang libclang-rt-14-dev
  libdiagnostic-updater-dev python3-diagnostic-msgs libstd-srvs-dev python3-std-srvs
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  python3-rosdep2 python3-diagnostic-updater python3-tf2-msgs
)
# rosdep: skin_sim's keys Debian's rosdep database lacks (assimp, suitesparse) or maps to
# development packages it does not need (rviz, robot_state_publisher), listed before
# Debian's own (rosdep/skin_sim.yaml). Then `rosdep update` (offline: with
# ROSDISTRO_INDEX_URL=file://.../rosdep/index-v4.yaml) and `rosdep check --from-paths .`.
rosdep_list() {
  local src list=/etc/ros/rosdep/sources.list.d/05-skin_sim.list
  src="$(cd "$(dirname "$0")/.." && pwd)"
  local line="yaml file://$src/rosdep/skin_sim.yaml debian"
  [ -f "$list" ] && grep -qxF "$line" "$list" && return 0
  echo "install_deps: writing $list"
  $SUDO mkdir -p "$(dirname "$list")" && echo "$line" | $SUDO tee "$list" > /dev/null
}
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PKGS[@]} packages present"
  rosdep_list
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
rosdep_list
