/* Automatic skinning weights by heat diffusion (Baran and Popovic 2007,
 * "Automatic rigging and animation of 3D characters", the "pinocchio" rig).
 *
 * On the welded mesh, with the symmetric cotangent stiffness matrix L
 * (L_ij = -(cot a + cot b) / 2, L_ii = -sum_j L_ij) and the lumped
 * (barycentric) vertex areas M, the paper's -Lap w + H w = H p, Lap =
 * -M^-1 L, becomes the symmetric positive definite system
 *     (L + M H) w_j = M H p_j,
 * H_ii = c / d_i^2 with d_i the distance from vertex i to the nearest
 * segment and p_j(i) = 1 where that segment belongs to owner j (1/2 each
 * for a vertex exactly as near to two owners). It is
 * factored once with CHOLMOD and solved for all owners together (one column
 * each). As in the paper, only segments visible from the vertex count (the
 * straight line to the segment's nearest point crosses no face; tested with
 * a bounding-volume tree): a torso vertex beside a hanging arm binds to the
 * spine, not to the arm across the gap. A vertex that sees no segment uses
 * all of them.
 * Afterwards: clamp to >= 0, a few passes of neighbour averaging, weights
 * below min_weight dropped, normalised to a partition of unity; a vertex
 * whose second-nearest owner is more than rigid_ratio times farther than the
 * nearest is bound rigidly (weight 1) to the nearest. */
#include <cholmod.h>

#include "skin_sim/ss_mesh.h"
#include "skin_sim/ssa_avatar.h"
#include "ssa_util.h"

ssa_autoweight_opts ssa_autoweight_default_opts(void) {
  ssa_autoweight_opts o;
  o.heat_c = 1.0;
  o.rigid_ratio = 2.5;
  o.min_weight = 0.01;
  o.smooth_iters = 2;
  o.visibility = 1;
  return o;
}

/* The parameter t in [0, 1] of the point of segment s (x0 y0 z0 x1 y1 z1)
 * closest to p; d = s1 - s0 and w = p - s0 are left for the caller. */
static double seg_param(const double *p, const double *s, double d[3], double w[3]) {
  for (int c = 0; c < 3; c++) {
    d[c] = s[3 + c] - s[c];
    w[c] = p[c] - s[c];
  }
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double t = dd > 0 ? (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd : 0.0;
  if (t < 0) t = 0;
  if (t > 1) t = 1;
  return t;
}

static double seg_dist2(const double *p, const double *s) {
  double d[3], w[3];
  double t = seg_param(p, s, d, w);
  double e[3] = {w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]};
  return e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
}

/* ---------------------------------------------------------------- visibility
 * Pinocchio binds a vertex only to bones it can see: the segment from the
 * vertex to the bone's nearest point must not cross the surface. A small
 * bounding-volume tree over the rest triangles answers these segment tests. */

typedef struct vis_node {
  double lo[3], hi[3];
  int left, right; /* children, or -1 for a leaf */
  int start, count; /* leaf: faces order[start .. start+count-1] */
} vis_node;

typedef struct vis_tree {
  vis_node *node;
  int nnode;
  int *order;
  const double *pos;
  const int *faces;
  const int *vert_weld;
} vis_tree;


static void face_box(const vis_tree *t, int f, double *lo, double *hi) {
  for (int c = 0; c < 3; c++) {
    lo[c] = INFINITY;
    hi[c] = -INFINITY;
  }
  for (int k = 0; k < 3; k++) {
    const double *p = t->pos + 3 * t->faces[3 * f + k];
    for (int c = 0; c < 3; c++) {
      if (p[c] < lo[c]) lo[c] = p[c];
      if (p[c] > hi[c]) hi[c] = p[c];
    }
  }
}

