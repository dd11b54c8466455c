/* Bad input never crashes: each case returns an error code and one sentence
 * naming the file and the problem. Files are written by the test into a
 * temporary folder. Run it under AddressSanitizer and UBSan too. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

static char dir[] = "/tmp/ssa_bad_XXXXXX";

static const char *put(const char *name, const void *data, size_t n) {
  static char paths[16][256];
  static int k = 0;
  char *p = paths[k++ % 16];
  snprintf(p, 256, "%s/%s", dir, name);
  FILE *f = fopen(p, "wb");
  if (f) {
    fwrite(data, 1, n, f);
    fclose(f);
  }
  return p;
}

static const char *put_text(const char *name, const char *text) {
  return put(name, text, strlen(text));
}

/* status as expected, the message non-empty and containing each of the needles */
#define EXPECT(call, status, ...)                                                        \
  do {                                                                                   \
    char err_[1024] = "";                                                                \
    int st_ = (call);                                                                    \
    (void)err_;                                                                          \
    CHECK_MSG(st_ == (status), "%s returned %d (%s), expected %d", #call, st_, err, status); \
    const char *needles_[] = {__VA_ARGS__, NULL};                                        \
    for (int i_ = 0; needles_[i_]; i_++)                                                 \
      CHECK_MSG(strstr(err, needles_[i_]) != NULL, "'%s' not in: %s", needles_[i_], err); \
    CHECK(strchr(err, '\n') == NULL);                                                    \
    printf("%-28s -> %s\n", ss_status_string(st_), err);                                 \
    err[0] = '\0';                                                                       \
  } while (0)

static const char *robot_with_mesh =
    "<robot name='r'><link name='a'><visual><geometry><mesh filename='%s'/></geometry>"
    "</visual></link></robot>";

int main(void) {
  if (!mkdtemp(dir)) return 1;
  char err[1024] = "", buf[2048];
  ssa_robot *r = NULL;
  ssa_avatar *av = NULL;
  ssa_asset *as = NULL;
  ssa_motion *mo = NULL;

  /* URDF: missing file, not XML, XML but not a robot, joint to an unknown link, bad mimic */
  EXPECT(ssa_robot_load(&r, "/nonexistent/robot.urdf", NULL, err, sizeof err), SS_E_IO,
         "/nonexistent/robot.urdf", "cannot be opened");
  /* SSA_MAX_LINKS links load (a chain, a box on each link: the boxes' vertices share
   * their x, which made the weld quadratic); one more is refused, the bound named */
  for (int extra = 0; extra <= 1; extra++) {
    const int nl = SSA_MAX_LINKS + extra;
    size_t cap = 240 * (size_t)(nl + 2), len = 0;
    char *big = malloc(cap);
    len += (size_t)snprintf(big + len, cap - len, "<robot name='many'>");
    for (int i = 0; i < nl; i++)
      len += (size_t)snprintf(big + len, cap - len, "<link name='l%d'><visual><geometry><box "
                              "size='0.01 0.01 0.01'/></geometry></visual></link>", i);
    for (int i = 1; i < nl; i++)
      len += (size_t)snprintf(big + len, cap - len,
                              "<joint name='j%d' type='fixed'><parent link='l%d'/>"
                              "<child link='l%d'/><origin xyz='0 0 0.01'/></joint>", i, i - 1, i);
    snprintf(big + len, cap - len, "</robot>");
    const char *mp = put_text("many.urdf", big);
    if (extra) {
      EXPECT(ssa_avatar_load_urdf(&av, mp, NULL, NULL, err, sizeof err), SS_E_ARG,
             "many.urdf", "10001 links", "over the bound of 10000");
    } else {
      CHECK_MSG(ssa_avatar_load_urdf(&av, mp, NULL, NULL, err, sizeof err) == SS_OK, "%s", err);
      CHECK(av && av->robot && av->robot->nlink == SSA_MAX_LINKS && av->nface >= 12 * nl);
      ssa_avatar_destroy(av);
      av = NULL;
    }
    free(big);
  }
  const char *p = put_text("garbage.urdf", "this is <not xml");
  EXPECT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_E_IO, "garbage.urdf", "not a valid URDF");
  p = put_text("norobot.urdf", "<?xml version='1.0'?><world name='w'/>");
  EXPECT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_E_IO, "norobot.urdf");
  p = put_text("badjoint.urdf",
               "<robot name='r'><link name='a'/><joint name='j' type='revolute'><parent link='a'/>"
               "<child link='ghost'/><limit lower='0' upper='1' effort='1' velocity='1'/>"
               "</joint></robot>");
  EXPECT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_E_IO, "badjoint.urdf");
  p = put_text("badmimic.urdf",
               "<robot name='r'><link name='a'/><link name='b'/><joint name='j' type='continuous'>"
               "<parent link='a'/><child link='b'/><mimic joint='nobody'/></joint></robot>");
  EXPECT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_E_ARG, "badmimic.urdf", "nobody");
  p = put_text("badtype.urdf",
               "<robot name='r'><link name='a'/><link name='b'/><joint name='j' type='wobbly'>"
               "<parent link='a'/><child link='b'/></joint></robot>");
  EXPECT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_E_IO, "badtype.urdf");
  CHECK(r == NULL);
  EXPECT(ssa_robot_load_string(&r, "", NULL, NULL, err, sizeof err), SS_E_IO, "URDF text");

  /* meshes: missing, unknown format, no triangles, NaN, empty */
  EXPECT(ssa_asset_load(&as, "/nonexistent/body.dae", NULL, err, sizeof err), SS_E_IO,
         "/nonexistent/body.dae");
  p = put("junk.stl", "garbage\x01\x02", 9);
  EXPECT(ssa_asset_load(&as, p, NULL, err, sizeof err), SS_E_IO, "junk.stl");
  p = put_text("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n");
  CHECK(ssa_asset_load(&as, p, NULL, err, sizeof err) < 0 && strstr(err, "lines.obj"));
  printf("%-28s -> %s\n", "(no triangles)", err);
  unsigned char stl[80 + 4 + 50];
  memset(stl, 'x', 80);
  unsigned n1 = 1;
  memcpy(stl + 80, &n1, 4);
  float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, NAN, 1, 0};
  memcpy(stl + 84, tri, sizeof tri);
  memset(stl + 84 + 48, 0, 2);
  p = put("nan.stl", stl, sizeof stl);
  EXPECT(ssa_asset_load(&as, p, NULL, err, sizeof err), SS_E_NONFINITE, "nan.stl", "not finite");
  n1 = 0;
  memcpy(stl + 80, &n1, 4);
  p = put("empty.stl", stl, 84);
  CHECK(ssa_asset_load(&as, p, NULL, err, sizeof err) < 0 && strstr(err, "empty.stl"));
  CHECK(as == NULL);

  /* a URDF whose visual mesh is missing, or whose package cannot be resolved */
  snprintf(buf, sizeof buf, robot_with_mesh, "file:///nonexistent/part.stl");
  p = put_text("missingmesh.urdf", buf);
  EXPECT(ssa_avatar_load_urdf(&av, p, NULL, NULL, err, sizeof err), SS_E_IO, "missingmesh.urdf",
         "/nonexistent/part.stl");
  snprintf(buf, sizeof buf, robot_with_mesh, "package://no_such_pkg/meshes/part.stl");
  p = put_text("nopkg.urdf", buf);
  EXPECT(ssa_avatar_load_urdf(&av, p, NULL, NULL, err, sizeof err), SS_E_IO, "nopkg.urdf",
         "no_such_pkg", "cannot be resolved");
  snprintf(buf, sizeof buf, robot_with_mesh, "http://example.com/part.stl");
  p = put_text("http.urdf", buf);
  EXPECT(ssa_avatar_load_urdf(&av, p, NULL, NULL, err, sizeof err), SS_E_IO, "http.urdf",
         "unsupported scheme");
  /* a URDF whose visual is a NaN mesh */
  p = put("nanpart.stl", stl, sizeof stl);
  n1 = 1;
  memcpy(stl + 80, &n1, 4);
  p = put("nanpart.stl", stl, sizeof stl);
  snprintf(buf, sizeof buf, robot_with_mesh, "nanpart.stl"); /* relative to the URDF */
  p = put_text("nanpart.urdf", buf);
  EXPECT(ssa_avatar_load_urdf(&av, p, NULL, NULL, err, sizeof err), SS_E_NONFINITE,
         "nanpart.urdf", "nanpart.stl");
  /* a URDF without any visual mesh, as a body */
  p = put_text("novisual.urdf", "<robot name='r'><link name='a'/></robot>");
  EXPECT(ssa_avatar_load_urdf(&av, p, NULL, NULL, err, sizeof err), SS_E_MESH, "novisual.urdf");
  /* a body mesh that is missing */
  EXPECT(ssa_avatar_load_urdf(&av, p, "/nonexistent/body.glb", NULL, err, sizeof err), SS_E_IO,
         "/nonexistent/body.glb");
  CHECK(av == NULL);

  /* a body given as arrays: NaN, no triangles, an index out of range */
  CHECK_EQ_INT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_OK);
  double pos[9] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
  int tri3[3] = {0, 1, 2};
  EXPECT(ssa_avatar_from_robot_mesh(&av, r, 3, pos, 1, tri3, NULL, err, sizeof err),
         SS_E_NONFINITE, "body mesh");
  CHECK_EQ_INT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_OK);
  pos[7] = 1;
  EXPECT(ssa_avatar_from_robot_mesh(&av, r, 3, pos, 0, tri3, NULL, err, sizeof err), SS_E_MESH,
         "body mesh");
  CHECK_EQ_INT(ssa_robot_load(&r, p, NULL, err, sizeof err), SS_OK);
  tri3[2] = 7;
  EXPECT(ssa_avatar_from_robot_mesh(&av, r, 3, pos, 1, tri3, NULL, err, sizeof err), SS_E_MESH,
         "body mesh");

  /* unknown joint names, in values and in a motion */
  CHECK_EQ_INT(ssa_robot_load_string(&r, ssa_mannequin_urdf(), NULL, NULL, err, sizeof err), SS_OK);
  double q[32] = {0};
  const char *names[2] = {"l_elbow", "l_wrist"};
  double vals[2] = {1, 1};
  EXPECT(ssa_robot_set_joints(r, q, 2, names, vals, err, sizeof err), SS_E_ARG, "l_wrist",
         "mannequin");
  p = put_text("unknown.csv", "time,l_elbow,tail_wag\n0,0,0\n1,1,1\n");
  CHECK_EQ_INT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_OK);
  int map[2];
  EXPECT(ssa_motion_bind(mo, r, map, err, sizeof err), SS_E_ARG, "tail_wag");
  ssa_motion_destroy(mo);
  mo = NULL;

  /* joint values outside the URDF limits: counted, one sentence naming the worst joint
   * and its limits (l_elbow [0, 2.6]); values in degrees are called so */
  double ql[32] = {0};
  int je = ssa_robot_joint_index(r, "l_elbow"), js = ssa_robot_joint_index(r, "l_shoulder_abduct");
  CHECK_EQ_INT(ssa_robot_check_limits(r, ql, err, sizeof err), 0);
  ql[je] = 2.6;
  CHECK_EQ_INT(ssa_robot_check_limits(r, ql, err, sizeof err), 0); /* on the limit is inside */
  ql[je] = 90.0;
  ql[js] = 2.0;
  CHECK_EQ_INT(ssa_robot_check_limits(r, ql, err, sizeof err), 2);
  CHECK(strstr(err, "'l_elbow'") && strstr(err, "[0, 2.6] rad") && strstr(err, "degrees?"));
  printf("%-28s -> %s\n", "limits (q)", err);
  ql[je] = 0;
  CHECK_EQ_INT(ssa_robot_check_limits(r, ql, err, sizeof err), 1);
  CHECK(strstr(err, "'l_shoulder_abduct'") && strstr(err, "[-0.6, 1.8]") && !strstr(err, "degrees"));
  p = put_text("degrees.csv", "time,l_elbow,r_elbow,neck_twist\n0,0,0,0\n1,90,45,0.5\n2,143,2,0\n");
  CHECK_EQ_INT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_OK);
  int map3[3];
  CHECK_EQ_INT(ssa_motion_bind(mo, r, map3, err, sizeof err), SS_OK);
  CHECK_EQ_INT(ssa_motion_check_limits(mo, map3, r, err, sizeof err), 3);
  CHECK(strstr(err, "3 values (of 2 joints) are outside") && strstr(err, "'l_elbow'") && strstr(err, "143") &&
        strstr(err, "[0, 2.6]") && strstr(err, "degrees?") && strstr(err, "t = 2 s"));
  printf("%-28s -> %s\n", "limits (motion)", err);
  ssa_motion_destroy(mo);
  mo = NULL;
  /* the built-in motions move the mannequin, not a robot without its joints */
  for (int i = 0; i < ssa_motion_builtin_count(); i++) CHECK(ssa_motion_builtin_coverage(i, r) > 0);
  ssa_robot_destroy(r);
  r = NULL;
  CHECK_EQ_INT(ssa_robot_load_string(&r, "<robot name='arm'><link name='a'/><link name='b'/>"
                                         "<joint name='j1' type='continuous'><parent link='a'/>"
                                         "<child link='b'/></joint></robot>",
                                     NULL, NULL, err, sizeof err), SS_OK);
  /* the mannequin's motions move none of its joints; sweep moves any robot's (its one) */
  const int sweep = ssa_motion_builtin_index("sweep");
  CHECK(sweep >= 0);
  for (int i = 0; i < ssa_motion_builtin_count(); i++)
    CHECK_EQ_INT(ssa_motion_builtin_coverage(i, r), i == sweep ? 1 : 0);
  ssa_robot_destroy(r);
  r = NULL;

  /* CSV motions: wrong column counts, not numbers, time not increasing, empty */
  p = put_text("short.csv", "time,a,b\n0,1,2\n1,1\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "short.csv", "line 3",
         "2 columns where the header has 3");
  p = put_text("long.csv", "# a comment\ntime,a\n0,1\n\n1,2,3\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "long.csv", "line 5");
  p = put_text("word.csv", "time,a\n0,one\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "word.csv", "'one'");
  p = put_text("nan.csv", "time,a\n0,nan\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "nan.csv");
  p = put_text("back.csv", "time,a\n0,0\n1,0\n0.5,0\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "back.csv", "does not increase");
  p = put_text("header.csv", "time\n0\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "header.csv");
  p = put_text("norows.csv", "time,a\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "norows.csv", "no rows");
  p = put_text("emptyname.csv", "time,,b\n0,1,2\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "emptyname.csv", "column 2");
  EXPECT(ssa_motion_read_csv(&mo, "/nonexistent/m.csv", err, sizeof err), SS_E_IO,
         "/nonexistent/m.csv");
  CHECK(mo == NULL);
  /* the first column must be time: a file that starts with a joint is refused */
  p = put_text("notime.csv", "l_elbow,r_elbow\n0,0\n1,1\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "notime.csv", "line 1",
         "first column must be 'time'", "'l_elbow'");
  p = put_text("notime2.csv", "# motion\nt,a\n0,0\n");
  EXPECT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_E_ARG, "notime2.csv", "line 2", "'t'");
  /* a CSV with spaces, CRLF and a capitalised Time is fine */
  p = put_text("ok.csv", "Time , a\r\n 0 , 1.5 \r\n2,2.5\r\n");
  CHECK_EQ_INT(ssa_motion_read_csv(&mo, p, err, sizeof err), SS_OK);
  if (mo) {
    CHECK(mo->njoint == 1 && mo->nframe == 2 && strcmp(mo->joint_name[0], "a") == 0);
    CHECK(mo->value[1] == 2.5);
  }
  ssa_motion_destroy(mo);

  /* NULL everywhere does not crash */
  CHECK(ssa_robot_load(NULL, NULL, NULL, NULL, 0) == SS_E_ARG);
  CHECK(ssa_asset_load(&as, NULL, NULL, NULL, 0) == SS_E_ARG);
  CHECK(ssa_avatar_pose_joints(NULL, NULL, NULL) == SS_E_ARG);
  CHECK(ssa_avatar_pose_anim(NULL, 0, 0, NULL) == SS_E_ARG);
  CHECK(ssa_motion_read_csv(NULL, "x", NULL, 0) == SS_E_ARG);
  ssa_robot_fk(NULL, NULL, NULL);
  ssa_avatar_destroy(NULL);
  ssa_asset_destroy(NULL);
  ssa_motion_destroy(NULL);

  ss_test_remove_dir(dir);
  return ss_test_finish("test_bad_input");
}
