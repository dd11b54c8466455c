/* Tests of the Stable Neo-Hookean membrane (src/core/membrane.c): rest state
 * stress free, closed forms under uniform scaling, plane-stress Young's
 * modulus and Poisson ratio recovered from small uniaxial stretch, central
 * finite differences (energy -> gradient, gradient -> exact Hessian) on random,
 * near-degenerate, flipped, stretched and compressed triangles, the closed-form
 * PSD projection checked against a numerical eigen-projection in F-space,
 * rigid-motion invariance, and finiteness on degenerate triangles. */
#include <stdio.h>
#include <string.h>

#include "energy.h"
#include "isa.h"
#include "ss_test.h"

static const double MU = 3.0, LAM = 7.0;

/* The membrane the generic checks run on: 1 the Stable Neo-Hookean one, then
 * the compression-soft one (main runs them for both). */
static double COMP = 1.0;

static double norm_inf(const double *a, int n) {
  double m = 0.0;
  for (int i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
  return m;
}

static int all_finite(const double *a, int n) {
  for (int i = 0; i < n; i++)
    if (!isfinite(a[i])) return 0;
  return 1;
}

static void rotate_points(const double r[9], const double t[3], const double *in, double *out,
                          int npts) {
  for (int p = 0; p < npts; p++)
    for (int i = 0; i < 3; i++)
      out[3 * p + i] = r[3 * i] * in[3 * p] + r[3 * i + 1] * in[3 * p + 1] +
                       r[3 * i + 2] * in[3 * p + 2] + t[i];
}

static double min_eigenvalue(const double *m, int n) {
  double ev[12], vec[144];
  ss_sym_eigen(m, n, ev, vec);
  double lo = ev[0];
  for (int i = 1; i < n; i++) lo = fmin(lo, ev[i]);
  return lo;
}

/* A random, reasonably shaped rest triangle, anywhere, any orientation. */
static void random_rest(unsigned long long *rng, double rest[9]) {
  for (;;) {
    for (int i = 0; i < 9; i++) rest[i] = ss_test_randu(rng);
    double dm[4], area;
    if (ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area) == 0 && area > 0.1) return;
  }
}

/* Kinds of current configuration, relative to the rest triangle. */
enum { RANDOM, NEAR_DEGENERATE, FLIPPED, STRETCH10, COMPRESS01, NKINDS };
static const char *kind_name[NKINDS] = {"random", "near-degenerate", "flipped", "stretched x10",
                                        "compressed x0.1"};

/* Builds a current configuration of the given kind: a 2D map of the rest
 * triangle's own frame, then a random rotation and translation. */
static void make_current(unsigned long long *rng, const double rest[9], int kind, double x[9]) {
  double dm[4], area;
  ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area);
  /* Rest 2D coordinates: (0,0), Dm column 0, Dm column 1 (Dm = inverse of dm_inv). */
  double det = dm[0] * dm[3] - dm[1] * dm[2];
  double dmat[4] = {dm[3] / det, -dm[1] / det, -dm[2] / det, dm[0] / det};
  double p2[3][2] = {{0, 0}, {dmat[0], dmat[2]}, {dmat[1], dmat[3]}};
  double a[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 0}}; /* 3x2 map, plus out-of-plane below */
  double local[9];
  switch (kind) {
  case RANDOM:
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 2; j++) a[i][j] += 0.5 * ss_test_randu(rng);
    break;
  case NEAR_DEGENERATE: break;
  case FLIPPED: a[1][1] = -0.8, a[0][1] = 0.3; break;
  case STRETCH10: a[0][0] = 10.0, a[1][1] = 9.0, a[2][0] = 1.0; break;
  case COMPRESS01: a[0][0] = 0.1, a[1][1] = 0.12, a[0][1] = 0.02; break;
  }
  for (int v = 0; v < 3; v++)
    for (int i = 0; i < 3; i++) local[3 * v + i] = a[i][0] * p2[v][0] + a[i][1] * p2[v][1];
  if (kind == NEAR_DEGENERATE) {
    /* Vertex 2 moved onto the line x0 x1, then lifted by an area ratio 1e-8. */
    double e1[2] = {p2[1][0], p2[1][1]};
    double len2 = e1[0] * e1[0] + e1[1] * e1[1];
    double t = (p2[2][0] * e1[0] + p2[2][1] * e1[1]) / len2;
    double rest_h = fabs(e1[0] * p2[2][1] - e1[1] * p2[2][0]) / sqrt(len2);
    local[6] = t * e1[0] - 1e-8 * rest_h * e1[1] / sqrt(len2);
    local[7] = t * e1[1] + 1e-8 * rest_h * e1[0] / sqrt(len2);
    local[8] = 0.0;
  }
  double r[9], tr[3] = {ss_test_randu(rng), ss_test_randu(rng), ss_test_randu(rng)};
  ss_test_random_rotation(rng, r);
  rotate_points(r, tr, local, x, 3);
}

