/* The one solver loop (solver.h): Newton and quasi-Newton plug their
 * directions into it; convergence, the iteration budget, the safety net,
 * round-off stalls and the statistics are decided here only.
 *
 * A solve starts with the energy and gradient at xd. Each iteration asks the
 * solver for its directions in order of preference and line-searches each
 * (line_search.c) until one takes a step; the gradient of the accepted point
 * is the next iteration's. It stops when the residual is within tol, when
 * the budget `iterations` is spent (a quasi-Newton substep still above
 * safety_residual, or with a face squeezed below SS_SAFETY_AREA of its rest
 * area, goes on up to iterations_max), when no direction decreases
 * E (stalled, or converged if within tol), or when E is flat to round-off
 * and the residual has not improved over SS_ROUNDOFF_STEPS accepted steps. */
#include <math.h>
#include <string.h>

#include "solver.h"
#include "ss_err.h"
#include "ss_vec.h"

static const ss_solver_ops *solver_ops(const ss_sim *sim) {
  return sim->set.solver == SS_SOLVER_NEWTON ? &ss_solver_newton_ops : &ss_solver_qn_ops;
}

int ss_solver_create(ss_sim *sim, char *err, int err_sz) {
  return sim->set.solver == SS_SOLVER_NEWTON ? ss_solver_newton_create(sim, err, err_sz)
                                             : ss_solver_qn_create(sim, err, err_sz);
}

/* After a line search returned ls (1 step taken, 2 step taken with E flat to
 * round-off, 0 no step, < 0 non-finite): judges round-off progress by the
 * residual, sets *converged, *stalled or *nonfinite and the step's residual
 * and energy; returns 1 to go on iterating, 0 to stop. */
static int after_line_search(ss_solve *s, int ls, double *best_res, int *roundoff_steps, int *converged,
                             int *stalled, int *nonfinite) {
  ss_sim *sim = s->sim;
  if (ls == 2) {
    /* E flat to round-off: progress is judged by the residual. */
    double r = ss_sim_residual(sim, s->g);
    *roundoff_steps = r < *best_res ? 0 : *roundoff_steps + 1;
    if (r < *best_res) *best_res = r;
    if (*roundoff_steps >= SS_ROUNDOFF_STEPS) ls = 0;
  }
  if (ls < 0) {
    *nonfinite = 2; /* xd is still the last finite iterate */
    return 0;
  }
  if (ls == 0) {
    ss_sim_stats *st = s->st;
    st->residual = ss_sim_residual(sim, s->g); /* g is at xd */
    st->energy = s->e;
    if (st->residual <= sim->set.tol)
      *converged = 1;
    else
      *stalled = 1;
    return 0;
  }
  return 1;
}

/* 1 if a simulated face at xfull (the iterate: the last evaluation's point)
 * has less than SS_SAFETY_AREA of its rest area. */
static int squeezed(const ss_sim *sim, const double *xfull) {
  for (int q = 0; q < sim->m->nsimface; q++) {
    const int f = sim->m->simface[q];
    const double rest = sim->m->rest_area[f];
    if (!(rest > 0.0)) continue;
    const int *fv = sim->m->faces + 3 * f;
    /* (2 A)^2 < (2 SS_SAFETY_AREA rest)^2, no square root */
    const double lim = 2.0 * SS_SAFETY_AREA * rest;
    if (tri_cross2(xfull + 3 * fv[0], xfull + 3 * fv[1], xfull + 3 * fv[2]) < lim * lim) return 1;
  }
  return 0;
}

int ss_solver_solve(ss_sim *sim, const ss_substep *in, ss_sim_stats *st, double *xd, int *converged,
                    int *stalled, int *nonfinite) {
  const ss_solver_ops *ops = solver_ops(sim);
  ss_solve s = {.sim = sim, .in = in, .st = st, .xd = xd, .g = sim->gd, .dir = sim->dir, .xt = sim->xt,
                .gt = sim->gt, .e = 0.0, .step_memory = ops->step_memory, .alpha0 = 1.0};
  *converged = *stalled = *nonfinite = 0;
  int roundoff_steps = 0;
  double best_res = INFINITY;
  int status = ops->begin(&s);
  if (status != SS_OK) return status;
  s.e = ss_sim_energy_at(sim, st, xd, s.g);
  const double t0 = ss_now_ms();
  ss_sim_normals_begin(sim, sim->xfull_t); /* xfull_t: xd scattered by the evaluation */
  st->orient_ms += ss_now_ms() - t0;
  double res = ss_sim_residual(sim, s.g);
  if (!isfinite(s.e) || !isfinite(res)) {
    *nonfinite = 1;
    return SS_OK;
  }
  for (int it = 0;; it++) {
    st->residual = res;
    st->energy = s.e;
    if (res <= sim->set.tol) {
      *converged = 1;
      break;
    }
    if (it >= sim->set.iterations) {
      /* past the budget: go on only while far from converged (safety net) */
      const int hard = sim->set.iterations_max > sim->set.iterations ? sim->set.iterations_max
                                                                      : sim->set.iterations;
      /* far from converged along the skin, where the membrane is crushed or
       * torn, not merely across it (ss_sim_residual_along <= res) */
      if (!ops->safety_net || !(sim->set.safety_residual > 0.0) || it >= hard ||
          !(ss_sim_residual_along(sim, s.g) > sim->set.safety_residual ||
            squeezed(sim, sim->xfull_t)))
        break;
    }
    st->iterations++;
    int ls = 0;
    for (int attempt = 0; ls == 0; attempt++) {
      int d = ops->direction(&s, attempt);
      if (d < 0) {
        status = d;
        break;
      }
      if (d == SS_DIR_NONE) break;
      if (d == SS_DIR_SKIP) continue;
      ls = ss_line_search(&s);
      if (ops->tried) ops->tried(&s, attempt, ls);
    }
    if (status != SS_OK) break;
    if (!after_line_search(&s, ls, &best_res, &roundoff_steps, converged, stalled, nonfinite)) break;
    if (ops->accepted) ops->accepted(&s);
    res = ss_sim_residual(sim, s.g);
  }
  /* the iterate back into the caller's array (accepted steps swap buffers) */
  if (s.xd != xd) memcpy(xd, s.xd, 3 * (size_t)sim->m->ndof * sizeof *xd);
  if (status != SS_OK) return status;
  /* the root mean square of the residual where the solve ended (g is at xd) */
  st->residual_rms = ss_sim_residual_rms(sim, s.g);
  return SS_OK;
}
