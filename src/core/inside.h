/* Internal: is a point inside the body? The generalized winding number
 * (Jacobson, Kavan, Sorkine-Hornung 2013) of the body's faces around it,
 * summed hierarchically over the BVH's tree with the far-field dipole
 * approximation of Barill et al. 2018 ("Fast winding numbers for soups and
 * clouds"). Robust where a plane test is not: it needs no nearest face, no
 * consistent neighbourhood, and it degrades gracefully on open meshes and
 * seams (a gap changes the number by the gap's solid angle only) and on
 * bodies that pass through themselves (the number is 2 inside two parts).
 * Used by the lab's measurements (run.c) and by the contact term
 * (collide.c) to leave out body faces buried in the body. */
#ifndef SKIN_SIM_INSIDE_H
#define SKIN_SIM_INSIDE_H

#include "bvh.h"

typedef struct ss_wind ss_wind;
/* On bvh's tree (bvh must have been refitted once, and outlive it). */
int ss_wind_create(ss_wind **out, const ss_bvh *bvh, const ss_topo *topo);
void ss_wind_destroy(ss_wind *w);
/* The node moments (area vectors, centroids, radii) for positions pos (the
 * body's caller vertices x 3). Allocates nothing. */
void ss_wind_refit(ss_wind *w, const double *pos);
/* The same, and the boxes of the BVH the hierarchy is on (ss_bvh_boxes_write
 * of it: as ss_bvh_refit sets them) in the same sweep, if box is not NULL;
 * its subtrees on nthread threads (OpenMP entered only for more than one),
 * the same bits for any count. */
void ss_wind_refit_boxes(ss_wind *w, const double *pos, double *box, int nthread);
/* Winding number of the body (pose of the last refit) around p: 1 inside a
 * closed outward-wound body, 0 outside, 1/2 on its surface, 2 inside two
 * overlapping parts. Exact per triangle near p (within SS_WIND_BETA node
 * radii), dipole-approximated beyond: error well under 0.05 at the
 * thresholds used (1/2 inside, 1/2 +- 1/4 clean). */
#define SS_WIND_BETA 3.0
double ss_wind_number(const ss_wind *w, const double *pos, const double p[3]);
/* The same with the near field within beta node radii: a smaller beta visits
 * fewer faces exactly (their number grows like beta^2 around a point on the
 * surface) for a larger far-field error. */
double ss_wind_number_beta(const ss_wind *w, const double *pos, const double p[3], double beta);
/* Exact winding number of one triangle (a, b, c) around p (solid angle / 4 pi). */
double ss_wind_triangle(const double p[3], const double a[3], const double b[3], const double c[3]);

/* A skin point inside the body (winding number above 1/2) is "buried" where
 * the body face nearest to it, or the face it is anchored on, lies inside
 * the body itself or is turned inside out: the winding number at the face's
 * centroid is not 1/2 (within 1/4). A point on a clean surface sees 1/2,
 * every layer of body around it adds 1, and a face of a fold (linear blend
 * skinning turning the surface over at a crushed crease) sees 1 or 0: a place where the body passes through itself
 * (linear blend skinning at a crushed crease, overlapping parts), and the
 * skin is inside because the part it belongs to is. Else "clean", a place
 * where the skin has cut into an intact body. */
#define SS_WIND_INSIDE 0.5
#define SS_WIND_CLEAN_TOL 0.25
enum { SS_INSIDE_OUT = 0, SS_INSIDE_CLEAN = 1, SS_INSIDE_BURIED = 2 };
/* A point inside by the winding number but in front of the surface nearest
 * to it (by the pseudo-normal there) is inside another part of the body
 * that passes through this one: buried too. */
/* Kind of point p and its depth (distance to the nearest body point, 0
 * outside); bvh and w refitted at pos. anchor_face: the body face the point
 * is anchored on, or -1. */
int ss_inside_classify(const ss_wind *w, const ss_bvh *bvh, const double *pos, const double p[3],
                       int anchor_face, double *depth);
/* 1 if body face f is buried in the body or turned over (its centroid's
 * winding number is not 1/2 within SS_WIND_CLEAN_TOL). */
int ss_wind_face_buried(const ss_wind *w, const double *pos, int f);
int ss_wind_face_buried_beta(const ss_wind *w, const double *pos, int f, double beta);

#endif
