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
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PKGS[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install_deps: installing ${missing[*]}"
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
