/* The backtracking line search both solvers use (solver.h).
 *
 * Backtracking from the full step, Armijo's sufficient decrease
 * E(x + a d) <= E(x) + 1e-4 a g.d, halving a up to 40 times (Nocedal and
 * Wright, "Numerical Optimization", 3.1). Each trial point's energy and
 * gradient are computed in one evaluation; the accepted point's gradient is
 * the next iteration's, so a full step that is accepted costs exactly one
 * evaluation. Close to the minimum the decrease g.d is below the round-off
 * of E; a step is then also accepted by Hager and Zhang's approximate Wolfe
 * conditions (which use the slope, not E).
 *
 * With step_memory (quasi-Newton) a search starts at twice the step the last
 * one took in this solve (at most 1), or where the direction asks for it
 * (terms_first_trial) at the first trial the energy terms give
 * (ss_sim_energy_first_trial: the minimum of the orient term's depth springs
 * along dir plus a quadratic model of the rest of E) where that is shorter, and a rejected trial is
 * followed by the secant estimate of the minimum along dir, alpha s0 / (s0 -
 * g_t.d) from the slopes at 0 and at the trial point (both known), kept
 * within [0.1, 0.5] of the trial step. The quasi-Newton direction from the
 * constant matrix A is mostly 3-4 times too long where the depth springs act
 * (stiff, one-sided, not in A): halving from 1 would spend two or three
 * energy evaluations per iteration on refused trials; the step memory, the
 * secant and the springs' model bring a search close to one evaluation, and
 * the error against the truth falls at every budget (doc/model.md,
 * "Solvers"; doc/benchmarks.md). */
#include <math.h>

#include "solver.h"

/* Times its own work into linesearch_ms: the whole search less the energy
 * evaluations, which ss_sim_energy_at counts in assemble_ms. */
static int line_search(ss_solve *s);

int ss_line_search(ss_solve *s) {
  const double t0 = ss_now_ms(), asm0 = s->st->assemble_ms;
  const int ls = line_search(s);
  s->st->linesearch_ms += ss_now_ms() - t0 - (s->st->assemble_ms - asm0);
  return ls;
}

static int line_search(ss_solve *s) {
  ss_sim *sim = s->sim;
  int n3 = 3 * sim->m->ndof;
  const double *dir = s->dir;
  const double *xd = s->xd;
  double *xt = s->xt, *gt = s->gt;
  /* the vector passes on the sim's threads, their sums by blocks (par.h) */
  const int nt = sim->nthread;
  double *part = sim->par_part;
  const double slope = ss_par_dot(nt, part, n3, s->g, dir);
  if (!(slope < 0.0)) return 0;
  double alpha = s->step_memory && s->alpha0 > 0.0 && s->alpha0 < 1.0 ? s->alpha0 : 1.0;
  if (s->step_memory && s->terms_first_trial) {
    const double model = ss_sim_energy_first_trial(sim, xd, dir, slope);
    if (model < alpha) alpha = model;
  }
  int any_finite = 0;
  for (int tries = 0; tries < 40; tries++) {
    ss_par_axpy(nt, part, n3, xt, xd, alpha, dir);
    double et = ss_sim_energy_at(sim, s->st, xt, gt);
    /* |g_t|^2 (finite?) and the slope g_t.d in one pass */
    double gg, st_slope;
    ss_par_norm2_dot(nt, part, n3, gt, dir, &gg, &st_slope);
    if (!isfinite(et) || !isfinite(gg)) {
      alpha *= 0.5;
      continue;
    }
    any_finite = 1;
    /* Armijo, on the difference (exact for nearby values): it asks for a
     * strict decrease even when 1e-4 a g.d is below the last bit of E. */
    int armijo = et - s->e <= 1e-4 * alpha * slope;
    /* Near the minimum the change of E drowns in round-off: Hager and
     * Zhang's approximate Wolfe conditions (CG_DESCENT, 2005), E not above
     * round-off and the slope along dir reduced: 0.9 s0 <= g_t.d <= 0.8 |s0|. */
    int roundoff = et <= s->e + 1e-12 * fabs(s->e) && st_slope >= 0.9 * slope && st_slope <= -0.8 * slope;
    if (armijo || roundoff) {
      s->xt = s->xd, s->xd = xt;
      s->gt = s->g, s->g = gt;
      int decreased = et < s->e;
      if (s->step_memory) s->alpha0 = 2.0 * alpha < 1.0 ? 2.0 * alpha : 1.0;
      s->e = et;
      return decreased ? 1 : 2;
    }
    double next = 0.5 * alpha;
    if (s->step_memory && st_slope > slope) {
      /* where the slope would vanish if it grew linearly from s0 to g_t.d */
      next = alpha * slope / (slope - st_slope);
      if (!(next <= 0.5 * alpha)) next = 0.5 * alpha;
      if (!(next >= 0.1 * alpha)) next = 0.1 * alpha;
    }
    alpha = next;
  }
  return any_finite ? 0 : -1;
}
