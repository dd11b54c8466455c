/* The anchor walk (paper, section 2): every stop reason, crossings between
 * faces of very different shapes and orientations, seams, slivers and
 * zero-area faces, clamping, and the step bound. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "isa.h"
#include "mover.h"
#include "ss_test.h"
#include "ss_test_mesh.h"

typedef struct {
  ss_topo *topo;
  ss_frames *frames;
  ss_walker *walker;
  const double *pos;
} walk_env;

static walk_env env_make(const test_mesh *m) {
  walk_env e = {0};
  char err[256] = "";
  int status = ss_topo_create(&e.topo, m->nvert, m->pos, m->nface, m->faces, -1.0, err, sizeof err);
  CHECK_MSG(status == SS_OK, "%s", err);
  CHECK(ss_frames_create(&e.frames, m->nface) == SS_OK);
  CHECK(ss_walker_create(&e.walker, m->nface) == SS_OK);
  ss_frames_update(e.frames, e.topo, m->pos);
  e.pos = m->pos;
  return e;
}

static void env_free(walk_env *e) {
  ss_walker_destroy(e->walker);
  ss_frames_destroy(e->frames);
  ss_topo_destroy(e->topo);
}

static int uv_inside(const double uv[2]) {
  return isfinite(uv[0]) && isfinite(uv[1]) && uv[0] >= 0.0 && uv[1] >= 0.0 &&
         uv[0] + uv[1] <= 1.0 + 1e-15;
}

/* Finds the (non-degenerate) face of a planar z = 0 mesh containing (x, y)
 * and its uv. */
static int locate(const walk_env *e, double x, double y, double uv[2]) {
  for (int f = 0; f < e->topo->nface; f++) {
    if (e->frames->degenerate[f]) continue;
    const double *o = ss_frames_origin(e->frames, f), *t = ss_frames_to_canon(e->frames, f);
    double d[3] = {x - o[0], y - o[1], -o[2]};
    double u = t[0] * d[0] + t[1] * d[1] + t[2] * d[2], v = t[3] * d[0] + t[4] * d[1] + t[5] * d[2];
    if (u >= -1e-12 && v >= -1e-12 && u + v <= 1.0 + 1e-12) {
      uv[0] = u, uv[1] = v;
      return f;
    }
  }
  return -1;
}

/* On a flat mesh, a walk to a target above an interior point ends exactly
 * below it (the orthogonal projection), whatever faces it crosses. */
static void test_flat_jittered(void) {
  test_mesh m = test_grid(16, 16, 0.3, 7); /* thin and fat triangles mixed */
  walk_env e = env_make(&m);
  double min_area = INFINITY, max_area = 0.0;
  for (int f = 0; f < m.nface; f++) {
    const double *n = e.frames->normal + 3 * f;
    CHECK(n[2] > 0.0); /* a valid planar mesh: no face folded over */
    min_area = fmin(min_area, e.frames->area[f]);
    max_area = fmax(max_area, e.frames->area[f]);
  }
  CHECK(max_area > 5.0 * min_area);
  unsigned long long s = 99;
  int crossings = 0;
  for (int trial = 0; trial < 2000; trial++) {
    double x0 = 0.5 + 15.0 * ss_test_rand(&s), y0 = 0.5 + 15.0 * ss_test_rand(&s);
    double x1 = 0.5 + 15.0 * ss_test_rand(&s), y1 = 0.5 + 15.0 * ss_test_rand(&s);
    double uv[2];
    int f = locate(&e, x0, y0, uv);
    CHECK(f >= 0);
    if (f < 0) continue;
    double target[3] = {x1, y1, 2.0 * ss_test_rand(&s) - 1.0};
    ss_walk_result r;
    ss_walk(e.walker, e.topo, e.frames, f, uv, target, 10000, &r);
    CHECK_EQ_INT(r.stop, SS_STOP_INSIDE);
    CHECK(uv_inside(r.uv));
    double a1[3];
    ss_anchor_position(e.frames, r.face, r.uv, a1);
    CHECK_NEAR(a1[0], x1, 1e-9);
    CHECK_NEAR(a1[1], y1, 1e-9);
    CHECK_NEAR(a1[2], 0.0, 1e-12);
    /* on a plane the walked path is the straight segment */
    CHECK_NEAR(r.length, hypot(x1 - x0, y1 - y0), 1e-9);
    crossings += r.steps;
  }
  CHECK(crossings > 2000 * 5); /* the walks really crossed many faces */
  env_free(&e);
  test_mesh_free(&m);
}

/* Flipping the orientation of half the faces (a mesh of inconsistent
 * winding) must not change where walks end: points cross edges by welded ids. */
