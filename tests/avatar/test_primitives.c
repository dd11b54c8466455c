/* URDF primitives become bodies, and Collada up axes are an option.
 *
 * ssa_primitive_mesh: box, sphere and cylinder meshes are closed (every edge
 * used once in each direction: consistently wound), outward (positive
 * volume), near the analytic volume and area, with well-shaped triangles
 * (smallest angle) and a resolution that follows the edge length. A URDF of
 * primitives and one mixing them with a mesh (written here) load as avatars
 * whose pieces are closed, placed by each <origin> and moved by the joints.
 * A Y_UP Collada mesh reads as written by default (rviz) with one warning,
 * and turned Z-up with mesh_up_axis FILE. */
#include <string.h>
#include <unistd.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

#define PI 3.14159265358979323846

static char dir[] = "/tmp/ssa_prim_XXXXXX";

static const char *put(const char *name, const char *text) {
  static char paths[8][256];
  static int k = 0;
  char *p = paths[k++ % 8];
  snprintf(p, 256, "%s/%s", dir, name);
  FILE *f = fopen(p, "wb");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
  return p;
}

typedef struct shape {
  double volume, area, min_angle_deg, max_edge;
  int open_edges; /* directed edges without their reverse, or used twice */
} shape;

static int cmp_ll(const void *a, const void *b) {
  long long x = *(const long long *)a, y = *(const long long *)b;
  return x < y ? -1 : x > y;
}

/* Measures faces [f0, f1) of a mesh (vertices of those faces only). */
static shape measure(const double *pos, const int *faces, int f0, int f1, int nvert) {
  shape s = {0, 0, 180, 0, 0};
  int n = f1 - f0;
  long long *e = malloc(sizeof(long long) * 3 * (size_t)(n > 0 ? n : 1));
  for (int f = f0; f < f1; f++) {
    const int *t = faces + 3 * f;
    const double *p[3] = {pos + 3 * t[0], pos + 3 * t[1], pos + 3 * t[2]};
    double c[3] = {p[1][1] * p[2][2] - p[1][2] * p[2][1], p[1][2] * p[2][0] - p[1][0] * p[2][2],
                   p[1][0] * p[2][1] - p[1][1] * p[2][0]};
    s.volume += (p[0][0] * c[0] + p[0][1] * c[1] + p[0][2] * c[2]) / 6.0;
    double u[3], v[3];
    for (int k = 0; k < 3; k++) u[k] = p[1][k] - p[0][k], v[k] = p[2][k] - p[0][k];
    double x[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    s.area += 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int k = 0; k < 3; k++) {
      const double *a = p[k], *b = p[(k + 1) % 3], *cc = p[(k + 2) % 3];
      double ab[3], ac[3];
      for (int d = 0; d < 3; d++) ab[d] = b[d] - a[d], ac[d] = cc[d] - a[d];
      double lab = sqrt(ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
      double lac = sqrt(ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2]);
      double ang = acos((ab[0] * ac[0] + ab[1] * ac[1] + ab[2] * ac[2]) / (lab * lac)) * 180 / PI;
      if (ang < s.min_angle_deg) s.min_angle_deg = ang;
      if (lab > s.max_edge) s.max_edge = lab;
      e[3 * (f - f0) + k] = (long long)t[k] * nvert + t[(k + 1) % 3];
    }
  }
  qsort(e, 3 * (size_t)n, sizeof(long long), cmp_ll);
  for (int i = 0; i < 3 * n; i++) {
    long long a = e[i] / nvert, b = e[i] % nvert, rev = b * nvert + a;
    int dup = (i > 0 && e[i - 1] == e[i]);
    void *hit = bsearch(&rev, e, 3 * (size_t)n, sizeof(long long), cmp_ll);
    if (dup || !hit) s.open_edges++;
  }
  free(e);
  return s;
}

static int warnings = 0;
static char last_warning[1024];
static void on_warn(void *user, const char *msg) {
  (void)user;
  warnings++;
  snprintf(last_warning, sizeof last_warning, "%s", msg);
  printf("warning: %s\n", msg);
}

