/* The incremental potential of one implicit Euler step and its derivatives.
 *
 * Backward Euler, x_{n+1} = argmin E(x) (Martin et al. 2011 "Example-based
 * elastic materials"; Gast et al. 2015 "Optimization integrator"):
 *   E(x) = sum_v m_v/(2h^2) |x_v - x~_v|^2 + c m_v/(2h) |x_v - x_n,v|^2 - m_v g.x_v
 *        + sum_v k_v/2 |x_v - a_v|^2 + sum_f k_f/2 |(x0 + x1 + x2)/3 - a_f|^2
 *        + sum_f A_f Psi_SNH(F_f) + sum_e hinge_e,
 * x~ = x_n + h v_n, c the mass damping (1/s), g gravity. The three diagonal
 * quadratic terms in the first line are folded into one,
 *   mi_v/2 |x_v - t_v|^2,  mi = m (1/h^2 + c/h),
 *   t = (x~ + c h x_n) / (1 + c h) + g / (1/h^2 + c/h),
 * which has the same minimiser and derivatives (E differs by a constant).
 * Only free vertices are unknowns; terms touching only fixed vertices are
 * constants and skipped.
 *
 * Sums run in a fixed order: per-face and per-vertex work may run on
 * several threads, but every total is summed in one order, so the bits do
 * not depend on the thread count. A new term adds its energy to the total
 * and its gradient to g after the per-vertex gather, as the hinges do. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "energy.h"
#include "isa.h"
#include "sim_internal.h"
#include "ss_err.h"
#include "ss_vec.h"

typedef struct inertia_ctx {
  ss_sim *sim;
  double h;
} inertia_ctx;

static void inertia_begin_block(void *ctx, int k0, int k1, double *sums) {
  const inertia_ctx *ic = ctx;
  ss_sim *sim = ic->sim;
  (void)sums;
  const double h = ic->h, c = sim->set.damping, w = 1.0 / (h * h) + c / h;
  const double *g = sim->set.gravity;
  for (int k = k0; k < k1; k++) {
    int v = sim->m->dof_vert[k];
    sim->mi[k] = sim->m->mass[v] * w;
    for (int i = 0; i < 3; i++) {
      double xn = sim->x_prev[3 * v + i];
      double pred = xn + h * sim->v[3 * v + i];
      sim->target[3 * k + i] = (pred + c * h * xn) / (1.0 + c * h) + g[i] / w;
    }
  }
}

void ss_sim_energy_begin(ss_sim *sim, double h) {
  inertia_ctx ic = {sim, h};
  ss_par_sum(sim->nthread, sim->m->ndof, 0, inertia_begin_block, &ic, sim->par_part, NULL);
  ss_sim_orient_begin(sim); /* orient.c: its normals in this pose */
}

typedef struct scatter_ctx {
  const ss_sim *sim;
  const double *xd;
  double *xfull;
} scatter_ctx;

static void scatter_block(void *ctx, int k0, int k1, double *sums) {
  const scatter_ctx *c = ctx;
  (void)sums;
  /* every vertex free (dofs are the free vertices in increasing order, so
   * dof k is vertex k): one copy, not one per vertex through dof_vert */
  if (c->sim->m->ndof == c->sim->m->nvert) {
    memcpy(c->xfull + 3 * (size_t)k0, c->xd + 3 * (size_t)k0, 3 * (size_t)(k1 - k0) * sizeof(double));
    return;
  }
  for (int k = k0; k < k1; k++) memcpy(c->xfull + 3 * c->sim->m->dof_vert[k], c->xd + 3 * k, 3 * sizeof(double));
}

void ss_sim_scatter(const ss_sim *sim, const double *xd, double *xfull) {
  scatter_ctx c = {sim, xd, xfull};
  ss_par_sum(sim->nthread, sim->m->ndof, 0, scatter_block, &c, sim->par_part, NULL);
}

/* g[dof of v] += gv (3 values), if v is free. */
static inline void add_grad(const ss_sim *sim, double *g, int v, const double *gv) {
  int k = sim->m->dof[v];
  if (k < 0) return;
  g[3 * k] += gv[0];
  g[3 * k + 1] += gv[1];
  g[3 * k + 2] += gv[2];
}

