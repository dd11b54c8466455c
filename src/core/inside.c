/* The generalized winding number of the body around a point (inside.h).
 *
 * Each node of the BVH's tree (bvh.c: built at rest, the same tree every
 * pose) carries the first-order moments of its faces in the current pose:
 * the area vector N = sum of (e1 x e2) / 2, the area-weighted centroid c and
 * a radius r bounding its faces around c. Seen from a point p farther than
 * SS_WIND_BETA r, the node's solid angle is that of a dipole,
 * N . (c - p) / |c - p|^3 (Barill et al. 2018, first order); nearer, its
 * children are visited, down to each face's exact solid angle (Van
 * Oosterom and Strackee 1983). The dipole's relative error falls like
 * (r / |c - p|)^2: at 3 radii the total stays within a few hundredths of
 * the exact sum, far from the thresholds (1/2, and 1/2 +- 1/4 on the surface; the core test
 * test_inside checks it against the exact sum on a body with both).
 *
 * Deterministic: a fixed traversal order. The refit's subtrees may run on
 * the sim's threads (each its own nodes, the few nodes above them merged
 * on one), the same bits for any count; a number is one point's, on the
 * caller's thread. */
#include "inside.h"

#include <math.h>
#include <stdlib.h>

#include "closest.h"
#include "isa.h"
#include "ss_free.h"

#define WIND_STACK 256 /* bvh.c's MAX_DEPTH 96 with both children pushed */
#define FOUR_PI 12.566370614359172953850573533118 /* 4 pi: the full solid angle */

/* Subtrees the refit cuts the tree into for the threads (its nodes at this
 * depth, and leaves above it): 16 of about equal size on bvh.c's median
 * splits, enough for two threads to share evenly. */
#define WIND_CUT_DEPTH 4

struct ss_wind {
  const ss_topo *topo;
  ss_bvh_shape s;
  double *mom;   /* (nnode x 8) N xyz, c xyz, r, area */
  int *corner;   /* (3 nface) the corners of face face_order[i] at 3 i: a leaf's faces' corners
                    side by side, one load of indices away from their positions */
  int *vstart;   /* (nnode + 1) CSR: leaf q's distinct corners vert[vstart[q] .. vstart[q + 1]) */
  int *vert;     /* (none for an internal node), in the order first met among its faces' corners:
                    its box and radius over each once (the 19k quadruped's leaves: 7.2 distinct
                    corners of 8.6) */
  int ncut;      /* subtrees for the threads (0: the tree is swept whole) */
  int *cut;      /* (ncut) their roots, */
  int *cut_lo;   /* (ncut) a root's descendants nodes cut_lo .. cut_end - 1 */
  int *cut_end;  /* (ncut) */
  int ntop;      /* nodes above the subtrees, */
  int *top;      /* (ntop) in decreasing order: merged after them */
};

/* The subtrees of the refit on the threads: the nodes at WIND_CUT_DEPTH
 * (and leaves above it), each with its descendants in one range of the
 * order (as bvh.c numbers them: a node's two children side by side, then
 * the left one's descendants, then the right one's); none if they are not.
 * tmp: scratch of 4 nnode ints. */
static void find_cuts(ss_wind *w, int *tmp) {
  const ss_bvh_shape *s = &w->s;
  int *depth = tmp, *size = tmp + s->nnode, *dlo = tmp + 2 * s->nnode, *dhi = tmp + 3 * s->nnode;
  depth[0] = 0;
  for (int q = 0; q < s->nnode; q++)
    if (s->left[q] >= 0) depth[s->left[q]] = depth[s->right[q]] = depth[q] + 1;
  for (int q = s->nnode - 1; q >= 0; q--) { /* children after their parent */
    const int l = s->left[q], r = s->right[q];
    if (l < 0) {
      size[q] = 1, dlo[q] = s->nnode, dhi[q] = -1; /* no descendants */
      continue;
    }
    size[q] = 1 + size[l] + size[r];
    dlo[q] = l < r ? l : r;
    dlo[q] = dlo[l] < dlo[q] ? dlo[l] : dlo[q];
    dlo[q] = dlo[r] < dlo[q] ? dlo[r] : dlo[q];
    dhi[q] = l > r ? l : r;
    dhi[q] = dhi[l] > dhi[q] ? dhi[l] : dhi[q];
    dhi[q] = dhi[r] > dhi[q] ? dhi[r] : dhi[q];
  }
  w->ncut = w->ntop = 0;
  for (int q = 0; q < s->nnode; q++) {
    if (depth[q] > WIND_CUT_DEPTH || (depth[q] < WIND_CUT_DEPTH && s->left[q] >= 0)) continue;
    if (s->left[q] >= 0 && dhi[q] - dlo[q] + 2 != size[q]) {
      w->ncut = 0; /* descendants not in one range: the tree is swept whole */
      return;
    }
    w->cut[w->ncut] = q;
    w->cut_lo[w->ncut] = s->left[q] < 0 ? 0 : dlo[q];
    w->cut_end[w->ncut++] = s->left[q] < 0 ? 0 : dhi[q] + 1;
  }
  for (int q = s->nnode - 1; q >= 0; q--)
    if (depth[q] < WIND_CUT_DEPTH && s->left[q] >= 0) w->top[w->ntop++] = q;
}

