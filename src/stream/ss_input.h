/* skin_sim stream: meshes and stamps arriving from outside (ROS messages, files).
 *
 * The nodes' stream policy, in the node library (src/stream, libskin_sim_stream,
 * not installed): built on the core's public API, with no ROS in it, so that it
 * is tested without ROS.
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

#include "skin_sim/ss_common.h"

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

/* ---- a stream that the node may fall behind ---------------------------------
 *
 * A node stepping a skin may be slower than its input: it then skips the
 * older queued messages and steps the newest once. The time it skipped is
 * its own doing: it must neither reset the skin (only a real jump of the
 * input's stamps, between consecutively published messages, or time going
 * backwards does) nor cost more substeps (the number of substeps comes from
 * the input's own period). The step covers the elapsed time quantised to
 * whole input periods (kept while the skin's clock stays close), so that a
 * stream steps with few distinct dt (each a quasi-Newton refactorisation,
 * about half a step's cost at 19k triangles) rather than a new one every
 * frame; the skin's clock (skin_ns) keeps the remainder, so no time is lost
 * or gained. */

#define SS_INPUT_PERIOD_WINDOW 15

/* What a node knows of the stream it receives, fed every message in arrival
 * order (ss_input_stream_arrive) whether or not it will be stepped. Plain
 * data: zero it to start. */
typedef struct ss_input_stream {
  int have_prev;
  uint32_t prev_seq;        /* header.seq of the last message */
  int64_t prev_ns;          /* and its stamp */
  int64_t diff_us[SS_INPUT_PERIOD_WINDOW]; /* stamp differences of consecutive messages (us) */
  int ndiff, diff_head;
  int64_t period_us;        /* the input's period used for stepping: the median of diff_us,
                               changed only when the median moves by more than 10%; 0 unknown */
  uint64_t lost;            /* messages lost before they arrived (gaps in seq), so far */
} ss_input_stream;

/* One arriving message (publisher sequence number seq, stamp stamp_ns):
 * counts messages lost in between (seq gaps; a smaller seq is a new
 * publisher), learns the input period, and returns how the stamp follows the
 * previous message's: SS_TIME_FIRST, SS_TIME_STEP, SS_TIME_SAME,
 * SS_TIME_BACKWARDS, or SS_TIME_GAP when the stamps jumped forward by more
 * than max_gap_s per publication (k lost messages in between: more than
 * (k + 1) max_gap_s). BACKWARDS and GAP are real discontinuities of the
 * input: the skin resets on the next message it steps. */
int ss_input_stream_arrive(ss_input_stream *s, uint32_t seq, int64_t stamp_ns, double max_gap_s);

/* What to do with the message stamped stamp_ns that the node steps now. */
typedef struct ss_input_plan {
  int kind;        /* SS_TIME_FIRST (create the skin), SS_TIME_BACKWARDS / SS_TIME_GAP
                      (reset: create it again), SS_TIME_STEP, SS_TIME_SAME (no step) */
  int periods;     /* STEP: whole input periods covered (>= 1) */
  int substeps;    /* STEP: equal substeps, from the input period alone (max_step, max_split) */
  double dt;       /* STEP: s, periods x period (a whole number of microseconds) */
  int64_t skin_ns; /* the skin's clock after this message */
} ss_input_plan;

/* Plans the step to stamp_ns from the skin's clock skin_ns (have_skin 0: no
 * skin yet). discontinuity: SS_TIME_BACKWARDS or SS_TIME_GAP if a message
 * since the last stepped one arrived as such (the node carries it over the
 * messages it skipped), else 0. The period is s->period_us (unknown: the
 * elapsed time is one period). The step is whole periods: prev_periods (the
 * last plan's; 0 none) while the skin's clock stays within tol =
 * max(1, prev_periods / 4) periods of stamp_ns, one more or one fewer within
 * 2 tol, else the elapsed time rounded. A node about k frames behind then
 * keeps one dt for several steps (no quasi-Newton refactorisation) instead of
 * alternating k and k + 1 every step. An elapsed time over 2^48 us (8
 * years) is SS_TIME_GAP. Stamps are clamped to +-2^62 ns here and in
 * ss_input_stream_arrive (ROS time is below that). Returns plan->kind; plan
 * may not be NULL. */
int ss_input_plan_step(const ss_input_stream *s, int have_skin, int64_t skin_ns, int64_t stamp_ns,
                       int discontinuity, int prev_periods, double max_step, int max_split,
                       ss_input_plan *plan);

/* A SkinMesh topology_id for a mesh's layout: FNV-1a over the vertex and
 * triangle counts, the triangles, and (rigid_part not NULL: nvert values) what
 * each vertex moves with; never 0. Equal layouts give equal ids. */
uint32_t ss_input_topology_id(int nvert, int nface, const int *faces, const uint32_t *rigid_part);

/* Slide: the distance between where an anchor is now and where it was bound,
 * both on the body in pose body_pos (body nvert x 3, faces nface x 3).
 * Anchors are (face, u, v) as in ss_anchor.h: n anchors now (face, uv: n and
 * n x 2) and as bound (face0, uv0). out (n, may be NULL) gets each distance;
 * returns the largest (0 for n = 0). Faces out of range count as 0. */
