/* ss_budget.h: the real-time budget lowers substeps, then iterations, until a
 * step fits; raises them again when there is time; does not hunt between
 * levels under a steady load; and goes back to the settings without a budget. */
#include "ss_budget.h"
#include "ss_test.h"

/* A machine where a step costs unit ms per unit of work (plus noise). */
static double cost(const ss_budget *b, double unit, unsigned long long *seed) {
  double noise = seed ? 0.9 + 0.2 * ss_test_rand(seed) : 1.0;
  return unit * b->substeps * (b->iterations + SS_BUDGET_SUBSTEP_COST) * noise;
}

int main(void) {
  ss_budget b;
  ss_budget_init(&b, 4, 2);
  CHECK(b.substeps == 4 && b.iterations == 2 && !ss_budget_lowered(&b));

  /* 2 ms a unit of work: 4 x 2 costs 32 ms, over 0.8 of a 33 ms budget */
  unsigned long long seed = 7;
  int changes = 0;
  for (int k = 0; k < 300; k++) changes += ss_budget_update(&b, cost(&b, 2.0, &seed), 33.0);
  CHECK(ss_budget_lowered(&b));
  CHECK_MSG(cost(&b, 2.0, NULL) <= 0.8 * 33.0, "still over: %d x %d", b.substeps, b.iterations);
  /* substeps go first: iterations stay while substeps are above one */
  CHECK(b.iterations == 2);
  /* no hunting: it settled after a few changes */
  CHECK_MSG(changes <= 3, "%d level changes under a steady load", changes);
  int s_settled = b.substeps;
  CHECK(s_settled >= 2);

  /* a busier machine (5 ms a unit): down to one substep, then fewer iterations */
  for (int k = 0; k < 100; k++) ss_budget_update(&b, cost(&b, 5.0, &seed), 33.0);
  CHECK(b.substeps == 1 && b.iterations == 2);
  for (int k = 0; k < 100; k++) ss_budget_update(&b, cost(&b, 12.0, &seed), 33.0);
  CHECK(b.substeps == 1 && b.iterations == 1);
  /* the lowest level stays whatever the load: never below 1 x 1 */
  for (int k = 0; k < 100; k++) ss_budget_update(&b, 500.0, 33.0);
  CHECK(b.substeps == 1 && b.iterations == 1);
  CHECK(b.lowered_steps > 0);

  /* the machine frees up: back up level by level to the settings' */
  for (int k = 0; k < 400; k++) ss_budget_update(&b, cost(&b, 0.5, &seed), 33.0);
  CHECK(b.substeps == 4 && b.iterations == 2 && !ss_budget_lowered(&b));

  /* no budget: straight back to the settings */
  for (int k = 0; k < 50; k++) ss_budget_update(&b, cost(&b, 5.0, &seed), 33.0);
  CHECK(ss_budget_lowered(&b));
  CHECK(ss_budget_update(&b, 100.0, 0.0) == 1);
  CHECK(b.substeps == 4 && b.iterations == 2);
  CHECK(ss_budget_update(&b, 100.0, -1.0) == 0);

  /* nonsense times change nothing */
  ss_budget_init(&b, 3, 3);
  for (int k = 0; k < 20; k++) CHECK(ss_budget_update(&b, -1.0, 33.0) == 0);
  CHECK(b.substeps == 3 && b.iterations == 3);

  /* one slow step (a hiccup) is not enough to lower it: the median of three */
  ss_budget_init(&b, 4, 2);
  for (int k = 0; k < 10; k++) ss_budget_update(&b, 10.0, 33.0);
  CHECK(ss_budget_update(&b, 200.0, 33.0) == 0);
  CHECK(ss_budget_update(&b, 10.0, 33.0) == 0);
  CHECK(b.substeps == 4);

  /* a settings level of 1 x 1 has nowhere to go */
  ss_budget_init(&b, 0, 0);
  CHECK(b.substeps == 1 && b.iterations == 1);
  for (int k = 0; k < 10; k++) CHECK(ss_budget_update(&b, 1000.0, 33.0) == 0);
  return ss_test_finish("test_budget");
}
