/* Reference runs and the error metric (ss_reference.h): the reference
 * settings (idempotent; the run's slide rate kept), keys (change with what
 * determines the result, not with what does not), the error of a skin
 * against a reference (0 for itself, the RMS distance over edge length for a
 * shifted skin, ~0 at rest for a coarser skin lying on the reference), and a
 * cache file written and read back. No files outside a temporary folder. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ss_reference.h"
#include "ss_scene.h"
#include "ss_test.h"

static void test_settings(void) {
  ss_run_settings run = ss_run_default_settings();
  ss_run_settings ref = ss_reference_settings(&run);
  CHECK(ref.sim.solver == SS_SOLVER_NEWTON);
  CHECK(ref.sim.substeps == SS_REFERENCE_SUBSTEPS);
  CHECK(ref.sim.iterations == SS_REFERENCE_ITERATIONS);
  CHECK(ref.sim.tol == SS_REFERENCE_TOL);
  /* slide is a rate per second: the reference has the run's own */
  CHECK(ref.sim.slide == run.sim.slide);
  ss_run_settings again = ss_reference_settings(&ref);
  CHECK(again.sim.slide == ref.sim.slide); /* idempotent, bit for bit */
  CHECK(again.sim.substeps == ref.sim.substeps);
  run.sim.substeps = 32; /* more than the reference's: kept, slide kept */
  ref = ss_reference_settings(&run);
  CHECK(ref.sim.substeps == 32 && ref.sim.slide == run.sim.slide);
  run.sim.tol = 1e-9; /* tighter than the reference's: kept (and idempotent) */
  ref = ss_reference_settings(&run);
  CHECK(ref.sim.tol == 1e-9 && ss_reference_settings(&ref).sim.tol == 1e-9);
  run.sim.tol = 1e-2; /* looser: the reference's own */
  CHECK(ss_reference_settings(&run).sim.tol == SS_REFERENCE_TOL);
  run.sim.tol = 0.0; /* 0 means "never converged": the reference's own */
  CHECK(ss_reference_settings(&run).sim.tol == SS_REFERENCE_TOL);
}

static void test_keys(const ss_body *body) {
  ss_run_settings a = ss_run_default_settings();
  a.frames = 4;
  unsigned long long k0 = 0, k = 0;
  CHECK(ss_reference_key(body, &a, &k0, NULL, 0) == SS_OK);
  ss_run_settings b = a;
  b.sim.iterations = 3; /* the run's solver does not change its reference */
  b.sim.solver = SS_SOLVER_NEWTON;
  CHECK(ss_reference_key(body, &b, &k, NULL, 0) == SS_OK && k == k0);
  b = a;
  b.sim.substeps = 2; /* the same slide rate: the same reference */
  CHECK(ss_reference_key(body, &b, &k, NULL, 0) == SS_OK && k == k0);
  b = a;
  b.sim.young *= 2.0;
  CHECK(ss_reference_key(body, &b, &k, NULL, 0) == SS_OK && k != k0);
  b = a;
  b.sim.mover.method = SS_METHOD_PROJECT;
  CHECK(ss_reference_key(body, &b, &k, NULL, 0) == SS_OK && k != k0);
  b = a;
  b.frames = 5;
  CHECK(ss_reference_key(body, &b, &k, NULL, 0) == SS_OK && k != k0);
}

