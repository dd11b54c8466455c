/* Quasi-Newton (L-BFGS) for the implicit Euler step: the real-time solver.
 *
 * Liu, Bouaziz and Kavan 2017, "Quasi-Newton methods for real-time simulation
 * of hyperelastic materials": L-BFGS (Nocedal and Wright, "Numerical
 * Optimization", algorithm 7.4, the two-loop recursion) whose initial inverse
 * Hessian is not a multiple of the identity but the inverse of a constant
 * matrix close to the true Hessian:
 *   A = M/h^2 (+ damping) + anchor springs + (mu + lam) * cotangent Laplacian,
 * every term of which is isotropic, so A = L (x) I3 with L the scalar n x n
 * matrix on the same pattern (model_pattern.c). L is factored by CHOLMOD once
 * per topology and time step (analysis once per model, sim_internal.h
 * "symbolic analysis"; numeric factorisation when h changes), and each
 * application of A^-1 is one cholmod_solve2 with three right-hand sides
 * (x, y, z): about 27 times fewer flops than factoring the 3n x 3n matrix.
 * An iteration costs one energy gradient, one pair of triangular solves and
 * O(m n) vector work.
 *
 * The history is cleared at the start of every step and kept from one
 * substep to the next within it: the substeps share h and so A, and the
 * pairs of the substep before measured the curvature the constant matrix
 * misses (the membrane's nonlinearity, the orient term's springs) at a nearby
 * point, so the first iteration of a substep is not a bare -A^-1 g again
 * (error against the truth on the 19k quadruped: 0.386 -> 0.357 edge lengths
 * at 4 x 2, 0.660 -> 0.453 at 4 x 1). Not across steps: a step then depends
 * only on the state (positions, velocities, anchors), which ss_sim_set_state
 * and a replay restore. A direction that is
 * not a descent direction (possible when curvature pairs are stale) is
 * replaced by -A^-1 g, which always is (A is positive definite). Pairs with
 * s.y <= 1e-12 |s| |y| are skipped (keeps the implicit Hessian positive
 * definite). The outer loop, the line search and convergence are solver.c's
 * and line_search.c's; this file gives the directions: the L-BFGS one, then
 * (if its line search fails with a history) -A^-1 g (ss_solver_qn_ops).
 *
 * Budget: `iterations` per substep, the real-time cost. A substep still far
 * from converged after it (residual above `safety_residual`, e.g. a skin
 * spun hard against soft anchors) goes on up to `iterations_max`: with the
 * isotropic A, L-BFGS needs many iterations exactly where skipping them
 * would leave the membrane crushed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "solver.h"
#include "ss_err.h"

/* Factors L for the current h (sim->mi set by ss_sim_energy_begin). */
static int factor_scalar(ss_sim *sim, double h, ss_sim_stats *st) {
  ss_sim_scalar_matrix(sim, sim->A->x);
  int ok = cholmod_factorize(sim->A, sim->LA, &sim->cc);
  if (st) st->factorizations++;
  if (!ok || sim->cc.status != CHOLMOD_OK) {
    sim->a_h = 0.0;
    return SS_E_SOLVER;
  }
  sim->a_h = h;
  return SS_OK;
}

/* cholmod_solve2 on ncol columns of qb from column c0 (a view of them),
 * into *x with workspaces *y, *e and common cc. Its simplicial path asks for
 * a workspace Y of 4 x n (4 columns at a time) and leaves it shaped ncol x n
 * after ncol columns; the shape is restored first, or the call frees and
 * reallocates it. */
static int solve_columns(ss_sim *sim, int c0, int ncol, cholmod_dense **x, cholmod_dense **y,
                         cholmod_dense **e, cholmod_common *cc) {
  const size_t n = (size_t)sim->m->ndof;
  cholmod_dense b = *sim->qb;
  b.ncol = (size_t)ncol;
  b.nzmax = (size_t)ncol * n;
  b.x = (double *)sim->qb->x + (size_t)c0 * n;
  if (*y && (*y)->nzmax >= 4 * n) (*y)->nrow = 4, (*y)->d = 4, (*y)->ncol = n;
  return cholmod_solve2(CHOLMOD_A, sim->LA, &b, NULL, x, NULL, y, e, cc) ? SS_OK : SS_E_SOLVER;
}

/* The copies between the interleaved dof vectors (n x 3) and CHOLMOD's
 * columns, on the sim's threads (par.h, no sums). */
