/* Internal to the experiment library: small helpers shared by its modules. */
#ifndef SKIN_SIM_SS_UTIL_H
#define SKIN_SIM_SS_UTIL_H

/* Median of values[0..n) (sorted in place); 0 for an empty set. */
double ss_median(double *values, int n);

#endif
