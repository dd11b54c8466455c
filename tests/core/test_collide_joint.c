/* The contact pass's joint move (collide.c, "No move squeezes or stretches
 * a skin face"): a patch of skin whose inner vertices are all 1.2 edges
 * behind a box's top, its rim held on the top. Each inner vertex moved out
 * alone, or with its ring carried along, stretches the faces it shares
 * with the vertices left behind past ten times their rest area; moved all
 * at once they leave the inner faces as they were and the rim's flatter.
 * They must all come out whole in one pass, no face squeezed, stretched or
 * turned over. */
#include <math.h>
#include <string.h>

#include "collide.h"
#include "ss_test.h"
#include "ss_test_body.h"
#include "ss_test_mesh.h"

#define GRID 8
#define NV_BOX TEST_BOX_NVERT(GRID)
#define NF_BOX TEST_BOX_NFACE(GRID)
#define N 6 /* skin vertices a side */
#define NV (N * N)
#define NF (2 * (N - 1) * (N - 1))

static void tri_normal(const double *x, const int *f, double n[3]) {
  const double *a = x + 3 * f[0], *b = x + 3 * f[1], *c = x + 3 * f[2];
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

static double norm3(const double n[3]) { return sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]); }

int main(void) {
  static double pos[3 * NV_BOX];
  static int bfaces[3 * NF_BOX];
  const double lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1};
  test_box(lo, hi, GRID, pos, bfaces, 0);
  test_body body;
  if (!test_body_create(&body, NV_BOX, pos, NF_BOX, bfaces)) return ss_test_finish("test_collide_joint");

  /* the skin: an N x N grid of spacing s on the top (z 1) around (1, 0.5),
   * its inner vertices pressed 0.3 under it; rest areas those of the flat
   * grid */
  const double s = 0.02, edge = 0.25, depth = 0.3;
  double x[3 * NV], anchor_pos[3 * NV], rest_area[NF];
  int faces[3 * NF], anchor_face[NV], dof_vert[NV], ndof = 0;
  for (int i = 0; i < N; i++)
    for (int j = 0; j < N; j++) {
      const int v = i * N + j;
      const int rim = i == 0 || j == 0 || i == N - 1 || j == N - 1;
      const double p[3] = {1.0 + s * (i - 0.5 * (N - 1)), 0.5 + s * (j - 0.5 * (N - 1)), 1.0};
      double uv[2];
      memcpy(anchor_pos + 3 * v, p, sizeof p);
      ss_bvh_closest(body.bvh, pos, p, &anchor_face[v], uv);
      memcpy(x + 3 * v, p, sizeof p);
      if (!rim) x[3 * v + 2] -= depth, dof_vert[ndof++] = v;
    }
  int nf = 0;
  for (int i = 0; i + 1 < N; i++)
    for (int j = 0; j + 1 < N; j++) {
      const int a = i * N + j, b = a + N, c = a + N + 1, d = a + 1;
      const int f2[6] = {a, b, c, a, c, d};
      for (int t = 0; t < 2; t++, nf++) {
        memcpy(faces + 3 * nf, f2 + 3 * t, 3 * sizeof(int));
        rest_area[nf] = 0.5 * s * s;
      }
    }
  double before[3 * NF];
  for (int f = 0; f < NF; f++) tri_normal(x, faces + 3 * f, before + 3 * f);

  ss_collider *col = NULL;
  CHECK_EQ_INT(ss_collider_create(&col, body.topo, pos, NV, NF, faces), SS_OK);
  if (col) {
    ss_collide_in in = {body.topo, body.fr, pos, anchor_face, anchor_pos, faces, rest_area, 0.0, edge};
    ss_collider_run(col, &in, ndof, dof_vert, 1, 0, x, NULL);
    ss_collider_destroy(col);
  }
  for (int k = 0; k < ndof; k++) {
    const int v = dof_vert[k];
    CHECK_MSG(fabs(x[3 * v + 2] - 1.0) < 1e-9, "vertex %d at z %.17g, not out on the top", v, x[3 * v + 2]);
  }
  for (int f = 0; f < NF; f++) {
    double n[3];
    tri_normal(x, faces + 3 * f, n);
    const double a = 0.5 * norm3(n);
    CHECK_MSG(a >= 0.1 * rest_area[f] && a <= 10.0 * rest_area[f], "face %d at %.3f of its rest area", f,
              a / rest_area[f]);
    CHECK_MSG(n[0] * before[3 * f] + n[1] * before[3 * f + 1] + n[2] * before[3 * f + 2] > 0.0,
              "face %d turned over", f);
  }

  test_body_destroy(&body);
  return ss_test_finish("test_collide_joint");
}