/* Builds node n over order[start .. start+count-1] by median splits; returns the next free node. */
static int vis_build(vis_tree *t, const double *cent, int n, int start, int count, int next) {
  vis_node *nd = &t->node[n];
  nd->start = start;
  nd->count = count;
  nd->left = nd->right = -1;
  for (int c = 0; c < 3; c++) {
    nd->lo[c] = INFINITY;
    nd->hi[c] = -INFINITY;
  }
  for (int i = start; i < start + count; i++) {
    double lo[3], hi[3];
    face_box(t, t->order[i], lo, hi);
    for (int c = 0; c < 3; c++) {
      if (lo[c] < nd->lo[c]) nd->lo[c] = lo[c];
      if (hi[c] > nd->hi[c]) nd->hi[c] = hi[c];
    }
  }
  if (count <= 4) return next;
  int axis = 0;
  for (int c = 1; c < 3; c++)
    if (nd->hi[c] - nd->lo[c] > nd->hi[axis] - nd->lo[axis]) axis = c;
  /* insertion-free split: partial sort by centroid along axis (quickselect) */
  int *o = t->order + start, lo = 0, hi = count - 1, k = count / 2;
  while (lo < hi) {
    double pivot = cent[3 * o[(lo + hi) / 2] + axis];
    int i = lo, j = hi;
    while (i <= j) {
      while (cent[3 * o[i] + axis] < pivot) i++;
      while (cent[3 * o[j] + axis] > pivot) j--;
      if (i <= j) {
        int tmp = o[i];
        o[i] = o[j];
        o[j] = tmp;
        i++;
        j--;
      }
    }
    if (k <= j)
      hi = j;
    else if (k >= i)
      lo = i;
    else
      break;
  }
  int l = next, r = next + 1;
  nd->left = l;
  nd->right = r;
  next += 2;
  next = vis_build(t, cent, l, start, k, next);
  next = vis_build(t, cent, r, start + k, count - k, next);
  return next;
}

static int vis_tree_create(vis_tree *t, const double *pos, int nface, const int *faces,
                           const int *vert_weld) {
  memset(t, 0, sizeof *t);
  t->pos = pos;
  t->faces = faces;
  t->vert_weld = vert_weld;
  t->order = malloc(sizeof(int) * (size_t)nface);
  t->node = malloc(sizeof(vis_node) * (size_t)(2 * nface + 1));
  double *cent = malloc(sizeof(double) * 3 * (size_t)nface);
  if (!t->order || !t->node || !cent) {
    free(cent);
    return 0;
  }
  for (int f = 0; f < nface; f++) {
    t->order[f] = f;
    for (int c = 0; c < 3; c++)
      cent[3 * f + c] = (pos[3 * faces[3 * f] + c] + pos[3 * faces[3 * f + 1] + c] +
                         pos[3 * faces[3 * f + 2] + c]) / 3.0;
  }
  t->nnode = vis_build(t, cent, 0, 0, nface, 1);
  free(cent);
  return 1;
}

static void vis_tree_destroy(vis_tree *t) {
  free(t->order);
  free(t->node);
}

static int seg_box(const double *a, const double *d, const double *lo, const double *hi) {
  double t0 = 0.0, t1 = 1.0;
  for (int c = 0; c < 3; c++) {
    if (fabs(d[c]) < 1e-300) {
      if (a[c] < lo[c] || a[c] > hi[c]) return 0;
      continue;
    }
    double inv = 1.0 / d[c], ta = (lo[c] - a[c]) * inv, tb = (hi[c] - a[c]) * inv;
    if (ta > tb) {
      double tmp = ta;
      ta = tb;
      tb = tmp;
    }
    if (ta > t0) t0 = ta;
    if (tb < t1) t1 = tb;
    if (t0 > t1) return 0;
  }
  return 1;
}

