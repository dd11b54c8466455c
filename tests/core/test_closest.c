/* The baselines' closest points: the triangle routine against dense
 * sampling (degenerate triangles included), the BVH against brute force on
 * random meshes and points, before and after deformation, and the n-ring
 * search; and the surface distance used for snag detection. */
#include <string.h>

#include "bvh.h"
#include "closest.h"
#include "geodesic.h"
#include "walk.h"
#include "ss_test.h"
#include "ss_test_mesh.h"

static double brute_closest(const ss_topo *t, const double *pos, const double p[3], int *face) {
  double best = INFINITY;
  *face = -1;
  for (int f = 0; f < t->nface; f++) {
    double uv[2];
    const int *fv = t->face_vert + 3 * f;
    double d2 = ss_closest_point_triangle(p, pos + 3 * fv[0], pos + 3 * fv[1], pos + 3 * fv[2], uv);
    if (d2 < best) best = d2, *face = f;
  }
  return best;
}

static void test_triangle_vs_sampling(void) {
  unsigned long long s = 3;
  for (int trial = 0; trial < 300; trial++) {
    double a[3], b[3], c[3], p[3];
    for (int i = 0; i < 3; i++) {
      a[i] = ss_test_rand(&s), b[i] = ss_test_rand(&s), c[i] = ss_test_rand(&s);
      p[i] = 3.0 * ss_test_rand(&s) - 1.0;
    }
    if (trial % 3 == 1) memcpy(c, b, sizeof c);               /* two corners coincide */
    if (trial % 3 == 2) for (int i = 0; i < 3; i++) c[i] = 0.5 * (a[i] + b[i]); /* collinear */
    double uv[2];
    double d2 = ss_closest_point_triangle(p, a, b, c, uv);
    CHECK(isfinite(d2) && uv[0] >= 0 && uv[1] >= 0 && uv[0] + uv[1] <= 1 + 1e-12);
    /* the returned uv really is at that distance */
    double q[3], dq = 0;
    for (int i = 0; i < 3; i++) {
      q[i] = a[i] + uv[0] * (b[i] - a[i]) + uv[1] * (c[i] - a[i]);
      dq += (q[i] - p[i]) * (q[i] - p[i]);
    }
    CHECK_NEAR(dq, d2, 1e-12);
    /* nothing sampled on the triangle is closer */
    double sampled = INFINITY;
    const int n = 60;
    for (int i = 0; i <= n; i++)
      for (int j = 0; i + j <= n; j++) {
        double u = (double)i / n, v = (double)j / n, d = 0;
        for (int k = 0; k < 3; k++) {
          double x = a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]) - p[k];
          d += x * x;
        }
        if (d < sampled) sampled = d;
      }
    CHECK(d2 <= sampled + 1e-12);
    CHECK(sqrt(sampled) - sqrt(d2) <= 0.05); /* and it is not far from the best sample */
  }
}

/* A random closed-ish soup: a jittered grid bent into a wave plus random
 * extra triangles (overlapping, of all shapes). */
static test_mesh random_mesh(unsigned long long seed) {
  test_mesh g = test_grid(20, 20, 0.4, seed);
  unsigned long long s = seed * 7 + 1;
  for (int v = 0; v < g.nvert; v++) g.pos[3 * v + 2] = 0.7 * sin(0.5 * g.pos[3 * v]) * cos(0.3 * g.pos[3 * v + 1]);
  const int extra = 150;
  test_mesh m;
  m.nvert = g.nvert + 3 * extra;
  m.nface = g.nface + extra;
  m.pos = malloc(sizeof(double) * 3 * (size_t)m.nvert);
  m.faces = malloc(sizeof(int) * 3 * (size_t)m.nface);
  memcpy(m.pos, g.pos, sizeof(double) * 3 * (size_t)g.nvert);
  memcpy(m.faces, g.faces, sizeof(int) * 3 * (size_t)g.nface);
  for (int i = 0; i < extra; i++) {
    double cx = 20 * ss_test_rand(&s), cy = 20 * ss_test_rand(&s), cz = 4 * ss_test_rand(&s) - 2;
    for (int k = 0; k < 3; k++) {
      double *p = m.pos + 3 * (g.nvert + 3 * i + k);
      p[0] = cx + 2 * ss_test_rand(&s) - 1;
      p[1] = cy + 2 * ss_test_rand(&s) - 1;
      p[2] = cz + 2 * ss_test_rand(&s) - 1;
      m.faces[3 * (g.nface + i) + k] = g.nvert + 3 * i + k;
    }
  }
  test_mesh_free(&g);
  return m;
}

