# shellcheck shell=bash
# tests/ros/ros_env.sh: a private ROS master for one test script. Source it, then:
#
#   . "$(dirname "$0")/ros_env.sh"
#   ros_env_start "$@" || exit $?         # 77 (CTest: skipped) only if ROS is absent
#   ros_env_bg echo "$bld/tests/ros/rosc_echo" echo   # a tracked background process
#   ros_env_wait_node /rosc_echo 10 || exit 1
#   ...
# and everything started here is stopped when the script exits (EXIT trap).
#
# ros_env_setup: Debian's python3 first in PATH (ROS_NOTES.md, "The Python pitfall"),
# sources BUILD/devel/setup.bash, picks a free port (bind to port 0), exports
# ROS_MASTER_URI=http://127.0.0.1:PORT, ROS_HOSTNAME=127.0.0.1 and a private ROS_HOME
# and ROS_LOG_DIR under a fresh temporary folder ($ROS_ENV_DIR), starts
# `rosmaster --core -p PORT` and /usr/lib/rosout/rosout in the background and waits
# (bounded) until /rosout is registered with the master. If the port was taken in
# between, it tries another (three attempts).
#
# Cleanup: every tracked process gets TERM (background rosmaster/rosout ignore INT in a
# non-interactive shell), then KILL after $ROS_ENV_STOP_TIMEOUT seconds (default 5).
# A watchdog process does the same if the test script itself dies without running its
# trap (e.g. killed by a CTest timeout), so no master is ever left behind. The
# temporary folder is removed when the script succeeds and kept (its path printed,
# the logs' tails shown) when it fails; ROS_ENV_KEEP=1 always keeps it.
#
# ros_env_start BUILD_DIR [SOURCE_DIR]: the scripts' usual start: sets bld and src (the
# tree this file is in unless given), then ros_env_setup "$bld".
#
# After ros_env_setup: ROS_MASTER_URI, ROS_ENV_PORT, ROS_HOME, ROS_LOG_DIR (rosout.log,
# the master's log), ROS_ENV_DIR (NAME.log of each ros_env_bg process). Functions:
# ros_env_bg, ros_env_stop PID..., ros_env_wait_node NODE [S] (ROS_ENV_START_S: the
# start-up bound the tests use, default 60),
# ros_env_wait_subscribers TOPIC N [S], ros_env_free_port, ros_env_now_ms; for the test
# scripts' common steps: check NAME EXPR (tests/check.sh: ok/FAIL lines, fail: the exit
# status), ros_env_check NAME EXPR (the same, also setting ROS_ENV_FAIL), ros_env_node_exe, ros_env_helper_exe, ros_env_run, ros_env_sigint,
# ros_env_launch_skin, ros_env_set_robot_description, ros_env_ellipsoid_obj,
# ros_env_hostile_meshes, ros_env_check_sanitizer (each described where defined).
# Everything here works under `set -euo pipefail` as well as without it.

export PATH=/usr/bin:/bin:$PATH
ROS_ENV_PIDS=()
ROS_ENV_DIR=
ROS_ENV_WATCHDOG=
ROS_ENV_STOP_TIMEOUT=${ROS_ENV_STOP_TIMEOUT:-5}
# How long a process may take to come up (master, rosout, a node from roslaunch):
# a bound on waiting, returned from as soon as it is up, so generous: on a busy
# 2-core machine under ASan, roslaunch alone was seen to need over 20 s.
ROS_ENV_START_S=${ROS_ENV_START_S:-60}
ROS_ENV_LAST_PID=
ROS_ENV_FAIL=0
ROS_ENV_BUILD=
# the source tree this file belongs to (the scripts source it as SRC/tests/ros/ros_env.sh)
ROS_ENV_SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=../check.sh
. "$ROS_ENV_SRC/tests/check.sh"

ros_env_log() { echo "ros_env: $*" >&2; }

# Milliseconds since the epoch (for timing messages).
ros_env_now_ms() { echo $(($(date +%s%N) / 1000000)); }

