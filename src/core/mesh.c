/* Mesh validation and topology of the body mesh (see ss_mesh.h).
 *
 * Welding: vertices closer than weld_tol at rest get one welded id (the
 * smallest caller index among them), so that faces on either side of a UV or
 * normal seam become neighbours. Found in cells of side weld_tol sorted
 * lexicographically (ss_weld_ids), joined with union-find: O(n log n) whatever
 * the mesh's orientation, and deterministic.
 *
 * Edges: the 3 nface half-edges are keyed by their welded end points
 * (low, high) and sorted; a run of equal keys is one edge. One half-edge:
 * boundary; two of different faces: interior (the faces are neighbours
 * whatever their orientation; the walk maps points across by welded ids);
 * three or more: non-manifold, a boundary for walking. A face that repeats a
 * vertex has a zero-length edge that is given no neighbour. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_weld.h"
#include "topo.h"
#include "ss_err.h"
#include "ss_vec.h"
#include "union_find.h"

int ss_mesh_check(int nvert, const double *pos, int nface, const int *faces, char *err,
                  int err_sz) {
  if (nvert <= 0) return ss_fail(err, err_sz, SS_E_MESH, "mesh has no vertices");
  if (nface <= 0) return ss_fail(err, err_sz, SS_E_MESH, "mesh has no triangles");
  if (!faces) return ss_fail(err, err_sz, SS_E_ARG, "mesh: triangle array is NULL");
  for (int f = 0; f < nface; f++)
    for (int k = 0; k < 3; k++) {
      int v = faces[3 * f + k];
      if (v < 0 || v >= nvert)
        return ss_fail(err, err_sz, SS_E_MESH,
                       "triangle %d refers to vertex %d, outside [0, %d)", f, v, nvert);
    }
  if (pos)
    for (int v = 0; v < nvert; v++)
      for (int c = 0; c < 3; c++)
        if (!isfinite(pos[3 * v + c]))
          return ss_fail(err, err_sz, SS_E_NONFINITE, "vertex %d has a non-finite coordinate",
                         v);
  return SS_OK;
}

void ss_topo_destroy(ss_topo *topo) {
  if (!topo) return;
  free(topo->face_vert);
  free(topo->vert_weld);
  free(topo->weld_rep);
  free(topo->face_adj);
  free(topo->face_adj_edge);
  free(topo->edge_kind);
  free(topo->face_degenerate);
  free(topo->vf_start);
  free(topo->vf_face);
  free(topo);
}

/* ---- welding ------------------------------------------------------------- */

/* Cells of side h >= tol: two vertices within tol of each other are in the
 * same or adjacent cells. Sorted by cell (x, y, z, then caller index), the
 * vertices of any cell are one run, found by binary search: each vertex is
 * compared with those after it in its own cell and with every vertex of the 13
 * neighbour cells that sort after its own. O(n log n) plus the pairs of
 * vertices in neighbouring cells, whatever the mesh's orientation (a sweep
 * along x alone compared every pair of a mesh in a plane x = const). */
typedef struct {
  double c[3]; /* cell: integers as doubles, |c| <= 2^40 */
  int v;
} weld_key;

static int cmp_cell(const double *a, const double *b) {
  for (int k = 0; k < 3; k++) {
    if (a[k] < b[k]) return -1;
    if (a[k] > b[k]) return 1;
  }
  return 0;
}

static int cmp_weld_key(const void *pa, const void *pb) {
  const weld_key *a = pa, *b = pb;
  int c = cmp_cell(a->c, b->c);
  return c ? c : (a->v > b->v) - (a->v < b->v);
}

