/* skin_sim core: how anchors move over the body surface (the settings).
 *
 * An anchor lives on the body as (face, u, v): its world position is
 *   v0 + u (v1 - v0) + v (v2 - v0)
 * with v0, v1, v2 the face's corners in the current pose, so an anchor rides
 * along as the body moves. (u, v) are also the anchor's coordinates in the
 * face's canonical 2D space of the paper (section 2); inside means u >= 0,
 * v >= 0, u + v <= 1.
 *
 * Moving an anchor from where it is (a0) towards a candidate a* off the surface:
 *  - walk    (the paper): 2D ray tracing face to face, never leaving the surface;
 *  - project ("projection springs"): a* snapped to the closest point of the whole body;
 *  - nring:  the closest point among faces within N rings of the anchor's face.
 *
 * Only the settings are public (ss_sim_settings.mover, ss_track_settings.mover);
 * the frames, the walk, the BVH, the n-ring search and the mover that runs them
 * are the core's inside (src/core/walk.h, bvh.h, closest.h, mover.h). */
#ifndef SKIN_SIM_SS_ANCHOR_H
#define SKIN_SIM_SS_ANCHOR_H

#include "ss_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_mover_settings {
  int method;          /* ss_method */
  int walk_max_steps;  /* bound on edges crossed by one walk */
  int nring_rings;     /* N for SS_METHOD_NRING */
} ss_mover_settings;
ss_mover_settings ss_mover_default_settings(void);

#ifdef __cplusplus
}
#endif
#endif