/* Gradient of dof k's own terms (inertia, vertex spring) into g. */
static inline void own_grad(const ss_sim *sim, int k, const double *xfull, double *g) {
  int v = sim->m->dof_vert[k];
  const double *x = xfull + 3 * v, *t = sim->target + 3 * k, *a = sim->anchor_pos + 3 * v;
  double mi = sim->mi[k], kv = sim->m->k_vert[v];
  g[3 * k] = mi * (x[0] - t[0]) + kv * (x[0] - a[0]);
  g[3 * k + 1] = mi * (x[1] - t[1]) + kv * (x[1] - a[1]);
  g[3 * k + 2] = mi * (x[2] - t[2]) + kv * (x[2] - a[2]);
}

/* Gradient of dof k: its own terms (inertia, vertex spring), then the
 * per-face parts it shares, summed in the order of grad_slot. */
static inline void gather_grad(const ss_sim *sim, int k, const double *xfull, double *g) {
  own_grad(sim, k, xfull, g);
  double g0 = g[3 * k], g1 = g[3 * k + 1], g2 = g[3 * k + 2];
  const double *fg = sim->face_grad;
  for (int e = sim->m->grad_ptr[k]; e < sim->m->grad_ptr[k + 1]; e++) {
    const double *p = fg + sim->m->grad_slot[e];
    g0 += p[0];
    g1 += p[1];
    g2 += p[2];
  }
  g[3 * k] = g0, g[3 * k + 1] = g1, g[3 * k + 2] = g2;
}

/* Every term's energy is summed into one total in a fixed order (vertex
 * terms, simulated faces' membrane with barycenter spring, hinges: the place
 * for a new term is between the faces and the hinges, or after them), and every dof's
 * gradient is summed in the same order of terms: bit-for-bit the same for
 * any thread count. */
typedef struct sum_ctx {
  const ss_sim *sim;
  const double *xfull;
  const double *a; /* sum_block's terms */
  double *g;       /* inertia_block: each dof's own gradient (own_grad) written here too, if not NULL */
} sum_ctx;

/* Inertia (with damping and gravity) and vertex springs: energy of dofs
 * [k0, k1), dof k0 + j's into lane j % SS_PAR_LANES (par.h); with c->g
 * also each dof's own gradient (own_grad's arithmetic), from the same
 * differences in the same pass. */
static void inertia_block(void *ctx, int k0, int k1, double *sums) {
  const sum_ctx *c = ctx;
  const ss_sim *sim = c->sim;
  double *g = c->g;
  double e[SS_PAR_LANES] = {0};
  for (int k = k0, l = 0; k < k1; k++, l = (l + 1) % SS_PAR_LANES) {
    int v = sim->m->dof_vert[k];
    const double *x = c->xfull + 3 * v, *t = sim->target + 3 * k, *a = sim->anchor_pos + 3 * v;
    double mi = sim->mi[k], kv = sim->m->k_vert[v];
    double ek = 0.0;
    for (int i = 0; i < 3; i++) {
      double dt = x[i] - t[i], da = x[i] - a[i];
      ek += 0.5 * (mi * dt * dt + kv * da * da);
      if (g) g[3 * k + i] = mi * dt + kv * da;
    }
    e[l] += ek;
  }
  sums[0] = ss_par_lanes_total(e);
}

static void sum_block(void *ctx, int i0, int i1, double *sums) {
  const sum_ctx *c = ctx;
  const double *restrict a = c->a;
  double e[SS_PAR_LANES] = {0};
  int i = i0;
  for (; i1 - i >= SS_PAR_LANES; i += SS_PAR_LANES)
    SS_PAR_LANE_LOOP
    for (int l = 0; l < SS_PAR_LANES; l++) e[l] += a[i + l];
  for (int l = 0; i < i1; i++, l++) e[l] += a[i];
  sums[0] = ss_par_lanes_total(e);
}

