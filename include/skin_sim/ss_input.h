/* skin_sim core: meshes and stamps arriving from outside (ROS messages, files).
 *
 * What a node needs to decide before handing a received mesh to ss_sim, with
 * no ROS in it: is the mesh well formed (sizes agree, indices in range, every
 * value finite, not empty), does it keep the topology of the simulation it
 * drives, how does its stamp relate to the previous one (a step, the same
 * time, time going backwards, a gap), and how far the skin has slid from
 * where it was bound (for colours and statistics).
 *
 * Sizes are counts of array elements, as in messages: npos floats
 * (nvert x 3, xyz interleaved) and ntri indices (nface x 3). */
#ifndef SKIN_SIM_SS_INPUT_H
#define SKIN_SIM_SS_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "ss_common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Checks a received mesh: npos a non-zero multiple of 3, ntri a non-zero
 * multiple of 3, nvert within int range, every index below nvert, every
 * position finite. Returns SS_OK, or SS_E_MESH / SS_E_NONFINITE with one
 * sentence naming the first problem in err (may be NULL). */
int ss_input_mesh_check(size_t npos, const float *pos, size_t ntri, const uint32_t *tri,
                        char *err, int err_sz);

/* 1 if a received mesh (already checked) has nvert vertices and exactly the
 * triangles faces (nface x 3), else 0 (with a sentence in err saying what
 * differs). */
int ss_input_same_topology(size_t npos, size_t ntri, const uint32_t *tri, int nvert, int nface,
                           const int *faces, char *err, int err_sz);

/* How a stamp follows the previous one. */
enum ss_input_time {
  SS_TIME_FIRST = 0,     /* no previous stamp */
  SS_TIME_STEP = 1,      /* later by at most max_gap: step by *dt */
  SS_TIME_SAME = 2,      /* the same time: nothing to step */
  SS_TIME_BACKWARDS = 3, /* earlier (a bag looping): reset */
  SS_TIME_GAP = 4        /* later by more than max_gap: reset */
};
/* "first", "step", "same", "backwards", "gap"; "?" for other values. */
const char *ss_input_time_name(int kind);

/* Classifies stamp now_ns (nanoseconds) against prev_ns (have_prev 0: none).
 * For SS_TIME_STEP, *dt (may be NULL) gets the difference in seconds rounded
 * to whole microseconds, so that a regular stream whose stamps round to
 * nanoseconds (1/30 s is 33333333 or 33333334 ns) gives one bit-identical dt
 * and the solver keeps its factorisation; otherwise *dt is 0. */
int ss_input_classify_time(int have_prev, int64_t prev_ns, int64_t now_ns, double max_gap_s,
                           double *dt);

/* Number of equal steps to cover dt with steps of at most max_step seconds
 * (>= 1; max_step <= 0: 1), capped at max_count (>= 1). */
int ss_input_split_steps(double dt, double max_step, int max_count);

/* Slide: the distance between where an anchor is now and where it was bound,
 * both on the body in pose body_pos (body nvert x 3, faces nface x 3).
 * Anchors are (face, u, v) as in ss_anchor.h: n anchors now (face, uv: n and
 * n x 2) and as bound (face0, uv0). out (n, may be NULL) gets each distance;
 * returns the largest (0 for n = 0). Faces out of range count as 0. */
double ss_input_slide(int n, const int *face, const double *uv, const int *face0,
                      const double *uv0, const double *body_pos, int body_nvert,
                      const int *body_faces, int body_nface, double *out);

/* A colour for a slide distance d: blue (0) through green to red (d >= scale),
 * opaque; rgba gets 4 floats in [0, 1]. scale <= 0 or d not finite: blue. */
void ss_input_slide_color(double d, double scale, float rgba[4]);

#ifdef __cplusplus
}
#endif
#endif
