/* skin_sim core: anchors on the body surface and the three ways to move them.
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
 */
#ifndef SKIN_SIM_SS_ANCHOR_H
#define SKIN_SIM_SS_ANCHOR_H

#include "ss_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- per-face canonical frames of one pose ---------------------------- */

/* Per-face data of the body in its current pose, computed once per frame
 * (ss_frames_update) and then shared read-only by every anchor update. */
typedef struct ss_frames {
  int nface;
  double *origin;    /* (nface x 3) corner v0 */
  double *edge;      /* (nface x 6) Dm = [v1 - v0, v2 - v0], stored as e1 xyz then e2 xyz */
  double *to_canon;  /* (nface x 6) R^-1 Q^T from the QR of Dm: 2x3 row-major; maps a world
                        vector to canonical (u, v) coordinates. Regularised on degenerate faces
                        so it is always finite. */
  double *normal;    /* (nface x 3) unit normal (zero on a degenerate face) */
  double *area;      /* (nface) area */
  unsigned char *degenerate; /* (nface) 1 where the face is too thin for its QR to be
                                inverted in this pose (zero area, collinear corners):
                                to_canon is then the regularised pseudo-inverse and
                                walks pass straight through the face */
  /* The walk's own copy, one 128-byte record per face (two cache lines):
   * origin, e1, e2, to_canon, then 1.0 where degenerate (else 0.0). */
  double *walk;      /* (nface x 16) */
  /* Crossing of edge k of face f: -1 (no neighbour), else
   * 8 g + 2 kg + flip, g the neighbour, kg the edge's index in g, flip 1
   * where g runs along the edge the other way. Built from the topology at the
   * first update with it. */
  int *cross;        /* (nface x 3) */
  const ss_topo *cross_topo;
} ss_frames;

int ss_frames_create(ss_frames **out, int nface);
void ss_frames_destroy(ss_frames *frames);
/* Recomputes all per-face data for positions pos (nvert x 3). Allocates nothing. */
void ss_frames_update(ss_frames *frames, const ss_topo *topo, const double *pos);

/* World position of anchor (face, uv) in the pose of frames. */
void ss_anchor_position(const ss_frames *frames, int face, const double uv[2], double out[3]);

/* ---- the walk (paper, section 2) ---------------------------------------- */

enum ss_walk_stop {
  SS_STOP_INSIDE = 0,     /* the ray ended inside a face: the normal case */
  SS_STOP_BOUNDARY = 1,   /* hit a boundary (or non-manifold) edge: stopped on it */
  SS_STOP_CREASE = 2,     /* would re-enter a face already visited: stopped on the edge */
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

/* ---- closest points: the baselines -------------------------------------- */

/* Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision
 * Detection 5.1.5). Writes its canonical coordinates uv and returns the squared
 * distance. Robust on degenerate triangles. */
double ss_closest_point_triangle(const double p[3], const double a[3], const double b[3],
                                 const double c[3], double uv[2]);

/* Bounding volume hierarchy over the body's faces: built once per topology,
 * refitted per pose. */
typedef struct ss_bvh ss_bvh;
int ss_bvh_create(ss_bvh **out, const ss_topo *topo);
void ss_bvh_destroy(ss_bvh *bvh);
/* Refits boxes to positions pos (nvert x 3). Allocates nothing. */
void ss_bvh_refit(ss_bvh *bvh, const double *pos);
/* Exact Euclidean closest point on the whole mesh (pose of the last refit);
 * ties go to the lower face index. Returns the squared distance. */
double ss_bvh_closest(const ss_bvh *bvh, const double *pos, const double p[3], int *face,
                      double uv[2]);

/* Scratch for n-ring searches: one per thread. */
typedef struct ss_nring ss_nring;
int ss_nring_create(ss_nring **out, const ss_topo *topo);
void ss_nring_destroy(ss_nring *nring);
/* Closest point to p among the faces within `rings` vertex rings of face
 * (rings = 0: the face alone; 1: faces sharing a vertex with it; ...).
 * Returns the squared distance. */
double ss_nring_closest(ss_nring *nring, const ss_topo *topo, const double *pos, int face,
                        int rings, const double p[3], int *face_out, double uv[2]);

/* ---- one interface for all three methods ---------------------------------- */

typedef struct ss_mover_settings {
  int method;          /* ss_method; default SS_METHOD_WALK */
  int walk_max_steps;  /* bound on edges crossed by one walk; default 512 */
  int nring_rings;     /* N for SS_METHOD_NRING; default 2 */
} ss_mover_settings;
ss_mover_settings ss_mover_default_settings(void);

/* Holds per-pose frames and the scratch of the chosen method. */
typedef struct ss_mover ss_mover;
int ss_mover_create(ss_mover **out, const ss_topo *topo, const ss_mover_settings *settings,
                    char *err, int err_sz);
void ss_mover_destroy(ss_mover *mover);
/* Sets the body pose for the following moves (frames, and the BVH refit for
 * project). Allocates nothing. */
void ss_mover_set_pose(ss_mover *mover, const double *pos);
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

/* ---- surface distance (for snag detection) -------------------------------- */

/* Scratch for surface distances on one topology. */
typedef struct ss_geodesic ss_geodesic;
int ss_geodesic_create(ss_geodesic **out, const ss_topo *topo);
void ss_geodesic_destroy(ss_geodesic *geo);
/* Distance along the surface between two anchors in pose pos: straight line
 * when both are in one face, else the shortest path that leaves a through a
 * corner of its face, follows mesh edges (Dijkstra over welded vertices) and
 * enters b's face through one of its corners. An upper bound of the true
 * geodesic distance, exact on a flat face. The search stops once paths exceed
 * `limit`, and then returns INFINITY: cost grows with limit, not with mesh size. */
double ss_surface_distance(ss_geodesic *geo, const ss_topo *topo, const double *pos,
                           int face_a, const double uv_a[2], int face_b, const double uv_b[2],
                           double limit);

#ifdef __cplusplus
}
#endif
#endif
