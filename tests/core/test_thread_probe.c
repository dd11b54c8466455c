/* threads 0: the probe that decides whether all cores pay (sim.c,
 * ss_sim_choose_threads), driven with step times made up here, so that the
 * test does not depend on this machine's cores or load: one thread first,
 * the all-threads steps cut short once they have lost, the faster kept for
 * the rest of the period, the period doubled after each probe one thread
 * wins (up to SS_PROBE_PERIOD_MAX) and set back when all threads win. */
#include <stdlib.h>
#include <string.h>

#include "sim_internal.h"
#include "ss_scene.h"
#include "ss_test.h"

/* The sim as threads 0 leaves it at create on a 2-core machine. */
static void start_probe(ss_sim *sim) {
  sim->nthread_max = 2;
  sim->thread_probe = 0;
  sim->probe_period = SS_PROBE_PERIOD;
  sim->probe_ms[0] = sim->probe_ms[1] = 0.0;
  sim->nthread = 1;
}

/* Runs the one-thread steps of a probe (ms each); the next step is on all. */
static void one_thread_steps(ss_sim *sim, double ms) {
  for (int i = 0; i < SS_PROBE_STEPS; i++) {
    CHECK_EQ_INT(sim->nthread, 1);
    ss_sim_choose_threads(sim, ms);
  }
  CHECK_EQ_INT(sim->nthread, 2);
}

/* Steps on the chosen count until the next probe starts. */
static void rest_of_period(ss_sim *sim, int expect_threads) {
  int guard = 0;
  while (sim->thread_probe != 0 && guard++ < 10 * SS_PROBE_PERIOD_MAX) {
    CHECK_EQ_INT(sim->nthread, expect_threads);
    ss_sim_choose_threads(sim, 1.0);
  }
  CHECK_EQ_INT(sim->thread_probe, 0);
  CHECK_EQ_INT(sim->nthread, 1); /* a new probe: one thread first */
}

int main(void) {
  char err[256] = "";
  ss_scene *sc = NULL;
  CHECK_EQ_INT(ss_scene_create(&sc, "twist", 200, err, sizeof err), SS_OK);
  if (!sc) return ss_test_finish("test_thread_probe");
  ss_sim_settings set = ss_sim_default_settings();
  set.threads = 1;
  ss_sim *sim = NULL;
  CHECK_MSG(ss_sim_create(&sim, ss_scene_nvert(sc), ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc),
                          NULL, &set, err, sizeof err) == SS_OK, "%s", err);
  if (!sim) return ss_test_finish("test_thread_probe");
  CHECK_EQ_INT(sim->thread_probe, -1); /* threads 1: no probe */
  ss_sim_stats st;
  double *pose = malloc(sizeof(double) * 3 * (size_t)ss_scene_nvert(sc));
  ss_scene_pose(sc, 1.0, pose);
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_OK);
  CHECK_EQ_INT(st.threads, 1); /* what the step ran on, for a node's diagnostics */
  free(pose);
  const int nt = sim->nthread;
  ss_sim_choose_threads(sim, 5.0);
  CHECK_EQ_INT(sim->nthread, nt);

  /* all threads win: kept for the period, which stays at its base */
  start_probe(sim);
  one_thread_steps(sim, 10.0);
  for (int i = 0; i < SS_PROBE_STEPS; i++) ss_sim_choose_threads(sim, 4.0);
  CHECK_EQ_INT(sim->nthread, 2);
  CHECK_EQ_INT(sim->probe_period, SS_PROBE_PERIOD);
  CHECK_EQ_INT(sim->thread_probe, 2 * SS_PROBE_STEPS);
  rest_of_period(sim, 2);

  /* a busy machine: the first step on all threads already takes longer than
   * the one-thread steps together: one thread at once, no more steps on all,
   * and the next probe twice as far */
  one_thread_steps(sim, 7.0);
  ss_sim_choose_threads(sim, 4400.0);
  CHECK_EQ_INT(sim->nthread, 1);
  CHECK_EQ_INT(sim->thread_probe, 2 * SS_PROBE_STEPS);
  CHECK_EQ_INT(sim->probe_period, 2 * SS_PROBE_PERIOD);
  rest_of_period(sim, 1);

  /* lost only on the sum of all its steps: decided at the last one */
  one_thread_steps(sim, 10.0);
  ss_sim_choose_threads(sim, 9.0);
  CHECK_EQ_INT(sim->nthread, 2); /* 9 < 30: go on */
  ss_sim_choose_threads(sim, 9.0);
  CHECK_EQ_INT(sim->nthread, 2); /* 18 < 30 */
  ss_sim_choose_threads(sim, 15.0); /* 33 > 30 */
  CHECK_EQ_INT(sim->nthread, 1);
  CHECK_EQ_INT(sim->probe_period, 4 * SS_PROBE_PERIOD);
  rest_of_period(sim, 1);

  /* probes lost in a row: the period doubles up to its longest, no further */
  for (int k = 0; k < 8; k++) {
    one_thread_steps(sim, 5.0);
    ss_sim_choose_threads(sim, 50.0);
    CHECK_EQ_INT(sim->nthread, 1);
    CHECK(sim->probe_period <= SS_PROBE_PERIOD_MAX);
    rest_of_period(sim, 1);
  }
  CHECK_EQ_INT(sim->probe_period, SS_PROBE_PERIOD_MAX);
  /* and all threads winning again sets it back */
  one_thread_steps(sim, 10.0);
  for (int i = 0; i < SS_PROBE_STEPS; i++) ss_sim_choose_threads(sim, 6.0);
  CHECK_EQ_INT(sim->nthread, 2);
  CHECK_EQ_INT(sim->probe_period, SS_PROBE_PERIOD);

  ss_sim_destroy(sim);
  ss_scene_destroy(sc);
  return ss_test_finish("test_thread_probe");
}
