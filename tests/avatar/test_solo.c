/* The Solo quadruped's URDF (Gepetto/example-robot-data, in ../shared/data)
 * with package:// meshes: resolved by an explicit NAME=DIR entry and by a
 * search root, its visual meshes become a rigid-link body, posed with joint
 * values by name; each vertex follows its link exactly. Skips (77) when the
 * shared data is absent. */
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

int main(void) {
  char root[1024], pkg[1100], urdf[1200], pp[2400], err[1024] = "";
  snprintf(root, sizeof root, "%s/data/urdf-solo-quadruped", SS_SHARED_DIR);
  snprintf(pkg, sizeof pkg, "%s/example-robot-data", root);
  snprintf(urdf, sizeof urdf, "%s/robots/solo_description/robots/solo.urdf", pkg);
  struct stat st;
  if (stat(urdf, &st) != 0) {
    printf("test_solo: skipped: %s is not present\n", urdf);
    return SS_TEST_SKIP;
  }
  /* without a package path the meshes do not resolve: a clear error */
  ssa_avatar_opts o = ssa_avatar_default_opts();
  ssa_avatar *av = NULL;
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, urdf, NULL, &o, err, sizeof err), SS_E_IO);
  CHECK(av == NULL);
  CHECK_MSG(strstr(err, "example-robot-data") && strstr(err, "solo.urdf"), "%s", err);
  printf("without a package path: %s\n", err);

  /* a search root: the folder named example-robot-data is found under it */
  o.package_path = root;
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, urdf, NULL, &o, err, sizeof err), SS_OK);
  CHECK_MSG(av != NULL, "%s", err);
  ssa_avatar_destroy(av);
  av = NULL;

  /* an explicit NAME=DIR entry (after a root that has no such package) */
  snprintf(pp, sizeof pp, "/nonexistent:example-robot-data=%s", pkg);
  o.package_path = pp;
  double times[7];
  for (int k = 0; k < 7; k++) {
    ssa_avatar_destroy(av);
    av = NULL;
    double t0 = ss_test_now_s();
    CHECK_EQ_INT(ssa_avatar_load_urdf(&av, urdf, NULL, &o, err, sizeof err), SS_OK);
    times[k] = ss_test_now_s() - t0;
  }
  if (!av) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  const ssa_robot *r = av->robot;
  CHECK_EQ_INT(av->kind, SSA_AVATAR_ROBOT);
  CHECK_EQ_INT(av->weight_source, SSA_WEIGHTS_RIGID);
  CHECK_EQ_INT(r->nvisual, 13); /* body, 4 upper legs, 4 lower legs, 4 feet */
  /* faces per MANIFEST: body 16410, feet 4 x 3384, upper 4 x 3114, lower 4 x 1740 */
  CHECK_EQ_INT(av->nface, 16410 + 4 * 3384 + 4 * 3114 + 4 * 1740);
  for (int v = 0; v < av->nvert; v++) CHECK(av->w_start[v + 1] - av->w_start[v] == 1);

  /* rest pose reproduced exactly by q = 0 */
  double *pos = malloc(sizeof(double) * 3 * (size_t)av->nvert);
  CHECK_EQ_INT(ssa_avatar_pose_joints(av, NULL, pos), SS_OK);
  CHECK(memcmp(pos, av->rest_pos, sizeof(double) * 3 * (size_t)av->nvert) == 0);

  /* pose by joint names, as in sensor_msgs/JointState */
  const char *names[8] = {"FL_HFE", "FL_KFE", "FR_HFE", "FR_KFE",
                          "HL_HFE", "HL_KFE", "HR_HFE", "HR_KFE"};
  const double vals[8] = {0.8, -1.6, -0.8, 1.6, 0.5, -1.0, -0.5, 1.0};
  double *q = calloc((size_t)r->njoint, sizeof(double));
  CHECK_EQ_INT(ssa_robot_set_joints(r, q, 8, names, vals, err, sizeof err), SS_OK);
  double ptimes[21];
  for (int k = 0; k < 21; k++) {
    double t0 = ss_test_now_s();
    CHECK_EQ_INT(ssa_avatar_pose_joints(av, q, pos), SS_OK);
    ptimes[k] = ss_test_now_s() - t0;
  }
  /* each vertex = link pose x link-at-rest^-1 x rest position (rigid links) */
  double *lw = malloc(sizeof(double) * 16 * (size_t)r->nlink);
  double *l0 = malloc(sizeof(double) * 16 * (size_t)r->nlink);
  ssa_robot_fk(r, q, lw);
  ssa_robot_fk(r, NULL, l0);
  double maxerr = 0, maxmove = 0;
  int nfinite = 0;
  for (int v = 0; v < av->nvert; v++) {
    int l = av->vert_link[v];
    const double *A = l0 + 16 * l, *B = lw + 16 * l, *p = av->rest_pos + 3 * v;
    /* local = A^T (p - tA) (A rigid), world = B local */
    double d[3] = {p[0] - A[3], p[1] - A[7], p[2] - A[11]}, loc[3];
    for (int i = 0; i < 3; i++) loc[i] = A[i] * d[0] + A[4 + i] * d[1] + A[8 + i] * d[2];
    for (int i = 0; i < 3; i++) {
      double w = B[4 * i] * loc[0] + B[4 * i + 1] * loc[1] + B[4 * i + 2] * loc[2] + B[4 * i + 3];
      double e = fabs(w - pos[3 * v + i]);
      if (e > maxerr) maxerr = e;
      double mv = fabs(pos[3 * v + i] - p[i]);
      if (mv > maxmove) maxmove = mv;
      nfinite += isfinite(pos[3 * v + i]) != 0;
    }
  }
  CHECK_EQ_INT(nfinite, 3 * av->nvert);
  CHECK_MSG(maxerr < 1e-12, "max error %g", maxerr);
  CHECK(maxmove > 0.1);
  /* the feet are rigid on FL_FOOT etc.: a foot's vertices end below the body when legs bend */
  int foot = ssa_robot_link_index(r, "FL_FOOT");
  CHECK(foot >= 0);
  qsort(times, 7, sizeof(double), ss_test_cmp_double);
  qsort(ptimes, 21, sizeof(double), ss_test_cmp_double);
  printf("solo: %d links, %d joints, %d visuals, %d vertices, %d triangles; load median %.1f ms, "
         "pose median %.3f ms\n",
         r->nlink, r->njoint, r->nvisual, av->nvert, av->nface, 1e3 * times[3], 1e3 * ptimes[10]);
  free(q);
  free(lw);
  free(l0);
  free(pos);
  ssa_avatar_destroy(av);
  return ss_test_finish("test_solo");
}
