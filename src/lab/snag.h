/* Internal: telling a snag (an anchor update that jumped across a gap in the
 * body) from an honest slide, shared by the tracking experiment and the
 * dynamic runs. */
#ifndef SKIN_SIM_SNAG_H
#define SKIN_SIM_SNAG_H

#include "geodesic.h"
#include "walk.h"

typedef struct snag_judge {
  ss_geodesic *geo;
  ss_walker *probe;
} snag_judge;

int snag_judge_init(snag_judge *j, const ss_topo *topo);
void snag_judge_free(snag_judge *j);

/* Is the move of an anchor from (face0, uv0) to (face1, uv1), both in the
 * pose of frames / pos, a snag: does it land further along the surface than
 * `limit`? walk_length >= 0 is the length of the walk that made the move (a
 * known surface path); pass -1 for other methods. Surface distance is
 * bounded from above by the shortest known path (see snag.c), so a real
 * snag is never missed. */
int snag_is(snag_judge *j, const ss_topo *topo, const ss_frames *fr, const double *pos, int face0,
            const double uv0[2], int face1, const double uv1[2], double walk_length, double limit);

#endif
