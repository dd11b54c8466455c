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
 * Deterministic: a fixed traversal order, no threads. */
#include "inside.h"

#include <math.h>
#include <stdlib.h>

#include "closest.h"
#include "ss_free.h"

#define WIND_STACK 256 /* bvh.c's MAX_DEPTH 96 with both children pushed */
#define FOUR_PI 12.566370614359172953850573533118 /* 4 pi: the full solid angle */

struct ss_wind {
  const ss_topo *topo;
  ss_bvh_shape s;
  double *mom; /* (nnode x 8) N xyz, c xyz, r, area */
};

int ss_wind_create(ss_wind **out, const ss_bvh *bvh, const ss_topo *topo) {
  if (!out || !bvh || !topo) return SS_E_ARG;
  *out = NULL;
  ss_bvh_shape s = ss_bvh_get_shape(bvh);
  if (s.nnode <= 0) return SS_E_ARG; /* not refitted yet: no tree */
  ss_wind *w = calloc(1, sizeof *w);
  if (!w) return SS_E_NOMEM;
  w->topo = topo;
  w->s = s;
  w->mom = malloc(sizeof(double) * 8 * (size_t)s.nnode);
  if (!w->mom) {
    free(w);
    return SS_E_NOMEM;
  }
  *out = w;
  return SS_OK;
}

void ss_wind_destroy(ss_wind *w) {
  if (!w) return;
  SS_FREE_ALL(w->mom, w);
}

static double dist2(const double a[3], const double b[3]) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

/* max(a, b) as fmax for the values here (a NaN passed over), inline. */
static inline double max_num(double a, double b) { return a > b || b != b ? a : b; }

/* Leaf moments from its faces; internal nodes from their children, in one
 * reverse sweep (children after their parent in the order). The radius
 * bounds every corner of the node's faces around its centroid: a leaf's from
 * its corners, a parent's from its children's balls. */
void ss_wind_refit(ss_wind *w, const double *pos) { ss_wind_refit_boxes(w, pos, NULL); }

void ss_wind_refit_boxes(ss_wind *w, const double *pos, double *box) {
  const ss_topo *t = w->topo;
  for (int node = w->s.nnode - 1; node >= 0; node--) {
    double *m = w->mom + 8 * (size_t)node;
    if (w->s.left[node] < 0) {
      double N[3] = {0, 0, 0}, c[3] = {0, 0, 0}, area = 0.0;
      double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
      const int i0 = w->s.first[node], i1 = i0 + w->s.count[node];
      for (int i = i0; i < i1; i++) {
        const int *fv = t->face_vert + 3 * w->s.face_order[i];
        const double *a = pos + 3 * fv[0], *b = pos + 3 * fv[1], *d = pos + 3 * fv[2];
        if (box)
          for (int k = 0; k < 3; k++) { /* as bvh.c's face boxes (a NaN passed over) */
            if (a[k] < lo[k]) lo[k] = a[k];
            if (b[k] < lo[k]) lo[k] = b[k];
            if (d[k] < lo[k]) lo[k] = d[k];
            if (a[k] > hi[k]) hi[k] = a[k];
            if (b[k] > hi[k]) hi[k] = b[k];
            if (d[k] > hi[k]) hi[k] = d[k];
          }
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        const double n[3] = {0.5 * (e1[1] * e2[2] - e1[2] * e2[1]),
                             0.5 * (e1[2] * e2[0] - e1[0] * e2[2]),
                             0.5 * (e1[0] * e2[1] - e1[1] * e2[0])};
        const double A = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) {
          N[k] += n[k];
          c[k] += A * (a[k] + b[k] + d[k]); /* 3 x the area-weighted centroid */
        }
        area += A;
      }
      if (area > 0.0) {
        for (int k = 0; k < 3; k++) c[k] /= 3.0 * area;
      } else { /* faces without area: the mean of their corners */
        for (int k = 0; k < 3; k++) c[k] = 0.0;
        for (int i = i0; i < i1; i++) {
          const int *fv = t->face_vert + 3 * w->s.face_order[i];
          for (int k = 0; k < 3; k++) c[k] += pos[3 * fv[0] + k] + pos[3 * fv[1] + k] + pos[3 * fv[2] + k];
        }
        for (int k = 0; k < 3; k++) c[k] /= 3.0 * (i1 - i0);
      }
      double r2 = 0.0;
      for (int i = i0; i < i1; i++) {
        const int *fv = t->face_vert + 3 * w->s.face_order[i];
        for (int k = 0; k < 3; k++) r2 = max_num(r2, dist2(pos + 3 * fv[k], c));
      }
      m[0] = N[0], m[1] = N[1], m[2] = N[2], m[3] = c[0], m[4] = c[1], m[5] = c[2];
      m[6] = sqrt(r2), m[7] = area;
      if (box)
        for (int k = 0; k < 3; k++) box[6 * (size_t)node + k] = lo[k], box[6 * (size_t)node + 3 + k] = hi[k];
    } else {
      const double *l = w->mom + 8 * (size_t)w->s.left[node];
      const double *r = w->mom + 8 * (size_t)w->s.right[node];
      const double area = l[7] + r[7];
      for (int k = 0; k < 3; k++) {
        m[k] = l[k] + r[k];
        m[3 + k] = area > 0.0 ? (l[7] * l[3 + k] + r[7] * r[3 + k]) / area : 0.5 * (l[3 + k] + r[3 + k]);
      }
      m[6] = max_num(sqrt(dist2(l + 3, m + 3)) + l[6], sqrt(dist2(r + 3, m + 3)) + r[6]);
      m[7] = area;
      if (box) {
        double *bx = box + 6 * (size_t)node;
        const double *bl = box + 6 * (size_t)w->s.left[node], *br = box + 6 * (size_t)w->s.right[node];
        for (int k = 0; k < 3; k++) {
          bx[k] = bl[k] < br[k] ? bl[k] : br[k];
          bx[3 + k] = bl[3 + k] > br[3 + k] ? bl[3 + k] : br[3 + k];
        }
      }
    }
  }
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
  const ss_topo *t = w->topo;
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
        const int *fv = t->face_vert + 3 * w->s.face_order[i];
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
