/* A URDF skeleton driving a rigged body mesh from a file (RiggedSimple.glb,
 * ../shared/data): the file's bones bind to the links of the same name, or
 * to the nearest ancestor node that is a link; when no bone matches, weights
 * are computed. The rest pose is reproduced and a joint rotation moves the
 * vertices bound to its child link rigidly. Skips (77) without the data. */
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

static char dir[] = "/tmp/ssa_um_XXXXXX";

static const char *write_urdf(const char *name, const char *text) {
  static char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
  return path;
}

static void check_partition(const ssa_avatar *av) {
  for (int v = 0; v < av->nvert; v++) {
    double s = 0;
    for (int k = av->w_start[v]; k < av->w_start[v + 1]; k++) s += av->w_weight[k];
    CHECK_NEAR(s, 1.0, 1e-12);
  }
}

static void check_rest(ssa_avatar *av) {
  double *pos = malloc(sizeof(double) * 3 * (size_t)av->nvert);
  CHECK_EQ_INT(ssa_avatar_pose_joints(av, NULL, pos), SS_OK);
  double e = 0;
  for (int i = 0; i < 3 * av->nvert; i++) e = fmax(e, fabs(pos[i] - av->rest_pos[i]));
  CHECK_MSG(e < 1e-12, "rest pose error %g", e);
  free(pos);
}

