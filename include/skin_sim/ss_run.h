/* skin_sim core: the dynamic skin run over a built-in scene, with the
 * measurements the benchmark and the stability suite need (no ROS, no I/O).
 *
 * Each frame the scene's body moves to its next pose and the skin takes one
 * ss_sim_step of 1/fps seconds. Measured per run:
 *  - time per frame (median) and its parts (walk, assembly, factorisation,
 *    solves), solver iterations;
 *  - snags: anchors that in one frame land further along the body surface
 *    from where they were than snag_factor |a* - a0| + one mean edge length,
 *    |a* - a0| the pull the anchor update was given (ss_sim_anchor_pull): a
 *    jump across a gap is short in space and long on the surface. Surface
 *    distance is bounded by the shortest path known (snag.c), the walk's own
 *    path included;
 *  - failures: frames with a non-finite value met by the solver, a skin
 *    triangle whose area ratio left [0.05, 20], or a step that returned an
 *    error;
 *  - hugging: the distance of every skin vertex to the body surface, RMS and
 *    maximum over all frames, in mean edge lengths (the silhouette must
 *    follow the animation);
 *  - final_hash: FNV-1a of the bytes of the final skin positions, so that
 *    determinism can be checked across runs and machines. */
#ifndef SKIN_SIM_SS_RUN_H
#define SKIN_SIM_SS_RUN_H

#include <stddef.h>

#include "ss_scene.h"
#include "ss_sim.h"
#include "ss_track.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_run_settings {
  ss_sim_settings sim; /* ss_sim_default_settings() */
  int frames;          /* 0: the scene's default */
  double snag_factor;  /* default 3 */
} ss_run_settings;
ss_run_settings ss_run_default_settings(void);

typedef struct ss_run_stats {
  int triangles, vertices, anchors, frames, dof;
  double ms_per_frame_median;      /* whole ss_sim_step */
  double walk_ms_per_frame_median; /* anchor updates */
  double walk_share;               /* total walk time / total step time */
  double assemble_ms_per_frame_median, factor_ms_per_frame_median, solve_ms_per_frame_median;
  double iterations_mean;          /* solver iterations per frame */
  long long snags;
  long long failures;              /* frames */
  long long stalled;               /* substeps where no step decreased the energy */
  long long unconverged;           /* frames not reaching tol within the iterations */
  long long anchors_at_boundary, anchors_at_crease, anchors_at_step_limit;
  double min_area_ratio, max_area_ratio; /* over all frames and simulated faces */
  double hug_rms, hug_max;         /* mean edge lengths */
  double mean_edge_length;         /* body at rest, metres */
  unsigned long long final_hash;
} ss_run_stats;

/* Called after each frame with the simulation (for output); returning
 * non-zero stops the run. */
typedef int (*ss_frame_fn)(void *user, int frame, const ss_sim *sim, const double *body_pos);

/* Runs the skin over scene. on_frame and progress may be NULL. Returns SS_OK
 * (failures are counted, not returned) or an error with a message. */
int ss_run_scene(const ss_scene *scene, const ss_run_settings *settings, ss_frame_fn on_frame,
                 void *frame_user, ss_progress_fn progress, void *progress_user,
                 ss_run_stats *stats, char *err, int err_sz);

/* FNV-1a 64-bit hash of n bytes. */
unsigned long long ss_hash_bytes(const void *data, size_t n);

#ifdef __cplusplus
}
#endif
#endif
