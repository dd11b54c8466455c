/* The quasi-Newton line search's first trial (ss_sim_orient_line_step,
 * orient.c) through the internal interface:
 *  1. on a flat skin moved along the body's normal, where the orient term is
 *     its depth springs alone (the faces keep their projected area), the
 *     step is the minimum over (0, 1] of the model it claims, s_r a (1 - a/2)
 *     + the springs' energy along the line (taken from ss_sim_orient_energy,
 *     not from the function's own sums), found by sampling: with every
 *     spring on along the whole line, with springs turning on and off on the
 *     way, and 1 where the springs push along the whole line or no spring
 *     is in reach;
 *  2. the step is continuous in its input: a last-bit change of the
 *     direction moves it by rounding, not by a tolerance;
 *  3. on scenes the quasi-Newton solve's first trial is accepted far more
 *     often: energy evaluations per iteration (the first of each substep
 *     included) on fold and elbow, 2000 triangles, 30 frames at the default
 *     budget, below 1.45 (1.59 and 1.49 with the step memory alone). */
#include <math.h>
#include <string.h>

#include "sim_fixtures.h"
#include "sim_internal.h"
#include "ss_scene.h"
#include "ss_test.h"

typedef struct line_fixture {
  ss_sim *sim;
  fx_mesh g;
  int n3;
  double *x0, *dir, *grad, *xs, *full;
} line_fixture;

static int fixture_create(line_fixture *lf) {
  memset(lf, 0, sizeof *lf);
  lf->g = fx_grid(9, 9, 1.0, 1.0, 0.0); /* flat: the body's normal is +z everywhere */
  ss_sim_settings set = ss_sim_default_settings();
  set.solver = SS_SOLVER_QUASI_NEWTON;
  char err[256] = "";
  CHECK_MSG(ss_sim_create(&lf->sim, lf->g.nvert, lf->g.pos, lf->g.nface, lf->g.faces, NULL, &set,
                          err, sizeof err) == SS_OK,
            "%s", err);
  if (!lf->sim) return 0;
  /* one step at rest: frames, anchors and normals of a pose */
  CHECK(ss_sim_step(lf->sim, lf->g.pos, 0.0, NULL, NULL, 0) == SS_OK);
  ss_sim_energy_begin(lf->sim, 0.02);
  lf->n3 = 3 * lf->sim->m->ndof;
  lf->x0 = malloc((size_t)lf->n3 * sizeof(double));
  lf->dir = malloc((size_t)lf->n3 * sizeof(double));
  lf->grad = malloc((size_t)lf->n3 * sizeof(double));
  lf->xs = malloc((size_t)lf->n3 * sizeof(double));
  lf->full = malloc(3 * (size_t)lf->g.nvert * sizeof(double));
  return lf->x0 && lf->dir && lf->grad && lf->xs && lf->full;
}

static void fixture_destroy(line_fixture *lf) {
  ss_sim_destroy(lf->sim);
  fx_free(&lf->g);
  free(lf->x0), free(lf->dir), free(lf->grad), free(lf->xs), free(lf->full);
}

/* The orient term at x0 + a dir (the depth springs alone here); its slope
 * along dir into *slope if slope. */
static double orient_at(line_fixture *lf, double a, double *slope) {
  ss_sim *sim = lf->sim;
  for (int i = 0; i < lf->n3; i++) lf->xs[i] = lf->x0[i] + a * lf->dir[i];
  memcpy(lf->full, sim->x, 3 * (size_t)lf->g.nvert * sizeof(double));
  ss_sim_scatter(sim, lf->xs, lf->full);
  memset(lf->grad, 0, (size_t)lf->n3 * sizeof(double));
  double e = ss_sim_orient_energy(sim, lf->full, lf->grad, 0);
  if (slope) {
    *slope = 0.0;
    for (int i = 0; i < lf->n3; i++) *slope += lf->grad[i] * lf->dir[i];
  }
  return e;
}

/* Each free vertex at depth in [dlo, dhi] under its anchor, moving along
 * the normal at a rate in [rlo, rhi] per unit step (edge lengths). */
static void set_line(line_fixture *lf, double dlo, double dhi, double rlo, double rhi,
                     unsigned long long seed) {
  ss_sim *sim = lf->sim;
  const double l = sim->m->edge_len;
  unsigned long long rng = seed;
  for (int k = 0; k < sim->m->ndof; k++) {
    const double *a = sim->anchor_pos + 3 * sim->m->dof_vert[k];
    const double depth = (dlo + (dhi - dlo) * ss_test_rand(&rng)) * l;
    const double rate = (rlo + (rhi - rlo) * ss_test_rand(&rng)) * l;
    lf->x0[3 * k] = a[0], lf->x0[3 * k + 1] = a[1], lf->x0[3 * k + 2] = a[2] - depth;
    lf->dir[3 * k] = lf->dir[3 * k + 1] = 0.0;
    lf->dir[3 * k + 2] = rate; /* up the normal: depth(a) = depth - a rate */
  }
}

/* The model's minimiser over (0, 1] by sampling phi on a fine grid. */
static double sampled_minimum(line_fixture *lf, double rest_slope) {
  const double e0 = orient_at(lf, 0.0, NULL);
  double best = INFINITY, best_a = 1.0;
  for (int i = 1; i <= 20000; i++) {
    const double a = i / 20000.0;
    const double phi = rest_slope * a * (1.0 - 0.5 * a) + orient_at(lf, a, NULL) - e0;
    if (phi < best) best = phi, best_a = a;
  }
  return best_a;
}

