/* Tests of the dihedral hinge (src/core/hinge.c): the signed angle on known
 * configurations (flat, 90 degree folds of both signs, a full sweep including
 * angles near +-pi), rigid-motion invariance, central finite differences of
 * the energy and of the angle against the analytic gradient, the
 * Gauss-Newton Hessian against differences of the gradient where it is exact
 * (theta = theta0), PSD-ness, and degenerate wings. */
#include <string.h>

#include "energy.h"
#include "ss_test.h"

static const double PI = 3.14159265358979323846;

/* Hinge along the x axis from (0,0,0) to (1,0,0); wing A in the xy-plane
 * (normal +z); wing B turned by phi about the edge (phi > 0: down, away from
 * the normal, convex). */
static void make_hinge(double phi, double x[12]) {
  double h[12] = {0, 0, 0, 1, 0, 0, 0.3, 1, 0, 0.6, -cos(phi), -sin(phi)};
  memcpy(x, h, sizeof h);
}

static void random_rigid(unsigned long long *rng, const double *in, double *out, int npts) {
  double r[9];
  ss_test_random_rotation(rng, r);
  double t[3] = {ss_test_randu(rng), ss_test_randu(rng), ss_test_randu(rng)};
  for (int p = 0; p < npts; p++)
    for (int i = 0; i < 3; i++)
      out[3 * p + i] = r[3 * i] * in[3 * p] + r[3 * i + 1] * in[3 * p + 1] +
                       r[3 * i + 2] * in[3 * p + 2] + t[i];
}

static void test_known_angles(unsigned long long *rng) {
  double x[12];
  make_hinge(0.0, x);
  CHECK_NEAR(ss_hinge_angle(x), 0.0, 1e-15);
  make_hinge(PI / 2, x);
  CHECK_NEAR(ss_hinge_angle(x), PI / 2, 1e-14);
  make_hinge(-PI / 2, x);
  CHECK_NEAR(ss_hinge_angle(x), -PI / 2, 1e-14);
  /* An explicit valley: both wings lifted towards +z (their normal side). */
  double valley[12] = {0, 0, 0, 1, 0, 0, 0.5, 1, 1, 0.5, -1, 1};
  CHECK_NEAR(ss_hinge_angle(valley), -PI / 2, 1e-14);
  /* A sweep, near +-pi included, in random rigid placements. */
  for (int k = -100; k <= 100; k++) {
    double phi = k / 100.0 * (PI - 1e-9);
    double y[12];
    make_hinge(phi, x);
    random_rigid(rng, x, y, 4);
    CHECK_NEAR(ss_hinge_angle(y), phi, 1e-12);
  }
  /* Folded flat (theta = pi exactly is representable as +-pi). */
  make_hinge(PI, x);
  CHECK_NEAR(fabs(ss_hinge_angle(x)), PI, 1e-12);
}

/* Central differences of the energy against the gradient. */
static void fd_gradient(const double x0[12], double theta0, double weight, double h_step,
                        double tol, const char *what) {
  double g[12], x[12], worst = 0.0, scale = 0.0;
  ss_hinge_eval(x0, theta0, weight, g, NULL);
  for (int k = 0; k < 12; k++) {
    memcpy(x, x0, sizeof x);
    x[k] += h_step;
    double ep = ss_hinge_eval(x, theta0, weight, NULL, NULL);
    x[k] = x0[k] - h_step;
    double em = ss_hinge_eval(x, theta0, weight, NULL, NULL);
    worst = fmax(worst, fabs((ep - em) / (2 * h_step) - g[k]));
    scale = fmax(scale, fabs(g[k]));
  }
  CHECK_MSG(worst <= tol * (scale + weight), "%s: gradient vs FD %g (scale %g)", what, worst, scale);
}

static void random_hinge(unsigned long long *rng, double x[12]) {
  for (;;) {
    for (int i = 0; i < 12; i++) x[i] = ss_test_randu(rng);
    /* Keep wings away from degenerate for the derivative checks. */
    double e[3], a[3], b[3], na[3], nb[3];
    for (int i = 0; i < 3; i++) e[i] = x[3 + i] - x[i], a[i] = x[6 + i] - x[i], b[i] = x[9 + i] - x[i];
    na[0] = e[1] * a[2] - e[2] * a[1], na[1] = e[2] * a[0] - e[0] * a[2], na[2] = e[0] * a[1] - e[1] * a[0];
    nb[0] = e[1] * b[2] - e[2] * b[1], nb[1] = e[2] * b[0] - e[0] * b[2], nb[2] = e[0] * b[1] - e[1] * b[0];
    double el = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    double ha = sqrt(na[0] * na[0] + na[1] * na[1] + na[2] * na[2]) / el;
    double hb = sqrt(nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2]) / el;
    if (el > 0.3 && ha > 0.2 && hb > 0.2) return;
  }
}

