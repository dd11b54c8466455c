#!/usr/bin/env bash
# Real time through the real nodes: a body driven at 30 Hz joint_states through
# avatar_node and skin_sim_node on a private master, with and without CPU hogs
# (`yes > /dev/null`) beside them. A benchmark, not a test: it prints figures and
# judges nothing.
#
#   bash bench/ros_realtime.sh BUILD_DIR [SECONDS] [BODIES] [HOGS] [BUDGET]
#
#   SECONDS  measured per run after a warm-up of 5 s (default 20)
#   BODIES   comma-separated (default solo,quadruped,pieces,mannequin19k); BODY:N runs
#            that body beside N hogs only, whatever HOGS says:
#            solo          ../shared/data's Solo URDF (per-link OBJ meshes), motion sweep
#            quadruped     bench/make_robot.py quadruped (~15k triangles, 51 pieces), sweep
#            pieces        bench/make_robot.py pieces (~50k triangles, 1,349 pieces), sweep
#            mannequin19k  the built-in mannequin at 19,000 triangles (one deforming
#                          piece), motion all
#   HOGS     comma-separated hog counts (default 0,1,2)
#   BUDGET   skin_sim_node's ~step_budget in s (default 0: the input's period; -1: none)
#
# NODES_FROM=OTHER_BUILD_DIR runs avatar_node and skin_sim_node of another build (an
# earlier commit, for a before/after in one run); motion_node stays this build's.
# SKIN_ARGS="_collide:=true ..." adds private parameters of skin_sim_node (split at
# spaces), e.g. to time an option through the nodes.
#
# Per run it prints one row: inputs (kinematic_mesh published), answered (skin
# steps whose stamp is an input's, as a share of inputs), latency (skin_stats:
# ROS time at publication minus the input's stamp) median and 95th percentile,
# the work the budget chose (substeps x iterations, as shares of the answered
# steps), resets, skipped inputs, triangles simulated / carried, the skin's
# creation time from its log line, and the most skin vertices over an edge from
# their anchor (far) and skin faces turned against the body (turned) in a step.
set -uo pipefail
bld="$(cd "${1:?usage: ros_realtime.sh BUILD_DIR [SECONDS] [BODIES] [HOGS] [BUDGET]}" && pwd)"
seconds="${2:-20}"
bodies="${3:-solo,quadruped,pieces,mannequin19k}"
hogs="${4:-0,1,2}"
budget="${5:-0}"
src="$(cd "$(dirname "$0")/.." && pwd)"
shared="${SS_SHARED_DIR:-$src/../shared}"
export PATH=/usr/bin:/bin:$PATH
. "$src/tests/ros/ros_env.sh"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$src/bench/make_robot.py" quadruped "$work/quadruped" > /dev/null
/usr/bin/python3 "$src/bench/make_robot.py" pieces "$work/pieces" > /dev/null
solo="$shared/data/urdf-solo-quadruped/example-robot-data"

printf '%-13s %4s %6s %9s %9s %9s  %-22s %6s %7s %15s %9s %5s %6s\n' body hogs inputs answered \
  "lat.med" "lat.p95" "work (share of steps)" resets skipped "simulated/carr." "create" far turned
