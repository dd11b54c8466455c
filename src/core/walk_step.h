/* Internal: the arithmetic of one ray step of the walk (walk.c), inline,
 * shared by the walk and by the anchor pass (sim.c), which runs the leash's
 * slide (ss_slide_in_face) for every anchor in each of its instruction sets
 * (isa.h): a call per anchor, and the slide compiled for SSE2 only, cost the
 * anchor stage instructions. The walk itself stays in walk.c, called: inlined
 * into the pass as well, it made the stage slower. */
#ifndef SKIN_SIM_WALK_STEP_H
#define SKIN_SIM_WALK_STEP_H

#include <math.h>

#include "isa.h"
#include "walk.h"

/* 1 where x, y are both finite: x - x is 0 for a finite x and NaN for an
 * infinite or NaN one, and a sum with a NaN is NaN (two subtractions, an
 * add and one compare, where isfinite takes a mask and a compare each: the
 * walk tests two or three values at every ray step). */
static inline SS_ALWAYS_INLINE int finite2(double x, double y) { return (x - x) + (y - y) == 0.0; }

/* Clamps (u, v) into the canonical triangle; non-finite becomes the barycenter.
 * On two scalars, inline: the walk keeps its point in registers (through an
 * array and a call, the two stores and the vector load that read them back
 * could not be forwarded, twice per walk: a third of a walk that stays in
 * its face). */
static inline SS_ALWAYS_INLINE void clamp_uv(double *u_io, double *v_io) {
  double u = *u_io, v = *v_io;
  if (!finite2(u, v)) {
    *u_io = *v_io = 1.0 / 3.0;
    return;
  }
  if (u < 0.0) u = 0.0;
  if (v < 0.0) v = 0.0;
  double s = u + v;
  if (s > 1.0) {
    u /= s;
    v /= s;
  }
  *u_io = u;
  *v_io = v;
}

/* World length of the canonical displacement (du, dv) on face f: |Dm (du, dv)|. */
static inline double canonical_length(const double *e, double du, double dv) {
  double x = du * e[0] + dv * e[3], y = du * e[1] + dv * e[4], z = du * e[2] + dv * e[5];
  return sqrt(x * x + y * y + z * z);
}

/* The result of a walk or slide that ends in `face` at (u, v) without
 * crossing an edge (the walk's start, the slide's end). */
static inline SS_ALWAYS_INLINE void result_in_face(ss_walk_result *res, int face, double u, double v,
                                                   double length) {
  res->face = face;
  res->uv[0] = u;
  res->uv[1] = v;
  res->stop = SS_STOP_INSIDE;
  res->steps = 0;
  res->length = length;
}

/* The ray of a walk step from canonical point (pu, pv) of the face whose
 * record is w towards world point a: its canonical direction (du, dv). The
 * arithmetic and its order are those of dot3 and face_point. */
static inline SS_ALWAYS_INLINE void ray_direction(const double *w, double pu, double pv, double ax, double ay,
                                                  double az, double *du, double *dv) {
  const double dx = ax - (w[0] + pu * w[3] + pv * w[6]);
  const double dy = ay - (w[1] + pu * w[4] + pv * w[7]);
  const double dz = az - (w[2] + pu * w[5] + pv * w[8]);
  *du = w[9] * dx + w[10] * dy + w[11] * dz;
  *dv = w[12] * dx + w[13] * dy + w[14] * dz;
}

/* The point of the canonical triangle nearest (in the face's own metric,
 * G = Dm^T Dm: world distance in its plane) to canonical point (qu, qv)
 * outside it, which lies beyond the edges flagged (u < 0: edge 2, u + v > 1:
 * edge 1, v < 0: edge 0; at least one, at most two). The nearest point of a
 * convex polygon to a point outside lies on an edge the point is beyond:
 * each such edge's nearest point (the projection in G, clamped to the edge),
 * the nearer of them. Selects, not branches: which edge wins is as
 * unpredictable as where a skin pulls, so the general closest point on a
 * triangle (ss_closest_point_triangle, which branches on the region) would
 * mispredict. e are the face's edges e1, e2. */
