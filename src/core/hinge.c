/* The skin's bending energy: a dihedral-angle hinge on each interior edge
 * (doc/model.md, "Bending"), energy = weight (theta - theta0)^2 with
 * weight = k |e_rest|^2 / A_e precomputed by the caller.
 *
 * Angle: vertices (e0, e1, o0, o1), faces A = (e0, e1, o0) and B = (e1, e0, o1)
 * with normals nA = e x (o0 - e0), nB = (e0 - e1) x (o1 - e1), e = e1 - e0.
 *   theta = atan2((nA x nB) . e/|e|, nA . nB)   in (-pi, pi], flat = 0.
 * Sign: theta > 0 where the surface is convex seen from the side its normals
 * point to (as everywhere on a sphere with outward normals); theta < 0 in a
 * valley (the wings fold up towards their normals). atan2 keeps it accurate
 * near 0 and near +-pi, where acos/asin lose precision.
 * theta - theta0 is wrapped into [-pi, pi] so the energy stays continuous when
 * the angle crosses the +-pi branch cut.
 *
 * Gradient (Bridson, Marino, Fedkiw 2003; Tamstorf & Grinspun 2013,
 * "Discrete bending forces and their Jacobians"): with |nA| = |e| hA,
 *   dtheta/do0 = -nA / (|nA| hA),  dtheta/do1 = -nB / (|nB| hB),
 *   dtheta/de0 = -(1 - tA) dtheta/do0 - (1 - tB) dtheta/do1,
 *   dtheta/de1 = -tA dtheta/do0 - tB dtheta/do1,
 * tA, tB the positions of o0, o1 projected on the edge (0 at e0, 1 at e1).
 *
 * Hessian: the Gauss-Newton part 2 weight grad(theta) grad(theta)^T, PSD by
 * construction and exact where theta = theta0. The dropped term
 * 2 weight (theta - theta0) Hess(theta) is indefinite; projected to PSD it
 * would add little stiffness while costing a 12x12 eigen-decomposition per
 * hinge, and bending is off by default (doc/model.md, "Bending").
 *
 * Degenerate hinge (zero-length edge or a zero-area wing): the angle is not
 * defined; the energy is still computed from whatever atan2 returns (finite)
 * and gradient and Hessian are zero. */
#include <math.h>
#include <string.h>

#include "energy.h"
#include "ss_vec.h"

typedef struct {
  double e[3], na[3], nb[3];
  double e_len2, na_len2, nb_len2;
  double theta;
} hinge_geometry;

static void hinge_geometry_init(const double x[12], hinge_geometry *g) {
  const double *e0 = x, *e1 = x + 3, *o0 = x + 6, *o1 = x + 9;
  double a0[3], b0[3], minus_e[3], m[3];
  for (int i = 0; i < 3; i++) {
    g->e[i] = e1[i] - e0[i];
    minus_e[i] = -g->e[i];
    a0[i] = o0[i] - e0[i];
    b0[i] = o1[i] - e1[i];
  }
  cross3(g->e, a0, g->na);
  cross3(minus_e, b0, g->nb);
  g->e_len2 = dot3(g->e, g->e);
  g->na_len2 = dot3(g->na, g->na);
  g->nb_len2 = dot3(g->nb, g->nb);
  cross3(g->na, g->nb, m);
  double e_len = sqrt(g->e_len2);
  double sine_part = e_len > 0.0 ? dot3(m, g->e) / e_len : 0.0;
  g->theta = atan2(sine_part, dot3(g->na, g->nb));
}

double ss_hinge_angle(const double x[12]) {
  hinge_geometry g;
  hinge_geometry_init(x, &g);
  return g.theta;
}

/* The angle difference wrapped into [-pi, pi]. */
static double wrapped_difference(double theta, double theta0) {
  double diff = theta - theta0;
  const double pi = 3.14159265358979323846, two_pi = 6.28318530717958647692;
  if (diff > pi) diff -= two_pi;
  if (diff < -pi) diff += two_pi;
  return diff;
}

double ss_hinge_eval(const double x[12], double theta0, double weight, double *grad,
                     double *hess) {
  hinge_geometry g;
  hinge_geometry_init(x, &g);
  double diff = wrapped_difference(g.theta, theta0);
  double energy = weight * diff * diff;
  if (!grad && !hess) return energy;

  double dtheta[12];
  /* A wing of height below 1e-12 |e| (or a zero edge) has no usable angle. */
  double tiny = 1e-24 * g.e_len2 * g.e_len2;
  int degenerate = !(g.e_len2 > 0.0) || !(g.na_len2 > tiny) || !(g.nb_len2 > tiny) ||
                   !isfinite(g.na_len2 + g.nb_len2 + g.e_len2);
  if (degenerate) {
    memset(dtheta, 0, sizeof dtheta);
  } else {
    const double *e0 = x, *o0 = x + 6, *o1 = x + 9;
    double e_len = sqrt(g.e_len2);
    double ta = 0.0, tb = 0.0;
    for (int i = 0; i < 3; i++) {
      ta += (o0[i] - e0[i]) * g.e[i];
      tb += (o1[i] - e0[i]) * g.e[i];
    }
    ta /= g.e_len2;
    tb /= g.e_len2;
    double sa = -e_len / g.na_len2, sb = -e_len / g.nb_len2;
    for (int i = 0; i < 3; i++) {
      double d_o0 = sa * g.na[i], d_o1 = sb * g.nb[i];
      dtheta[6 + i] = d_o0;
      dtheta[9 + i] = d_o1;
      dtheta[i] = -(1.0 - ta) * d_o0 - (1.0 - tb) * d_o1;
      dtheta[3 + i] = -ta * d_o0 - tb * d_o1;
    }
  }
  if (grad)
    for (int i = 0; i < 12; i++) grad[i] = 2.0 * weight * diff * dtheta[i];
  if (hess) {
    /* A negative weight would make the Gauss-Newton term indefinite. */
    double w2 = weight > 0.0 ? 2.0 * weight : 0.0;
    for (int r = 0; r < 12; r++)
      for (int c = r; c < 12; c++) hess[12 * r + c] = hess[12 * c + r] = w2 * dtheta[r] * dtheta[c];
  }
  return energy;
}
