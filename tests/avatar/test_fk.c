/* Forward kinematics against hand-computed poses: a chain with a revolute,
 * a prismatic, a continuous and a fixed joint (origins with rotations), a
 * mimic joint, limits that clamp, joint values by name. */
#include <string.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

static const char *chain_urdf =
    "<?xml version='1.0'?>\n"
    "<robot name='chain'>\n"
    "  <link name='base'/><link name='l1'/><link name='l2'/><link name='l3'/><link name='l4'/>\n"
    "  <link name='m1'/>\n"
    "  <joint name='j1' type='revolute'><parent link='base'/><child link='l1'/>\n"
    "    <origin xyz='1 0 0'/><axis xyz='0 0 1'/>\n"
    "    <limit lower='-1' upper='1' effort='1' velocity='1'/></joint>\n"
    "  <joint name='j2' type='prismatic'><parent link='l1'/><child link='l2'/>\n"
    "    <origin xyz='0 1 0' rpy='0 0 1.5707963267948966'/><axis xyz='2 0 0'/>\n"
    "    <limit lower='0' upper='0.5' effort='1' velocity='1'/></joint>\n"
    "  <joint name='j3' type='continuous'><parent link='l2'/><child link='l3'/>\n"
    "    <origin xyz='0 0 1'/><axis xyz='0 1 0'/></joint>\n"
    "  <joint name='j4' type='fixed'><parent link='l3'/><child link='l4'/>\n"
    "    <origin xyz='1 0 0'/></joint>\n"
    "  <joint name='j5' type='revolute'><parent link='base'/><child link='m1'/>\n"
    "    <axis xyz='1 0 0'/><limit lower='-0.5' upper='0.5' effort='1' velocity='1'/>\n"
    "    <mimic joint='j1' multiplier='2' offset='0.1'/></joint>\n"
    "</robot>\n";

static const double *pose_of(const ssa_robot *r, const double *lw, const char *link) {
  int l = ssa_robot_link_index(r, link);
  CHECK(l >= 0);
  return lw + 16 * (l < 0 ? 0 : l);
}

/* the translation column and the rotation entries against expected values */
static void check_pose(const double *m, const double *t, const double *R) {
  CHECK_NEAR(m[3], t[0], 1e-12);
  CHECK_NEAR(m[7], t[1], 1e-12);
  CHECK_NEAR(m[11], t[2], 1e-12);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) CHECK_NEAR(m[4 * i + j], R[3 * i + j], 1e-12);
  CHECK(m[12] == 0 && m[13] == 0 && m[14] == 0 && m[15] == 1);
}

