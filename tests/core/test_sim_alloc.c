/* Stepping allocates nothing: the quasi-Newton solver (the default) with
 * every anchor method, bending and substeps on, counted by interposing
 * malloc/calloc/realloc (glibc only; skipped under the sanitizers, which
 * interpose malloc themselves). Exempt, as CHOLMOD allocates temporaries
 * inside cholmod_factorize: a step with a new time step (the quasi-Newton
 * matrix is refactored), and the Newton solver (a factorisation per
 * iteration, and the threaded BLAS under its supernodal factor). */
#include <stddef.h>
#include <string.h>

#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

#if defined(__SANITIZE_ADDRESS__) || !defined(__GLIBC__)
#define SS_ALLOC_TEST_SKIP 1
#endif
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SS_ALLOC_TEST_SKIP 1
#endif
#endif

#ifndef SS_ALLOC_TEST_SKIP
extern void *__libc_malloc(size_t n);
extern void *__libc_calloc(size_t n, size_t size);
extern void *__libc_realloc(void *p, size_t n);
static int counting = 0;
static long allocations = 0;
void *malloc(size_t n) {
  allocations += counting;
  return __libc_malloc(n);
}
void *calloc(size_t n, size_t size) {
  allocations += counting;
  return __libc_calloc(n, size);
}
void *realloc(void *p, size_t n) {
  allocations += counting;
  return __libc_realloc(p, n);
}
#endif

int main(void) {
#ifdef SS_ALLOC_TEST_SKIP
  printf("test_sim_alloc: skipped (malloc is interposed by the sanitizer)\n");
  return SS_TEST_SKIP;
#else
  char err[256];
  ss_scene *sc = NULL;
  CHECK_EQ_INT(ss_scene_create(&sc, "twist", 800, err, sizeof err), SS_OK);
  if (!sc) return ss_test_finish("test_sim_alloc");
  /* threads 0 on a skin of 4000+ faces: all cores, probing one thread
   * against them (steps 1-3 all, 4-6 one, then the faster) */
  ss_scene *big = NULL;
  CHECK_EQ_INT(ss_scene_create(&big, "twist", 4200, err, sizeof err), SS_OK);
  if (!big) return ss_test_finish("test_sim_alloc");
  double *pose = malloc(3 * (size_t)ss_scene_nvert(big) * sizeof(double));
  for (int run = 0; run < 5; run++) {
    /* every method on one thread, and the walk on two and on threads 0 */
    const int method = run < 3 ? run : SS_METHOD_WALK;
    ss_sim_settings set = ss_sim_default_settings();
    set.mover.method = method;
    set.threads = run < 3 ? 1 : run == 3 ? 2 : 0;
    const ss_scene *sc_run = run == 4 ? big : sc;
    const int nv = ss_scene_nvert(sc_run);
    set.bending = 1e-3;
    set.substeps = 2;
    set.damping = 1.0;
    set.collide = 1; /* its pass, tree searches and winding tests too */
    ss_sim *sim = NULL;
    CHECK_EQ_INT(ss_sim_create(&sim, nv, ss_scene_rest(sc_run), ss_scene_nface(sc_run), ss_scene_faces(sc_run), NULL,
                               &set, err, sizeof err),
                 SS_OK);
    if (!sim) continue;
    allocations = 0;
    int iterations = 0;
    for (int f = 1; f <= 10; f++) {
      ss_scene_pose(sc_run, f, pose);
      ss_sim_stats st;
      counting = 1;
      ss_sim_step(sim, pose, 0.0, &st, NULL, 0);
      counting = 0;
      iterations += st.iterations;
    }
    CHECK(iterations > 0);
    CHECK_MSG(allocations == 0, "method %s, %d threads: %ld allocations while stepping",
              ss_method_name(method), set.threads, allocations);
    ss_sim_destroy(sim);
  }
  free(pose);
  ss_scene_destroy(sc);
  ss_scene_destroy(big);
  return ss_test_finish("test_sim_alloc");
#endif
}