static void bbox(const ssa_avatar *av, int v0, int v1, double *lo, double *hi) {
  for (int k = 0; k < 3; k++) lo[k] = 1e300, hi[k] = -1e300;
  for (int v = v0; v < v1; v++)
    for (int k = 0; k < 3; k++) {
      double x = av->rest_pos[3 * v + k];
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
}

static const char *collada(const char *up) {
  static char buf[2048];
  snprintf(buf, sizeof buf,
           "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
           "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
           "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>%s</up_axis></asset>\n"
           "<library_geometries><geometry id=\"g\" name=\"g\"><mesh>\n"
           "<source id=\"gp\"><float_array id=\"gpa\" count=\"12\">0 0 0 1 0 0 0 2 0 0 0 3</float_array>\n"
           "<technique_common><accessor source=\"#gpa\" count=\"4\" stride=\"3\">"
           "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
           "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
           "<vertices id=\"gv\"><input semantic=\"POSITION\" source=\"#gp\"/></vertices>\n"
           "<triangles count=\"4\"><input semantic=\"VERTEX\" source=\"#gv\" offset=\"0\"/>"
           "<p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>\n"
           "</mesh></geometry></library_geometries>\n"
           "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\" name=\"n\">"
           "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
           "<scene><instance_visual_scene url=\"#s\"/></scene></COLLADA>\n",
           up);
  return buf;
}

int main(void) {
  if (!mkdtemp(dir)) return 1;
  char err[1024] = "";

  /* ---- single primitives: closed, outward, analytic volume and area, good triangles */
  struct {
    int kind;
    double size[3];
    double volume, area;
  } cases[] = {
      {SSA_VISUAL_BOX, {0.3, 0.2, 0.1}, 0.006, 2 * (0.06 + 0.03 + 0.02)},
      {SSA_VISUAL_SPHERE, {0.1, 0, 0}, 4.0 / 3.0 * PI * 1e-3, 4 * PI * 0.01},
      {SSA_VISUAL_CYLINDER, {0.05, 0.4, 0}, PI * 0.0025 * 0.4, 2 * PI * 0.05 * 0.4 + 2 * PI * 0.0025},
      {SSA_VISUAL_CYLINDER, {0.3, 0.01, 0}, PI * 0.09 * 0.01, 2 * PI * 0.3 * 0.01 + 2 * PI * 0.09},
  };
  const double edge = 0.02;
  int ntri_coarse[4] = {0};
  for (int c = 0; c < 4; c++) {
    double *pos = NULL;
    int *faces = NULL, nv = 0, nf = 0;
    CHECK_EQ_INT(ssa_primitive_mesh(cases[c].kind, cases[c].size, edge, &pos, &nv, &faces, &nf,
                                    err, sizeof err), SS_OK);
    if (!pos) continue;
    shape s = measure(pos, faces, 0, nf, nv);
    printf("primitive %d (%g %g %g): %d vertices, %d triangles, volume %.6g (analytic %.6g), area "
           "%.6g (%.6g), smallest angle %.1f deg, longest edge %.4f m, open edges %d\n",
           cases[c].kind, cases[c].size[0], cases[c].size[1], cases[c].size[2], nv, nf, s.volume,
           cases[c].volume, s.area, cases[c].area, s.min_angle_deg, s.max_edge, s.open_edges);
    CHECK_EQ_INT(s.open_edges, 0);
    CHECK_EQ_INT(nv - 3 * nf / 2 + nf, 2); /* Euler characteristic of a sphere: closed, one piece */
    CHECK(s.volume > 0);
    CHECK_MSG(fabs(s.volume / cases[c].volume - 1) < 0.03, "volume %g vs %g", s.volume, cases[c].volume);
    CHECK_MSG(fabs(s.area / cases[c].area - 1) < 0.03, "area %g vs %g", s.area, cases[c].area);
    CHECK_MSG(s.min_angle_deg > 25, "smallest angle %g deg", s.min_angle_deg);
    CHECK_MSG(s.max_edge < 2.0 * edge, "longest edge %g m for a target of %g", s.max_edge, edge);
    ntri_coarse[c] = nf;
    free(pos);
    free(faces);
    /* half the edge length: about four times the triangles (fewer where the 24 columns
       around a circle or the one row of a thin side are the minimum) */
    CHECK_EQ_INT(ssa_primitive_mesh(cases[c].kind, cases[c].size, edge / 2, &pos, &nv, &faces,
                                    &nf, err, sizeof err), SS_OK);
    CHECK_MSG(nf > 2.5 * ntri_coarse[c] && nf < 5 * ntri_coarse[c], "%d -> %d triangles", ntri_coarse[c], nf);
    if (pos) CHECK_EQ_INT(measure(pos, faces, 0, nf, nv).open_edges, 0);
    free(pos);
    free(faces);
  }
  /* a tiny sphere still has a shape; sizes that are no length are refused */
  {
    double *pos = NULL;
    int *faces = NULL, nv = 0, nf = 0;
    double tiny[3] = {0.001, 0, 0};
    CHECK_EQ_INT(ssa_primitive_mesh(SSA_VISUAL_SPHERE, tiny, edge, &pos, &nv, &faces, &nf, err, sizeof err), SS_OK);
    CHECK(nf >= 400);
    free(pos);
    free(faces);
    double bad[3][3] = {{0, 1, 1}, {-1, 1, 1}, {NAN, 1, 1}};
    for (int b = 0; b < 3; b++) {
      err[0] = '\0';
      CHECK_EQ_INT(ssa_primitive_mesh(SSA_VISUAL_BOX, bad[b], edge, &pos, &nv, &faces, &nf, err, sizeof err), SS_E_ARG);
      CHECK(strstr(err, "box size") != NULL && pos == NULL);
      printf("bad box -> %s\n", err);
    }
    CHECK_EQ_INT(ssa_primitive_mesh(SSA_VISUAL_MESH, tiny, edge, &pos, &nv, &faces, &nf, err, sizeof err), SS_E_ARG);
    /* a 20 m box at 2 cm edges would be 6 million triangles: capped, still closed */
    double huge[3] = {20, 20, 20};
    CHECK_EQ_INT(ssa_primitive_mesh(SSA_VISUAL_BOX, huge, edge, &pos, &nv, &faces, &nf, err, sizeof err), SS_OK);
    CHECK_MSG(nf > 100000 && nf <= 250000, "%d triangles", nf);
    if (pos) CHECK_EQ_INT(measure(pos, faces, 0, nf, nv).open_edges, 0);
    free(pos);
    free(faces);
  }

  /* ---- a robot of primitives: base box, an arm cylinder placed by its origin, a ball */
  const char *urdf = put("prims.urdf",
      "<robot name='prims'>"
      "<link name='base'><visual><origin xyz='0 0 0.05'/><geometry><box size='0.4 0.3 0.1'/></geometry></visual></link>"
      "<link name='arm'><visual><origin xyz='0.15 0 0' rpy='0 1.5707963267948966 0'/>"
      "<geometry><cylinder radius='0.04' length='0.3'/></geometry></visual></link>"
      "<link name='ball'><visual><geometry><sphere radius='0.06'/></geometry></visual></link>"
      "<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/>"
      "<origin xyz='0 0 0.2'/><axis xyz='0 0 1'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>"
      "<joint name='wrist' type='fixed'><parent link='arm'/><child link='ball'/><origin xyz='0.3 0 0'/></joint>"
      "</robot>");
  ssa_avatar_opts o = ssa_avatar_default_opts();
  o.warn = on_warn;
  ssa_avatar *av = NULL;
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, urdf, NULL, &o, err, sizeof err), SS_OK);
  if (!av) fprintf(stderr, "%s\n", err);
  if (av) {
    const ssa_robot *r = av->robot;
    printf("robot of primitives: %d vertices, %d triangles\n", av->nvert, av->nface);
    CHECK_EQ_INT(r->nvisual, 3);
    CHECK_EQ_INT(warnings, 0);
    double exact[3] = {0.4 * 0.3 * 0.1, PI * 0.04 * 0.04 * 0.3, 4.0 / 3.0 * PI * 0.06 * 0.06 * 0.06};
    double *posed = malloc(sizeof(double) * 3 * (size_t)av->nvert);
    double q[2] = {0};
    int js = ssa_robot_joint_index(r, "shoulder");
    for (int pass = 0; pass < 2; pass++) {
      if (pass == 1) q[js] = PI / 2;
      ssa_avatar_pose_joints(av, q, posed);
      int f0 = 0;
      for (int piece = 0; piece < 3; piece++) {
        int f1 = f0;
        while (f1 < av->nface && av->vert_part[av->faces[3 * f1]] == av->vert_part[av->faces[3 * f0]]) f1++;
        shape s = measure(posed, av->faces, f0, f1, av->nvert);
        int vis = av->vert_part[av->faces[3 * f0]];
        int kind = r->visual_kind[vis];
        int which = kind == SSA_VISUAL_BOX ? 0 : kind == SSA_VISUAL_CYLINDER ? 1 : 2;
        CHECK_EQ_INT(s.open_edges, 0);
        CHECK_MSG(fabs(s.volume / exact[which] - 1) < 0.03, "piece %d volume %g vs %g", piece,
                  s.volume, exact[which]);
        /* the piece's centre where the link pose and the visual origin put it */
        double c[3] = {0, 0, 0};
        int n = 0;
        for (int v = 0; v < av->nvert; v++)
          if (av->vert_part[v] == vis) {
            for (int k = 0; k < 3; k++) c[k] += posed[3 * v + k];
            n++;
          }
        for (int k = 0; k < 3; k++) c[k] /= n;
        double want[3][2][3] = {{{0, 0, 0.05}, {0, 0, 0.05}},
                                {{0.15, 0, 0.2}, {0, 0.15, 0.2}},
                                {{0.3, 0, 0.2}, {0, 0.3, 0.2}}};
        for (int k = 0; k < 3; k++) CHECK_NEAR(c[k], want[which][pass][k], 1e-3);
        f0 = f1;
      }
      CHECK_EQ_INT(f0, av->nface);
    }
    /* the cylinder lies along x at rest (its origin turns z onto x): its extent in x is its length */
    double lo[3], hi[3];
    int v0 = -1, v1 = -1;
    for (int v = 0; v < av->nvert; v++)
      if (r->visual_kind[av->vert_part[v]] == SSA_VISUAL_CYLINDER) {
        if (v0 < 0) v0 = v;
        v1 = v + 1;
      }
    bbox(av, v0, v1, lo, hi);
    CHECK_NEAR(hi[0] - lo[0], 0.3, 1e-9);
    CHECK_NEAR(hi[2] - lo[2], 0.08, 1e-3);
    free(posed);
    /* a coarser edge: fewer triangles */
    int fine = av->nface;
    ssa_avatar_destroy(av);
    av = NULL;
    o.primitive_edge = 0.05;
    CHECK_EQ_INT(ssa_avatar_load_urdf(&av, urdf, NULL, &o, err, sizeof err), SS_OK);
    if (av) CHECK_MSG(av->nface < fine / 2, "%d triangles at 5 cm vs %d at 2 cm", av->nface, fine);
    ssa_avatar_destroy(av);
    av = NULL;
    o.primitive_edge = 0.02;
  }

  /* a primitive with a size that is no length: refused, naming the link */
  const char *badp = put("badprim.urdf",
      "<robot name='b'><link name='plate'><visual><geometry><box size='0.1 0 0.1'/></geometry>"
      "</visual></link></robot>");
  err[0] = '\0';
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, badp, NULL, &o, err, sizeof err), SS_E_ARG);
  CHECK(strstr(err, "plate") && strstr(err, "box size"));
  printf("zero box -> %s\n", err);

  /* ---- mixed: a Y_UP Collada mesh on one link, a sphere on another */
  put("tet_y.dae", collada("Y_UP"));
  put("tet_z.dae", collada("Z_UP"));
  const char *mixed = put("mixed.urdf",
      "<robot name='mixed'>"
      "<link name='body'><visual><geometry><mesh filename='tet_y.dae'/></geometry></visual>"
      "<visual><origin xyz='5 0 0'/><geometry><mesh filename='tet_y.dae'/></geometry></visual></link>"
      "<link name='head'><visual><geometry><sphere radius='0.1'/></geometry></visual></link>"
      "<joint name='neck' type='fixed'><parent link='body'/><child link='head'/><origin xyz='0 0 4'/></joint>"
      "</robot>");
  for (int mode = 0; mode < 2; mode++) {
    warnings = 0;
    o.mesh_up_axis = mode ? SSA_UP_AXIS_FILE : SSA_UP_AXIS_IGNORE;
    CHECK_EQ_INT(ssa_avatar_load_urdf(&av, mixed, NULL, &o, err, sizeof err), SS_OK);
    if (!av) {
      fprintf(stderr, "%s\n", err);
      continue;
    }
    /* the first tetrahedron: as written (x 1, y 2, z 3), or Y_UP turned Z-up: (x, -z, y) */
    double lo[3], hi[3];
    bbox(av, 0, 4, lo, hi);
    const double want_lo[2][3] = {{0, 0, 0}, {0, -3, 0}}, want_hi[2][3] = {{1, 2, 3}, {1, 0, 2}};
    printf("mesh_up_axis %s: tetrahedron box [%g %g %g] .. [%g %g %g], %d warning(s)\n",
           mode ? "file" : "ignore", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], warnings);
    for (int k = 0; k < 3; k++) {
      CHECK_NEAR(lo[k], want_lo[mode][k], 1e-6);
      CHECK_NEAR(hi[k], want_hi[mode][k], 1e-6);
    }
    CHECK_EQ_INT(warnings, mode ? 0 : 1);
    if (!mode)
      CHECK(strstr(last_warning, "tet_y.dae") && strstr(last_warning, "Y_UP") &&
            strstr(last_warning, "mesh-up-axis") && strstr(last_warning, "mesh_up_axis") &&
            strstr(last_warning, "2 Collada meshes"));
    /* the mesh pieces and the sphere all there; the sphere closed, on its link */
    CHECK_EQ_INT(av->robot->nvisual, 3);
    int fs = -1;
    for (int f = 0; f < av->nface && fs < 0; f++)
      if (av->robot->visual_kind[av->vert_part[av->faces[3 * f]]] == SSA_VISUAL_SPHERE) fs = f;
    CHECK(fs > 0);
    if (fs > 0) {
      shape s = measure(av->rest_pos, av->faces, fs, av->nface, av->nvert);
      CHECK_EQ_INT(s.open_edges, 0);
      CHECK_NEAR(s.volume, 4.0 / 3.0 * PI * 1e-3, 1e-4);
      bbox(av, av->faces[3 * fs], av->nvert, lo, hi);
      CHECK_NEAR(0.5 * (lo[2] + hi[2]), 4.0, 1e-9);
    }
    ssa_avatar_destroy(av);
    av = NULL;
  }
  /* a Z_UP file: no warning; files that are not Collada have no up axis */
  const char *zurdf = put("z.urdf", "<robot name='z'><link name='a'><visual><geometry>"
                                    "<mesh filename='tet_z.dae'/></geometry></visual></link></robot>");
  warnings = 0;
  o.mesh_up_axis = SSA_UP_AXIS_IGNORE;
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, zurdf, NULL, &o, err, sizeof err), SS_OK);
  CHECK_EQ_INT(warnings, 0);
  ssa_avatar_destroy(av);
  char path[512];
  snprintf(path, sizeof path, "%s/tet_z.dae", dir);
  CHECK_EQ_INT(ssa_collada_up_axis(path), 2);
  snprintf(path, sizeof path, "%s/tet_y.dae", dir);
  CHECK_EQ_INT(ssa_collada_up_axis(path), 1);
  CHECK_EQ_INT(ssa_collada_up_axis(urdf), -1);

  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
  return ss_test_finish("test_primitives");
}
