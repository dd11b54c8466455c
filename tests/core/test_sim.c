/* Tests of the dynamic skin (src/core/sim*.c, solver_*.c) on small grid
 * patches: rest stays put with both solvers, a stretched patch returns to
 * rest, the membrane's static stretch under load matches plane-stress
 * elasticity, Newton and quasi-Newton agree when run tightly, the face mask
 * pins and follows, bad input is rejected with the state kept, violent motion
 * stays finite, and two identical runs give identical bits. */
#include <string.h>

#include "sim_fixtures.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

static int all_finite(const double *a, int n) {
  for (int i = 0; i < n; i++)
    if (!isfinite(a[i])) return 0;
  return 1;
}

static ss_sim *make_sim(const fx_mesh *g, const ss_sim_settings *set) {
  char err[256] = "";
  ss_sim *sim = NULL;
  int status = ss_sim_create(&sim, g->nvert, g->pos, g->nface, g->faces, NULL, set, err, sizeof err);
  CHECK_MSG(status == SS_OK && sim, "create: %s", err);
  return sim;
}

/* At rest on a body at rest, the skin does not move (both solvers, with
 * bending, barycenters, damping; and with a separate, bound skin mesh). */
static void test_rest_stays_put(void) {
  fx_mesh g = fx_grid(10, 10, 1.0, 1.0, 0.2);
  for (int solver = 0; solver < 2; solver++) {
    for (int bending = 0; bending < 2; bending++) {
      ss_sim_settings set = ss_sim_default_settings();
      set.solver = solver;
      set.bending = bending ? 1e-3 : 0.0;
      set.damping = 1.0;
      set.tol = 1e-10;
      ss_sim *sim = make_sim(&g, &set);
      if (!sim) continue;
      ss_sim_stats st;
      for (int f = 0; f < 10; f++) CHECK_EQ_INT(ss_sim_step(sim, g.pos, 0.0, &st, NULL, 0), SS_OK);
      double d = ss_test_max_dist(ss_sim_skin_positions(sim), g.pos, g.nvert);
      CHECK_MSG(d < 1e-13, "solver %d bending %d: moved %g at rest", solver, bending, d);
      CHECK(st.converged);
      CHECK_EQ_INT(st.failures, 0);
      CHECK_NEAR(st.min_area_ratio, 1.0, 1e-12);
      CHECK_NEAR(st.max_area_ratio, 1.0, 1e-12);
      ss_sim_destroy(sim);
    }
  }
  fx_free(&g);
}

/* Deformed and released, the skin returns to rest: anchors pull it back. */
static void test_stretched_returns(void) {
  fx_mesh g = fx_grid(9, 9, 1.0, 1.0, 0.0);
  for (int solver = 0; solver < 2; solver++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.solver = solver;
    set.damping = 5.0;
    set.slide = 0.0; /* anchors glued: the rest state is the unique minimum */
    set.tol = 1e-7;
    ss_sim *sim = make_sim(&g, &set);
    if (!sim) continue;
    double *x = malloc(3 * (size_t)g.nvert * sizeof(double));
    for (int v = 0; v < g.nvert; v++) {
      x[3 * v] = 1.3 * (g.pos[3 * v] - 0.5) + 0.5;
      x[3 * v + 1] = 0.8 * (g.pos[3 * v + 1] - 0.5) + 0.5;
      x[3 * v + 2] = 0.1 * sin(7.0 * g.pos[3 * v]);
    }
    CHECK_EQ_INT(ss_sim_set_state(sim, x, NULL, NULL, 0), SS_OK);
    double d0 = ss_test_max_dist(ss_sim_skin_positions(sim), g.pos, g.nvert);
    ss_sim_stats st;
    for (int f = 0; f < 120; f++) ss_sim_step(sim, g.pos, 0.0, &st, NULL, 0);
    double d = ss_test_max_dist(ss_sim_skin_positions(sim), g.pos, g.nvert);
    CHECK_MSG(d < 1e-4 * d0, "solver %d: %g from rest after release (started %g)", solver, d, d0);
    CHECK_EQ_INT(st.failures, 0);
    free(x);
    ss_sim_destroy(sim);
  }
  /* Without anchors the membrane alone restores the rest shape (up to a
   * rigid motion): every edge back to its rest length. */
  {
    ss_sim_settings set = ss_sim_default_settings();
    set.solver = SS_SOLVER_NEWTON;
    set.anchor_stiffness = 0.0;
    set.damping = 5.0;
    set.tol = 1e-8;
    ss_sim *sim = make_sim(&g, &set);
    double *x = malloc(3 * (size_t)g.nvert * sizeof(double));
    for (int v = 0; v < g.nvert; v++) {
      x[3 * v] = 1.2 * g.pos[3 * v];
      x[3 * v + 1] = 1.1 * g.pos[3 * v + 1];
      x[3 * v + 2] = 0.0;
    }
    ss_sim_set_state(sim, x, NULL, NULL, 0);
    ss_sim_stats st;
    for (int f = 0; f < 150; f++) ss_sim_step(sim, g.pos, 0.0, &st, NULL, 0);
    const double *p = ss_sim_skin_positions(sim);
    double worst = 0.0;
    for (int f = 0; f < g.nface; f++)
      for (int c = 0; c < 3; c++) {
        int a = g.faces[3 * f + c], b = g.faces[3 * f + (c + 1) % 3];
        double l = 0.0, l0 = 0.0;
        for (int i = 0; i < 3; i++) {
          l += (p[3 * a + i] - p[3 * b + i]) * (p[3 * a + i] - p[3 * b + i]);
          l0 += (g.pos[3 * a + i] - g.pos[3 * b + i]) * (g.pos[3 * a + i] - g.pos[3 * b + i]);
        }
        worst = fmax(worst, fabs(sqrt(l) / sqrt(l0) - 1.0));
      }
    CHECK_MSG(worst < 1e-4, "membrane only: edge strain %g after release", worst);
    free(x);
    ss_sim_destroy(sim);
  }
  fx_free(&g);
}

