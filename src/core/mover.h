/* Internal: one interface for the three ways of moving an anchor (mover.c):
 * walk (walk.h), project (bvh.h) and nring (closest.h). The settings are public
 * (skin_sim/ss_anchor.h); the mover itself is used by the skin (sim.c) and the
 * tracking experiment (src/lab/track.c). */
#ifndef SKIN_SIM_MOVER_H
#define SKIN_SIM_MOVER_H

#include "skin_sim/ss_anchor.h"
#include "bvh.h"
#include "walk.h"

/* Holds per-pose frames and the scratch of the chosen method. bvh_shape: a
 * built BVH of topo whose tree a project mover borrows (ss_bvh_create_on; it
 * must outlive the mover), or NULL to build its own. */
typedef struct ss_mover ss_mover;
int ss_mover_create(ss_mover **out, const ss_topo *topo, const ss_mover_settings *settings,
                    const ss_bvh *bvh_shape, char *err, int err_sz);
void ss_mover_destroy(ss_mover *mover);
/* Sets the body pose for the following moves (frames, and the BVH refit for
 * project). Allocates nothing. */
void ss_mover_set_pose(ss_mover *mover, const double *pos);
/* The same, the frames computed by nthread threads (the same bits). */
void ss_mover_set_pose_threads(ss_mover *mover, const double *pos, int nthread);
/* The vector instruction set of its frame update (ss_frames.isa). */
void ss_mover_set_isa(ss_mover *mover, int isa);
const ss_frames *ss_mover_frames(const ss_mover *mover);
/* Moves anchor (face, uv) towards target with the mover's method. For project
 * and nring, stop is SS_STOP_INSIDE and steps 0. */
void ss_mover_move(ss_mover *mover, int face, const double uv[2], const double target[3],
                   ss_walk_result *res);

/* As ss_mover_move with the caller's walk scratch, so that several threads
 * can move anchors at once over the same pose (one walker each): the frames
 * and the BVH are only read. For SS_METHOD_NRING, which needs the mover's own
 * scratch, call ss_mover_move from one thread. */
void ss_mover_walk_with(const ss_mover *mover, ss_walker *walker, int face, const double uv[2],
                        const double target[3], ss_walk_result *res);
int ss_mover_method(const ss_mover *mover);

#endif
