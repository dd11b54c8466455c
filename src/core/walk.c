/* The anchor walk of Kautzman, Cameron and Kim, "Robust Skin Simulation in
 * Incredibles 2" (SIGGRAPH 2018 Talks), section 2, and the per-face canonical
 * frames it runs on.
 *
 * Canonical frames. For face (v0, v1, v2), Dm = [v1 - v0, v2 - v0] = Q R
 * (Gram-Schmidt QR, Q 3x2 orthonormal, R 2x2 upper triangular). The map
 * T = R^-1 Q^T takes a world vector to canonical (u, v): the face becomes the
 * triangle (0,0), (1,0), (0,1), and T (p - v0) is the orthogonal projection
 * of p onto the face's plane in those coordinates. T is computed once per face
 * and pose (ss_frames_update), so a step of the walk costs a 2x3 product and
 * three line tests. Faces too thin for R to be inverted (|r22| tiny against
 * |r11|: zero-area and collinear faces) get the regularised pseudo-inverse
 * (Dm^T Dm + eps I)^-1 Dm^T instead, which is finite, moves a point along the
 * degenerate face's line, and is zero on a face collapsed to a point.
 *
 * The walk. From a point p inside face f, the ray p + t d_hat with
 * d_hat = T (a* - world(p)) is traced against the three canonical edges. If it
 * ends inside (t = 1 reached), that point is the new anchor and it is the
 * orthogonal projection of a* onto the face, as the paper asks. Otherwise it
 * leaves through edge k at h: with no face across k (boundary or non-manifold
 * edge) the walk stops at h; across k lies g: if g was already visited in this
 * walk the surface folds back (a crease) and the walk stops on edge k at its
 * point nearest a* ("the optimal anchor position lies along an edge");
 * else h is carried to the same point of the shared edge in g (matched by
 * welded vertex ids, so neighbours of either orientation work), and tracing
 * starts again in g towards a*. Points are clamped into the canonical
 * triangle after every crossing and at the end (the paper's "simple clamp"),
 * and the number of crossings is bounded.
 *
 * Zero-area faces are the one place where the paper's recipe is silent: a
 * ray cannot be traced across a face with no interior, and a walk entering
 * one would stop there as if at a crease. Such a face has all its edges on
 * one line, so the entry point also lies on one of its other edges: the walk
 * passes straight through onto the neighbour across that edge (a crossing
 * like any other, counted and bounded), and traces on from there. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "walk.h"
#include "walk_step.h"
#include "isa.h"
#include "ss_vec.h"
#include "ss_free.h"

/* ---- frames ------------------------------------------------------------- */

int ss_frames_create(ss_frames **out, int nface) {
  if (!out || nface <= 0) return SS_E_ARG;
  *out = NULL;
  ss_frames *fr = calloc(1, sizeof *fr);
  if (!fr) return SS_E_NOMEM;
  fr->nface = nface;
  fr->isa = ss_isa_best();
  fr->normal = malloc(sizeof(double) * 3 * (size_t)nface);
  fr->area = malloc(sizeof(double) * (size_t)nface);
  fr->degenerate = malloc((size_t)nface);
  fr->walk = aligned_alloc(64, sizeof(double) * SS_FRAME_RECORD * (size_t)nface);
  fr->cross = malloc(sizeof(int) * 3 * (size_t)nface);
  if (!fr->normal || !fr->area || !fr->degenerate || !fr->walk || !fr->cross) {
    ss_frames_destroy(fr);
    return SS_E_NOMEM;
  }
  *out = fr;
  return SS_OK;
}

void ss_frames_destroy(ss_frames *fr) {
  if (!fr) return;
  SS_FREE_ALL(fr->normal, fr->area, fr->degenerate, fr->walk, fr->cross, fr);
}

/* T for one face from its edges e1, e2 (see the file comment). Returns 1
 * where the face is degenerate and T is the regularised pseudo-inverse. */