static inline SS_ALWAYS_INLINE void nearest_in_face(const double *e, int out2, int out1, int out0,
                                                    double *qu_io, double *qv_io) {
  const double qu = *qu_io, qv = *qv_io;
  const double a = e[0] * e[0] + e[1] * e[1] + e[2] * e[2]; /* e1.e1 */
  const double b = e[0] * e[3] + e[1] * e[4] + e[2] * e[5]; /* e1.e2 */
  const double c = e[3] * e[3] + e[4] * e[4] + e[5] * e[5]; /* e2.e2 */
  /* edge 0 (v = 0): (t, 0); edge 2 (u = 0): (0, t); edge 1: (1 - t, t) */
  double t0 = qu + b * qv / a, t2 = qv + b * qu / c;
  double t1 = ((c - b) * qv + (a - b) * (1.0 - qu)) / (a + c - 2.0 * b);
  t0 = t0 < 0.0 ? 0.0 : t0 > 1.0 ? 1.0 : t0;
  t1 = t1 < 0.0 ? 0.0 : t1 > 1.0 ? 1.0 : t1;
  t2 = t2 < 0.0 ? 0.0 : t2 > 1.0 ? 1.0 : t2;
  const double u0 = t0 - qu, v0 = -qv, u1 = 1.0 - t1 - qu, v1 = t1 - qv, u2 = -qu, v2 = t2 - qv;
  double d0 = a * u0 * u0 + 2.0 * b * u0 * v0 + c * v0 * v0;
  double d1 = a * u1 * u1 + 2.0 * b * u1 * v1 + c * v1 * v1;
  double d2 = a * u2 * u2 + 2.0 * b * u2 * v2 + c * v2 * v2;
  d0 = out0 ? d0 : INFINITY;
  d1 = out1 ? d1 : INFINITY;
  d2 = out2 ? d2 : INFINITY;
  double nu = d0 <= d1 ? t0 : 1.0 - t1, nv = d0 <= d1 ? 0.0 : t1;
  const double dm = d0 <= d1 ? d0 : d1;
  nu = d2 < dm ? 0.0 : nu;
  nv = d2 < dm ? t2 : nv;
  *qu_io = nu;
  *qv_io = nv;
}

/* The slide of an anchor on a leash (see walk.h). Its first part is the
 * walk's first ray step, in the same order of operations, so that a slide
 * ending inside the face is the walk's to the bit. */
static inline SS_ALWAYS_INLINE int ss_slide_in_face_inline(const ss_frames *fr, int face, const double uv[2],
                                                           const double target[3], int measure,
                                                           ss_walk_result *res) {
  double pu = uv[0], pv = uv[1];
  clamp_uv(&pu, &pv);
  const double ax = target[0], ay = target[1], az = target[2];
  if (!finite2(ax, ay) || !finite2(az, 0.0)) return 0;
  const double *w = fr->walk + SS_FRAME_RECORD * (size_t)face;
  double du, dv;
  ray_direction(w, pu, pv, ax, ay, az, &du, &dv);
  if (!finite2(du, dv)) return 0;
  const double sum = du + dv, rest = 1.0 - pu - pv;
  double qu = pu + du, qv = pv + dv;
  if (qv >= 0.0 && (!(sum > 0.0) || rest >= sum) && qu >= 0.0) {
    clamp_uv(&qu, &qv); /* inside: where the walk ends */
  } else {
    /* outside: within reach, the face's point nearest the target */
    const double qw = 1.0 - qu - qv;
    const double lowest = qu < qv ? (qu < qw ? qu : qw) : (qv < qw ? qv : qw);
    if (!(lowest > -SS_LEASH_REACH) || w[15] != 0.0) return 0; /* far, or a degenerate face */
    /* the edges beyond which the walk's test above put it (one at least) */
    nearest_in_face(w + 3, !(qu >= 0.0), sum > 0.0 && rest < sum, !(qv >= 0.0), &qu, &qv);
    clamp_uv(&qu, &qv);
  }
  result_in_face(res, face, qu, qv, measure ? canonical_length(w + 3, qu - pu, qv - pv) : 0.0);
  return 1;
}

#endif