/* A strip hanging from its pinned end under an in-plane load (gravity along
 * +x, no anchors), solved quasi-statically (a long time step, Newton): the
 * elongation of a bar under its own weight, rho g L^2 / (2 E), and the
 * lateral contraction -nu of the strain near the middle (plane stress). */
static void test_membrane_moduli(double compression) {
  const double len = 2.0, width = 0.25, young = 1000.0, nu = 0.3, rho = 1.0, grav = 5.0;
  /* The compression-soft membrane (compression c < 1) in uniaxial tension:
   * the lateral direction is compressed, so it contracts more, nu_c = l /
   * (2 c mu + l), and the bar is softer, E_c = 2 mu + 2 c mu nu_c^2 + l (1 -
   * nu_c)^2 (mu the shear modulus, l the plane-stress first Lame parameter;
   * from minimising mu e^2 + c mu d^2 + l/2 (e + d)^2 over the lateral strain
   * d; c = 1 gives young and nu back). */
  const double mu = young / (2.0 * (1.0 + nu)), l = young * nu / (1.0 - nu * nu);
  const double nu_c = l / (2.0 * compression * mu + l);
  const double young_c = 2.0 * mu + 2.0 * compression * mu * nu_c * nu_c + l * (1.0 - nu_c) * (1.0 - nu_c);
  fx_mesh g = fx_grid(41, 6, len, width, 0.0);
  unsigned char *mask = malloc((size_t)g.nface);
  /* The first column of cells is not simulated: its vertices follow the body,
   * which makes the x = 0 and x = dx columns the pinned root. */
  for (int f = 0; f < g.nface; f++) {
    int cell = f / 2, i = cell % 40;
    mask[f] = i != 0;
  }
  ss_sim_settings set = ss_sim_default_settings();
  set.solver = SS_SOLVER_NEWTON;
  set.anchor_stiffness = 0.0;
  set.young = young;
  set.poisson = nu;
  set.density = rho;
  set.gravity[0] = grav;
  set.dt = 100.0;
  set.iterations = 100;
  set.tol = 1e-10;
  set.face_mask = mask;
  set.compression = compression;
  ss_sim *sim = make_sim(&g, &set);
  free(mask);
  if (!sim) return;
  ss_sim_stats st;
  for (int f = 0; f < 3; f++) ss_sim_step(sim, g.pos, 0.0, &st, NULL, 0);
  CHECK(st.converged);
  const double *p = ss_sim_skin_positions(sim);
  /* Free length from the pinned column x = dx. */
  double dx = len / 40.0, free_len = len - dx;
  double tip = 0.0;
  for (int j = 0; j < 6; j++) tip += p[3 * (j * 41 + 40)] / 6.0;
  double expect = rho * grav * free_len * free_len / (2.0 * young_c);
  double got = tip - len;
  CHECK_MSG(fabs(got - expect) < 0.05 * expect, "compression %g: elongation %g, expected %g",
            compression, got, expect);
  /* Near the middle (x = 1.25): stress rho g (L - x), lateral strain -nu eps. */
  int i = 25;
  double x_mid = i * dx, eps = rho * grav * (len - x_mid) / young_c;
  double wid = p[3 * (5 * 41 + i) + 1] - p[3 * (0 * 41 + i) + 1];
  double lat = wid / width - 1.0;
  CHECK_MSG(fabs(lat + nu_c * eps) < 0.1 * nu_c * eps, "compression %g: lateral strain %g, expected %g",
            compression, lat, -nu_c * eps);
  ss_sim_destroy(sim);
  fx_free(&g);
}

