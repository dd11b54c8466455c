/* Internal: bounding volume hierarchy over the body's faces, for the exact
 * Euclidean closest point of the "projection springs" baseline (bvh.c): built
 * once per topology, refitted per pose. */
#ifndef SKIN_SIM_BVH_H
#define SKIN_SIM_BVH_H

#include "topo.h"

typedef struct ss_bvh ss_bvh;
int ss_bvh_create(ss_bvh **out, const ss_topo *topo);
/* A BVH with boxes of its own on the tree of `shape` (refitted at least once:
 * its tree is built), which it borrows: shape must outlive it and is never
 * written. A model keeps one tree of its body for every sim on it. */
int ss_bvh_create_on(ss_bvh **out, const ss_bvh *shape);
void ss_bvh_destroy(ss_bvh *bvh);
/* Refits boxes to positions pos (nvert x 3). Allocates nothing. */
void ss_bvh_refit(ss_bvh *bvh, const double *pos);
/* Exact Euclidean closest point on the whole mesh (pose of the last refit);
 * ties go to the lower face index. Returns the squared distance. */
double ss_bvh_closest(const ss_bvh *bvh, const double *pos, const double p[3], int *face,
                      double uv[2]);
/* The same within a bound: the closest point nearer than sqrt(bound2), or
 * face -1 and bound2 returned if there is none (the search visits only the
 * boxes within the bound, so a small bound is cheap). */
double ss_bvh_closest_within(const ss_bvh *bvh, const double *pos, const double p[3], double bound2,
                             int *face, double uv[2]);
/* The tree's shape (read-only; 0 nodes before the first refit): nodes in
 * depth-first order, parent before children; left/right -1 at a leaf, whose
 * faces are face_order[first .. first + count). Lets another hierarchy over
 * the same faces (inside.c's winding-number moments) share the tree. */
typedef struct ss_bvh_shape {
  int nnode;
  const int *left, *right, *first, *count, *face_order;
} ss_bvh_shape;
ss_bvh_shape ss_bvh_get_shape(const ss_bvh *bvh);
/* The boxes of the last refit (nnode x 6: lo xyz, hi xyz), read-only. */
const double *ss_bvh_boxes(const ss_bvh *bvh);
/* The same to write: for a refit done elsewhere with another hierarchy over
 * the same tree (ss_wind_refit_boxes), which must set them as ss_bvh_refit
 * would. */
double *ss_bvh_boxes_write(ss_bvh *bvh);

/* Squared distance from p to a box (lo xyz, hi xyz); 0 inside. Compared,
 * not branched (maxsd); the nearest-point searches of bvh.c and collide.c. */
static inline double ss_bvh_box_dist2(const double box[6], const double p[3]) {
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double lo = box[k] - p[k], hi = p[k] - box[3 + k];
    double d = lo > hi ? lo : hi;
    d = d > 0.0 ? d : 0.0;
    d2 += d * d;
  }
  return d2;
}

/* A nearest-point search's step down: children l and r (box distances dl,
 * dr) pushed on the stack where within best, the farther first so that the
 * nearer is searched first. The caller leaves room for two. */
static inline void ss_bvh_push_children(int *stack, double *sdist, int *top, int l, double dl,
                                        int r, double dr, double best) {
  int t = *top;
  if (dl <= dr) {
    if (dr <= best) stack[t] = r, sdist[t++] = dr;
    if (dl <= best) stack[t] = l, sdist[t++] = dl;
  } else {
    if (dl <= best) stack[t] = l, sdist[t++] = dl;
    if (dr <= best) stack[t] = r, sdist[t++] = dr;
  }
  *top = t;
}

#endif
