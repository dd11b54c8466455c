/* skin_sim core: the real-time budget of a node's skin steps (ss_budget.h). */
#include "ss_budget.h"

#include <math.h>

/* Levels are numbered from 0 (the settings': S x I) down the list
 * S x I, (S-1) x I, ..., 1 x I, 1 x (I-1), ..., 1 x 1. */
static int level_count(const ss_budget *b) { return b->substeps_max + b->iterations_max - 1; }

static void level_at(const ss_budget *b, int k, int *s, int *i) {
  if (k < b->substeps_max) {
    *s = b->substeps_max - k;
    *i = b->iterations_max;
  } else {
    *s = 1;
    *i = b->iterations_max - (k - b->substeps_max + 1);
  }
}

static int level_of(const ss_budget *b) {
  return b->substeps > 1 || b->iterations == b->iterations_max
             ? b->substeps_max - b->substeps
             : b->substeps_max - 1 + (b->iterations_max - b->iterations);
}

static double work(int s, int i) { return s * (i + SS_BUDGET_SUBSTEP_COST); }

static void set_level(ss_budget *b, int k) {
  level_at(b, k, &b->substeps, &b->iterations);
  b->nms = b->head = b->held = 0;
}

void ss_budget_init(ss_budget *b, int substeps, int iterations) {
  b->substeps_max = substeps > 1 ? substeps : 1;
  b->iterations_max = iterations > 1 ? iterations : 1;
  b->lowered_steps = 0;
  set_level(b, 0);
}

int ss_budget_lowered(const ss_budget *b) { return level_of(b) > 0; }

/* The slowest of the window's step times. */
static double window_max(const ss_budget *b) {
  double m = 0.0;
  for (int j = 0; j < b->nms; j++) m = b->ms[j] > m ? b->ms[j] : m;
  return m;
}

/* Median of the latest n (<= nms) step times. */
static double recent_median(const ss_budget *b, int n) {
  double v[SS_BUDGET_WINDOW];
  for (int j = 0; j < n; j++) {
    double x = b->ms[(b->head - 1 - j + 2 * SS_BUDGET_WINDOW) % SS_BUDGET_WINDOW];
    int k = j;
    for (; k > 0 && v[k - 1] > x; k--) v[k] = v[k - 1];
    v[k] = x;
  }
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int ss_budget_update(ss_budget *b, double step_ms, double budget_ms) {
  const int k = level_of(b);
  if (!(budget_ms > 0.0) || !isfinite(budget_ms)) {
    if (k == 0) return 0;
    set_level(b, 0);
    return 1;
  }
  if (k > 0) b->lowered_steps++;
  if (!isfinite(step_ms) || step_ms < 0.0) return 0;
  b->ms[b->head] = step_ms;
  b->head = (b->head + 1) % SS_BUDGET_WINDOW;
  if (b->nms < SS_BUDGET_WINDOW) b->nms++;
  b->held++;
  const int n = level_count(b);
  double w = work(b->substeps, b->iterations);
  if (b->nms >= 3 && k + 1 < n) {
    double med = recent_median(b, 3);
    if (med > SS_BUDGET_HIGH * budget_ms) {
      /* the highest level below predicted within the target, else the lowest */
      int to = k + 1;
      for (; to + 1 < n; to++) {
        int s, i;
        level_at(b, to, &s, &i);
        if (med * work(s, i) / w <= SS_BUDGET_TARGET * budget_ms) break;
      }
      set_level(b, to);
      return 1;
    }
  }
  if (k > 0 && b->held >= SS_BUDGET_HOLD) {
    int s, i;
    level_at(b, k - 1, &s, &i);
    if (window_max(b) * work(s, i) / w < SS_BUDGET_LOW * budget_ms) {
      set_level(b, k - 1);
      return 1;
    }
  }
  return 0;
}
