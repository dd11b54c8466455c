/* Topology of the body mesh: closed, open, non-manifold, seamed and
 * degenerate meshes, and the one clear error for each kind of bad input. */
#include <string.h>

#include "topo.h"
#include "ss_test.h"
#include "ss_test_mesh.h"

/* Every interior edge's neighbour points back at it, across the same welded edge. */
static void check_adjacency_symmetric(const ss_topo *t) {
  for (int f = 0; f < t->nface; f++)
    for (int k = 0; k < 3; k++) {
      int g = t->face_adj[3 * f + k], kg = t->face_adj_edge[3 * f + k];
      if (g < 0) {
        CHECK(t->edge_kind[3 * f + k] != SS_EDGE_INTERIOR);
        continue;
      }
      CHECK(t->edge_kind[3 * f + k] == SS_EDGE_INTERIOR);
      CHECK(kg >= 0 && kg < 3);
      CHECK_EQ_INT(t->face_adj[3 * g + kg], f);
      CHECK_EQ_INT(t->face_adj_edge[3 * g + kg], k);
      int a = t->vert_weld[t->face_vert[3 * f + k]], b = t->vert_weld[t->face_vert[3 * f + (k + 1) % 3]];
      int c = t->vert_weld[t->face_vert[3 * g + kg]], d = t->vert_weld[t->face_vert[3 * g + (kg + 1) % 3]];
      CHECK((a == c && b == d) || (a == d && b == c));
    }
}

static void test_closed_seamed_cube(void) {
  test_mesh m = test_seamed_cube();
  ss_topo *t = NULL;
  char err[256] = "";
  CHECK_EQ_INT(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, -1.0, err, sizeof err), SS_OK);
  CHECK_EQ_INT(t->nvert, 24);
  CHECK_EQ_INT(t->nweld, 8);           /* the seams are welded */
  CHECK_EQ_INT(t->nedge, 18);          /* 12 cube edges + 6 diagonals */
  CHECK_EQ_INT(t->nboundary_edge, 0);  /* closed */
  CHECK_EQ_INT(t->nnonmanifold_edge, 0);
  CHECK_EQ_INT(t->ndegenerate_face, 0);
  check_adjacency_symmetric(t);
  /* the welded representative is the smallest caller index */
  for (int v = 0; v < t->nvert; v++) CHECK(t->weld_rep[t->vert_weld[v]] <= v);
  /* faces around a corner: each cube corner touches 4 or 5 triangles... at least 3 */
  for (int w = 0; w < t->nweld; w++) CHECK(t->vf_start[w + 1] - t->vf_start[w] >= 3);
  CHECK_NEAR(t->mean_edge_length, (12.0 + 6.0 * sqrt(2.0)) / 18.0, 1e-12);
  /* the caller's order is kept */
  CHECK(memcmp(t->face_vert, m.faces, sizeof(int) * 36) == 0);
  ss_topo_destroy(t);

  /* weld_tol 0 welds only identical positions: here they are identical */
  CHECK_EQ_INT(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, 0.0, err, sizeof err), SS_OK);
  CHECK_EQ_INT(t->nweld, 8);
  ss_topo_destroy(t);
  /* a seam opened by 1e-6: welded with a tolerance, open without */
  m.pos[3 * 5] += 1e-6;
  CHECK_EQ_INT(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, 1e-5, err, sizeof err), SS_OK);
  CHECK_EQ_INT(t->nweld, 8);
  CHECK_EQ_INT(t->nboundary_edge, 0);
  ss_topo_destroy(t);
  CHECK_EQ_INT(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, 0.0, err, sizeof err), SS_OK);
  CHECK_EQ_INT(t->nweld, 9);
  CHECK(t->nboundary_edge > 0);
  ss_topo_destroy(t);
  test_mesh_free(&m);
}

static void test_open_grid(void) {
  test_mesh m = test_grid(3, 2, 0.0, 1);
  ss_topo *t = NULL;
  char err[256] = "";
  CHECK_EQ_INT(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, -1.0, err, sizeof err), SS_OK);
  CHECK_EQ_INT(t->nweld, 12);
  CHECK_EQ_INT(t->nedge, 3 * 3 + 4 * 2 + 6); /* horizontal + vertical + diagonals */
  CHECK_EQ_INT(t->nboundary_edge, 2 * 3 + 2 * 2);
  check_adjacency_symmetric(t);
  ss_topo_destroy(t);
  test_mesh_free(&m);
}

static void test_nonmanifold(void) {
  /* three triangles on the edge (0,1), like pages of a book */
  double pos[] = {0, 0, 0, 0, 0, 1, 1, 0, 0, -1, 0, 0, 0, 1, 0};
  int faces[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  ss_topo *t = NULL;
  char err[256] = "";
  CHECK_EQ_INT(ss_topo_create(&t, 5, pos, 3, faces, -1.0, err, sizeof err), SS_OK);
  CHECK_EQ_INT(t->nnonmanifold_edge, 1);
  for (int f = 0; f < 3; f++) {
    CHECK_EQ_INT(t->edge_kind[3 * f], SS_EDGE_NONMANIFOLD);
    CHECK_EQ_INT(t->face_adj[3 * f], -1); /* a boundary for walking */
  }
  CHECK_EQ_INT(t->nboundary_edge, 6);
  ss_topo_destroy(t);
}

static void test_degenerate(void) {
  /* a good face, a face repeating a vertex, a face of collinear points */
  double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0};
  int faces[] = {0, 1, 2, 1, 1, 2, 1, 3, 4};
  ss_topo *t = NULL;
  char err[256] = "";
  CHECK_EQ_INT(ss_topo_create(&t, 5, pos, 3, faces, -1.0, err, sizeof err), SS_OK);
  CHECK_EQ_INT(t->ndegenerate_face, 2);
  CHECK(!t->face_degenerate[0] && t->face_degenerate[1] && t->face_degenerate[2]);
  /* the zero-length edge of face 1 has no neighbour */
  CHECK_EQ_INT(t->face_adj[3 * 1 + 0], -1);
  ss_topo_destroy(t);
}

static void test_bad_input(void) {
  double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  int faces[] = {0, 1, 2};
  int bad_faces[] = {0, 1, 3};
  ss_topo *t = NULL;
  char err[256] = "";
  CHECK_EQ_INT(ss_topo_create(&t, 3, pos, 1, bad_faces, -1.0, err, sizeof err), SS_E_MESH);
  CHECK(t == NULL && strstr(err, "triangle 0") && strstr(err, "vertex 3"));
  CHECK_EQ_INT(ss_topo_create(&t, 3, pos, 0, faces, -1.0, err, sizeof err), SS_E_MESH);
  CHECK(strstr(err, "no triangles") != NULL);
  CHECK_EQ_INT(ss_topo_create(&t, 0, pos, 1, faces, -1.0, err, sizeof err), SS_E_MESH);
  pos[4] = NAN;
  CHECK_EQ_INT(ss_topo_create(&t, 3, pos, 1, faces, -1.0, err, sizeof err), SS_E_NONFINITE);
  CHECK(strstr(err, "vertex 1") != NULL);
  CHECK_EQ_INT(ss_mesh_check(3, NULL, 1, faces, err, sizeof err), SS_OK);
  CHECK_EQ_INT(ss_topo_create(&t, 3, NULL, 1, faces, -1.0, NULL, 0), SS_E_ARG);
  CHECK(t == NULL);
}

int main(void) {
  test_closed_seamed_cube();
  test_open_grid();
  test_nonmanifold();
  test_degenerate();
  test_bad_input();
  return ss_test_finish("test_topology");
}