static void check_case(line_fixture *lf, const char *what, double rest_over_curv, int expect_one) {
  double spring_slope = 0.0;
  orient_at(lf, 0.0, &spring_slope);
  /* the springs' curvature along the line at the full step's scale */
  const double curv = orient_at(lf, 1.0, NULL) - 2.0 * orient_at(lf, 0.0, NULL) + orient_at(lf, -1.0, NULL);
  const double rest_slope = -rest_over_curv * (curv > 0.0 ? curv : 1.0);
  const double a = ss_sim_orient_line_step(lf->sim, lf->x0, lf->dir, rest_slope + spring_slope);
  const double want = sampled_minimum(lf, rest_slope);
  if (expect_one) {
    CHECK_MSG(want == 1.0, "%s: the case must have its minimum at the full step, sampled %.5f", what, want);
    CHECK_MSG(a == 1.0, "%s: step %.6f, expected the full step", what, a);
    return;
  }
  CHECK_MSG(want < 0.999, "%s: the case must have its minimum inside (0, 1), sampled %.5f", what, want);
  CHECK_MSG(fabs(a - want) <= 1e-4, "%s: step %.6f, the model's sampled minimum %.6f", what, a, want);
}

static void test_model(void) {
  line_fixture lf;
  if (!fixture_create(&lf)) {
    CHECK(0);
    fixture_destroy(&lf);
    return;
  }
  /* all under the body and staying under: phi quadratic */
  set_line(&lf, 0.05, 0.1, -0.04, 0.04, 1);
  check_case(&lf, "every spring on", 0.3, 0);
  /* under the body and coming out, still under at the full step: the springs
   * push along the whole way, the minimum is past it */
  set_line(&lf, 0.1, 0.2, 0.01, 0.05, 4);
  check_case(&lf, "springs pushing out", 0.3, 1);
  /* springs on at the start that come out, and others that go in */
  set_line(&lf, -0.1, 0.1, -0.3, 0.3, 2);
  check_case(&lf, "springs turning on and off", 0.2, 0);
  check_case(&lf, "springs turning on and off, softer rest", 0.05, 0);
  /* everyone above the body and moving up: nothing in reach */
  set_line(&lf, -0.2, -0.1, -0.1, 0.0, 3);
  check_case(&lf, "no spring in reach", 0.3, 1);

  /* continuity: one bit of one rate changes the step by rounding only */
  set_line(&lf, -0.1, 0.1, -0.3, 0.3, 2);
  double spring_slope = 0.0;
  orient_at(&lf, 0.0, &spring_slope);
  const double slope = spring_slope - 0.2 * (orient_at(&lf, 1.0, NULL) - 2.0 * orient_at(&lf, 0.0, NULL) +
                                             orient_at(&lf, -1.0, NULL));
  const double a1 = ss_sim_orient_line_step(lf.sim, lf.x0, lf.dir, slope);
  int changed = 0;
  for (int k = 0; k < lf.sim->m->ndof && !changed; k++)
    if (lf.dir[3 * k + 2] != 0.0) lf.dir[3 * k + 2] = nextafter(lf.dir[3 * k + 2], 0.0), changed = 1;
  const double a2 = ss_sim_orient_line_step(lf.sim, lf.x0, lf.dir, slope);
  CHECK_MSG(a1 < 1.0 && fabs(a1 - a2) <= 1e-12 * a1, "a last-bit change moved the step %.17g -> %.17g",
            a1, a2);
  fixture_destroy(&lf);
}

/* Energy evaluations per iteration of the quasi-Newton solve on a scene. */
static double evaluations_per_iteration(const char *scene) {
  char err[256] = "";
  ss_scene *sc = NULL;
  CHECK_MSG(ss_scene_create(&sc, scene, 2000, err, sizeof err) == SS_OK, "%s", err);
  if (!sc) return NAN;
  ss_sim_settings set = ss_sim_default_settings();
  set.solver = SS_SOLVER_QUASI_NEWTON;
  set.threads = 1;
  /* the budget the bound was set at: every substep begins with one
   * evaluation, so the ratio is at least 1 + substeps / iterations (1.33
   * here, 1.5 at 4 substeps of 2) whatever the line search does */
  set.substeps = 2;
  set.iterations = 3;
  ss_sim *sim = NULL;
  const int nv = ss_scene_nvert(sc);
  CHECK_MSG(ss_sim_create(&sim, nv, ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc), NULL,
                          &set, err, sizeof err) == SS_OK,
            "%s", err);
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  long long evals = 0, its = 0;
  for (int f = 1; sim && pose && f <= 30; f++) {
    ss_sim_stats st;
    ss_scene_pose(sc, f, pose);
    CHECK_MSG(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err) == SS_OK, "%s frame %d: %s", scene, f, err);
    evals += st.energy_evaluations;
    its += st.iterations;
  }
  free(pose);
  ss_sim_destroy(sim);
  ss_scene_destroy(sc);
  return its > 0 ? (double)evals / (double)its : NAN;
}

int main(void) {
  (void)fx_pose; /* the fixtures' motion: not used here (a flat body at rest) */
  test_model();
  const char *scenes[] = {"fold", "elbow"};
  for (int i = 0; i < 2; i++) {
    const double r = evaluations_per_iteration(scenes[i]);
    printf("%s 2000: %.3f energy evaluations per iteration\n", scenes[i], r);
    CHECK_MSG(r < 1.45, "%s: %.3f energy evaluations per iteration (the first trial refused too often)",
              scenes[i], r);
  }
  return ss_test_finish("test_line_step");
}