static int canonical_map(const double e1[3], const double e2[3], double t[6]) {
  const double r11 = sqrt(dot3(e1, e1));
  if (r11 > 0.0 && isfinite(r11)) {
    double q1[3] = {e1[0] / r11, e1[1] / r11, e1[2] / r11};
    const double r12 = dot3(q1, e2);
    double w[3] = {e2[0] - r12 * q1[0], e2[1] - r12 * q1[1], e2[2] - r12 * q1[2]};
    const double r22 = sqrt(dot3(w, w));
    if (r22 > 1e-10 * r11) {
      /* R^-1 = [[1/r11, -r12/(r11 r22)], [0, 1/r22]]; rows of R^-1 Q^T */
      const double a = 1.0 / r11, b = -r12 / (r11 * r22), c = 1.0 / r22;
      for (int i = 0; i < 3; i++) {
        double q2 = w[i] / r22;
        t[i] = a * q1[i] + b * q2;
        t[3 + i] = c * q2;
      }
      return 0;
    }
  }
  /* degenerate: (Dm^T Dm + eps I)^-1 Dm^T */
  double m00 = dot3(e1, e1), m01 = dot3(e1, e2), m11 = dot3(e2, e2);
  double eps = 1e-10 * (m00 + m11);
  if (!(eps > 0.0) || !isfinite(eps)) {
    memset(t, 0, 6 * sizeof(double));
    return 1;
  }
  m00 += eps;
  m11 += eps;
  const double det = m00 * m11 - m01 * m01;
  const double i00 = m11 / det, i01 = -m01 / det, i11 = m00 / det;
  for (int i = 0; i < 3; i++) {
    t[i] = i00 * e1[i] + i01 * e2[i];
    t[3 + i] = i01 * e1[i] + i11 * e2[i];
  }
  return 1;
}

/* The crossings of every edge (see ss_frames.cross), once per topology. */
static void build_crossings(ss_frames *fr, const ss_topo *topo) {
  for (int f = 0; f < topo->nface; f++)
    for (int k = 0; k < 3; k++) {
      const int g = topo->face_adj[3 * f + k], kg = topo->face_adj_edge[3 * f + k];
      if (g < 0 || kg < 0) {
        fr->cross[3 * f + k] = -1;
        continue;
      }
      const int start_f = topo->vert_weld[topo->face_vert[3 * f + k]];
      const int start_g = topo->vert_weld[topo->face_vert[3 * g + kg]];
      fr->cross[3 * f + k] = 8 * g + 2 * kg + (start_f == start_g ? 0 : 1);
    }
  fr->cross_topo = topo;
}

/* Face f's walk record (origin, edges, canonical map, degenerate flag),
 * normal and area, each written once. */
static inline void frame_update_face(ss_frames *fr, const int *fv, const double *pos, int f) {
  const double *v0 = pos + 3 * fv[3 * f];
  const double *v1 = pos + 3 * fv[3 * f + 1];
  const double *v2 = pos + 3 * fv[3 * f + 2];
  double *w = fr->walk + SS_FRAME_RECORD * (size_t)f, *n = fr->normal + 3 * f;
  double *o = w, *e = w + 3;
  for (int i = 0; i < 3; i++) {
    o[i] = v0[i];
    e[i] = v1[i] - v0[i];
    e[3 + i] = v2[i] - v0[i];
  }
  n[0] = e[1] * e[5] - e[2] * e[4];
  n[1] = e[2] * e[3] - e[0] * e[5];
  n[2] = e[0] * e[4] - e[1] * e[3];
  double len = sqrt(dot3(n, n));
  fr->area[f] = 0.5 * len;
  if (len > 0.0 && isfinite(len)) {
    n[0] /= len, n[1] /= len, n[2] /= len;
  } else {
    n[0] = n[1] = n[2] = 0.0;
  }
  const int deg = canonical_map(e, e + 3, w + 9);
  fr->degenerate[f] = (unsigned char)deg;
  w[15] = deg ? 1.0 : 0.0;
}

/* Faces [f0, f1) as frame_update_face computes them, SS_FRAME_LANES at a
 * time: corners gathered into lanes, one elementwise loop (the same
 * operations in the same order, so the same bits at any vector width), and
 * the faces whose normal or QR needs a branch of frame_update_face (zero
 * area, degenerate, non-finite) done again by it. One face at a time its 12
 * divisions and 3 square roots were most of the pose stage. */