int ss_wind_create(ss_wind **out, const ss_bvh *bvh, const ss_topo *topo) {
  if (!out || !bvh || !topo) return SS_E_ARG;
  *out = NULL;
  ss_bvh_shape s = ss_bvh_get_shape(bvh);
  if (s.nnode <= 0) return SS_E_ARG; /* not refitted yet: no tree */
  ss_wind *w = calloc(1, sizeof *w);
  if (!w) return SS_E_NOMEM;
  w->topo = topo;
  w->s = s;
  int nslot = 0; /* faces under the leaves */
  for (int q = 0; q < s.nnode; q++)
    if (s.left[q] < 0 && s.first[q] + s.count[q] > nslot) nslot = s.first[q] + s.count[q];
  const size_t nn = (size_t)s.nnode + 1;
  w->mom = malloc(sizeof(double) * 8 * (size_t)s.nnode);
  w->corner = malloc(sizeof(int) * (3 * (size_t)nslot + 1));
  w->vstart = malloc(sizeof(int) * nn);
  w->vert = malloc(sizeof(int) * (3 * (size_t)nslot + 1));
  w->cut = malloc(sizeof(int) * nn);
  w->cut_lo = malloc(sizeof(int) * nn);
  w->cut_end = malloc(sizeof(int) * nn);
  w->top = malloc(sizeof(int) * nn);
  int *tmp = malloc(sizeof(int) * 4 * nn);
  if (!w->mom || !w->corner || !w->vstart || !w->vert || !w->cut || !w->cut_lo || !w->cut_end || !w->top || !tmp) {
    free(tmp);
    ss_wind_destroy(w);
    return SS_E_NOMEM;
  }
  int nv = 0;
  for (int q = 0; q < s.nnode; q++) {
    w->vstart[q] = nv;
    if (s.left[q] >= 0) continue;
    for (int i = s.first[q]; i < s.first[q] + s.count[q]; i++)
      for (int k = 0; k < 3; k++) {
        const int v = topo->face_vert[3 * s.face_order[i] + k];
        w->corner[3 * i + k] = v;
        int seen = 0;
        for (int u = w->vstart[q]; u < nv && !seen; u++) seen = w->vert[u] == v;
        if (!seen) w->vert[nv++] = v;
      }
  }
  w->vstart[s.nnode] = nv;
  find_cuts(w, tmp);
  free(tmp);
  *out = w;
  return SS_OK;
}

void ss_wind_destroy(ss_wind *w) {
  if (!w) return;
  SS_FREE_ALL(w->mom, w->corner, w->vstart, w->vert, w->cut, w->cut_lo, w->cut_end, w->top, w);
}

/* max(a, b) as fmax for the values here (a NaN passed over), inline. */
static inline double max_num(double a, double b) { return a > b || b != b ? a : b; }

/* Leaf q's moments from its faces (and its box into box, if not NULL): the
 * radius bounds every corner of its faces around its centroid, each
 * distinct corner once, and the box is over the same corners as bvh.c's
 * face boxes (a NaN passed over; a corner met again changes no minimum or
 * maximum, so the bits are those of a sweep over every face's corners).
 * Written out per coordinate, in locals: one pass over the faces, one over
 * the distinct corners (L1-hot by then). */