typedef struct copy_ctx {
  int n;
  const double *q;
  double *b;
  const double *c0, *c1, *c2; /* the solution's three columns */
  double *z;
} copy_ctx;

static void to_columns(void *ctx, int k0, int k1, double *sums) {
  const copy_ctx *c = ctx;
  (void)sums;
  for (int k = k0; k < k1; k++)
    for (int i = 0; i < 3; i++) c->b[k + (size_t)i * c->n] = c->q[3 * k + i];
}

static void from_columns(void *ctx, int k0, int k1, double *sums) {
  const copy_ctx *c = ctx;
  (void)sums;
  for (int k = k0; k < k1; k++) {
    c->z[3 * k] = c->c0[k];
    c->z[3 * k + 1] = c->c1[k];
    c->z[3 * k + 2] = c->c2[k];
  }
}

/* z = A^-1 q for dof vectors (n x 3 interleaved). With threads (and the
 * split made at create) the z column is solved on a second thread beside x
 * and y: the simplicial solve treats each column on its own, with the same
 * operations whatever columns it is given with, so the bits do not change
 * (the solve was the largest part of a frame left on one core). */
static int apply_inverse(ss_sim *sim, const double *q, double *z) {
  int n = sim->m->ndof;
  copy_ctx cp = {.n = n, .q = q, .b = sim->qb->x, .z = z};
  ss_par_sum(sim->nthread, n, 0, to_columns, &cp, sim->par_part, NULL);
#ifdef _OPENMP
  if (sim->nthread > 1 && sim->cc_z_started) {
    int st_xy = SS_OK, st_z = SS_OK;
#pragma omp parallel sections num_threads(2)
    {
#pragma omp section
      st_xy = solve_columns(sim, 0, 2, &sim->qx_xy, &sim->qy_xy, &sim->qe_xy, &sim->cc);
#pragma omp section
      st_z = solve_columns(sim, 2, 1, &sim->qx_z, &sim->qy_z, &sim->qe_z, &sim->cc_z);
    }
    if (st_xy != SS_OK || st_z != SS_OK) return SS_E_SOLVER;
    const double *xy = sim->qx_xy->x;
    cp.c0 = xy, cp.c1 = xy + (size_t)n, cp.c2 = sim->qx_z->x;
    ss_par_sum(sim->nthread, n, 0, from_columns, &cp, sim->par_part, NULL);
    return SS_OK;
  }
#endif
  if (solve_columns(sim, 0, 3, &sim->qx, &sim->qy, &sim->qe, &sim->cc) != SS_OK) return SS_E_SOLVER;
  const double *xs = sim->qx->x;
  cp.c0 = xs, cp.c1 = xs + (size_t)n, cp.c2 = xs + 2 * (size_t)n;
  ss_par_sum(sim->nthread, n, 0, from_columns, &cp, sim->par_part, NULL);
  return SS_OK;
}

/* The pattern of the scalar matrix: the model's block pattern itself. */
static void scalar_pattern(const ss_model *m, cholmod_sparse *A) {
  memcpy(A->p, m->bcolp, ((size_t)m->ndof + 1) * sizeof(int));
  memcpy(A->i, m->brow, (size_t)m->nblock * sizeof(int));
}

/* A simplicial LDL' factor: CHOLMOD's simplicial solve does the three
 * columns in one pass over L, and no BLAS (nor its threads) is involved,
 * which keeps the result bit-for-bit reproducible (the supernodal solve,
 * through BLAS, is slower at these sizes, where the factor is sparse).
 * LDL' rather than LL': the LL' solves divide by the diagonal at every
 * column of both triangular passes, on their chains of dependent
 * operations; LDL' divides by D in a pass of its own. supernodal is read by
 * cholmod_analyze (the model's cc), final_ll by cholmod_factorize (each
 * sim's): both cc's are set alike. (Each cholmod_common serves only this
 * solver.) */
static void scalar_common(cholmod_common *cc) {
  cc->supernodal = CHOLMOD_SIMPLICIAL;
  cc->final_ll = 0;
}

int ss_solver_qn_analyze(ss_model *m, char *err, int err_sz) {
  cholmod_common *cc = &m->cc;
  const size_t n = (size_t)m->ndof;
  /* the analysis reads the pattern alone: no values */
  cholmod_sparse *A = cholmod_allocate_sparse(n, n, (size_t)m->nblock, 1, 1, 1, CHOLMOD_PATTERN, cc);
  if (!A) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the quasi-Newton analysis");
  scalar_pattern(m, A);
  scalar_common(cc);
  m->sym_qn = cholmod_analyze(A, cc);
  cholmod_free_sparse(&A, cc);
  if (!m->sym_qn || cc->status < CHOLMOD_OK)
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD analysis of the quasi-Newton matrix failed (status %d)",
                   cc->status);
  return SS_OK;
}