static void test_bvh_vs_brute(void) {
  for (unsigned long long seed = 1; seed <= 3; seed++) {
    test_mesh m = random_mesh(seed);
    ss_topo *t = NULL;
    ss_bvh *bvh = NULL;
    char err[256];
    CHECK(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, -1.0, err, sizeof err) == SS_OK);
    CHECK(ss_bvh_create(&bvh, t) == SS_OK);
    double *pos = malloc(sizeof(double) * 3 * (size_t)m.nvert);
    memcpy(pos, m.pos, sizeof(double) * 3 * (size_t)m.nvert);
    unsigned long long s = seed + 100;
    for (int pose = 0; pose < 3; pose++) {
      if (pose > 0) /* deform a lot: the tree shape is the rest pose's, boxes must follow */
        for (int v = 0; v < m.nvert; v++) {
          double *p = pos + 3 * v;
          double ang = 0.6 * pose * p[1] / 20.0, x = p[0], z = p[2];
          p[0] = cos(ang) * x - sin(ang) * z + 0.3 * sin(p[1]);
          p[2] = sin(ang) * x + cos(ang) * z;
        }
      ss_bvh_refit(bvh, pos);
      int mismatch = 0;
      for (int q = 0; q < 2000; q++) {
        double p[3] = {26 * ss_test_rand(&s) - 3, 26 * ss_test_rand(&s) - 3, 12 * ss_test_rand(&s) - 6};
        int fb, fr;
        double uv[2];
        double d_brute = brute_closest(t, pos, p, &fb);
        double d_bvh = ss_bvh_closest(bvh, pos, p, &fr, uv);
        if (!(d_bvh == d_brute && fr == fb)) mismatch++;
      }
      CHECK_MSG(mismatch == 0, "seed %llu pose %d: %d of 2000 queries differ from brute force",
                seed, pose, mismatch);
    }
    free(pos);
    ss_bvh_destroy(bvh);
    ss_topo_destroy(t);
    test_mesh_free(&m);
  }
}

static void test_nring(void) {
  test_mesh m = test_grid(12, 12, 0.2, 9);
  ss_topo *t = NULL;
  ss_nring *nr = NULL;
  char err[256];
  CHECK(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, -1.0, err, sizeof err) == SS_OK);
  CHECK(ss_nring_create(&nr, t) == SS_OK);
  unsigned long long s = 4;
  for (int q = 0; q < 300; q++) {
    int face = (int)(ss_test_rand(&s) * m.nface) % m.nface;
    double p[3] = {12 * ss_test_rand(&s), 12 * ss_test_rand(&s), ss_test_rand(&s)};
    int f_out, fb;
    double uv[2];
    /* enough rings cover the whole mesh: the global closest point */
    double d_all = ss_nring_closest(nr, t, m.pos, face, 100, p, &f_out, uv);
    CHECK(d_all == brute_closest(t, m.pos, p, &fb) && f_out == fb);
    /* zero rings: the face alone */
    ss_nring_closest(nr, t, m.pos, face, 0, p, &f_out, uv);
    CHECK_EQ_INT(f_out, face);
    /* one ring: a face sharing a vertex with the start face */
    ss_nring_closest(nr, t, m.pos, face, 1, p, &f_out, uv);
    int shares = 0;
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++)
        shares |= t->vert_weld[t->face_vert[3 * face + a]] == t->vert_weld[t->face_vert[3 * f_out + b]];
    CHECK(shares);
  }
  ss_nring_destroy(nr);
  ss_topo_destroy(t);
  test_mesh_free(&m);
}

