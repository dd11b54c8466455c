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
  const double *a, *b, *c, *d;
  double alpha;
} vec_ctx;

/* Each block's sum in SS_PAR_LANES interleaved partial sums (par.h): the
 * lanes are independent chains that the compiler may keep in vectors of any
 * width, and one add no longer waits for the one before. */
enum { L = SS_PAR_LANES };

static void dot_block(void *ctx, int i0, int i1, double *sums) {
  const vec_ctx *v = ctx;
  const double *restrict a = v->a, *restrict b = v->b;
  double s[L] = {0};
  int i = i0;
  for (; i1 - i >= L; i += L)
    SS_PAR_LANE_LOOP
    for (int l = 0; l < L; l++) s[l] += a[i + l] * b[i + l];
  for (int l = 0; i < i1; i++, l++) s[l] += a[i] * b[i];
  sums[0] = ss_par_lanes_total(s);
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
  double *restrict out = v->out;
  const double *restrict a = v->a, *restrict b = v->b;
  double s[L] = {0};
  int i = i0;
  for (; i1 - i >= L; i += L)
    SS_PAR_LANE_LOOP
    for (int l = 0; l < L; l++) {
      out[i + l] = a[i + l];
      s[l] += b[i + l] * a[i + l];
    }
  for (int l = 0; i < i1; i++, l++) {
    out[i] = a[i];
    s[l] += b[i] * a[i];
  }
  sums[0] = ss_par_lanes_total(s);
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
  double *restrict out = v->out;
  const double *restrict a = v->a, *restrict b = v->b;
  const double alpha = v->alpha;
  if (b) {
    double s[L] = {0};
    int i = i0;
    for (; i1 - i >= L; i += L)
      SS_PAR_LANE_LOOP
      for (int l = 0; l < L; l++) {
        const double o = out[i + l] + alpha * a[i + l];
        out[i + l] = o;
        s[l] += b[i + l] * o;
      }
    for (int l = 0; i < i1; i++, l++) {
      const double o = out[i] + alpha * a[i];
      out[i] = o;
      s[l] += b[i] * o;
    }
    sums[0] = ss_par_lanes_total(s);
  } else {
    for (int i = i0; i < i1; i++) out[i] += alpha * a[i];
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
  double *restrict out = v->out;
  const double *restrict a = v->a, *restrict b = v->b;
  const double alpha = v->alpha;
  double s[L] = {0};
  int i = i0;
  if (a) {
    for (; i1 - i >= L; i += L)
      SS_PAR_LANE_LOOP
      for (int l = 0; l < L; l++) {
        const double o = -(out[i + l] + alpha * a[i + l]);
        out[i + l] = o;
        s[l] += o * b[i + l];
      }
    for (int l = 0; i < i1; i++, l++) {
      const double o = -(out[i] + alpha * a[i]);
      out[i] = o;
      s[l] += o * b[i];
    }
  } else {
    for (; i1 - i >= L; i += L)
      SS_PAR_LANE_LOOP
      for (int l = 0; l < L; l++) {
        const double o = -out[i + l];
        out[i + l] = o;
        s[l] += o * b[i + l];
      }
    for (int l = 0; i < i1; i++, l++) {
      const double o = -out[i];
      out[i] = o;
      s[l] += o * b[i];
    }
  }
  sums[0] = ss_par_lanes_total(s);
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
  const double *restrict a = v->a, *restrict b = v->b;
  double aa[L] = {0}, ab[L] = {0};
  int i = i0;
  for (; i1 - i >= L; i += L)
    SS_PAR_LANE_LOOP
    for (int l = 0; l < L; l++) {
      aa[l] += a[i + l] * a[i + l];
      ab[l] += a[i + l] * b[i + l];
    }
  for (int l = 0; i < i1; i++, l++) {
    aa[l] += a[i] * a[i];
    ab[l] += a[i] * b[i];
  }
  sums[0] = ss_par_lanes_total(aa), sums[1] = ss_par_lanes_total(ab);
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
  double *restrict s_out = v->out, *restrict y_out = v->out2;
  const double *restrict x = v->a, *restrict g = v->b, *restrict x_old = v->c, *restrict g_old = v->d;
  double sy[L] = {0}, ss[L] = {0}, yy[L] = {0};
  int i = i0;
  for (; i1 - i >= L; i += L)
    SS_PAR_LANE_LOOP
    for (int l = 0; l < L; l++) {
      const double si = x[i + l] - x_old[i + l], yi = g[i + l] - g_old[i + l];
      s_out[i + l] = si, y_out[i + l] = yi;
      sy[l] += si * yi;
      ss[l] += si * si;
      yy[l] += yi * yi;
    }
  for (int l = 0; i < i1; i++, l++) {
    const double si = x[i] - x_old[i], yi = g[i] - g_old[i];
    s_out[i] = si, y_out[i] = yi;
    sy[l] += si * yi;
    ss[l] += si * si;
    yy[l] += yi * yi;
  }
  sums[0] = ss_par_lanes_total(sy), sums[1] = ss_par_lanes_total(ss), sums[2] = ss_par_lanes_total(yy);
}

void ss_par_pair(int nthread, double *part, int n, double *s, const double *x, const double *x_old,
                 double *y, const double *g, const double *g_old, double sums[3]) {
  vec_ctx v = {.out = s, .out2 = y, .a = x, .b = g, .c = x_old, .d = g_old};
  ss_par_sum(nthread, n, 3, pair_block, &v, part, sums);
}
