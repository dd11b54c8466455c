/* The built-in mannequin: its URDF text equals urdf/mannequin.urdf; its
 * generated body is closed, welded, one piece of genus 0, outward, near the
 * requested triangle count; as an avatar (automatic weights) every built-in
 * motion poses it finitely and really moves it: arms down into the torso,
 * elbows bent, torso twisted; motions round-trip through CSV. */
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "topo.h"
#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

static void check_mesh(int target, int *nface_out) {
  double *pos = NULL;
  int *faces = NULL, nv = 0, nf = 0;
  char err[256] = "";
  double t0 = ss_test_now_s();
  CHECK_EQ_INT(ssa_mannequin_mesh(target, &pos, &nv, &faces, &nf, err, sizeof err), SS_OK);
  double dt = ss_test_now_s() - t0;
  if (!pos) return;
  int req = target > 0 ? target : 5000;
  CHECK_MSG(fabs((double)nf / req - 1.0) < 0.10, "%d triangles for %d requested", nf, req);
  ss_topo *t = NULL;
  CHECK_EQ_INT(ss_topo_create(&t, nv, pos, nf, faces, 0.0, err, sizeof err), SS_OK);
  if (t) {
    CHECK_EQ_INT(t->nboundary_edge, 0);     /* closed */
    CHECK_EQ_INT(t->nnonmanifold_edge, 0);  /* manifold */
    CHECK_EQ_INT(t->ndegenerate_face, 0);
    CHECK_EQ_INT(t->nweld - t->nedge + nf, 2); /* one piece, genus 0 */
    ss_topo_destroy(t);
  }
  /* welded: no two vertices at the same place, even with a relative tolerance */
  CHECK_EQ_INT(ss_topo_create(&t, nv, pos, nf, faces, -1.0, err, sizeof err), SS_OK);
  if (t) CHECK_EQ_INT(t->nweld, nv);
  ss_topo_destroy(t);
  /* outward: positive enclosed volume, about a person's (0.04 to 0.08 m^3) */
  double vol = 0, zmin = 1e9, zmax = -1e9, ymax = -1e9;
  for (int f = 0; f < nf; f++) {
    const double *a = pos + 3 * faces[3 * f], *b = pos + 3 * faces[3 * f + 1],
                 *c = pos + 3 * faces[3 * f + 2];
    vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
            a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  }
  for (int v = 0; v < nv; v++) {
    if (pos[3 * v + 2] < zmin) zmin = pos[3 * v + 2];
    if (pos[3 * v + 2] > zmax) zmax = pos[3 * v + 2];
    if (pos[3 * v + 1] > ymax) ymax = pos[3 * v + 1];
  }
  CHECK_MSG(vol > 0.04 && vol < 0.08, "volume %g", vol);
  /* triangle quality 4 sqrt(3) area / sum of squared edges (1 equilateral) */
  double qmin = 1;
  for (int f = 0; f < nf; f++) {
    const double *a = pos + 3 * faces[3 * f], *b = pos + 3 * faces[3 * f + 1],
                 *c = pos + 3 * faces[3 * f + 2];
    double e1[3], e2[3], e3[3];
    for (int k = 0; k < 3; k++) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], e3[k] = c[k] - b[k];
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    double area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double l2 = 0;
    for (int k = 0; k < 3; k++) l2 += e1[k] * e1[k] + e2[k] * e2[k] + e3[k] * e3[k];
    qmin = fmin(qmin, 4 * sqrt(3.0) * area / l2);
  }
  CHECK_MSG(qmin > 0.2, "worst triangle quality %g", qmin);
  CHECK_MSG(zmax - zmin > 1.6 && zmax - zmin < 1.9, "height %g", zmax - zmin);
  CHECK_MSG(ymax > 0.75 && ymax < 0.9, "half arm span %g", ymax);
  printf("mannequin %5d requested: %5d triangles, %5d vertices, volume %.4f m^3, height %.3f m, "
         "worst triangle quality %.2f, %.0f ms\n", req, nf, nv, vol, zmax - zmin, qmin, 1e3 * dt);
  if (nface_out) *nface_out = nf;
  free(pos);
  free(faces);
}

