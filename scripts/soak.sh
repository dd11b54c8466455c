#!/usr/bin/env bash
# Soak test: the headless ROS demo (built-in mannequin, motion 'all', avatar and
# skin nodes, robot_state_publisher; no rviz, no recording) for MINUTES minutes on
# a private ROS master. Every 10 s the resident set size (VmRSS) of each node is
# sampled; skin_stats and avatar_stats are read at the start and at the end.
# Prints per node the RSS after one minute of warm-up, at the end, its growth and
# its maximum, and the skin's rejects, drops and resets over the run. Exits 1 if
# a node died. Needs a build with ROS: bash scripts/build.sh build/release.
#
#   bash scripts/soak.sh 30                 # 30 minutes
#   SOAK_BUILD=build/asan bash scripts/soak.sh 5
#   SOAK_OUT=DIR: where the samples (rss.csv) and the launch log go
#                 (default build/soak/<stamp>)
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
minutes="${1:?usage: soak.sh MINUTES}"
case "$minutes" in
  ''|*[!0-9.]*) echo "soak.sh: MINUTES must be a number, got '$minutes'" >&2; exit 2 ;;
esac
src="$(cd "$(dirname "$0")/.." && pwd)"
bld="$(cd "$src" && cd "${SOAK_BUILD:-build/release}" 2> /dev/null && pwd)" \
  || { echo "soak.sh: build folder ${SOAK_BUILD:-build/release} not found; run bash scripts/build.sh build/release" >&2; exit 2; }
if [ ! -f "$bld/devel/setup.bash" ]; then
  echo "soak.sh: $bld has no devel/setup.bash (ROS was not found by the build)" >&2
  exit 2