static void test_lame(void) {
  double mu, lam;
  ss_membrane_lame(1000.0, 0.3, &mu, &lam);
  CHECK_NEAR(mu, 1000.0 / 2.6, 1e-9);
  CHECK_NEAR(lam, 1000.0 * 0.3 / 0.91 + 1000.0 / 2.6, 1e-9);
}

/* Zero energy and zero gradient at rest, in any orientation; and the exact
 * statement dPsi/dF = 0 at F = [I; 0]. */
static void test_rest_state(unsigned long long *rng) {
  for (int trial = 0; trial < 100; trial++) {
    double rest[9], dm[4], area, g[9], h[81];
    random_rest(rng, rest);
    CHECK_EQ_INT(ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area), 0);
    double e = ss_membrane_eval(rest, dm, area, MU, LAM, COMP, g, h);
    CHECK_NEAR(e, 0.0, 1e-13);
    CHECK_MSG(norm_inf(g, 9) < 1e-12, "trial %d: |grad| at rest = %g", trial, norm_inf(g, 9));
    /* Rest Hessian is PSD already: projected equals raw. */
    double hr[81];
    ss_membrane_eval_raw(rest, dm, area, MU, LAM, COMP, NULL, hr);
    double diff = 0.0;
    for (int i = 0; i < 81; i++) diff = fmax(diff, fabs(h[i] - hr[i]));
    CHECK_MSG(diff < 1e-10 * norm_inf(hr, 81), "rest Hessian projected vs raw %g", diff);
  }
  /* F = [I; 0] exactly: unit right triangle in the xy-plane, dm_inv = I. */
  double x[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, id[4] = {1, 0, 0, 1}, g[9];
  double e = ss_membrane_eval(x, id, 1.0, MU, LAM, COMP, g, NULL);
  CHECK_NEAR(e, 0.0, 0.0);
  for (int i = 0; i < 9; i++) CHECK_NEAR(g[i], 0.0, 1e-15);
  /* Without alpha = 1 + mu/lam (i.e. alpha = 1) the rest would be stressed:
   * the check above is not vacuous. The stress then is mu F: gradient -mu
   * at x0 along x. Reproduce it through lam -> infinity limit of alpha. */
  double g_big[9];
  ss_membrane_eval(x, id, 1.0, MU, 1e12, 1.0, g_big, NULL);
  CHECK_NEAR(g_big[0], 0.0, 1e-3);
}

/* Uniform scaling s: Psi = mu/2 (2 s^2 - 2) + lam/2 (s^2 - alpha)^2. */
static void test_uniform_scaling(unsigned long long *rng) {
  const double scales[] = {0.1, 0.5, 0.9, 1.0, 1.1, 2.0, 10.0};
  double alpha = 1.0 + MU / LAM;
  for (int trial = 0; trial < 10; trial++) {
    double rest[9], dm[4], area, x[9], r[9],
        t[3] = {ss_test_randu(rng), ss_test_randu(rng), ss_test_randu(rng)};
    random_rest(rng, rest);
    ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area);
    ss_test_random_rotation(rng, r);
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++) {
      double s = scales[k], scaled[9];
      for (int i = 0; i < 9; i++) scaled[i] = s * rest[i];
      rotate_points(r, t, scaled, x, 3);
      double psi = MU / 2 * (2 * s * s - 2) + LAM / 2 * (s * s - alpha) * (s * s - alpha) -
                   MU * MU / (2 * LAM); /* minus the rest offset, see membrane.c */
      double e = ss_membrane_eval(x, dm, area, MU, LAM, 1.0, NULL, NULL);
      CHECK_NEAR(e, area * psi, 1e-11 * (1.0 + fabs(area * psi)));
      /* the compression-soft membrane: 2 mu_s (s - 1)^2 + l_J/2 (s^2 - 1)^2 */
      const double c = 0.1, ms = s >= 1.0 ? MU : c * MU, lj = s * s >= 1.0 ? LAM - MU : c * (LAM - MU);
      const double psi_c = 2.0 * ms * (s - 1) * (s - 1) + 0.5 * lj * (s * s - 1) * (s * s - 1);
      double ec = ss_membrane_eval(x, dm, area, MU, LAM, c, NULL, NULL);
      CHECK_NEAR(ec, area * psi_c, 1e-11 * (1.0 + fabs(area * psi_c)));
    }
  }
}

