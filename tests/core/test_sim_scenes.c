/* ss_sim on every built-in scene (small sizes, so it stays fast under the
 * sanitizers): the skin at rest on the body at rest stays put with both
 * solvers; with the body moving, quasi-Newton run to a tight tolerance lands
 * within a small distance of Newton's result; no failures, areas sane; and a
 * separately given skin mesh (a copy of the body, bound by closest point)
 * behaves like the built-in copy. */
#include <string.h>

#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

static double mean_edge(const ss_scene *sc) {
  const int *f = ss_scene_faces(sc);
  const double *p = ss_scene_rest(sc);
  double sum = 0.0;
  int nf = ss_scene_nface(sc);
  for (int t = 0; t < nf; t++)
    for (int c = 0; c < 3; c++) {
      const double *a = p + 3 * f[3 * t + c], *b = p + 3 * f[3 * t + (c + 1) % 3];
      sum += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
  return sum / (3.0 * nf);
}

/* Runs `frames` frames from frame 0 and returns the final positions (malloc'd). */
static double *run(const ss_scene *sc, const ss_sim_settings *set, const ss_sim_mesh *skin, int frames,
                   int moving, int *failures, int *unconverged, double *amin, double *amax) {
  int nv = ss_scene_nvert(sc);
  char err[256];
  ss_sim *sim = NULL;
  int status = ss_sim_create(&sim, nv, ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc), skin, set,
                             err, sizeof err);
  CHECK_MSG(status == SS_OK, "%s: create: %s", ss_scene_get_name(sc), err);
  if (status != SS_OK) return NULL;
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  *failures = *unconverged = 0;
  *amin = 1e300, *amax = 0.0;
  for (int f = 1; f <= frames; f++) {
    if (moving)
      ss_scene_pose(sc, f, pose);
    else
      memcpy(pose, ss_scene_rest(sc), 3 * (size_t)nv * sizeof(double));
    ss_sim_stats st;
    CHECK_EQ_INT(ss_sim_step(sim, pose, 1.0 / ss_scene_fps(sc), &st, err, sizeof err), SS_OK);
    *failures += st.failures;
    *unconverged += !st.converged;
    *amin = fmin(*amin, st.min_area_ratio);
    *amax = fmax(*amax, st.max_area_ratio);
  }
  int n = ss_sim_skin_nvert(sim);
  double *out = malloc(3 * (size_t)n * sizeof(double));
  memcpy(out, ss_sim_skin_positions(sim), 3 * (size_t)n * sizeof(double));
  free(pose);
  ss_sim_destroy(sim);
  return out;
}

int main(void) {
  for (int s = 0; s < ss_scene_count(); s++) {
    const char *name = ss_scene_name(s);
    char err[256];
    ss_scene *sc = NULL;
    if (ss_scene_create(&sc, name, 400, err, sizeof err) != SS_OK) {
      CHECK_MSG(0, "scene %s: %s", name, err);
      continue;
    }
    int nv = ss_scene_nvert(sc), failures, unconverged;
    double amin, amax, edge = mean_edge(sc);

    /* At rest: stays put, both solvers. */
    for (int solver = 0; solver < 2; solver++) {
      ss_sim_settings set = ss_sim_default_settings();
      set.solver = solver;
      double *x = run(sc, &set, NULL, 5, 0, &failures, &unconverged, &amin, &amax);
      if (!x) continue;
      double d = ss_test_max_dist(x, ss_scene_rest(sc), nv);
      CHECK_MSG(d < 1e-12 * (1.0 + edge), "%s solver %d: moved %g at rest", name, solver, d);
      free(x);
    }

    /* Moving: Newton and quasi-Newton, both tight, agree. */
    double *res[2] = {NULL, NULL};
    const int frames = 10;
    for (int solver = 0; solver < 2; solver++) {
      ss_sim_settings set = ss_sim_default_settings();
      set.solver = solver;
      set.tol = 1e-9;
      /* Stiff anchors keep each frame's minimum unique. With the default
       * soft anchors the skin of twist and quadruped lags far enough to be
       * compressed, and a membrane without bending buckles freely under
       * compression: the incremental energy then has several equally valid
       * minima, and two solvers may each land in a different one. */
      set.anchor_stiffness = 1e4;
      /* Projected Newton converges only linearly where the skin is
       * compressed (clamped eigenvalues: the crease of the elbow); L-BFGS
       * needs a long memory and many iterations on slivers. */
      set.iterations = solver == SS_SOLVER_NEWTON ? 500 : 5000;
      set.lbfgs_history = 16;
      res[solver] = run(sc, &set, NULL, frames, 1, &failures, &unconverged, &amin, &amax);
      CHECK_MSG(failures == 0, "%s solver %d: %d failures", name, solver, failures);
      /* Projected Newton can stall short of a tight tolerance where clamped
       * eigenvalues leave it only linear convergence (twist: the skin lags
       * far behind the spinning body and is compressed); it is the
       * positions that are compared below. */
      if (solver == SS_SOLVER_QUASI_NEWTON)
        CHECK_MSG(unconverged == 0, "%s solver %d: %d frames unconverged", name, solver, unconverged);
      else if (unconverged)
        printf("%-9s Newton: %d of %d frames stopped short of tol %g\n", name, unconverged, frames, set.tol);
      CHECK_MSG(amin > 0.05 && amax < 20.0, "%s solver %d: area ratios [%g, %g]", name, solver, amin, amax);
    }
    if (res[0] && res[1]) {
      double d = ss_test_max_dist(res[0], res[1], nv);
      printf("%-9s quasi-Newton vs Newton after %d frames: %.3g edge lengths\n", name, frames, d / edge);
      CHECK_MSG(d < 1e-5 * edge, "%s: quasi-Newton vs Newton %g edge lengths", name, d / edge);
    }
    free(res[1]);

    /* The same skin given as a separate mesh, bound by closest point. */
    {
      ss_sim_settings set = ss_sim_default_settings();
      set.solver = SS_SOLVER_NEWTON;
      set.tol = 1e-9;
      set.iterations = 500;
      set.anchor_stiffness = 1e4; /* as res[0], which it is compared with */
      ss_sim_mesh skin = {nv, ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc)};
      double *x = run(sc, &set, &skin, frames, 1, &failures, &unconverged, &amin, &amax);
      if (x && res[0]) {
        double d = ss_test_max_dist(x, res[0], nv);
        printf("%-9s bound skin vs copied skin after %d frames: %.3g edge lengths\n", name, frames, d / edge);
        /* Closest-point anchors sit where the copy's are, up to round-off
         * and ties between faces sharing the point: in `slivers` the
         * barycenter of a sliver (aspect ~300) or of a zero-area face is as
         * close to a neighbour, which then carries the anchor (measured
         * 9e-4 edge lengths after 10 frames; the other scenes < 1e-6). */
        double tol = strcmp(name, "slivers") == 0 ? 1e-2 : 1e-5;
        CHECK_MSG(d < tol * edge, "%s: bound skin vs copied skin %g edge lengths", name, d / edge);
      }
      free(x);
    }
    free(res[0]);
    ss_scene_destroy(sc);
  }
  return ss_test_finish("test_sim_scenes");
}
