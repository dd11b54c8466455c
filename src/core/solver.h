/* Internal: the one solver loop and what a solver plugs into it.
 *
 * A step's implicit Euler system is minimised by one outer loop (solver.c):
 * energy and gradient at the start, convergence test, iteration budget and
 * the safety net (safety_residual / iterations_max), round-off stall
 * detection, statistics. Newton (solver_newton.c) and quasi-Newton
 * (solver_qn.c) differ only in how they compute a search direction; each
 * direction is tried with the one line search (line_search.c). A solver
 * offers its directions in order of preference (attempt 0, 1, ...): the loop
 * line-searches each until one takes a step. */
#ifndef SKIN_SIM_SOLVER_H
#define SKIN_SIM_SOLVER_H

#include "sim_internal.h"

/* One solve's state, owned by the loop; the solver reads and may update it. */
typedef struct ss_solve {
  ss_sim *sim;
  const ss_substep *in; /* the substep being solved (its h) */
  ss_sim_stats *st;     /* its step's counters */
  double *xd;      /* (ndof x 3) the iterate */
  double *g;       /* (ndof x 3) the gradient of E at xd */
  double *dir;     /* (ndof x 3) the direction a solver writes */
  double *xt, *gt; /* (ndof x 3) the line search's trial point and its gradient; an
                      accepted trial swaps with xd and g (no copy), so after it they
                      hold the point and gradient before the step (qn_accepted) */
  double e;        /* E at xd */
  int step_memory; /* the line search starts where the last one ended (ss_solver_ops) */
  double alpha0;   /* with step_memory: the next search's first trial step, in (0, 1] */
  int terms_first_trial; /* set by a direction from a matrix that has not learned every
                            term (quasi-Newton: the constant matrix and fewer curvature pairs
                            than the history holds): the search's first trial is at most the
                            one the energy terms give (ss_sim_energy_first_trial) */
  double own[4];   /* the solver's own state in this solve (its begin() sets it) */
} ss_solve;

/* What direction() returns besides an error code (< 0). */
enum { SS_DIR_NONE = 0, /* no further attempt this iteration */
       SS_DIR_OK = 1,   /* dir is set: line-search it */
       SS_DIR_SKIP = 2  /* nothing for this attempt: go to the next */ };

typedef struct ss_solver_ops {
  /* Whether a substep above safety_residual after `iterations` goes on up to
   * iterations_max (quasi-Newton; Newton stops at its budget). */
  int safety_net;
  /* Whether the line search remembers its step within a solve, starts at
   * the depth springs' model where the direction asks for it (depth_model)
   * and interpolates when it backtracks (quasi-Newton: its constant A knows
   * nothing of the stiff one-sided depth springs, so the full step is
   * mostly 3-4 times too long; Newton's full step is its model's minimum:
   * it halves from 1, which keeps the truth and references bit for bit). */
  int step_memory;
  /* Before the first energy evaluation of a solve (factorisations for a new
   * h, history reset). SS_OK or an error code. */
  int (*begin)(ss_solve *s);
  /* Attempt number `attempt` of this iteration: writes s->dir (a descent
   * direction) and returns SS_DIR_OK, or SS_DIR_SKIP / SS_DIR_NONE, or an
   * error code (< 0). */
  int (*direction)(ss_solve *s, int attempt);
  /* The line search's outcome ls (see ss_sim_line_search) for an attempt
   * that gave a direction (may be NULL). */
  void (*tried)(ss_solve *s, int attempt, int ls);
  /* After a step is taken and the loop goes on: s->xd, s->g, s->e are at the
   * new point (may be NULL). */
  void (*accepted)(ss_solve *s);
} ss_solver_ops;

extern const ss_solver_ops ss_solver_newton_ops;
extern const ss_solver_ops ss_solver_qn_ops;

/* ---- line_search.c ----
 * Backtracking line search along s->dir from s->xd (energy s->e, gradient
 * s->g), the energy and gradient of each trial point computed together. On
 * success xd, g, e are the accepted point (xd and g swapped with xt and gt;
 * g is the gradient there, the next iteration's gradient: no second
 * evaluation) and 1 is
 * returned (2 if E did not decrease: accepted by the approximate Wolfe
 * conditions, E flat to round-off); 0 if no step decreased E; -1 if
 * everything tried was non-finite. */
int ss_line_search(ss_solve *s);
/* Accepted steps in a row without progress, E flat to round-off, after
 * which a solve stops (stalled unless within tolerance). Progress across the
 * skin (ss_sim_residual) moves E by less than its round-off long before the
 * residual is within a tight tol: at 8, quasi-Newton gave up on the slivers
 * scene at 3e-9 to 2e-8 still improving, and reached 1e-9 with 32. */
#define SS_ROUNDOFF_STEPS 32
/* The safety net also goes on while a simulated face is squeezed below this
 * share of its rest area (twice the share a run counts as a failed frame):
 * a quasi-Newton substep with a small budget can end in a collapsed face
 * whose residual along the skin is already small (elbow, 200 frames, 2
 * substeps of 3 iterations: a face at 0.026 of its area, a failed frame;
 * with this net 0.196, 6.03 instead of 6.02 iterations per frame). */
#define SS_SAFETY_AREA 0.1

#endif