/* first key at or after cell c */
static int lower_bound_cell(const weld_key *keys, int n, const double *c) {
  int lo = 0, hi = n;
  while (lo < hi) {
    int mid = lo + (hi - lo) / 2;
    if (cmp_cell(keys[mid].c, c) < 0) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

int ss_weld_ids(int nvert, const double *pos, double tol, int *vert_weld, long long *ncompare) {
  if (ncompare) *ncompare = 0;
  if (nvert <= 0) return 0;
  int *parent = malloc(sizeof(int) * (size_t)nvert);
  weld_key *keys = malloc(sizeof(weld_key) * (size_t)nvert);
  if (!parent || !keys) {
    free(parent);
    free(keys);
    return -1;
  }
  /* the cell side: tol, or more where coordinates are over 2^40 tol (cells stay
   * exact integers), with a margin so that rounding never puts two vertices
   * within tol two cells apart */
  double big = 0.0;
  for (size_t i = 0; i < 3 * (size_t)nvert; i++) big = fmax(big, fabs(pos[i]));
  double h = fmax(tol > 0.0 ? tol : 0.0, big * 0x1p-40) * 1.0001;
  if (!(h > 0.0) || !isfinite(h)) h = 1.0;
  for (int v = 0; v < nvert; v++) {
    parent[v] = v;
    for (int k = 0; k < 3; k++) keys[v].c[k] = floor(pos[3 * (size_t)v + k] / h);
    keys[v].v = v;
  }
  qsort(keys, (size_t)nvert, sizeof *keys, cmp_weld_key);
  const double tol2 = tol * tol;
  long long ncmp = 0;
  for (int i = 0; i < nvert;) {
    int end = i; /* the run of i's cell: [i, end) */
    while (end < nvert && cmp_cell(keys[end].c, keys[i].c) == 0) end++;
    /* the 13 neighbour cells after this one in the sort order, then the cell itself */
    for (int d = 14; d <= 27; d++) {
      int lo = end, hi = end;
      if (d < 27) {
        double c[3] = {keys[i].c[0] + (double)(d / 9 - 1), keys[i].c[1] + (double)(d / 3 % 3 - 1),
                       keys[i].c[2] + (double)(d % 3 - 1)};
        lo = lower_bound_cell(keys, nvert, c);
        hi = lo;
        while (hi < nvert && cmp_cell(keys[hi].c, c) == 0) hi++;
      }
      for (int a = i; a < end; a++) {
        const double *p = pos + 3 * (size_t)keys[a].v;
        for (int b = (d < 27 ? lo : a + 1); b < (d < 27 ? hi : end); b++) {
          const double *q = pos + 3 * (size_t)keys[b].v;
          double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
          ncmp++;
          if (dx * dx + dy * dy + dz * dz <= tol2) uf_union(parent, keys[a].v, keys[b].v);
        }
      }
    }
    i = end;
  }
  int nweld = 0;
  for (int v = 0; v < nvert; v++) {
    int r = uf_find(parent, v);
    vert_weld[v] = (r == v) ? nweld++ : vert_weld[r]; /* r <= v: already numbered */
  }
  free(parent);
  free(keys);
  if (ncompare) *ncompare = ncmp;
  return nweld;
}

/* ---- edges ----------------------------------------------------------------- */

typedef struct {
  int lo, hi; /* welded end points, lo <= hi */
  int face, k;
} half_edge;

static int cmp_half_edge(const void *pa, const void *pb) {
  const half_edge *a = pa, *b = pb;
  if (a->lo != b->lo) return (a->lo > b->lo) - (a->lo < b->lo);
  if (a->hi != b->hi) return (a->hi > b->hi) - (a->hi < b->hi);
  if (a->face != b->face) return (a->face > b->face) - (a->face < b->face);
  return (a->k > b->k) - (a->k < b->k);
}

/* Mean edge length over distinct welded edges. An interior edge is counted
 * once, from the lower of its two faces; a non-manifold edge (rare) from every
 * face that holds it, a slight over-weighting that is harmless for a length
 * scale. */
double ss_topo_mean_edge_length(const ss_topo *topo, const double *pos) {
  double sum = 0.0;
  long long count = 0;
  for (int f = 0; f < topo->nface; f++)
    for (int k = 0; k < 3; k++) {
      int g = topo->face_adj[3 * f + k];
      if (g >= 0 && g < f) continue;
      int a = topo->face_vert[3 * f + k], b = topo->face_vert[3 * f + (k + 1) % 3];
      sum += dist3(pos + 3 * a, pos + 3 * b);
      count++;
    }
  return count ? sum / (double)count : 0.0;
}

int ss_topo_nvert(const ss_topo *topo) { return topo->nvert; }
int ss_topo_nface(const ss_topo *topo) { return topo->nface; }
int ss_topo_nweld(const ss_topo *topo) { return topo->nweld; }
const int *ss_topo_vert_weld(const ss_topo *topo) { return topo->vert_weld; }
const int *ss_topo_weld_rep(const ss_topo *topo) { return topo->weld_rep; }
const unsigned char *ss_topo_face_degenerate(const ss_topo *topo) { return topo->face_degenerate; }
double ss_topo_rest_edge_length(const ss_topo *topo) { return topo->mean_edge_length; }

int ss_topo_create(ss_topo **out, int nvert, const double *rest_pos, int nface, const int *faces,
                   double weld_tol, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "topology: NULL output");
  *out = NULL;
  if (!rest_pos) return ss_fail(err, err_sz, SS_E_ARG, "topology: rest positions are NULL");
  int status = ss_mesh_check(nvert, rest_pos, nface, faces, err, err_sz);
  if (status) return status;
  if (nface > (1 << 28) || nvert > (1 << 28))
    return ss_fail(err, err_sz, SS_E_MESH, "mesh too large (%d vertices, %d triangles)", nvert,
                   nface);
  if (!(weld_tol == weld_tol)) weld_tol = -1.0;
  if (weld_tol < 0.0) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int v = 0; v < nvert; v++)
      for (int c = 0; c < 3; c++) {
        lo[c] = fmin(lo[c], rest_pos[3 * v + c]);
        hi[c] = fmax(hi[c], rest_pos[3 * v + c]);
      }
    weld_tol = 1e-9 * dist3(lo, hi);
  }

  ss_topo *t = calloc(1, sizeof *t);
  half_edge *he = malloc(sizeof(half_edge) * 3 * (size_t)nface);
  if (!t || !he) {
    free(t);
    free(he);
    return ss_fail(err, err_sz, SS_E_NOMEM, "topology: out of memory");
  }
  t->nvert = nvert;
  t->nface = nface;
  t->face_vert = malloc(sizeof(int) * 3 * (size_t)nface);
  t->vert_weld = malloc(sizeof(int) * (size_t)nvert);
  t->face_adj = malloc(sizeof(int) * 3 * (size_t)nface);
  t->face_adj_edge = malloc(sizeof(int) * 3 * (size_t)nface);
  t->edge_kind = malloc(3 * (size_t)nface);
  t->face_degenerate = calloc((size_t)nface, 1);
  if (!t->face_vert || !t->vert_weld || !t->face_adj || !t->face_adj_edge || !t->edge_kind ||
      !t->face_degenerate)
    goto nomem;
  memcpy(t->face_vert, faces, sizeof(int) * 3 * (size_t)nface);

  t->nweld = ss_weld_ids(nvert, rest_pos, weld_tol, t->vert_weld, NULL);
  if (t->nweld < 0) goto nomem;
  t->weld_rep = malloc(sizeof(int) * (size_t)t->nweld);
  t->vf_start = calloc((size_t)t->nweld + 1, sizeof(int));
  t->vf_face = malloc(sizeof(int) * 3 * (size_t)nface);
  if (!t->weld_rep || !t->vf_start || !t->vf_face) goto nomem;
  for (int v = nvert - 1; v >= 0; v--) t->weld_rep[t->vert_weld[v]] = v;

  /* faces around each welded vertex (CSR), a face listed once per distinct corner */
  for (int f = 0; f < nface; f++) {
    int w0 = t->vert_weld[faces[3 * f]], w1 = t->vert_weld[faces[3 * f + 1]],
        w2 = t->vert_weld[faces[3 * f + 2]];
    t->vf_start[w0 + 1]++;
    if (w1 != w0) t->vf_start[w1 + 1]++;
    if (w2 != w0 && w2 != w1) t->vf_start[w2 + 1]++;
  }
  for (int w = 0; w < t->nweld; w++) t->vf_start[w + 1] += t->vf_start[w];
  {
    int *fill = malloc(sizeof(int) * (size_t)t->nweld);
    if (!fill) goto nomem;
    memcpy(fill, t->vf_start, sizeof(int) * (size_t)t->nweld);
    for (int f = 0; f < nface; f++) {
      int w0 = t->vert_weld[faces[3 * f]], w1 = t->vert_weld[faces[3 * f + 1]],
          w2 = t->vert_weld[faces[3 * f + 2]];
      t->vf_face[fill[w0]++] = f;
      if (w1 != w0) t->vf_face[fill[w1]++] = f;
      if (w2 != w0 && w2 != w1) t->vf_face[fill[w2]++] = f;
    }
    free(fill);
  }

  /* degenerate faces: a repeated (welded) vertex, or an area that is
   * negligible against the face's squared edge lengths */
  for (int f = 0; f < nface; f++) {
    const double *a = rest_pos + 3 * faces[3 * f], *b = rest_pos + 3 * faces[3 * f + 1],
                 *c = rest_pos + 3 * faces[3 * f + 2];
    double e1[3], e2[3], n[3];
    for (int i = 0; i < 3; i++) {
      e1[i] = b[i] - a[i];
      e2[i] = c[i] - a[i];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double twice_area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double l2 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2] + e2[0] * e2[0] +
                e2[1] * e2[1] + e2[2] * e2[2];
    int w0 = t->vert_weld[faces[3 * f]], w1 = t->vert_weld[faces[3 * f + 1]],
        w2 = t->vert_weld[faces[3 * f + 2]];
    if (w0 == w1 || w1 == w2 || w0 == w2 || !(twice_area > 1e-12 * l2)) {
      t->face_degenerate[f] = 1;
      t->ndegenerate_face++;
    }
  }

  /* edges */
  for (int f = 0; f < nface; f++)
    for (int k = 0; k < 3; k++) {
      int a = t->vert_weld[faces[3 * f + k]], b = t->vert_weld[faces[3 * f + (k + 1) % 3]];
      half_edge *h = he + 3 * f + k;
      h->lo = a < b ? a : b;
      h->hi = a < b ? b : a;
      h->face = f;
      h->k = k;
    }
  qsort(he, 3 * (size_t)nface, sizeof *he, cmp_half_edge);
  for (int i = 0; i < 3 * nface;) {
    int j = i + 1;
    while (j < 3 * nface && he[j].lo == he[i].lo && he[j].hi == he[i].hi) j++;
    const int count = j - i;
    t->nedge++;
    unsigned char kind = count == 1 ? SS_EDGE_BOUNDARY
                         : count == 2 ? SS_EDGE_INTERIOR
                                      : SS_EDGE_NONMANIFOLD;
    /* a zero-length edge (repeated vertex) or an edge a face shares with itself */
    if (he[i].lo == he[i].hi || (count == 2 && he[i].face == he[i + 1].face))
      kind = SS_EDGE_BOUNDARY;
    if (kind == SS_EDGE_BOUNDARY) t->nboundary_edge++;
    if (kind == SS_EDGE_NONMANIFOLD) t->nnonmanifold_edge++;
    for (int m = i; m < j; m++) {
      int slot = 3 * he[m].face + he[m].k;
      t->edge_kind[slot] = kind;
      t->face_adj[slot] = -1;
      t->face_adj_edge[slot] = -1;
      if (kind == SS_EDGE_INTERIOR) {
        const half_edge *o = &he[m == i ? i + 1 : i];
        t->face_adj[slot] = o->face;
        t->face_adj_edge[slot] = o->k;
      }
    }
    i = j;
  }
  free(he);
  he = NULL;
  t->mean_edge_length = ss_topo_mean_edge_length(t, rest_pos);
  *out = t;
  return SS_OK;