#define SS_FRAME_LANES 8
static inline SS_ALWAYS_INLINE void frames_kernel(ss_frames *fr, const int *fv, const double *pos,
                                                  int f0, int f1) {
  enum { L = SS_FRAME_LANES };
  for (int fb = f0; fb < f1; fb += L) {
    const int m = f1 - fb < L ? f1 - fb : L;
    double vs[9][L], rec[15][L], nl[3][L], al[L], ok[L];
    for (int l = 0; l < L; l++) {
      const int *c = fv + 3 * (fb + (l < m ? l : 0));
      for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) vs[3 * k + i][l] = pos[3 * c[k] + i];
    }
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) {
      const double ox = vs[0][l], oy = vs[1][l], oz = vs[2][l];
      const double e0 = vs[3][l] - ox, e1 = vs[4][l] - oy, e2 = vs[5][l] - oz;
      const double e3 = vs[6][l] - ox, e4 = vs[7][l] - oy, e5 = vs[8][l] - oz;
      const double n0 = e1 * e5 - e2 * e4, n1 = e2 * e3 - e0 * e5, n2 = e0 * e4 - e1 * e3;
      const double len = sqrt(n0 * n0 + n1 * n1 + n2 * n2);
      al[l] = 0.5 * len;
      nl[0][l] = n0 / len, nl[1][l] = n1 / len, nl[2][l] = n2 / len;
      /* canonical_map's regular branch */
      const double r11 = sqrt(e0 * e0 + e1 * e1 + e2 * e2);
      const double q0 = e0 / r11, q1 = e1 / r11, q2 = e2 / r11;
      const double r12 = q0 * e3 + q1 * e4 + q2 * e5;
      const double w0 = e3 - r12 * q0, w1 = e4 - r12 * q1, w2 = e5 - r12 * q2;
      const double r22 = sqrt(w0 * w0 + w1 * w1 + w2 * w2);
      const double a = 1.0 / r11, b = -r12 / (r11 * r22), c = 1.0 / r22;
      const double u0 = w0 / r22, u1 = w1 / r22, u2 = w2 / r22;
      rec[0][l] = ox, rec[1][l] = oy, rec[2][l] = oz;
      rec[3][l] = e0, rec[4][l] = e1, rec[5][l] = e2;
      rec[6][l] = e3, rec[7][l] = e4, rec[8][l] = e5;
      rec[9][l] = a * q0 + b * u0, rec[10][l] = a * q1 + b * u1, rec[11][l] = a * q2 + b * u2;
      rec[12][l] = c * u0, rec[13][l] = c * u1, rec[14][l] = c * u2;
      /* len > 0 and finite, r11 > 0 and finite, r22 > 1e-10 r11: else
       * frame_update_face's other branches. The tests joined by & (all
       * evaluated), not &&: the branches of && kept GCC from vectorising
       * the loop for AVX2 (only AVX-512's masks took them), and on an AVX2
       * CPU the pose stage would run one face at a time. */
      ok[l] = (double)((len > 0.0) & (len <= DBL_MAX) & (r11 > 0.0) & (r11 <= DBL_MAX) & (r22 > 1e-10 * r11));
    }
    for (int l = 0; l < m; l++) {
      const int f = fb + l;
      if (ok[l] == 0.0) {
        frame_update_face(fr, fv, pos, f);
        continue;
      }
      double *w = fr->walk + SS_FRAME_RECORD * (size_t)f, *n = fr->normal + 3 * (size_t)f;
      for (int i = 0; i < 15; i++) w[i] = rec[i][l];
      w[15] = 0.0;
      n[0] = nl[0][l], n[1] = nl[1][l], n[2] = nl[2][l];
      fr->area[f] = al[l];
      fr->degenerate[f] = 0;
    }
  }
}

SS_ISA_VARIANTS(frames, (ss_frames *fr, const int *fv, const double *pos, int f0, int f1),
                frames_kernel(fr, fv, pos, f0, f1);)

/* Faces [f0, f1) in fr->isa's vectors (isa < 0: one face at a time, the
 * reference the kernels are tested against). */
static void frames_range(ss_frames *fr, const int *fv, const double *pos, int f0, int f1) {
  if (fr->isa < 0) {
    for (int f = f0; f < f1; f++) frame_update_face(fr, fv, pos, f);
    return;
  }
  SS_ISA_CALL(fr->isa, frames, (fr, fv, pos, f0, f1));
}

void ss_frames_update(ss_frames *fr, const ss_topo *topo, const double *pos) {
  ss_frames_update_threads(fr, topo, pos, 1);
}

/* One pass over the faces in blocks of SS_FRAME_LANES; each face is its own
 * (the same bits for any thread count). */
