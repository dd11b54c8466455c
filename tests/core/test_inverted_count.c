/* The inverted-face count of a run (ss_run_stats.inverted_faces_max, issue 11
 * point 5) sees turn-overs and only them:
 *  - the paper's skin (orient 0) on `elbow` turns faces over at the inner
 *    elbow: the count is not 0 (16 at 1000 triangles, 18 more over body folds);
 *  - on `slivers` with a tether the skin's needle faces stand at any angle to
 *    the body without having turned over (before SS_SLIVER_AREA the count said
 *    68 at 1000 triangles, 235 at 3000): slivers are not judged, and the count is 0;
 *  - where the pose folds the body over (elbow's inner crease passes through
 *    itself: body faces turned against neighbours they agreed with at rest)
 *    the body has no one "out": skin faces over such a fold are counted apart
 *    (inverted_over_folds_max) beside the folded body faces (body_folds_max);
 *    a capsule that only twists (`twist`) has none, and neither has the
 *    `boundary` sheet, whose rim faces have no neighbour;
 *  - the default skin (orient term on, 2976 triangles, the scene's own size,
 *    with a 3 s settle) turns no face over on `elbow` (point 5: 0 at the
 *    defaults). Before the orient term's normal leaned on the faces under a
 *    skin face's corners where the body under its barycenter is crushed
 *    (orient.c, normal_under) one face bridging the inner crease stood past
 *    90 degrees to the crushed triangle under it and was counted here. */
#include <stdio.h>

#include "ss_run.h"
#include "ss_scene.h"
#include "ss_test.h"

static ss_run_stats run_sized(const char *name, int tris, double orient, double tether,
                             double settle) {
  char err[256] = "";
  ss_run_stats st = {0};
  ss_scene *scene = NULL;
  if (ss_scene_create(&scene, name, tris, err, sizeof err) != SS_OK) {
    CHECK_MSG(0, "%s: %s", name, err);
    st.inverted_faces_max = -1;
    return st;
  }
  ss_run_settings s = ss_run_default_settings();
  s.sim.orient = orient;
  s.sim.tether = tether;
  s.settle = settle;
  int status = ss_run_scene(scene, &s, NULL, NULL, NULL, NULL, &st, err, sizeof err);
  CHECK_MSG(status == SS_OK, "%s: %s", name, err);
  CHECK(st.failures == 0 && st.snags == 0);
  printf("test_inverted_count: %s %d triangles orient %g tether %g settle %g: inverted faces max "
         "%d, over folds %d, body faces folded %d\n",
         name, st.triangles, orient, tether, settle, st.inverted_faces_max,
         st.inverted_over_folds_max, st.body_folds_max);
  ss_scene_destroy(scene);
  if (status != SS_OK) st.inverted_faces_max = -1;
  return st;
}

static ss_run_stats run(const char *name, double orient, double tether) {
  return run_sized(name, 1000, orient, tether, 0.0);
}

int main(void) {
  const double orient = ss_sim_default_settings().orient;
  ss_run_stats elbow = run("elbow", 0.0, 0.0);
  CHECK(elbow.inverted_faces_max > 0);
  CHECK(elbow.body_folds_max > 0);
  CHECK(elbow.inverted_over_folds_max > 0);
  CHECK_EQ_INT(run("slivers", orient, 3.0).inverted_faces_max, 0);
  ss_run_stats twist = run("twist", orient, 3.0);
  CHECK_EQ_INT(twist.body_folds_max, 0);
  CHECK_EQ_INT(twist.inverted_over_folds_max, 0);
  CHECK_EQ_INT(run("boundary", orient, 3.0).body_folds_max, 0);
  const ss_sim_settings def = ss_sim_default_settings();
  ss_run_stats own = run_sized("elbow", 0, def.orient, def.tether, 3.0);
  CHECK_EQ_INT(own.inverted_faces_max, 0);
  CHECK(own.body_folds_max > 0); /* the crease is there to be crossed */
  return ss_test_finish("test_inverted_count");
}
