/* The truth (ss_reference.h, ss_truth_settings): one run per body, motion and
 * physical settings that every method is measured against. Checked on the
 * `fold` scene (small, a few frames):
 *  - the truth's key does not depend on the run's anchor method, solver,
 *    iterations, tolerance, substeps or quasi-Newton settings (safety net,
 *    L-BFGS pairs: Newton has none), and
 *    does depend on a physical setting;
 *  - a run with the truth's own settings has error_vs_truth exactly 0;
 *  - the error shrinks as the step shrinks: the walk with Newton converged at
 *    1, 2 and 4 substeps per frame (slide and tether are rates: the same
 *    physics), each closer to the truth, 4 at most half as far as 1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ss_reference.h"
#include "ss_scene.h"
#include "ss_test.h"

#define FRAMES 12

/* error_vs_truth of run s against truth (ss_run_ref_errors); -1 on error. */
static double error_against(const ss_body *body, const ss_reference *truth,
                            const ss_run_settings *s) {
  char err[256] = "";
  ss_run_settings rs = *s;
  rs.frames = FRAMES;
  double v = -1.0;
  ss_run_stats st = {0};
  /* the welded skin of a scene is the body's own: bound vertex to vertex */
  int status = ss_run_ref_errors(body, &rs, &truth, 1, &v, NULL, NULL, NULL, NULL, &st, err,
                                 sizeof err);
  CHECK_MSG(status == SS_OK, "%s", err);
  CHECK(st.failures == 0 && st.snags == 0);
  return status == SS_OK ? v : -1.0;
}

static ss_run_settings converged_walk(int substeps) {
  ss_run_settings s = ss_run_default_settings();
  s.frames = FRAMES;
  s.sim.solver = SS_SOLVER_NEWTON;
  s.sim.iterations = SS_REFERENCE_ITERATIONS;
  s.sim.tol = SS_REFERENCE_TOL;
  s.sim.substeps = substeps;
  return s;
}

static void test_keys(const ss_body *body) {
  ss_run_settings a = ss_run_default_settings();
  a.frames = FRAMES;
  unsigned long long k0 = 0, k = 0;
  ss_run_settings t = ss_truth_settings(&a);
  CHECK(t.sim.mover.method == SS_METHOD_WALK && t.sim.solver == SS_SOLVER_NEWTON &&
        t.sim.substeps == SS_REFERENCE_SUBSTEPS && t.sim.tol == SS_REFERENCE_TOL);
  CHECK(ss_reference_key(body, &t, &k0, NULL, 0) == SS_OK);
  ss_run_settings b = a;
  b.sim.mover.method = SS_METHOD_PROJECT; /* every method: one truth */
  t = ss_truth_settings(&b);
  CHECK(ss_reference_key(body, &t, &k, NULL, 0) == SS_OK && k == k0);
  b.sim.mover.method = SS_METHOD_NRING;
  b.sim.mover.nring_rings = 4;
  b.sim.solver = SS_SOLVER_NEWTON;
  b.sim.iterations = 3;
  b.sim.tol = 1e-2;
  t = ss_truth_settings(&b);
  CHECK(ss_reference_key(body, &t, &k, NULL, 0) == SS_OK && k == k0);
  b = a; /* the quasi-Newton run's own settings: the truth is Newton's */
  b.sim.safety_residual = 0.0;
  b.sim.iterations_max = 8;
  b.sim.lbfgs_history = 3;
  t = ss_truth_settings(&b);
  CHECK(ss_reference_key(body, &t, &k, NULL, 0) == SS_OK && k == k0);
  t = ss_reference_settings(&b); /* and so is the reference */
  ss_run_settings r = ss_reference_settings(&a);
  unsigned long long kr = 0;
  CHECK(ss_reference_key(body, &r, &kr, NULL, 0) == SS_OK &&
        ss_reference_key(body, &t, &k, NULL, 0) == SS_OK && k == kr);
  for (int sub = 2; sub <= 32; sub *= 4) { /* 2 and 32 substeps */
    b = converged_walk(sub);
    t = ss_truth_settings(&b);
    CHECK_MSG(ss_reference_key(body, &t, &k, NULL, 0) == SS_OK && k == k0, "substeps %d", sub);
  }
  b = a;
  b.sim.young *= 2.0; /* a physical setting: another truth */
  t = ss_truth_settings(&b);
  CHECK(ss_reference_key(body, &t, &k, NULL, 0) == SS_OK && k != k0);
}

static void test_convergence(const ss_body *body) {
  char err[256] = "";
  ss_run_settings s1 = converged_walk(1);
  const ss_run_settings ts = ss_truth_settings(&s1);
  ss_reference *truth = NULL;
  int status = ss_reference_get(&truth, body, &ts, NULL, NULL, NULL, err, sizeof err);
  CHECK_MSG(status == SS_OK, "%s", err);
  if (status) return;
  const double self = error_against(body, truth, &ts);
  CHECK_MSG(self == 0.0, "the truth's own settings against the truth: %g", self);
  const double e1 = error_against(body, truth, &s1);
  const ss_run_settings s2 = converged_walk(2);
  const double e2 = error_against(body, truth, &s2);
  const ss_run_settings s4 = converged_walk(4);
  const double e4 = error_against(body, truth, &s4);
  printf("test_truth: error_vs_truth on fold, walk, Newton converged: 1 substep %.4g, "
         "2 substeps %.4g, 4 substeps %.4g mean edge lengths\n", e1, e2, e4);
  /* Steadily: each halving of the step comes closer. With `slide` a fraction per
   * substep instead of a rate (the old physics) 4 substeps slide more and land at
   * 0.158 against 0.262 at 1 (checked by hand): this fails. */
  CHECK_MSG(e1 > 0.0 && e4 > 0.0 && e4 < 0.5 * e1, "1 substep %g, 4 substeps %g", e1, e4);
  CHECK_MSG(e2 < e1 && e4 < e2, "not steadily: 1 substep %g, 2 substeps %g, 4 substeps %g", e1,
            e2, e4);
  ss_reference_destroy(truth);
}

int main(void) {
  char err[256] = "";
  ss_scene *scene = NULL;
  if (ss_scene_create(&scene, "fold", 300, err, sizeof err) != SS_OK) {
    fprintf(stderr, "test_truth: %s\n", err);
    return 1;
  }
  ss_body body = ss_body_of_scene(scene);
  test_keys(&body);
  test_convergence(&body);
  ss_scene_destroy(scene);
  return ss_test_finish("test_truth");
}
