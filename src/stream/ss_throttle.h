/* skin_sim stream: a log throttle that says what it held back (the node library,
 * src/stream; no ROS). rosconsole's ROS_*_THROTTLE drops lines silently; a node's
 * reader wants "(12 similar messages held back)". Counting is policy, so it lives
 * here and the shim only hands a finished line to rosconsole (src/nodes/node_log.h
 * joins the two). One throttle per call site or per kind of problem. */
#ifndef SKIN_SIM_SS_THROTTLE_H
#define SKIN_SIM_SS_THROTTLE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_throttle {
  double last_s; /* when the last line went out (ss_throttle_now_s) */
  uint64_t held; /* lines held back since */
  int started;   /* a line went out */
} ss_throttle;
#define SS_THROTTLE_INIT {0.0, 0, 0}

/* Seconds of a monotonic clock: the wall's pace, so that a bag looping ROS time
 * back does not silence a throttle. */
double ss_throttle_now_s(void);
/* 1 if a line may go out at now_s with at most one per period_s (period_s <= 0:
 * always); *held (may be NULL) receives the lines held back since the last one
 * that went out. 0: the line is held back (and counted). One thread per throttle. */
int ss_throttle_pass(ss_throttle *t, double now_s, double period_s, uint64_t *held);

#ifdef __cplusplus
}
#endif
#endif