static void test_surface_distance(void) {
  test_mesh m = test_grid(10, 10, 0.0, 1);
  ss_topo *t = NULL;
  ss_geodesic *geo = NULL;
  char err[256];
  CHECK(ss_topo_create(&t, m.nvert, m.pos, m.nface, m.faces, -1.0, err, sizeof err) == SS_OK);
  CHECK(ss_geodesic_create(&geo, t) == SS_OK);
  ss_frames *fr = NULL;
  CHECK(ss_frames_create(&fr, t->nface) == SS_OK);
  ss_frames_update(fr, t, m.pos);
  unsigned long long s = 8;
  for (int q = 0; q < 500; q++) {
    int fa = (int)(ss_test_rand(&s) * m.nface) % m.nface, fb = (int)(ss_test_rand(&s) * m.nface) % m.nface;
    double ua[2] = {0.5 * ss_test_rand(&s), 0.5 * ss_test_rand(&s)};
    double ub[2] = {0.5 * ss_test_rand(&s), 0.5 * ss_test_rand(&s)};
    double a[3], b[3];
    ss_anchor_position(fr, fa, ua, a);
    ss_anchor_position(fr, fb, ub, b);
    double eu = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]));
    double d = ss_surface_distance(geo, t, m.pos, fa, ua, fb, ub, 1e9);
    /* on a plane: never shorter than the straight line; on this grid (one
     * diagonal per cell) an edge path is at most sqrt 2 longer, plus the two
     * legs to and from corners (each under one diagonal) */
    CHECK(d >= eu - 1e-12);
    CHECK_MSG(d <= sqrt(2.0) * eu + 2.0 * sqrt(2.0), "d %g eu %g", d, eu);
    if (fa == fb) CHECK_NEAR(d, eu, 1e-12);
    for (int k = 0; k < 3; k++)
      if (t->face_adj[3 * fa + k] == fb) CHECK_NEAR(d, eu, 1e-9); /* flat neighbours: exact */
    /* beyond the limit: INFINITY */
    if (eu > 1.0) CHECK(isinf(ss_surface_distance(geo, t, m.pos, fa, ua, fb, ub, 0.5 * eu)));
  }
  ss_frames_destroy(fr);
  ss_geodesic_destroy(geo);
  ss_topo_destroy(t);
  test_mesh_free(&m);
}

/* The snag geometry itself: on a thin closed slab, the two sides are close
 * in space and far along the surface. */
static void test_surface_distance_across_gap(void) {
  /* a strip folded over: bottom sheet y in [0,10] at z = 0, top at z = 0.1,
   * joined along y = 10 */
  test_mesh g = test_grid(2, 20, 0.0, 1);
  for (int v = 0; v < g.nvert; v++) {
    double y = g.pos[3 * v + 1];
    if (y > 10.0) {
      g.pos[3 * v + 1] = 20.0 - y;
      g.pos[3 * v + 2] = 0.1;
    }
  }
  ss_topo *t = NULL;
  ss_geodesic *geo = NULL;
  char err[256];
  CHECK(ss_topo_create(&t, g.nvert, g.pos, g.nface, g.faces, -1.0, err, sizeof err) == SS_OK);
  CHECK(ss_geodesic_create(&geo, t) == SS_OK);
  double uv[2] = {0.3, 0.3};
  /* face 0 at y ~ 0 bottom; the last face at y ~ 0 top */
  double d = ss_surface_distance(geo, t, g.pos, 0, uv, g.nface - 1, uv, 1e9);
  CHECK(d > 19.0);
  CHECK(isinf(ss_surface_distance(geo, t, g.pos, 0, uv, g.nface - 1, uv, 5.0)));
  ss_geodesic_destroy(geo);
  ss_topo_destroy(t);
  test_mesh_free(&g);
}

/* Regression (issue 14, found by fuzzing): a degenerate triangle and a far
 * finite point made every squared distance overflow to inf and left uv
 * unwritten; the n-ring search and the BVH then read uninitialised stack. Every
 * path now writes uv, far points are scaled before the arithmetic, non-finite
 * points get the barycenter and an infinite distance. */