/* Segment a + t d, t in (tmin, 1], against triangle f (Moller-Trumbore). */
static int seg_tri(const vis_tree *t, int f, const double *a, const double *d, double tmin) {
  const double *p0 = t->pos + 3 * t->faces[3 * f], *p1 = t->pos + 3 * t->faces[3 * f + 1],
               *p2 = t->pos + 3 * t->faces[3 * f + 2];
  double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  double h[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
  double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
  if (fabs(det) < 1e-300) return 0;
  double inv = 1.0 / det;
  double s[3] = {a[0] - p0[0], a[1] - p0[1], a[2] - p0[2]};
  double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) * inv;
  if (u < 0.0 || u > 1.0) return 0;
  double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
  double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
  if (v < 0.0 || u + v > 1.0) return 0;
  double tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
  return tt > tmin && tt <= 1.0;
}

/* 1 if the segment from welded vertex w at a to b crosses no face (faces
 * touching w are ignored). stack holds 64 ints. */
static int vis_clear(const vis_tree *t, int w, const double *a, const double *b) {
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  int stack[64], top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const vis_node *nd = &t->node[stack[--top]];
    if (!seg_box(a, d, nd->lo, nd->hi)) continue;
    if (nd->left < 0) {
      for (int i = nd->start; i < nd->start + nd->count; i++) {
        int f = t->order[i];
        const int *fv = t->faces + 3 * f;
        if (t->vert_weld[fv[0]] == w || t->vert_weld[fv[1]] == w || t->vert_weld[fv[2]] == w)
          continue;
        if (seg_tri(t, f, a, d, 1e-9)) return 0;
      }
    } else if (top + 2 <= 64) {
      stack[top++] = nd->left;
      stack[top++] = nd->right;
    } else {
      return 1; /* deeper than any balanced tree of 2^31 faces: cannot happen */
    }
  }
  return 1;
}

static void seg_closest(const double *p, const double *s, double *out) {
  double d[3], w[3];
  double t = seg_param(p, s, d, w);
  for (int c = 0; c < 3; c++) out[c] = s[c] + t * d[c];
}