static void refit_leaf(ss_wind *w, const double *pos, double *box, int q) {
  double Nx = 0.0, Ny = 0.0, Nz = 0.0, cx = 0.0, cy = 0.0, cz = 0.0, area = 0.0;
  const int *fv = w->corner + 3 * w->s.first[q], *fend = fv + 3 * w->s.count[q];
  for (; fv < fend; fv += 3) {
    const double *a = pos + 3 * fv[0], *b = pos + 3 * fv[1], *d = pos + 3 * fv[2];
    const double e1x = b[0] - a[0], e1y = b[1] - a[1], e1z = b[2] - a[2];
    const double e2x = d[0] - a[0], e2y = d[1] - a[1], e2z = d[2] - a[2];
    const double nx = 0.5 * (e1y * e2z - e1z * e2y), ny = 0.5 * (e1z * e2x - e1x * e2z),
                 nz = 0.5 * (e1x * e2y - e1y * e2x);
    const double A = sqrt(nx * nx + ny * ny + nz * nz);
    Nx += nx, Ny += ny, Nz += nz;
    /* 3 x the area-weighted centroid */
    cx += A * (a[0] + b[0] + d[0]), cy += A * (a[1] + b[1] + d[1]), cz += A * (a[2] + b[2] + d[2]);
    area += A;
  }
  if (area > 0.0) {
    cx /= 3.0 * area, cy /= 3.0 * area, cz /= 3.0 * area;
  } else { /* faces without area: the mean of their corners */
    cx = cy = cz = 0.0;
    for (fv = w->corner + 3 * w->s.first[q]; fv < fend; fv += 3) {
      const double *a = pos + 3 * fv[0], *b = pos + 3 * fv[1], *d = pos + 3 * fv[2];
      cx += a[0] + b[0] + d[0], cy += a[1] + b[1] + d[1], cz += a[2] + b[2] + d[2];
    }
    const int n3 = 3 * w->s.count[q];
    cx /= n3, cy /= n3, cz /= n3;
  }
  double r2 = 0.0, lox = INFINITY, loy = INFINITY, loz = INFINITY, hix = -INFINITY, hiy = -INFINITY,
         hiz = -INFINITY;
  for (const int *u = w->vert + w->vstart[q], *uend = w->vert + w->vstart[q + 1]; u < uend; u++) {
    const double *p = pos + 3 * *u;
    const double px = p[0], py = p[1], pz = p[2];
    lox = px < lox ? px : lox, loy = py < loy ? py : loy, loz = pz < loz ? pz : loz;
    hix = px > hix ? px : hix, hiy = py > hiy ? py : hiy, hiz = pz > hiz ? pz : hiz;
    const double x = px - cx, y = py - cy, z = pz - cz;
    r2 = max_num(r2, x * x + y * y + z * z);
  }
  double *m = w->mom + 8 * (size_t)q;
  m[0] = Nx, m[1] = Ny, m[2] = Nz, m[3] = cx, m[4] = cy, m[5] = cz, m[6] = sqrt(r2), m[7] = area;
  if (box) {
    double *bx = box + 6 * (size_t)q;
    bx[0] = lox, bx[1] = loy, bx[2] = loz, bx[3] = hix, bx[4] = hiy, bx[5] = hiz;
  }
}

/* Internal node q's moments (and box) from its children's, refitted before
 * it: its radius bounds their balls. */
static inline void refit_merge(ss_wind *w, double *box, int q) {
  const int lq = w->s.left[q], rq = w->s.right[q];
  double *m = w->mom + 8 * (size_t)q;
  const double *l = w->mom + 8 * (size_t)lq, *r = w->mom + 8 * (size_t)rq;
  const double la = l[7], ra = r[7], area = la + ra;
  m[0] = l[0] + r[0], m[1] = l[1] + r[1], m[2] = l[2] + r[2];
  double cx, cy, cz;
  if (area > 0.0) {
    cx = (la * l[3] + ra * r[3]) / area, cy = (la * l[4] + ra * r[4]) / area;
    cz = (la * l[5] + ra * r[5]) / area;
  } else {
    cx = 0.5 * (l[3] + r[3]), cy = 0.5 * (l[4] + r[4]), cz = 0.5 * (l[5] + r[5]);
  }
  m[3] = cx, m[4] = cy, m[5] = cz;
  const double lx = l[3] - cx, ly = l[4] - cy, lz = l[5] - cz;
  const double rx = r[3] - cx, ry = r[4] - cy, rz = r[5] - cz;
  m[6] = max_num(sqrt(lx * lx + ly * ly + lz * lz) + l[6], sqrt(rx * rx + ry * ry + rz * rz) + r[6]);
  m[7] = area;
  if (box) {
    double *bx = box + 6 * (size_t)q;
    const double *bl = box + 6 * (size_t)lq, *br = box + 6 * (size_t)rq;
    bx[0] = bl[0] < br[0] ? bl[0] : br[0], bx[1] = bl[1] < br[1] ? bl[1] : br[1];
    bx[2] = bl[2] < br[2] ? bl[2] : br[2], bx[3] = bl[3] > br[3] ? bl[3] : br[3];
    bx[4] = bl[4] > br[4] ? bl[4] : br[4], bx[5] = bl[5] > br[5] ? bl[5] : br[5];
  }
}