static void test_far_and_nonfinite_points(void) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {2, 0, 0}; /* collinear */
  const double far[3] = {1e300, -1e300, 3e299};
  double uv[2] = {NAN, NAN};
  double d2 = ss_closest_point_triangle(far, a, b, c, uv);
  CHECK_MSG(isfinite(uv[0]) && isfinite(uv[1]) && uv[0] >= 0 && uv[1] >= 0 && uv[0] + uv[1] <= 1 + 1e-12,
            "degenerate triangle, far point: uv (%g, %g)", uv[0], uv[1]);
  CHECK(!(d2 < 1e300)); /* the true squared distance is beyond double range */
  /* far from a unit triangle (beyond double resolution: any point of it) */
  const double b2[3] = {1, 0, 0}, c2[3] = {0, 1, 0}, px[3] = {1e200, 0, 0};
  uv[0] = uv[1] = NAN;
  CHECK(isinf(ss_closest_point_triangle(px, a, b2, c2, uv)));
  CHECK_MSG(uv[0] >= 0 && uv[1] >= 0 && uv[0] + uv[1] <= 1 + 1e-12, "far +x: uv (%g, %g)", uv[0], uv[1]);
  /* a huge scene (products would overflow): the answer of the same scene at unit scale */
  const double p2[3] = {3, 1, -2}, a3[3] = {0.1, 0.2, 0.3};
  const double *unit[4] = {p2, a3, b2, c2};
  double big[4][3];
  for (int k = 0; k < 4; k++)
    for (int i = 0; i < 3; i++) big[k][i] = 1e300 * unit[k][i];
  double uv1[2], uv2[2];
  double d2big = ss_closest_point_triangle(big[0], big[1], big[2], big[3], uv1);
  double d2unit = ss_closest_point_triangle(p2, a3, b2, c2, uv2);
  CHECK(isinf(d2big) && isfinite(d2unit));
  CHECK_NEAR(uv1[0], uv2[0], 1e-9);
  CHECK_NEAR(uv1[1], uv2[1], 1e-9);
  const double nanp[3] = {NAN, 0, 0}, infp[3] = {0, INFINITY, 0};
  uv[0] = uv[1] = NAN;
  CHECK(isinf(ss_closest_point_triangle(nanp, a, b, c, uv)) && uv[0] == 1.0 / 3.0 && uv[1] == 1.0 / 3.0);
  uv[0] = uv[1] = NAN;
  CHECK(isinf(ss_closest_point_triangle(infp, a, b2, c2, uv)) && isfinite(uv[0]) && isfinite(uv[1]));
  /* a strip whose every face is degenerate (all on the x axis): n-ring and BVH */
  double pos[3 * 6];
  int faces[3 * 4] = {0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4};
  for (int v = 0; v < 6; v++) pos[3 * v] = v, pos[3 * v + 1] = pos[3 * v + 2] = 0.0;
  ss_topo *t = NULL;
  char err[256];
  CHECK(ss_topo_create(&t, 6, pos, 4, faces, -1.0, err, sizeof err) == SS_OK);
  if (!t) return;
  ss_nring *r = NULL;
  ss_bvh *bvh = NULL;
  CHECK(ss_nring_create(&r, t) == SS_OK && ss_bvh_create(&bvh, t) == SS_OK);
  ss_bvh_refit(bvh, pos);
  const double *qs[3] = {far, nanp, infp};
  for (int k = 0; k < 3; k++) {
    int f = -1;
    uv[0] = uv[1] = NAN;
    ss_nring_closest(r, t, pos, 1, 2, qs[k], &f, uv);
    CHECK_MSG(f >= 0 && f < 4 && isfinite(uv[0]) && isfinite(uv[1]), "n-ring, query %d", k);
    f = -1;
    uv[0] = uv[1] = NAN;
    ss_bvh_closest(bvh, pos, qs[k], &f, uv);
    CHECK_MSG(f >= 0 && f < 4 && isfinite(uv[0]) && isfinite(uv[1]), "BVH, query %d", k);
  }
  ss_bvh_destroy(bvh);
  ss_nring_destroy(r);
  ss_topo_destroy(t);
}

int main(void) {
  test_triangle_vs_sampling();
  test_bvh_vs_brute();
  test_nring();
  test_surface_distance();
  test_surface_distance_across_gap();
  test_far_and_nonfinite_points();
  return ss_test_finish("test_closest");
}