/* Plane stress, uniaxial: stretch by 1 + eps along x, let y relax. Expect
 * lateral strain -nu eps and energy density E eps^2 / 2. */
static void test_plane_stress_moduli(void) {
  const double young = 50.0, nu = 0.35, eps = 1e-4;
  double mu, lam;
  ss_membrane_lame(young, nu, &mu, &lam);
  double id[4] = {1, 0, 0, 1};
  double sy = 1.0;
  for (int it = 0; it < 30; it++) { /* Newton on the y-coordinate of vertex 2 */
    double x[9] = {0, 0, 0, 1 + eps, 0, 0, 0, sy, 0}, g[9], h[81];
    ss_membrane_eval(x, id, 0.5, mu, lam, 1.0, g, h);
    sy -= g[7] / h[7 * 9 + 7];
  }
  double x[9] = {0, 0, 0, 1 + eps, 0, 0, 0, sy, 0};
  double e = ss_membrane_eval(x, id, 0.5, mu, lam, 1.0, NULL, NULL);
  CHECK_NEAR(-(sy - 1.0) / eps, nu, 1e-3);
  CHECK_NEAR(e / 0.5 / (0.5 * eps * eps), young, 1e-2 * young);
}

/* Central differences of energy -> gradient and of gradient -> raw Hessian. */
static void fd_check(const double x0[9], const double dm[4], double area, double h_step,
                     double grad_tol, double hess_tol, const char *what) {
  double g[9], hraw[81], x[9];
  ss_membrane_eval_raw(x0, dm, area, MU, LAM, COMP, g, hraw);
  double fd_g[9], fd_h[81];
  for (int k = 0; k < 9; k++) {
    double gp[9], gm[9];
    memcpy(x, x0, sizeof x);
    x[k] += h_step;
    double ep = ss_membrane_eval(x, dm, area, MU, LAM, COMP, gp, NULL);
    x[k] = x0[k] - h_step;
    double em = ss_membrane_eval(x, dm, area, MU, LAM, COMP, gm, NULL);
    fd_g[k] = (ep - em) / (2 * h_step);
    for (int i = 0; i < 9; i++) fd_h[9 * i + k] = (gp[i] - gm[i]) / (2 * h_step);
  }
  double gerr = 0.0, herr = 0.0;
  for (int i = 0; i < 9; i++) gerr = fmax(gerr, fabs(fd_g[i] - g[i]));
  for (int i = 0; i < 81; i++) herr = fmax(herr, fabs(fd_h[i] - hraw[i]));
  double gs = norm_inf(g, 9) + area * (MU + LAM), hs = norm_inf(hraw, 81);
  CHECK_MSG(gerr <= grad_tol * gs, "%s: gradient vs FD %g (scale %g)", what, gerr, gs);
  CHECK_MSG(herr <= hess_tol * hs, "%s: Hessian vs FD %g (scale %g)", what, herr, hs);
}

/* Projection done numerically in F-space for comparison: recover the 6x6
 * H_F from the raw 9x9 (H_x = D^T H_F D with D = d^T (x) I3 of full row rank),
 * project it with Jacobi, map back. */