static void test_mixed_orientation(void) {
  test_mesh m = test_grid(8, 8, 0.3, 3);
  for (int f = 0; f < m.nface; f += 2) {
    int t = m.faces[3 * f + 1];
    m.faces[3 * f + 1] = m.faces[3 * f + 2];
    m.faces[3 * f + 2] = t;
  }
  walk_env e = env_make(&m);
  unsigned long long s = 5;
  for (int trial = 0; trial < 500; trial++) {
    double x0 = 0.5 + 7.0 * ss_test_rand(&s), y0 = 0.5 + 7.0 * ss_test_rand(&s);
    double x1 = 0.5 + 7.0 * ss_test_rand(&s), y1 = 0.5 + 7.0 * ss_test_rand(&s);
    double uv[2], a1[3], target[3] = {x1, y1, 0.3};
    int f = locate(&e, x0, y0, uv);
    ss_walk_result r;
    ss_walk(e.walker, e.topo, e.frames, f, uv, target, 10000, &r);
    ss_anchor_position(e.frames, r.face, r.uv, a1);
    CHECK_EQ_INT(r.stop, SS_STOP_INSIDE);
    CHECK_NEAR(a1[0], x1, 1e-9);
    CHECK_NEAR(a1[1], y1, 1e-9);
  }
  env_free(&e);
  test_mesh_free(&m);
}

/* A target beyond the border: the walk stops on the boundary edge where the
 * ray leaves the mesh. */
static void test_boundary(void) {
  test_mesh m = test_grid(4, 4, 0.0, 1);
  walk_env e = env_make(&m);
  double uv[2];
  int f = locate(&e, 1.25, 2.0, uv);
  double target[3] = {9.25, 2.0 + 0.5 * 8.0 / 2.0, 0.7}; /* ray from (1.25,2) with slope 0.25 */
  ss_walk_result r;
  ss_walk(e.walker, e.topo, e.frames, f, uv, target, 512, &r);
  CHECK_EQ_INT(r.stop, SS_STOP_BOUNDARY);
  double a1[3];
  ss_anchor_position(e.frames, r.face, r.uv, a1);
  CHECK_NEAR(a1[0], 4.0, 1e-12); /* on the border x = 4 */
  /* the hit point: the projected ray (1.25,2) + t (8, 2) at x = 4 */
  CHECK_NEAR(a1[1], 2.0 + (4.0 - 1.25) / 8.0 * 2.0, 1e-9);
  CHECK(uv_inside(r.uv));
  env_free(&e);
  test_mesh_free(&m);
}

/* A sharp fold of two faces (wings rising from a shared edge, 2 x 18 degrees
 * apart from vertical) and a target below the fold line (seen from the
 * other side: beyond a sharp ridge). Its projection onto either wing lies
 * beyond the shared edge, so the walk crosses over, is pulled straight back
 * and stops on the shared edge (the paper's crease). */
static void test_crease(void) {
  /* edge (0,0,0)-(0,1,0) shared; wings rising to x = -1 and x = +1 at height 3 */
  double pos[] = {0, 0, 0, 0, 1, 0, -1, 0.5, 3, 1, 0.5, 3};
  int faces[] = {0, 1, 2, 1, 0, 3};
  test_mesh m = {4, 2, pos, faces};
  walk_env e = env_make(&m);
  double uv[2] = {0.2, 0.6}; /* on the left wing */
  double target[3] = {0.3, 0.5, -1.0};
  ss_walk_result r;
  ss_walk(e.walker, e.topo, e.frames, 0, uv, target, 512, &r);
  CHECK_EQ_INT(r.stop, SS_STOP_CREASE);
  CHECK_EQ_INT(r.steps, 1);
  double a1[3];
  ss_anchor_position(e.frames, r.face, r.uv, a1);
  CHECK_NEAR(a1[0], 0.0, 1e-12); /* on the shared edge x = z = 0 */
  CHECK_NEAR(a1[2], 0.0, 1e-12);
  CHECK(a1[1] >= 0.0 && a1[1] <= 1.0);
  /* "the optimal anchor position lies along an edge": the point of the
   * crease edge nearest the target, wherever the ray met it */
  const double targets[2][3] = {{0.3, 0.85, -1.0}, {0.3, 0.1, -2.0}};
  const double expect_y[2] = {0.85, 0.1};
  for (int k = 0; k < 2; k++) {
    ss_walk(e.walker, e.topo, e.frames, 0, uv, targets[k], 512, &r);
    CHECK_EQ_INT(r.stop, SS_STOP_CREASE);
    ss_anchor_position(e.frames, r.face, r.uv, a1);
    CHECK_NEAR(a1[0], 0.0, 1e-12);
    CHECK_NEAR(a1[1], expect_y[k], 1e-12);
    CHECK_NEAR(a1[2], 0.0, 1e-12);
  }
  env_free(&e);
}

/* Round a corner: from a grid vertex on a ridge (a corner of each face it
 * may start in) towards points all round it, on the ridge's two slopes and
 * in faces that only share the vertex with the start face, the walk ends
 * exactly where the target projects (the tether walks anchors home to bind
 * points, which are often body vertices). */