void ss_frames_update_threads(ss_frames *fr, const ss_topo *topo, const double *pos, int nthread) {
  if (fr->cross_topo != topo) build_crossings(fr, topo);
  const int *fv = topo->face_vert;
  const int nface = topo->nface;
#ifdef _OPENMP
  if (nthread > 1) {
    const int nblock = (nface + SS_FRAME_LANES - 1) / SS_FRAME_LANES;
#pragma omp parallel for schedule(static) num_threads(nthread)
    for (int b = 0; b < nblock; b++) {
      const int f0 = b * SS_FRAME_LANES, f1 = nface - f0 < SS_FRAME_LANES ? nface : f0 + SS_FRAME_LANES;
      frames_range(fr, fv, pos, f0, f1);
    }
    return;
  }
#else
  (void)nthread;
#endif
  frames_range(fr, fv, pos, 0, nface);
}

/* World point of canonical uv on face f (the walk's hot path: inlined). */
static inline void face_point(const ss_frames *fr, int f, const double uv[2], double out[3]) {
  ss_anchor_position(fr, f, uv, out);
}

/* ---- the walk ------------------------------------------------------------ */

const char *ss_walk_stop_name(int stop) {
  switch (stop) {
    case SS_STOP_INSIDE: return "inside";
    case SS_STOP_BOUNDARY: return "boundary";
    case SS_STOP_CREASE: return "crease";
    case SS_STOP_STEP_LIMIT: return "step_limit";
    default: return "unknown";
  }
}

/* One cache line of its own: each thread walks with its own walker and
 * writes its stamp at every walk that crosses an edge; two walkers side by
 * side in one line (as malloc places them) had the threads take the line
 * from each other at every such walk. */
struct ss_walker {
  _Alignas(64) int nface;
  unsigned int stamp;    /* id of the current walk */
  unsigned int *visited; /* (nface) stamp of the last walk that entered the face */
};
_Static_assert(sizeof(struct ss_walker) % 64 == 0, "a walker fills whole cache lines");

int ss_walker_create(ss_walker **out, int nface) {
  if (!out || nface <= 0) return SS_E_ARG;
  *out = NULL;
  ss_walker *w = aligned_alloc(64, sizeof *w); /* sizeof is a multiple of 64 */
  if (!w) return SS_E_NOMEM;
  memset(w, 0, sizeof *w);
  w->nface = nface;
  w->visited = calloc((size_t)nface, sizeof(unsigned int));
  if (!w->visited) {
    free(w);
    return SS_E_NOMEM;
  }
  *out = w;
  return SS_OK;
}

void ss_walker_destroy(ss_walker *w) {
  if (!w) return;
  free(w->visited);
  free(w);
}

/* Canonical point at parameter s (0 at corner k, 1 at corner k+1) of edge k. */
static void edge_point(int k, double s, double uv[2]) {
  switch (k) {
    case 0: uv[0] = s, uv[1] = 0.0; break;        /* (0,0) -> (1,0) */
    case 1: uv[0] = 1.0 - s, uv[1] = s; break;    /* (1,0) -> (0,1) */
    default: uv[0] = 0.0, uv[1] = 1.0 - s; break; /* (0,1) -> (0,0) */
  }
}

/* Parameter of canonical point uv along edge k (inverse of edge_point). */
static double edge_param(int k, const double uv[2]) {
  double s = k == 0 ? uv[0] : k == 1 ? uv[1] : 1.0 - uv[1];
  return s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
}

/* Squared distance from world point x to edge k of face f, and the edge
 * parameter of the closest point. */