/* Node q's moments and box, a leaf's or a parent's (inlined in the sweeps:
 * a merge is a few dozen operations). */
static inline SS_ALWAYS_INLINE void refit_node(ss_wind *w, const double *pos, double *box, int q) {
  if (w->s.left[q] < 0) refit_leaf(w, pos, box, q);
  else refit_merge(w, box, q);
}

/* Subtree i of the cut: its descendants (children after their parent in
 * the order: one reverse sweep), then its root. */
static void refit_subtree(ss_wind *w, const double *pos, double *box, int i) {
  for (int q = w->cut_end[i] - 1; q >= w->cut_lo[i]; q--) refit_node(w, pos, box, q);
  refit_node(w, pos, box, w->cut[i]);
}

/* In one reverse sweep of the order (children after their parent), or on
 * the threads the subtrees of the cut (each its own nodes) and then the
 * nodes above them: each node from the same operands either way. */
void ss_wind_refit(ss_wind *w, const double *pos) { ss_wind_refit_boxes(w, pos, NULL, 1); }

void ss_wind_refit_boxes(ss_wind *w, const double *pos, double *box, int nthread) {
#ifdef _OPENMP
  if (nthread > 1 && w->ncut > 0 && w->s.nnode >= 512) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthread)
    for (int i = 0; i < w->ncut; i++) refit_subtree(w, pos, box, i);
    for (int j = 0; j < w->ntop; j++) refit_node(w, pos, box, w->top[j]);
    return;
  }
#endif
  (void)nthread;
  for (int q = w->s.nnode - 1; q >= 0; q--) refit_node(w, pos, box, q);
}

double ss_wind_triangle(const double p[3], const double a[3], const double b[3],
                        const double c[3]) {
  const double x[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]};
  const double y[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
  const double z[3] = {c[0] - p[0], c[1] - p[1], c[2] - p[2]};
  const double lx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  const double ly = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  const double lz = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  const double det = x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) +
                     x[2] * (y[0] * z[1] - y[1] * z[0]);
  const double xy = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  const double yz = y[0] * z[0] + y[1] * z[1] + y[2] * z[2];
  const double zx = z[0] * x[0] + z[1] * x[1] + z[2] * x[2];
  const double den = lx * ly * lz + xy * lz + yz * lx + zx * ly;
  /* a point on the triangle's plane (det 0) sees no solid angle */
  if (det == 0.0) return 0.0;
  return 2.0 * atan2(det, den) / FOUR_PI;
}

double ss_wind_number(const ss_wind *w, const double *pos, const double p[3]) {
  return ss_wind_number_beta(w, pos, p, SS_WIND_BETA);
}

double ss_wind_number_beta(const ss_wind *w, const double *pos, const double p[3], double beta) {
  if (!(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])) || w->s.nnode <= 0) return 0.0;
  double sum = 0.0, far = 0.0; /* exact and dipole parts, summed apart */
  int stack[WIND_STACK];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int node = stack[--top];
    const double *m = w->mom + 8 * (size_t)node;
    const double d[3] = {m[3] - p[0], m[4] - p[1], m[5] - p[2]};
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 > beta * beta * m[6] * m[6]) {
      far += (m[0] * d[0] + m[1] * d[1] + m[2] * d[2]) / (r2 * sqrt(r2));
      continue;
    }
    if (w->s.left[node] < 0 || top + 2 > WIND_STACK) {
      /* a leaf (or, never on trees bvh.c builds, a stack too deep: its faces
       * exactly, which is slower, never wrong) */
      const int i0 = w->s.first[node], i1 = i0 + w->s.count[node];
      for (int i = i0; i < i1; i++) {
        const int *fv = w->corner + 3 * i;
        sum += ss_wind_triangle(p, pos + 3 * fv[0], pos + 3 * fv[1], pos + 3 * fv[2]);
      }
      continue;
    }
    stack[top++] = w->s.right[node];
    stack[top++] = w->s.left[node];
  }
  return sum + far / FOUR_PI;
}