/* Both solvers, run tightly, land on the same trajectory. */
static void test_solvers_agree(void) {
  fx_mesh g = fx_grid(10, 10, 1.0, 1.0, 0.15);
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  double *res[2];
  for (int solver = 0; solver < 2; solver++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.solver = solver;
    set.tol = 1e-10;
    set.iterations = 2000;
    set.bending = 1e-3;
    ss_sim *sim = make_sim(&g, &set);
    ss_sim_stats st;
    int converged = 1;
    for (int f = 1; f <= 15; f++) {
      fx_pose(&g, f / 30.0, pose);
      CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, NULL, 0), SS_OK);
      converged &= st.converged;
    }
    CHECK_MSG(converged, "solver %d did not converge (residual %g)", solver, st.residual);
    res[solver] = malloc(3 * (size_t)g.nvert * sizeof(double));
    memcpy(res[solver], ss_sim_skin_positions(sim), 3 * (size_t)g.nvert * sizeof(double));
    ss_sim_destroy(sim);
  }
  double d = ss_test_max_dist(res[0], res[1], g.nvert);
  double moved = ss_test_max_dist(res[0], g.pos, g.nvert);
  CHECK_MSG(d < 1e-6 && moved > 0.05, "Newton vs quasi-Newton differ by %g (moved %g)", d, moved);
  free(res[0]);
  free(res[1]);
  free(pose);
  fx_free(&g);
}

/* The face mask: vertices outside follow the body, the border is pinned,
 * only the inside moves freely. */
static void test_face_mask(void) {
  fx_mesh g = fx_grid(9, 9, 1.0, 1.0, 0.1);
  unsigned char *mask = calloc((size_t)g.nface, 1);
  for (int f = 0; f < g.nface; f++) {
    int cell = f / 2, i = cell % 8, j = cell / 8;
    mask[f] = i >= 2 && i < 6 && j >= 2 && j < 6;
  }
  ss_sim_settings set = ss_sim_default_settings();
  set.face_mask = mask;
  ss_sim *sim = make_sim(&g, &set);
  free(mask);
  if (!sim) return;
  /* Inside a 4x4-cell block: 3x3 free vertices. */
  CHECK_EQ_INT(ss_sim_ndof(sim), 9);
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  ss_sim_stats st;
  for (int f = 1; f <= 10; f++) {
    fx_pose(&g, f / 30.0, pose);
    ss_sim_step(sim, pose, 0.0, &st, NULL, 0);
  }
  const double *p = ss_sim_skin_positions(sim);
  double worst_fixed = 0.0, most_free = 0.0;
  for (int v = 0; v < g.nvert; v++) {
    int i = v % 9, j = v / 9;
    double d = ss_test_max_dist(p + 3 * v, pose + 3 * v, 1);
    if (i >= 3 && i <= 5 && j >= 3 && j <= 5)
      most_free = fmax(most_free, d);
    else
      worst_fixed = fmax(worst_fixed, d);
  }
  CHECK_MSG(worst_fixed < 1e-12, "fixed vertices off the body by %g", worst_fixed);
  CHECK_MSG(most_free > 1e-6, "free vertices did not move off the body (%g)", most_free);
  ss_sim_destroy(sim);
  /* Nothing simulated: the skin is the body. */
  unsigned char *none = calloc((size_t)g.nface, 1);
  for (int solver = 0; solver < 2; solver++) {
    set = ss_sim_default_settings();
    set.solver = solver;
    set.face_mask = none;
    sim = make_sim(&g, &set);
    if (!sim) continue;
    CHECK_EQ_INT(ss_sim_ndof(sim), 0);
    fx_pose(&g, 0.2, pose);
    CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, NULL, 0), SS_OK);
    CHECK(ss_test_max_dist(ss_sim_skin_positions(sim), pose, g.nvert) < 1e-12);
    ss_sim_destroy(sim);
  }
  free(none);
  free(pose);
  fx_free(&g);
}

/* Gravity on a patch held by anchor springs only (no membrane): every vertex
 * sags by rho g / k (stiffness and mass are both per area, shared half and
 * half between vertex and barycenter springs). Solved quasi-statically. */
static void test_gravity_sag(void) {
  fx_mesh g = fx_grid(7, 7, 1.0, 1.0, 0.0);
  for (int bary = 0; bary < 2; bary++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.young = 0.0;
    set.orient = 0.0; /* the sag goes into the flat body, which orient's depth spring resists */
    set.density = 2.0;
    set.anchor_stiffness = 500.0;
    set.barycenter_anchors = bary;
    set.gravity[2] = -9.81;
    set.slide = 0.0;
    set.dt = 1e3;
    set.tol = 1e-12;
    ss_sim *sim = make_sim(&g, &set);
    if (!sim) continue;
    for (int f = 0; f < 3; f++) ss_sim_step(sim, g.pos, 0.0, NULL, NULL, 0);
    const double *p = ss_sim_skin_positions(sim);
    double expect = -2.0 * 9.81 / 500.0, worst = 0.0;
    for (int v = 0; v < g.nvert; v++) {
      worst = fmax(worst, fabs(p[3 * v + 2] - expect));
      worst = fmax(worst, fabs(p[3 * v] - g.pos[3 * v]) + fabs(p[3 * v + 1] - g.pos[3 * v + 1]));
    }
    CHECK_MSG(worst < 1e-9, "barycenters %d: sag off by %g (expected %g)", bary, worst, expect);
    ss_sim_destroy(sim);
  }
  fx_free(&g);
}

