/* Internal: loops over fixed blocks, on the sim's threads, whose sums do not
 * depend on the thread count (par.c).
 *
 * A sum over n terms is cut into blocks of SS_PAR_BLOCK terms, each block's
 * partial sum is accumulated in a fixed order (by whichever thread runs it),
 * and the partial sums are added in block order on one thread: the blocks
 * are the same for any thread count, so are the bits. The vector work of the
 * solver (dots, updates) and the sums of the energy's per-element terms run
 * this way, so that the second core works on them too instead of spinning. */
#ifndef SKIN_SIM_PAR_H
#define SKIN_SIM_PAR_H

#define SS_PAR_BLOCK 2048 /* terms per block */
/* Within a block, term i0 + j is accumulated into partial sum j % SS_PAR_LANES
 * (each in index order), and the block's sum is ss_par_lanes_total of them:
 * independent chains, vectorised at any width with the same bits. */
#define SS_PAR_LANES 8
/* Before a loop over the lanes: each lane its own (no reduction across
 * them), so vectorising it changes no bit. */
#ifdef _OPENMP
#define SS_PAR_LANE_LOOP _Pragma("omp simd")
#else
#define SS_PAR_LANE_LOOP
#endif
static inline double ss_par_lanes_total(const double s[SS_PAR_LANES]) {
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}
#define SS_PAR_SUMS 3     /* the most sums one pass forms */

/* Blocks of a pass over n terms. */
static inline int ss_par_nblocks(int n) { return n > 0 ? (n + SS_PAR_BLOCK - 1) / SS_PAR_BLOCK : 0; }

/* The work of one block, terms [i0, i1): writes its k partial sums into
 * sums[0..k) (each accumulated from 0.0 in index order), or nothing if k is
 * 0. ctx is the caller's. */
typedef void (*ss_par_fn)(void *ctx, int i0, int i1, double *sums);

/* Runs fn over the blocks of [0, n) (on nthread threads where nthread > 1
 * and there are several blocks; without OpenMP or at one thread, plainly in
 * order), then adds the blocks' k sums (k <= SS_PAR_SUMS) in block order into
 * sums[0..k). part: scratch of ss_par_nblocks(n) * k doubles. */
void ss_par_sum(int nthread, int n, int k, ss_par_fn fn, void *ctx, double *part, double *sums);

/* Vector passes of the solver on ss_par_sum (n terms; part as there). Each
 * does elementwise what its name says and returns the sums it names. */
/* sum a[i] b[i] */
double ss_par_dot(int nthread, double *part, int n, const double *a, const double *b);
/* out = x + alpha y */
void ss_par_axpy(int nthread, double *part, int n, double *out, const double *x, double alpha,
                 const double *y);
/* out = src; returns sum z[i] out[i] */
double ss_par_copy_dot(int nthread, double *part, int n, double *out, const double *src,
                       const double *z);
/* out += alpha y; returns sum z[i] out[i] (z NULL: 0, no sum) */
double ss_par_axpy_dot(int nthread, double *part, int n, double *out, double alpha, const double *y,
                       const double *z);
/* out = -(out + alpha y) (y NULL: out = -out); returns sum out[i] z[i] */
double ss_par_neg_axpy_dot(int nthread, double *part, int n, double *out, double alpha,
                           const double *y, const double *z);
/* *aa = sum a[i]^2, *ab = sum a[i] b[i] */
void ss_par_norm2_dot(int nthread, double *part, int n, const double *a, const double *b, double *aa,
                      double *ab);
/* s = x - x_old, y = g - g_old; sums[0..3) = s.y, s.s, y.y */
void ss_par_pair(int nthread, double *part, int n, double *s, const double *x, const double *x_old,
                 double *y, const double *g, const double *g_old, double sums[3]);

#endif