# ros_env_free_port: prints a TCP port that was free a moment ago.
ros_env_free_port() {
  /usr/bin/python3 -c 'import socket
s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
s.bind(("127.0.0.1", 0))
print(s.getsockname()[1])
s.close()'
}

# ros_env_wait_node NODE [TIMEOUT_S [PID [LOG]]]: waits until NODE (e.g. /rosout) is
# registered with the master and its XML-RPC server answers (NODE /master: until the
# master answers). Returns 1 on timeout, or as soon as PID (if given) has exited;
# 2 as soon as LOG (if given) says its port is "already in use".
ros_env_wait_node() {
  local node="$1" timeout="${2:-10}" pid="${3:-0}" log="${4:-}"
  /usr/bin/python3 - "$ROS_MASTER_URI" "$node" "$timeout" "$pid" "$log" <<'EOF'
import os, sys, time, xmlrpc.client, socket
uri, node, timeout, pid, log = sys.argv[1], sys.argv[2], float(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
socket.setdefaulttimeout(1.0)
deadline = time.monotonic() + timeout
while True:
    try:
        if node == "/master":
            code, _, node_uri = 1, "", uri
        else:
            code, _, node_uri = xmlrpc.client.ServerProxy(uri).lookupNode("/ros_env", node)
        if code == 1:
            code, _, _ = xmlrpc.client.ServerProxy(node_uri).getPid("/ros_env")
            if code == 1:
                sys.exit(0)
    except (OSError, xmlrpc.client.Error):
        pass
    if time.monotonic() > deadline:
        sys.exit(1)
    if pid > 0:
        try:
            os.kill(pid, 0)
        except OSError:
            sys.exit(1)  # the process it waits for is gone
    if log:
        try:
            with open(log, errors="replace") as f:
                if "already in use" in f.read():
                    sys.exit(2)  # rosmaster lost the port race (and would hang)
        except OSError:
            pass
    time.sleep(0.02)
EOF
}

# ros_env_wait_subscribers TOPIC N [TIMEOUT_S]: waits until TOPIC has at least N
# subscribers registered with the master.
ros_env_wait_subscribers() {
  local topic="$1" n="$2" timeout="${3:-10}"
  /usr/bin/python3 - "$ROS_MASTER_URI" "$topic" "$n" "$timeout" <<'EOF'
import sys, time, xmlrpc.client, socket
uri, topic, n, timeout = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
socket.setdefaulttimeout(1.0)
deadline = time.monotonic() + timeout
while True:
    try:
        code, _, state = xmlrpc.client.ServerProxy(uri).getSystemState("/ros_env")
        if code == 1 and any(t == topic and len(subs) >= n for t, subs in state[1]):
            sys.exit(0)
    except (OSError, xmlrpc.client.Error):
        pass
    if time.monotonic() > deadline:
        sys.exit(1)
    time.sleep(0.05)
EOF
}

# ros_env_track PID: stop PID at exit.
ros_env_track() {
  ROS_ENV_PIDS+=("$1")
  [ -n "$ROS_ENV_DIR" ] && echo "$1" >> "$ROS_ENV_DIR/pids"
  return 0
}

# ros_env_bg NAME CMD [ARGS...]: starts CMD in the background with its output in
# $ROS_ENV_DIR/NAME.log, tracked for cleanup; its pid is in ROS_ENV_LAST_PID.
ros_env_bg() {
  local name="$1"; shift
  "$@" > "$ROS_ENV_DIR/$name.log" 2>&1 < /dev/null &
  ROS_ENV_LAST_PID=$!
  ros_env_track "$ROS_ENV_LAST_PID"
}

# ros_env_stop PID...: TERM, then KILL after ROS_ENV_STOP_TIMEOUT seconds; reaps.
ros_env_stop() {
  local pid alive t
  for pid in "$@"; do kill -TERM "$pid" 2> /dev/null || true; done
  t=0
  while :; do
    alive=0
    for pid in "$@"; do kill -0 "$pid" 2> /dev/null && alive=1; done
    [ "$alive" = 0 ] && break
    if [ "$t" -ge $((ROS_ENV_STOP_TIMEOUT * 20)) ]; then
      for pid in "$@"; do
        if kill -0 "$pid" 2> /dev/null; then
          ros_env_log "pid $pid ignored TERM for ${ROS_ENV_STOP_TIMEOUT}s: KILL"
          kill -KILL "$pid" 2> /dev/null || true
        fi
      done
      break
    fi
    sleep 0.05
    t=$((t + 1))
  done
  for pid in "$@"; do wait "$pid" 2> /dev/null || true; done
  return 0
}

# ros_env_dump_logs: the last lines of every log of this run (for failures).
ros_env_dump_logs() {
  [ -n "$ROS_ENV_DIR" ] || return 0
  local f
  for f in "$ROS_ENV_DIR"/*.log; do
    [ -f "$f" ] || continue
    echo "---- ${f##*/} (last 30 lines)"
    tail -n 30 "$f"
  done
}