run_one() { # body hogs
  local body="$1" nhog="$2" urdf="" avatar_args=() motion=sweep
  case "$body" in
    solo) urdf="$solo/robots/solo_description/robots/solo.urdf"
          avatar_args=(_package_path:="example-robot-data=$solo")
          [ -f "$urdf" ] || { echo "$body: $urdf absent, skipped"; return 0; } ;;
    quadruped|pieces) urdf="$work/$body/robot.urdf" ;;
    mannequin19k) avatar_args=(_avatar:=mannequin _tris:=19000); motion=all ;;
    *) echo "unknown body $body"; return 1 ;;
  esac
  (
    ros_env_setup "$bld" > /dev/null 2>&1 || { echo "$body: no ROS master"; exit 1; }
    [ -n "$urdf" ] && ros_env_set_robot_description "$urdf"
    local nodes="${NODES_FROM:-$bld}/devel/lib/skin_sim"
    ros_env_bg avatar "$nodes/avatar_node" "${avatar_args[@]}"
    local skin_args=()
    read -r -a skin_args <<< "${SKIN_ARGS:-}"
    ros_env_bg skin "$nodes/skin_sim_node" _step_budget:="$budget" _marker_rate:=0 "${skin_args[@]}"
    ros_env_wait_node /avatar 60 > /dev/null && ros_env_wait_node /skin_sim 60 > /dev/null \
      || { echo "$body: nodes did not come up"; tail -5 "$ROS_ENV_DIR"/*.log; exit 1; }
    local hog_pids=()
    # tracked: stopped with the master even if this run ends early
    for ((h = 0; h < nhog; h++)); do yes > /dev/null & hog_pids+=($!); ros_env_track $!; done
    ros_env_bg motion "$(ros_env_node_exe motion_node)" _motion:="$motion" _rate:=30
    sleep 5
    /usr/lib/rosbag/record -O "$ROS_ENV_DIR/run.bag" --duration="$seconds" /avatar_stats \
      /skin_stats > "$ROS_ENV_DIR/record.log" 2>&1
    kill "${hog_pids[@]}" 2> /dev/null
    local create
    create=$(grep -o 'skin created.*' "$ROS_ENV_DIR/skin.log" | tail -1 | grep -oE '[0-9.]+ ms\)' | grep -oE '[0-9.]+')
    /usr/bin/python3 - "$ROS_ENV_DIR/run.bag" "$body" "$nhog" "${create:-?}" <<'PY'
import sys
import rosbag
bag, body, nhog, create = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
inputs, steps = [], {}
with rosbag.Bag(bag) as b:
    for topic, m, _ in b.read_messages():
        if topic.endswith("avatar_stats"):
            inputs.append(m.header.stamp.to_nsec())
        else:
            steps[m.header.stamp.to_nsec()] = m
ins = set(inputs)
ans = [m for s, m in steps.items() if s in ins]
lat = sorted(m.latency_ms for m in ans)
q = lambda p: lat[min(len(lat) - 1, int(round(p * (len(lat) - 1))))] if lat else float("nan")
work = {}
for m in ans:
    k = "%dx%d" % (m.substeps, getattr(m, "iterations_per_substep", 0))
    work[k] = work.get(k, 0) + 1
works = " ".join("%s:%.0f%%" % (k, 100.0 * v / len(ans))
                 for k, v in sorted(work.items(), key=lambda kv: -kv[1])[:2]) if ans else "-"
last = max(steps.values(), key=lambda m: m.header.stamp.to_nsec()) if steps else None
first = min(steps.values(), key=lambda m: m.header.stamp.to_nsec()) if steps else None
resets = (last.resets - first.resets) if steps else 0
skipped = (last.inputs_skipped - first.inputs_skipped) if steps else 0
tri = ("%d/%d" % (last.triangles_simulated, last.triangles_carried)
       if last and hasattr(last, "triangles_carried") else "-")
far = max((getattr(m, "vertices_far", -1) for m in ans), default=-1)
turned = max((getattr(m, "faces_turned", -1) for m in ans), default=-1)
print("%-13s %4s %6d %8.1f%% %7.0fms %7.0fms  %-22s %6d %7d %15s %7sms %5s %6s"
      % (body, nhog, len(inputs), 100.0 * len(ans) / max(1, len(inputs)), q(0.5), q(0.95),
         works, resets, skipped, tri, create, far if far >= 0 else "-",
         turned if turned >= 0 else "-"))
PY
  )
}
IFS=, read -r -a body_list <<< "$bodies"
IFS=, read -r -a hog_list <<< "$hogs"
for b in "${body_list[@]}"; do
  if [[ "$b" == *:* ]]; then run_one "${b%%:*}" "${b##*:}"; continue; fi # BODY:HOGS alone
  for h in "${hog_list[@]}"; do run_one "$b" "$h"; done
done