static void reference_projection(const double hraw[81], const double dm_inv[4], double out[81]) {
  double d[3][2];
  for (int j = 0; j < 2; j++) d[1][j] = dm_inv[j], d[2][j] = dm_inv[2 + j], d[0][j] = -d[1][j] - d[2][j];
  /* M = (d^T d)^-1 d^T (2x3); H_F = (M (x) I3) H_x (M (x) I3)^T. */
  double dtd[4] = {0, 0, 0, 0};
  for (int a = 0; a < 3; a++)
    for (int j = 0; j < 2; j++)
      for (int l = 0; l < 2; l++) dtd[2 * j + l] += d[a][j] * d[a][l];
  double det = dtd[0] * dtd[3] - dtd[1] * dtd[2];
  double inv[4] = {dtd[3] / det, -dtd[1] / det, -dtd[2] / det, dtd[0] / det};
  double m[2][3];
  for (int j = 0; j < 2; j++)
    for (int a = 0; a < 3; a++) m[j][a] = inv[2 * j] * d[a][0] + inv[2 * j + 1] * d[a][1];
  double hf[36];
  for (int j = 0; j < 2; j++)
    for (int i = 0; i < 3; i++)
      for (int l = 0; l < 2; l++)
        for (int k = 0; k < 3; k++) {
          double s = 0.0;
          for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) s += m[j][a] * m[l][b] * hraw[9 * (3 * a + i) + 3 * b + k];
          hf[6 * (3 * j + i) + 3 * l + k] = s;
        }
  ss_project_psd(hf, 6);
  for (int a = 0; a < 3; a++)
    for (int i = 0; i < 3; i++)
      for (int b = 0; b < 3; b++)
        for (int k = 0; k < 3; k++) {
          double s = 0.0;
          for (int j = 0; j < 2; j++)
            for (int l = 0; l < 2; l++) s += d[a][j] * d[b][l] * hf[6 * (3 * j + i) + 3 * l + k];
          out[9 * (3 * a + i) + 3 * b + k] = s;
        }
}

static void test_derivatives(unsigned long long *rng) {
  for (int kind = 0; kind < NKINDS; kind++) {
    for (int trial = 0; trial < 20; trial++) {
      double rest[9], dm[4], area, x[9];
      random_rest(rng, rest);
      ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area);
      make_current(rng, rest, kind, x);
      /* Near-degenerate: J ~ 1e-8, so the step must be far below that scale. */
      double h_step = kind == NEAR_DEGENERATE ? 1e-12 : 1e-6;
      double gtol = kind == NEAR_DEGENERATE ? 1e-3 : 1e-7;
      double htol = kind == NEAR_DEGENERATE ? 1e-3 : 1e-6;
      char what[64];
      snprintf(what, sizeof what, "%s #%d", kind_name[kind], trial);
      fd_check(x, dm, area, h_step, gtol, htol, what);

      double g[9], h[81], g2[9], hraw[81], href[81];
      double e = ss_membrane_eval(x, dm, area, MU, LAM, COMP, g, h);
      double e2 = ss_membrane_eval(x, dm, area, MU, LAM, COMP, g2, NULL);
      CHECK(e == e2 && memcmp(g, g2, sizeof g) == 0); /* the fast path agrees bit for bit */
      CHECK(all_finite(h, 81));
      double hs = norm_inf(h, 81);
      CHECK_MSG(min_eigenvalue(h, 9) >= -1e-9 * hs, "%s: projected Hessian min eigenvalue %g", what,
                min_eigenvalue(h, 9));
      for (int i = 0; i < 9; i++)
        for (int j = 0; j < 9; j++) CHECK(h[9 * i + j] == h[9 * j + i]);
      ss_membrane_eval_raw(x, dm, area, MU, LAM, COMP, NULL, hraw);
      reference_projection(hraw, dm, href);
      double diff = 0.0;
      for (int i = 0; i < 81; i++) diff = fmax(diff, fabs(h[i] - href[i]));
      /* The reference works on the raw matrix, whose 1/J entries (~1e8 when
       * near-degenerate) bound its own accuracy. */
      double tol = 1e-8 * norm_inf(href, 81) + 1e-13 * norm_inf(hraw, 81);
      CHECK_MSG(diff <= tol, "%s: closed-form vs Jacobi projection %g of %g", what, diff,
                norm_inf(href, 81));
    }
  }
}

