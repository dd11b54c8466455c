#!/usr/bin/env bash
# Configures and builds skin_sim: scripts/build.sh BUILD_DIR [extra cmake args...]
# Warnings are errors. Debian's python3 comes first in PATH, as catkin needs
# (ROS_NOTES.md: "The Python pitfall").
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
src="$(cd "$(dirname "$0")/.." && pwd)"
bld="${1:?usage: build.sh BUILD_DIR [cmake args]}"
shift
mkdir -p "$bld"
cmake -S "$src" -B "$bld" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DSKIN_SIM_WERROR=ON "$@" > "$bld.configure.log" 2>&1 \
  || { cat "$bld.configure.log"; echo "build.sh: cmake configure failed" >&2; exit 1; }
cmake --build "$bld" -j"$(nproc)"
