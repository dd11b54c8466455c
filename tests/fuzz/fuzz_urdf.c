/* libFuzzer harness: URDF text through the avatar layer (ssa_robot_load_string:
 * urdfdom's parser, then our joints, mimics and links), then joint values set
 * by name and forward kinematics. Asserts that a load either succeeds with a
 * robot or fails with a message, and that FK of finite joint values within a
 * finite robot is never NaN. */
#include <assert.h>

#include "fuzz_util.h"
#include "skin_sim/ssa_avatar.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* assimp and urdfdom keep some memory for the process (their own caches):
 * leaks inside them are theirs, not ours. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) {
  return "leak:libassimp.so\nleak:liburdfdom\nleak:libtinyxml\nleak:libconsole_bridge\n";
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 65536) return 0;
  char *xml = malloc(size + 1);
  memcpy(xml, data, size);
  xml[size] = '\0';
  ssa_robot *r = NULL;
  char err[256] = "";
  int st = ssa_robot_load_string(&r, xml, "/nonexistent", "", err, sizeof err);
  if (st != SS_OK) {
    assert(r == NULL && err[0] != '\0');
    free(xml);
    return 0;
  }
  assert(r != NULL);
  int nq = r->njoint, nl = r->nlink;
  double *q = calloc((size_t)nq + 1, sizeof(double));
  double *world = malloc(16 * ((size_t)nl + 1) * sizeof(double));
  const char *names[2] = {"a", nl > 0 ? r->link_name[0] : "b"};
  double vals[2] = {0.5, -0.25};
  (void)ssa_robot_set_joints(r, q, 2, names, vals, err, sizeof err);
  ssa_robot_fk(r, q, world);
  (void)ssa_robot_link_index(r, names[1]);
  (void)ssa_robot_joint_index(r, "a");
  free(world);
  free(q);
  free(xml);
  ssa_robot_destroy(r);
  return 0;
}