int main(void) {
  char mesh[1024], err[1024] = "", urdf[2048];
  snprintf(mesh, sizeof mesh, "%s/data/gltf-khronos-skinned/RiggedSimple/glTF-Binary/RiggedSimple.glb",
           SS_SHARED_DIR);
  struct stat st;
  if (stat(mesh, &st) != 0) {
    printf("test_urdf_mesh: skipped: %s is not present\n", mesh);
    return SS_TEST_SKIP;
  }
  if (!mkdtemp(dir)) return 1;
  /* where the file's bones are at rest, to build a URDF that matches them */
  ssa_asset *a = NULL;
  CHECK_EQ_INT(ssa_asset_load(&a, mesh, NULL, err, sizeof err), SS_OK);
  if (!a) return 1;
  int b0 = ssa_asset_node_index(a, "Bone"), b1 = ssa_asset_node_index(a, "Bone.001");
  CHECK(b0 >= 0 && b1 >= 0);
  double *nw = malloc(sizeof(double) * 16 * (size_t)a->nnode);
  ssa_asset_node_world(a, -1, 0.0, nw);
  double jx = nw[16 * b1 + 3] - nw[16 * b0 + 3], jy = nw[16 * b1 + 7] - nw[16 * b0 + 7],
         jz = nw[16 * b1 + 11] - nw[16 * b0 + 11];
  double root[3] = {nw[16 * b0 + 3], nw[16 * b0 + 7], nw[16 * b0 + 11]};
  free(nw);
  ssa_asset_destroy(a);

  /* 1. names match: the file's weights, rest reproduced, rigid part rotates about the joint */
  snprintf(urdf, sizeof urdf,
           "<robot name='bendy'><link name='world'/><link name='Bone'/><link name='Bone.001'/>"
           "<joint name='mount' type='fixed'><parent link='world'/><child link='Bone'/>"
           "<origin xyz='%.17g %.17g %.17g'/></joint>"
           "<joint name='bend' type='revolute'><parent link='Bone'/><child link='Bone.001'/>"
           "<origin xyz='%.17g %.17g %.17g'/><axis xyz='1 0 0'/>"
           "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint></robot>",
           root[0], root[1], root[2], jx, jy, jz);
  const char *p = write_urdf("bendy.urdf", urdf);
  ssa_avatar *av = NULL;
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, p, mesh, NULL, err, sizeof err), SS_OK);
  if (!av) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  CHECK_EQ_INT(av->weight_source, SSA_WEIGHTS_FILE);
  CHECK_EQ_INT(av->nvert, 160);
  check_partition(av);
  check_rest(av);
  int l1 = ssa_robot_link_index(av->robot, "Bone.001");
  double q[1] = {0.8};
  double *pos = malloc(sizeof(double) * 3 * (size_t)av->nvert);
  CHECK_EQ_INT(ssa_avatar_pose_joints(av, q, pos), SS_OK);
  /* the joint sits where Bone.001 is at rest: a rotation about x through that point */
  double c = cos(0.8), s = sin(0.8);
  int nrigid = 0;
  double jp[3] = {root[0] + jx, root[1] + jy, root[2] + jz};
  for (int v = 0; v < av->nvert; v++) {
    if (!(av->w_start[v + 1] - av->w_start[v] == 1 && av->w_bone[av->w_start[v]] == l1)) continue;
    nrigid++;
    const double *r0 = av->rest_pos + 3 * v;
    double d[3] = {r0[0] - jp[0], r0[1] - jp[1], r0[2] - jp[2]};
    CHECK_NEAR(pos[3 * v], r0[0], 1e-9);
    CHECK_NEAR(pos[3 * v + 1], jp[1] + c * d[1] - s * d[2], 1e-9);
    CHECK_NEAR(pos[3 * v + 2], jp[2] + s * d[1] + c * d[2], 1e-9);
  }
  CHECK_MSG(nrigid > 10, "only %d vertices bound to Bone.001 alone", nrigid);
  ssa_avatar_destroy(av);
  av = NULL;

  /* 2. forced automatic weights on the same pair */
  ssa_avatar_opts o = ssa_avatar_default_opts();
  o.force_auto_weights = 1;
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, p, mesh, &o, err, sizeof err), SS_OK);
  if (av) {
    CHECK_EQ_INT(av->weight_source, SSA_WEIGHTS_AUTO);
    check_partition(av);
    check_rest(av);
    ssa_avatar_destroy(av);
    av = NULL;
  }

  /* 3. only an ancestor node is a link: every bone binds to it, the body is rigid */
  p = write_urdf("armature.urdf", "<robot name='a'><link name='Armature'/></robot>");
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, p, mesh, NULL, err, sizeof err), SS_OK);
  if (av) {
    CHECK_EQ_INT(av->weight_source, SSA_WEIGHTS_FILE);
    for (int v = 0; v < av->nvert; v++) {
      CHECK_EQ_INT(av->w_start[v + 1] - av->w_start[v], 1);
      CHECK_NEAR(av->w_weight[av->w_start[v]], 1.0, 1e-12);
    }
    ssa_avatar_destroy(av);
    av = NULL;
  }

  /* 4. no name matches: automatic weights from the links' segments */
  snprintf(urdf, sizeof urdf,
           "<robot name='other'><link name='upper'/><link name='lower'/>"
           "<joint name='knee' type='revolute'><parent link='upper'/><child link='lower'/>"
           "<origin xyz='%.17g %.17g %.17g'/><axis xyz='1 0 0'/>"
           "<limit lower='-2' upper='2' effort='1' velocity='1'/></joint></robot>",
           jx, jy, jz);
  p = write_urdf("other.urdf", urdf);
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, p, mesh, NULL, err, sizeof err), SS_OK);
  if (av) {
    CHECK_EQ_INT(av->weight_source, SSA_WEIGHTS_AUTO);
    check_partition(av);
    check_rest(av);
    CHECK_EQ_INT(ssa_avatar_pose_joints(av, q, pos), SS_OK);
    for (int i = 0; i < 3 * av->nvert; i++) CHECK(isfinite(pos[i]));
    ssa_avatar_destroy(av);
  }
  /* an asset avatar cannot be posed with joints, nor a robot avatar with an animation */
  CHECK_EQ_INT(ssa_avatar_load_asset(&av, mesh, NULL, err, sizeof err), SS_OK);
  if (av) {
    CHECK_EQ_INT(ssa_avatar_pose_joints(av, q, pos), SS_E_ARG);
    CHECK_EQ_INT(ssa_avatar_pose_anim(av, 5, 0.0, pos), SS_E_ARG);
    CHECK_EQ_INT(ssa_avatar_pose_anim(av, 0, NAN, pos), SS_E_ARG);
    ssa_avatar_destroy(av);
  }
  free(pos);
  ss_test_remove_dir(dir);
  return ss_test_finish("test_urdf_mesh");
}