/* slide = 0 glues the anchors; slide > 0 lets them follow the skin, and the
 * statistics count every move. */
static void test_slide(void) {
  fx_mesh g = fx_grid(9, 9, 1.0, 1.0, 0.1);
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  for (int k = 0; k < 2; k++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.slide = k ? 1.0 : 0.0;
    ss_sim *sim = make_sim(&g, &set);
    if (!sim) continue;
    int na = ss_sim_nanchors(sim);
    CHECK_EQ_INT(na, g.nvert + g.nface);
    int *face0 = malloc((size_t)na * sizeof(int));
    double *uv0 = malloc(2 * (size_t)na * sizeof(double));
    memcpy(face0, ss_sim_anchor_faces(sim), (size_t)na * sizeof(int));
    memcpy(uv0, ss_sim_anchor_uv(sim), 2 * (size_t)na * sizeof(double));
    ss_sim_stats st;
    for (int f = 1; f <= 10; f++) {
      fx_pose(&g, f / 30.0, pose);
      ss_sim_step(sim, pose, 0.0, &st, NULL, 0);
    }
    int changed = memcmp(face0, ss_sim_anchor_faces(sim), (size_t)na * sizeof(int)) != 0 ||
                  memcmp(uv0, ss_sim_anchor_uv(sim), 2 * (size_t)na * sizeof(double)) != 0;
    if (k == 0) {
      CHECK_MSG(!changed, "slide 0: anchors moved");
      CHECK_EQ_INT(st.anchors_moved, 0);
    } else {
      CHECK_MSG(changed, "slide 1: anchors did not move");
      CHECK_EQ_INT(st.anchors_moved, na * set.substeps); /* every anchor, every substep */
    }
    /* Anchor world positions lie on the body in its current pose. */
    double *ap = malloc(3 * (size_t)na * sizeof(double));
    ss_sim_anchor_positions(sim, ap);
    CHECK(all_finite(ap, 3 * na));
    free(ap);
    free(face0);
    free(uv0);
    ss_sim_destroy(sim);
  }
  free(pose);
  fx_free(&g);
}

/* Each anchor's pull and path are measured only when asked, and measuring
 * them changes nothing: a measured and an unmeasured sim (slide and
 * tether on) step to the same bits, the unmeasured one reports NULL, the
 * measured one a pull and a walked path for the anchors that moved. */
static void test_measure_anchors(void) {
  fx_mesh g = fx_grid(9, 9, 1.0, 1.0, 0.1);
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  ss_sim_settings set = ss_sim_default_settings();
  set.slide = 4.0;
  set.tether = 2.0;
  ss_sim *plain = make_sim(&g, &set), *measured = make_sim(&g, &set);
  if (plain && measured) {
    const int na = ss_sim_nanchors(plain);
    CHECK(ss_sim_anchor_pull(plain) == NULL && ss_sim_anchor_path(plain) == NULL);
    ss_sim_measure_anchors(measured, 1);
    CHECK(ss_sim_anchor_pull(measured) != NULL && ss_sim_anchor_path(measured) != NULL);
    int moved = 0, walked = 0, bad = 0;
    ss_sim_stats st;
    for (int f = 1; f <= 12; f++) {
      fx_pose(&g, f / 30.0, pose);
      CHECK_EQ_INT(ss_sim_step(plain, pose, 0.0, &st, NULL, 0), SS_OK);
      CHECK_EQ_INT(ss_sim_step(measured, pose, 0.0, &st, NULL, 0), SS_OK);
      const double *pull = ss_sim_anchor_pull(measured), *path = ss_sim_anchor_path(measured);
      for (int a = 0; a < na; a++) {
        moved += pull[a] > 0.0;
        walked += path[a] > 0.0;
        bad += !(pull[a] >= 0.0 && path[a] >= 0.0 && isfinite(pull[a]) && isfinite(path[a]));
      }
    }
    CHECK_MSG(moved > na && walked > na, "anchors with a pull %d, with a path %d (of %d x 12)", moved, walked, na);
    CHECK_EQ_INT(bad, 0);
    CHECK(memcmp(ss_sim_skin_positions(plain), ss_sim_skin_positions(measured),
                 3 * (size_t)ss_sim_skin_nvert(plain) * sizeof(double)) == 0);
    CHECK(memcmp(ss_sim_anchor_faces(plain), ss_sim_anchor_faces(measured), (size_t)na * sizeof(int)) == 0);
    CHECK(memcmp(ss_sim_anchor_uv(plain), ss_sim_anchor_uv(measured), 2 * (size_t)na * sizeof(double)) == 0);
    ss_sim_measure_anchors(measured, 0);
    CHECK(ss_sim_anchor_pull(measured) == NULL && ss_sim_anchor_path(measured) == NULL);
  }
  ss_sim_destroy(plain);
  ss_sim_destroy(measured);
  free(pose);
  fx_free(&g);
}

