/* Internal: the body's surface near a point, for the contact pass
 * (collide_surface.c). */
#ifndef SKIN_SIM_COLLIDE_SURFACE_H
#define SKIN_SIM_COLLIDE_SURFACE_H

#include "collide.h"

/* A local nearest point of the body's surface to p: from face f, over to
 * the face across the edge, or around the corner, that the nearest point so
 * far lies on, while one is nearer (the distance falls at every move, so
 * the descent never returns to a face). Its face (-1 if f has no area),
 * uv and squared distance; *settled 0 if it was still moving after
 * SS_COLLIDE_DESCENT (32) faces. */
int ss_collide_descend(const ss_collide_in *in, int f, const double p[3], double uv[2], double *d2,
                       int *settled);

/* Where point p is against the body's surface near face nf (its nearest
 * point there at uv, squared distance d2): the signed distance *sd along
 * the pseudo-normal n (Baerentzen and Aanaes 2005: the normals of the faces
 * nearest there summed, one face's inside it, an edge's two, a corner's
 * ring) and the nearest point c. 0 if there is no normal. */
int ss_collide_surface_at(const ss_collide_in *in, int nf, const double uv[2], const double p[3], double d2,
                          double n[3], double c[3], double *sd);

/* The lowest face other than nf as near to p as nf is, at the edge or the
 * corner of nf that p's nearest point on nf lies on (a buried face and a
 * clean one meet there, where the body passes through itself); -1 if none. */
int ss_collide_tied_face(const ss_collide_in *in, int nf, const double p[3]);

#endif
