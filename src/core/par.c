/* Loops over fixed blocks with thread-count-independent sums (par.h). */
#include <stddef.h>

#include "par.h"

/* Block b of [0, n): terms [b B, min(n, (b + 1) B)), its sums at part + b k. */
static inline void run_block(int n, int k, ss_par_fn fn, void *ctx, double *part, int b) {
  const int i0 = b * SS_PAR_BLOCK, i1 = n - i0 < SS_PAR_BLOCK ? n : i0 + SS_PAR_BLOCK;
  fn(ctx, i0, i1, part + (size_t)b * k);
}

void ss_par_sum(int nthread, int n, int k, ss_par_fn fn, void *ctx, double *part, double *sums) {
  const int nb = ss_par_nblocks(n);
#ifdef _OPENMP
  if (nthread > 1 && nb > 1) {
#pragma omp parallel for schedule(static) num_threads(nthread)
    for (int b = 0; b < nb; b++) run_block(n, k, fn, ctx, part, b);
  } else
#else
  (void)nthread;
#endif
  {
    for (int b = 0; b < nb; b++) run_block(n, k, fn, ctx, part, b);
  }
  for (int j = 0; j < k; j++) {
    double s = 0.0;
    for (int b = 0; b < nb; b++) s += part[(size_t)b * k + j];
    sums[j] = s;
  }
}

/* ---- the solver's vector passes ---- */

typedef struct vec_ctx {
  double *out, *out2;
  const double *a, *b;
  double alpha;
} vec_ctx;

static void dot_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  double s = 0.0;
  for (int i = i0; i < i1; i++) s += v->a[i] * v->b[i];
  sums[0] = s;
}

double ss_par_dot(int nthread, double *part, int n, const double *a, const double *b) {
  vec_ctx v = {.a = a, .b = b};
  double s;
  ss_par_sum(nthread, n, 1, dot_block, &v, part, &s);
  return s;
}

static void axpy_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  (void)sums;
  for (int i = i0; i < i1; i++) v->out[i] = v->a[i] + v->alpha * v->b[i];
}

void ss_par_axpy(int nthread, double *part, int n, double *out, const double *x, double alpha,
                 const double *y) {
  vec_ctx v = {.out = out, .a = x, .b = y, .alpha = alpha};
  ss_par_sum(nthread, n, 0, axpy_block, &v, part, NULL);
}

static void copy_dot_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  double s = 0.0;
  for (int i = i0; i < i1; i++) {
    v->out[i] = v->a[i];
    s += v->b[i] * v->out[i];
  }
  sums[0] = s;
}

double ss_par_copy_dot(int nthread, double *part, int n, double *out, const double *src,
                       const double *z) {
  vec_ctx v = {.out = out, .a = src, .b = z};
  double s;
  ss_par_sum(nthread, n, 1, copy_dot_block, &v, part, &s);
  return s;
}

static void axpy_dot_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  double s = 0.0;
  if (v->b) {
    for (int i = i0; i < i1; i++) {
      v->out[i] += v->alpha * v->a[i];
      s += v->b[i] * v->out[i];
    }
    sums[0] = s;
  } else {
    for (int i = i0; i < i1; i++) v->out[i] += v->alpha * v->a[i];
  }
}

double ss_par_axpy_dot(int nthread, double *part, int n, double *out, double alpha, const double *y,
                       const double *z) {
  vec_ctx v = {.out = out, .a = y, .b = z, .alpha = alpha};
  double s = 0.0;
  ss_par_sum(nthread, n, z ? 1 : 0, axpy_dot_block, &v, part, &s);
  return s;
}

static void neg_axpy_dot_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  double s = 0.0;
  if (v->a) {
    for (int i = i0; i < i1; i++) {
      v->out[i] = -(v->out[i] + v->alpha * v->a[i]);
      s += v->out[i] * v->b[i];
    }
  } else {
    for (int i = i0; i < i1; i++) {
      v->out[i] = -v->out[i];
      s += v->out[i] * v->b[i];
    }
  }
  sums[0] = s;
}

double ss_par_neg_axpy_dot(int nthread, double *part, int n, double *out, double alpha,
                           const double *y, const double *z) {
  vec_ctx v = {.out = out, .a = y, .b = z, .alpha = alpha};
  double s;
  ss_par_sum(nthread, n, 1, neg_axpy_dot_block, &v, part, &s);
  return s;
}

static void norm2_dot_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  double aa = 0.0, ab = 0.0;
  for (int i = i0; i < i1; i++) {
    aa += v->a[i] * v->a[i];
    ab += v->a[i] * v->b[i];
  }
  sums[0] = aa, sums[1] = ab;
}

void ss_par_norm2_dot(int nthread, double *part, int n, const double *a, const double *b, double *aa,
                      double *ab) {
  vec_ctx v = {.a = a, .b = b};
  double s[2];
  ss_par_sum(nthread, n, 2, norm2_dot_block, &v, part, s);
  *aa = s[0], *ab = s[1];
}

static void pair_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  double sy = 0.0, ss = 0.0, yy = 0.0;
  for (int i = i0; i < i1; i++) {
    v->out[i] = v->a[i] - v->out[i];
    v->out2[i] = v->b[i] - v->out2[i];
    sy += v->out[i] * v->out2[i];
    ss += v->out[i] * v->out[i];
    yy += v->out2[i] * v->out2[i];
  }
  sums[0] = sy, sums[1] = ss, sums[2] = yy;
}

void ss_par_pair(int nthread, double *part, int n, double *s, const double *x, double *y,
                 const double *g, double sums[3]) {
  vec_ctx v = {.out = s, .out2 = y, .a = x, .b = g};
  ss_par_sum(nthread, n, 3, pair_block, &v, part, sums);
}
