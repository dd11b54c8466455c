/* Projected Newton for the implicit Euler step, with CHOLMOD.
 *
 * Each iteration assembles H = (inertia + springs, constant per h) + the
 * elastic Hessian and factors it. It first tries the exact membrane Hessian;
 * if CHOLMOD finds that H is not positive definite, or its step does not
 * decrease E, it assembles the sum of per-element Hessians each projected to
 * PSD (membrane: closed-form eigensystem; hinge: Gauss-Newton), positive
 * definite with the mass, so that -H^-1 g is a descent direction (Teran et al.
 * 2005 "Robust quasistatic finite elements"; Smith et al. 2018), and tries the
 * exact one again after an exponentially growing wait (projection on demand;
 * Longva et al. 2023, "Pitfalls of projection"). If even that step finds no
 * decrease, a Jacobi-scaled gradient step is taken. H is a 3n x 3n symmetric matrix with its
 * upper triangle stored in compressed columns; its pattern and the map from
 * element entries to slots are built once (model_pattern.c), cholmod_analyze
 * (fill-reducing ordering, symbolic factor) runs once per model (each sim
 * copies its symbolic factor), then
 * cholmod_factorize per iteration and cholmod_solve2 with reused workspace.
 *
 * The outer loop, the line search and convergence are solver.c's and
 * line_search.c's; this file gives the directions: exact Newton, projected
 * Newton, Jacobi-scaled gradient, in that order (ss_solver_newton_ops). */
#include <math.h>
#include <string.h>

#include "solver.h"
#include "ss_err.h"

/* The pattern of H: each block of the model's block pattern expanded to
 * 3 x 3 (upper triangle of the diagonal blocks). */
static void hessian_pattern(const ss_model *m, cholmod_sparse *H) {
  int *p = H->p, *ri = H->i;
  for (int c = 0; c <= 3 * m->ndof; c++) p[c] = m->colp3[c];
  for (int j = 0; j < m->ndof; j++) {
    for (int b = 0; b < 3; b++) {
      int s = m->colp3[3 * j + b];
      for (int q = m->bcolp[j]; q < m->bcolp[j + 1]; q++) {
        int i = m->brow[q];
        int last = i == j ? b : 2;
        for (int a = 0; a <= last; a++) ri[s++] = 3 * i + a;
      }
    }
  }
}

int ss_solver_newton_analyze(ss_model *m, char *err, int err_sz) {
  cholmod_common *cc = &m->cc;
  const size_t n3 = 3 * (size_t)m->ndof;
  /* the analysis reads the pattern alone: no values; cc keeps CHOLMOD's
   * defaults (supernodal or simplicial as it judges), as each sim's does */
  cholmod_sparse *H = cholmod_allocate_sparse(n3, n3, (size_t)m->nnz3, 1, 1, 1, CHOLMOD_PATTERN, cc);
  if (!H) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the Newton analysis");
  hessian_pattern(m, H);
  m->sym_newton = cholmod_analyze(H, cc);
  cholmod_free_sparse(&H, cc);
  if (!m->sym_newton || cc->status < CHOLMOD_OK)
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD analysis of the Newton matrix failed (status %d)",
                   cc->status);
  return SS_OK;
}

int ss_solver_newton_create(ss_sim *sim, char *err, int err_sz) {
  int n3 = 3 * sim->m->ndof;
  cholmod_common *cc = &sim->cc;
  sim->H = cholmod_allocate_sparse((size_t)n3, (size_t)n3, (size_t)sim->m->nnz3, 1, 1, 1, CHOLMOD_REAL, cc);
  sim->nb = cholmod_zeros((size_t)n3, 1, CHOLMOD_REAL, cc);
  if (!sim->H || !sim->nb)
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the Newton matrix");
  hessian_pattern(sim->m, sim->H);
  /* The model's symbolic factor, copied (numeric factorisations are this
   * sim's); analysed here only on a model built for quasi-Newton. */
  sim->LH = sim->m->sym_newton ? cholmod_copy_factor(sim->m->sym_newton, cc) : cholmod_analyze(sim->H, cc);
  if (!sim->LH || cc->status < CHOLMOD_OK)
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD analysis of the Newton matrix failed (status %d)",
                   cc->status);
  /* One factorisation and solve now, on the constant part, so that the
   * factor's values and the solve workspace are allocated before stepping. */
  const double h = sim->set.dt / sim->set.substeps;
  ss_sim_energy_begin(sim, h);
  ss_sim_constant_hessian(sim, sim->h_const);
  sim->h_const_h = h;
  memcpy(sim->H->x, sim->h_const, (size_t)sim->m->nnz3 * sizeof(double));
  if (!cholmod_factorize(sim->H, sim->LH, cc) || cc->status != CHOLMOD_OK ||
      !cholmod_solve2(CHOLMOD_A, sim->LH, sim->nb, NULL, &sim->nx, NULL, &sim->ny, &sim->ne, cc))
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD factorisation of the Newton matrix failed (status %d)",
                   cc->status);
  return SS_OK;
}

