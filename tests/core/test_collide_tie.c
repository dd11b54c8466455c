/* The contact pass at the line where the body passes through itself
 * (collide.c, pick_moves): box B's end lies inside box A, so the faces of
 * B's top whose centroids are inside A are buried and the rest clean; the
 * grid line between them is an edge shared by a buried face and a clean
 * one. A skin vertex under B's top, nearest to that edge (as near to the
 * buried face as to the clean one), is as much behind the clean surface
 * as behind the buried one: the inside measure may take either face, and
 * takes the clean one here. It must come out like a vertex under B's
 * clean top. ss_collide_tied_face names the other face at an edge and
 * none inside a face. */
#include <math.h>
#include <string.h>

#include "collide.h"
#include "collide_surface.h"
#include "inside.h"
#include "ss_test.h"
#include "ss_test_body.h"
#include "ss_test_mesh.h"

#define GRID_A 8
#define GRID_B 4
#define NV (TEST_BOX_NVERT(GRID_A) + TEST_BOX_NVERT(GRID_B))
#define NF (TEST_BOX_NFACE(GRID_A) + TEST_BOX_NFACE(GRID_B))

int main(void) {
  static double pos[3 * NV];
  static int faces[3 * NF];
  /* B's top (z 0.8) has grid lines at x 1.525, 1.9, 2.275, ...: the
   * triangles left of 1.9 have centroids at x < 2 (inside A: buried), those
   * right of it at x > 2 (clean) */
  const double alo[3] = {0, 0, 0}, ahi[3] = {2, 1, 1}, blo[3] = {1.525, 0.2, 0.2}, bhi[3] = {3.025, 0.8, 0.8};
  test_box(alo, ahi, GRID_A, pos, faces, 0);
  test_box(blo, bhi, GRID_B, pos + 3 * TEST_BOX_NVERT(GRID_A), faces + 3 * TEST_BOX_NFACE(GRID_A),
           TEST_BOX_NVERT(GRID_A));
  test_body body;
  if (!test_body_create(&body, NV, pos, NF, faces)) return ss_test_finish("test_collide_tie");
  ss_wind *wind = NULL;
  CHECK_EQ_INT(ss_wind_create(&wind, body.bvh, body.topo), SS_OK);
  ss_collider *col = NULL;
  CHECK_EQ_INT(ss_collider_create(&col, body.topo, pos, 1, 0, NULL), SS_OK);
  if (!wind || !col) {
    ss_wind_destroy(wind);
    ss_collider_destroy(col);
    test_body_destroy(&body);
    return ss_test_finish("test_collide_tie");
  }
  ss_wind_refit(wind, pos);

  /* the two faces of B's top at the edge x 1.9 (y 0.45): one buried, one clean */
  const double edge_pt[3] = {1.9, 0.45, 0.8}, left[3] = {1.85, 0.45, 0.8}, right[3] = {1.95, 0.45, 0.8};
  int fl, fr, fe;
  double uv[2];
  ss_bvh_closest(body.bvh, pos, left, &fl, uv);
  ss_bvh_closest(body.bvh, pos, right, &fr, uv);
  ss_bvh_closest(body.bvh, pos, edge_pt, &fe, uv);
  CHECK_MSG(ss_wind_face_buried(wind, pos, fl), "face %d left of the edge should be buried", fl);
  CHECK_MSG(!ss_wind_face_buried(wind, pos, fr), "face %d right of the edge should be clean", fr);
  CHECK_MSG(fe == fl || fe == fr, "the edge point's face %d is neither %d nor %d", fe, fl, fr);

  const double edge = 0.25;
  int anchor_face = -1;
  const double anchor[3] = {2.1, 0.45, 0.8}; /* on B's clean top */
  ss_bvh_closest(body.bvh, pos, anchor, &anchor_face, uv);
  ss_collide_in in = {body.topo, body.fr, pos, &anchor_face, anchor, NULL, NULL, 0.0, edge};
  /* the other face at the edge, none inside a face */
  const double under_edge[3] = {1.9, 0.45, 0.75};
  CHECK_EQ_INT(ss_collide_tied_face(&in, fe, under_edge), fe == fl ? fr : fl);
  const double under_left[3] = {1.85, 0.45, 0.75};
  CHECK_EQ_INT(ss_collide_tied_face(&in, fl, under_left), -1);

  /* 0.05 under the edge (a fifth of an edge: deeper than a move made
   * without the clean-surface test), 0.1 from A's end: out onto B's top */
  double x[3] = {1.9, 0.45, 0.75};
  const int dof_vert[1] = {0};
  CHECK_EQ_INT(ss_collider_run(col, &in, 1, dof_vert, 1, 0, x, NULL), 1);
  CHECK_NEAR(x[0], 1.9, 1e-12);
  CHECK_NEAR(x[1], 0.45, 1e-12);
  CHECK_NEAR(x[2], 0.8, 1e-12);

  ss_collider_destroy(col);
  ss_wind_destroy(wind);
  test_body_destroy(&body);
  return ss_test_finish("test_collide_tie");
}
