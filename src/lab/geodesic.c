/* Surface distance between two points on the body, for telling a snag (an
 * anchor update that jumped across a gap) from an honest slide.
 *
 * Exact geodesics (e.g. MMP) are far more than a snag test needs: it only
 * has to tell "a few edge lengths along the surface" from "across the body".
 * So the distance is the shortest of
 *  - the straight line, when both points are in one face (exact);
 *  - across the shared edge, when the faces are neighbours: the minimum over
 *    points e of that edge of |a - e| + |e - b| (each segment lies in its
 *    face, so this is the exact geodesic across two faces, flat or not);
 *  - a path that leaves a's face through one of its corners, follows mesh
 *    edges (Dijkstra over welded vertices, edge lengths in the current pose)
 *    and enters b's face through one of its corners.
 * Every candidate is the length of a real path on the surface, so the result
 * is an upper bound of the geodesic distance. Edge paths zig-zag: on a
 * regular grid with one diagonal per cell they overestimate by up to sqrt 2
 * in the worst direction (about 8% on average), which a snag test with a
 * threshold of several times the pull tolerates. Dijkstra stops as soon as every
 * open path exceeds `limit`, so a snag test costs what its threshold covers,
 * not what the mesh holds. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geodesic.h"
#include "ss_vec.h"
#include "walk.h"
#include "ss_free.h"

struct ss_geodesic {
  int nweld;
  int *adj_start;        /* (nweld + 1) CSR of welded neighbours */
  int *adj;              /* (2 nedge-ish) */
  double *dist;          /* (nweld) tentative distance of the current search */
  unsigned int *seen;    /* (nweld) stamp: dist valid for this search */
  unsigned int *done;    /* (nweld) stamp: settled in this search */
  unsigned int stamp;
  int heap_cap;
  double *heap_key;      /* lazy-deletion binary heap of (key, vertex) */
  int *heap_vert;
};

int ss_geodesic_create(ss_geodesic **out, const ss_topo *topo) {
  if (!out || !topo) return SS_E_ARG;
  *out = NULL;
  ss_geodesic *g = calloc(1, sizeof *g);
  if (!g) return SS_E_NOMEM;
  const int nweld = topo->nweld, nface = topo->nface;
  g->nweld = nweld;
  g->adj_start = calloc((size_t)nweld + 1, sizeof(int));
  g->dist = malloc(sizeof(double) * (size_t)nweld);
  g->seen = calloc((size_t)nweld, sizeof(unsigned int));
  g->done = calloc((size_t)nweld, sizeof(unsigned int));
  /* every half-edge as a directed pair (both ways): at most 6 nface entries */
  int *pairs = malloc(sizeof(int) * 12 * (size_t)nface);
  if (!g->adj_start || !g->dist || !g->seen || !g->done || !pairs) {
    free(pairs);
    ss_geodesic_destroy(g);
    return SS_E_NOMEM;
  }
  int npair = 0;
  for (int f = 0; f < nface; f++)
    for (int k = 0; k < 3; k++) {
      int a = topo->vert_weld[topo->face_vert[3 * f + k]];
      int b = topo->vert_weld[topo->face_vert[3 * f + (k + 1) % 3]];
      if (a == b) continue;
      pairs[2 * npair] = a, pairs[2 * npair + 1] = b, npair++;
      pairs[2 * npair] = b, pairs[2 * npair + 1] = a, npair++;
    }
  /* CSR, keeping duplicates (an interior edge appears twice each way): harmless
   * for Dijkstra, and cheaper than deduplicating */
  for (int i = 0; i < npair; i++) g->adj_start[pairs[2 * i] + 1]++;
  for (int w = 0; w < nweld; w++) g->adj_start[w + 1] += g->adj_start[w];
  g->adj = malloc(sizeof(int) * (size_t)(npair > 0 ? npair : 1));
  int *fill = malloc(sizeof(int) * (size_t)nweld);
  g->heap_cap = npair + 8;
  g->heap_key = malloc(sizeof(double) * (size_t)g->heap_cap);
  g->heap_vert = malloc(sizeof(int) * (size_t)g->heap_cap);
  if (!g->adj || !fill || !g->heap_key || !g->heap_vert) {
    free(pairs);
    free(fill);
    ss_geodesic_destroy(g);
    return SS_E_NOMEM;
  }
  memcpy(fill, g->adj_start, sizeof(int) * (size_t)nweld);
  for (int i = 0; i < npair; i++) g->adj[fill[pairs[2 * i]]++] = pairs[2 * i + 1];
  free(fill);
  free(pairs);
  *out = g;
  return SS_OK;
}

void ss_geodesic_destroy(ss_geodesic *g) {
  if (!g) return;
  SS_FREE_ALL(g->adj_start, g->adj, g->dist, g->seen, g->done, g->heap_key, g->heap_vert, g);
}

static void point_on_face(const ss_topo *topo, const double *pos, int f, const double uv[2],
                          double out[3]) {
  const double *v0 = pos + 3 * topo->face_vert[3 * f], *v1 = pos + 3 * topo->face_vert[3 * f + 1],
               *v2 = pos + 3 * topo->face_vert[3 * f + 2];
  for (int i = 0; i < 3; i++) out[i] = v0[i] + uv[0] * (v1[i] - v0[i]) + uv[1] * (v2[i] - v0[i]);
}

/* min over e on segment [p, q] of |a - e| + |e - b|: a convex function of the
 * segment parameter, minimised by golden-section search. */