static void test_derivatives(unsigned long long *rng) {
  for (int trial = 0; trial < 200; trial++) {
    double x[12], g[12], h[144];
    random_hinge(rng, x);
    double theta = ss_hinge_angle(x);
    double weight = 0.5 + ss_test_rand(rng);
    double theta0 = ss_test_randu(rng) * 3.0;
    char what[64];
    snprintf(what, sizeof what, "random #%d", trial);
    fd_gradient(x, theta0, weight, 1e-6, 1e-7, what);

    /* At theta0 = theta the Gauss-Newton Hessian is the exact one. */
    double x2[12];
    ss_hinge_eval(x, theta, weight, g, h);
    for (int i = 0; i < 12; i++) CHECK_NEAR(g[i], 0.0, 0.0);
    double worst = 0.0, scale = 0.0;
    for (int k = 0; k < 12; k++) {
      double gp[12], gm[12];
      memcpy(x2, x, sizeof x2);
      x2[k] += 1e-6;
      ss_hinge_eval(x2, theta, weight, gp, NULL);
      x2[k] = x[k] - 1e-6;
      ss_hinge_eval(x2, theta, weight, gm, NULL);
      for (int i = 0; i < 12; i++) worst = fmax(worst, fabs((gp[i] - gm[i]) / 2e-6 - h[12 * i + k]));
    }
    for (int i = 0; i < 144; i++) scale = fmax(scale, fabs(h[i]));
    CHECK_MSG(worst <= 1e-6 * scale, "%s: Hessian vs FD at theta0 = theta: %g of %g", what, worst, scale);

    /* PSD and symmetric (rank one, 2 weight |grad theta|^2 on its one mode). */
    ss_hinge_eval(x, theta0, weight, g, h);
    double ev[12], vec[144], lo = 1e300;
    ss_sym_eigen(h, 12, ev, vec);
    for (int i = 0; i < 12; i++) lo = fmin(lo, ev[i]);
    CHECK(lo >= -1e-9 * scale);
    for (int i = 0; i < 12; i++)
      for (int j = 0; j < 12; j++) CHECK(h[12 * i + j] == h[12 * j + i]);

    /* Rigid invariance. */
    double y[12];
    random_rigid(rng, x, y, 4);
    CHECK_NEAR(ss_hinge_eval(y, theta0, weight, NULL, NULL), ss_hinge_eval(x, theta0, weight, NULL, NULL),
               1e-10);
  }
}

/* Near +-pi: finite, continuous across the branch cut, derivatives right. */
static void test_near_pi(void) {
  double x[12], g[12], h[144];
  /* theta0 just below pi, theta just past -pi: the wrapped difference is small. */
  make_hinge(-(PI - 0.01), x);
  double e = ss_hinge_eval(x, PI - 0.01, 2.0, g, h);
  CHECK_NEAR(e, 2.0 * 0.02 * 0.02, 1e-12);
  fd_gradient(x, PI - 0.01, 2.0, 1e-7, 1e-6, "across the branch cut");
  /* The mirror case: theta just below pi, theta0 just past -pi. */
  double m[12];
  make_hinge(PI - 0.01, m);
  CHECK_NEAR(ss_hinge_eval(m, -(PI - 0.01), 2.0, NULL, NULL), 2.0 * 0.02 * 0.02, 1e-12);
  fd_gradient(m, -(PI - 0.01), 2.0, 1e-7, 1e-6, "across the branch cut, mirrored");
  for (int i = 0; i < 12; i++) CHECK(isfinite(g[i]));
  for (int i = 0; i < 144; i++) CHECK(isfinite(h[i]));
  /* Energy continuous across the cut: equal on both sides of theta = pi. */
  double a[12], b[12];
  make_hinge(PI - 1e-9, a);
  make_hinge(-(PI - 1e-9), b);
  CHECK_NEAR(ss_hinge_eval(a, 0.5, 1.0, NULL, NULL), ss_hinge_eval(b, 0.5, 1.0, NULL, NULL), 1e-7);
  CHECK_NEAR(ss_hinge_eval(a, 0.5, 1.0, NULL, NULL), (PI - 0.5) * (PI - 0.5), 1e-7);
}

/* Zero-area wings and a zero-length edge: finite energy, zero derivatives. */
static void test_degenerate(void) {
  double cases[3][12] = {
      {0, 0, 0, 1, 0, 0, 0.5, 0, 0, 0.5, -1, 0.2},  /* o0 on the edge line */
      {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 2.0, 0, 0},     /* o1 on the edge line */
      {0, 0, 0, 0, 0, 0, 0.5, 1, 0, 0.5, -1, 0.2}}; /* edge of length 0 */
  for (int c = 0; c < 3; c++) {
    double g[12], h[144];
    double e = ss_hinge_eval(cases[c], 0.3, 1.5, g, h);
    CHECK(isfinite(e));
    for (int i = 0; i < 12; i++) CHECK_NEAR(g[i], 0.0, 0.0);
    for (int i = 0; i < 144; i++) CHECK_NEAR(h[i], 0.0, 0.0);
  }
  /* Nearly degenerate (height 1e-9 of the edge): large but finite. */
  double x[12] = {0, 0, 0, 1, 0, 0, 0.5, 1e-9, 1e-10, 0.5, -1, 0.2}, g[12];
  double e = ss_hinge_eval(x, 0.0, 1.0, g, NULL);
  CHECK(isfinite(e));
  for (int i = 0; i < 12; i++) CHECK(isfinite(g[i]));
}

int main(void) {
  unsigned long long rng = 0xfeedfacecafebeefULL;
  test_known_angles(&rng);
  test_derivatives(&rng);
  test_near_pi();
  test_degenerate();
  return ss_test_finish("test_energy_hinge");
}