ros_env_cleanup() {
  local rc=$?
  set +e
  if [ "${#ROS_ENV_PIDS[@]}" -gt 0 ]; then
    # stop the test's own processes first, the master last
    local i pids=()
    for ((i = ${#ROS_ENV_PIDS[@]} - 1; i >= 0; i--)); do pids+=("${ROS_ENV_PIDS[$i]}"); done
    ros_env_stop "${pids[@]}"
  fi
  if [ -n "$ROS_ENV_WATCHDOG" ]; then
    kill -TERM "$ROS_ENV_WATCHDOG" 2> /dev/null
    wait "$ROS_ENV_WATCHDOG" 2> /dev/null
  fi
  if [ -n "$ROS_ENV_DIR" ] && [ -d "$ROS_ENV_DIR" ]; then
    if [ "$rc" -ne 0 ] && [ "$rc" -ne 77 ]; then
      ros_env_dump_logs
      ros_env_log "exit status $rc; logs kept in $ROS_ENV_DIR"
    elif [ "${ROS_ENV_KEEP:-0}" = 1 ]; then
      ros_env_log "logs kept in $ROS_ENV_DIR"
    else
      rm -rf "$ROS_ENV_DIR"
    fi
  fi
  return "$rc"
}

# ros_env_setup BUILD_DIR: see the top of this file. Returns 0, 77 (no ROS) or 1.
ros_env_setup() {
  local bld="$1"
  ROS_ENV_BUILD=$bld
  if ! command -v rosmaster > /dev/null 2>&1 || [ ! -x /usr/lib/rosout/rosout ]; then
    ros_env_log "ROS 1 is not installed (rosmaster, /usr/lib/rosout/rosout): skipped"
    return 77
  fi
  if [ ! -f "$bld/devel/setup.bash" ]; then
    ros_env_log "$bld/devel/setup.bash missing: was $bld configured with ROS?"
    return 1
  fi
  # setup.bash reads unset variables: relax -u while sourcing it
  local had_u=0
  case $- in *u*) had_u=1; set +u ;; esac
  # shellcheck disable=SC1091
  . "$bld/devel/setup.bash"
  [ "$had_u" = 1 ] && set -u
  export PATH=/usr/bin:/bin:$PATH   # setup.bash may have put other paths first

  ROS_ENV_DIR=$(mktemp -d "${TMPDIR:-/tmp}/ros_env.XXXXXX")
  : > "$ROS_ENV_DIR/pids"
  export ROS_HOME="$ROS_ENV_DIR/home" ROS_LOG_DIR="$ROS_ENV_DIR/home/log"
  mkdir -p "$ROS_LOG_DIR"
  export ROS_HOSTNAME=127.0.0.1 ROSCONSOLE_STDOUT_LINE_BUFFERED=1 PYTHONUNBUFFERED=1
  unset ROS_IP ROS_NAMESPACE
  trap ros_env_cleanup EXIT
  trap 'exit 130' INT
  trap 'exit 143' TERM

  # watchdog: if this shell dies without its trap, stop what it started
  local owner=$$
  (
    trap '' INT
    trap 'exit 0' TERM
    while kill -0 "$owner" 2> /dev/null; do sleep 0.5; done
    # shellcheck disable=SC2013  # one pid per line
    for p in $(cat "$ROS_ENV_DIR/pids" 2> /dev/null); do kill -TERM "$p" 2> /dev/null; done
    sleep "$ROS_ENV_STOP_TIMEOUT"
    # shellcheck disable=SC2013
    for p in $(cat "$ROS_ENV_DIR/pids" 2> /dev/null); do kill -KILL "$p" 2> /dev/null; done
    rm -rf "$ROS_ENV_DIR"
  ) > /dev/null 2>&1 < /dev/null &
  ROS_ENV_WATCHDOG=$!

  local attempt port t0 master_pid wrc
  t0=$(ros_env_now_ms)
  for attempt in 1 2 3; do
    port=$(ros_env_free_port) || { ros_env_log "no free port"; return 1; }
    export ROS_MASTER_URI="http://127.0.0.1:$port"
    ros_env_bg master rosmaster --core -p "$port"
    master_pid=$ROS_ENV_LAST_PID
    # the master first (rosout started earlier only retries and complains)
    # (rosmaster does not exit when its port is taken: the log says so)
    wrc=0
    ros_env_wait_node /master "$ROS_ENV_START_S" "$master_pid" "$ROS_ENV_DIR/master.log" || wrc=$?
    case $wrc in
      0) ;;
      2) ros_env_log "port $port was taken before rosmaster bound it: another port"
         ros_env_stop "$master_pid"
         continue ;;
      *) if kill -0 "$master_pid" 2> /dev/null; then
           ros_env_log "master on port $port running but not answering in $ROS_ENV_START_S s"
           return 1
         fi
         ros_env_log "master on port $port did not start (attempt $attempt):"
         tail -n 5 "$ROS_ENV_DIR/master.log" >&2
         ros_env_stop "$master_pid"
         continue ;;
    esac
    ros_env_bg rosout /usr/lib/rosout/rosout
    if ros_env_wait_node /rosout "$ROS_ENV_START_S"; then
      export ROS_ENV_PORT=$port
      ros_env_log "master $ROS_MASTER_URI and /rosout up in $(($(ros_env_now_ms) - t0)) ms"
      return 0
    fi
    ros_env_log "/rosout did not register in $ROS_ENV_START_S s"
    return 1
  done
  return 1
}