/* Near rest in pure stretch the exact Hessian is PSD: projection leaves it. */
static void test_projection_identity_when_psd(unsigned long long *rng) {
  int compared = 0;
  for (int trial = 0; trial < 20; trial++) {
    double rest[9], dm[4], area, x[9], r[9], t[3] = {0, 0, 0};
    random_rest(rng, rest);
    ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area);
    double s = 1.0 + 0.05 * ss_test_rand(rng), scaled[9];
    for (int i = 0; i < 9; i++) scaled[i] = s * rest[i];
    ss_test_random_rotation(rng, r);
    rotate_points(r, t, scaled, x, 3);
    double h[81], hraw[81];
    ss_membrane_eval(x, dm, area, MU, LAM, COMP, NULL, h);
    ss_membrane_eval_raw(x, dm, area, MU, LAM, COMP, NULL, hraw);
    double hs = norm_inf(hraw, 81);
    CHECK(min_eigenvalue(hraw, 9) >= -1e-12 * hs);
    double diff = 0.0;
    for (int i = 0; i < 81; i++) diff = fmax(diff, fabs(h[i] - hraw[i]));
    CHECK_MSG(diff <= 1e-10 * hs, "stretch %g: projected differs from PSD raw by %g", s, diff);
    compared++;
  }
  CHECK_EQ_INT(compared, 20);
  /* And in compression the exact Hessian is indefinite (the projection does work). */
  double x[9] = {0, 0, 0, 0.5, 0, 0, 0, 0.5, 0}, id[4] = {1, 0, 0, 1}, hraw[81];
  ss_membrane_eval_raw(x, id, 0.5, MU, LAM, COMP, NULL, hraw);
  CHECK(min_eigenvalue(hraw, 9) < -1e-3);
}

/* Rigid motions (rotation, translation, reflection) leave the energy unchanged
 * and transform the gradient and Hessian covariantly. */
static void test_rigid_invariance(unsigned long long *rng) {
  for (int trial = 0; trial < 50; trial++) {
    double rest[9], dm[4], area, x[9], y[9], r[9], t[3] = {ss_test_randu(rng), ss_test_randu(rng), ss_test_randu(rng)};
    random_rest(rng, rest);
    ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area);
    make_current(rng, rest, trial % 2 ? RANDOM : STRETCH10, x);
    ss_test_random_rotation(rng, r);
    if (trial % 3 == 0)
      for (int j = 0; j < 3; j++) r[j] = -r[j]; /* a reflection */
    rotate_points(r, t, x, y, 3);
    double gx[9], gy[9], hx[81], hy[81];
    double ex = ss_membrane_eval(x, dm, area, MU, LAM, COMP, gx, hx);
    double ey = ss_membrane_eval(y, dm, area, MU, LAM, COMP, gy, hy);
    CHECK_NEAR(ex, ey, 1e-10 * (1.0 + fabs(ex)));
    double zero[3] = {0, 0, 0}, rg[9];
    rotate_points(r, zero, gx, rg, 3);
    double gdiff = 0.0;
    for (int i = 0; i < 9; i++) gdiff = fmax(gdiff, fabs(rg[i] - gy[i]));
    CHECK(gdiff <= 1e-9 * (1.0 + norm_inf(gx, 9)));
    /* hy = R9 hx R9^T, R9 = blockdiag(R, R, R). */
    double hdiff = 0.0;
    for (int a = 0; a < 3; a++)
      for (int i = 0; i < 3; i++)
        for (int b = 0; b < 3; b++)
          for (int k = 0; k < 3; k++) {
            double s = 0.0;
            for (int p = 0; p < 3; p++)
              for (int q = 0; q < 3; q++) s += r[3 * i + p] * hx[9 * (3 * a + p) + 3 * b + q] * r[3 * k + q];
            hdiff = fmax(hdiff, fabs(s - hy[9 * (3 * a + i) + 3 * b + k]));
          }
    CHECK(hdiff <= 1e-9 * (1.0 + norm_inf(hx, 81)));
  }
}

