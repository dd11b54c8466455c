/* libFuzzer harness: topology, the anchor walk, the n-ring and BVH searches
 * and the surface distance on small random meshes: degenerate and zero-area
 * faces, repeated and coincident vertices, non-manifold fans, far and
 * non-finite query points and targets (issue 14: a degenerate triangle and a
 * far point left the closest point's uv unwritten). Asserts what ss_anchor.h
 * promises: a walk ends on a face of the mesh with uv finite inside it; a
 * search returns a face in range and finite uv. */
#include <assert.h>

#include "fuzz_util.h"
#include "bvh.h"
#include "closest.h"
#include "geodesic.h"
#include "mover.h"
#include "skin_sim/ss_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_uv(int face, const double uv[2], int nface) {
  assert(face >= 0 && face < nface);
  assert(isfinite(uv[0]) && isfinite(uv[1]));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fz f = {data, size};
  int nvert = fz_int(&f, 1, 12), nface = fz_int(&f, 1, 16);
  double pos[3 * 12], pose[3 * 12];
  int faces[3 * 16];
  double scale = (fz_u8(&f) & 0x80) ? 1e-6 : 1.0;
  for (int i = 0; i < 3 * nvert; i++) pos[i] = fz_double(&f, scale);
  for (int i = 0; i < 3 * nface; i++) faces[i] = (fz_u8(&f) & 0xf0) ? fz_int(&f, 0, nvert - 1) : fz_int(&f, -1, nvert);
  ss_topo *t = NULL;
  char err[128];
  double weld = (fz_u8(&f) & 1) ? -1.0 : fz_double(&f, 1e-3);
  if (ss_topo_create(&t, nvert, pos, nface, faces, weld, err, sizeof err) != SS_OK) return 0;
  /* a pose: the rest shape moved, sometimes with a far or non-finite vertex */
  for (int i = 0; i < 3 * nvert; i++) pose[i] = pos[i] + ((fz_u8(&f) & 3) ? 0.0 : fz_double(&f, 0.5));
  int finite_pose = 1;
  for (int i = 0; i < 3 * nvert; i++) finite_pose &= isfinite(pose[i]) != 0;
  ss_frames *fr = NULL;
  ss_walker *w = NULL;
  ss_bvh *bvh = NULL;
  ss_nring *nr = NULL;
  ss_geodesic *geo = NULL;
  if (ss_frames_create(&fr, nface) != SS_OK || ss_walker_create(&w, nface) != SS_OK ||
      ss_bvh_create(&bvh, t) != SS_OK || ss_nring_create(&nr, t) != SS_OK ||
      ss_geodesic_create(&geo, t) != SS_OK)
    abort();
  ss_frames_update(fr, t, pose);
  ss_bvh_refit(bvh, pose);
  (void)ss_topo_mean_edge_length(t, pose);
  int nq = fz_int(&f, 1, 6);
  for (int q = 0; q < nq; q++) {
    int face = fz_int(&f, 0, nface - 1);
    double uv[2] = {fz_double(&f, 0.25), fz_double(&f, 0.25)};
    if (!(uv[0] >= 0 && uv[1] >= 0 && uv[0] + uv[1] <= 1)) uv[0] = uv[1] = 1.0 / 3.0;
    double target[3];
    for (int i = 0; i < 3; i++) target[i] = fz_double(&f, 1.0);
    ss_walk_result r;
    ss_walk(w, t, fr, face, uv, target, fz_int(&f, 0, 64), &r);
    assert(r.face >= 0 && r.face < nface && r.steps >= 0);
    if (finite_pose) {
      check_uv(r.face, r.uv, nface);
      assert(!isnan(r.length) && r.length >= 0.0); /* inf: a path beyond double range */
    }
    double anchor[3];
    ss_anchor_position(fr, r.face, r.uv, anchor);
    int fo = -1;
    double uvo[2] = {NAN, NAN};
    double d2 = ss_bvh_closest(bvh, pose, target, &fo, uvo);
    check_uv(fo, uvo, nface);
    assert(!isnan(d2));
    fo = -1;
    uvo[0] = uvo[1] = NAN;
    d2 = ss_nring_closest(nr, t, pose, face, fz_int(&f, 0, 4), target, &fo, uvo);
    check_uv(fo, uvo, nface);
    assert(!isnan(d2));
    /* the triangle routine on three raw points */
    double a[3], b[3], c[3];
    for (int i = 0; i < 3; i++) a[i] = fz_double(&f, 1.0), b[i] = fz_double(&f, 1.0), c[i] = fz_double(&f, 1.0);
    uvo[0] = uvo[1] = NAN;
    d2 = ss_closest_point_triangle(target, a, b, c, uvo);
    assert(isfinite(uvo[0]) && isfinite(uvo[1]) && !isnan(d2));
    if (finite_pose) {
      double dist = ss_surface_distance(geo, t, pose, face, uv, r.face, r.uv, fz_double(&f, 4.0));
      assert(!isnan(dist));
    }
  }
  for (int m = 0; m < 3; m++) {
    ss_mover_settings ms = ss_mover_default_settings();
    ms.method = m;
    ms.walk_max_steps = fz_int(&f, -1, 40);
    ms.nring_rings = fz_int(&f, -1, 5);
    ss_mover *mv = NULL;
    if (ss_mover_create(&mv, t, &ms, NULL, err, sizeof err) != SS_OK) continue;
    ss_mover_set_pose(mv, pose);
    double uv[2] = {1.0 / 3.0, 1.0 / 3.0}, target[3];
    for (int i = 0; i < 3; i++) target[i] = fz_double(&f, 1.0);
    ss_walk_result r;
    ss_mover_move(mv, fz_int(&f, 0, nface - 1), uv, target, &r);
    assert(r.face >= 0 && r.face < nface);
    if (finite_pose) check_uv(r.face, r.uv, nface);
    ss_mover_destroy(mv);
  }
  ss_geodesic_destroy(geo);
  ss_nring_destroy(nr);
  ss_bvh_destroy(bvh);
  ss_walker_destroy(w);
  ss_frames_destroy(fr);
  ss_topo_destroy(t);
  return 0;
}