static void test_round_corner(void) {
  const double dirs[8][2] = {{-0.4, -0.3}, {0.3, 0.4}, {-0.3, 0.4}, {0.4, -0.3},
                             {-0.5, 0.05}, {0.35, -0.5}, {0.45, 0.45}, {-0.45, -0.45}};
  int n_faces = 0, stuck = 0, runs = 0;
  /* the ridge along y (x = 2) or along x (y = 2), on the grid as made and mirrored */
  for (int variant = 0; variant < 4; variant++) {
    const int along_x = variant & 1, mirror = variant >> 1;
    test_mesh m = test_grid(4, 4, 0.0, 1);
    for (int v = 0; v < m.nvert; v++) {
      double *p = m.pos + 3 * v;
      if (mirror) p[0] = 4.0 - p[0];
      p[2] = -0.2 * fabs(p[along_x ? 1 : 0] - 2.0);
    }
    if (mirror) /* keep the faces' winding (normals up) */
      for (int f = 0; f < m.nface; f++) {
        int t = m.faces[3 * f + 1];
        m.faces[3 * f + 1] = m.faces[3 * f + 2];
        m.faces[3 * f + 2] = t;
      }
    walk_env e = env_make(&m);
    for (int f = 0; f < e.topo->nface; f++) {
      const int *fv = m.faces + 3 * f;
      for (int c = 0; c < 3; c++) {
        const double *v = m.pos + 3 * fv[c];
        if (fabs(v[0] - 2.0) > 1e-12 || fabs(v[1] - 2.0) > 1e-12) continue;
        n_faces++;
        const double uv[2] = {c == 1 ? 1.0 : 0.0, c == 2 ? 1.0 : 0.0};
        for (int k = 0; k < 8; k++) {
          const double d0 = along_x ? dirs[k][1] : dirs[k][0], d1 = along_x ? dirs[k][0] : dirs[k][1];
          const double target[3] = {2.0 + d0, 2.0 + d1, 0.5};
          ss_walk_result r;
          ss_walk(e.walker, e.topo, e.frames, f, uv, target, 512, &r);
          double a1[3];
          ss_anchor_position(e.frames, r.face, r.uv, a1);
          /* the ridge's two slopes z = slope (u - 2), u across the ridge:
           * the target projects onto the one on its side (|du| >= 0.3: not
           * into the ridge's wedge) */
          const int across = along_x ? 1 : 0;
          const double du = target[across] - 2.0, slope = du < 0.0 ? 0.2 : -0.2;
          const double t = (target[2] - slope * du) / (1.0 + slope * slope);
          double want[2] = {target[0], target[1]};
          want[across] += t * slope;
          runs++;
          if (!(r.stop == SS_STOP_INSIDE && fabs(a1[0] - want[0]) < 1e-9 && fabs(a1[1] - want[1]) < 1e-9)) {
            stuck++;
            printf("test_round_corner: variant %d, from face %d corner %d to (%g, %g): stop %d at "
                   "(%g, %g), want (%g, %g)\n", variant, f, c, target[0], target[1], r.stop, a1[0],
                   a1[1], want[0], want[1]);
          }
        }
      }
    }
    env_free(&e);
    test_mesh_free(&m);
  }
  CHECK(n_faces >= 16);
  CHECK_MSG(stuck == 0, "%d of %d walks round a corner did not end where the target projects", stuck, runs);
}

/* The step bound: a long strip, at most max_steps crossings. */
static void test_step_limit(void) {
  test_mesh m = test_grid(40, 1, 0.0, 1);
  walk_env e = env_make(&m);
  double uv[2];
  int f = locate(&e, 0.3, 0.5, uv);
  double target[3] = {39.5, 0.5, 0.0};
  ss_walk_result r;
  ss_walk(e.walker, e.topo, e.frames, f, uv, target, 3, &r);
  CHECK_EQ_INT(r.stop, SS_STOP_STEP_LIMIT);
  CHECK_EQ_INT(r.steps, 3);
  CHECK(uv_inside(r.uv));
  ss_walk(e.walker, e.topo, e.frames, f, uv, target, 1000, &r);
  CHECK_EQ_INT(r.stop, SS_STOP_INSIDE);
  CHECK(r.steps > 40);
  env_free(&e);
  test_mesh_free(&m);
}

/* Seams: around the seamed cube (every side its own vertices), a target far
 * away on the opposite side is reached through the welded seams. */
