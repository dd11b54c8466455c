/* skin_sim lab (src/lab, not installed): the dynamic skin run over a built-in scene, with the
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
 *  - failures: frames with a non-finite value met by the solver, a
 *    simulated skin triangle whose area ratio left [0.05, 20], or a step that
 *    returned an error;
 *  - hugging: the distance of every skin vertex to the body surface, RMS and
 *    maximum over all frames, in mean edge lengths (the silhouette must
 *    follow the animation);
 *  - inverted faces: simulated skin faces whose normal points against the
 *    body's normal under the face: halfway between the normal where it is
 *    anchored (its barycenter anchor's body face, else the sum over its
 *    vertices' anchor faces) and that of the body face it was bound to; not
 *    judged where those two differ by more than 120 degrees (a skin of its
 *    own wound the other way at rest is judged against its rest orientation),
 *    nor where one of those body faces is folded over by the pose (turned
 *    more than 90 degrees against a neighbour it faced the same way as at
 *    rest: a crease crushed by linear blend skinning, a body passing through
 *    itself), where the body has no one "out": those are counted apart
 *    (inverted_over_folds_max), beside the folded body faces themselves
 *    (body_folds_max); the most in one frame. A face can turn over at full
 *    area, which the area ratios do not see;
 *  - inside: how deep a skin vertex goes under the body surface (behind the
 *    plane of the closest body face), the deepest over all frames, in mean
 *    edge lengths; and every inside_every frames, the skin vertices inside
 *    the body by its winding number, split into those where the body is
 *    clean and those where it passes through itself (inside.h);
 *  - slide: the largest distance of an anchor from where it was bound,
 *    measured in the current pose, over the motion's frames;
 *  - rest return (settle > 0): after the last frame the body goes back to
 *    its rest pose over one second, linearly in its joint angles
 *    (ss_body.pose_toward_rest; without it linearly in the positions), then
 *    holds still for `settle`
 *    seconds while the skin keeps stepping; then each skin vertex's distance
 *    to its own rest position (RMS and maximum). Failures, snags, inversions
 *    and depth count the settle frames too; times, hug and slide are the
 *    motion's;
 *  - final_hash: FNV-1a of the bytes of the skin positions after the last
 *    motion frame (before any settling), so that determinism can be checked
 *    across runs and machines. */
#ifndef SKIN_SIM_SS_RUN_H
#define SKIN_SIM_SS_RUN_H

#include <stddef.h>

#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_track.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_run_settings {
  ss_sim_settings sim; /* ss_sim_default_settings() */
  int frames;          /* 0: the scene's default */
  double snag_factor;  /* default 3 */
  double settle;       /* s: after the motion, blend the body back to rest over 1 s, then hold
                          it still this long and measure the rest return; 0 (default): no */
  const ss_sim_mesh *skin; /* a skin mesh of its own (e.g. coarser than the body), placed
                              on the body at rest; NULL (default): a welded copy of the body */
  int inside_every;        /* measure the skin inside the body (winding number) every this many
                              motion frames (default 10); 0: never */
  ss_model *model;         /* a model to run on, shared with other runs of this body and skin
                              (ss_run_model_create; its model settings must be sim's); NULL
                              (default): the run builds its own */
} ss_run_settings;
ss_run_settings ss_run_default_settings(void);