nomem:
  free(he);
  ss_topo_destroy(t);
  return ss_fail(err, err_sz, SS_E_NOMEM, "topology: out of memory for %d triangles", nface);
}

/* ---- welded mesh ----------------------------------------------------------- */

void ss_weld_destroy(ss_weld *w) {
  if (!w) return;
  free(w->pos);
  free(w->faces);
  free(w->vert_weld);
  free(w->weld_rep);
  free(w);
}

int ss_weld_create(ss_weld **out, int nvert, const double *pos, int nface, const int *faces,
                   double weld_tol, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "weld: NULL output");
  *out = NULL;
  ss_topo *topo = NULL;
  int status = ss_topo_create(&topo, nvert, pos, nface, faces, weld_tol, err, err_sz);
  if (status) return status;
  ss_weld *w = calloc(1, sizeof *w);
  if (w) {
    w->nvert = nvert;
    w->nweld = topo->nweld;
    w->nface = nface;
    w->pos = malloc(sizeof(double) * 3 * (size_t)topo->nweld);
    w->faces = malloc(sizeof(int) * 3 * (size_t)nface);
    w->vert_weld = malloc(sizeof(int) * (size_t)nvert);
    w->weld_rep = malloc(sizeof(int) * (size_t)topo->nweld);
  }
  if (!w || !w->pos || !w->faces || !w->vert_weld || !w->weld_rep) {
    ss_topo_destroy(topo);
    ss_weld_destroy(w);
    return ss_fail(err, err_sz, SS_E_NOMEM, "weld: out of memory for %d vertices", nvert);
  }
  for (int k = 0; k < topo->nweld; k++)
    memcpy(w->pos + 3 * (size_t)k, pos + 3 * (size_t)topo->weld_rep[k], 3 * sizeof(double));
  for (size_t i = 0; i < 3 * (size_t)nface; i++) w->faces[i] = topo->vert_weld[topo->face_vert[i]];
  memcpy(w->vert_weld, topo->vert_weld, sizeof(int) * (size_t)nvert);
  memcpy(w->weld_rep, topo->weld_rep, sizeof(int) * (size_t)topo->nweld);
  ss_topo_destroy(topo);
  *out = w;
  return SS_OK;
}