double ss_sim_energy(const ss_sim *sim, const double *xfull, double *g) {
  enum { L = SS_MEMBRANE_LANES };
  int n = sim->m->ndof;
  double *fg = sim->face_grad;
  /* sums by blocks (par.h): the same bits for any thread count. On one
   * thread (the kernel below adds the faces' gradients to the dofs' own)
   * each dof's own gradient is written in the same pass. */
  const int nsim = sim->m->nsimface;
  const int threaded = sim->nthread > 1 && nsim > 256;
  sum_ctx sc = {sim, xfull, NULL, threaded ? NULL : g};
  double part_sum;
  ss_par_sum(sim->nthread, n, 1, inertia_block, &sc, sim->par_part, &part_sum);
  double e = part_sum;
  /* Membrane and barycenter springs: blocks of faces on all threads (each
   * face's spring in the membrane's pass over its corners), energies summed
   * in face order. The gradient: on threads, each face's into face_grad and
   * each dof's gathered from there in face order; on one thread, each dof's
   * own terms first and each face's added to its corners in face order by
   * the kernel itself: the same additions in the same order, without the
   * round trip through face_grad. */
  const int nblock = (nsim + L - 1) / L;
  double *fe = sim->face_energy;
  const double *bary_anchor = sim->set.barycenter_anchors ? sim->anchor_pos + 3 * (size_t)sim->m->nvert : NULL;
  /* with the orient term, each face's s from the corners the membrane
   * gathers (orient.c reads them: ss_sim_orient_energy's s_ready) */
  double *os = sim->set.orient > 0.0 ? sim->orient_s : NULL;
#ifdef _OPENMP
  if (threaded) {
#pragma omp parallel for schedule(static) num_threads(sim->nthread)
    for (int b = 0; b < nblock; b++)
      ss_membrane_eval_batch_orient_isa(sim->isa, sim->m->mface, b * L, b * L + L < nsim ? b * L + L : nsim,
                                        xfull, bary_anchor, sim->m->mu, sim->m->lam, sim->m->set.compression, fe,
                                        g ? fg : NULL, NULL, NULL, sim->orient_n, SS_ORIENT_S0, os);
    if (g) {
      if (n > 256) {
#pragma omp parallel for schedule(static) num_threads(sim->nthread)
        for (int k = 0; k < n; k++) gather_grad(sim, k, xfull, g);
      } else {
        for (int k = 0; k < n; k++) gather_grad(sim, k, xfull, g);
      }
    }
  } else
#endif
  {
    /* each dof's own gradient already in g (inertia_block) */
    ss_membrane_eval_batch_orient_isa(sim->isa, sim->m->mface, 0, nsim, xfull, bary_anchor, sim->m->mu,
                                      sim->m->lam, sim->m->set.compression, fe, NULL, g, sim->m->dof,
                                      sim->orient_n, SS_ORIENT_S0, os);
  }
  sc.a = fe;
  ss_par_sum(sim->nthread, nsim, 1, sum_block, &sc, sim->par_part, &part_sum);
  e += part_sum;
  /* Bending. */
  for (int q = 0; q < sim->m->nhinge; q++) {
    const int *hv = sim->m->hinge_vert + 4 * q;
    double x12[12], g12[12];
    for (int c = 0; c < 4; c++) memcpy(x12 + 3 * c, xfull + 3 * hv[c], 3 * sizeof(double));
    e += ss_hinge_eval(x12, sim->m->hinge_theta0[q], sim->m->hinge_weight[q], g ? g12 : NULL, NULL);
    if (g)
      for (int c = 0; c < 4; c++) add_grad(sim, g, hv[c], g12 + 3 * c);
  }
  e += ss_sim_orient_energy(sim, xfull, g, os != NULL); /* orient.c */
  return e;
}

double ss_sim_energy_at(ss_sim *sim, ss_sim_stats *st, const double *xd, double *g) {
  double t0 = ss_now_ms();
  ss_sim_scatter(sim, xd, sim->xfull_t);
  double e = ss_sim_energy(sim, sim->xfull_t, g);
  st->assemble_ms += ss_now_ms() - t0, st->energy_evaluations++;
  return e;
}

double ss_sim_energy_first_trial(ss_sim *sim, const double *xd, const double *dir, double slope) {
  /* the membrane, hinges and springs are what the solvers' matrices model:
   * their minimum along a direction of those matrices is the full step. The
   * orient term's depth springs (one-sided, stiff) are not: they answer
   * with the minimum along the line of their exact model (orient.c) */
  return ss_sim_orient_line_step(sim, xd, dir, slope);
}

/* The stiffness across the skin is taken as at least this share of that
 * along it (the true ratio is 1/640 at the demo avatar's fingers). A tenth
 * is enough for a vertex lifted a fifth of an edge off its anchor to count
 * as unconverged (ten times tol there) while a step across the skin is
 * judged at most ten times larger than it would be along it, not hundreds. */
#define SS_ACROSS_MIN 0.1

