/* The paper's claim, reproduced on the built-in scenes at their default sizes:
 * the walk never snags or fails, while "projection springs" snag where the
 * body folds onto itself (armpit, thin fold, the quadruped's legs in its
 * belly). */
#include "ss_track.h"
#include "ss_test.h"

/* Runs the experiment on scene `name` at about `tris` triangles (0: default). */
static ss_track_stats run_tris(const char *name, int method, int tris) {
  ss_track_stats st = {0};
  ss_scene *scene = NULL;
  char err[256] = "";
  int status = ss_scene_create(&scene, name, tris, err, sizeof err);
  CHECK_MSG(status == SS_OK, "%s: %s", name, err);
  if (status) return st;
  ss_track_settings s = ss_track_default_settings();
  s.mover.method = method;
  status = ss_track_run(scene, &s, NULL, NULL, &st, err, sizeof err);
  CHECK_MSG(status == SS_OK, "%s: %s", name, err);
  printf("%-9s %-8s tris %6d anchors %6d frames %4d snags %6lld failures %lld boundary %lld "
         "crease %lld steplimit %lld steps %.2f\n",
         name, ss_method_name(method), st.triangles, st.anchors, st.frames, st.snags, st.failures,
         st.anchors_at_boundary, st.anchors_at_crease, st.anchors_at_step_limit, st.mean_steps);
  ss_scene_destroy(scene);
  return st;
}

static ss_track_stats run(const char *name, int method) { return run_tris(name, method, 0); }

int main(void) {
  /* the walk: no snag and no failure on the scenes where projection breaks */
  const char *hard[] = {"armpit", "fold", "twist"};
  for (int i = 0; i < 3; i++) {
    ss_track_stats w = run(hard[i], SS_METHOD_WALK);
    CHECK(w.frames > 0 && w.updates == (long long)w.frames * w.anchors);
    CHECK_EQ_INT(w.snags, 0);
    CHECK_EQ_INT(w.failures, 0);
    CHECK_EQ_INT(w.anchors_at_step_limit, 0);
  }
  /* twist is there to make anchors cross many faces per frame */
  ss_track_stats tw = run("twist", SS_METHOD_WALK);
  CHECK_MSG(tw.mean_steps > 2.0, "twist: mean walk steps %.2f", tw.mean_steps);

  /* projection springs: the paper's failure, reproduced */
  const char *snaggy[] = {"armpit", "fold"};
  for (int i = 0; i < 2; i++) {
    ss_track_stats p = run(snaggy[i], SS_METHOD_PROJECT);
    CHECK_MSG(p.snags > 0, "%s: project should snag", snaggy[i]);
    CHECK_EQ_INT(p.failures, 0);
  }

  /* the other scenes: the walk stays sound everywhere */
  const char *rest[] = {"elbow", "slivers", "boundary"};
  for (int i = 0; i < 3; i++) {
    ss_track_stats w = run(rest[i], SS_METHOD_WALK);
    CHECK_EQ_INT(w.failures, 0);
    CHECK_EQ_INT(w.snags, 0);
  }
  /* the raccoon-scale gallop (~19k triangles): the walk holds; projection
   * (run smaller, it is slow) snags where the legs cross the belly */
  ss_track_stats q = run("quadruped", SS_METHOD_WALK);
  CHECK(q.triangles >= 17000 && q.updates == (long long)q.frames * q.anchors);
  CHECK_EQ_INT(q.snags, 0);
  CHECK_EQ_INT(q.failures, 0);
  CHECK_EQ_INT(q.anchors_at_step_limit, 0);
  ss_track_stats qp = run_tris("quadruped", SS_METHOD_PROJECT, 3000);
  CHECK_MSG(qp.snags > 0, "quadruped: project should snag");
  CHECK_EQ_INT(qp.failures, 0);

  ss_track_stats b = run("boundary", SS_METHOD_WALK);
  CHECK_MSG(b.anchors_at_boundary > 0, "boundary: anchors should reach the border");

  /* bad settings are refused with a message */
  ss_scene *scene = NULL;
  char err[256] = "";
  CHECK(ss_scene_create(&scene, "fold", 0, err, sizeof err) == SS_OK);
  ss_track_settings s = ss_track_default_settings();
  ss_track_stats st;
  s.lift = -1;
  err[0] = 0;
  CHECK_EQ_INT(ss_track_run(scene, &s, NULL, NULL, &st, err, sizeof err), SS_E_ARG);
  CHECK(err[0] != 0);
  s = ss_track_default_settings();
  s.mover.method = 7;
  err[0] = 0;
  CHECK_EQ_INT(ss_track_run(scene, &s, NULL, NULL, &st, err, sizeof err), SS_E_ARG);
  CHECK(err[0] != 0);
  ss_scene_destroy(scene);
  return ss_test_finish("test_track");
}
