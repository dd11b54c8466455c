/* Projected Newton for the implicit Euler step, with CHOLMOD; and the
 * backtracking line search both solvers share.
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
 * element entries to slots are built once (sim_pattern.c), cholmod_analyze
 * (fill-reducing ordering, symbolic factor) runs once at create, then
 * cholmod_factorize per iteration and cholmod_solve2 with reused workspace.
 *
 * Line search: backtracking from the full step, Armijo's sufficient decrease
 * E(x + a d) <= E(x) + 1e-4 a g.d, halving a up to 40 times (Nocedal and
 * Wright, "Numerical Optimization", 3.1). Close to the minimum the decrease
 * g.d is below the round-off of E; a step is then also accepted by Hager and
 * Zhang's approximate Wolfe conditions (which use the slope, not E). A solver
 * whose energy does not decrease and whose residual does not improve over
 * SS_ROUNDOFF_STEPS accepted steps in a row has reached the floor of its
 * precision and stops (reported as stalled unless within tolerance). */
#include <math.h>
#include <string.h>

#include "sim_internal.h"
#include "ss_err.h"

static double dot(const double *a, const double *b, int n) {
  double s = 0.0;
  for (int i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

int ss_sim_after_line_search(ss_sim *sim, int ls, const double *g, double e, double *best_res,
                             int *roundoff_steps, int *converged, int *stalled, int *nonfinite) {
  if (ls == 2) {
    /* E flat to round-off: progress is judged by the residual. */
    double r = ss_sim_residual(sim, g);
    *roundoff_steps = r < *best_res ? 0 : *roundoff_steps + 1;
    if (r < *best_res) *best_res = r;
    if (*roundoff_steps >= SS_ROUNDOFF_STEPS) ls = 0;
  }
  if (ls < 0) {
    *nonfinite = 2; /* xd is still the last finite iterate */
    return 0;
  }
  if (ls == 0) {
    ss_sim_stats *st = sim->st;
    st->residual = ss_sim_residual(sim, g); /* g is at xd */
    st->energy = e;
    if (st->residual <= sim->set.tol)
      *converged = 1;
    else
      *stalled = 1;
    return 0;
  }
  return 1;
}

int ss_sim_line_search(ss_sim *sim, double *xd, double *gd, double *e, const double *dir) {
  int n3 = 3 * sim->ndof;
  double slope = dot(gd, dir, n3);
  if (!(slope < 0.0)) return 0;
  double alpha = 1.0;
  int any_finite = 0;
  for (int tries = 0; tries < 40; tries++, alpha *= 0.5) {
    for (int i = 0; i < n3; i++) sim->xt[i] = xd[i] + alpha * dir[i];
    double et = ss_sim_energy_at(sim, sim->xt, sim->gt);
    /* |g_t|^2 (finite?) and the slope g_t.d in one pass */
    double gg = 0.0, st_slope = 0.0;
    for (int i = 0; i < n3; i++) {
      gg += sim->gt[i] * sim->gt[i];
      st_slope += sim->gt[i] * dir[i];
    }
    if (!isfinite(et) || !isfinite(gg)) continue;
    any_finite = 1;
    /* Armijo, on the difference (exact for nearby values): it asks for a
     * strict decrease even when 1e-4 a g.d is below the last bit of E. */
    int armijo = et - *e <= 1e-4 * alpha * slope;
    /* Near the minimum the change of E drowns in round-off: Hager and
     * Zhang's approximate Wolfe conditions (CG_DESCENT, 2005), E not above
     * round-off and the slope along dir reduced: 0.9 s0 <= g_t.d <= 0.8 |s0|. */
    int roundoff = et <= *e + 1e-12 * fabs(*e) && st_slope >= 0.9 * slope && st_slope <= -0.8 * slope;
    if (armijo || roundoff) {
      memcpy(xd, sim->xt, (size_t)n3 * sizeof *xd);
      memcpy(gd, sim->gt, (size_t)n3 * sizeof *gd);
      int decreased = et < *e;
      *e = et;
      return decreased ? 1 : 2;
    }
  }
  return any_finite ? 0 : -1;
}

int ss_solver_newton_create(ss_sim *sim, char *err, int err_sz) {
  int n3 = 3 * sim->ndof;
  cholmod_common *cc = &sim->cc;
  sim->H = cholmod_allocate_sparse((size_t)n3, (size_t)n3, (size_t)sim->nnz3, 1, 1, 1, CHOLMOD_REAL, cc);
  sim->h_const = malloc((size_t)(sim->nnz3 ? sim->nnz3 : 1) * sizeof *sim->h_const);
  sim->nb = cholmod_zeros((size_t)n3, 1, CHOLMOD_REAL, cc);
  if (!sim->H || !sim->h_const || !sim->nb)
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the Newton matrix");
  int *p = sim->H->p, *ri = sim->H->i;
  for (int c = 0; c <= n3; c++) p[c] = sim->colp3[c];
  for (int j = 0; j < sim->ndof; j++) {
    for (int b = 0; b < 3; b++) {
      int s = sim->colp3[3 * j + b];
      for (int q = sim->bcolp[j]; q < sim->bcolp[j + 1]; q++) {
        int i = sim->brow[q];
        int last = i == j ? b : 2;
        for (int a = 0; a <= last; a++) ri[s++] = 3 * i + a;
      }
    }
  }
  sim->LH = cholmod_analyze(sim->H, cc);
  if (!sim->LH || cc->status < CHOLMOD_OK)
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD analysis of the Newton matrix failed (status %d)",
                   cc->status);
  /* One factorisation and solve now, on the constant part, so that the
   * factor's values and the solve workspace are allocated before stepping. */
  ss_sim_energy_begin(sim, sim->set.dt / sim->set.substeps);
  ss_sim_constant_hessian(sim, sim->h_const);
  sim->h_const_h = sim->h;
  memcpy(sim->H->x, sim->h_const, (size_t)sim->nnz3 * sizeof(double));
  if (!cholmod_factorize(sim->H, sim->LH, cc) || cc->status != CHOLMOD_OK ||
      !cholmod_solve2(CHOLMOD_A, sim->LH, sim->nb, NULL, &sim->nx, NULL, &sim->ny, &sim->ne, cc))
    return ss_fail(err, err_sz, SS_E_SOLVER, "CHOLMOD factorisation of the Newton matrix failed (status %d)",
                   cc->status);
  return SS_OK;
}

/* Newton direction dir = -H^-1 g at xd with the exact (exact != 0) or the
 * per-element projected elastic Hessian. Returns 1 on success, 0 if H is not
 * positive definite, or SS_E_SOLVER (< 0) if CHOLMOD failed. */
static int newton_direction(ss_sim *sim, const double *xd, const double *g, double *dir, int exact) {
  int n3 = 3 * sim->ndof;
  cholmod_common *cc = &sim->cc;
  ss_sim_stats *st = sim->st;
  double t0 = ss_now_ms();
  ss_sim_scatter(sim, xd, sim->xfull_t); /* a failed line search left a trial point there */
  double *vals = sim->H->x;
  memcpy(vals, sim->h_const, (size_t)sim->nnz3 * sizeof *vals);
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

int ss_solver_newton_solve(ss_sim *sim, double *xd, int *converged, int *stalled, int *nonfinite) {
  ss_sim_stats *st = sim->st;
  double *g = sim->gd, *dir = sim->dir;
  *converged = *stalled = *nonfinite = 0;
  int roundoff_steps = 0;
  double best_res = INFINITY;
  /* Projection on demand (in the spirit of Longva et al. 2023): the exact
   * Hessian where it is positive definite and its step decreases E
   * (quadratic convergence near the solution, where projecting element by
   * element leaves only a linear rate in compressed regions); else the
   * per-element projected one, trying the exact one again after 1, 2, 4, ...
   * iterations; else (no decrease either) a Jacobi-scaled gradient step. */
  int skip_exact = 0, backoff = 1;
  if (sim->h_const_h != sim->h) {
    ss_sim_constant_hessian(sim, sim->h_const);
    sim->h_const_h = sim->h;
  }
  double e = ss_sim_energy_at(sim, xd, g);
  double res = ss_sim_residual(sim, g);
  if (!isfinite(e) || !isfinite(res)) {
    *nonfinite = 1;
    return SS_OK;
  }
  for (int it = 0;; it++) {
    st->residual = res;
    st->energy = e;
    if (res <= sim->set.tol) {
      *converged = 1;
      break;
    }
    if (it >= sim->set.iterations) break;
    st->iterations++;
    int ls = 0;
    if (skip_exact == 0) {
      int d = newton_direction(sim, xd, g, dir, 1);
      if (d < 0) return SS_E_SOLVER;
      if (d > 0) ls = ss_sim_line_search(sim, xd, g, &e, dir);
      if (ls != 0) {
        backoff = 1;
      } else {
        skip_exact = backoff;
        backoff = backoff < 64 ? 2 * backoff : backoff;
      }
    } else {
      skip_exact--;
    }
    if (ls == 0) {
      int d = newton_direction(sim, xd, g, dir, 0);
      if (d < 0) return SS_E_SOLVER;
      if (d > 0) ls = ss_sim_line_search(sim, xd, g, &e, dir);
    }
    if (ls == 0) {
      /* No decrease along the projected step either (clamped eigenvalues can
       * leave it nearly orthogonal to -g deep in compression): a
       * Jacobi-scaled gradient step, a descent direction by construction. */
      for (int k = 0; k < sim->ndof; k++) {
        double inv = 1.0 / (sim->mi[k] + sim->diag_const[k]);
        for (int c = 0; c < 3; c++) dir[3 * k + c] = -inv * g[3 * k + c];
      }
      ls = ss_sim_line_search(sim, xd, g, &e, dir);
    }
    if (!ss_sim_after_line_search(sim, ls, g, e, &best_res, &roundoff_steps, converged, stalled,
                                  nonfinite))
      break;
    ss_sim_scatter(sim, xd, sim->xfull_t);
    res = ss_sim_residual(sim, g);
  }
  return SS_OK;
}
