/* Mesh URIs: package:// through NAME=DIR entries, search roots (a folder
 * named like the package, or one whose package.xml names it), and
 * ROS_PACKAGE_PATH; file:// and names relative to the URDF's folder; and a
 * URDF whose visual (an OBJ written here) is found that way, with its
 * visual origin and scale applied. */
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "skin_sim/ssa_avatar.h"
#include "ss_test.h"

static char dir[] = "/tmp/ssa_res_XXXXXX";

static void mk(const char *rel) {
  char p[512];
  snprintf(p, sizeof p, "%s/%s", dir, rel);
  mkdir(p, 0700);
}

static void put(const char *rel, const char *text) {
  char p[512];
  snprintf(p, sizeof p, "%s/%s", dir, rel);
  FILE *f = fopen(p, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
}

static const char *tri_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

int main(void) {
  if (!mkdtemp(dir)) return 1;
  mk("ws");
  mk("ws/src");
  mk("ws/src/checkout");          /* folder name differs from the package name */
  mk("ws/src/checkout/meshes");
  put("ws/src/checkout/package.xml", "<package><name> robo_parts </name></package>");
  put("ws/src/checkout/meshes/tri.obj", tri_obj);
  mk("ws/src/plain_pkg");         /* folder named like the package, no package.xml */
  mk("ws/src/plain_pkg/m");
  put("ws/src/plain_pkg/m/tri.obj", tri_obj);
  mk("elsewhere");
  put("elsewhere/tri.obj", tri_obj);
  mk("robot");
  put("robot/tri.obj", tri_obj);

  char out[1024], err[1024], pp[2048], expect[1024];
  snprintf(pp, sizeof pp, "%s/ws", dir);
  CHECK_EQ_INT(ssa_resolve_uri("package://robo_parts/meshes/tri.obj", NULL, pp, out, sizeof out,
                               err, sizeof err), SS_OK);
  snprintf(expect, sizeof expect, "%s/ws/src/checkout/meshes/tri.obj", dir);
  CHECK_MSG(strcmp(out, expect) == 0, "%s", out);
  CHECK_EQ_INT(ssa_resolve_uri("package://plain_pkg/m/tri.obj", NULL, pp, out, sizeof out, err,
                               sizeof err), SS_OK);
  /* NAME=DIR wins over a root that also has the package */
  snprintf(pp, sizeof pp, "%s/ws:plain_pkg=%s/elsewhere", dir, dir);
  CHECK_EQ_INT(ssa_resolve_uri("package://plain_pkg/tri.obj", NULL, pp, out, sizeof out, err,
                               sizeof err), SS_OK);
  snprintf(expect, sizeof expect, "%s/elsewhere/tri.obj", dir);
  CHECK_MSG(strcmp(out, expect) == 0, "%s", out);
  /* ROS_PACKAGE_PATH */
  snprintf(pp, sizeof pp, "/nonexistent:%s/ws/src", dir);
  setenv("ROS_PACKAGE_PATH", pp, 1);
  CHECK_EQ_INT(ssa_resolve_uri("package://robo_parts/meshes/tri.obj", NULL, NULL, out, sizeof out,
                               err, sizeof err), SS_OK);
  unsetenv("ROS_PACKAGE_PATH");
  CHECK_EQ_INT(ssa_resolve_uri("package://robo_parts/meshes/tri.obj", NULL, NULL, out, sizeof out,
                               err, sizeof err), SS_E_IO);
  CHECK(strstr(err, "robo_parts") != NULL);
  /* a package found but the file missing */
  snprintf(pp, sizeof pp, "%s/ws", dir);
  CHECK_EQ_INT(ssa_resolve_uri("package://robo_parts/meshes/none.obj", NULL, pp, out, sizeof out,
                               err, sizeof err), SS_E_IO);
  CHECK(strstr(err, "none.obj") != NULL);
  /* file:// and relative */
  snprintf(expect, sizeof expect, "file://%s/elsewhere/tri.obj", dir);
  CHECK_EQ_INT(ssa_resolve_uri(expect, NULL, NULL, out, sizeof out, err, sizeof err), SS_OK);
  snprintf(expect, sizeof expect, "%s/robot", dir);
  CHECK_EQ_INT(ssa_resolve_uri("tri.obj", expect, NULL, out, sizeof out, err, sizeof err), SS_OK);

  /* a URDF with three visuals found three ways; origin and scale applied */
  put("robot/r.urdf",
      "<robot name='r'><link name='a'>"
      "<visual><origin xyz='0 0 1'/><geometry><mesh filename='tri.obj' scale='2 2 2'/></geometry></visual>"
      "<visual><geometry><mesh filename='package://robo_parts/meshes/tri.obj'/></geometry></visual>"
      "<visual><geometry><box size='1 1 1'/></geometry></visual></link>"
      "<link name='b'><visual><origin xyz='0 0 0' rpy='0 0 1.5707963267948966'/>"
      "<geometry><mesh filename='package://plain_pkg/m/tri.obj'/></geometry></visual></link>"
      "<joint name='slide' type='prismatic'><parent link='a'/><child link='b'/>"
      "<origin xyz='5 0 0'/><axis xyz='0 0 1'/>"
      "<limit lower='0' upper='1' effort='1' velocity='1'/></joint></robot>");
  char urdf[600];
  snprintf(urdf, sizeof urdf, "%s/robot/r.urdf", dir);
  ssa_avatar_opts o = ssa_avatar_default_opts();
  o.package_path = pp;
  o.primitive_edge = 0.5; /* the unit box: 2 x 2 cells a face, 26 vertices, 48 triangles */
  ssa_avatar *av = NULL;
  CHECK_EQ_INT(ssa_avatar_load_urdf(&av, urdf, NULL, &o, err, sizeof err), SS_OK);
  if (av) {
    CHECK_EQ_INT(av->robot->nvisual, 4);
    CHECK_EQ_INT(av->nface, 3 + 48); /* the box is tessellated (visual 2, after two meshes) */
    CHECK_EQ_INT(av->nvert, 9 + 26);
    for (int w = 6; w < 6 + 26; w++) {
      CHECK_EQ_INT(av->vert_part[w], 2);
      for (int k = 0; k < 3; k++) CHECK(fabs(fabs(av->rest_pos[3 * w + k]) - 0.5) < 1e-12 ||
                                        fabs(av->rest_pos[3 * w + k]) < 1e-12);
    }
    /* visual 0: scaled by 2, lifted by 1 */
    CHECK_NEAR(av->rest_pos[3 * 1 + 0], 2.0, 1e-12);
    CHECK_NEAR(av->rest_pos[3 * 1 + 2], 1.0, 1e-12);
    /* visual of link b: turned a quarter about z, at x = 5: (1,0,0) -> (5,1,0) */
    int v = 7 + 26;
    CHECK_EQ_INT(av->vert_link[v], ssa_robot_link_index(av->robot, "b"));
    CHECK_NEAR(av->rest_pos[3 * v + 0], 5.0, 1e-12);
    CHECK_NEAR(av->rest_pos[3 * v + 1], 1.0, 1e-12);
    double q[1] = {0.5}, pos[3 * (9 + 26)];
    CHECK_EQ_INT(ssa_avatar_pose_joints(av, q, pos), SS_OK);
    CHECK_NEAR(pos[3 * v + 2], 0.5, 1e-12);
    CHECK_NEAR(pos[3 * 1 + 2], 1.0, 1e-12);
    ssa_avatar_destroy(av);
  } else {
    fprintf(stderr, "%s\n", err);
  }
  ss_test_remove_dir(dir);
  return ss_test_finish("test_resolve");
}
