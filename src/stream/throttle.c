/* skin_sim stream: a log throttle that counts what it holds back (ss_throttle.h). */
#include "ss_throttle.h"

#include <time.h>

double ss_throttle_now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int ss_throttle_pass(ss_throttle *t, double now_s, double period_s, uint64_t *held) {
  if (held) *held = 0;
  if (t == NULL) return 1;
  if (t->started && period_s > 0.0 && now_s - t->last_s < period_s) {
    t->held++;
    return 0;
  }
  if (held) *held = t->held;
  t->held = 0;
  t->last_s = now_s;
  t->started = 1;
  return 1;
}