int ss_solver_qn_create(ss_sim *sim, char *err, int err_sz) {
  int n = sim->m->ndof;
  cholmod_common *cc = &sim->cc;
  sim->lb_m = sim->set.lbfgs_history;
  /* lb_s, lb_y, lb_rho, lb_alpha: the data's arena (SS_SIM_QN_HISTORY) */
  sim->A = cholmod_allocate_sparse((size_t)n, (size_t)n, (size_t)sim->m->nblock, 1, 1, 1, CHOLMOD_REAL, cc);
  sim->qb = cholmod_zeros((size_t)n, 3, CHOLMOD_REAL, cc);
  if (!sim->A || !sim->qb)
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the quasi-Newton solver");
  scalar_pattern(sim->m, sim->A);
  scalar_common(cc);
  /* The model's symbolic factor, copied (the numeric factorisation, once
   * per h, is this sim's); analysed here only on a model built for Newton. */
  sim->LA = sim->m->sym_qn ? cholmod_copy_factor(sim->m->sym_qn, cc) : cholmod_analyze(sim->A, cc);
  if (!sim->LA || cc->status < CHOLMOD_OK)
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD analysis of the quasi-Newton matrix failed (status %d)",
                   cc->status);
  /* Factor and solve once now: the factor and the solve workspace are then
   * allocated before stepping. */
  const double h = sim->set.dt / sim->set.substeps;
  ss_sim_energy_begin(sim, h);
  if (factor_scalar(sim, h, NULL) != SS_OK || solve_columns(sim, 0, 3, &sim->qx, &sim->qy, &sim->qe, cc) != SS_OK)
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD factorisation of the quasi-Newton matrix failed (status %d)",
                   cc->status);
#ifdef _OPENMP
  if (sim->nthread_max > 1) {
    /* the split solve's common and workspaces, allocated by one split solve now */
    cholmod_start(&sim->cc_z);
    sim->cc_z_started = 1;
    sim->cc_z.print = 0;
    scalar_common(&sim->cc_z);
    if (solve_columns(sim, 0, 2, &sim->qx_xy, &sim->qy_xy, &sim->qe_xy, cc) != SS_OK)
      return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD solve of the quasi-Newton matrix failed (status %d)",
                     cc->status);
    if (solve_columns(sim, 2, 1, &sim->qx_z, &sim->qy_z, &sim->qe_z, &sim->cc_z) != SS_OK)
      return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD solve of the quasi-Newton matrix failed (status %d)",
                     sim->cc_z.status);
  }
#endif
  return SS_OK;
}

static int qn_begin(ss_solve *s) {
  ss_sim *sim = s->sim;
  if (sim->a_h != s->in->h) {
    double t = ss_now_ms();
    int status = factor_scalar(sim, s->in->h, s->st);
    s->st->factor_ms += ss_now_ms() - t;
    if (status != SS_OK) return status;
  }
  /* the pairs of the substep before are kept within a step (file comment) */
  if (s->in->first) {
    sim->lb_count = 0;
    sim->lb_head = 0;
  }
  return SS_OK;
}

/* dir = -A^-1 g, always a descent direction (A is positive definite). */
static int preconditioned_gradient(ss_solve *s) {
  int n3 = 3 * s->sim->m->ndof;
  if (apply_inverse(s->sim, s->g, s->dir) != SS_OK) return SS_E_SOLVER;
  for (int i = 0; i < n3; i++) s->dir[i] = -s->dir[i];
  s->terms_first_trial = 1;
  return SS_DIR_OK;
}

/* The L-BFGS direction. The newest pair goes to the ring buffer's slot at
 * lb_head when the step is accepted (qn_accepted). */