/* Degenerate inputs: everything finite; a degenerate rest triangle is flagged. */
static void test_degenerate(unsigned long long *rng) {
  double rest[9], dm[4], area;
  random_rest(rng, rest);
  ss_membrane_rest(rest, rest + 3, rest + 6, dm, &area);
  double cases[4][9] = {
      {1, 2, 3, 1, 2, 3, 1, 2, 3},       /* all points equal */
      {0, 0, 0, 1, 1, 1, 2, 2, 2},       /* collinear */
      {0, 0, 0, 1, 0, 0, 0.5, 0, 0},     /* zero area, vertex 2 inside edge */
      {0, 0, 0, 0, 0, 0, 0, 1e-300, 0}}; /* almost all equal */
  for (int c = 0; c < 4; c++) {
    double g[9], h[81];
    double e = ss_membrane_eval(cases[c], dm, area, MU, LAM, COMP, g, h);
    CHECK_MSG(isfinite(e) && all_finite(g, 9) && all_finite(h, 81), "degenerate case %d", c);
    CHECK(min_eigenvalue(h, 9) >= -1e-9 * norm_inf(h, 81));
    /* A collapsed triangle holds energy (it resists losing its area). */
    CHECK(e > 0.0);
  }
  /* The gradient of a collapsed (but not coincident) triangle pushes it open:
   * a small step against it lowers the energy. */
  {
    double x[9] = {0, 0, 0, 1, 0, 0, 0.5, 1e-9, 0}, g[9], y[9];
    double e = ss_membrane_eval(x, dm, area, MU, LAM, COMP, g, NULL);
    for (int i = 0; i < 9; i++) y[i] = x[i] - 1e-4 * g[i];
    CHECK(ss_membrane_eval(y, dm, area, MU, LAM, COMP, NULL, NULL) < e);
  }
  /* Degenerate rest triangles. */
  double line[9] = {0, 0, 0, 1, 1, 0, 2, 2, 0}, point[9] = {1, 1, 1, 1, 1, 1, 1, 1, 1};
  double *bad[2] = {line, point};
  for (int b = 0; b < 2; b++) {
    double d[4] = {9, 9, 9, 9}, a = 9.0;
    CHECK_EQ_INT(ss_membrane_rest(bad[b], bad[b] + 3, bad[b] + 6, d, &a), -1);
    CHECK(d[0] == 1.0 && d[1] == 0.0 && d[2] == 0.0 && d[3] == 1.0 && a == 0.0);
    double x[9], g[9], h[81];
    for (int i = 0; i < 9; i++) x[i] = ss_test_randu(rng);
    CHECK_NEAR(ss_membrane_eval(x, d, a, MU, LAM, COMP, g, h), 0.0, 0.0);
    CHECK(norm_inf(g, 9) == 0.0 && norm_inf(h, 81) == 0.0);
  }
}

/* The stepping kernel (ss_membrane_eval_batch_isa) computes exactly what
 * ss_membrane_eval computes, bit for bit, for every kind of face (collapsed
 * ones included: J = 0 takes the fallback normal), at any count (a last,
 * partial block of lanes), from any starting block, and in each vector width
 * this CPU runs (isa.h). */