int ssa_auto_weights(int nvert, const double *pos, int nface, const int *faces, double weld_tol,
                     int nseg, const double *seg, const int *seg_owner, int nowner,
                     const ssa_autoweight_opts *opts, int **w_start_out, int **w_bone_out,
                     double **w_weight_out, int *dominant, char *err, int err_sz) {
  if (!w_start_out || !w_bone_out || !w_weight_out)
    return ss_fail(err, err_sz, SS_E_ARG, "no output arrays given");
  *w_start_out = NULL;
  *w_bone_out = NULL;
  *w_weight_out = NULL;
  if (nseg <= 0 || !seg || !seg_owner || nowner <= 0)
    return ss_fail(err, err_sz, SS_E_ARG, "no skeleton segments given");
  for (int s = 0; s < nseg; s++) {
    if (seg_owner[s] < 0 || seg_owner[s] >= nowner)
      return ss_fail(err, err_sz, SS_E_ARG, "segment %d has owner %d outside [0, %d)", s,
                     seg_owner[s], nowner);
    for (int c = 0; c < 6; c++)
      if (!isfinite(seg[6 * s + c]))
        return ss_fail(err, err_sz, SS_E_NONFINITE, "segment %d is not finite", s);
  }
  ssa_autoweight_opts o = opts ? *opts : ssa_autoweight_default_opts();
  ss_topo *topo = NULL;
  int st = ss_topo_create(&topo, nvert, pos, nface, faces, weld_tol, err, err_sz);
  if (st != SS_OK) return st;
  const int nw = ss_topo_nweld(topo);
  const int *vert_weld = ss_topo_vert_weld(topo), *weld_rep = ss_topo_weld_rep(topo);
  const unsigned char *face_degenerate = ss_topo_face_degenerate(topo);
  double *area = calloc((size_t)nw, sizeof(double));
  double *dist = malloc(sizeof(double) * (size_t)nw);
  int *near1 = malloc(sizeof(int) * (size_t)nw);
  int *near2 = malloc(sizeof(int) * (size_t)nw); /* a second owner at the same distance, or -1 */
  unsigned char *rigid = calloc((size_t)nw, 1);
  double *w = NULL;
  double *nbr_sum = NULL, *nbr_cnt = NULL;
  cholmod_common cc;
  int cc_started = 0;
  cholmod_triplet *T = NULL;
  cholmod_sparse *A = NULL;
  cholmod_factor *F = NULL;
  cholmod_dense *B = NULL, *X = NULL;
  int *ws = NULL, *wb = NULL;
  double *wv = NULL;
  if (!area || !dist || !near1 || !near2 || !rigid) {
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  /* nearest and second-nearest owners of each welded vertex, among the
     segments it sees (all segments if it sees none) */
  vis_tree vt;
  int have_vt = 0;
  unsigned char *seen = malloc((size_t)nseg);
  if (!seen) {
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  if (o.visibility) {
    if (!vis_tree_create(&vt, pos, nface, faces, vert_weld)) {
      vis_tree_destroy(&vt);
      free(seen);
      st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
      goto done;
    }
    have_vt = 1;
  }
  double *sd = malloc(sizeof(double) * (size_t)nseg);
  if (!sd) {
    if (have_vt) vis_tree_destroy(&vt);
    free(seen);
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  for (int i = 0; i < nw; i++) {
    const double *p = pos + 3 * weld_rep[i];
    /* visit segments nearest first; stop at the second visible owner */
    for (int s = 0; s < nseg; s++) {
      sd[s] = seg_dist2(p, seg + 6 * s);
      seen[s] = 0; /* 0 not tested, 1 visible, 2 hidden */
    }
    double d1 = INFINITY, d2 = INFINITY;
    int o1 = -1, o2 = -1;
    for (int pass = 0; pass < 2 && o2 < 0; pass++) {
      /* pass 0: visible segments only; pass 1 (nothing or one owner visible): all */
      for (;;) {
        int best = -1;
        for (int s = 0; s < nseg; s++)
          if (seen[s] == 0 && (best < 0 || sd[s] < sd[best])) best = s;
        if (best < 0) break;
        if (pass == 0 && have_vt) {
          double c[3];
          seg_closest(p, seg + 6 * best, c);
          seen[best] = vis_clear(&vt, i, p, c) ? 1 : 2;
        } else {
          seen[best] = 1;
        }
        if (seen[best] != 1) continue;
        int ow = seg_owner[best];
        if (o1 < 0) {
          o1 = ow;
          d1 = sd[best];
        } else if (ow != o1 && o2 < 0) {
          o2 = ow;
          d2 = sd[best];
          break;
        }
      }
      if (pass == 0 && o1 >= 0) break; /* only one owner visible: others stay hidden */
      if (pass == 0)
        for (int s = 0; s < nseg; s++) seen[s] = 0;
    }
    near1[i] = o1;
    /* a tie (the vertex is as near to two owners) shares the heat source */
    near2[i] = (o2 >= 0 && d2 - d1 <= 1e-9 * d1) ? o2 : -1;
    dist[i] = sqrt(d1);
    rigid[i] = sqrt(d2) > o.rigid_ratio * sqrt(d1);
  }
  if (have_vt) vis_tree_destroy(&vt);
  free(seen);
  free(sd);
  /* cotangent stiffness (upper triangle triplets) and lumped areas */
  cholmod_start(&cc);
  cc_started = 1;
  cc.print = 0;
  cc.error_handler = NULL;
  /* simplicial: no BLAS, so the weights (and every skin over them) are the
   * same bits for any BLAS thread count; the supernodal factor's BLAS calls
   * gave OPENBLAS_NUM_THREADS 1 and 2 different weights on the 19k-triangle
   * mannequin */
  cc.supernodal = CHOLMOD_SIMPLICIAL;
  T = cholmod_allocate_triplet((size_t)nw, (size_t)nw, (size_t)(6 * nface + nw), 1, CHOLMOD_REAL,
                               &cc);
  if (!T) {
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  int *Ti = T->i, *Tj = T->j;
  double *Tx = T->x;
  double *diag = calloc((size_t)nw, sizeof(double));
  if (!diag) {
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  size_t nt = 0;
  for (int f = 0; f < nface; f++) {
    if (face_degenerate[f]) continue;
    int v[3];
    const double *x[3];
    for (int c = 0; c < 3; c++) {
      v[c] = vert_weld[faces[3 * f + c]];
      x[c] = pos + 3 * faces[3 * f + c];
    }
    double e1[3], e2[3], n[3];
    for (int c = 0; c < 3; c++) {
      e1[c] = x[1][c] - x[0][c];
      e2[c] = x[2][c] - x[0][c];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double a2 = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(a2 > 0)) continue;
    for (int c = 0; c < 3; c++) area[v[c]] += a2 / 6.0;
    for (int c = 0; c < 3; c++) {
      /* angle at corner c is opposite the edge (c+1, c+2) */
      const double *p0 = x[c], *p1 = x[(c + 1) % 3], *p2 = x[(c + 2) % 3];
      double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
      double s[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
      double cot = (u[0] * s[0] + u[1] * s[1] + u[2] * s[2]) / a2;
      double wgt = 0.5 * cot;
      int i = v[(c + 1) % 3], j = v[(c + 2) % 3];
      if (i == j) continue;
      Ti[nt] = i < j ? i : j;
      Tj[nt] = i < j ? j : i;
      Tx[nt] = -wgt;
      nt++;
      diag[i] += wgt;
      diag[j] += wgt;
    }
  }
  const double mel = ss_topo_rest_edge_length(topo) > 0 ? ss_topo_rest_edge_length(topo) : 1.0;
  for (int i = 0; i < nw; i++) {
    double d = dist[i];
    if (d < 1e-3 * mel) d = 1e-3 * mel;
    double h = o.heat_c / (d * d);
    /* a vertex in no (non-degenerate) face has no area: give it some, so that it
       simply takes its nearest owner instead of making the matrix singular */
    double ai = area[i] > 0 ? area[i] : mel * mel;
    Ti[nt] = Tj[nt] = i;
    Tx[nt] = diag[i] + ai * h;
    nt++;
    dist[i] = ai * h; /* reuse: M H on the diagonal */
  }
  free(diag);
  T->nnz = nt;
  A = cholmod_triplet_to_sparse(T, nt, &cc);
  B = cholmod_zeros((size_t)nw, (size_t)nowner, CHOLMOD_REAL, &cc);
  if (!A || !B) {
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  double *Bx = B->x;
  for (int i = 0; i < nw; i++) {
    if (near2[i] >= 0) {
      Bx[(size_t)near1[i] * (size_t)nw + (size_t)i] = 0.5 * dist[i];
      Bx[(size_t)near2[i] * (size_t)nw + (size_t)i] = 0.5 * dist[i];
    } else {
      Bx[(size_t)near1[i] * (size_t)nw + (size_t)i] = dist[i];
    }
  }
  F = cholmod_analyze(A, &cc);
  if (!F || !cholmod_factorize(A, F, &cc) || cc.status != CHOLMOD_OK) {
    st = ss_fail(err, err_sz, SS_E_SOLVER,
                 "the heat diffusion matrix could not be factored (CHOLMOD status %d)", cc.status);
    goto done;
  }
  X = cholmod_solve(CHOLMOD_A, F, B, &cc);
  if (!X) {
    st = ss_fail(err, err_sz, SS_E_SOLVER, "the heat diffusion solve failed (CHOLMOD status %d)",
                 cc.status);
    goto done;
  }
  /* post-processing on welded vertices: w (nowner x nw, owner-major) */
  w = malloc(sizeof(double) * (size_t)nw * (size_t)nowner);
  nbr_sum = malloc(sizeof(double) * (size_t)nw);
  nbr_cnt = malloc(sizeof(double) * (size_t)nw);
  if (!w || !nbr_sum || !nbr_cnt) {
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  const double *Xx = X->x;
  for (size_t k = 0; k < (size_t)nw * (size_t)nowner; k++) {
    double v = Xx[k];
    w[k] = isfinite(v) && v > 0 ? v : 0.0;
  }
  for (int it = 0; it < o.smooth_iters; it++) {
    for (int j = 0; j < nowner; j++) {
      double *wj = w + (size_t)j * (size_t)nw;
      memset(nbr_sum, 0, sizeof(double) * (size_t)nw);
      memset(nbr_cnt, 0, sizeof(double) * (size_t)nw);
      for (int f = 0; f < nface; f++)
        for (int c = 0; c < 3; c++) {
          int a = vert_weld[faces[3 * f + c]], b = vert_weld[faces[3 * f + (c + 1) % 3]];
          if (a == b) continue;
          nbr_sum[a] += wj[b];
          nbr_cnt[a] += 1;
          nbr_sum[b] += wj[a];
          nbr_cnt[b] += 1;
        }
      for (int i = 0; i < nw; i++)
        if (nbr_cnt[i] > 0) wj[i] = 0.5 * wj[i] + 0.5 * nbr_sum[i] / nbr_cnt[i];
    }
  }
  /* count, drop small, normalise, rigid */
  ws = calloc((size_t)nvert + 1, sizeof(int));
  int *cnt_w = calloc((size_t)nw + 1, sizeof(int));
  if (!ws || !cnt_w) {
    free(cnt_w);
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  for (int i = 0; i < nw; i++) {
    double sum = 0;
    for (int j = 0; j < nowner; j++) sum += w[(size_t)j * nw + i];
    int keep = 0;
    for (int j = 0; j < nowner; j++) {
      double *x = &w[(size_t)j * nw + i];
      *x = sum > 0 ? *x / sum : 0.0;
      if (rigid[i] || *x < o.min_weight) *x = 0.0;
    }
    if (rigid[i] || sum <= 0) w[(size_t)near1[i] * nw + i] = 1.0;
    sum = 0;
    for (int j = 0; j < nowner; j++) sum += w[(size_t)j * nw + i];
    if (!(sum > 0)) {
      w[(size_t)near1[i] * nw + i] = 1.0;
      sum = 1.0;
    }
    for (int j = 0; j < nowner; j++) {
      w[(size_t)j * nw + i] /= sum;
      keep += w[(size_t)j * nw + i] > 0;
    }
    cnt_w[i] = keep;
  }
  for (int v = 0; v < nvert; v++) ws[v + 1] = ws[v] + cnt_w[vert_weld[v]];
  free(cnt_w);
  wb = malloc(sizeof(int) * (size_t)(ws[nvert] > 0 ? ws[nvert] : 1));
  wv = malloc(sizeof(double) * (size_t)(ws[nvert] > 0 ? ws[nvert] : 1));
  if (!wb || !wv) {
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for automatic weights");
    goto done;
  }
  for (int v = 0; v < nvert; v++) {
    int i = vert_weld[v], k = ws[v], best = -1;
    double bw = -1;
    for (int j = 0; j < nowner; j++) {
      double x = w[(size_t)j * nw + i];
      if (x > 0) {
        wb[k] = j;
        wv[k] = x;
        k++;
        if (x > bw) {
          bw = x;
          best = j;
        }
      }
    }
    if (dominant) dominant[v] = best;
  }
  *w_start_out = ws;
  *w_bone_out = wb;
  *w_weight_out = wv;
  ws = NULL;
  wb = NULL;
  wv = NULL;
done:
  free(ws);
  free(wb);
  free(wv);
  free(w);
  free(nbr_sum);
  free(nbr_cnt);
  free(area);
  free(dist);
  free(near1);
  free(near2);
  free(rigid);
  if (cc_started) {
    cholmod_free_triplet(&T, &cc);
    cholmod_free_sparse(&A, &cc);
    cholmod_free_factor(&F, &cc);
    cholmod_free_dense(&B, &cc);
    cholmod_free_dense(&X, &cc);
    cholmod_finish(&cc);
  }
  ss_topo_destroy(topo);
  return st;
}