static void test_seamed_cube_walk(void) {
  test_mesh m = test_seamed_cube();
  walk_env e = env_make(&m);
  /* start at the centre of the bottom (z = 0) side: face 0 or 1 */
  double uv[2];
  int f = -1;
  for (int g = 0; g < 2 && f < 0; g++) {
    const double *o = ss_frames_origin(e.frames, g), *t = ss_frames_to_canon(e.frames, g);
    double d[3] = {0.5 - o[0], 0.25 - o[1], -o[2]};
    uv[0] = t[0] * d[0] + t[1] * d[1] + t[2] * d[2];
    uv[1] = t[3] * d[0] + t[4] * d[1] + t[5] * d[2];
    if (uv[0] >= 0 && uv[1] >= 0 && uv[0] + uv[1] <= 1) f = g;
  }
  CHECK(f >= 0);
  /* pulled towards a point beside the y = 0 side: walks over the seam onto it */
  double target[3] = {0.5, -3.0, 0.5};
  ss_walk_result r;
  ss_walk(e.walker, e.topo, e.frames, f, uv, target, 512, &r);
  double a1[3];
  ss_anchor_position(e.frames, r.face, r.uv, a1);
  CHECK(r.steps >= 1);
  CHECK(r.face == 4 || r.face == 5); /* the y = 0 side */
  CHECK_NEAR(a1[1], 0.0, 1e-12);
  CHECK_NEAR(a1[0], 0.5, 1e-9);
  CHECK_NEAR(a1[2], 0.5, 1e-9);
  CHECK_EQ_INT(r.stop, SS_STOP_INSIDE);
  env_free(&e);
  test_mesh_free(&m);
}

/* Slivers and zero-area faces: grid vertices (i+1, i) moved onto the cell
 * diagonal (i+0.5, i+0.5) make the faces beside that diagonal collinear
 * (zero area) on even i, and needles 1e-9 wide on odd i, all without any
 * face folding over. Walks across them never give NaN, always end inside a
 * face, and on this flat mesh still land exactly on the projected target. */
static void test_slivers_and_zero_area(void) {
  test_mesh m = test_grid(10, 10, 0.0, 1);
  for (int i = 1; i < 9; i++) {
    double *p = m.pos + 3 * (i * 11 + i + 1);
    p[0] = i + 0.5 + (i % 2 ? 1e-9 : 0.0);
    p[1] = i + 0.5;
  }
  walk_env e = env_make(&m);
  CHECK(e.topo->ndegenerate_face > 0);
  int needles = 0;
  for (int f = 0; f < m.nface; f++) {
    CHECK(e.frames->normal[3 * f + 2] >= 0.0); /* nothing folded over */
    if (e.frames->area[f] > 0 && e.frames->area[f] < 1e-8) needles++;
  }
  CHECK(needles > 0);
  unsigned long long s = 11;
  int bad = 0, off = 0, across = 0;
  for (int trial = 0; trial < 2000; trial++) {
    double x0 = 0.3 + 9.4 * ss_test_rand(&s), y0 = 0.3 + 9.4 * ss_test_rand(&s);
    double x1 = 0.3 + 9.4 * ss_test_rand(&s), y1 = 0.3 + 9.4 * ss_test_rand(&s);
    double uv[2], a1[3], target[3] = {x1, y1, 0.5};
    int f = locate(&e, x0, y0, uv);
    if (f < 0) continue;
    ss_walk_result r;
    ss_walk(e.walker, e.topo, e.frames, f, uv, target, 10000, &r);
    ss_anchor_position(e.frames, r.face, r.uv, a1);
    if (!uv_inside(r.uv) || !isfinite(a1[0] + a1[1] + a1[2])) bad++;
    if (fabs(a1[0] - x1) > 1e-6 || fabs(a1[1] - y1) > 1e-6) off++;
    if ((x0 - y0) * (x1 - y1) < 0.0) across++;
  }
  CHECK(across > 500); /* many walks had to cross the degenerate column */
  CHECK_EQ_INT(bad, 0);
  CHECK_MSG(off == 0, "%d of 2000 walks ended away from their projected target", off);
  /* a walk that starts inside a zero-area face */
  for (int f = 0; f < e.topo->nface; f++) {
    if (!e.topo->face_degenerate[f]) continue;
    double uv[2] = {0.3, 0.3}, target[3] = {8.0, 2.0, 1.0};
    ss_walk_result r;
    ss_walk(e.walker, e.topo, e.frames, f, uv, target, 1000, &r);
    CHECK(uv_inside(r.uv));
  }
  /* a face collapsed to a point: finite and stays put */
  double pos1[] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  int faces1[] = {0, 1, 2};
  test_mesh p = {3, 1, pos1, faces1};
  walk_env e1 = env_make(&p);
  double uv[2] = {0.2, 0.2}, target[3] = {1, 2, 3};
  ss_walk_result r;
  ss_walk(e1.walker, e1.topo, e1.frames, 0, uv, target, 10, &r);
  CHECK(uv_inside(r.uv));
  for (int i = 0; i < 6; i++) CHECK(isfinite(ss_frames_to_canon(e1.frames, 0)[i]));
  env_free(&e1);
  env_free(&e);
  test_mesh_free(&m);
}

/* Clamping against round-off and bad input: a start slightly outside is
 * pulled in; a NaN start becomes the barycenter; a NaN target leaves the
 * anchor where it is. */
