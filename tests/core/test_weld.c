/* ss_mesh.h, ss_weld_create: a mesh with duplicated seam vertices becomes one
 * welded skin; a mesh without seams is unchanged; bad meshes are refused. */
#include "mesh_weld.h"
#include "skin_sim/ss_mesh.h"
#include "ss_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A G x G grid of spacing 1 in the plane normal to axis `normal`, each vertex
 * duplicated (a seam everywhere): 2 G^2 vertices, welded to G^2. */
static double *seam_grid(int g, int normal)
{
  double *p = malloc(sizeof(double) * 6 * (size_t)g * (size_t)g);
  for (int i = 0; i < g; i++)
    for (int j = 0; j < g; j++)
      for (int copy = 0; copy < 2; copy++) {
        double *q = p + 3 * (2 * ((size_t)i * (size_t)g + (size_t)j) + (size_t)copy);
        int a = (normal + 1) % 3, b = (normal + 2) % 3;
        q[normal] = 0.25;
        q[a] = i;
        q[b] = j;
      }
  return p;
}

/* The weld's work (issue 34): a sweep along x alone compared every pair of a
 * mesh in a plane x = const, 40x the work of the same grid in z = const (a
 * URDF of 10,000 links did not load within 120 s). Counted, not timed: the
 * distance tests are about the same for the grid in any orientation, and a
 * few per vertex. The welded ids agree with a brute-force weld on a small
 * shuffled cloud with clusters. */
static void test_weld_work(void)
{
  const int g = 142; /* 40,328 vertices */
  const int n = 2 * g * g;
  int *ids = malloc(sizeof(int) * (size_t)n);
  long long count[3] = {0, 0, 0};
  for (int normal = 0; normal < 3; normal++) {
    double *p = seam_grid(g, normal);
    int nweld = ss_weld_ids(n, p, 1e-6, ids, &count[normal]);
    CHECK_MSG(nweld == g * g, "grid normal to axis %d: %d welded of %d", normal, nweld, n);
    int pairs_ok = 1;
    for (int v = 0; v < n; v += 2) pairs_ok &= ids[v] == ids[v + 1] && ids[v] == v / 2;
    CHECK_MSG(pairs_ok, "grid normal to axis %d: each vertex welded with its copy", normal);
    free(p);
  }
  printf("weld of a %d-vertex grid: %lld, %lld, %lld distance tests (planes x, y, z = const)\n",
         n, count[0], count[1], count[2]);
  for (int normal = 0; normal < 3; normal++)
    CHECK_MSG(count[normal] <= 4LL * n, "normal %d: %lld distance tests for %d vertices",
              normal, count[normal], n);
  CHECK(count[0] == count[2] && count[1] == count[2]);
  free(ids);

  /* against every pair, on a cloud with clusters closer than tol and chains */
  const int m = 600;
  double *c = malloc(sizeof(double) * 3 * m);
  srand(7);
  for (int v = 0; v < m; v++)
    for (int k = 0; k < 3; k++)
      c[3 * v + k] = (v % 3 == 0 && v > 0) ? c[3 * (v - 1) + k] + 0.6e-3 * (k == v % 2)
                                           : (double)(rand() % 20) * 0.01 - 1e3 * (k == 2);
  int *a = malloc(sizeof(int) * m), *parent = malloc(sizeof(int) * m), *b = malloc(sizeof(int) * m);
  const double tol = 1e-3;
  CHECK(ss_weld_ids(m, c, tol, a, NULL) > 0);
  for (int v = 0; v < m; v++) parent[v] = v;
  for (int changed = 1; changed;) { /* the closure of the pairs within tol: smallest index */
    changed = 0;
    for (int u = 0; u < m; u++)
      for (int v = u + 1; v < m; v++) {
        double d = 0;
        for (int k = 0; k < 3; k++) d += (c[3 * u + k] - c[3 * v + k]) * (c[3 * u + k] - c[3 * v + k]);
        if (d <= tol * tol && parent[u] != parent[v]) {
          int lo = parent[u] < parent[v] ? parent[u] : parent[v];
          int hi = parent[u] + parent[v] - lo;
          for (int w = 0; w < m; w++)
            if (parent[w] == hi) parent[w] = lo;
          changed = 1;
        }
      }
  }
  int nb = 0;
  for (int v = 0; v < m; v++) b[v] = parent[v] == v ? nb++ : b[parent[v]];
  int same = 1;
  for (int v = 0; v < m; v++) same &= a[v] == b[v];
  CHECK_MSG(same, "the weld agrees with every pair's (%d welded ids)", nb);
  CHECK(nb < m);
  free(a); free(b); free(parent); free(c);
}

