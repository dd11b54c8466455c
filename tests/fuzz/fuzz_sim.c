/* libFuzzer harness: ss_sim_create and a few ss_sim_step calls on small
 * random meshes (a jittered grid patch, or raw random triangles), with
 * settings inside and outside their ranges, face masks, poses that move,
 * jump far or carry NaN, and any dt (issue 14: a huge jump over a tiny dt put
 * +-inf in the velocities). Asserts ss_sim.h's promise: whatever a step
 * returns, the skin's positions and velocities stay finite; a refused step
 * leaves them untouched. */
#include <assert.h>

#include "fuzz_util.h"
#include "skin_sim/ss_sim.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define MAXV 25
#define MAXF 32

static void check_state(const ss_sim *sim, int n) {
  const double *x = ss_sim_skin_positions(sim), *v = ss_sim_skin_velocities(sim);
  for (int i = 0; i < 3 * n; i++) assert(isfinite(x[i]) && isfinite(v[i]));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fz f = {data, size};
  double pos[3 * MAXV];
  int faces[3 * MAXF], nvert, nface;
  if (fz_u8(&f) & 1) { /* a k x k grid patch, jittered */
    int k = fz_int(&f, 1, 4);
    nvert = (k + 1) * (k + 1);
    nface = 2 * k * k;
    for (int j = 0; j <= k; j++)
      for (int i = 0; i <= k; i++) {
        double *p = pos + 3 * (j * (k + 1) + i);
        p[0] = 0.1 * i + 0.01 * fz_double(&f, 1.0);
        p[1] = 0.1 * j + 0.01 * fz_double(&f, 1.0);
        p[2] = 0.01 * fz_double(&f, 1.0);
      }
    int q = 0;
    for (int j = 0; j < k; j++)
      for (int i = 0; i < k; i++) {
        int a = j * (k + 1) + i, b = a + 1, c = a + k + 1, d = c + 1;
        int *t = faces + 6 * q++;
        t[0] = a, t[1] = b, t[2] = d, t[3] = a, t[4] = d, t[5] = c;
      }
  } else {
    nvert = fz_int(&f, 1, MAXV);
    nface = fz_int(&f, 1, MAXF);
    for (int i = 0; i < 3 * nvert; i++) pos[i] = fz_double(&f, 0.1);
    for (int i = 0; i < 3 * nface; i++) faces[i] = fz_int(&f, (fz_u8(&f) & 0xf8) ? 0 : -1, nvert - 1);
  }
  ss_sim_settings set = ss_sim_default_settings();
  unsigned char mask[MAXF];
  uint8_t which = fz_u8(&f);
  if (which & 1) set.solver = fz_int(&f, -1, 2);
  if (which & 2) set.substeps = fz_int(&f, -1, 3);
  if (which & 4) set.iterations = fz_int(&f, -1, 12);
  if (which & 8) set.tol = fz_double(&f, 1e-3);
  if (which & 16) {
    set.young = fz_double(&f, 50.0);
    set.poisson = fz_double(&f, 0.25);
    set.density = fz_double(&f, 1.0);
    set.anchor_stiffness = fz_double(&f, 1e3);
  }
  if (which & 32) {
    set.bending = fz_double(&f, 1e-3);
    set.damping = fz_double(&f, 1.0);
    for (int i = 0; i < 3; i++) set.gravity[i] = fz_double(&f, 10.0);
    set.barycenter_anchors = fz_int(&f, -1, 2);
  }
  if (which & 64) {
    set.slide = fz_double(&f, 0.5);
    set.mover.method = fz_int(&f, -1, 3);
    set.mover.walk_max_steps = fz_int(&f, -1, 20);
    set.mover.nring_rings = fz_int(&f, -1, 3);
    set.lbfgs_history = fz_int(&f, -1, 33);
    set.safety_residual = fz_double(&f, 0.05);
    set.iterations_max = fz_int(&f, -1, 40);
  }
  if (which & 128) {
    for (int q = 0; q < nface; q++) mask[q] = fz_u8(&f) & 1;
    set.face_mask = mask;
  }
  set.dt = (fz_u8(&f) & 3) ? 1.0 / 30.0 : fz_double(&f, 0.03);
  set.threads = 1;
  ss_sim *sim = NULL;
  char err[256];
  if (ss_sim_create(&sim, nvert, pos, nface, faces, NULL, &set, err, sizeof err) != SS_OK) {
    assert(sim == NULL && err[0] != '\0');
    return 0;
  }
  const int n = ss_sim_skin_nvert(sim);
  check_state(sim, n);
  double pose[3 * MAXV];
  double *before = malloc(6 * (size_t)n * sizeof(double));
  int nstep = fz_int(&f, 1, 4);
  for (int s = 0; s < nstep; s++) {
    uint8_t how = fz_u8(&f);
    for (int i = 0; i < 3 * nvert; i++) {
      pose[i] = pos[i];
      if (how & 1) pose[i] += 0.05 * fz_double(&f, 1.0);           /* jiggle */
      if ((how & 6) == 2 && i % 3 == 0) pose[i] += fz_double(&f, 1e3); /* jump */
    }
    if ((how & 6) == 4) pose[fz_int(&f, 0, 3 * nvert - 1)] = fz_double(&f, 1.0); /* one raw value */
    double dt = (how & 8) ? fz_double(&f, 0.01) : 0.0;
    memcpy(before, ss_sim_skin_positions(sim), 3 * (size_t)n * sizeof(double));
    memcpy(before + 3 * n, ss_sim_skin_velocities(sim), 3 * (size_t)n * sizeof(double));
    ss_sim_stats st;
    err[0] = '\0';
    int status = ss_sim_step(sim, pose, dt, &st, err, sizeof err);
    check_state(sim, n);
    if (status == SS_E_ARG || status == SS_E_NONFINITE) {
      assert(err[0] != '\0');
      /* refused before anything changed */
      assert(memcmp(before, ss_sim_skin_positions(sim), 3 * (size_t)n * sizeof(double)) == 0);
      assert(memcmp(before + 3 * n, ss_sim_skin_velocities(sim), 3 * (size_t)n * sizeof(double)) == 0);
    }
    if (how & 16) ss_sim_reset(sim);
  }
  free(before);
  ss_sim_destroy(sim);
  return 0;
}
