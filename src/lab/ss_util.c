/* Small helpers shared by the experiments (ss_util.h). */
#include "ss_util.h"

#include <stdlib.h>

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double ss_median(double *values, int n) {
  if (n <= 0) return 0.0;
  qsort(values, (size_t)n, sizeof(double), cmp_double);
  return (n % 2) ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}
