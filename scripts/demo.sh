#!/usr/bin/env bash
# The README's main-job command: installs what is missing, builds skin_sim and
# runs the built-in demo — every procedural scene with every anchor method,
# showing where projection snags and the paper's walk does not.
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
src="$(cd "$(dirname "$0")/.." && pwd)"
cd "$src"
bash scripts/install_deps.sh
mkdir -p build
bash scripts/build.sh build/release > build/release.build.log 2>&1 \
  || { tail -n 40 build/release.build.log; echo "demo.sh: build failed" >&2; exit 1; }
exe=$(find build/release -type f -name skinsim -perm -u+x | head -n 1)
"$exe" compare "$@"