static void test_clamp_and_nan(void) {
  test_mesh m = test_grid(2, 2, 0.0, 1);
  walk_env e = env_make(&m);
  double uv[2] = {-1e-13, 1.0 + 1e-12};
  double target[3];
  ss_anchor_position(e.frames, 0, (double[2]){0.0, 1.0}, target);
  ss_walk_result r;
  ss_walk(e.walker, e.topo, e.frames, 0, uv, target, 512, &r);
  CHECK(uv_inside(r.uv));
  double nan_uv[2] = {NAN, 0.1};
  ss_walk(e.walker, e.topo, e.frames, 0, nan_uv, target, 512, &r);
  CHECK(uv_inside(r.uv));
  double good_uv[2] = {0.2, 0.3}, nan_target[3] = {NAN, 0, 0};
  ss_walk(e.walker, e.topo, e.frames, 3, good_uv, nan_target, 512, &r);
  CHECK_EQ_INT(r.face, 3);
  CHECK_EQ_INT(r.steps, 0);
  CHECK(r.uv[0] == 0.2 && r.uv[1] == 0.3);
  double inf_target[3] = {0, INFINITY, 0};
  ss_walk(e.walker, e.topo, e.frames, 3, good_uv, inf_target, 512, &r);
  CHECK(r.face == 3 && r.steps == 0);
  CHECK(strcmp(ss_walk_stop_name(SS_STOP_CREASE), "crease") == 0);
  env_free(&e);
  test_mesh_free(&m);
}

/* On a curved closed surface (a cube corner region), when a walk ends
 * inside a face its point is the orthogonal projection of a* onto that face. */
static void test_projection_property(void) {
  test_mesh m = test_seamed_cube();
  walk_env e = env_make(&m);
  unsigned long long s = 17;
  for (int trial = 0; trial < 500; trial++) {
    int f = (int)(12 * ss_test_rand(&s)) % 12;
    double uv[2] = {0.5 * ss_test_rand(&s), 0.5 * ss_test_rand(&s)};
    double a0[3], target[3], a1[3];
    ss_anchor_position(e.frames, f, uv, a0);
    for (int c = 0; c < 3; c++) target[c] = a0[c] + 0.8 * (2.0 * ss_test_rand(&s) - 1.0);
    ss_walk_result r;
    ss_walk(e.walker, e.topo, e.frames, f, uv, target, 512, &r);
    CHECK(uv_inside(r.uv));
    ss_anchor_position(e.frames, r.face, r.uv, a1);
    if (r.stop != SS_STOP_INSIDE) continue;
    /* a* - a1 is along the face normal */
    const double *n = e.frames->normal + 3 * r.face;
    double d[3] = {target[0] - a1[0], target[1] - a1[1], target[2] - a1[2]};
    double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    for (int c = 0; c < 3; c++) CHECK_NEAR(d[c] - dn * n[c], 0.0, 1e-12);
  }
  env_free(&e);
  test_mesh_free(&m);
}

/* The frame update's per-face record is the face: origin v0, edges v1 - v0
 * and v2 - v0, a canonical map that takes the edges to (1,0) and (0,1), and
 * the degenerate flag. */
static void test_frame_records(void) {
  test_mesh m = test_grid(6, 5, 0.3, 3);
  walk_env e = env_make(&m);
  for (int f = 0; f < m.nface; f++) {
    const double *v0 = m.pos + 3 * m.faces[3 * f], *v1 = m.pos + 3 * m.faces[3 * f + 1],
                 *v2 = m.pos + 3 * m.faces[3 * f + 2];
    const double *o = ss_frames_origin(e.frames, f), *ed = ss_frames_edges(e.frames, f);
    const double *t = ss_frames_to_canon(e.frames, f);
    for (int i = 0; i < 3; i++) {
      CHECK(o[i] == v0[i]);
      CHECK(ed[i] == v1[i] - v0[i]);
      CHECK(ed[3 + i] == v2[i] - v0[i]);
    }
    CHECK(e.frames->walk[SS_FRAME_RECORD * f + 15] == (e.frames->degenerate[f] ? 1.0 : 0.0));
    CHECK(!e.frames->degenerate[f]);
    for (int k = 0; k < 2; k++) { /* T e1 = (1, 0), T e2 = (0, 1) */
      CHECK_NEAR(t[0] * ed[3 * k] + t[1] * ed[3 * k + 1] + t[2] * ed[3 * k + 2], k == 0, 1e-12);
      CHECK_NEAR(t[3] * ed[3 * k] + t[4] * ed[3 * k + 1] + t[5] * ed[3 * k + 2], k == 1, 1e-12);
    }
  }
  env_free(&e);
  test_mesh_free(&m);
}

/* The frame update in lanes (each vector width the CPU runs, 1 and 2
 * threads) writes exactly what one face at a time writes (frames.isa -1):
 * records, normals, areas and flags, bit for bit, on a mesh whose faces take
 * every branch: regular, needles, zero area, collapsed to a point, huge
 * (overflowing squares) and non-finite corners, and a count that leaves a
 * partial block of lanes. */