int ss_wind_face_buried(const ss_wind *w, const double *pos, int f) {
  return ss_wind_face_buried_beta(w, pos, f, SS_WIND_BETA);
}

int ss_wind_face_buried_beta(const ss_wind *w, const double *pos, int f, double beta) {
  const int *fv = w->topo->face_vert + 3 * f;
  double c[3];
  for (int k = 0; k < 3; k++) c[k] = (pos[3 * fv[0] + k] + pos[3 * fv[1] + k] + pos[3 * fv[2] + k]) / 3.0;
  /* the face's own solid angle at a point on it is 0 or +-1/2 by the sign
   * of a rounding error (det of three vectors in one plane): taken out, the
   * same value the sum added */
  const double own = ss_wind_triangle(c, pos + 3 * fv[0], pos + 3 * fv[1], pos + 3 * fv[2]);
  return !(fabs(ss_wind_number_beta(w, pos, c, beta) - own - 0.5) < SS_WIND_CLEAN_TOL);
}

static void face_normal(const ss_topo *t, const double *pos, int f, double n[3]) {
  const int *fv = t->face_vert + 3 * f;
  const double *a = pos + 3 * fv[0], *b = pos + 3 * fv[1], *c = pos + 3 * fv[2];
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (len > 0.0)
    for (int k = 0; k < 3; k++) n[k] /= len;
}

/* 1 if p lies in front of the surface at its nearest point (on face f at
 * uv, squared distance d2): by the pseudo-normal there, the sum of the
 * normals of the faces around f's corners as near as f (Baerentzen and
 * Aanaes 2005), so a point by an edge or a corner is judged by all its
 * faces. */
static int in_front(const ss_topo *t, const double *pos, const double p[3], int f, const double uv[2],
                    double d2) {
  double n[3] = {0, 0, 0}, m[3];
  const double eps = 1e-9;
  const int *fv = t->face_vert + 3 * f;
  if (uv[0] > eps && uv[1] > eps && 1.0 - uv[0] - uv[1] > eps) {
    face_normal(t, pos, f, n);
  } else {
    const double tie = d2 * (1.0 + 1e-9) + 1e-300;
    for (int c = 0; c < 3; c++) {
      const int w = t->vert_weld[fv[c]];
      for (int i = t->vf_start[w]; i < t->vf_start[w + 1]; i++) {
        const int g = t->vf_face[i];
        const int *gv = t->face_vert + 3 * g;
        int seen = 0; /* met around an earlier corner of f */
        for (int e = 0; e < c && !seen; e++) {
          const int we = t->vert_weld[fv[e]];
          seen = t->vert_weld[gv[0]] == we || t->vert_weld[gv[1]] == we || t->vert_weld[gv[2]] == we;
        }
        double guv[2];
        if (seen || (g != f && !(ss_closest_point_triangle(p, pos + 3 * gv[0], pos + 3 * gv[1],
                                                            pos + 3 * gv[2], guv) <= tie)))
          continue;
        face_normal(t, pos, g, m);
        for (int k = 0; k < 3; k++) n[k] += m[k];
      }
    }
  }
  const double *a = pos + 3 * fv[0], *b = pos + 3 * fv[1], *c = pos + 3 * fv[2];
  double s = 0.0;
  for (int k = 0; k < 3; k++) s += (p[k] - (a[k] + uv[0] * (b[k] - a[k]) + uv[1] * (c[k] - a[k]))) * n[k];
  return s > 0.0;
}

int ss_inside_classify(const ss_wind *w, const ss_bvh *bvh, const double *pos, const double p[3],
                       int anchor_face, double *depth) {
  *depth = 0.0;
  if (!(ss_wind_number(w, pos, p) > SS_WIND_INSIDE)) return SS_INSIDE_OUT;
  int face;
  double uv[2];
  *depth = sqrt(ss_bvh_closest(bvh, pos, p, &face, uv));
  if (ss_wind_face_buried(w, pos, face)) return SS_INSIDE_BURIED;
  if (anchor_face >= 0 && anchor_face != face && anchor_face < w->topo->nface &&
      ss_wind_face_buried(w, pos, anchor_face))
    return SS_INSIDE_BURIED;
  /* in front of the surface nearest to it and yet inside: inside another
   * part of the body that passes through this one (a leg through the
   * belly), whose faces there are buried */
  if (in_front(w->topo, pos, p, face, uv, *depth * *depth)) return SS_INSIDE_BURIED;
  return SS_INSIDE_CLEAN;
}