/* Bending resists bending: a cantilever strip (root pinned through the face
 * mask, no anchors) under gravity droops less with hinge bending on, and
 * less again with a stiffer hinge; the membrane alone hardly resists. */
static void test_bending_cantilever(void) {
  fx_mesh g = fx_grid(21, 4, 1.0, 0.15, 0.0);
  unsigned char *mask = malloc((size_t)g.nface);
  for (int f = 0; f < g.nface; f++) mask[f] = (f / 2) % 20 >= 2; /* two root columns follow the body */
  double tip[3];
  const double ks[3] = {0.0, 0.1, 1.0};
  for (int k = 0; k < 3; k++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.solver = SS_SOLVER_NEWTON;
    set.anchor_stiffness = 0.0;
    set.bending = ks[k];
    set.gravity[2] = -9.81;
    set.face_mask = mask;
    set.dt = 10.0; /* quasi-static */
    set.iterations = 200;
    set.tol = 1e-9;
    ss_sim *sim = make_sim(&g, &set);
    if (!sim) return;
    ss_sim_stats st;
    for (int f = 0; f < 5; f++) ss_sim_step(sim, g.pos, 0.0, &st, NULL, 0);
    CHECK_EQ_INT(st.failures, 0);
    const double *p = ss_sim_skin_positions(sim);
    tip[k] = 0.0;
    for (int j = 0; j < 4; j++) tip[k] += p[3 * (j * 21 + 20) + 2] / 4.0;
    ss_sim_destroy(sim);
  }
  printf("cantilever tip z: %g (no bending), %g (k 0.1), %g (k 1)\n", tip[0], tip[1], tip[2]);
  CHECK_MSG(tip[0] < -0.5, "membrane only: tip at z = %g, expected to hang down", tip[0]);
  CHECK_MSG(tip[1] > tip[0] + 0.01 && tip[2] > tip[1] + 0.01, "tip z: %g (k 0), %g (k 0.1), %g (k 1)",
            tip[0], tip[1], tip[2]);
  free(mask);
  fx_free(&g);
}

/* A skin coarser than the body (every other grid line), bound by closest
 * point: it follows the moving body, its vertices near their anchors. */
static void test_coarse_skin(void) {
  fx_mesh body = fx_grid(13, 13, 1.0, 1.0, 0.15), skin = fx_grid(7, 7, 1.0, 1.0, 0.15);
  ss_sim_settings set = ss_sim_default_settings();
  set.iterations = 50;
  ss_sim_mesh sk = {skin.nvert, skin.pos, skin.nface, skin.faces};
  char err[256];
  ss_sim *sim = NULL;
  CHECK_EQ_INT(ss_sim_create(&sim, body.nvert, body.pos, body.nface, body.faces, &sk, &set, err, sizeof err),
               SS_OK);
  if (!sim) return;
  CHECK_EQ_INT(ss_sim_skin_nvert(sim), skin.nvert);
  CHECK_EQ_INT(ss_sim_nanchors(sim), skin.nvert + skin.nface);
  double *pose = malloc(3 * (size_t)body.nvert * sizeof(double));
  double *ap = malloc(3 * (size_t)ss_sim_nanchors(sim) * sizeof(double));
  ss_sim_stats st;
  for (int f = 1; f <= 15; f++) {
    fx_pose(&body, f / 30.0, pose);
    CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_OK);
  }
  ss_sim_anchor_positions(sim, ap);
  const double *p = ss_sim_skin_positions(sim);
  double worst = 0.0;
  for (int v = 0; v < skin.nvert; v++) worst = fmax(worst, ss_test_max_dist(p + 3 * v, ap + 3 * v, 1));
  /* Edge length of the skin: 1/6. */
  CHECK_MSG(worst < 0.1 / 6.0, "coarse skin: %g from its anchors", worst);
  CHECK(st.min_area_ratio > 0.5 && st.max_area_ratio < 2.0);
  free(ap);
  free(pose);
  ss_sim_destroy(sim);
  fx_free(&body);
  fx_free(&skin);
}