static void test_frame_lanes(void) {
  test_mesh m = test_grid(9, 7, 0.3, 5);
  for (int i = 1; i < 6; i++) { /* zero-area and needle faces */
    double *p = m.pos + 3 * (i * 10 + i + 1);
    p[0] = i + 0.5 + (i % 2 ? 1e-9 : 0.0);
    p[1] = i + 0.5;
  }
  ss_topo *topo = NULL;
  char err[256] = "";
  CHECK_MSG(ss_topo_create(&topo, m.nvert, m.pos, m.nface, m.faces, -1.0, err, sizeof err) == SS_OK, "%s", err);
  /* a pose, bent out of the plane, with what no rest mesh may have */
  for (int v = 0; v < m.nvert; v++) m.pos[3 * v + 2] = 0.3 * sin(1.7 * v);
  m.pos[3 * 33 + 0] = m.pos[3 * 34 + 0], m.pos[3 * 33 + 1] = m.pos[3 * 34 + 1]; /* a collapsed edge */
  m.pos[3 * 40 + 2] = 1e200; /* squares overflow */
  m.pos[3 * 52 + 1] = NAN;   /* non-finite */
  m.pos[3 * 61 + 0] = INFINITY;
  ss_frames *ref = NULL, *fr = NULL;
  CHECK(ss_frames_create(&ref, m.nface) == SS_OK && ss_frames_create(&fr, m.nface) == SS_OK);
  if (!topo || !ref || !fr) return;
  CHECK(m.nface % 8 != 0);
  ref->isa = -1;
  ss_frames_update(ref, topo, m.pos);
  int degenerate = 0;
  for (int f = 0; f < m.nface; f++) degenerate += ref->degenerate[f];
  CHECK(degenerate > 0);
  for (int isa = 0; isa < SS_ISA_COUNT; isa++) {
    if (!ss_isa_supported(isa)) {
      printf("test_walk: frames in %s not run (not on this CPU)\n", ss_isa_name(isa));
      continue;
    }
    for (int threads = 1; threads <= 2; threads++) {
      memset(fr->walk, 0xab, sizeof(double) * SS_FRAME_RECORD * (size_t)m.nface);
      fr->isa = isa;
      ss_frames_update_threads(fr, topo, m.pos, threads);
      const size_t nf = (size_t)m.nface;
      CHECK_MSG(memcmp(ref->walk, fr->walk, sizeof(double) * SS_FRAME_RECORD * nf) == 0 &&
                    memcmp(ref->normal, fr->normal, sizeof(double) * 3 * nf) == 0 &&
                    memcmp(ref->area, fr->area, sizeof(double) * nf) == 0 &&
                    memcmp(ref->degenerate, fr->degenerate, nf) == 0,
                "frames in %s at %d threads differ from one face at a time", ss_isa_name(isa), threads);
    }
  }
  ss_frames_destroy(ref);
  ss_frames_destroy(fr);
  ss_topo_destroy(topo);
  test_mesh_free(&m);
}

/* One triangle (every edge a boundary): the walk's outcome equals that of the
 * three exit divisions of the paper's ray test, computed here step by step,
 * for rays that end near an edge within a few ulps (the walk skips the
 * divisions where exact comparisons show that the ray ends inside). */
static void test_exit_exact(void) {
  const double pos[9] = {0.1, -0.2, 0.05, 1.3, 0.1, -0.1, 0.2, 0.9, 0.3};
  const int faces[3] = {0, 1, 2};
  ss_topo *topo = NULL;
  char err[256] = "";
  CHECK_MSG(ss_topo_create(&topo, 3, pos, 1, faces, -1.0, err, sizeof err) == SS_OK, "%s", err);
  ss_frames *fr = NULL;
  ss_walker *walker = NULL;
  CHECK(ss_frames_create(&fr, 1) == SS_OK && ss_walker_create(&walker, 1) == SS_OK);
  ss_frames_update(fr, topo, pos);
  const double *w = ss_frames_origin(fr, 0), *t = ss_frames_to_canon(fr, 0);
  unsigned long long s = 5;
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 20000; trial++) {
    double p[2] = {ss_test_rand(&s), ss_test_rand(&s)};
    if (p[0] + p[1] > 1.0) p[0] = 1.0 - p[0], p[1] = 1.0 - p[1];
    if (trial % 4 == 0) p[trial % 8 == 0 ? 0 : 1] = 0.0; /* start on an edge */
    /* a target above a point of an edge (or corner), nudged by a few ulps */
    double q[2], sq = ss_test_rand(&s);
    int k = trial % 3;
    q[0] = k == 0 ? sq : k == 1 ? 1.0 - sq : 0.0;
    q[1] = k == 0 ? 0.0 : k == 1 ? sq : 1.0 - sq;
    if (trial % 7 == 0) q[0] = q[1] = 0.0;
    double target[3];
    ss_anchor_position(fr, 0, q, target);
    for (int i = 0; i < 3; i++) {
      int ulps = (int)(9 * ss_test_rand(&s)) - 4;
      for (; ulps > 0; ulps--) target[i] = nextafter(target[i], INFINITY);
      for (; ulps < 0; ulps++) target[i] = nextafter(target[i], -INFINITY);
    }
    /* the ray test as written in the paper's terms: three divisions */
    double here[3], d[3];
    for (int i = 0; i < 3; i++) here[i] = w[i] + p[0] * w[3 + i] + p[1] * w[6 + i];
    for (int i = 0; i < 3; i++) d[i] = target[i] - here[i];
    const double du = t[0] * d[0] + t[1] * d[1] + t[2] * d[2];
    const double dv = t[3] * d[0] + t[4] * d[1] + t[5] * d[2];
    double t_exit = 1.0;
    int k_exit = -1;
    if (dv < 0.0 && -p[1] / dv < t_exit) t_exit = -p[1] / dv, k_exit = 0;
    if (du + dv > 0.0 && (1.0 - p[0] - p[1]) / (du + dv) < t_exit)
      t_exit = (1.0 - p[0] - p[1]) / (du + dv), k_exit = 1;
    if (du < 0.0 && -p[0] / du < t_exit) t_exit = -p[0] / du, k_exit = 2;
    ss_walk_result r;
    ss_walk(walker, topo, fr, 0, p, target, 512, &r);
    CHECK_EQ_INT(r.steps, 0);
    if (k_exit < 0) {
      inside++;
      double e_uv[2] = {p[0] + du, p[1] + dv};
      if (e_uv[0] < 0.0) e_uv[0] = 0.0;
      if (e_uv[1] < 0.0) e_uv[1] = 0.0;
      if (e_uv[0] + e_uv[1] > 1.0) {
        double sum = e_uv[0] + e_uv[1];
        e_uv[0] /= sum, e_uv[1] /= sum;
      }
      CHECK_EQ_INT(r.stop, SS_STOP_INSIDE);
      CHECK(r.uv[0] == e_uv[0] && r.uv[1] == e_uv[1]);
    } else {
      outside++;
      CHECK_EQ_INT(r.stop, SS_STOP_BOUNDARY);
    }
  }
  CHECK(inside > 2000 && outside > 2000); /* both outcomes are exercised */
  ss_walker_destroy(walker);
  ss_frames_destroy(fr);
  ss_topo_destroy(topo);
}

