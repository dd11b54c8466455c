#!/usr/bin/env bash
# The ROS user's build and install path: the package in a fresh catkin workspace
# (ws/src/skin_sim), `catkin_make install`, then `roslaunch skin_sim demo.launch`
# from the install space alone (a clean environment that sources only
# install/setup.bash), counting skin_mesh messages for a few seconds.
# Also: the install space holds what a user runs (nodes, skinsim, bench_sim,
# library, headers, launch, urdf, rviz, messages) and no test programs; its C
# headers are the public API alone (the core's and the avatars', each compiling
# on its own), not the lab's, the nodes' stream policy or the core's inside.
# Usage: test_catkin_install.sh BUILD_DIR [SOURCE_DIR].
#
# The workspace build is the same in the normal and the sanitizer build of the
# suite, so it runs once, in the normal build (the sanitizer build skips it,
# saying so); it builds without the test programs (-DSKIN_SIM_TESTS=OFF).
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
export PATH=/usr/bin:/bin:$PATH
if grep -q '^SKIN_SIM_SANITIZE:BOOL=ON' "$bld/CMakeCache.txt" 2>/dev/null; then
  echo "skipped: the catkin workspace build runs once, in the normal build"
  exit 77
fi
command -v catkin_make > /dev/null || { echo "skipped: catkin_make not installed"; exit 77; }
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?

ws="$ROS_ENV_DIR/ws"
mkdir -p "$ws/src"
ln -s "$src" "$ws/src/skin_sim"
t0=$(ros_env_now_ms)
# a clean environment: nothing of the build under test leaks into the workspace
clean_env=(env -i PATH=/usr/bin:/bin HOME="$HOME" ROS_HOME="$ROS_HOME" ROS_LOG_DIR="$ROS_LOG_DIR"
           ROS_MASTER_URI="$ROS_MASTER_URI" ROS_HOSTNAME="$ROS_HOSTNAME" LANG=C.UTF-8)
(cd "$ws" && "${clean_env[@]}" catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 \
   -DSKIN_SIM_TESTS=OFF -DCMAKE_BUILD_TYPE=Release install) > "$ROS_ENV_DIR/catkin_make.log" 2>&1
rc=$?
echo "catkin_make install: exit $rc in $((($(ros_env_now_ms) - t0) / 1000)) s"
check "catkin_make install succeeds" "[ $rc -eq 0 ]" || tail -30 "$ROS_ENV_DIR/catkin_make.log"
inst="$ws/install"
for f in lib/skin_sim/skin_sim_node lib/skin_sim/avatar_node lib/skin_sim/motion_node \
         lib/skin_sim/skinsim lib/skin_sim/bench_sim lib/skin_sim/skin_bag_summary.py \
         lib/libskin_sim_core.a include/skin_sim/ss_sim.h include/skin_sim/ssa_avatar.h \
         include/skin_sim/SkinMesh.h include/skin_sim/SkinStats.h \
         share/skin_sim/package.xml share/skin_sim/launch/demo.launch \
         share/skin_sim/launch/skin.launch share/skin_sim/urdf/mannequin.urdf \
         share/skin_sim/rviz/skin_sim.rviz share/skin_sim/msg/SkinMesh.msg \
         share/skin_sim/scripts/plot_bench.py; do
  check "installed: $f" "[ -e '$inst/$f' ]"
done
# the C API installed: these six headers and no other ss_*.h (the lab's, the
# stream's and the core's internal headers stay in the source tree)
api="ss_anchor.h ss_common.h ss_mesh.h ss_settings.h ss_sim.h ssa_avatar.h"
got=$(cd "$inst/include/skin_sim" 2> /dev/null && LC_ALL=C ls ss_*.h ssa_*.h 2> /dev/null | tr '\n' ' ')
check "the installed C headers are the public API ($got)" "[ '${got% }' = '$api' ]"
for h in $api; do
  check "installed $h compiles alone (C11)" \
    "echo '#include <skin_sim/$h>' | cc -std=c11 -Wall -Wextra -Werror -fsyntax-only -I'$inst/include' -x c -"
done
for l in libskin_sim_lab.a libskin_sim_stream.a; do
  check "not installed: lib/$l" "[ ! -e '$inst/lib/$l' ]"
done
check "ss_topo is opaque in the installed ss_mesh.h" \
  "! grep -q 'struct ss_topo *{' '$inst/include/skin_sim/ss_mesh.h'"
check "no test program in lib/skin_sim" \
  "! ls '$inst/lib/skin_sim' '$ws/devel/lib/skin_sim' | grep -q 'test_\|rosc_echo\|skin_probe'"
check "skinsim from the install space runs" "'$inst/lib/skin_sim/skinsim' scenes > /dev/null"

if [ $rc -eq 0 ]; then
  # the demo from the install space, headless, for a few seconds
  count_py='import rospy, sys, time
rospy.init_node("count_skin", anonymous=True)
n = [0]
rospy.Subscriber("/skin_mesh", rospy.AnyMsg, lambda m: n.__setitem__(0, n[0] + 1))
end = time.time() + float(sys.argv[1])
while time.time() < end and not rospy.is_shutdown():
    time.sleep(0.1)
print(n[0])'
  "${clean_env[@]}" bash -c ". '$inst/setup.bash' && rospack find skin_sim" \
    > "$ROS_ENV_DIR/find.txt" 2>&1
  check "rospack finds skin_sim in the install space ($(cat "$ROS_ENV_DIR/find.txt"))" \
    "[ \"\$(cat '$ROS_ENV_DIR/find.txt')\" = '$inst/share/skin_sim' ]"
  "${clean_env[@]}" bash -c ". '$inst/setup.bash' && exec roslaunch skin_sim demo.launch \
     rviz:=false tf:=false tris:=3000 output:=log" > "$ROS_ENV_DIR/demo.log" 2>&1 &
  ros_env_track $!
  ros_env_wait_node /skin_sim $ROS_ENV_START_S || { echo "FAIL: /skin_sim did not come up"; fail=1; }
  n=$("${clean_env[@]}" bash -c ". '$inst/setup.bash' && python3 -c '$count_py' 6" 2>> "$ROS_ENV_DIR/count.err")
  check "demo from the install space publishes skin_mesh (${n:-0} in 6 s)" "[ '${n:-0}' -gt 5 ]" \
    || tail -20 "$ROS_ENV_DIR/demo.log" "$ROS_ENV_DIR/count.err"
fi
exit $fail