# ros_env_start BUILD_DIR [SOURCE_DIR]: bld, src, then ros_env_setup (see the top of this file).
# shellcheck disable=SC2034  # bld, src: the scripts'
ros_env_start() {
  bld="$1"
  src="${2:-$ROS_ENV_SRC}"
  ros_env_setup "$bld"
}

# ---- steps the test scripts share (after ros_env_setup)

# ros_env_check NAME EXPR: check (tests/check.sh) that also sets ROS_ENV_FAIL=1 on a failure.
# shellcheck disable=SC2034  # ROS_ENV_FAIL: the scripts' exit status
ros_env_check() { check "$@" || { ROS_ENV_FAIL=1; return 1; }; }

# ros_env_node_exe NODE: prints the path of the package's node NODE (BUILD/devel/lib/skin_sim), or says FAIL and returns 1.
ros_env_node_exe() {
  local exe
  exe=$(find "$ROS_ENV_BUILD/devel/lib/skin_sim" -name "$1" -type f | head -n 1)
  if [ -z "$exe" ] || [ ! -x "$exe" ]; then echo "FAIL: $1 not built" >&2; return 1; fi
  echo "$exe"
}

# ros_env_helper_exe NAME: prints the path of the test helper BUILD/tests/ros/NAME, or says FAIL and returns 1.
ros_env_helper_exe() {
  [ -x "$ROS_ENV_BUILD/tests/ros/$1" ] || { echo "FAIL: $ROS_ENV_BUILD/tests/ros/$1 not built" >&2; return 1; }
  echo "$ROS_ENV_BUILD/tests/ros/$1"
}