/* Squared distance between world points a and b. */
static double dist2(const double a[3], const double b[3]) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

/* The slide on the tether's leash (ss_slide_in_face): a target that projects
 * into the face gives the walk's end to the bit; one that projects outside
 * but within reach gives the face's point nearest it (no point of the face
 * nearer, 0 steps, the path its straight length); a farther, non-finite or
 * degenerate case is left to the walk (0). */
static void test_slide_in_face(void) {
  test_mesh m = test_seamed_cube();
  walk_env e = env_make(&m);
  unsigned long long s = 29;
  int inside = 0, clamped = 0, far = 0;
  for (int trial = 0; trial < 2000; trial++) {
    const int f = (int)(12 * ss_test_rand(&s)) % 12;
    double uv[2] = {ss_test_rand(&s), ss_test_rand(&s)};
    if (uv[0] + uv[1] > 1.0) uv[0] = 1.0 - uv[0], uv[1] = 1.0 - uv[1];
    if (trial % 4 == 0) uv[0] = 0.0; /* on an edge, as a leashed anchor often is */
    double a0[3], target[3];
    ss_anchor_position(e.frames, f, uv, a0);
    const double reach = trial % 2 ? 0.3 : 1.5;
    for (int c = 0; c < 3; c++) target[c] = a0[c] + reach * (2.0 * ss_test_rand(&s) - 1.0);
    /* the target's barycentric coordinates in the face's plane */
    const double *o = ss_frames_origin(e.frames, f), *t = ss_frames_to_canon(e.frames, f);
    const double d[3] = {target[0] - o[0], target[1] - o[1], target[2] - o[2]};
    const double qu = t[0] * d[0] + t[1] * d[1] + t[2] * d[2], qv = t[3] * d[0] + t[4] * d[1] + t[5] * d[2];
    const double lowest = fmin(fmin(qu, qv), 1.0 - qu - qv);
    ss_walk_result r, w;
    const int got = ss_slide_in_face(e.frames, f, uv, target, 1, &r);
    if (fabs(lowest) < 1e-9 || fabs(lowest + SS_LEASH_REACH) < 1e-9) continue; /* on a border */
    CHECK_EQ_INT(got, lowest > -SS_LEASH_REACH);
    if (!got) {
      far++;
      continue;
    }
    CHECK_EQ_INT(r.face, f);
    CHECK_EQ_INT(r.steps, 0);
    CHECK_EQ_INT(r.stop, SS_STOP_INSIDE);
    CHECK(uv_inside(r.uv));
    double a1[3];
    ss_anchor_position(e.frames, f, r.uv, a1);
    CHECK_NEAR(r.length, sqrt(dist2(a1, a0)), 1e-12);
    if (lowest > 0.0) {
      inside++;
      ss_walk(e.walker, e.topo, e.frames, f, uv, target, 512, &w);
      CHECK(w.face == r.face && w.uv[0] == r.uv[0] && w.uv[1] == r.uv[1]);
      CHECK(w.length == r.length);
    } else {
      clamped++;
      const double d1 = dist2(a1, target);
      for (int i = 0; i <= 20; i++)
        for (int j = 0; i + j <= 20; j++) {
          double x[3];
          ss_anchor_position(e.frames, f, (double[2]){i / 20.0, j / 20.0}, x);
          CHECK(d1 <= dist2(x, target) + 1e-12);
        }
    }
  }
  CHECK_MSG(inside > 100 && clamped > 100 && far > 100, "cases: %d inside, %d clamped, %d far", inside,
            clamped, far);
  /* At rest a leashed anchor sits on a corner or an edge of its home face
   * and its target is where it is, within rounding: it stays there (the
   * walk's in-face test and the nearest point must agree on the edges it
   * is beyond, or the anchor jumps to another edge) */
  const double on_border[7][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}, {0.3, 0.7}};
  for (int f = 0; f < 12; f++)
    for (int i = 0; i < 7; i++)
      for (int j = 0; j < 12; j++) {
        double t[3]; /* off by a few units of the last place or less, as rounding leaves it */
        ss_anchor_position(e.frames, f, on_border[i], t);
        const int c = j % 3, up = (j / 3) & 1;
        if (j < 6) t[c] = nextafter(t[c], up ? INFINITY : -INFINITY); /* one unit of the last place */
        else t[c] += up ? 1e-15 : -1e-15;
        ss_walk_result rb;
        CHECK(ss_slide_in_face(e.frames, f, on_border[i], t, 0, &rb));
        double at[3];
        ss_anchor_position(e.frames, f, rb.uv, at);
        const double moved = sqrt(dist2(at, t));
        CHECK_MSG(moved < 1e-12, "face %d, (%g, %g): the slide to where it is moved it %g", f,
                  on_border[i][0], on_border[i][1], moved);
      }
  /* The same at a corner at the world's origin, where rounding leaves the
   * target off by far less than a unit of the last place of 1: the walk's
   * test sees the point beyond an edge that u + v = 1 in rounding does not
   * (as a skin at rest gave), the origin at each corner in turn */
  const double uv_corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  for (int rot = 0; rot < 3; rot++) {
    test_mesh tri = {3, 1, malloc(9 * sizeof(double)), malloc(3 * sizeof(int))};
    const double corner[3][3] = {{0, 0, 0}, {1, 0, 0}, {0.3, 0.8, 0}};
    for (int k = 0; k < 3; k++) {
      tri.faces[k] = k;
      for (int c = 0; c < 3; c++) tri.pos[3 * k + c] = corner[(k + 3 - rot) % 3][c];
    }
    walk_env et = env_make(&tri);
    const double *uv0 = uv_corner[rot]; /* the corner at the origin */
    for (int j = 0; j < 6; j++) {
      double t[3];
      ss_anchor_position(et.frames, 0, uv0, t);
      CHECK(t[0] == 0.0 && t[1] == 0.0 && t[2] == 0.0);
      t[j % 3] = j < 3 ? 1e-20 : -1e-20;
      ss_walk_result rt;
      CHECK(ss_slide_in_face(et.frames, 0, uv0, t, 0, &rt));
      double at[3];
      ss_anchor_position(et.frames, 0, rt.uv, at);
      CHECK_MSG(fabs(at[0]) + fabs(at[1]) + fabs(at[2]) < 1e-12, "corner %d, offset %d: moved to (%g, %g)",
                rot, j, rt.uv[0], rt.uv[1]);
    }
    env_free(&et);
    test_mesh_free(&tri);
  }

  ss_walk_result r;
  const double nan_target[3] = {0.1, NAN, 0.0}, uv[2] = {0.2, 0.2};
  CHECK_EQ_INT(ss_slide_in_face(e.frames, 0, uv, nan_target, 0, &r), 0);
  env_free(&e);
  test_mesh_free(&m);

  /* a face with no area: left to the walk, which passes through it */
  test_mesh z = test_grid(3, 3, 0.0, 1);
  for (int c = 0; c < 3; c++) z.pos[3 * z.faces[2] + c] = z.pos[3 * z.faces[0] + c];
  walk_env ez = env_make(&z);
  CHECK(ez.frames->degenerate[0]);
  double a[3]; /* beyond its far end, along the line it is */
  ss_anchor_position(ez.frames, 0, (double[2]){1.5, 0.0}, a);
  CHECK_EQ_INT(ss_slide_in_face(ez.frames, 0, uv, a, 0, &r), 0);
  env_free(&ez);
  test_mesh_free(&z);
}

int main(void) {
  test_frame_records();
  test_frame_lanes();
  test_exit_exact();
  test_flat_jittered();
  test_mixed_orientation();
  test_boundary();
  test_crease();
  test_round_corner();
  test_step_limit();
  test_seamed_cube_walk();
  test_slivers_and_zero_area();
  test_clamp_and_nan();
  test_projection_property();
  test_slide_in_face();
  return ss_test_finish("test_walk");
}
