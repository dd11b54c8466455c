/* The inside test (inside.h): the fast winding number against the exact
 * per-triangle sum, and the split of skin points inside the body into
 * "clean" and "buried" on a body built to have both: two overlapping closed
 * boxes (the second's end and the parts of its sides within the first lie
 * inside the body, as linear blend skinning buries a crushed crease), with
 * points placed inside at known depths; and the refit with the tree's boxes
 * (the contact pass's), on one thread and two. */
#include <string.h>

#include "bvh.h"
#include "inside.h"
#include "ss_test.h"
#include "ss_test_mesh.h"

#define GRID 8 /* quads per box face side */
#define NV_BOX TEST_BOX_NVERT(GRID)
#define NF_BOX TEST_BOX_NFACE(GRID)

static void make_box(const double lo[3], const double hi[3], double *pos, int *faces, int vbase) {
  test_box(lo, hi, GRID, pos, faces, vbase);
}

int main(void) {
  /* A = [0,2] x [0,1] x [0,1]; B = [1.5,3] x [0.2,0.8]^2 enters A through
   * A's end x = 2: B's end x = 1.5 and its sides for x < 2 are inside A */
  static double pos[2 * 3 * NV_BOX];
  static int faces[2 * 3 * NF_BOX];
  const double alo[3] = {0, 0, 0}, ahi[3] = {2, 1, 1}, blo[3] = {1.5, 0.2, 0.2}, bhi[3] = {3, 0.8, 0.8};
  make_box(alo, ahi, pos, faces, 0);
  make_box(blo, bhi, pos + 3 * NV_BOX, faces + 3 * NF_BOX, NV_BOX);
  const int nvert = 2 * NV_BOX, nface = 2 * NF_BOX;
  char err[256];
  ss_topo *topo = NULL;
  ss_bvh *bvh = NULL;
  ss_wind *w = NULL;
  CHECK_EQ_INT(ss_topo_create(&topo, nvert, pos, nface, faces, -1.0, err, sizeof err), SS_OK);
  CHECK_EQ_INT(ss_bvh_create(&bvh, topo), SS_OK);
  if (!topo || !bvh) return ss_test_finish("test_inside");
  ss_bvh_refit(bvh, pos);
  CHECK_EQ_INT(ss_wind_create(&w, bvh, topo), SS_OK);
  if (!w) return ss_test_finish("test_inside");
  ss_wind_refit(w, pos);

  /* the fast sum against the exact one, near and far, inside and out */
  unsigned long long s = 7;
  double worst = 0.0, worst2 = 0.0;
  for (int trial = 0; trial < 400; trial++) {
    double p[3] = {4.0 * ss_test_rand(&s) - 0.5, 1.6 * ss_test_rand(&s) - 0.3, 1.6 * ss_test_rand(&s) - 0.3};
    double exact = 0.0;
    for (int f = 0; f < nface; f++) {
      const int *fv = faces + 3 * f;
      exact += ss_wind_triangle(p, pos + 3 * fv[0], pos + 3 * fv[1], pos + 3 * fv[2]);
    }
    const double fast = ss_wind_number(w, pos, p);
    const double e = fabs(fast - exact);
    if (e > worst) worst = e;
    /* the contact pass's coarser near field (collide.c) */
    const double e2 = fabs(ss_wind_number_beta(w, pos, p, 2.0) - exact);
    if (e2 > worst2) worst2 = e2;
    /* the exact sum is an integer off the surface: 0, 1 or 2 here */
    const int inA = p[0] > 0 && p[0] < 2 && p[1] > 0 && p[1] < 1 && p[2] > 0 && p[2] < 1;
    const int inB = p[0] > 1.5 && p[0] < 3 && p[1] > 0.2 && p[1] < 0.8 && p[2] > 0.2 && p[2] < 0.8;
    CHECK_NEAR(exact, inA + inB, 1e-6);
  }
  CHECK_MSG(worst < 0.02, "fast winding number off by %g", worst);
  CHECK_MSG(worst2 < 0.05, "fast winding number at beta 2 off by %g", worst2);

  /* points at known depths */
  struct {
    double p[3];
    int kind;
    double depth;
  } pt[] = {
      {{0.5, 0.5, 0.9}, SS_INSIDE_CLEAN, 0.1},    /* under A's top, far from B */
      {{0.5, 0.03, 0.5}, SS_INSIDE_CLEAN, 0.03},  /* just inside A's side */
      {{2.5, 0.5, 0.75}, SS_INSIDE_CLEAN, 0.05},  /* under B's top, out of A */
      {{1.55, 0.5, 0.5}, SS_INSIDE_BURIED, 0.05}, /* by B's end, which is inside A */
      {{1.8, 0.25, 0.5}, SS_INSIDE_BURIED, 0.05}, /* by B's side where it runs in A */
      {{-0.1, 0.5, 0.5}, SS_INSIDE_OUT, 0.0},
      {{2.5, 0.9, 0.5}, SS_INSIDE_OUT, 0.0},
  };
  for (size_t i = 0; i < sizeof pt / sizeof pt[0]; i++) {
    double depth = -1.0;
    const int kind = ss_inside_classify(w, bvh, pos, pt[i].p, -1, &depth);
    CHECK_MSG(kind == pt[i].kind, "point %zu: kind %d, expected %d", i, kind, pt[i].kind);
    CHECK_NEAR(depth, pt[i].depth, 1e-12);
  }
  /* just out of A's end and inside B, by the rim where B runs into A: the
   * nearest face is one of A's end whose centroid is out of B (clean), and
   * the point is in front of it; inside B, which passes through A: buried */
  int rim = 0;
  for (int i = 0; i <= 40; i++) {
    const double q[3] = {2.004, 0.205 + 0.001 * (i % 5), 0.3 + 0.01 * i};
    int qf;
    double quv[2], depth;
    ss_bvh_closest(bvh, pos, q, &qf, quv);
    if (ss_wind_face_buried(w, pos, qf)) continue;
    rim++;
    CHECK_EQ_INT(ss_inside_classify(w, bvh, pos, q, -1, &depth), SS_INSIDE_BURIED);
  }
  CHECK_MSG(rim > 0, "no point by B's rim has a clean nearest face");

  /* a face of B's end lies inside A; one of A's top does not */
  double c[3] = {1.5, 0.5, 0.5};
  int face;
  double uv[2];
  ss_bvh_closest(bvh, pos, c, &face, uv);
  CHECK(ss_wind_face_buried(w, pos, face));
  double c2[3] = {0.5, 0.5, 1.0};
  ss_bvh_closest(bvh, pos, c2, &face, uv);
  CHECK(!ss_wind_face_buried(w, pos, face));

  /* the refit with the tree's boxes in a bent pose: the boxes ss_bvh_refit
   * sets, bit for bit, and on one thread and two the same boxes and
   * moments (the numbers, near field and far, bit for bit) */
  static double bent[2 * 3 * NV_BOX];
  for (int i = 0; i < 3 * nvert; i++) bent[i] = pos[i] + 0.02 * ss_test_randu(&s);
  ss_bvh *bref = NULL, *bw = NULL;
  CHECK_EQ_INT(ss_bvh_create_on(&bref, bvh), SS_OK);
  CHECK_EQ_INT(ss_bvh_create_on(&bw, bvh), SS_OK);
  if (bref && bw) {
    const int nnode = ss_bvh_get_shape(bvh).nnode;
    CHECK(nnode >= 512); /* enough nodes for the threads (inside.c) */
    ss_bvh_refit(bref, bent);
    double num[2][64];
    for (int threads = 1; threads <= 2; threads++) {
      memset(ss_bvh_boxes_write(bw), 0, sizeof(double) * 6 * (size_t)nnode);
      ss_wind_refit_boxes(w, bent, ss_bvh_boxes_write(bw), threads);
      CHECK_MSG(memcmp(ss_bvh_boxes(bw), ss_bvh_boxes(bref), sizeof(double) * 6 * (size_t)nnode) == 0,
                "%d threads: the refit's boxes are not ss_bvh_refit's", threads);
      unsigned long long sp = 11;
      for (int i = 0; i < 64; i++) {
        const double p[3] = {4.0 * ss_test_rand(&sp) - 0.5, 1.6 * ss_test_rand(&sp) - 0.3,
                             1.6 * ss_test_rand(&sp) - 0.3};
        num[threads - 1][i] = ss_wind_number_beta(w, bent, p, i % 2 ? 1.5 : SS_WIND_BETA);
      }
    }
    CHECK_MSG(memcmp(num[0], num[1], sizeof num[0]) == 0, "the refit on two threads moved the numbers");
  }
  ss_bvh_destroy(bw);
  ss_bvh_destroy(bref);

  ss_wind_destroy(w);
  ss_bvh_destroy(bvh);
  ss_topo_destroy(topo);
  return ss_test_finish("test_inside");
}