double ss_input_slide(int n, const int *face, const double *uv, const int *face0,
                      const double *uv0, const double *body_pos, int body_nvert,
                      const int *body_faces, int body_nface, double *out);

/* A colour for a slide distance d: light blue (0) through green to red (d >= scale),
 * each hue a third white, opaque; rgba gets 4 floats in [0, 1]. scale <= 0 or d not
 * finite: blue. */
void ss_input_slide_color(double d, double scale, float rgba[4]);

/* A colour for how a piece of skin's area compares with its rest area (ratio = now /
 * rest): blue where compressed (fully at half its rest area or less), light grey at
 * rest, red where stretched (fully at twice or more); opaque. ratio <= 0 or not finite:
 * grey. */
void ss_input_stretch_color(double ratio, float rgba[4]);

/* Each vertex's area ratio: the area of the faces around it now over their area at rest
 * (pos, rest: nvert x 3; faces: nface x 3; ratio: nvert; area: nvert x 2 scratch). A
 * vertex in no face, or whose faces have no rest area, gets 1. */
void ss_input_vertex_area_ratio(int nvert, const double *pos, const double *rest, int nface,
                                const int *faces, double *area, double *ratio);

/* Shades colours so that a mesh's shape reads in a viewer that does not light it (rviz
 * draws a TRIANGLE_LIST marker unlit): each vertex's rgb (rgba: nvert x 4, alpha kept) is
 * multiplied by a light term from its normal (the area-weighted normal of its faces;
 * normal: nvert x 3 scratch) and a fixed light from above, in front and a little to the
 * side (+x, -y, +z of the mesh's frame, SS_SHADE_LIGHT): 1 facing the light, down to
 * SS_SHADE_AMBIENT facing away (half-Lambert, squared). A vertex in no face keeps its
 * colour. pos: nvert x 3; faces: nface x 3. */
#define SS_SHADE_LIGHT {1.0, -0.6, 0.8}
#define SS_SHADE_AMBIENT 0.25
void ss_input_shade(int nvert, const double *pos, int nface, const int *faces, double *normal,
                    float *rgba);

/* ---- health over a window (for /diagnostics) -------------------------------
 *
 * What a node did in the last window (diagnostic period), judged into one
 * level and one sentence. Counts are of this window only. Thresholds:
 * - ERROR: a substep failed (non-finite values, last good state kept); or
 *   inputs arrived and every one was rejected (nothing stepped); or the mean
 *   step took more than twice the input period (the node cannot keep up).
 * - WARN: no input in the window; some inputs rejected; inputs dropped
 *   (lost before the callback) or skipped (the node fell behind); the skin
 *   was reset (the input's time jumped or went backwards, or ~reset); steps
 *   ran below the settings' work to fit a real-time budget (accuracy traded
 *   for time); or the mean step took more than SS_HEALTH_BUDGET (0.8) of the
 *   input period.
 * - OK otherwise. Step times are compared only when the period is known. */
#define SS_HEALTH_BUDGET 0.8
enum { SS_HEALTH_OK = 0, SS_HEALTH_WARN = 1, SS_HEALTH_ERROR = 2 };
typedef struct ss_input_window {
  uint32_t arrived;     /* meshes that reached the node */
  uint32_t stepped;     /* meshes processed (created, stepped or republished) */
  uint32_t rejected, dropped, skipped, resets, failures;
  double step_ms_mean;  /* mean processing time per stepped mesh, ms (0 if none) */
  double period_ms;     /* the input's period, ms (0: unknown) */
  uint32_t lowered;     /* steps run with fewer substeps or iterations than the settings'
                           (a real-time budget traded accuracy for time) */
  uint32_t not_stepped; /* of the processed, those that gave no skin step (the skin created
                           again, or a stamp not past the skin's clock) */
} ss_input_window;
/* Returns SS_HEALTH_OK / WARN / ERROR for w, with a sentence naming the worst
 * reason (or "stepping normally") in msg (may be NULL). */
int ss_input_health(const ss_input_window *w, char *msg, int msg_sz);

/* A step still running (/diagnostics publishes "step in progress for N s" while one
 * step takes longer than the diagnostic period): WARN, and ERROR once it has run for
 * more than the seconds returned here, twice the input period (period_ms; the bound a
 * mean step is judged by: the node cannot keep up); 0 (never ERROR) when the period is
 * unknown (<= 0 or not finite). */
double ss_input_busy_error_s(double period_ms);
/* The status /diagnostics publishes while a step has run for busy_s seconds (the input
 * period period_ms, 0 if unknown; last_level the level of the last status, SS_HEALTH_*
 * or anything else for none): WARN, ERROR after ss_input_busy_error_s, a worse last
 * level kept; "step in progress for N s" in msg and N ("%.1f") in value. */
int ss_input_busy(double busy_s, double period_ms, int last_level, char *msg, int msg_sz,
                  char *value, int value_sz);

#ifdef __cplusplus
}
#endif
#endif
