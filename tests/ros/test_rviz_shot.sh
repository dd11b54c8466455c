#!/usr/bin/env bash
# rviz shows the skin: the headless demo (demo.launch rviz:=false) runs, rviz is started
# under Xvfb with the shipped config rviz/skin_sim.rviz, a screenshot is taken with
# ImageMagick's `import`, and the skin marker's colour (one orange, ~marker_color, on a
# grey background) must cover a visible part of it, shaded: the brightness of those
# pixels must spread (rviz draws the marker unlit; a flat colour is a silhouette).
# The screenshot is kept as BUILD_DIR/rviz_skin.png. Skipped (77) when xvfb-run, import
# or rviz is missing.
# Usage: test_rviz_shot.sh BUILD_DIR [SOURCE_DIR].
set -u
bld="$1"
src="${2:-$(cd "$(dirname "$0")/../.." && pwd)}"
for c in xvfb-run import rviz convert; do
  command -v "$c" > /dev/null 2>&1 || { echo "skipped: $c not installed (apt: xvfb imagemagick rviz)"; exit 77; }
done
. "$src/tests/ros/ros_env.sh"
ros_env_setup "$bld" || exit $?
D="$ROS_ENV_DIR"
# one colour (orange), so that any spread of the marker's brightness is its shading
ros_env_bg demo roslaunch "$src/launch/demo.launch" rviz:=false tris:=3000 marker_rate:=10 \
  marker_color:="1 0.5 0.2"
dpid=$ROS_ENV_LAST_PID
check "demo.launch starts" "ros_env_wait_node /skin_sim $ROS_ENV_START_S $dpid"
shot="$D/shot.png"
# pixels whose channels differ by more than 80 in the 3D view: the marker's colours (grid,
# background and panels are grey)
count_cmd="convert '$shot' -crop 760x700+264+40 +repage -fx '(max(r,max(g,b))-min(r,min(g,b)))>0.31' -format '%[fx:round(mean*w*h)]' info:"
# screenshots every 5 s (up to 40 s: rviz starts slowly on a loaded machine) until the
# skin shows
ros_env_bg rviz xvfb-run -a -s "-screen 0 1024x768x24" bash -c \
  "rviz -d '$src/rviz/skin_sim.rviz' & p=\$!
   for i in 1 2 3 4 5 6 7 8; do
     sleep 5; import -window root '$shot'; n=\$($count_cmd 2> /dev/null || echo 0)
     echo \"shot \$i: \$n coloured pixels\"; [ \"\${n:-0}\" -gt 3000 ] && break
   done
   kill \$p; wait \$p"
rpid=$ROS_ENV_LAST_PID
for _ in $(seq 600); do kill -0 "$rpid" 2> /dev/null || break; sleep 0.1; done
wait "$rpid" 2> /dev/null
grep "^shot" "$D/rviz.log"
check "a screenshot was taken" "[ -s '$shot' ]"
if [ -s "$shot" ]; then
  cp "$shot" "$bld/rviz_skin.png"
  n=$(eval "$count_cmd" 2> /dev/null || echo 0)
  echo "coloured pixels in the 3D view: $n (screenshot: $bld/rviz_skin.png)"
  check "the skin marker covers a visible part of the view ($n pixels)" "[ ${n:-0} -gt 3000 ]"
  # brightness (the largest channel) of the marker's pixels: 10th and 90th percentiles
  spread=$(convert "$shot" -crop 760x700+264+40 +repage -depth 8 rgb:- | /usr/bin/python3 -c '
import sys
b = sys.stdin.buffer.read()
v = sorted(max(b[i:i + 3]) for i in range(0, len(b) - 2, 3) if max(b[i:i + 3]) - min(b[i:i + 3]) > 79)
print("%.3f %.3f" % (v[len(v) // 10] / 255, v[9 * len(v) // 10] / 255) if v else "0 0")')
  echo "marker brightness, 10th / 90th percentile: $spread"
  check "the skin is shaded: its brightness spreads by more than 0.15 ($spread)" \
    "/usr/bin/python3 -c 'import sys; a, b = map(float, sys.argv[1:3]); sys.exit(0 if b - a > 0.15 else 1)' $spread"
fi
exit $fail