fi
stamp=$(date -u +%Y%m%d-%H%M%S)
out="${SOAK_OUT:-$src/build/soak/$stamp}"
mkdir -p "$out"
set +u
# shellcheck disable=SC1091
. "$bld/devel/setup.bash"
set -u
export PATH=/usr/bin:/bin:$PATH
export ROS_HOME="$out/ros_home" ROS_LOG_DIR="$out/ros_home/log" ROS_HOSTNAME=127.0.0.1
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1
unset ROS_IP ROS_NAMESPACE
mkdir -p "$ROS_HOME"
port=$(/usr/bin/python3 -c 'import socket
s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()')
export ROS_MASTER_URI="http://127.0.0.1:$port"
log="$out/launch.log"
seconds=$(/usr/bin/python3 -c "print(int(round(float('$minutes') * 60)))")
echo "soak.sh: ROS master on port $port; demo (mannequin, motion 'all', skin) for $minutes min; samples in $out"
roslaunch -p "$port" "$src/launch/demo.launch" rviz:=false output:=log > "$log" 2>&1 &
launch_pid=$!
# roslaunch started in the background of a script ignores SIGINT: TERM it.
stop() {
  kill -TERM "$launch_pid" 2> /dev/null || true
  wait "$launch_pid" 2> /dev/null || true
}
trap stop EXIT

# The nodes are children of roslaunch; found by their executable's name.
nodes=(motion_node avatar_node skin_sim_node robot_state_publisher)
declare -A pid=()
find_pids() {
  local c exe
  for c in $(pgrep -P "$launch_pid" || true); do
    exe=$(basename "$(readlink "/proc/$c/exe" 2> /dev/null || echo none)")
    for n in "${nodes[@]}"; do
      if [ "$exe" = "$n" ]; then pid[$n]=$c; fi
    done
  done
}
rss_kb() { awk '/^VmRSS:/ {print $2}' "/proc/$1/status" 2> /dev/null || echo 0; }
# one SkinStats message as "rejected dropped resets seq skipped" (empty if none came)
# (rostopic starts slowly on a loaded machine: up to three tries of 60 s)
read_stats() {
  local out=""
  for _ in 1 2 3; do
    out=$(timeout 60 rostopic echo -n 1 "$1" 2> /dev/null |
      awk '/^  seq:/ {s=$2} /^inputs_rejected:/ {r=$2} /^inputs_dropped:/ {d=$2} /^resets:/ {x=$2}
           /^inputs_skipped:/ {k=$2} END {if (s != "") print r, d, x, s, k + 0}' || true)
    [ -n "$out" ] && break
  done
  echo "$out"
}

for _ in $(seq 1 60); do
  find_pids
  [ ${#pid[@]} -eq ${#nodes[@]} ] && break
  sleep 1
done
if [ ${#pid[@]} -ne ${#nodes[@]} ]; then
  echo "soak.sh: not every node started (found: ${!pid[*]}); the launch log ($log) ends with:" >&2
  tail -n 30 "$log" >&2
  exit 1
fi
skin0=$(read_stats skin_stats)
avatar0=$(read_stats avatar_stats)
if [ -z "$skin0" ]; then
  echo "soak.sh: no skin_stats read within 3 minutes; the launch log ($log) ends with:" >&2
  tail -n 30 "$log" >&2
  exit 1
fi
t0=$(date +%s)
echo "t_s,${nodes[*]}" | tr ' ' ',' > "$out/rss.csv"
died=""
snapped=""
# Where RSS grows: each node's /proc/PID/smaps after the warm-up minute and at the
# end (the report lists the mappings whose Rss grew: [heap], thread arenas (anon
# maps inside 64 MiB reservations), stacks, libraries); with SOAK_MALLOC_STATS=1
# and gdb, at the end (after the counters are read: gdb stops the node a while)
# also glibc's malloc_stats() (per arena: system bytes and in use), written by the
# node into its stderr log in ROS_LOG_DIR.
snap() {
  local n
  for n in "${nodes[@]}"; do
    cp "/proc/${pid[$n]}/smaps" "$out/smaps_$1_$n.txt" 2> /dev/null || true
    if [ "$1" = end ] && [ -n "${SOAK_MALLOC_STATS:-}" ] && command -v gdb > /dev/null; then
      timeout 60 gdb -p "${pid[$n]}" -batch -ex 'call (void)malloc_stats()' > /dev/null 2>&1 || true
    fi
  done
}
while :; do
  now=$(date +%s)
  row="$((now - t0))"
  if [ -z "$snapped" ] && [ $((now - t0)) -ge 60 ]; then snap start; snapped=1; fi
  for n in "${nodes[@]}"; do
    if [ -d "/proc/${pid[$n]}" ]; then row="$row,$(rss_kb "${pid[$n]}")"; else row="$row,0"; died="$died $n"; fi
  done
  echo "$row" >> "$out/rss.csv"
  [ -n "$died" ] && break
  [ $((now - t0)) -ge "$seconds" ] && break
  sleep 10
done
skin1=$(read_stats skin_stats || true)
avatar1=$(read_stats avatar_stats || true)
snap end
stop
trap - EXIT

/usr/bin/python3 - "$out/rss.csv" "$skin0" "$skin1" "$avatar0" "$avatar1" <<'EOF'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head, data = rows[0], [[int(x) for x in r] for r in rows[1:]]
t = [r[0] for r in data]
warm = next((i for i, s in enumerate(t) if s >= 60), 0)
print("soak: %d samples over %.1f min (RSS from the sample at %d s on; KiB)" % (len(data), t[-1] / 60.0, t[warm]))
print("%-22s %10s %10s %10s %10s" % ("node", "rss_start", "rss_end", "growth", "rss_max"))
for j, name in enumerate(head[1:], 1):
    col = [r[j] for r in data]
    print("%-22s %10d %10d %+10d %10d" % (name, col[warm], col[-1], col[-1] - col[warm], max(col)))
def parse(s):
    f = s.split()
    return [int(x) for x in f] if len(f) == 5 else None
for topic, a, b in (("skin_stats", sys.argv[2], sys.argv[3]), ("avatar_stats", sys.argv[4], sys.argv[5])):
    a, b = parse(a), parse(b)
    if not a or not b:
        print("%s: not read at %s" % (topic, "start" if not a else "end"))
        continue
    print("%s: %d messages; rejected %d -> %d, dropped %d -> %d, skipped %d -> %d, resets %d -> %d"
          % (topic, b[3] - a[3], a[0], b[0], a[1], b[1], a[4], b[4], a[2], b[2]))
EOF
/usr/bin/python3 - "$out" "${nodes[@]}" <<'EOF'
import os, re, sys
out = sys.argv[1]
def maps(path):
    m, key = {}, None
    for line in open(path):
        if re.match(r"^[0-9a-f]+-[0-9a-f]+ ", line):
            f = line.split()
            lo, hi = (int(x, 16) for x in f[0].split("-"))
            key = (f[0].split("-")[0], f[5] if len(f) > 5 else "[anon]")
            m[key] = [0, (hi - lo) // 1024]
        elif line.startswith("Rss:") and key:
            m[key][0] = int(line.split()[1])
    return m
for n in sys.argv[2:]:
    a, b = (os.path.join(out, "smaps_%s_%s.txt" % (w, n)) for w in ("start", "end"))
    if not (os.path.exists(a) and os.path.exists(b)):
        continue
    ma, mb = maps(a), maps(b)
    z = [0, 0]
    d = sorted(((mb.get(k, z)[0] - ma.get(k, z)[0], k, mb.get(k, ma.get(k))[1])
                for k in set(ma) | set(mb)), reverse=True)
    d = [x for x in d if x[0] != 0]
    if not d:
        continue
    print("%s: Rss change per mapping, minute 1 to the end (KiB; mapping, start, size KiB at the"
          " end; a thread's malloc arena is an [anon] mapping at a 64 MiB boundary):" % n)
    for g, (addr, name), size in d[:6]:
        print("  %+8d  %-36s %s %d" % (g, name[-36:], addr, size))
    if len(d) > 6:
        print("  %+8d  (%d other mappings)" % (sum(x[0] for x in d[6:]), len(d) - 6))
EOF
echo "samples: $out/rss.csv   launch log: $log"
if [ -n "$died" ]; then
  echo "soak.sh: node(s) died:$died; the launch log ends with:" >&2
  tail -n 30 "$log" >&2
  exit 1
fi
