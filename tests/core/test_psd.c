/* Tests of the small symmetric eigen-solver and the PSD projection
 * (src/core/psd.c): matrices with a known spectrum built from random
 * orthogonal bases, reconstruction, orthonormality, clamping, idempotence,
 * determinism. */
#include <string.h>

#include "energy.h"
#include "ss_test.h"

#define NMAX 12

/* A random orthogonal matrix (row-major, n x n) by Gram-Schmidt. */
static void random_orthogonal(int n, unsigned long long *rng, double *q) {
  for (int col = 0; col < n; col++) {
    for (;;) {
      double v[NMAX];
      for (int i = 0; i < n; i++) v[i] = 2.0 * ss_test_rand(rng) - 1.0;
      for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < col; k++) {
          double d = 0.0;
          for (int i = 0; i < n; i++) d += v[i] * q[i * n + k];
          for (int i = 0; i < n; i++) v[i] -= d * q[i * n + k];
        }
      double len = 0.0;
      for (int i = 0; i < n; i++) len += v[i] * v[i];
      len = sqrt(len);
      if (len < 1e-3) continue;
      for (int i = 0; i < n; i++) q[i * n + col] = v[i] / len;
      break;
    }
  }
}

/* m = Q diag(lambda) Q^T */
static void compose(int n, const double *q, const double *lambda, double *m) {
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      double s = 0.0;
      for (int k = 0; k < n; k++) s += q[i * n + k] * lambda[k] * q[j * n + k];
      m[i * n + j] = s;
    }
  for (int i = 0; i < n; i++) /* exactly symmetric, as element Hessians are */
    for (int j = 0; j < i; j++) m[i * n + j] = m[j * n + i];
}

static double frob(int n, const double *a) {
  double s = 0.0;
  for (int i = 0; i < n * n; i++) s += a[i] * a[i];
  return sqrt(s);
}

static double max_diff(int n, const double *a, const double *b) {
  double d = 0.0;
  for (int i = 0; i < n * n; i++) d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double min_eigenvalue(int n, const double *m) {
  double ev[NMAX], vec[NMAX * NMAX];
  ss_sym_eigen(m, n, ev, vec);
  double lo = ev[0];
  for (int i = 1; i < n; i++) lo = fmin(lo, ev[i]);
  return lo;
}

static void test_known_spectrum(unsigned long long *rng) {
  for (int trial = 0; trial < 200; trial++) {
    int n = 1 + trial % NMAX;
    double q[NMAX * NMAX], lambda[NMAX], m[NMAX * NMAX];
    random_orthogonal(n, rng, q);
    for (int k = 0; k < n; k++) lambda[k] = 10.0 * (ss_test_rand(rng) - 0.5);
    if (trial % 5 == 0 && n > 2) lambda[1] = lambda[0]; /* repeated eigenvalue */
    compose(n, q, lambda, m);

    double ev[NMAX], vec[NMAX * NMAX], rec[NMAX * NMAX];
    ss_sym_eigen(m, n, ev, vec);
    /* Eigenvalues match the known ones. */
    double sorted_ev[NMAX], sorted_lambda[NMAX];
    memcpy(sorted_ev, ev, sizeof(double) * (size_t)n);
    memcpy(sorted_lambda, lambda, sizeof(double) * (size_t)n);
    qsort(sorted_ev, (size_t)n, sizeof(double), cmp_double);
    qsort(sorted_lambda, (size_t)n, sizeof(double), cmp_double);
    for (int k = 0; k < n; k++) CHECK_NEAR(sorted_ev[k], sorted_lambda[k], 1e-12 * 10.0);
    /* Eigenvectors orthonormal and M = V diag V^T. */
    double worst = 0.0;
    for (int a = 0; a < n; a++)
      for (int b = 0; b < n; b++) {
        double d = 0.0;
        for (int i = 0; i < n; i++) d += vec[i * n + a] * vec[i * n + b];
        worst = fmax(worst, fabs(d - (a == b ? 1.0 : 0.0)));
      }
    CHECK_MSG(worst < 1e-13, "n %d: V^T V - I = %g", n, worst);
    compose(n, vec, ev, rec);
    CHECK_MSG(max_diff(n, rec, m) < 1e-13 * (1.0 + frob(n, m)), "n %d: reconstruction %g", n,
              max_diff(n, rec, m));

    /* Projection: equals Q max(lambda, 0) Q^T, PSD, idempotent. */
    double clamped[NMAX], expect[NMAX * NMAX], proj[NMAX * NMAX], again[NMAX * NMAX];
    for (int k = 0; k < n; k++) clamped[k] = fmax(lambda[k], 0.0);
    compose(n, q, clamped, expect);
    memcpy(proj, m, sizeof(double) * (size_t)(n * n));
    ss_project_psd(proj, n);
    CHECK_MSG(max_diff(n, proj, expect) < 1e-12 * (1.0 + frob(n, m)), "n %d: projection off by %g",
              n, max_diff(n, proj, expect));
    CHECK(min_eigenvalue(n, proj) >= -1e-12 * frob(n, proj));
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) CHECK(proj[i * n + j] == proj[j * n + i]);
    memcpy(again, proj, sizeof(double) * (size_t)(n * n));
    ss_project_psd(again, n);
    CHECK(max_diff(n, again, proj) < 1e-12 * (1.0 + frob(n, proj)));
  }
}