static void test_error_and_cache(const ss_body *body) {
  char dir[] = "/tmp/ss_test_reference_XXXXXX";
  CHECK(mkdtemp(dir) != NULL);
  ss_run_settings s = ss_run_default_settings();
  s.frames = 3;
  char err[256] = "";
  ss_reference *ref = NULL;
  int status = ss_reference_get(&ref, body, &s, dir, NULL, NULL, err, sizeof err);
  CHECK_MSG(status == SS_OK, "%s", err);
  if (status) return;
  CHECK(!ref->cache_hit && !ref->cache_rejected && ref->frames == 3);
  ss_reference *again = NULL;
  CHECK(ss_reference_get(&again, body, &s, dir, NULL, NULL, err, sizeof err) == SS_OK);
  CHECK(again && again->cache_hit && again->nvert == ref->nvert &&
        memcmp(again->pos, ref->pos, sizeof(double) * 3 * (size_t)ref->nvert * 3) == 0);
  ss_reference_destroy(again);

  const size_t n3 = 3 * (size_t)ref->nvert;
  /* the reference against itself: 0 */
  ss_ref_error *e = NULL;
  CHECK(ss_ref_error_create(&e, ref, ref->nvert, ref->rest, err, sizeof err) == SS_OK);
  for (int f = 1; f <= 3; f++) ss_ref_error_add(e, f, ref->pos + n3 * (size_t)(f - 1));
  CHECK(ss_ref_error_value(e) == 0.0);
  /* shifted by half an edge length along x in every frame: 0.5 */
  double *shift = malloc(sizeof(double) * n3);
  for (int f = 1; f <= 3 && shift; f++) {
    memcpy(shift, ref->pos + n3 * (size_t)(f - 1), sizeof(double) * n3);
    for (int v = 0; v < ref->nvert; v++) shift[3 * v] += 0.5 * ref->mean_edge_length;
    ss_ref_error_add(e, f, shift);
  }
  /* mean of 0 (three frames) and 0.25 (three frames) squared edges: sqrt(0.125) */
  CHECK_NEAR(ss_ref_error_value(e), sqrt(0.125), 1e-9);
  ss_ref_error_destroy(e);
  /* a skin of its own made of the reference's face barycenters: bound through
   * closest points, so at the reference positions its error is ~0 */
  double *bary = malloc(sizeof(double) * 3 * (size_t)ref->nface);
  double *bpos = malloc(sizeof(double) * 3 * (size_t)ref->nface);
  CHECK(bary && bpos);
  if (bary && bpos) {
    for (int t = 0; t < ref->nface; t++)
      for (int i = 0; i < 3; i++) {
        bary[3 * t + i] = 0.0;
        for (int c = 0; c < 3; c++) bary[3 * t + i] += ref->rest[3 * ref->faces[3 * t + c] + i] / 3.0;
      }
    CHECK(ss_ref_error_create(&e, ref, ref->nface, bary, err, sizeof err) == SS_OK);
    for (int f = 1; f <= 3; f++) {
      const double *r = ref->pos + n3 * (size_t)(f - 1);
      for (int t = 0; t < ref->nface; t++)
        for (int i = 0; i < 3; i++) {
          bpos[3 * t + i] = 0.0;
          for (int c = 0; c < 3; c++) bpos[3 * t + i] += r[3 * ref->faces[3 * t + c] + i] / 3.0;
        }
      ss_ref_error_add(e, f, bpos);
    }
    CHECK_MSG(ss_ref_error_value(e) < 1e-9, "barycenter skin error %g", ss_ref_error_value(e));
    ss_ref_error_destroy(e);
  }
  free(bary);
  free(bpos);
  free(shift);

  /* a corrupted file is rejected and recomputed to the same positions */
  char path[512];
  snprintf(path, sizeof path, "%s/ref_%016llx.bin", dir, ref->key);
  FILE *f = fopen(path, "r+b");
  CHECK(f != NULL);
  if (f) {
    fseek(f, 100, SEEK_SET);
    fputc(0x55, f);
    fclose(f);
  }
  CHECK(ss_reference_get(&again, body, &s, dir, NULL, NULL, err, sizeof err) == SS_OK);
  CHECK(again && !again->cache_hit && again->cache_rejected &&
        memcmp(again->pos, ref->pos, sizeof(double) * n3 * 3) == 0);
  ss_reference_destroy(again);
  remove(path);
  rmdir(dir);
  ss_reference_destroy(ref);
}

int main(void) {
  char err[256];
  ss_scene *scene = NULL;
  if (ss_scene_create(&scene, "elbow", 200, err, sizeof err) != SS_OK) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  ss_body body = ss_body_of_scene(scene);
  test_settings();
  test_keys(&body);
  test_error_and_cache(&body);
  ss_scene_destroy(scene);
  return ss_test_finish("test_reference");
}
