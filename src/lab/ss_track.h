/* skin_sim lab (src/lab, not installed): the anchor tracking experiment (no dynamics).
 *
 * Anchors are seeded on the body at rest, one at each vertex and one at each
 * face barycenter (as the skin's anchors would be). Each frame the body moves
 * and anchors ride along on their faces; each anchor is then pulled towards
 * its world position of the frame before, lifted `lift` mean edge lengths
 * along the body normal there (skin lagging behind the body), and moved there
 * with the chosen method. An update is a snag when its result lies further
 * along the surface from its start than snag_factor |a* - a0| + one mean edge
 * length (surface distance: the shortest known path on the surface, see
 * track.c); a failure is a non-finite position or an anchor outside its face. */
#ifndef SKIN_SIM_SS_TRACK_H
#define SKIN_SIM_SS_TRACK_H

#include "skin_sim/ss_anchor.h"
#include "ss_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_track_settings {
  ss_mover_settings mover;
  int frames;          /* 0: the scene's default */
  double lift;         /* target lift along the normal, in mean edge lengths; default 0.1 */
  double snag_factor;  /* default 3 */
} ss_track_settings;
ss_track_settings ss_track_default_settings(void);

typedef struct ss_track_stats {
  int triangles, vertices, anchors, frames;
  long long updates;            /* anchor updates made (anchors x frames) */
  long long snags;
  long long failures;
  long long anchors_at_boundary;   /* updates that stopped on a boundary edge */
  long long anchors_at_crease;     /* updates that stopped at a crease */
  long long anchors_at_step_limit; /* updates that hit walk_max_steps */
  double mean_steps;               /* edges crossed per walk */
  double ms_per_frame_median;      /* anchor-update time per frame (excludes pose and metrics) */
  double ms_per_anchor_update_median;
  double mean_edge_length;         /* of the body at rest, metres */
} ss_track_stats;

/* Called after each frame (may be NULL); returning non-zero stops the run. */
typedef int (*ss_progress_fn)(void *user, int frame, int frames);

int ss_track_run(const ss_scene *scene, const ss_track_settings *settings,
                 ss_progress_fn progress, void *user, ss_track_stats *stats,
                 char *err, int err_sz);

#ifdef __cplusplus
}
#endif
#endif
