/* Internal to the experiment library: surface distance between two anchors,
 * for snag detection (geodesic.c, used by snag.c). */
#ifndef SKIN_SIM_GEODESIC_H
#define SKIN_SIM_GEODESIC_H

#include "topo.h" /* the lab is built with the core and reads its topology directly */

/* Scratch for surface distances on one topology. */
typedef struct ss_geodesic ss_geodesic;
int ss_geodesic_create(ss_geodesic **out, const ss_topo *topo);
void ss_geodesic_destroy(ss_geodesic *geo);
/* Distance along the surface between two anchors in pose pos: straight line
 * when both are in one face, else the shortest path that leaves a through a
 * corner of its face, follows mesh edges (Dijkstra over welded vertices) and
 * enters b's face through one of its corners. An upper bound of the true
 * geodesic distance, exact on a flat face. The search stops once paths exceed
 * `limit`, and then returns INFINITY: cost grows with limit, not with mesh size. */
double ss_surface_distance(ss_geodesic *geo, const ss_topo *topo, const double *pos,
                           int face_a, const double uv_a[2], int face_b, const double uv_b[2],
                           double limit);

#endif