static double via_segment(const double a[3], const double b[3], const double p[3],
                          const double q[3]) {
  const double phi = 0.6180339887498949;
  double lo = 0.0, hi = 1.0;
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  double e[3], f1, f2;
  for (int i = 0; i < 3; i++) e[i] = p[i] + x1 * (q[i] - p[i]);
  f1 = dist3(a, e) + dist3(e, b);
  for (int i = 0; i < 3; i++) e[i] = p[i] + x2 * (q[i] - p[i]);
  f2 = dist3(a, e) + dist3(e, b);
  for (int it = 0; it < 48; it++) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - phi * (hi - lo);
      for (int i = 0; i < 3; i++) e[i] = p[i] + x1 * (q[i] - p[i]);
      f1 = dist3(a, e) + dist3(e, b);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + phi * (hi - lo);
      for (int i = 0; i < 3; i++) e[i] = p[i] + x2 * (q[i] - p[i]);
      f2 = dist3(a, e) + dist3(e, b);
    }
  }
  return f1 < f2 ? f1 : f2;
}

static void heap_push(ss_geodesic *g, int *n, double key, int v) {
  if (*n >= g->heap_cap) return; /* cannot happen: one push per relaxation */
  int i = (*n)++;
  while (i > 0) {
    int parent = (i - 1) / 2;
    if (g->heap_key[parent] <= key) break;
    g->heap_key[i] = g->heap_key[parent];
    g->heap_vert[i] = g->heap_vert[parent];
    i = parent;
  }
  g->heap_key[i] = key;
  g->heap_vert[i] = v;
}

static void heap_pop(ss_geodesic *g, int *n, double *key, int *v) {
  *key = g->heap_key[0];
  *v = g->heap_vert[0];
  (*n)--;
  double k = g->heap_key[*n];
  int w = g->heap_vert[*n];
  int i = 0;
  for (;;) {
    int c = 2 * i + 1;
    if (c >= *n) break;
    if (c + 1 < *n && g->heap_key[c + 1] < g->heap_key[c]) c++;
    if (g->heap_key[c] >= k) break;
    g->heap_key[i] = g->heap_key[c];
    g->heap_vert[i] = g->heap_vert[c];
    i = c;
  }
  g->heap_key[i] = k;
  g->heap_vert[i] = w;
}

double ss_surface_distance(ss_geodesic *g, const ss_topo *topo, const double *pos, int face_a,
                           const double uv_a[2], int face_b, const double uv_b[2],
                           double limit) {
  double a[3], b[3];
  point_on_face(topo, pos, face_a, uv_a, a);
  point_on_face(topo, pos, face_b, uv_b, b);
  if (face_a == face_b) {
    double d = dist3(a, b);
    return d <= limit ? d : INFINITY;
  }
  double best = INFINITY;
  for (int k = 0; k < 3; k++)
    if (topo->face_adj[3 * face_a + k] == face_b) {
      const double *p = pos + 3 * topo->face_vert[3 * face_a + k];
      const double *q = pos + 3 * topo->face_vert[3 * face_a + (k + 1) % 3];
      double d = via_segment(a, b, p, q);
      if (d < best) best = d;
    }
  if (best <= limit && best <= dist3(a, b) * (1.0 + 1e-12)) return best; /* cannot beat a line */

  if (++g->stamp == 0) {
    memset(g->seen, 0, sizeof(unsigned int) * (size_t)g->nweld);
    memset(g->done, 0, sizeof(unsigned int) * (size_t)g->nweld);
    g->stamp = 1;
  }
  const unsigned int stamp = g->stamp;
  /* targets: corners of b's face, each with its last leg into b */
  int target_w[3];
  double target_leg[3];
  for (int k = 0; k < 3; k++) {
    int v = topo->face_vert[3 * face_b + k];
    target_w[k] = topo->vert_weld[v];
    target_leg[k] = dist3(pos + 3 * v, b);
  }
  int n = 0;
  for (int k = 0; k < 3; k++) {
    int v = topo->face_vert[3 * face_a + k], w = topo->vert_weld[v];
    double d = dist3(a, pos + 3 * v);
    if (g->seen[w] != stamp || d < g->dist[w]) {
      g->seen[w] = stamp;
      g->dist[w] = d;
      heap_push(g, &n, d, w);
    }
  }
  const double cutoff = fmin(limit, best);
  while (n > 0) {
    double key;
    int w;
    heap_pop(g, &n, &key, &w);
    if (g->done[w] == stamp || key > g->dist[w]) continue; /* stale entry */
    if (key >= best || key > cutoff) break; /* nothing left can improve */
    g->done[w] = stamp;
    for (int k = 0; k < 3; k++)
      if (target_w[k] == w && key + target_leg[k] < best) best = key + target_leg[k];
    const double *pw = pos + 3 * topo->weld_rep[w];
    for (int i = g->adj_start[w]; i < g->adj_start[w + 1]; i++) {
      const int u = g->adj[i];
      if (g->done[u] == stamp) continue;
      const double d = key + dist3(pw, pos + 3 * topo->weld_rep[u]);
      if (d > limit) continue;
      if (g->seen[u] != stamp || d < g->dist[u]) {
        g->seen[u] = stamp;
        g->dist[u] = d;
        heap_push(g, &n, d, u);
      }
    }
  }
  return best <= limit ? best : INFINITY;
}
