/* How far a steady pull along the body takes the anchors from home, against
 * what the tether's rate would give.
 *
 *   bench_tether [substeps] [tether] [frames] [n] [gravity]
 *
 * A flat n x n patch of 1 m (the body, and the skin a copy of it), default
 * settings but for the substeps and the tether, gravity along the patch
 * (x): the skin is pulled along its body as by its own weight on a slope.
 * After `frames` frames (steady by then: the tether's time constant is
 * 1/tether s), for the anchors of the middle (x and y in [0.3, 0.7] at
 * home): the mean and largest distance from home along x of the vertex
 * anchors and of the barycenter anchors, the spring's mean stretch w (skin
 * vertex minus its anchor), and the distance a relaxation at the tether's
 * rate would settle at, (1 - tf) sigma / tf w, sigma = 1 - exp(-slide h)
 * and tf = 1 - exp(-tether h) the slide's and the tether's fractions of the
 * way per substep of h seconds. A number to read, not a test. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scene_geom.h"
#include "skin_sim/ss_sim.h"

/* argv[i] as a number if there is one, else `fallback`; *bad set where it is not a number. */
static double arg(int argc, char **argv, int i, double fallback, int *bad) {
  if (argc <= i) return fallback;
  char *end = NULL;
  const double v = strtod(argv[i], &end);
  if (end == argv[i] || *end != '\0') *bad = 1;
  return v;
}

int main(int argc, char **argv) {
  int bad = 0;
  const double substeps_d = arg(argc, argv, 1, 1.0, &bad), tether = arg(argc, argv, 2, 3.0, &bad);
  const double frames_d = arg(argc, argv, 3, 300.0, &bad), n_d = arg(argc, argv, 4, 81.0, &bad);
  const double gravity = arg(argc, argv, 5, 9.81, &bad);
  if (bad || !(substeps_d >= 1.0 && substeps_d <= 64.0) || !(tether >= 0.0) || !(frames_d >= 1.0 && frames_d <= 1e6) ||
      !(n_d >= 5.0 && n_d <= 2000.0) || !isfinite(gravity)) {
    fprintf(stderr, "usage: bench_tether [substeps 1..64] [tether >= 0 /s] [frames 1..1e6] [n 5..2000] [gravity m/s^2]\n");
    return 2;
  }
  const int substeps = (int)substeps_d, frames = (int)frames_d, n = (int)n_d;
  /* the patch: the scenes' open grid sheet over [0, 1]^2 (scene_geom.h) */
  double *coord = malloc(sizeof(double) * (size_t)n);
  ss_mb mb = {0};
  mb.failed = !coord;
  if (coord) {
    for (int i = 0; i < n; i++) coord[i] = (double)i / (n - 1);
    ss_mb_sheet(&mb, coord, n - 1, coord, n - 1, NULL);
    free(coord);
  }
  if (mb.failed) {
    fprintf(stderr, "bench_tether: out of memory\n");
    ss_mb_free(&mb);
    return 1;
  }
  const int nvert = mb.nv, nface = mb.nf;
  const double *pos = mb.pos;
  const int *faces = mb.tri;
  ss_sim_settings set = ss_sim_default_settings();
  set.substeps = substeps;
  set.tether = tether;
  set.threads = 1;
  set.gravity[0] = gravity;
  char err[256] = "";
  ss_sim *sim = NULL;
  if (ss_sim_create(&sim, nvert, pos, nface, faces, NULL, &set, err, sizeof err) != SS_OK) {
    fprintf(stderr, "bench_tether: %s\n", err);
    return 1;
  }
  const int na = ss_sim_nanchors(sim);
  double *home = malloc(3 * sizeof(double) * (size_t)na), *now = malloc(3 * sizeof(double) * (size_t)na);
  if (!home || !now) {
    fprintf(stderr, "bench_tether: out of memory\n");
    return 1;
  }
  ss_sim_anchor_positions(sim, home);
  for (int f = 0; f < frames; f++)
    if (ss_sim_step(sim, pos, 0.0, NULL, err, sizeof err) != SS_OK) {
      fprintf(stderr, "bench_tether: frame %d: %s\n", f + 1, err);
      return 1;
    }
  ss_sim_anchor_positions(sim, now);
  const double *x = ss_sim_skin_positions(sim);
  double sum[2] = {0.0, 0.0}, most[2] = {0.0, 0.0}, stretch = 0.0;
  int count[2] = {0, 0};
  for (int a = 0; a < na; a++) {
    const double *h = home + 3 * a;
    if (h[0] < 0.3 || h[0] > 0.7 || h[1] < 0.3 || h[1] > 0.7) continue;
    const int kind = a < nvert ? 0 : 1; /* vertex, barycenter */
    const double u = now[3 * a] - h[0];
    sum[kind] += u;
    most[kind] = fmax(most[kind], fabs(u));
    count[kind]++;
    if (kind == 0) stretch += x[3 * a] - now[3 * a];
  }
  const double edge = 1.0 / (n - 1), w = count[0] ? stretch / count[0] : 0.0;
  const double h = set.dt / substeps, sigma = -expm1(-set.slide * h), tf = -expm1(-tether * h);
  const double rate = tf > 0.0 ? (1.0 - tf) * sigma / tf * w : INFINITY;
  printf("patch %dx%d (edge %.4g m) substeps %d tether %g /s slide %g /s gravity %g frames %d: "
         "vertex anchors mean %.5g m max %.5g m (%.3g edges), barycenter anchors mean %.5g m max %.5g m; "
         "stretch w %.5g m; a rate would settle at %.5g m (%.3g edges); mean / rate %.3g\n",
         n, n, edge, substeps, tether, set.slide, gravity, frames, count[0] ? sum[0] / count[0] : 0.0, most[0],
         (count[0] ? sum[0] / count[0] : 0.0) / edge, count[1] ? sum[1] / count[1] : 0.0, most[1], w, rate,
         rate / edge, count[0] && rate > 0.0 ? sum[0] / count[0] / rate : 0.0);
  ss_sim_destroy(sim);
  free(home);
  free(now);
  ss_mb_free(&mb);
  return 0;
}