typedef struct ss_run_stats {
  int triangles, vertices, anchors, frames, dof; /* triangles: the body's; vertices: the skin's */
  int skin_triangles;
  int region_faces;                /* simulated skin faces (all without a face mask) */
  double ms_per_frame_median;      /* whole ss_sim_step */
  double walk_ms_per_frame_median; /* anchor updates */
  double walk_share;               /* total walk time / total step time */
  double assemble_ms_per_frame_median, factor_ms_per_frame_median, solve_ms_per_frame_median;
  double iterations_mean;          /* solver iterations per frame */
  double walk_steps_per_update;    /* edges crossed per anchor update (walk; 0 otherwise) */
  long long snags;
  long long failures;              /* frames */
  long long stalled;               /* substeps where no step decreased the energy */
  long long unconverged;           /* frames not reaching tol within the iterations */
  long long anchors_at_boundary, anchors_at_crease, anchors_at_step_limit;
  double min_area_ratio, max_area_ratio; /* over all frames and simulated faces */
  double hug_rms, hug_max;         /* mean edge lengths */
  double mean_edge_length;         /* body at rest, metres */
  int inverted_faces_max;          /* most simulated skin faces turned against the body in a frame
                                      (slivers, SS_SLIVER_AREA, and faces over a body fold not
                                      judged) */
  int inverted_over_folds_max;     /* most skin faces turned against a body face that the pose has
                                      folded over, in a frame (not in inverted_faces_max) */
  int body_folds_max;              /* most body faces folded over by the pose in a frame: turned
                                      more than 90 degrees against a neighbour they faced the same
                                      way as at rest (the rig's crease artefacts, the skin's input) */
  int faces_turned_max;            /* most skin faces turned more than 90 degrees against the body
                                      under them in a frame, counted plainly: slivers, faces over
                                      folds and outside the simulated region too
                                      (ss_sim_count_off_body) */
  int hug_far_max;                 /* most skin vertices farther than one mean edge length from the
                                      body surface in a frame */
  int triangles_carried;           /* skin faces carried rigidly with the body (not simulated) */
  double inside_max;               /* deepest skin vertex under the body surface, mean edge lengths */
  /* inside the body by winding number (inside_every): skin vertices with the body's winding
   * number above 1/2 around them, deeper than 1e-6 mean edge lengths; "buried" where the body
   * face nearest to the vertex lies inside the body itself (the body passes through itself
   * there), else "clean". Depths: to the nearest body point, in mean edge lengths. */
  int inside_samples;              /* frames measured */
  double inside_mean;              /* skin vertices inside per measured frame, mean */
  int inside_count_max;            /* ... the most in one frame */
  double inside_buried_max;        /* deepest buried */
  double inside_clean_max;         /* deepest clean */
  int inside_clean_over_005_max;   /* most clean vertices deeper than 0.05 edge in a frame */
  int inside_clean_over_01_max;    /* most clean vertices deeper than 0.1 edge in a frame */
  int inside_clean_worst_frame;    /* frame of the deepest clean vertex (0: none) */
  double slide_max, slide_max_m;   /* farthest anchor from where it was bound during the motion:
                                      mean edge lengths, metres */
  int settle_frames;               /* frames stepped after the motion (blend + hold) */
  double rest_error_rms, rest_error_max; /* after settling: skin vertex to its rest position,
                                            mean edge lengths (0 without settle) */
  double rest_error_max_m;         /* the same maximum in metres */
  double rest_slide_max;           /* after settling: farthest anchor from where it was bound,
                                      mean edge lengths */
  unsigned long long final_hash;
} ss_run_stats;

/* A moving body from anywhere (a built-in scene, an avatar): its mesh at
 * rest and its pose at any frame. The caller owns the arrays. */
typedef int (*ss_body_pose_fn)(void *user, double frame, double *pos); /* SS_OK or an error */
/* The pose of frame `frame` a fraction w in [0, 1] of the way back to rest
 * (0: that frame's pose, 1: rest), moved in the body's own joint angles (a
 * skeleton's, a scene's), so that its parts keep their shape on the way. */
typedef int (*ss_body_pose_toward_rest_fn)(void *user, double frame, double w, double *pos);
typedef struct ss_body {
  int nvert, nface;
  const double *rest; /* (nvert x 3) the pose of frame 0 */
  const int *faces;   /* (nface x 3) */
  int frames;         /* default frame count */
  double fps;         /* frames per second (> 0) */
  ss_body_pose_fn pose;
  void *user;
  /* optional (NULL: the settle blends the positions linearly: half way back a
   * part turned by an angle a comes cos(a / 2) times as far from its joint) */
  ss_body_pose_toward_rest_fn pose_toward_rest;
} ss_body;

/* The body of a built-in scene. */
ss_body ss_body_of_scene(const ss_scene *scene);

/* Called after each frame with the simulation (for output); returning
 * non-zero stops the run. Settle frames (ss_run_settings.settle) follow as
 * frames + 1, frames + 2, ... */
typedef int (*ss_frame_fn)(void *user, int frame, const ss_sim *sim, const double *body_pos);

/* Runs the skin over a body. The skin is settings->skin, or else a copy of
 * the body at rest, its coincident vertices (UV seams of a mesh file) welded
 * so that it is one sheet; either is bound to the body by closest point. on_frame and progress may be
 * NULL. Returns SS_OK (failures are counted, not returned) or an error with
 * a message (a pose that fails stops the run with its error). */
int ss_run_body(const ss_body *body, const ss_run_settings *settings, ss_frame_fn on_frame,
                void *frame_user, ss_progress_fn progress, void *progress_user,
                ss_run_stats *stats, char *err, int err_sz);
/* The model ss_run_body builds for body and settings (its skin, its model
 * settings), to share between runs through ss_run_settings.model: the run
 * itself, its reference and its truth (ss_reference_settings keeps it). Release
 * with ss_model_destroy. */
int ss_run_model_create(ss_model **out, const ss_body *body, const ss_run_settings *settings,
                        char *err, int err_sz);

/* ss_run_body over a built-in scene. */
int ss_run_scene(const ss_scene *scene, const ss_run_settings *settings, ss_frame_fn on_frame,
                 void *frame_user, ss_progress_fn progress, void *progress_user,
                 ss_run_stats *stats, char *err, int err_sz);

/* FNV-1a 64-bit hash of n bytes. */
unsigned long long ss_hash_bytes(const void *data, size_t n);

#ifdef __cplusplus
}
#endif
#endif