/* Bad input: an error code and a message, and the state kept. */
static void test_bad_input(void) {
  fx_mesh g = fx_grid(6, 6, 1.0, 1.0, 0.0);
  char err[256];
  ss_sim *sim = NULL;
  ss_sim_settings set = ss_sim_default_settings();
  set.dt = -1.0;
  err[0] = 0;
  CHECK_EQ_INT(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err), SS_E_ARG);
  CHECK(sim == NULL && strlen(err) > 0);
  set = ss_sim_default_settings();
  set.poisson = 0.5;
  CHECK_EQ_INT(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err), SS_E_ARG);
  set = ss_sim_default_settings();
  g.faces[4] = g.nvert; /* index out of range */
  CHECK_EQ_INT(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err), SS_E_MESH);
  g.faces[4] = 1;
  g.pos[7] = NAN;
  CHECK_EQ_INT(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err),
               SS_E_NONFINITE);
  g.pos[7] = 0.2;
  CHECK_EQ_INT(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err), SS_OK);
  if (!sim) return;
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  fx_pose(&g, 0.1, pose);
  ss_sim_step(sim, pose, 0.0, NULL, NULL, 0);
  double *before = malloc(3 * (size_t)g.nvert * sizeof(double));
  memcpy(before, ss_sim_skin_positions(sim), 3 * (size_t)g.nvert * sizeof(double));
  pose[10] = NAN;
  err[0] = 0;
  ss_sim_stats st;
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_E_NONFINITE);
  CHECK(strlen(err) > 0);
  pose[10] = INFINITY;
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_E_NONFINITE);
  CHECK_EQ_INT(ss_sim_step(sim, NULL, 0.0, &st, err, sizeof err), SS_E_ARG);
  CHECK(memcmp(before, ss_sim_skin_positions(sim), 3 * (size_t)g.nvert * sizeof(double)) == 0);
  before[5] = NAN;
  CHECK_EQ_INT(ss_sim_set_state(sim, before, NULL, err, sizeof err), SS_E_NONFINITE);
  CHECK(all_finite(ss_sim_skin_positions(sim), 3 * g.nvert));
  /* Still steps normally afterwards. */
  fx_pose(&g, 0.2, pose);
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_OK);
  CHECK(all_finite(ss_sim_skin_positions(sim), 3 * g.nvert));
  free(before);
  free(pose);
  ss_sim_destroy(sim);
  fx_free(&g);
}

/* Warnings are counted over the sim's life: a refused step names its step
 * and vertex, an unconverged step counts, ss_sim_reset keeps them and
 * ss_sim_clear_warnings clears them. */
static void test_warnings(void) {
  fx_mesh g = fx_grid(6, 6, 1.0, 1.0, 0.0);
  char err[256];
  ss_sim *sim = NULL;
  ss_sim_settings set = ss_sim_default_settings();
  set.iterations = set.iterations_max = 200; /* converges: no warning */
  CHECK_EQ_INT(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err), SS_OK);
  if (!sim) return;
  const ss_warning *w = ss_sim_warnings(sim);
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  fx_pose(&g, 0.1, pose);
  ss_sim_stats st;
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_OK);
  CHECK(st.converged && st.failures == 0);
  CHECK(ss_sim_step_count(sim) == 1);
  for (int k = 0; k < SS_NWARNING; k++) CHECK_MSG(w[k].number == 0, "%s after a clean step", ss_warning_name(k));
  pose[10] = NAN; /* vertex 3 */
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_E_NONFINITE);
  CHECK(w[SS_WARN_REFUSED].number == 1 && w[SS_WARN_REFUSED].last_step == 2 &&
        w[SS_WARN_REFUSED].last_info == 3);
  CHECK(ss_sim_step_count(sim) == 1);
  ss_sim_reset(sim);
  CHECK(w[SS_WARN_REFUSED].number == 1);
  /* one iteration towards an unreachable tolerance */
  set.iterations = set.iterations_max = 1;
  set.tol = 1e-15;
  int recreate = 0;
  CHECK_EQ_INT(ss_sim_set_settings(sim, &set, &recreate, err, sizeof err), SS_OK);
  CHECK(recreate == 0);
  fx_pose(&g, 0.3, pose);
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, err, sizeof err), SS_OK);
  CHECK(!st.converged);
  CHECK(w[SS_WARN_UNCONVERGED].number == 1 && w[SS_WARN_UNCONVERGED].last_step == 2 &&
        w[SS_WARN_UNCONVERGED].last_info == st.substeps);
  CHECK(w[SS_WARN_FAILURE].number == 0 && w[SS_WARN_SOLVER].number == 0);
  ss_sim_clear_warnings(sim);
  for (int k = 0; k < SS_NWARNING; k++) CHECK(w[k].number == 0 && w[k].last_step == 0);
  CHECK(strcmp(ss_warning_name(SS_WARN_STEP_LIMIT), "step_limit") == 0);
  CHECK(strcmp(ss_warning_name(SS_NWARNING), "unknown") == 0);
  free(pose);
  ss_sim_destroy(sim);
  fx_free(&g);
}

/* Small and odd meshes: one triangle; a body with a vertex in no face (its
 * skin copy follows it) and a zero-area face. */