/* Newton direction dir = -H^-1 g at xd with the exact (exact != 0) or the
 * per-element projected elastic Hessian. Returns 1 on success, 0 if H is not
 * positive definite, or SS_E_SOLVER (< 0) if CHOLMOD failed. */
static int newton_direction(ss_sim *sim, ss_sim_stats *st, const double *xd, const double *g, double *dir,
                            int exact) {
  int n3 = 3 * sim->m->ndof;
  cholmod_common *cc = &sim->cc;
  double t0 = ss_now_ms();
  ss_sim_scatter(sim, xd, sim->xfull_t); /* a failed line search left a trial point there */
  double *vals = sim->H->x;
  memcpy(vals, sim->h_const, (size_t)sim->m->nnz3 * sizeof *vals);
  ss_sim_add_elastic_hessian(sim, sim->xfull_t, vals, exact);
  double t1 = ss_now_ms();
  st->assemble_ms += t1 - t0;
  int ok = cholmod_factorize(sim->H, sim->LH, cc);
  st->factorizations++;
  double t2 = ss_now_ms();
  st->factor_ms += t2 - t1;
  if (!ok || cc->status < CHOLMOD_OK) return SS_E_SOLVER;
  if (cc->status == CHOLMOD_NOT_POSDEF) return 0;
  double *b = sim->nb->x;
  for (int i = 0; i < n3; i++) b[i] = -g[i];
  if (!cholmod_solve2(CHOLMOD_A, sim->LH, sim->nb, NULL, &sim->nx, NULL, &sim->ny, &sim->ne, cc))
    return SS_E_SOLVER;
  memcpy(dir, sim->nx->x, (size_t)n3 * sizeof *dir);
  st->solve_ms += ss_now_ms() - t2;
  return 1;
}

/* Newton's own state in a solve (ss_solve's `own`). */
typedef struct newton_state {
  int skip_exact; /* iterations left before the exact Hessian is tried again */
  int backoff;    /* the next wait after a failed exact step */
} newton_state;
_Static_assert(sizeof(newton_state) <= sizeof(((ss_solve *)0)->own), "newton_state fits ss_solve's own");

static newton_state *own(ss_solve *s) { return (newton_state *)(void *)s->own; }

static int newton_begin(ss_solve *s) {
  ss_sim *sim = s->sim;
  *own(s) = (newton_state){.skip_exact = 0, .backoff = 1};
  if (sim->h_const_h != s->in->h) {
    ss_sim_constant_hessian(sim, sim->h_const);
    sim->h_const_h = s->in->h;
  }
  return SS_OK;
}

/* A failed exact step: wait 1, 2, 4, ... (at most 64) iterations before the
 * exact Hessian is tried again. */
static void exact_failed(ss_solve *s) {
  newton_state *ns = own(s);
  ns->skip_exact = ns->backoff;
  ns->backoff = ns->backoff < 64 ? 2 * ns->backoff : ns->backoff;
}

/* Projection on demand (in the spirit of Longva et al. 2023): the exact
 * Hessian where it is positive definite and its step decreases E (quadratic
 * convergence near the solution, where projecting element by element leaves
 * only a linear rate in compressed regions); else the per-element projected
 * one, trying the exact one again after 1, 2, 4, ... iterations; else (no
 * decrease either) a Jacobi-scaled gradient step. */
static int newton_dir(ss_solve *s, int attempt) {
  ss_sim *sim = s->sim;
  int d;
  switch (attempt) {
  case 0:
    if (own(s)->skip_exact > 0) {
      own(s)->skip_exact--;
      return SS_DIR_SKIP;
    }
    d = newton_direction(sim, s->st, s->xd, s->g, s->dir, 1);
    if (d < 0) return d;
    if (d == 0) exact_failed(s);
    return d > 0 ? SS_DIR_OK : SS_DIR_SKIP;
  case 1:
    d = newton_direction(sim, s->st, s->xd, s->g, s->dir, 0);
    if (d < 0) return d;
    return d > 0 ? SS_DIR_OK : SS_DIR_SKIP;
  case 2:
    /* No decrease along the projected step either (clamped eigenvalues can
     * leave it nearly orthogonal to -g deep in compression): a Jacobi-scaled
     * gradient step, a descent direction by construction. */
    for (int k = 0; k < sim->m->ndof; k++) {
      double inv = 1.0 / (sim->mi[k] + sim->m->diag_const[k]);
      for (int c = 0; c < 3; c++) s->dir[3 * k + c] = -inv * s->g[3 * k + c];
    }
    return SS_DIR_OK;
  default:
    return SS_DIR_NONE;
  }
}

static void newton_tried(ss_solve *s, int attempt, int ls) {
  if (attempt != 0) return;
  if (ls != 0)
    own(s)->backoff = 1;
  else
    exact_failed(s);
}

const ss_solver_ops ss_solver_newton_ops = {
    .safety_net = 0, .step_memory = 0, .begin = newton_begin, .direction = newton_dir, .tried = newton_tried, .accepted = NULL};