/* The residual of dof k in mean rest edge lengths: the gradient divided by
 * the stiffness that holds the vertex, which is not the same in every
 * direction. Along the skin, inertia, the anchor springs and the membrane
 * (the scalar matrix's diagonal); across it (skin_n), a flat membrane has no
 * stiffness of its own and only inertia and the anchor springs hold it: the
 * same force moves a vertex hundreds of times further across the skin than
 * along it (mi + diag_const against mi + diag_springs: 290 against 0.45 at
 * the demo avatar's fingers). Judged by the membrane's diagonal alone, a
 * vertex 0.2 edge lengths off its anchor across the skin passed for
 * converged, and after a motion the skin never came home. */
static inline SS_ALWAYS_INLINE double dof_residual2(const ss_sim *sim, const double *g, int k) {
  const double *gk = g + 3 * k, *n = sim->skin_n + 3 * k;
  double g2 = gk[0] * gk[0] + gk[1] * gk[1] + gk[2] * gk[2];
  double gn = gk[0] * n[0] + gk[1] * n[1] + gk[2] * n[2]; /* 0 where n is 0 */
  double along = sim->mi[k] + sim->m->diag_const[k], across = sim->mi[k] + sim->m->diag_springs[k];
  if (across < SS_ACROSS_MIN * along) across = SS_ACROSS_MIN * along;
  double ga2 = g2 - gn * gn;
  if (ga2 < 0.0) ga2 = 0.0;
  return (ga2 / (along * along) + gn * gn / (across * across)) / (sim->m->edge_len * sim->m->edge_len);
}

static inline SS_ALWAYS_INLINE double dof_residual_along(const ss_sim *sim, const double *g, int k) {
  double gn = sqrt(g[3 * k] * g[3 * k] + g[3 * k + 1] * g[3 * k + 1] + g[3 * k + 2] * g[3 * k + 2]);
  return gn / ((sim->mi[k] + sim->m->diag_const[k]) * sim->m->edge_len);
}

/* The largest residual of dofs [k0, k1) (along: ss_sim_residual_along's
 * measure; else its square) into *worst, and the number of NaN among them
 * into *nan. A maximum is exact in any order: in vector lanes and on the
 * sim's threads, the same bits. In each instruction set (isa.h): baseline
 * x86-64 divides two doubles at a time, and this pass has three divisions
 * per dof, several times a frame. */
static inline SS_ALWAYS_INLINE void residual_kernel(const ss_sim *sim, const double *g, int k0, int k1,
                                                    double *worst_out, int *nan_out, const int along) {
  /* in lanes of their own (an omp simd max reduction was left scalar by the
   * vectoriser): each lane's largest and whether it met a NaN, as doubles */
  enum { L = 8 };
  double wl[L], nl[L];
  for (int l = 0; l < L; l++) wl[l] = 0.0, nl[l] = 0.0;
  int k = k0;
  for (; k + L <= k1; k += L) {
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) {
      const double r = along ? dof_residual_along(sim, g, k + l) : dof_residual2(sim, g, k + l);
      wl[l] = r > wl[l] ? r : wl[l];
      nl[l] = r != r ? 1.0 : nl[l];
    }
  }
  double worst = 0.0;
  int nan = 0;
  for (int l = 0; l < L; l++) {
    worst = wl[l] > worst ? wl[l] : worst;
    nan += nl[l] != 0.0;
  }
  for (; k < k1; k++) {
    const double r = along ? dof_residual_along(sim, g, k) : dof_residual2(sim, g, k);
    worst = r > worst ? r : worst;
    nan += r != r;
  }
  *worst_out = worst;
  *nan_out = nan;
}
/* specialised by the constant along: one loop each */
SS_ISA_VARIANTS(residual, (const ss_sim *sim, const double *g, int along, int k0, int k1, double *worst, int *nan),
                if (along) residual_kernel(sim, g, k0, k1, worst, nan, 1);
                else residual_kernel(sim, g, k0, k1, worst, nan, 0);)

/* The largest residual over the dofs (along: ss_sim_residual_along's
 * measure), NaN if any is NaN. The square root is taken of the largest
 * square (sqrt is correctly rounded, so monotone: the same value as the
 * largest root), not of every dof's. */