static void test_small_meshes(void) {
  double p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, q[9] = {0, 0, 0.1, 1, 0, 0.1, 0, 1, 0.1};
  int f[3] = {0, 1, 2};
  char err[256];
  for (int solver = 0; solver < 2; solver++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.solver = solver;
    set.bending = 1.0;
    /* The body jumps 0.1 at the first frame; the skin, undamped, rings
     * about it and settles in 2 s at 4 substeps (shorter steps: less of
     * implicit Euler's damping; 1.2e-3 away after 1 s), its substeps
     * converged: at the default tol the skin stops where a substep's step
     * falls under it, 1.6e-3 from the body here at 4 substeps (3e-4 at 2);
     * at 1e-6, 6e-5 after 2 s */
    set.tol = 1e-6;
    ss_sim *sim = NULL;
    CHECK_EQ_INT(ss_sim_create(&sim, 3, p, 1, f, NULL, &set, err, sizeof err), SS_OK);
    if (!sim) continue;
    CHECK_EQ_INT(ss_sim_ndof(sim), 3);
    for (int i = 0; i < 60; i++) CHECK_EQ_INT(ss_sim_step(sim, q, 0.0, NULL, NULL, 0), SS_OK);
    CHECK(ss_test_max_dist(ss_sim_skin_positions(sim), q, 3) < 1e-3);
    ss_sim_destroy(sim);
  }
  double p2[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5, 2, 0, 0}, q2[15];
  int f2[6] = {0, 1, 2, 0, 1, 4}; /* vertex 3 in no face; face 1 has zero area */
  for (int i = 0; i < 15; i++) q2[i] = p2[i] + 0.1;
  ss_sim *sim = NULL;
  CHECK_EQ_INT(ss_sim_create(&sim, 5, p2, 2, f2, NULL, NULL, err, sizeof err), SS_OK);
  if (sim) {
    ss_sim_stats st;
    CHECK_EQ_INT(ss_sim_step(sim, q2, 0.0, &st, NULL, 0), SS_OK);
    CHECK(all_finite(ss_sim_skin_positions(sim), 15));
    CHECK(ss_test_max_dist(ss_sim_skin_positions(sim) + 9, q2 + 9, 1) < 1e-15);
    CHECK_EQ_INT(st.failures, 0);
    ss_sim_destroy(sim);
  }
  /* A skin without area is refused. */
  double line[9] = {0, 0, 0, 0.5, 0, 0, 1, 0, 0};
  ss_sim_mesh m = {3, line, 1, f};
  err[0] = 0;
  CHECK_EQ_INT(ss_sim_create(&sim, 3, p, 1, f, &m, NULL, err, sizeof err), SS_E_MESH);
  CHECK(sim == NULL && strlen(err) > 0);
}

/* Violent motion (teleports, huge stretch): finite, areas positive. */
static void test_violent_motion(void) {
  fx_mesh g = fx_grid(8, 8, 1.0, 1.0, 0.1);
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  for (int solver = 0; solver < 2; solver++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.solver = solver;
    ss_sim *sim = make_sim(&g, &set);
    ss_sim_stats st;
    for (int f = 0; f < 20; f++) {
      for (int v = 0; v < g.nvert; v++)
        for (int i = 0; i < 3; i++)
          pose[3 * v + i] = g.pos[3 * v + i] * (f % 2 ? 5.0 : 0.2) + (f % 3) * 100.0;
      CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, &st, NULL, 0), SS_OK);
      CHECK(all_finite(ss_sim_skin_positions(sim), 3 * g.nvert));
      CHECK(all_finite(ss_sim_skin_velocities(sim), 3 * g.nvert));
      CHECK(isfinite(st.residual) && isfinite(st.min_area_ratio) && isfinite(st.max_area_ratio));
    }
    ss_sim_destroy(sim);
  }
  free(pose);
  fx_free(&g);
}

/* Same inputs, same bits (both solvers, substeps, all terms on), also after
 * ss_sim_reset. */
static void test_determinism(void) {
  fx_mesh g = fx_grid(10, 10, 1.0, 1.0, 0.2);
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  for (int solver = 0; solver < 2; solver++) {
    double *out[3];
    ss_sim *sim = NULL;
    /* Runs 0 and 1: two simulations; run 2: the second one after a reset. */
    for (int run = 0; run < 3; run++) {
      ss_sim_settings set = ss_sim_default_settings();
      set.solver = solver;
      set.substeps = 2;
      set.bending = 1e-3;
      set.damping = 0.5;
      set.gravity[2] = -9.81;
      if (run < 2) {
        if (sim) ss_sim_destroy(sim);
        sim = make_sim(&g, &set);
      } else {
        ss_sim_reset(sim);
        CHECK(memcmp(ss_sim_skin_positions(sim), g.pos, 3 * (size_t)g.nvert * sizeof(double)) == 0);
      }
      CHECK_EQ_INT(ss_sim_body_nvert(sim), g.nvert);
      CHECK_EQ_INT(ss_sim_body_nface(sim), g.nface);
      for (int f = 1; f <= 10; f++) {
        fx_pose(&g, f / 30.0, pose);
        ss_sim_step(sim, pose, 0.0, NULL, NULL, 0);
      }
      out[run] = malloc(3 * (size_t)g.nvert * sizeof(double));
      memcpy(out[run], ss_sim_skin_positions(sim), 3 * (size_t)g.nvert * sizeof(double));
    }
    ss_sim_destroy(sim);
    size_t bytes = 3 * (size_t)g.nvert * sizeof(double);
    CHECK_MSG(memcmp(out[0], out[1], bytes) == 0, "solver %d not deterministic", solver);
    CHECK_MSG(memcmp(out[0], out[2], bytes) == 0, "solver %d: a reset run differs", solver);
    for (int r = 0; r < 3; r++) free(out[r]);
  }
  free(pose);
  fx_free(&g);
}