static double edge_dist2(const ss_frames *fr, int f, int k, const double x[3], double *s_out) {
  double a[3], b[3], ca[2], cb[2];
  edge_point(k, 0.0, ca);
  edge_point(k, 1.0, cb);
  face_point(fr, f, ca, a);
  face_point(fr, f, cb, b);
  double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double ax[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
  double l2 = dot3(ab, ab), s = l2 > 0.0 ? dot3(ax, ab) / l2 : 0.0;
  s = s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
  double d2 = 0.0;
  for (int i = 0; i < 3; i++) {
    double d = a[i] + s * ab[i] - x[i];
    d2 += d * d;
  }
  *s_out = s;
  return d2;
}

/* Crosses edge k of face *f at parameter s into the neighbour: updates *f
 * and p (canonical point in the new face) and returns SS_STOP_INSIDE, or
 * returns why it cannot (boundary, crease, step bound), leaving *f and p. */
static inline int cross_edge(ss_walker *walker, const int *cross, int *f, int k, double s, double p[2],
                             int max_steps, int *steps) {
  const int cr = cross[3 * *f + k];
  if (cr < 0) return SS_STOP_BOUNDARY;
  const int g = cr >> 3;
  if (walker->visited[g] == walker->stamp) return SS_STOP_CREASE;
  if (*steps >= max_steps) return SS_STOP_STEP_LIMIT;
  /* the same point of the shared edge, in g, matched by welded end points */
  const int kg = (cr >> 1) & 3;
  edge_point(kg, (cr & 1) == 0 ? s : 1.0 - s, p);
  *f = g;
  walker->visited[g] = walker->stamp;
  ++*steps;
  return SS_STOP_INSIDE;
}

/* In a degenerate face (zero area) the entry point lies on another of its
 * edges too: all three are on one line, or at one point. Ray tracing cannot
 * see across such a face, so the walk passes through it onto the unvisited
 * neighbour across the edge nearest to the point (within round-off of the
 * face's size), as if the face were not there. Returns that edge or -1. */
static int pass_through_edge(const ss_walker *walker, const ss_topo *topo, const ss_frames *fr,
                             int f, const double p[2], double *s_out) {
  const double *e = ss_frames_edges(fr, f);
  const double size2 = dot3(e, e) + dot3(e + 3, e + 3);
  double x[3];
  face_point(fr, f, p, x);
  int best_k = -1;
  double best_d2 = 1e-18 * size2;
  for (int k = 0; k < 3; k++) {
    const int g = topo->face_adj[3 * f + k];
    if (g < 0 || walker->visited[g] == walker->stamp) continue;
    double s;
    double d2 = edge_dist2(fr, f, k, x, &s);
    if (d2 <= best_d2) {
      if (best_k >= 0 && d2 == best_d2) continue; /* ties: the lower edge */
      best_d2 = d2;
      best_k = k;
      *s_out = s;
    }
  }
  return best_k;
}

/* The walk; with `measure` 0 (a constant: two copies) the path's length is
 * not summed (res->length 0): a square root per face walked less, on the
 * chain of dependent operations every walk is. */
static inline SS_ALWAYS_INLINE void walk(ss_walker *walker, const ss_topo *topo, const ss_frames *fr,
                                         int face, const double uv[2], const double target[3],
                                         int max_steps, ss_walk_result *res, const int measure) {
  /* Scalars, not arrays, for the point and what every step computes: the
   * compiler keeps them in registers (a point stored element by element and
   * read back as one vector stalls the load). The arithmetic and its order
   * are those of dot3 and face_point. */
  double pu = uv[0], pv = uv[1];
  clamp_uv(&pu, &pv);
  result_in_face(res, face, pu, pv, 0.0); /* where it stays if it cannot walk */
  const double ax = target[0], ay = target[1], az = target[2];
  if (!finite2(ax, ay) || !finite2(az, 0.0)) return;

  int f = face;
  const int *cross = fr->cross;
  double length = 0.0;
  int stamped = 0; /* this walk's stamp taken and its start face marked (at its first crossing) */
  int steps = 0;   /* edges crossed */
  for (;;) {
    /* direction towards a* in f's canonical space */
    const double *w = fr->walk + SS_FRAME_RECORD * (size_t)f; /* origin, e1, e2, to_canon */
    double du, dv;
    ray_direction(w, pu, pv, ax, ay, az, &du, &dv);
    if (!finite2(du, dv)) break; /* stay where we are */

    /* Most rays end inside their face. An edge's exit parameter te = a / b
     * (b > 0) is >= 1 when a >= b exactly (rounding is monotone), so where
     * all three compare so, no edge is crossed, as the divisions below would
     * find, without them. The smallest ray parameter at which the ray
     * leaves the triangle: */
    double t_exit = 1.0;
    int k_exit = -1;
    const double sum = du + dv, rest = 1.0 - pu - pv;
    /* The point is never negative (clamped at the start, on an edge after a
     * crossing), so edge 0 is not crossed (dv >= 0, or pv >= -dv) exactly
     * where pv + dv >= 0: a rounded sum has the sign of the exact one. The
     * same for edge 2, and the sums are the end point's if it is inside. */
    double qu = pu + du, qv = pv + dv;
    if (!(qv >= 0.0 && (!(sum > 0.0) || rest >= sum) && qu >= 0.0)) {
      /* Only the edges that test failed: where it passed, the exit
       * parameter is >= 1 (see above) and would not be taken. */
      if (qv < 0.0) { /* edge 0: v = 0 (dv < -pv <= 0) */
        double te = -pv / dv;
        if (te < t_exit) t_exit = te, k_exit = 0;
      }
      if (sum > 0.0 && rest < sum) { /* edge 1: u + v = 1 */
        double te = rest / sum;
        if (te < t_exit) t_exit = te, k_exit = 1;
      }
      if (qu < 0.0) { /* edge 2: u = 0 */
        double te = -pu / du;
        if (te < t_exit) t_exit = te, k_exit = 2;
      }
    }
    if (k_exit < 0) { /* ends inside f: the orthogonal projection of a* */
      clamp_uv(&qu, &qv);
      if (measure) length += canonical_length(w + 3, qu - pu, qv - pv);
      pu = qu, pv = qv;
      break;
    }
    if (t_exit < 0.0) t_exit = 0.0;
    double p[2], h[2] = {pu + t_exit * du, pv + t_exit * dv};
    double s = edge_param(k_exit, h);
    if (measure) {
      edge_point(k_exit, s, p); /* exactly on the edge */
      length += canonical_length(w + 3, p[0] - pu, p[1] - pv);
    }
    if (!stamped) {
      if (++walker->stamp == 0) { /* wrapped after 2^32 walks: forget old stamps */
        memset(walker->visited, 0, sizeof(unsigned int) * (size_t)walker->nface);
        walker->stamp = 1;
      }
      walker->visited[face] = walker->stamp;
      stamped = 1;
    }
    int k_edge = k_exit; /* the edge p lies on */
    int stop = cross_edge(walker, cross, &f, k_exit, s, p, max_steps, &steps);
    /* stopped: on the edge met, exactly (a crossing put p in the neighbour,
     * and unmeasured, the point on this side is needed only here) */
    if (stop != SS_STOP_INSIDE && !measure) edge_point(k_exit, s, p);
    while (stop == SS_STOP_INSIDE && fr->walk[SS_FRAME_RECORD * (size_t)f + 15] != 0.0) {
      const int k_pass = pass_through_edge(walker, topo, fr, f, p, &s);
      if (k_pass < 0) break;
      k_edge = k_pass;
      stop = cross_edge(walker, cross, &f, k_pass, s, p, max_steps, &steps);
    }
    if (stop == SS_STOP_CREASE) {
      /* "the optimal anchor position lies along an edge": the point of the
       * crease edge nearest a*, not where the ray happened to meet it. At
       * the ray's point an anchor pulled along a ridge (a tether walking
       * home round the rim of a capsule's cap) met it again at the same
       * point every frame and stayed there for good (twist, 1000
       * triangles, settling after the motion: 18 anchors, a third to half a
       * turn from home, did not move in 10 s). */
      const double hu = p[0], hv = p[1];
      double se = NAN;
      edge_dist2(fr, f, k_edge, target, &se);
      if (isfinite(se)) { /* NaN where the face's corners overflow: stay at h */
        edge_point(k_edge, se, p);
        if (measure) length += canonical_length(ss_frames_edges(fr, f), p[0] - hu, p[1] - hv);
      }
    }
    pu = p[0], pv = p[1];
    if (stop != SS_STOP_INSIDE) {
      res->stop = stop;
      break;
    }
  }
  res->face = f;
  res->uv[0] = pu;
  res->uv[1] = pv;
  res->steps = steps;
  res->length = length;
}

void ss_walk(ss_walker *walker, const ss_topo *topo, const ss_frames *fr, int face,
             const double uv[2], const double target[3], int max_steps, ss_walk_result *res) {
  walk(walker, topo, fr, face, uv, target, max_steps, res, 1);
}

void ss_walk_unmeasured(ss_walker *walker, const ss_topo *topo, const ss_frames *fr, int face,
                        const double uv[2], const double target[3], int max_steps,
                        ss_walk_result *res) {
  walk(walker, topo, fr, face, uv, target, max_steps, res, 0);
}

int ss_slide_in_face(const ss_frames *fr, int face, const double uv[2], const double target[3],
                     int measure, ss_walk_result *res) {
  return ss_slide_in_face_inline(fr, face, uv, target, measure, res);
}
