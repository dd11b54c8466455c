/* The contact pass (collide.c) gives the same bits on any number of
 * threads: on a quadruped big enough that every part of it runs on the
 * threads (the refit's subtrees, the descents and searches per vertex, the
 * clean-surface tests per face), the skin and the anchors after some frames
 * with 2 and 3 threads are those with 1, and contact moved the skin. */
#include <string.h>

#include "sim_internal.h"
#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

#define FRAMES 8

/* The skin positions and anchors after FRAMES frames of sc, contact on or
 * off, on threads threads. */
static void run(const ss_scene *sc, int collide, int threads, double *x, double *uv) {
  ss_sim_settings set = ss_sim_default_settings();
  set.collide = collide;
  set.threads = threads;
  ss_sim *sim = NULL;
  char err[256] = "";
  const int nv = ss_scene_nvert(sc);
  CHECK_MSG(ss_sim_create(&sim, nv, ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc), NULL, &set,
                          err, sizeof err) == SS_OK, "%s", err);
  if (!sim) return;
  CHECK(sim->m->ndof > 1024); /* the pass's per-vertex loops on the threads (collide.c) */
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  for (int f = 1; f <= FRAMES && pose; f++) {
    ss_scene_pose(sc, f, pose);
    CHECK_MSG(ss_sim_step(sim, pose, 0.0, NULL, err, sizeof err) == SS_OK, "%s", err);
  }
  memcpy(x, ss_sim_skin_positions(sim), 3 * (size_t)nv * sizeof(double));
  memcpy(uv, ss_sim_anchor_uv(sim), 2 * (size_t)ss_sim_nanchors(sim) * sizeof(double));
  free(pose);
  ss_sim_destroy(sim);
}

int main(void) {
  char err[256];
  ss_scene *sc = NULL;
  CHECK_EQ_INT(ss_scene_create(&sc, "quadruped", 2400, err, sizeof err), SS_OK);
  if (!sc) return ss_test_finish("test_collide_threads");
  const size_t nx = 3 * (size_t)ss_scene_nvert(sc);
  const size_t nuv = 2 * ((size_t)ss_scene_nvert(sc) + ss_scene_nface(sc));
  double *x1 = calloc(nx, sizeof(double)), *uv1 = calloc(nuv, sizeof(double));
  double *xt = calloc(nx, sizeof(double)), *uvt = calloc(nuv, sizeof(double));
  if (!x1 || !uv1 || !xt || !uvt) return ss_test_finish("test_collide_threads");
  run(sc, 1, 1, x1, uv1);
  for (int threads = 2; threads <= 3; threads++) {
    run(sc, 1, threads, xt, uvt);
    CHECK_MSG(memcmp(x1, xt, nx * sizeof(double)) == 0, "%d threads moved the skin", threads);
    CHECK_MSG(memcmp(uv1, uvt, nuv * sizeof(double)) == 0, "%d threads moved the anchors", threads);
  }
  /* contact acts on this scene (its skin cuts into the body) */
  run(sc, 0, 2, xt, uvt);
  CHECK(memcmp(x1, xt, nx * sizeof(double)) != 0);
  free(x1), free(uv1), free(xt), free(uvt);
  ss_scene_destroy(sc);
  return ss_test_finish("test_collide_threads");
}
