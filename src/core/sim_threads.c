/* threads 0 (the settings' `threads`): the thread count of the next step,
 * measured by probes (sim_internal.h, SS_PROBE_*). */
#include "sim_internal.h"

/* threads 0: whether all cores pay is measured, not guessed (on a machine
 * whose cores are busy, every barrier waits for a descheduled thread and two
 * threads can be several times slower than one). Each probe period starts
 * with SS_PROBE_STEPS steps on one thread, then up to SS_PROBE_STEPS on all;
 * the rest of the period uses the faster (sum of wall-clock step times).
 * One thread goes first and the all-threads steps stop as soon as their sum
 * passes the one-thread steps': beside a CPU hog a step on two threads can
 * take hundreds of times as long as on one, and several of them in a row
 * would leave a node seconds behind.
 * Each probe that one thread wins doubles the period (up to
 * SS_PROBE_PERIOD_MAX steps), so that a busy machine is not asked again
 * every 50 steps; one that all threads win sets it back. The bits do not
 * depend on the thread count, so switching changes no result. */
void ss_sim_choose_threads(ss_sim *sim, double step_ms) {
  int p = sim->thread_probe;
  if (p < 0) return;
  const int n = SS_PROBE_STEPS;
  if (p < n)
    sim->probe_ms[1] += step_ms; /* this step ran on one thread */
  else if (p < 2 * n)
    sim->probe_ms[0] += step_ms; /* on all */
  p++;
  if (p < n) {
    sim->nthread = 1;
  } else if (p < 2 * n) {
    if (p > n && sim->probe_ms[0] > sim->probe_ms[1]) p = 2 * n; /* lost already: decide now */
    else sim->nthread = sim->nthread_max;
  }
  if (p == 2 * n) {
    const int all = !(sim->probe_ms[0] > sim->probe_ms[1]);
    sim->nthread = all ? sim->nthread_max : 1;
    sim->probe_period = all ? SS_PROBE_PERIOD
                            : (2 * sim->probe_period < SS_PROBE_PERIOD_MAX ? 2 * sim->probe_period
                                                                           : SS_PROBE_PERIOD_MAX);
  }
  if (p >= sim->probe_period) { /* a new probe: one thread first */
    p = 0;
    sim->probe_ms[0] = sim->probe_ms[1] = 0.0;
    sim->nthread = 1;
  }
  sim->thread_probe = p;
}

