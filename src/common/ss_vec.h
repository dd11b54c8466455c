/* Internal: 3-vector helpers shared by the core and the lab (flat double[3]). */
#ifndef SKIN_SIM_SS_VEC_H
#define SKIN_SIM_SS_VEC_H

#include <math.h>

/* One third as a factor: barycenters and the barycenter springs' shares are
 * products by it, not quotients by 3 (six divisions per face in the
 * membrane kernel and three on every barycenter anchor's walk, where a
 * division is a long latency on the dependency chain; a product differs from
 * the quotient by at most an ulp). */
#define SS_THIRD (1.0 / 3.0)

/* max(m, x) and min(m, x) for an m that is not NaN, x dropped where it is
 * NaN: fmax and fmin then, inline (those are calls into libm, whose
 * NaN handling the compiler may not assume away: 12 of them per closest
 * point on a triangle, which the tether asks for two anchors in five per
 * substep). */
static inline double max_keep(double m, double x) { return x > m ? x : m; }
static inline double min_keep(double m, double x) { return x < m ? x : m; }

static inline double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void cross3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* (b - a) x (c - a): triangle abc's normal, twice its area long. The edges
 * in scalars: through two arrays (a loop the compiler kept) they would be
 * stored element by element and read back two at a time, a load that
 * cannot be forwarded. The operations of cross3. */
static inline void tri_area_vector(const double a[3], const double b[3], const double c[3], double n[3]) {
  const double e1x = b[0] - a[0], e1y = b[1] - a[1], e1z = b[2] - a[2];
  const double e2x = c[0] - a[0], e2y = c[1] - a[1], e2z = c[2] - a[2];
  n[0] = e1y * e2z - e1z * e2y;
  n[1] = e1z * e2x - e1x * e2z;
  n[2] = e1x * e2y - e1y * e2x;
}

/* |(b - a) x (c - a)|^2: the squared doubled area of triangle abc (area
 * ratios and the safety net's squeezed-face test take it without a root). */
static inline double tri_cross2(const double a[3], const double b[3], const double c[3]) {
  double n[3];
  tri_area_vector(a, b, c, n);
  return dot3(n, n);
}

/* |a - b| */
static inline double dist3(const double a[3], const double b[3]) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

#endif