static int lbfgs_direction(ss_solve *s) {
  ss_sim *sim = s->sim;
  int n3 = 3 * sim->m->ndof, m = sim->lb_m;
  ss_sim_stats *st = s->st;
  const double *g = s->g;
  double *dir = s->dir;
  double t1 = ss_now_ms();
  /* Two-loop recursion: dir = -H g. Each pass over the vectors applies
   * one pair's update and already forms the next pair's dot product (the
   * same operations in the same order as two separate loops: same bits,
   * half the memory traffic). */
  int count = sim->lb_count;
  s->terms_first_trial = count < m;
  double next = 0.0;
  /* the passes on the sim's threads, their dots summed by blocks (par.h) */
  const int nt = sim->nthread;
  double *part = sim->par_part;
  if (count > 0) {
    /* dir = g and the first dot in one pass */
    int slot = (sim->lb_head - 1 + m) % m;
    next = sim->lb_rho[slot] * ss_par_copy_dot(nt, part, n3, dir, g, sim->lb_s + (size_t)slot * n3);
  } else {
    memcpy(dir, g, (size_t)n3 * sizeof *dir);
  }
  for (int c = 0; c < count; c++) {
    int slot = (sim->lb_head - 1 - c + m) % m;
    const double *y = sim->lb_y + (size_t)slot * n3;
    double a = next;
    sim->lb_alpha[slot] = a;
    if (c + 1 < count) {
      int nslot = (sim->lb_head - 2 - c + m) % m;
      next = sim->lb_rho[nslot] * ss_par_axpy_dot(nt, part, n3, dir, -a, y, sim->lb_s + (size_t)nslot * n3);
    } else {
      ss_par_axpy_dot(nt, part, n3, dir, -a, y, NULL);
    }
  }
  if (apply_inverse(sim, dir, dir) != SS_OK) return SS_E_SOLVER;
  if (count > 0) {
    int slot = (sim->lb_head - count + m) % m;
    next = sim->lb_rho[slot] * ss_par_dot(nt, part, n3, sim->lb_y + (size_t)slot * n3, dir);
  }
  /* The last pass also negates dir and forms the slope g.dir. */
  double slope = 0.0;
  for (int c = count - 1; c >= 0; c--) {
    int slot = (sim->lb_head - 1 - c + m) % m;
    const double *sv = sim->lb_s + (size_t)slot * n3;
    double coef = sim->lb_alpha[slot] - next;
    if (c > 0) {
      int nslot = (sim->lb_head - c + m) % m;
      next = sim->lb_rho[nslot] * ss_par_axpy_dot(nt, part, n3, dir, coef, sv, sim->lb_y + (size_t)nslot * n3);
    } else {
      slope = ss_par_neg_axpy_dot(nt, part, n3, dir, coef, sv, g);
    }
  }
  if (count == 0) slope = ss_par_neg_axpy_dot(nt, part, n3, dir, 0.0, NULL, g);
  if (!(slope < 0.0) && sim->lb_count > 0) {
    /* Not a descent direction: drop the history, use -A^-1 g. */
    sim->lb_count = 0;
    if (preconditioned_gradient(s) != SS_DIR_OK) return SS_E_SOLVER;
  }
  st->solve_ms += ss_now_ms() - t1;
  return SS_DIR_OK;
}

static int qn_dir(ss_solve *s, int attempt) {
  if (attempt == 0) return lbfgs_direction(s);
  /* Retry once from the plain preconditioned gradient. */
  if (attempt == 1 && s->sim->lb_count > 0) {
    s->sim->lb_count = 0;
    return preconditioned_gradient(s);
  }
  return SS_DIR_NONE;
}

/* The new pair and its three dots in one pass. The point and gradient
 * before the step are where the accepted line search left them: it swapped
 * them into xt and gt (line_search.c), so no copy of them is kept. */
static void qn_accepted(ss_solve *s) {
  ss_sim *sim = s->sim;
  int n3 = 3 * sim->m->ndof, m = sim->lb_m;
  const double *xd = s->xd, *g = s->g;
  double *s_new = sim->lb_s + (size_t)sim->lb_head * n3, *y_new = sim->lb_y + (size_t)sim->lb_head * n3;
  double sums[3];
  ss_par_pair(sim->nthread, sim->par_part, n3, s_new, xd, s->xt, y_new, g, s->gt, sums);
  const double sy = sums[0], ss = sums[1], yy = sums[2];
  if (sy > 1e-12 * sqrt(ss * yy)) {
    sim->lb_rho[sim->lb_head] = 1.0 / sy;
    sim->lb_head = (sim->lb_head + 1) % m;
    if (sim->lb_count < m) sim->lb_count++;
  }
}

const ss_solver_ops ss_solver_qn_ops = {
    .safety_net = 1, .step_memory = 1, .begin = qn_begin, .direction = qn_dir, .tried = NULL, .accepted = qn_accepted};