/* Regression (issue 14, found by fuzzing): the body jumping by a huge finite
 * distance over a tiny legal dt gave the vertices that follow the body
 * (outside the face mask, and the pinned border) v = jump / h = +-inf with
 * SS_OK. Now the step is refused, naming the problem, with the state untouched;
 * a huge but representable jump keeps every velocity finite. */
static void test_jump_velocity_overflow(void) {
  fx_mesh g = fx_grid(6, 6, 1.0, 1.0, 0.1);
  unsigned char *mask = calloc((size_t)g.nface, 1);
  for (int f = 0; f < g.nface / 2; f++) mask[f] = 1;
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  double *before = malloc(6 * (size_t)g.nvert * sizeof(double));
  for (int solver = 0; solver < 2; solver++) {
    ss_sim_settings set = ss_sim_default_settings();
    set.solver = solver;
    set.face_mask = mask;
    ss_sim *sim = make_sim(&g, &set);
    if (!sim) continue;
    size_t n3 = 3 * (size_t)g.nvert;
    memcpy(before, ss_sim_skin_positions(sim), n3 * sizeof(double));
    memcpy(before + n3, ss_sim_skin_velocities(sim), n3 * sizeof(double));
    for (size_t i = 0; i < n3; i++) pose[i] = g.pos[i] + (i % 3 == 0 ? 1e300 : 0.0);
    char err[256] = "";
    ss_sim_stats st;
    int status = ss_sim_step(sim, pose, 1e-12, &st, err, sizeof err);
    CHECK_MSG(status == SS_E_NONFINITE, "huge jump over a tiny dt: status %d", status);
    CHECK_MSG(strstr(err, "velocity overflows") != NULL, "message: %s", err);
    CHECK(memcmp(before, ss_sim_skin_positions(sim), n3 * sizeof(double)) == 0);
    CHECK(memcmp(before + n3, ss_sim_skin_velocities(sim), n3 * sizeof(double)) == 0);
    /* a move that overflows by itself, over a long dt */
    for (size_t i = 0; i < n3; i++) pose[i] = g.pos[i] + (i % 3 == 0 ? -1.7e308 : 0.0);
    CHECK_EQ_INT(ss_sim_step(sim, pose, 100.0, &st, err, sizeof err), SS_OK);
    CHECK(all_finite(ss_sim_skin_positions(sim), 3 * g.nvert));
    CHECK(all_finite(ss_sim_skin_velocities(sim), 3 * g.nvert));
    for (size_t i = 0; i < n3; i++) pose[i] = g.pos[i] + (i % 3 == 0 ? 1.7e308 : 0.0);
    status = ss_sim_step(sim, pose, 100.0, &st, err, sizeof err);
    CHECK_MSG(status == SS_E_NONFINITE, "a move beyond double range: status %d", status);
    for (size_t i = 0; i < n3; i++) pose[i] = g.pos[i];
    CHECK_EQ_INT(ss_sim_step(sim, pose, 100.0, &st, err, sizeof err), SS_OK);
    CHECK(all_finite(ss_sim_skin_positions(sim), 3 * g.nvert));
    /* huge but representable: accepted, every value finite */
    for (size_t i = 0; i < n3; i++) pose[i] = g.pos[i] + (i % 3 == 0 ? 1e290 : 0.0);
    CHECK_EQ_INT(ss_sim_step(sim, pose, 1e-12, &st, err, sizeof err), SS_OK);
    CHECK(all_finite(ss_sim_skin_positions(sim), 3 * g.nvert));
    CHECK(all_finite(ss_sim_skin_velocities(sim), 3 * g.nvert));
    ss_sim_destroy(sim);
  }
  free(before);
  free(pose);
  free(mask);
  fx_free(&g);
}

int main(void) {
  test_rest_stays_put();
  test_stretched_returns();
  test_membrane_moduli(1.0); /* the Stable Neo-Hookean membrane: young and poisson */
  test_membrane_moduli(ss_sim_default_settings().compression);
  test_solvers_agree();
  test_face_mask();
  test_gravity_sag();
  test_coarse_skin();
  test_bending_cantilever();
  test_slide();
  test_measure_anchors();
  test_bad_input();
  test_warnings();
  test_small_meshes();
  test_violent_motion();
  test_determinism();
  test_jump_velocity_overflow();
  return ss_test_finish("test_sim");
}