int main(void) {
  char err[512] = "";
  /* the URDF text is the package's file */
  char path[1024];
  snprintf(path, sizeof path, "%s/urdf/mannequin.urdf", SS_SOURCE_DIR);
  FILE *f = fopen(path, "rb");
  CHECK_MSG(f != NULL, "cannot open %s", path);
  if (f) {
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    CHECK(strcmp(buf, ssa_mannequin_urdf()) == 0);
  }
  check_mesh(0, NULL);
  check_mesh(20000, NULL);
  double *p0 = NULL;
  int *f0 = NULL, nv0, nf0;
  CHECK_EQ_INT(ssa_mannequin_mesh(1000, &p0, &nv0, &f0, &nf0, err, sizeof err), SS_E_ARG);
  CHECK(p0 == NULL && strstr(err, "1000"));

  /* as an avatar */
  ssa_avatar *av = NULL;
  double t0 = ss_test_now_s();
  CHECK_EQ_INT(ssa_avatar_mannequin(&av, 0, err, sizeof err), SS_OK);
  double t_make = ss_test_now_s() - t0;
  if (!av) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  const ssa_robot *r = av->robot;
  CHECK_EQ_INT(av->weight_source, SSA_WEIGHTS_AUTO);
  CHECK_EQ_INT(r->nlink, 12);
  for (int v = 0; v < av->nvert; v++) {
    double s = 0;
    for (int k = av->w_start[v]; k < av->w_start[v + 1]; k++) {
      CHECK(av->w_weight[k] > 0);
      s += av->w_weight[k];
    }
    CHECK_NEAR(s, 1.0, 1e-12);
  }
  /* the hands' vertices belong to the forearms, the head's to the head */
  int lfa = ssa_robot_link_index(r, "l_forearm"), head = ssa_robot_link_index(r, "head");
  int ua = ssa_robot_link_index(r, "l_upper_arm");
  for (int v = 0; v < av->nvert; v++) {
    const double *p = av->rest_pos + 3 * v;
    if (p[1] > 0.65) CHECK_EQ_INT(av->vert_link[v], lfa);
    if (p[2] > 0.72) CHECK_EQ_INT(av->vert_link[v], head);
  }
  /* a region by link names: exactly the vertices those links dominate */
  unsigned char *mask = malloc((size_t)av->nvert);
  const char *region[2] = {"l_forearm", "head"};
  int nmarked = ssa_avatar_region_mask(av, 2, region, mask, err, sizeof err);
  int expect = 0;
  for (int v = 0; v < av->nvert; v++) {
    int in = av->vert_link[v] == lfa || av->vert_link[v] == head;
    expect += in;
    CHECK(mask[v] == in);
  }
  CHECK(nmarked == expect && nmarked > 100);
  const char *bad_region[1] = {"tail"};
  CHECK_EQ_INT(ssa_avatar_region_mask(av, 1, bad_region, mask, err, sizeof err), SS_E_ARG);
  CHECK(strstr(err, "tail") != NULL);
  free(mask);
  double *pos = malloc(sizeof(double) * 3 * (size_t)av->nvert);
  double *q = calloc((size_t)r->njoint, sizeof(double));
  /* deterministic: a second mannequin is the same to the bit */
  ssa_avatar *av2 = NULL;
  CHECK_EQ_INT(ssa_avatar_mannequin(&av2, 0, err, sizeof err), SS_OK);
  if (av2) {
    CHECK(av2->nvert == av->nvert && av2->nface == av->nface);
    CHECK(memcmp(av2->rest_pos, av->rest_pos, sizeof(double) * 3 * (size_t)av->nvert) == 0);
    CHECK(memcmp(av2->faces, av->faces, sizeof(int) * 3 * (size_t)av->nface) == 0);
    CHECK(memcmp(av2->w_start, av->w_start, sizeof(int) * ((size_t)av->nvert + 1)) == 0);
    int nw = av->w_start[av->nvert];
    CHECK(av2->w_start[av->nvert] == nw &&
          memcmp(av2->w_weight, av->w_weight, sizeof(double) * (size_t)nw) == 0 &&
          memcmp(av2->w_bone, av->w_bone, sizeof(int) * (size_t)nw) == 0);
    ssa_avatar_destroy(av2);
  }
  /* a floating base: the whole body moves with the root pose */
  {
    double root[16] = {0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1}; /* quarter turn, shift */
    CHECK_EQ_INT(ssa_avatar_pose_joints_at(av, root, NULL, pos), SS_OK);
    double e = 0;
    for (int v = 0; v < av->nvert; v++) {
      const double *p = av->rest_pos + 3 * v;
      e = fmax(e, fabs(pos[3 * v] - (1 - p[1])));
      e = fmax(e, fabs(pos[3 * v + 1] - (2 + p[0])));
      e = fmax(e, fabs(pos[3 * v + 2] - (3 + p[2])));
    }
    CHECK_MSG(e < 1e-12, "root pose error %g", e);
  }
  /* zero pose reproduces the rest body */
  CHECK_EQ_INT(ssa_avatar_pose_joints(av, NULL, pos), SS_OK);
  double e = 0;
  for (int i = 0; i < 3 * av->nvert; i++) e = fmax(e, fabs(pos[i] - av->rest_pos[i]));
  CHECK_MSG(e < 1e-12, "rest pose error %g", e);

  double ptimes[64];
  int np = 0;
  for (int mi = 0; mi < ssa_motion_builtin_count(); mi++) {
    const char *name = ssa_motion_builtin_name(mi);
    CHECK_EQ_INT(ssa_motion_builtin_index(name), mi);
    double T = ssa_motion_builtin_period(mi), maxmove = 0;
    int nonfinite = 0;
    for (int k = 0; k <= 16; k++) {
      double t = T * k / 16.0;
      CHECK_EQ_INT(ssa_motion_builtin_eval(mi, t, r, q), SS_OK);
      double a = ss_test_now_s();
      ssa_avatar_pose_joints(av, q, pos);
      if (np < 64) ptimes[np++] = ss_test_now_s() - a;
      for (int i = 0; i < 3 * av->nvert; i++) {
        nonfinite += !isfinite(pos[i]);
        maxmove = fmax(maxmove, fabs(pos[i] - av->rest_pos[i]));
      }
    }
    CHECK_EQ_INT(nonfinite, 0);
    CHECK_MSG(maxmove > 0.15, "motion %s moves at most %g m", name, maxmove);
    printf("motion %-7s period %4.1f s: moves vertices up to %.3f m\n", name, T, maxmove);
  }
  /* arms: at the peak (t = 2 s, 1.75 rad) the left upper arm is down at the torso's side,
     pressed into it: its vertices near the shoulder go inside the chest's width */
  ssa_motion_builtin_eval(ssa_motion_builtin_index("arms"), 2.0, r, q);
  ssa_avatar_pose_joints(av, q, pos);
  double lw[16 * 12];
  ssa_robot_fk(r, q, lw);
  CHECK(lw[16 * lfa + 11] < 0.2); /* the elbow is far below the shoulder (z 0.46) */
  int inside = 0;
  for (int v = 0; v < av->nvert; v++)
    if (av->vert_link[v] == ua && pos[3 * v + 1] < 0.17) inside++;
  CHECK_MSG(inside > 0, "no upper-arm vertex pressed into the torso");
  /* elbows: at t = 1.5 s the left elbow is bent 2.5 rad: the wrist comes forward */
  ssa_motion_builtin_eval(ssa_motion_builtin_index("elbows"), 1.5, r, q);
  CHECK_NEAR(q[ssa_robot_joint_index(r, "l_elbow")], 2.5, 1e-12);
  /* twist: at t = 0.75 s the torso has turned 0.8 rad */
  ssa_motion_builtin_eval(ssa_motion_builtin_index("twist"), 0.75, r, q);
  CHECK_NEAR(q[ssa_robot_joint_index(r, "torso_twist")], 0.8, 1e-12);
  CHECK_EQ_INT(ssa_motion_builtin_eval(99, 0.0, r, q), SS_E_ARG);

  /* CSV round trip: written, read back bit for bit, sampled like the function */
  ssa_motion *m = NULL, *m2 = NULL;
  CHECK_EQ_INT(ssa_motion_from_builtin(&m, 3, r, 12.0, 121, err, sizeof err), SS_OK);
  char tmpl[] = "/tmp/ssa_motion_XXXXXX";
  int fd = mkstemp(tmpl);
  CHECK(fd >= 0);
  if (fd >= 0) close(fd);
  CHECK_EQ_INT(ssa_motion_write_csv(m, tmpl, err, sizeof err), SS_OK);
  CHECK_EQ_INT(ssa_motion_read_csv(&m2, tmpl, err, sizeof err), SS_OK);
  if (m && m2) {
    CHECK_EQ_INT(m2->njoint, m->njoint);
    CHECK_EQ_INT(m2->nframe, 121);
    CHECK(memcmp(m->time, m2->time, sizeof(double) * 121) == 0);
    CHECK(memcmp(m->value, m2->value, sizeof(double) * 121 * (size_t)m->njoint) == 0);
    int *map = malloc(sizeof(int) * (size_t)m2->njoint);
    CHECK_EQ_INT(ssa_motion_bind(m2, r, map, err, sizeof err), SS_OK);
    double *q2 = calloc((size_t)r->njoint, sizeof(double));
    ssa_motion_sample(m2, map, 3.0, q2); /* on a frame: exact */
    ssa_motion_builtin_eval(3, 3.0, r, q);
    for (int j = 0; j < r->njoint; j++) CHECK_NEAR(q2[j], q[j], 1e-12);
    ssa_motion_sample(m2, map, 3.05, q2); /* between frames: close */
    ssa_motion_builtin_eval(3, 3.05, r, q);
    for (int j = 0; j < r->njoint; j++) CHECK_NEAR(q2[j], q[j], 0.01);
    ssa_motion_sample(m2, map, 100.0, q2); /* after the end: held */
    ssa_motion_builtin_eval(3, 12.0, r, q);
    for (int j = 0; j < r->njoint; j++) CHECK_NEAR(q2[j], q[j], 1e-9);
    free(map);
    free(q2);
  }
  unlink(tmpl);
  ssa_motion_destroy(m);
  ssa_motion_destroy(m2);
  qsort(ptimes, (size_t)np, sizeof(double), ss_test_cmp_double);
  printf("mannequin avatar: %d vertices, %d triangles, %d links; made (mesh + heat weights) in "
         "%.0f ms; pose median %.3f ms\n",
         av->nvert, av->nface, r->nlink, 1e3 * t_make, 1e3 * ptimes[np / 2]);
  free(pos);
  free(q);
  ssa_avatar_destroy(av);
  return ss_test_finish("test_mannequin");
}
