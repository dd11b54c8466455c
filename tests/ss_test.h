/* A tiny test harness for skin_sim's C tests (in the manner of Box2D's
 * ENSURE macros). A failed check prints where and why and counts as a failure;
 * the test's main returns ss_test_finish(), non-zero if anything failed.
 * A test that cannot run here (missing data) returns SS_TEST_SKIP (77). */
#ifndef SKIN_SIM_TEST_H
#define SKIN_SIM_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

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

#endif