static void test_batch_bits(unsigned long long *rng) {
  enum { NF = 3 * SS_MEMBRANE_LANES + 5 };
  double x[3 * 3 * NF];
  ss_membrane_face rec[NF];
  double en[NF], gr[9 * NF], anchors[3 * NF];
  for (int q = 0; q < NF; q++) {
    double rest[9], cur[9];
    random_rest(rng, rest);
    make_current(rng, rest, q % NKINDS, cur);
    if (q % 11 == 7) /* collinear */
      for (int i = 0; i < 3; i++) cur[6 + i] = cur[i] + 0.5 * (cur[3 + i] - cur[i]);
    if (q % 13 == 9) /* coincident */
      for (int i = 0; i < 6; i++) cur[3 + i] = cur[i % 3];
    memcpy(x + 9 * q, cur, sizeof cur);
    for (int c = 0; c < 3; c++) rec[q].xo[c] = 9 * q + 3 * c;
    double area;
    ss_membrane_rest(rest, rest + 3, rest + 6, rec[q].dm_inv, &area);
    rec[q].area = area;
    rec[q].anchor = 3 * (NF - 1 - q); /* anchors in any order */
    rec[q].k_bary = q % 5 == 3 ? 0.0 : 10.0 * ss_test_rand(rng);
    for (int i = 0; i < 3; i++) anchors[rec[q].anchor + i] = cur[i] + 0.3 * ss_test_randu(rng);
  }
  for (int isa = 0; isa < SS_ISA_COUNT; isa++) {
    if (!ss_isa_supported(isa)) {
      printf("test_energy_membrane: the kernel in %s not run (not on this CPU)\n", ss_isa_name(isa));
      continue;
    }
    for (int start = 0; start <= SS_MEMBRANE_LANES; start += SS_MEMBRANE_LANES) {
      memset(en, 0, sizeof en);
      memset(gr, 0, sizeof gr);
      /* odd starts: with each face's barycenter spring (ss_bary_spring added) */
      const int bary = start != 0;
      ss_membrane_eval_batch_isa(isa, rec, start, NF, x, bary ? anchors : NULL, MU, LAM, COMP, en, gr, NULL,
                                 NULL);
      for (int q = start; q < NF; q++) {
        double g9[9];
        double e = ss_membrane_eval(x + 9 * q, rec[q].dm_inv, rec[q].area, MU, LAM, COMP, g9, NULL);
        if (bary) {
          double gb[3];
          e += ss_bary_spring(x + 9 * q, anchors + rec[q].anchor, rec[q].k_bary, gb);
          for (int r = 0; r < 9; r++) g9[r] += gb[r % 3];
        }
        CHECK_MSG(memcmp(&e, &en[q], sizeof e) == 0,
                  "batch energy of face %d differs in %s (%.17g vs %.17g)", q, ss_isa_name(isa), en[q], e);
        CHECK_MSG(memcmp(g9, gr + 9 * q, sizeof g9) == 0, "batch gradient of face %d differs in %s", q,
                  ss_isa_name(isa));
      }
    }
  }
}

/* The compression-soft membrane is the linear membrane of the same mu, lam in
 * tension and c times it in compression: equibiaxial strain of 1e-4 either
 * way against the Stable Neo-Hookean membrane. */
static void test_compression_moduli(void) {
  double id[4] = {1, 0, 0, 1};
  const double c = 0.1, eps = 1e-4;
  for (int sign = -1; sign <= 1; sign += 2) {
    const double s = 1.0 + sign * eps;
    double x[9] = {0, 0, 0, s, 0, 0, 0, s, 0};
    double snh = ss_membrane_eval(x, id, 0.5, MU, LAM, 1.0, NULL, NULL);
    double soft = ss_membrane_eval(x, id, 0.5, MU, LAM, c, NULL, NULL);
    CHECK_MSG(fabs(soft / snh - (sign > 0 ? 1.0 : c)) < 1e-3 * (sign > 0 ? 1.0 : c) + 2e-3 * c,
              "equibiaxial %+g: compression-soft / Stable Neo-Hookean energy %g", sign * eps, soft / snh);
  }
  /* the value 1 is the Stable Neo-Hookean membrane itself, bit for bit */
  double x[9] = {0.1, -0.2, 0.05, 1.3, 0.1, -0.1, 0.2, 0.7, 0.3}, g1[9], g2[9];
  CHECK(ss_membrane_eval(x, id, 0.5, MU, LAM, 1.0, g1, NULL) == ss_membrane_eval(x, id, 0.5, MU, LAM, 2.0, g2, NULL));
}

int main(void) {
  unsigned long long rng = 0x1234567887654321ULL;
  test_lame();
  test_rest_state(&rng);
  test_uniform_scaling(&rng);
  test_plane_stress_moduli();
  test_derivatives(&rng);
  test_projection_identity_when_psd(&rng);
  test_rigid_invariance(&rng);
  test_degenerate(&rng);
  test_batch_bits(&rng);
  test_compression_moduli();
  /* the generic checks again on the compression-soft membrane */
  COMP = 0.1;
  test_rest_state(&rng);
  test_derivatives(&rng);
  test_projection_identity_when_psd(&rng);
  test_rigid_invariance(&rng);
  test_degenerate(&rng);
  test_batch_bits(&rng);
  return ss_test_finish("test_energy_membrane");
}
