/* The contact pass's guard on the skin faces it moves (collide.c, "No move
 * squeezes or stretches a skin face"): a skin triangle with two corners
 * held (not the pass's) and the third behind a box's top. Moved whole out
 * of the box, a small triangle would be stretched thirty times its rest
 * area (the fan of faces at a pole): the vertex moves part of the way and
 * the face stays within ten times; the same move of a triangle with a
 * larger rest area is made whole. A vertex under a held corner, moved whole,
 * would close its face: it stops short of that, at no less than a tenth of
 * the rest area. */
#include <math.h>
#include <string.h>

#include "collide.h"
#include "ss_test.h"
#include "ss_test_body.h"
#include "ss_test_mesh.h"

#define GRID 8
#define NV_BOX TEST_BOX_NVERT(GRID)
#define NF_BOX TEST_BOX_NFACE(GRID)

static double tri_area(const double *x) {
  const double e1[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]};
  const double e2[3] = {x[6] - x[0], x[7] - x[1], x[8] - x[2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* One pass over the skin triangle x (3 x 3, corner 2 the pass's only vertex)
 * of rest area rest_area against the box; x in place. */
static void pass(const ss_topo *topo, const ss_bvh *bvh, const ss_frames *fr, const double *pos,
                 double rest_area, double *x, long long step) {
  static const int faces[3] = {0, 1, 2};
  int anchor_face[3], dof_vert[1] = {2};
  double anchor_pos[9];
  for (int i = 0; i < 3; i++) { /* anchored on the top, above each corner */
    const double a[3] = {x[3 * i], x[3 * i + 1], 1.0};
    double uv[2];
    ss_bvh_closest(bvh, pos, a, &anchor_face[i], uv);
    memcpy(anchor_pos + 3 * i, a, sizeof a);
  }
  ss_collider *col = NULL;
  CHECK_EQ_INT(ss_collider_create(&col, topo, pos, 3, 1, faces), SS_OK);
  if (!col) return;
  const double edge = 0.25;
  ss_collide_in in = {topo, fr, pos, anchor_face, anchor_pos, faces, &rest_area, 0.0, edge};
  ss_collider_run(col, &in, 1, dof_vert, 1, step, x, NULL);
  ss_collider_destroy(col);
}

int main(void) {
  static double pos[3 * NV_BOX];
  static int bfaces[3 * NF_BOX];
  const double lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1};
  test_box(lo, hi, GRID, pos, bfaces, 0);
  test_body body;
  if (!test_body_create(&body, NV_BOX, pos, NF_BOX, bfaces)) return ss_test_finish("test_collide_guard");
  const ss_topo *topo = body.topo;
  const ss_bvh *bvh = body.bvh;
  const ss_frames *fr = body.fr;

  /* a small triangle 0.3 under the top (1.2 edges), lying flat: out whole,
   * its third corner would stretch it to 30 times its area */
  const double flat[9] = {1.0, 0.5, 0.7, 1.01, 0.5, 0.7, 1.0, 0.51, 0.7};
  const double a0 = tri_area(flat);
  double x[9];
  memcpy(x, flat, sizeof x);
  pass(topo, bvh, fr, pos, a0, x, 0);
  CHECK_MSG(x[8] > 0.7 + 1e-9 && x[8] < 1.0 - 1e-9, "moved part of the way out: z %.17g", x[8]);
  CHECK_MSG(tri_area(x) <= 10.0 * a0 * (1.0 + 1e-12), "stretched %.3f times", tri_area(x) / a0);
  CHECK(memcmp(x, flat, 6 * sizeof(double)) == 0); /* the held corners stay */

  /* the same triangle with a rest area a fifth of the moved one's: out whole */
  memcpy(x, flat, sizeof x);
  const double whole[3] = {1.0, 0.51, 1.0};
  double big[9];
  memcpy(big, flat, sizeof big);
  memcpy(big + 6, whole, sizeof whole);
  pass(topo, bvh, fr, pos, 0.2 * tri_area(big), x, 1);
  for (int k = 0; k < 3; k++) CHECK_NEAR(x[6 + k], whole[k], 1e-12);

  /* the third corner 0.3 straight under a held one on the top: out whole,
   * the face would close */
  const double under[9] = {1.0, 0.5, 1.0, 1.01, 0.5, 1.0, 1.0, 0.5, 0.7};
  const double a1 = tri_area(under);
  memcpy(x, under, sizeof x);
  pass(topo, bvh, fr, pos, a1, x, 2);
  CHECK_MSG(x[8] > 0.7 + 1e-9 && x[8] < 1.0 - 1e-9, "moved part of the way out: z %.17g", x[8]);
  CHECK_MSG(tri_area(x) >= 0.1 * a1 * (1.0 - 1e-12), "squeezed to %.3f", tri_area(x) / a1);

  test_body_destroy(&body);
  return ss_test_finish("test_collide_guard");
}
