/* Internal: closest points on triangles, and the n-ring baseline of the anchor
 * update (closest.c). */
#ifndef SKIN_SIM_CLOSEST_H
#define SKIN_SIM_CLOSEST_H

#include "topo.h"

/* Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision
 * Detection 5.1.5). Writes its canonical coordinates uv and returns the squared
 * distance. Robust on degenerate triangles. */
double ss_closest_point_triangle(const double p[3], const double a[3], const double b[3],
                                 const double c[3], double uv[2]);

/* Scratch for n-ring searches: one per thread. */
typedef struct ss_nring ss_nring;
int ss_nring_create(ss_nring **out, const ss_topo *topo);
void ss_nring_destroy(ss_nring *nring);
/* Closest point to p among the faces within `rings` vertex rings of face
 * (rings = 0: the face alone; 1: faces sharing a vertex with it; ...).
 * Returns the squared distance. */
double ss_nring_closest(ss_nring *nring, const ss_topo *topo, const double *pos, int face,
                        int rings, const double p[3], int *face_out, double uv[2]);

#endif