static double worst_residual(const ss_sim *sim, const double *g, int along) {
  const int ndof = sim->m->ndof;
  double worst = 0.0; /* the largest residual along, or square */
  int nan = 0;
#ifdef _OPENMP
  if (sim->nthread > 1 && ndof > 256) {
#pragma omp parallel num_threads(sim->nthread) reduction(max : worst) reduction(+ : nan)
    {
      const int t = omp_get_thread_num(), nt = omp_get_num_threads();
      const int k0 = (int)((long long)ndof * t / nt), k1 = (int)((long long)ndof * (t + 1) / nt);
      double w = 0.0;
      int n = 0;
      SS_ISA_CALL(sim->isa, residual, (sim, g, along, k0, k1, &w, &n));
      worst = w > worst ? w : worst;
      nan += n;
    }
  } else
#endif
    SS_ISA_CALL(sim->isa, residual, (sim, g, along, 0, ndof, &worst, &nan));
  return nan ? NAN : along ? worst : sqrt(worst);
}

double ss_sim_residual(const ss_sim *sim, const double *g) { return worst_residual(sim, g, 0); }

double ss_sim_residual_along(const ss_sim *sim, const double *g) { return worst_residual(sim, g, 1); }

/* The sum over dofs [k0, k1) of the squared residuals, added to *sum in
 * dof order (as one at a time), each dof's computed in vector lanes first:
 * its three divisions were a chain per dof at the end of every substep. */
static inline SS_ALWAYS_INLINE void residual_sum_kernel(const ss_sim *sim, const double *g, int k0, int k1,
                                                        double *sum) {
  enum { L = 8 };
  double r[L], s = *sum;
  int k = k0;
  for (; k + L <= k1; k += L) {
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) r[l] = dof_residual2(sim, g, k + l);
    for (int l = 0; l < L; l++) s += r[l];
  }
  for (; k < k1; k++) s += dof_residual2(sim, g, k);
  *sum = s;
}
SS_ISA_VARIANTS(residual_sum, (const ss_sim *sim, const double *g, int k0, int k1, double *sum),
                residual_sum_kernel(sim, g, k0, k1, sum);)

double ss_sim_residual_rms(const ss_sim *sim, const double *g) {
  double sum = 0.0;
  SS_ISA_CALL(sim->isa, residual_sum, (sim, g, 0, sim->m->ndof, &sum));
  return sim->m->ndof ? sqrt(sum / sim->m->ndof) : 0.0;
}

/* Simulated face q's area vector (twice its area along its normal) into
 * fn[3 q ..]; zero for a sliver, whose normal swings with the smallest move
 * of a corner (a vertex with only slivers around it is judged as along the
 * skin). */
static inline void face_area_vector(const ss_sim *sim, const double *xfull, double min_area, int q,
                                    double *fn) {
  const ss_model *m = sim->m;
  const int f = m->simface[q];
  double *n = fn + 3 * (size_t)q;
  if (!(m->rest_area[f] >= min_area)) {
    n[0] = n[1] = n[2] = 0.0;
    return;
  }
  const int *fv = m->faces + 3 * f;
  tri_area_vector(xfull + 3 * fv[0], xfull + 3 * fv[1], xfull + 3 * fv[2], n);
}

/* The skin normals of dofs [k0, k1): each the sum of its simulated faces'
 * area vectors fn, gathered through its slots of grad_slot (simulated face
 * order, so the same sum in the same order as a scatter over the faces),
 * normalised; zero (judged as along the skin) where the sum is zero or not
 * finite. A sliver's zero adds nothing. The sums gathered into lanes, the
 * square roots and divisions in one elementwise loop (the same bits at any
 * width): one dof at a time they were a chain each, every substep. */
#define SS_NORMAL_LANES 8
static inline SS_ALWAYS_INLINE void dof_normals_kernel(const ss_sim *sim, const double *fn, int k0, int k1) {
  enum { L = SS_NORMAL_LANES };
  const ss_model *m = sim->m;
  for (int kb = k0; kb < k1; kb += L) {
    const int cnt = k1 - kb < L ? k1 - kb : L;
    double s[3][L], out[3][L], ok[L];
    for (int l = 0; l < L; l++) {
      double s0 = 0.0, s1 = 0.0, s2 = 0.0;
      if (l < cnt)
        for (int e = m->grad_ptr[kb + l]; e < m->grad_ptr[kb + l + 1]; e++) {
          const double *n = fn + 3 * (size_t)(m->grad_slot[e] / 9);
          s0 += n[0], s1 += n[1], s2 += n[2]; /* area weighted */
        }
      s[0][l] = s0, s[1][l] = s1, s[2][l] = s2;
    }
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) {
      const double len = sqrt(s[0][l] * s[0][l] + s[1][l] * s[1][l] + s[2][l] * s[2][l]);
      /* divided on every lane, chosen at the write-back: a division under a
       * condition is not if-converted for AVX2 (it might trap) */
      out[0][l] = s[0][l] / len, out[1][l] = s[1][l] / len, out[2][l] = s[2][l] / len;
      ok[l] = (double)(len > 0.0) * (double)(len <= DBL_MAX);
    }
    for (int l = 0; l < cnt; l++) {
      double *nk = sim->skin_n + 3 * (size_t)(kb + l);
      if (ok[l] != 0.0)
        nk[0] = out[0][l], nk[1] = out[1][l], nk[2] = out[2][l];
      else
        nk[0] = nk[1] = nk[2] = 0.0;
    }
  }
}
SS_ISA_VARIANTS(dof_normals, (const ss_sim *sim, const double *fn, int k0, int k1),
                dof_normals_kernel(sim, fn, k0, k1);)

