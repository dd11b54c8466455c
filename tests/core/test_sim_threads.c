/* Threads and vector widths change the speed, never the bits: the same run
 * with 1, 2 and 3 threads and with 0 (the default: all cores on a big enough
 * skin, checked on one of 4000+ faces) gives identical skin positions and
 * anchors, for walk and project (per-face energies and anchor moves are
 * computed independently, then summed in a fixed order); so does the run
 * with its kernels in each vector instruction set the CPU has (isa.h). */
#include <stdio.h>
#include <string.h>

#include "isa.h"
#include "sim_internal.h"
#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

/* isa -1: the sim's own choice (the widest). */
static void run_isa(const ss_scene *sc, int method, int threads, int isa, double *x, double *uv) {
  ss_sim_settings set = ss_sim_default_settings();
  set.mover.method = method;
  set.threads = threads;
  ss_sim *sim = NULL;
  char err[256] = "";
  int nv = ss_scene_nvert(sc);
  CHECK_MSG(ss_sim_create(&sim, nv, ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc), NULL,
                          &set, err, sizeof err) == SS_OK, "%s", err);
  if (!sim) return;
  if (isa >= 0) ss_sim_set_isa(sim, isa);
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  for (int f = 1; f <= 12; f++) {
    ss_scene_pose(sc, f, pose);
    CHECK(ss_sim_step(sim, pose, 0.0, NULL, err, sizeof err) == SS_OK);
  }
  memcpy(x, ss_sim_skin_positions(sim), 3 * (size_t)nv * sizeof(double));
  memcpy(uv, ss_sim_anchor_uv(sim), 2 * (size_t)ss_sim_nanchors(sim) * sizeof(double));
  free(pose);
  ss_sim_destroy(sim);
}

static void run(const ss_scene *sc, int method, int threads, double *x, double *uv) {
  run_isa(sc, method, threads, -1, x, uv);
}

int main(void) {
  char err[256];
  ss_scene *sc = NULL;
  CHECK_EQ_INT(ss_scene_create(&sc, "twist", 4200, err, sizeof err), SS_OK);
  if (!sc) return ss_test_finish("test_sim_threads");
  size_t nx = 3 * (size_t)ss_scene_nvert(sc), nuv = 2 * ((size_t)ss_scene_nvert(sc) + ss_scene_nface(sc));
  for (int method = SS_METHOD_WALK; method <= SS_METHOD_PROJECT; method++) {
    double *x1 = calloc(nx, sizeof(double)), *uv1 = calloc(nuv, sizeof(double));
    double *xt = calloc(nx, sizeof(double)), *uvt = calloc(nuv, sizeof(double));
    run(sc, method, 1, x1, uv1);
    CHECK(ss_scene_nface(sc) >= 4000); /* threads 0 means more than one here */
    for (int threads = 0; threads <= 3; threads++) {
      if (threads == 1) continue;
      run(sc, method, threads, xt, uvt);
      CHECK_MSG(memcmp(x1, xt, nx * sizeof(double)) == 0, "%s: %d threads moved the skin",
                ss_method_name(method), threads);
      CHECK_MSG(memcmp(uv1, uvt, nuv * sizeof(double)) == 0, "%s: %d threads moved the anchors",
                ss_method_name(method), threads);
    }
    for (int isa = 0; isa < SS_ISA_COUNT; isa++) {
      if (!ss_isa_supported(isa)) {
        printf("test_sim_threads: kernels in %s not run (not on this CPU)\n", ss_isa_name(isa));
        continue;
      }
      for (int threads = 1; threads <= 2; threads++) {
        run_isa(sc, method, threads, isa, xt, uvt);
        CHECK_MSG(memcmp(x1, xt, nx * sizeof(double)) == 0, "%s: kernels in %s at %d threads moved the skin",
                  ss_method_name(method), ss_isa_name(isa), threads);
        CHECK_MSG(memcmp(uv1, uvt, nuv * sizeof(double)) == 0,
                  "%s: kernels in %s at %d threads moved the anchors", ss_method_name(method),
                  ss_isa_name(isa), threads);
      }
    }
    free(x1), free(uv1), free(xt), free(uvt);
  }
  /* the default is 0; a thread count out of range is refused */
  ss_sim_settings set = ss_sim_default_settings();
  CHECK_EQ_INT(set.threads, 0);
  set.threads = -1;
  ss_sim *sim = NULL;
  CHECK_EQ_INT(ss_sim_create(&sim, ss_scene_nvert(sc), ss_scene_rest(sc), ss_scene_nface(sc),
                             ss_scene_faces(sc), NULL, &set, err, sizeof err),
               SS_E_ARG);
  CHECK(sim == NULL && strstr(err, "threads") != NULL);
  ss_scene_destroy(sc);
  return ss_test_finish("test_sim_threads");
}