static void rz(double a, double *R) {
  double c = cos(a), s = sin(a);
  double m[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  memcpy(R, m, sizeof m);
}

static void mul3(const double *A, const double *B, double *C) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

int main(void) {
  char err[512] = "";
  ssa_robot *r = NULL;
  CHECK_EQ_INT(ssa_robot_load_string(&r, chain_urdf, NULL, NULL, err, sizeof err), SS_OK);
  if (!r) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  CHECK_EQ_INT(r->nlink, 6);
  CHECK_EQ_INT(r->njoint, 5);
  CHECK_EQ_INT(r->root_link, ssa_robot_link_index(r, "base"));
  /* parents come before children in link_order */
  for (int i = 0; i < r->nlink; i++) {
    int l = r->link_order[i], p = r->link_parent[l];
    int pi = -1;
    for (int k = 0; k < r->nlink; k++)
      if (r->link_order[k] == p) pi = k;
    CHECK(p < 0 || pi < i);
  }
  int j1 = ssa_robot_joint_index(r, "j1"), j2 = ssa_robot_joint_index(r, "j2");
  int j3 = ssa_robot_joint_index(r, "j3"), j5 = ssa_robot_joint_index(r, "j5");
  CHECK_EQ_INT(r->joint_type[j1], SSA_JOINT_REVOLUTE);
  CHECK_EQ_INT(r->joint_type[j2], SSA_JOINT_PRISMATIC);
  CHECK_EQ_INT(r->joint_type[j3], SSA_JOINT_CONTINUOUS);
  CHECK_EQ_INT(r->joint_type[ssa_robot_joint_index(r, "j4")], SSA_JOINT_FIXED);
  CHECK_EQ_INT(r->joint_mimic[j5], j1);
  CHECK_NEAR(r->joint_axis[3 * j2], 1.0, 0); /* normalised */

  double q[5] = {0}, lw[6 * 16];
  const char *names[3] = {"j1", "j2", "j3"};
  const double vals[3] = {0.3, 0.2, 0.4};
  CHECK_EQ_INT(ssa_robot_set_joints(r, q, 3, names, vals, err, sizeof err), SS_OK);
  ssa_robot_fk(r, q, lw);
  double R1[9], Ra[9], Ry[9], R3[9], t[3];
  double a = 0.3 + 1.5707963267948966;
  rz(0.3, R1);
  check_pose(pose_of(r, lw, "l1"), (double[]){1, 0, 0}, R1);
  rz(a, Ra);
  t[0] = 1 - 1.2 * sin(0.3);
  t[1] = 1.2 * cos(0.3);
  t[2] = 0;
  check_pose(pose_of(r, lw, "l2"), t, Ra);
  double c4 = cos(0.4), s4 = sin(0.4);
  double ry[9] = {c4, 0, s4, 0, 1, 0, -s4, 0, c4};
  memcpy(Ry, ry, sizeof ry);
  mul3(Ra, Ry, R3);
  t[2] = 1;
  check_pose(pose_of(r, lw, "l3"), t, R3);
  double t4[3] = {t[0] + c4 * cos(a), t[1] + c4 * sin(a), 1 - s4};
  check_pose(pose_of(r, lw, "l4"), t4, R3);
  /* mimic: 2 * 0.3 + 0.1 = 0.7, clamped to its own upper limit 0.5 */
  CHECK_NEAR(ssa_robot_joint_value(r, q, j5), 0.5, 0);
  double c5 = cos(0.5), s5 = sin(0.5);
  check_pose(pose_of(r, lw, "m1"), (double[]){0, 0, 0}, (double[]){1, 0, 0, 0, c5, -s5, 0, s5, c5});
  /* a mimic inside its limits: q1 = 0.1 -> 0.3 */
  q[j1] = 0.1;
  ssa_robot_fk(r, q, lw);
  c5 = cos(0.3), s5 = sin(0.3);
  check_pose(pose_of(r, lw, "m1"), (double[]){0, 0, 0}, (double[]){1, 0, 0, 0, c5, -s5, 0, s5, c5});
  /* a value given for a mimic joint is ignored */
  q[j5] = 123.0;
  CHECK_NEAR(ssa_robot_joint_value(r, q, j5), 0.3, 1e-15);

  /* limits clamp: revolute and prismatic; continuous does not */
  q[j1] = 2.0;
  q[j2] = -1.0;
  q[j3] = 10.0;
  CHECK_NEAR(ssa_robot_joint_value(r, q, j1), 1.0, 0);
  CHECK_NEAR(ssa_robot_joint_value(r, q, j2), 0.0, 0);
  CHECK_NEAR(ssa_robot_joint_value(r, q, j3), 10.0, 0);
  q[j2] = 0.9;
  CHECK_NEAR(ssa_robot_joint_value(r, q, j2), 0.5, 0);
  ssa_robot_fk(r, q, lw);
  rz(1.0, R1);
  check_pose(pose_of(r, lw, "l1"), (double[]){1, 0, 0}, R1);
  const double *l2 = pose_of(r, lw, "l2");
  CHECK_NEAR(l2[3], 1 - 1.5 * sin(1.0), 1e-12);
  CHECK_NEAR(l2[7], 1.5 * cos(1.0), 1e-12);

  /* NULL q is the zero pose */
  ssa_robot_fk(r, NULL, lw);
  check_pose(pose_of(r, lw, "l1"), (double[]){1, 0, 0}, (double[]){1, 0, 0, 0, 1, 0, 0, 0, 1});

  /* unknown joint names and non-finite values are refused with a message */
  const char *bad[1] = {"elbow"};
  err[0] = '\0';
  CHECK_EQ_INT(ssa_robot_set_joints(r, q, 1, bad, vals, err, sizeof err), SS_E_ARG);
  CHECK(strstr(err, "elbow") != NULL);
  double nanv = NAN;
  CHECK_EQ_INT(ssa_robot_set_joints(r, q, 1, names, &nanv, err, sizeof err), SS_E_NONFINITE);
  /* ssa_joints_toward (the settle's way back to rest): linear per joint, a
   * continuous joint the short way round: from 6.0 rad to 0 it goes forward
   * through 2 pi (6.0 + 0.5 (2 pi - 6.0) half way), a revolute one back */
  {
    double from[5] = {0}, to[5] = {0}, out[5];
    from[j1] = 1.0, from[j2] = 0.4, from[j3] = 6.0;
    ssa_joints_toward(r, from, to, 0.5, out);
    CHECK_NEAR(out[j1], 0.5, 1e-15);
    CHECK_NEAR(out[j2], 0.2, 1e-15);
    CHECK_NEAR(out[j3], 6.0 + 0.5 * (2.0 * 3.14159265358979323846 - 6.0), 1e-12);
    ssa_joints_toward(r, from, to, 0.0, out);
    CHECK(out[j1] == 1.0 && out[j2] == 0.4 && out[j3] == 6.0);
    ssa_joints_toward(r, from, from, 0.7, from); /* in place */
    CHECK(from[j1] == 1.0 && from[j3] == 6.0);
  }

  ssa_robot_destroy(r);
  ssa_robot_destroy(NULL);
  return ss_test_finish("test_fk");
}