/* Each face, then each dof its own: on the sim's threads with the same
 * bits. The faces' area vectors go to face_grad, free outside an energy
 * evaluation. */
void ss_sim_normals_begin(ss_sim *sim, const double *xfull) {
  const int ndof = sim->m->ndof, nsim = sim->m->nsimface;
  const double min_area = SS_SLIVER_AREA * sim->m->edge_len * sim->m->edge_len;
  double *fn = sim->face_grad;
#ifdef _OPENMP
  if (sim->nthread > 1 && ndof > 256) {
#pragma omp parallel num_threads(sim->nthread)
    {
#pragma omp for schedule(static)
      for (int q = 0; q < nsim; q++) face_area_vector(sim, xfull, min_area, q, fn);
      enum { B = 64 * SS_NORMAL_LANES };
#pragma omp for schedule(static)
      for (int b = 0; b < (ndof + B - 1) / B; b++)
        SS_ISA_CALL(sim->isa, dof_normals, (sim, fn, b * B, (b + 1) * B < ndof ? (b + 1) * B : ndof));
    }
    return;
  }
#endif
  for (int q = 0; q < nsim; q++) face_area_vector(sim, xfull, min_area, q, fn);
  SS_ISA_CALL(sim->isa, dof_normals, (sim, fn, 0, ndof));
}

/* Current area over rest area of face f. */
static double area_ratio(const ss_sim *sim, const double *x9, int f) {
  return 0.5 * sqrt(tri_cross2(x9, x9 + 3, x9 + 6)) / sim->m->rest_area[f];
}

void ss_sim_add_elastic_hessian(const ss_sim *sim, const double *xfull, double *vals, int exact) {
  for (int q = 0; q < sim->m->nsimface; q++) {
    int f = sim->m->simface[q];
    const int *fv = sim->m->faces + 3 * f;
    double x9[9], h81[81];
    for (int c = 0; c < 3; c++) memcpy(x9 + 3 * c, xfull + 3 * fv[c], 3 * sizeof(double));
    /* The exact Hessian grows like 1/J: nearly collapsed faces stay projected. */
    if (exact && area_ratio(sim, x9, f) > 1e-3)
      ss_membrane_eval_raw(x9, sim->m->dm_inv + 4 * f, sim->m->rest_area[f], sim->m->mu, sim->m->lam,
                           sim->m->set.compression, NULL, h81);
    else
      ss_membrane_eval(x9, sim->m->dm_inv + 4 * f, sim->m->rest_area[f], sim->m->mu, sim->m->lam,
                       sim->m->set.compression, NULL, h81);
    ss_model_scatter_element(sim->m, fv, 3, sim->m->face_rank + 9 * f, h81, vals);
  }
  for (int q = 0; q < sim->m->nhinge; q++) {
    const int *hv = sim->m->hinge_vert + 4 * q;
    double x12[12], h144[144];
    for (int c = 0; c < 4; c++) memcpy(x12 + 3 * c, xfull + 3 * hv[c], 3 * sizeof(double));
    ss_hinge_eval(x12, sim->m->hinge_theta0[q], sim->m->hinge_weight[q], NULL, h144);
    ss_model_scatter_element(sim->m, hv, 4, sim->m->hinge_rank + 16 * q, h144, vals);
  }
  ss_sim_orient_hessian(sim, xfull, vals); /* orient.c */
}

void ss_sim_constant_hessian(const ss_sim *sim, double *vals) { ss_model_constant_terms(sim->m, sim->mi, vals, 0); }

void ss_sim_scalar_matrix(const ss_sim *sim, double *vals) { ss_model_scalar_matrix(sim->m, sim->mi, vals); }
