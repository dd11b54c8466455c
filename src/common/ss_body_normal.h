/* Internal: the body's normal under a skin face, as the orient term
 * (src/core/orient.c) and the inverted-face count of runs (src/lab/run.c)
 * both judge a face by it: one definition, so that the two cannot drift. */
#ifndef SKIN_SIM_SS_BODY_NORMAL_H
#define SKIN_SIM_SS_BODY_NORMAL_H

#include <math.h>
#include <string.h>

/* The share of its rest area area0 that a face of area `area` has lost, in
 * [0, 1]: 0 where it keeps (or gains) area, 1 where it is crushed to nothing
 * or had none at rest (its normal tells nothing). */
static inline double crush_share(double area, double area0) {
  if (!(area0 > 0.0)) return 1.0;
  const double r = area / area0;
  return r >= 1.0 ? 0.0 : r > 0.0 ? 1.0 - r : 1.0;
}

/* The body's normal under skin face f (unit, or zero), the body's faces
 * described by their unit normals `normal` (nbface x 3), areas `area` in the
 * pose and `area0` at rest; `anchor_face` the body face of each anchor (the
 * anchors now, or as bound), vertices' first (nvert), then, where nanchor >
 * nvert, one per skin face's barycenter; `faces` the skin's (nface x 3).
 * The normal of the body face its barycenter is anchored on, with those of
 * the faces its three corners are anchored on added, each weighted by the
 * share of its rest area that the barycenter's body face has lost. A body
 * face that keeps its area speaks for the skin face alone (its unit normal,
 * bit for bit); one the pose has crushed does not: linear blend skinning
 * crushes crease triangles to 1-30% of their area, where a crushed
 * triangle's normal swings with the smallest move of its corners, and a skin
 * face bridging the crease (its corners anchored on both walls) stood on edge
 * against it while lying face up on the walls (elbow and the 19k quadruped).
 * Without barycenter anchors: the normalised sum over the corners. */
static inline void body_normal_under(const double *normal, const double *area, const double *area0,
                                     const int *anchor_face, const int *faces, int nvert,
                                     int nanchor, int f, double n[3]) {
  n[0] = n[1] = n[2] = 0.0;
  double w = 1.0; /* the corners' weight */
  if (nanchor > nvert && anchor_face[nvert + f] >= 0) {
    const int b = anchor_face[nvert + f];
    memcpy(n, normal + 3 * b, 3 * sizeof(double));
    w = crush_share(area[b], area0[b]);
  }
  if (!(w > 0.0)) return; /* the barycenter's unit normal, as it is */
  for (int c = 0; c < 3; c++) {
    const int b = anchor_face[faces[3 * f + c]];
    if (b < 0) continue;
    for (int k = 0; k < 3; k++) n[k] += w * normal[3 * b + k];
  }
  const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (len > 0.0)
    for (int k = 0; k < 3; k++) n[k] /= len;
}

#endif
