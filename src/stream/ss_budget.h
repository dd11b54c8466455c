/* skin_sim stream: a real-time budget for a node's skin steps (the node library,
 * src/stream, not installed).
 *
 * A node on a robot's computer must finish each step within the input's
 * period, whatever else the computer is doing. The budget trades accuracy
 * for time in the order the error against the truth says is cheapest to
 * give up: substeps first (down to one), then iterations (down to one), and
 * buys them back in the reverse order when there is time again.
 *
 * Levels run from the settings' own (substeps S, iterations I: the most
 * work) down to 1 x 1: S x I, (S-1) x I, ..., 1 x I, 1 x (I-1), ..., 1 x 1.
 * After each step the node reports its wall time: when the median of the
 * last three steps at the level in force exceeds SS_BUDGET_HIGH of the
 * budget, the level drops to the highest one predicted (by work, substeps x
 * (iterations + SS_BUDGET_SUBSTEP_COST)) to take at most SS_BUDGET_TARGET of
 * it; after SS_BUDGET_HOLD steps at a level whose slowest recent step
 * predicts the level above under SS_BUDGET_LOW of the budget, it rises one
 * level. Lowering judges the median (one hiccup is not a trend), raising the
 * slowest (on a busy computer the slow steps are the ones that make the node
 * skip inputs), and the gap between the two thresholds keeps it from
 * hunting. Plain data, nothing allocated. */
#ifndef SKIN_SIM_SS_BUDGET_H
#define SKIN_SIM_SS_BUDGET_H

#ifdef __cplusplus
extern "C" {
#endif

#define SS_BUDGET_WINDOW 9
#define SS_BUDGET_HIGH 0.75         /* lower when the recent median passes this share */
#define SS_BUDGET_TARGET 0.6        /* ... to a level predicted at most this share */
#define SS_BUDGET_LOW 0.6           /* raise when the level above is predicted under this */
#define SS_BUDGET_HOLD 15           /* steps at a level before it may rise */
#define SS_BUDGET_SUBSTEP_COST 2.0  /* a substep's own work (posing, anchors), in iterations */

typedef struct ss_budget {
  int substeps_max, iterations_max; /* the settings': the most work */
  int substeps, iterations;         /* in force */
  double ms[SS_BUDGET_WINDOW];      /* wall times of the latest steps at the level in force */
  int nms, head;
  int held;                         /* steps at the level in force */
  long long lowered_steps;          /* steps taken below the settings' level, all told */
} ss_budget;

/* Starts at the settings' level (substeps, iterations >= 1; smaller values
 * are taken as 1). */
void ss_budget_init(ss_budget *b, int substeps, int iterations);
/* A step at the level in force took step_ms wall milliseconds, against a
 * budget of budget_ms (<= 0 or not finite: no budget, back to the settings'
 * level). Returns 1 if the level in force changed (b->substeps,
 * b->iterations), else 0. */
int ss_budget_update(ss_budget *b, double step_ms, double budget_ms);
/* 1 while the level in force is below the settings'. */
int ss_budget_lowered(const ss_budget *b);

#ifdef __cplusplus
}
#endif
#endif