# ros_env_run NAME CMD [ARGS...]: runs CMD in the foreground into $ROS_ENV_DIR/NAME.log, shows that log, returns CMD's exit status.
ros_env_run() {
  local name="$1" rc
  shift
  "$@" > "$ROS_ENV_DIR/$name.log" 2>&1
  rc=$?
  cat "$ROS_ENV_DIR/$name.log"
  return "$rc"
}

# ros_env_sigint PID [S]: sends SIGINT to PID, gives it S seconds (default 5) to end, returns its exit status.
ros_env_sigint() {
  local pid="$1" i
  kill -INT "$pid"
  for ((i = 0; i < ${2:-5} * 20; i++)); do kill -0 "$pid" 2> /dev/null || break; sleep 0.05; done
  wait "$pid"
}

# ros_env_launch_skin NAME QUEUE [S [ARG:=VALUE...]]: ros_env_bg NAME roslaunch skin.launch (queue_size:=QUEUE and the ARGs), waits for /skin_sim (S, default ROS_ENV_START_S).
ros_env_launch_skin() {
  local name="$1" queue="$2" wait_s="${3:-$ROS_ENV_START_S}"
  shift 2
  [ $# -gt 0 ] && shift
  ros_env_bg "$name" roslaunch "$ROS_ENV_SRC/launch/skin.launch" output:=screen queue_size:="$queue" "$@"
  ros_env_wait_node /skin_sim "$wait_s" "$ROS_ENV_LAST_PID"
}

# ros_env_set_robot_description URDF: puts the text of the file URDF on the master as /robot_description.
ros_env_set_robot_description() {
  /usr/bin/python3 -c 'import sys, xmlrpc.client
xmlrpc.client.ServerProxy(sys.argv[1]).setParam("/test", "/robot_description", open(sys.argv[2]).read())' \
    "$ROS_MASTER_URI" "$1"
}

# ros_env_ellipsoid_obj FILE NU NV: writes a torso-sized ellipsoid OBJ of NU x NV segments (2 + NU * (NV - 1) vertices).
ros_env_ellipsoid_obj() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import math, sys
nu, nv = int(sys.argv[2]), int(sys.argv[3])
verts = [(0.0, 0.0, 0.7)]
for j in range(1, nv):
    th = math.pi * j / nv
    for i in range(nu):
        ph = 2 * math.pi * i / nu
        verts.append((0.15 * math.sin(th) * math.cos(ph), 0.15 * math.sin(th) * math.sin(ph),
                      0.35 + 0.35 * math.cos(th)))
verts.append((0.0, 0.0, 0.0))
ring = lambda j, i: 1 + (j - 1) * nu + (i % nu)
faces = [(0, ring(1, i), ring(1, i + 1)) for i in range(nu)]
for j in range(1, nv - 1):
    for i in range(nu):
        a, b, c, e = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
        faces += [(a, c, e), (a, e, b)]
faces += [(ring(nv - 1, i), len(verts) - 1, ring(nv - 1, i + 1)) for i in range(nu)]
with open(sys.argv[1], "w") as f:
    f.writelines("v %.6f %.6f %.6f\n" % v for v in verts)
    f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in faces)
PY
}

# ros_env_hostile_meshes DIR: writes into DIR fifo.obj (a FIFO), huge.off (declares billions of vertices), abort.off (makes assimp 5.2 abort).
ros_env_hostile_meshes() {
  mkdir -p "$1"
  mkfifo "$1/fifo.obj"
  printf 'OFF\n4000000000 3000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$1/huge.off"
  printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 193 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$1/abort.off"
}

# ros_env_check_sanitizer LOG NAME: if LOG holds a sanitizer report, shows it and fails the check NAME.
ros_env_check_sanitizer() {
  if grep -qE "runtime error|AddressSanitizer|LeakSanitizer" "$1"; then
    grep -E -A5 "runtime error|AddressSanitizer|LeakSanitizer" "$1" | head -30
    ros_env_check "$2" false
  fi
}
