#!/usr/bin/env bash
# The skin inside the body on four bodies (doc/benchmarks.md, "Inside the body"):
# the built-in mannequin (all motions), the quadruped scene (~19k triangles), the
# elbow scene and the Khronos Fox (../shared/data), each measured by winding number
# every 10th frame (skinsim run --json: inside_*). Prints one markdown table.
#
#   bash bench/inside.sh [SKINSIM] [-- extra skinsim run settings, e.g. --collide false]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
skinsim="${1:-$here/build/release/devel/lib/skin_sim/skinsim}"
shift || true
[[ "${1:-}" == "--" ]] && shift
extra=("$@")
fox="$here/../shared/data/gltf-khronos-skinned/Fox/glTF-Binary/Fox.glb"
bodies=("mannequin|--avatar demo --motion all" "quadruped 19k|--scene quadruped"
        "elbow scene|--scene elbow")
[[ -f "$fox" ]] && bodies+=("Fox (glTF)|--asset $fox --asset-scale 0.01")
echo "| body | inside per frame, mean (max) of skin vertices | buried deepest | clean deepest | clean deeper than 0.05 / 0.1 edge, worst frame | ms per frame | snags, failures |"
echo "|---|---|---|---|---|---|---|"
for b in "${bodies[@]}"; do
  name="${b%%|*}"
  read -r -a args <<<"${b#*|}"
  { "$skinsim" run "${args[@]}" "${extra[@]}" --json - 2>/dev/null || true; } | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
e = d["mean_edge_length"] * 1000
print("| %s | %.0f (%d) of %s | %.2f edges (%.1f mm) | %.2f edges (%.1f mm), frame %d | %d / %d | %.1f | %d, %d |" % (
    sys.argv[1], d["inside_mean"], d["inside_count_max"], format(d["vertices"], ","),
    d["inside_buried_max"], d["inside_buried_max"] * e, d["inside_clean_max"], d["inside_clean_max"] * e,
    d["inside_clean_worst_frame"], d["inside_clean_over_005_max"], d["inside_clean_over_01_max"],
    d["ms_per_frame_median"], d["snags"], d["failures"]))' "$name"
done
