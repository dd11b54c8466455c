/* motion_node: scripted joint_states for the demo mannequin (glue only).
 *
 * Publishes sensor_msgs/JointState on joint_states at ~rate Hz for one of the
 * built-in motions (~motion: arms, elbows, twist, all for the mannequin; sweep for any
 * robot; ssa_motion_builtin_*),
 * so demos need no joystick or GUI. The robot is robot_description when set
 * (joints it lacks are left out), else the mannequin's own URDF. Stamps are
 * regular: the start time plus i / rate (re-based on the clock if the loop
 * falls more than half a second behind), so the stream steps the skin with
 * one constant dt. ~speed scales the motion's time; ~duration (s, 0: for
 * ever) ends the node after that long. A parameter of the wrong type or out of
 * range, or a motion that moves no joint of robot_description, stops the node
 * at start (exit 2) with one message. */
#include "node_msg.h"
#include "node_params.h"
#include "rosc/rosc.h"
#include "skin_sim/ssa_avatar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
  int st = rosc_init(&argc, argv, "motion", 0, -1.0);
  if (st != ROSC_OK) {
    fprintf(stderr, "motion_node: rosc_init: %s\n", rosc_strerror(st));
    return 1;
  }
  char motion[64], err[512] = "";
  double rate = 30.0, speed = 1.0, duration = 0.0;
  int ok = 1;
  ok &= param_ok(rosc_param_get_string("~motion", motion, sizeof motion, "all", NULL), "~motion",
                 "a string");
  ok &= param_ok(rosc_param_get_double("~rate", &rate, 30.0, NULL), "~rate", "a double (or an int)");
  ok &= param_ok(rosc_param_get_double("~speed", &speed, 1.0, NULL), "~speed", "a double (or an int)");
  ok &= param_ok(rosc_param_get_double("~duration", &duration, 0.0, NULL), "~duration",
                 "a double (or an int)");
  int mi = ssa_motion_builtin_index(motion);
  if (ok && mi < 0) {
    ROSC_ERROR("~motion: unknown motion '%s' (arms, elbows, twist, all, sweep)", motion);
    ok = 0;
  }
  if (ok && (!(rate > 0.0) || rate > 1000.0)) {
    ROSC_ERROR("~rate = %g Hz is out of range (0, 1000]", rate);
    ok = 0;
  }
  if (ok && (!isfinite(speed) || !isfinite(duration) || duration < 0.0)) {
    ROSC_ERROR("~speed (%g) must be finite and ~duration (%g s) finite and >= 0", speed, duration);
    ok = 0;
  }
  if (!ok) {
    rosc_shutdown();
    return 2;
  }
  char *urdf = NULL;
  int from_param = rosc_robot_description(&urdf, NULL) == ROSC_OK;
  ssa_robot *robot = NULL;
  st = ssa_robot_load_string(&robot, from_param ? urdf : ssa_mannequin_urdf(), NULL, NULL, err,
                             sizeof err);
  free(urdf);
  if (st != SS_OK) {
    ROSC_ERROR("%s: %s", from_param ? "robot_description" : "mannequin URDF", err);
    rosc_shutdown();
    return 1;
  }
  if (ssa_motion_builtin_coverage(mi, robot) == 0) {
    ROSC_ERROR("~motion '%s' moves joints of the mannequin, and robot '%s' (robot_description) "
               "has none of them: it would publish no motion", motion, robot->name);
    ssa_robot_destroy(robot);
    rosc_shutdown();
    return 2;
  }
  int nj = robot->njoint, n = 0;
  const char **names = malloc((size_t)(nj + 1) * sizeof *names);
  int *idx = malloc((size_t)(nj + 1) * sizeof *idx);
  double *q = calloc((size_t)nj + 1, sizeof *q), *val = calloc((size_t)nj + 1, sizeof *val);
  if (!names || !idx || !q || !val) return 1;
  for (int j = 0; j < nj; j++) {
    int t = robot->joint_type[j];
    if (t == SSA_JOINT_FIXED || t == SSA_JOINT_UNSUPPORTED || robot->joint_mimic[j] >= 0) continue;
    names[n] = robot->joint_name[j];
    idx[n++] = j;
  }
  msg_pub *pub = NULL;
  rosc_rate *loop = NULL;
  if (msg_pub_create(&pub, SS_MSG_JOINT_STATE, "joint_states", 10, 0) != ROSC_OK ||
      rosc_rate_create(&loop, rate) != ROSC_OK) {
    ROSC_ERROR("cannot advertise joint_states");
    rosc_shutdown();
    return 1;
  }
  ROSC_INFO("motion '%s' (period %.2f s) on %d joints at %g Hz", motion,
            ssa_motion_builtin_period(mi) / speed, n, rate);
  rosc_time start;
  rosc_now(&start);
  rosc_rate_reset(loop); /* cycles from now: stamp i is published at about its own time */
  int64_t base_ns = rosc_time_to_ns(start), period_ns = (int64_t)(1e9 / rate + 0.5);
  unsigned long i = 0, sent = 0;
  double t_motion0 = 0.0;
  while (rosc_ok()) {
    int64_t stamp_ns = base_ns + (int64_t)i * period_ns;
    rosc_time now;
    rosc_now(&now);
    if (rosc_time_to_ns(now) - stamp_ns > 500000000) { /* fell behind: re-base */
      t_motion0 += 1e-9 * (double)((int64_t)i * period_ns);
      base_ns = rosc_time_to_ns(now);
      i = 0;
      stamp_ns = base_ns;
    }
    double t = t_motion0 + 1e-9 * (double)((int64_t)i * period_ns);
    if (duration > 0.0 && t >= duration) break;
    ssa_motion_builtin_eval(mi, t * speed, robot, q);
    for (int k = 0; k < n; k++) val[k] = q[idx[k]];
    ss_msg_joint_state js;
    memset(&js, 0, sizeof js);
    js.header.stamp = ss_msg_time_from_ns(stamp_ns);
    js.name = names;
    js.n_name = (size_t)n;
    js.position = val;
    js.n_position = (size_t)n;
    if (msg_publish(pub, SS_MSG_JOINT_STATE, &js) == ROSC_OK) sent++;
    i++;
    rosc_spin_once(0.0);
    rosc_rate_sleep(loop, NULL);
  }
  ROSC_INFO("motion: %lu joint_states sent", sent);
  rosc_rate_destroy(loop);
  msg_pub_destroy(pub);
  rosc_shutdown();
  free(names); free(idx); free(q); free(val);
  ssa_robot_destroy(robot);
  return 0;
}
