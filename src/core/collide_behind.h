/* Internal: the contact pass's pre-test of a skin vertex in front of the
 * body's surface near it (collide_behind.c; collide.c, "Where, cheap
 * first"). */
#ifndef SKIN_SIM_COLLIDE_BEHIND_H
#define SKIN_SIM_COLLIDE_BEHIND_H

#include "bvh.h"
#include "collide.h"

/* 1 if p may be behind the body's surface at its nearest point within
 * bound (squared) of it: some face within bound has p less than lim in
 * front of its plane (a face without a normal counts). The tree of shape
 * s (boxes box, in in's pose; parent: each node's parent, -1 at the root)
 * is searched up from leaf, the leaf of a face near p. Allocates nothing;
 * reads only. */
int ss_collide_behind(const ss_bvh_shape *s, const double *box, const int *parent, int leaf,
                      const ss_collide_in *in, const double p[3], double bound, double lim);

#endif