int main(void)
{
  test_weld_work();
  /* a unit square of two triangles whose diagonal is a seam: vertices 0 and 2
   * are duplicated as 4 and 5 (the second triangle uses the copies) */
  const double pos[18] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0};
  const int faces[6] = {0, 1, 2, 4, 5, 3};
  char err[256] = "";
  ss_weld *w = NULL;
  CHECK(ss_weld_create(&w, 6, pos, 2, faces, -1.0, err, sizeof err) == SS_OK);
  if (w) {
    CHECK(w->nvert == 6 && w->nweld == 4 && w->nface == 2);
    CHECK(w->vert_weld[4] == w->vert_weld[0] && w->vert_weld[5] == w->vert_weld[2]);
    CHECK(w->weld_rep[w->vert_weld[4]] == 0 && w->weld_rep[w->vert_weld[5]] == 2);
    for (int v = 0; v < 6; v++)
      CHECK(memcmp(w->pos + 3 * w->vert_weld[v], pos + 3 * v, 3 * sizeof(double)) == 0);
    for (int i = 0; i < 6; i++) CHECK(w->faces[i] == w->vert_weld[faces[i]]);
    /* the two faces now share an edge of welded ids */
    CHECK(w->faces[0] == w->faces[3] && w->faces[2] == w->faces[4]);
  }
  ss_weld_destroy(w);
  /* a tolerance: 1 mm apart welds at 2 mm, not at 0 */
  double near[18];
  memcpy(near, pos, sizeof near);
  near[12] = 0.001;
  CHECK(ss_weld_create(&w, 6, near, 2, faces, 0.002, err, sizeof err) == SS_OK);
  CHECK(w && w->nweld == 4);
  ss_weld_destroy(w);
  CHECK(ss_weld_create(&w, 6, near, 2, faces, 0.0, err, sizeof err) == SS_OK);
  CHECK(w && w->nweld == 5);
  ss_weld_destroy(w);
  /* no seams: identity */
  const int f2[6] = {0, 1, 2, 0, 2, 3};
  CHECK(ss_weld_create(&w, 4, pos, 2, f2, -1.0, err, sizeof err) == SS_OK);
  CHECK(w && w->nweld == 4);
  for (int v = 0; w && v < 4; v++) CHECK(w->vert_weld[v] == v && w->weld_rep[v] == v);
  ss_weld_destroy(w);
  /* bad meshes: one clear error, no output */
  const int bad[6] = {0, 1, 2, 4, 9, 3};
  w = (ss_weld *)1;
  CHECK(ss_weld_create(&w, 6, pos, 2, bad, -1.0, err, sizeof err) == SS_E_MESH && w == NULL);
  CHECK(strstr(err, "triangle 1") != NULL);
  double nan_pos[18];
  memcpy(nan_pos, pos, sizeof nan_pos);
  nan_pos[7] = NAN;
  CHECK(ss_weld_create(&w, 6, nan_pos, 2, faces, -1.0, err, sizeof err) == SS_E_NONFINITE);
  CHECK(ss_weld_create(NULL, 6, pos, 2, faces, -1.0, err, sizeof err) == SS_E_ARG);
  ss_weld_destroy(NULL);
  return ss_test_finish("test_weld");
}
