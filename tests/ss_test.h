/* A tiny test harness for skin_sim's C tests (in the manner of Box2D's
 * ENSURE macros). A failed check prints where and why and counts as a failure;
 * the test's main returns ss_test_finish(), non-zero if anything failed.
 * A test that cannot run here (missing data) returns SS_TEST_SKIP (77). */
#ifndef SKIN_SIM_TEST_H
#define SKIN_SIM_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define SS_TEST_SKIP 77

static int ss_test_failures = 0;
static int ss_test_checks = 0;

#define CHECK(cond)                                                                     \
  do {                                                                                  \
    ss_test_checks++;                                                                   \
    if (!(cond)) {                                                                      \
      ss_test_failures++;                                                               \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);          \
    }                                                                                   \
  } while (0)

#define CHECK_MSG(cond, ...)                                                            \
  do {                                                                                  \
    ss_test_checks++;                                                                   \
    if (!(cond)) {                                                                      \
      ss_test_failures++;                                                               \
      fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond);          \
      fprintf(stderr, __VA_ARGS__);                                                     \
      fputc('\n', stderr);                                                              \
    }                                                                                   \
  } while (0)

/* |a - b| <= tol, and both finite. */
#define CHECK_NEAR(a, b, tol)                                                           \
  do {                                                                                  \
    double ss_a_ = (double)(a), ss_b_ = (double)(b), ss_t_ = (double)(tol);             \
    ss_test_checks++;                                                                   \
    if (!(isfinite(ss_a_) && isfinite(ss_b_) && fabs(ss_a_ - ss_b_) <= ss_t_)) {        \
      ss_test_failures++;                                                               \
      fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.17g, %s = %.17g, tol %g\n",     \
              __FILE__, __LINE__, #a, ss_a_, #b, ss_b_, ss_t_);                         \
    }                                                                                   \
  } while (0)

#define CHECK_EQ_INT(a, b)                                                              \
  do {                                                                                  \
    long long ss_a_ = (long long)(a), ss_b_ = (long long)(b);                           \
    ss_test_checks++;                                                                   \
    if (ss_a_ != ss_b_) {                                                               \
      ss_test_failures++;                                                               \
      fprintf(stderr, "%s:%d: CHECK_EQ failed: %s = %lld, %s = %lld\n", __FILE__,       \
              __LINE__, #a, ss_a_, #b, ss_b_);                                          \
    }                                                                                   \
  } while (0)

static inline int ss_test_finish(const char *name) {
  if (ss_test_failures) {
    fprintf(stderr, "%s: %d of %d checks failed\n", name, ss_test_failures, ss_test_checks);
    return 1;
  }
  printf("%s: all %d checks passed\n", name, ss_test_checks);
  return 0;
}

/* Deterministic random numbers for tests (xorshift64*). */
static inline double ss_test_rand(unsigned long long *state) {
  unsigned long long x = *state;
  x ^= x >> 12;
  x ^= x << 25;
  x ^= x >> 27;
  *state = x;
  return (double)((x * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform in [-1, 1), from ss_test_rand. */
static inline double ss_test_randu(unsigned long long *state) {
  return 2.0 * ss_test_rand(state) - 1.0;
}

/* A random rotation matrix (row-major) from a random unit quaternion. */
static inline void ss_test_random_rotation(unsigned long long *rng, double r[9]) {
  double q[4], len = 0.0;
  do {
    len = 0.0;
    for (int i = 0; i < 4; i++) q[i] = ss_test_randu(rng), len += q[i] * q[i];
  } while (len < 0.1 || len > 1.0);
  len = sqrt(len);
  double w = q[0] / len, x = q[1] / len, y = q[2] / len, z = q[3] / len;
  double m[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                 2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                 2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
  for (int i = 0; i < 9; i++) r[i] = m[i];
}

/* Monotonic seconds, for the timings tests print (and the few bounds they set). */
static inline double ss_test_now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* qsort's comparison of doubles (for medians). */
static inline int ss_test_cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The largest distance between the n points of a and of b (xyz interleaved). */
static inline double ss_test_max_dist(const double *a, const double *b, int n) {
  double m = 0.0;
  for (int v = 0; v < n; v++) {
    double d = 0.0;
    for (int i = 0; i < 3; i++) d += (a[3 * v + i] - b[3 * v + i]) * (a[3 * v + i] - b[3 * v + i]);
    m = fmax(m, sqrt(d));
  }
  return m;
}

/* Removes a test's temporary folder (from mkdtemp) and what is in it; says so
 * when it cannot (not a failure of the test). */
static inline void ss_test_remove_dir(const char *dir) {
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
}

#endif