/* A strictly positive definite matrix is left bit-for-bit unchanged. */
static void test_pd_unchanged(unsigned long long *rng) {
  for (int n = 1; n <= NMAX; n++) {
    double q[NMAX * NMAX], lambda[NMAX], m[NMAX * NMAX], p[NMAX * NMAX];
    random_orthogonal(n, rng, q);
    for (int k = 0; k < n; k++) lambda[k] = 0.1 + ss_test_rand(rng);
    compose(n, q, lambda, m);
    memcpy(p, m, sizeof(double) * (size_t)(n * n));
    ss_project_psd(p, n);
    CHECK(memcmp(p, m, sizeof(double) * (size_t)(n * n)) == 0);
  }
}

/* Negative definite goes to zero; a diagonal matrix is handled exactly. */
static void test_simple_cases(void) {
  double m[9] = {-1.0, 0.2, 0.0, 0.2, -2.0, 0.1, 0.0, 0.1, -3.0};
  ss_project_psd(m, 3);
  for (int i = 0; i < 9; i++) CHECK_NEAR(m[i], 0.0, 1e-15);

  double d[16] = {3.0, 0, 0, 0, 0, -1.0, 0, 0, 0, 0, 0.0, 0, 0, 0, 0, 2.0};
  ss_project_psd(d, 4);
  double expect[16] = {3.0, 0, 0, 0, 0, 0.0, 0, 0, 0, 0, 0.0, 0, 0, 0, 0, 2.0};
  for (int i = 0; i < 16; i++) CHECK_NEAR(d[i], expect[i], 0.0);

  /* 2x2 with known eigen-pairs: [[1, 2], [2, 1]] -> 3, -1; projection
   * 3 * (1, 1)(1, 1)^T / 2. */
  double t[4] = {1.0, 2.0, 2.0, 1.0};
  ss_project_psd(t, 2);
  for (int i = 0; i < 4; i++) CHECK_NEAR(t[i], 1.5, 1e-14);
}

/* Same input, same bits. */
static void test_determinism(unsigned long long *rng) {
  double m[144], a[144], b[144];
  for (int i = 0; i < 12; i++)
    for (int j = i; j < 12; j++) m[i * 12 + j] = m[j * 12 + i] = 2.0 * ss_test_rand(rng) - 1.0;
  memcpy(a, m, sizeof m);
  memcpy(b, m, sizeof m);
  ss_project_psd(a, 12);
  ss_project_psd(b, 12);
  CHECK(memcmp(a, b, sizeof a) == 0);
  CHECK(min_eigenvalue(12, a) >= -1e-12 * frob(12, a));
  CHECK(max_diff(12, a, m) > 1e-3); /* a random matrix is indefinite: it did change */
}

int main(void) {
  unsigned long long rng = 0x9e3779b97f4a7c15ULL;
  test_known_spectrum(&rng);
  test_pd_unchanged(&rng);
  test_simple_cases();
  test_determinism(&rng);
  return ss_test_finish("test_psd");
}
