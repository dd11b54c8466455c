/* Snag test (doc/model.md, "Accuracy"): an anchor update is a snag when its
 * result lies further along the surface from its start than a limit (a few
 * times the pull plus an edge length).
 *
 * The geodesic distance itself is not needed, only whether it exceeds the
 * limit, and every path on the surface bounds it from above. So the test
 * tries the shortest paths it knows, cheapest first, and calls a snag only
 * when none is short enough:
 *  1. the walk's own path, when the method walked;
 *  2. for the other methods, a probe walk from the start straight towards
 *     the result, continued from where it stops to the result by 3 (the
 *     same benefit for every method, so counts stay comparable);
 *  3. ss_surface_distance: within one face, across a shared edge, or through
 *     corners along mesh edges (Dijkstra stopped at the limit).
 * A snag is thus never missed; a slide is called a snag only when no path
 * shorter than the limit was found, which on the edge graph's zig-zag alone
 * (up to sqrt 2 on grids) happened often enough to need 1 and 2. */
#include "snag.h"

#include <math.h>
#include <stddef.h>

int snag_judge_init(snag_judge *j, const ss_topo *topo) {
  j->geo = NULL;
  j->probe = NULL;
  int status = ss_geodesic_create(&j->geo, topo);
  if (!status) status = ss_walker_create(&j->probe, topo->nface);
  if (status) snag_judge_free(j);
  return status;
}

void snag_judge_free(snag_judge *j) {
  ss_geodesic_destroy(j->geo);
  ss_walker_destroy(j->probe);
  j->geo = NULL;
  j->probe = NULL;
}

int snag_is(snag_judge *j, const ss_topo *topo, const ss_frames *fr, const double *pos, int face0,
            const double uv0[2], int face1, const double uv1[2], double walk_length, double limit) {
  if (walk_length >= 0.0 && walk_length <= limit) return 0;
  double a1[3];
  ss_anchor_position(fr, face1, uv1, a1);
  if (walk_length < 0.0) {
    /* probe walk towards a1, then from wherever it stopped on to a1 */
    ss_walk_result r;
    ss_walk(j->probe, topo, fr, face0, uv0, a1, 1 << 20, &r);
    if (r.length <= limit) {
      double rest = ss_surface_distance(j->geo, topo, pos, r.face, r.uv, face1, uv1,
                                        limit - r.length);
      if (r.length + rest <= limit) return 0;
    }
  }
  double d = ss_surface_distance(j->geo, topo, pos, face0, uv0, face1, uv1, limit);
  return !(d <= limit);
}
