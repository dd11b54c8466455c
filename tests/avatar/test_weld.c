/* Welding: a cube whose six sides have their own vertices (normal seams),
 * written by this test as OBJ and as PLY into a temporary folder and read
 * through assimp. The file keeps 24 vertices; topology welds them to 8, the
 * surface is closed and every face has three neighbours, sides meeting at a
 * seam are neighbours, and an anchor walks across a seam onto the next side. */
#include <string.h>
#include <unistd.h>

#include "walk.h"
#include "skin_sim/ss_mesh.h"
#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

/* side s: outward normal n, two tangents u, v (u x v = n) */
static const double sides[6][3][3] = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};

static void corner(int s, int k, double *p) {
  static const double uv[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int c = 0; c < 3; c++)
    p[c] = sides[s][0][c] + uv[k][0] * sides[s][1][c] + uv[k][1] * sides[s][2][c];
}

static void write_obj(const char *path) {
  FILE *f = fopen(path, "w");
  if (!f) return;
  fprintf(f, "# seamed cube: 4 vertices and 1 normal per side\n");
  for (int s = 0; s < 6; s++)
    for (int k = 0; k < 4; k++) {
      double p[3];
      corner(s, k, p);
      fprintf(f, "v %g %g %g\n", p[0], p[1], p[2]);
    }
  for (int s = 0; s < 6; s++)
    fprintf(f, "vn %g %g %g\n", sides[s][0][0], sides[s][0][1], sides[s][0][2]);
  for (int s = 0; s < 6; s++)
    fprintf(f, "f %d//%d %d//%d %d//%d %d//%d\n", 4 * s + 1, s + 1, 4 * s + 2, s + 1, 4 * s + 3,
            s + 1, 4 * s + 4, s + 1);
  fclose(f);
}

static void write_ply(const char *path) {
  FILE *f = fopen(path, "w");
  if (!f) return;
  fprintf(f, "ply\nformat ascii 1.0\nelement vertex 24\nproperty float x\nproperty float y\n"
             "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
             "element face 12\nproperty list uchar int vertex_indices\nend_header\n");
  for (int s = 0; s < 6; s++)
    for (int k = 0; k < 4; k++) {
      double p[3];
      corner(s, k, p);
      fprintf(f, "%g %g %g %g %g %g\n", p[0], p[1], p[2], sides[s][0][0], sides[s][0][1],
              sides[s][0][2]);
    }
  for (int s = 0; s < 6; s++) {
    fprintf(f, "3 %d %d %d\n", 4 * s, 4 * s + 1, 4 * s + 2);
    fprintf(f, "3 %d %d %d\n", 4 * s, 4 * s + 2, 4 * s + 3);
  }
  fclose(f);
}

static void check_cube(const char *path) {
  char err[512] = "";
  ssa_asset *a = NULL;
  ssa_asset_opts o = ssa_asset_default_opts();
  o.z_up = 0;
  CHECK_EQ_INT(ssa_asset_load(&a, path, &o, err, sizeof err), SS_OK);
  if (!a) {
    fprintf(stderr, "%s: %s\n", path, err);
    return;
  }
  CHECK_EQ_INT(a->nvert, 24); /* seams kept in the file's vertices */
  CHECK_EQ_INT(a->nface, 12);
  CHECK_EQ_INT(a->npart, 1);
  CHECK_EQ_INT(a->nbone_file, 0);
  for (int v = 0; v < a->nvert; v++) CHECK(a->vert_part[v] == 0 && a->vert_src[v] == v);
  /* without welding the sides are separate */
  ss_topo *t = NULL;
  CHECK_EQ_INT(ss_topo_create(&t, a->nvert, a->rest_pos, a->nface, a->faces, 0.0, err, sizeof err),
               SS_OK);
  if (t) {
    CHECK_EQ_INT(t->nweld, 8); /* bit-identical corners weld even at tolerance 0 */
    ss_topo_destroy(t);
  }
  CHECK_EQ_INT(ss_topo_create(&t, a->nvert, a->rest_pos, a->nface, a->faces, -1.0, err, sizeof err),
               SS_OK);
  if (!t) return;
  CHECK_EQ_INT(t->nweld, 8);
  CHECK_EQ_INT(t->nedge, 18);
  CHECK_EQ_INT(t->nboundary_edge, 0);
  CHECK_EQ_INT(t->nnonmanifold_edge, 0);
  int cross_side = 0;
  for (int f = 0; f < t->nface; f++)
    for (int k = 0; k < 3; k++) {
      int g = t->face_adj[3 * f + k];
      CHECK(g >= 0);
      /* the side of a face is its first vertex / 4 (the files list sides in order) */
      if (g >= 0 && a->faces[3 * f] / 4 != a->faces[3 * g] / 4) cross_side++;
    }
  CHECK_EQ_INT(cross_side, 24); /* 12 seam edges, seen from both sides */
  /* outward orientation: positive volume (8 for the 2 x 2 x 2 cube) */
  double vol = 0;
  for (int f = 0; f < a->nface; f++) {
    const double *p = a->rest_pos + 3 * a->faces[3 * f], *q = a->rest_pos + 3 * a->faces[3 * f + 1],
                 *r = a->rest_pos + 3 * a->faces[3 * f + 2];
    vol += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
            p[2] * (q[0] * r[1] - q[1] * r[0])) / 6.0;
  }
  CHECK_NEAR(vol, 8.0, 1e-9);
  /* walk from the middle of a +x face towards a point on the +y side */
  ss_frames *fr = NULL;
  ss_walker *wk = NULL;
  CHECK_EQ_INT(ss_frames_create(&fr, t->nface), SS_OK);
  CHECK_EQ_INT(ss_walker_create(&wk, t->nface), SS_OK);
  if (fr && wk) {
    ss_frames_update(fr, t, a->rest_pos);
    int start = -1;
    for (int f = 0; f < t->nface; f++) {
      double c[3];
      ss_anchor_position(fr, f, (double[]){1.0 / 3, 1.0 / 3}, c);
      if (c[0] > 0.99 && c[1] > 0.0) start = f; /* on +x, towards +y */
    }
    CHECK(start >= 0);
    if (start >= 0) {
      double target[3] = {0.8, 1.3, 0.1}; /* beyond the seam x = 1, y = 1, above the +y side */
      ss_walk_result res;
      ss_walk(wk, t, fr, start, (double[]){1.0 / 3, 1.0 / 3}, target, 64, &res);
      double end[3];
      ss_anchor_position(fr, res.face, res.uv, end);
      CHECK_EQ_INT(res.stop, SS_STOP_INSIDE);
      CHECK(res.steps >= 1);
      CHECK_MSG(fabs(end[1] - 1.0) < 1e-9 && end[0] < 1.0 - 1e-3,
                "the walk ended at %g %g %g, not on the +y side", end[0], end[1], end[2]);
    }
  }
  ss_frames_destroy(fr);
  ss_walker_destroy(wk);
  ss_topo_destroy(t);
  ssa_asset_destroy(a);
}

int main(void) {
  char dir[] = "/tmp/ssa_weld_XXXXXX";
  if (!mkdtemp(dir)) {
    fprintf(stderr, "cannot make a temporary folder\n");
    return 1;
  }
  char obj[64], ply[64];
  snprintf(obj, sizeof obj, "%s/cube.obj", dir);
  snprintf(ply, sizeof ply, "%s/cube.ply", dir);
  write_obj(obj);
  write_ply(ply);
  check_cube(obj);
  check_cube(ply);
  unlink(obj);
  unlink(ply);
  rmdir(dir);
  return ss_test_finish("test_weld");
}
