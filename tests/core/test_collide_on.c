/* Contact's scratch (the body's bounding volume tree and winding-number
 * sums) is made only where contact is on: at create, or when
 * ss_sim_set_settings turns `collide` on. A sim created without contact and
 * turned on before its first step gives the bits of one created with it;
 * one turned on after some steps goes on stepping, and contact moves its
 * skin from then on. */
#include <string.h>

#include "sim_internal.h"
#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

#define FRAMES 6

static ss_sim *make(const ss_scene *sc, int collide) {
  ss_sim_settings set = ss_sim_default_settings();
  set.collide = collide;
  set.threads = 1;
  ss_sim *sim = NULL;
  char err[256] = "";
  CHECK_MSG(ss_sim_create(&sim, ss_scene_nvert(sc), ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc),
                          NULL, &set, err, sizeof err) == SS_OK, "%s", err);
  return sim;
}

static void turn_on(ss_sim *sim) {
  ss_sim_settings set = *ss_sim_get_settings(sim);
  set.collide = 1;
  char err[256] = "";
  int recreate = 0;
  CHECK_MSG(ss_sim_set_settings(sim, &set, &recreate, err, sizeof err) == SS_OK, "%s", err);
  CHECK(!recreate);
  CHECK(sim->collider != NULL);
}

/* steps frames [f0, f1) of sc */
static void run(ss_sim *sim, const ss_scene *sc, int f0, int f1) {
  double *pose = malloc(3 * (size_t)ss_scene_nvert(sc) * sizeof(double));
  char err[256] = "";
  for (int f = f0; f < f1; f++) {
    ss_scene_pose(sc, f, pose);
    CHECK_MSG(ss_sim_step(sim, pose, 0.0, NULL, err, sizeof err) == SS_OK, "%s", err);
  }
  free(pose);
}

int main(void) {
  char err[256];
  ss_scene *sc = NULL;
  CHECK_EQ_INT(ss_scene_create(&sc, "quadruped", 2000, err, sizeof err), SS_OK);
  if (!sc) return ss_test_finish("collide_on");
  const size_t n3 = 3 * (size_t)ss_scene_nvert(sc);
  ss_sim *with = make(sc, 1), *later = make(sc, 0), *off = make(sc, 0), *midway = make(sc, 0);
  if (!with || !later || !off || !midway) return ss_test_finish("collide_on");
  CHECK(with->collider != NULL);
  CHECK(later->collider == NULL && off->collider == NULL); /* none without contact */
  turn_on(later);
  run(with, sc, 1, 1 + FRAMES);
  run(later, sc, 1, 1 + FRAMES);
  run(off, sc, 1, 1 + FRAMES);
  CHECK(off->collider == NULL);
  CHECK_MSG(memcmp(ss_sim_skin_positions(with), ss_sim_skin_positions(later), n3 * sizeof(double)) == 0,
            "turned on before the first step: the bits of contact from create");
  /* contact acts on this scene (its skin cuts into the body), so it is seen */
  CHECK(memcmp(ss_sim_skin_positions(with), ss_sim_skin_positions(off), n3 * sizeof(double)) != 0);
  run(midway, sc, 1, 1 + FRAMES / 2);
  turn_on(midway);
  run(midway, sc, 1 + FRAMES / 2, 1 + FRAMES);
  CHECK(memcmp(ss_sim_skin_positions(midway), ss_sim_skin_positions(off), n3 * sizeof(double)) != 0);
  ss_sim_destroy(with), ss_sim_destroy(later), ss_sim_destroy(off), ss_sim_destroy(midway);
  ss_scene_destroy(sc);
  return ss_test_finish("collide_on");
}
