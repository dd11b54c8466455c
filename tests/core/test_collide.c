/* The contact projection (collide.c) on a body built to have a clean and a
 * buried surface: two overlapping boxes (the second's end, inside the
 * first, is buried). A skin vertex behind the clean surface goes out to it
 * (plus the thickness) along its normal, one in front stays, one behind the
 * buried end stays where it is, a shallow one moves without the surface
 * test, one within 0.045 edge of the surface is not looked at (it can be no
 * deeper), one in front of the first box's end but inside the second box
 * goes out of the second; the same bits on one thread and two. */
#include <string.h>

#include "collide.h"
#include "inside.h"
#include "ss_test.h"
#include "ss_test_body.h"
#include "ss_test_mesh.h"

#define GRID 8
#define NV_BOX TEST_BOX_NVERT(GRID)
#define NF_BOX TEST_BOX_NFACE(GRID)
#define NSKIN 9

int main(void) {
  static double pos[2 * 3 * NV_BOX];
  static int faces[2 * 3 * NF_BOX];
  const double alo[3] = {0, 0, 0}, ahi[3] = {2, 1, 1}, blo[3] = {1.5, 0.2, 0.2}, bhi[3] = {3, 0.8, 0.8};
  test_box(alo, ahi, GRID, pos, faces, 0);
  test_box(blo, bhi, GRID, pos + 3 * NV_BOX, faces + 3 * NF_BOX, NV_BOX);
  const int nvert = 2 * NV_BOX, nface = 2 * NF_BOX;
  test_body body;
  if (!test_body_create(&body, nvert, pos, nface, faces)) return ss_test_finish("test_collide");
  const ss_topo *topo = body.topo;
  const ss_bvh *bvh = body.bvh;
  const ss_frames *fr = body.fr;
  ss_collider *col = NULL;
  CHECK_EQ_INT(ss_collider_create(&col, topo, pos, NSKIN, 0, NULL), SS_OK);
  if (!col) {
    test_body_destroy(&body);
    return ss_test_finish("test_collide");
  }

  /* skin vertices: where each is anchored (a point on the body), where it is */
  const double edge = 0.25;
  struct {
    double anchor[3], x[3], expect[3];
  } sv[NSKIN] = {
      {{0.5, 0.5, 1.0}, {0.5, 0.5, 0.9}, {0.5, 0.5, 1.0}},        /* 0.1 under A's top: out */
      {{0.5, 0.5, 1.0}, {0.52, 0.5, 1.02}, {0.52, 0.5, 1.02}},    /* in front: stays */
      {{1.5, 0.5, 0.5}, {1.6, 0.5, 0.5}, {1.6, 0.5, 0.5}},        /* behind B's buried end: stays */
      {{0.5, 0.5, 1.0}, {0.5, 0.5, 0.98}, {0.5, 0.5, 1.0}},       /* shallow: out, untested */
      {{2.5, 0.5, 0.8}, {2.5, 0.5, 0.7}, {2.5, 0.5, 0.8}},        /* under B's clean top: out */
      {{0.5, 0.99, 1.0}, {0.5, 0.97, 0.98}, {0.5, 0.97, 1.0}},    /* by A's top edge: up, the nearer */
      {{0.5, 0.5, 1.0}, {0.5, 0.5, 1.5}, {0.5, 0.5, 1.5}},        /* far in front: stays */
      {{0.5, 0.5, 1.0}, {0.5, 0.5, 0.995}, {0.5, 0.5, 0.995}},    /* by the surface: not looked at */
      {{2.0, 0.95, 0.9}, {2.1, 0.5, 0.75}, {2.1, 0.5, 0.8}},      /* off A's end, in B: out of B's top */
  };
  int anchor_face[NSKIN], dof_vert[NSKIN];
  double x[3 * NSKIN], anchor_pos[3 * NSKIN];
  for (int i = 0; i < NSKIN; i++) {
    double uv[2];
    ss_bvh_closest(bvh, pos, sv[i].anchor, &anchor_face[i], uv);
    dof_vert[i] = i;
    memcpy(x + 3 * i, sv[i].x, sizeof sv[i].x);
    memcpy(anchor_pos + 3 * i, sv[i].anchor, sizeof sv[i].anchor);
  }
  ss_collide_in in = {topo, fr, pos, anchor_face, anchor_pos, NULL, NULL, 0.0, edge};
  const int moved = ss_collider_run(col, &in, NSKIN, dof_vert, 1, 0, x, NULL);
  CHECK_EQ_INT(moved, 5);
  for (int i = 0; i < NSKIN; i++)
    for (int k = 0; k < 3; k++) CHECK_NEAR(x[3 * i + k], sv[i].expect[k], 1e-12);

  /* the thickness: in front of the surface by it */
  double xt[3 * NSKIN];
  for (int i = 0; i < NSKIN; i++) memcpy(xt + 3 * i, sv[i].x, sizeof sv[i].x);
  in.thickness = 0.01;
  ss_collider_run(col, &in, NSKIN, dof_vert, 1, 1, xt, NULL);
  CHECK_NEAR(xt[2], 1.01, 1e-12);
  CHECK_NEAR(xt[3 * 4 + 2], 0.81, 1e-12);
  CHECK_NEAR(xt[3 * 1 + 2], 1.02, 1e-12); /* 0.02 in front: stays */

  /* the velocity into the body is dropped, the rest kept */
  double xv[3 * NSKIN], vel[3 * NSKIN];
  for (int i = 0; i < NSKIN; i++) {
    memcpy(xv + 3 * i, sv[i].x, sizeof sv[i].x);
    vel[3 * i] = 1.0, vel[3 * i + 1] = 2.0, vel[3 * i + 2] = -3.0;
  }
  ss_collider_run(col, &in, NSKIN, dof_vert, 1, 4, xv, vel);
  CHECK_NEAR(vel[0], 1.0, 1e-15);
  CHECK_NEAR(vel[1], 2.0, 1e-15);
  CHECK_NEAR(vel[2], 0.0, 1e-15);      /* moved out of A's top: -z dropped */
  CHECK_NEAR(vel[3 * 1 + 2], -3.0, 1e-15); /* not moved: kept */
  CHECK_NEAR(vel[3 * 2 + 2], -3.0, 1e-15); /* by the buried end: kept */

  /* one thread and two: the same bits */
  double x2[3 * NSKIN];
  for (int i = 0; i < NSKIN; i++) memcpy(x2 + 3 * i, sv[i].x, sizeof sv[i].x);
  in.thickness = 0.0;
  ss_collider_run(col, &in, NSKIN, dof_vert, 2, 2, x2, NULL);
  CHECK(memcmp(x, x2, sizeof x) == 0);

  /* a second pass leaves the skin where the first put it */
  double x3[3 * NSKIN];
  memcpy(x3, x, sizeof x);
  ss_collider_run(col, &in, NSKIN, dof_vert, 1, 3, x3, NULL);
  for (int i = 0; i < 3 * NSKIN; i++) CHECK_NEAR(x3[i], x[i], 1e-15);

  ss_collider_destroy(col);
  test_body_destroy(&body);
  return ss_test_finish("test_collide");
}
