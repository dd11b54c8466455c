/* Internal: per-face canonical frames of one body pose and the anchor walk
 * (walk.c; the paper's section 2). An anchor lives on the body as (face, u, v):
 * its world position is v0 + u (v1 - v0) + v (v2 - v0) with v0, v1, v2 the
 * face's corners in the current pose; inside means u >= 0, v >= 0, u + v <= 1. */
#ifndef SKIN_SIM_WALK_H
#define SKIN_SIM_WALK_H

#include <stddef.h>

#include "topo.h"

/* Per-face data of the body in its current pose, computed once per frame
 * (ss_frames_update) and then shared read-only by every anchor update. */
typedef struct ss_frames {
  int nface;
  /* One 128-byte record per face (two adjacent cache lines, 64-byte aligned),
   * all a walk step reads of a face: origin v0 (3), e1 = v1 - v0 (3),
   * e2 = v2 - v0 (3), to_canon (6), then 1.0 where degenerate (else 0.0).
   * to_canon is R^-1 Q^T from the QR of Dm = [e1, e2], 2x3 row-major: it maps a
   * world vector to canonical (u, v) coordinates; regularised on degenerate
   * faces so that it is always finite. Read it through ss_frames_origin,
   * ss_frames_edges, ss_frames_to_canon. */
  double *walk;      /* (nface x 16) */
  double *normal;    /* (nface x 3) unit normal (zero on a degenerate face) */
  double *area;      /* (nface) area */
  unsigned char *degenerate; /* (nface) 1 where the face is too thin for its QR to be
                                inverted in this pose (zero area, collinear corners):
                                to_canon is then the regularised pseudo-inverse and
                                walks pass straight through the face */
  /* Crossing of edge k of face f: -1 (no neighbour), else
   * 8 g + 2 kg + flip, g the neighbour, kg the edge's index in g, flip 1
   * where g runs along the edge the other way. Built from the topology at the
   * first update with it. */
  int *cross;        /* (nface x 3) */
  const ss_topo *cross_topo;
  int isa;           /* vector instruction set of the update (isa.h): the widest the CPU
                        runs unless set otherwise; the same bits from any, and from -1:
                        one face at a time without lanes (the tests' reference) */
} ss_frames;

#define SS_FRAME_RECORD 16 /* doubles per face record in ss_frames.walk */

/* Corner v0 of face f (3 doubles). */
static inline const double *ss_frames_origin(const ss_frames *fr, int f) {
  return fr->walk + SS_FRAME_RECORD * (size_t)f;
}
/* Edges e1 = v1 - v0 then e2 = v2 - v0 of face f (6 doubles). */
static inline const double *ss_frames_edges(const ss_frames *fr, int f) {
  return fr->walk + SS_FRAME_RECORD * (size_t)f + 3;
}
/* The canonical map of face f (2x3 row-major). */
static inline const double *ss_frames_to_canon(const ss_frames *fr, int f) {
  return fr->walk + SS_FRAME_RECORD * (size_t)f + 9;
}

int ss_frames_create(ss_frames **out, int nface);
void ss_frames_destroy(ss_frames *frames);
/* Recomputes all per-face data for positions pos (nvert x 3). Allocates nothing. */
void ss_frames_update(ss_frames *frames, const ss_topo *topo, const double *pos);
/* The same with nthread threads (OpenMP; 1 or a build without it: one):
 * the same bits for any count. */
void ss_frames_update_threads(ss_frames *frames, const ss_topo *topo, const double *pos, int nthread);

/* Asks the memory for face f's record (both lines) ahead of a walk from it:
 * callers walking many anchors call it a few anchors ahead, so that the
 * record arrives while the walks before run. f < 0: nothing. */
#define SS_WALK_PREFETCH 8 /* anchors ahead */
static inline void ss_frames_prefetch(const ss_frames *frames, int f) {
#if defined(__GNUC__)
  if (f >= 0) {
    const double *w = frames->walk + SS_FRAME_RECORD * (size_t)f;
    __builtin_prefetch(w);
    __builtin_prefetch(w + 8);
  }
#else
  (void)frames, (void)f;
#endif
}

/* World position of anchor (face, uv) in the pose of frames (inline: the
 * frame update's callers run it for every anchor). */
static inline void ss_anchor_position(const ss_frames *frames, int face, const double uv[2],
                                      double out[3]) {
  const double *w = frames->walk + SS_FRAME_RECORD * (size_t)face;
  for (int i = 0; i < 3; i++) out[i] = w[i] + uv[0] * w[3 + i] + uv[1] * w[6 + i];
}

enum ss_walk_stop {
  SS_STOP_INSIDE = 0,     /* the ray ended inside a face: the normal case */
  SS_STOP_BOUNDARY = 1,   /* hit a boundary (or non-manifold) edge: stopped on it */
  SS_STOP_CREASE = 2,     /* would re-enter a face already visited: stopped on the edge, at
                             its point nearest the target */
  SS_STOP_STEP_LIMIT = 3  /* crossed walk_max_steps edges: stopped where it was */
};
const char *ss_walk_stop_name(int stop);

typedef struct ss_walk_result {
  int face;      /* final face */
  double uv[2];  /* final canonical coordinates, inside the face */
  int stop;      /* ss_walk_stop */
  int steps;     /* edges crossed */
  double length; /* length of the path walked on the surface (world units): an upper
                    bound of the geodesic distance moved; 0 for project and nring */
} ss_walk_result;

/* Scratch memory for walks (per-face visit stamps): one per thread. */
typedef struct ss_walker ss_walker;
int ss_walker_create(ss_walker **out, int nface);
void ss_walker_destroy(ss_walker *walker);

/* Walks anchor (face, uv) towards target over the pose of frames, crossing at
 * most max_steps edges. Never produces NaN: a non-finite target leaves the
 * anchor where it is (stop INSIDE, 0 steps). Allocates nothing. */
void ss_walk(ss_walker *walker, const ss_topo *topo, const ss_frames *frames, int face,
             const double uv[2], const double target[3], int max_steps,
             ss_walk_result *res);
/* ss_walk without the path's length (res->length 0), the same face and uv:
 * for callers that do not read it (a square root per face walked). */
void ss_walk_unmeasured(ss_walker *walker, const ss_topo *topo, const ss_frames *frames, int face,
                        const double uv[2], const double target[3], int max_steps,
                        ss_walk_result *res);

/* The slide of an anchor held on a leash to `face` (its home face): where
 * the target projects into the face, the walk's end (the same bits); where
 * it projects outside but within SS_LEASH_REACH (in the face's barycentric
 * coordinates: the triangle grown to four times its size about its
 * centroid, about as far as its neighbours reach), the face's point nearest
 * the target, and no walk. Returns 1 with *res set, or 0 (the target is
 * farther, not finite, or the face degenerate): the caller walks. */
#define SS_LEASH_REACH 1.0
int ss_slide_in_face(const ss_frames *frames, int face, const double uv[2], const double target[3],
                     int measure, ss_walk_result *res);

#endif
