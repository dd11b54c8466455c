/* Internal: the contact pass's pre-test of a skin vertex in front of the
 * body's surface near it (collide_behind.c; collide.c, "Where, cheap
 * first"), and the distance to a body face both it and the pass's
 * descents and searches use. */
#ifndef SKIN_SIM_COLLIDE_BEHIND_H
#define SKIN_SIM_COLLIDE_BEHIND_H

#include <math.h>

#include "bvh.h"
#include "closest.h"
#include "collide.h"
#include "ss_vec.h"

/* Squared distance from q to the segment from 0 to e, and where on it
 * (*s in [0, 1]; 0 for a segment without length). */
static inline double ss_collide_edge_dist2(const double q[3], const double e[3], double *s) {
  const double ee = dot3(e, e), qe = dot3(q, e);
  const double t = qe <= 0.0 || !(ee > 0.0) ? 0.0 : qe >= ee ? 1.0 : qe / ee;
  double r2 = 0.0;
  for (int k = 0; k < 3; k++) r2 += (q[k] - t * e[k]) * (q[k] - t * e[k]);
  *s = t;
  return r2;
}

/* Squared distance from p to body face g (any face) and uv of its nearest
 * point (p0 + u e1 + v e2), from the face's frame record (walk.h): p's
 * projection onto the plane by the canonical map, inside the face its own
 * nearest point, else the nearest point of the edges it falls beyond (of a
 * convex polygon those hold the nearest point). A third of the comparisons
 * and products of ss_closest_point_triangle, which a face without an
 * inverse map (degenerate in this pose) takes. */
static inline double ss_collide_tri_dist2(const ss_collide_in *in, int g, const double p[3], double uv[2]) {
  const double *o = ss_frames_origin(in->fr, g);
  if (o[15] != 0.0) {
    const int *gv = in->topo->face_vert + 3 * g;
    return ss_closest_point_triangle(p, in->body + 3 * gv[0], in->body + 3 * gv[1], in->body + 3 * gv[2], uv);
  }
  const double *e1 = o + 3, *e2 = o + 6, *T = o + 9;
  const double d[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
  const double u = T[0] * d[0] + T[1] * d[1] + T[2] * d[2], v = T[3] * d[0] + T[4] * d[1] + T[5] * d[2];
  if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) {
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) {
      const double r = d[k] - u * e1[k] - v * e2[k];
      r2 += r * r;
    }
    uv[0] = u, uv[1] = v;
    return r2;
  }
  double best = INFINITY, s;
  if (v < 0.0) { /* beyond edge v0 v1 */
    best = ss_collide_edge_dist2(d, e1, &s), uv[0] = s, uv[1] = 0.0;
  }
  if (u < 0.0) { /* beyond edge v0 v2 */
    const double r2 = ss_collide_edge_dist2(d, e2, &s);
    if (r2 < best) best = r2, uv[0] = 0.0, uv[1] = s;
  }
  if (u + v > 1.0) { /* beyond edge v1 v2 */
    const double f[3] = {e2[0] - e1[0], e2[1] - e1[1], e2[2] - e1[2]};
    const double q[3] = {d[0] - e1[0], d[1] - e1[1], d[2] - e1[2]};
    const double r2 = ss_collide_edge_dist2(q, f, &s);
    if (r2 < best) best = r2, uv[0] = 1.0 - s, uv[1] = s;
  }
  return best;
}

/* 1 if p may be behind the body's surface at its nearest point within
 * bound (squared) of it: some face within bound has p less than lim in
 * front of its plane (a face without a normal counts). The tree of shape
 * s (boxes box, in in's pose; parent: each node's parent, -1 at the root)
 * is searched up from leaf, the leaf of a face near p. Allocates nothing;
 * reads only. */
int ss_collide_behind(const ss_bvh_shape *s, const double *box, const int *parent, int leaf,
                      const ss_collide_in *in, const double p[3], double bound, double lim);

#endif
