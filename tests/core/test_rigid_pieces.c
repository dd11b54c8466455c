/* ss_mesh.h, ss_mesh_rigid_pieces: pieces whose vertices all move with one
 * body part are carried (mask 0), others simulated; seam copies join pieces;
 * and a skin built with that mask follows a rigidly moving piece exactly
 * while it simulates the deforming one. */
#include "skin_sim/ss_mesh.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"
#include "ss_test_mesh.h"

#include <math.h>
#include <string.h>

/* Two grids side by side as one mesh: a at x in [0, 2], b at x in [3, 5]. */
static test_mesh two_grids(void) {
  test_mesh a = test_grid(2, 2, 0.0, 1), m;
  m.nvert = 2 * a.nvert;
  m.nface = 2 * a.nface;
  m.pos = malloc(sizeof(double) * 3 * (size_t)m.nvert);
  m.faces = malloc(sizeof(int) * 3 * (size_t)m.nface);
  for (int v = 0; v < a.nvert; v++) {
    memcpy(m.pos + 3 * v, a.pos + 3 * v, 3 * sizeof(double));
    memcpy(m.pos + 3 * (a.nvert + v), a.pos + 3 * v, 3 * sizeof(double));
    m.pos[3 * (a.nvert + v)] += 3.0;
  }
  for (int i = 0; i < 3 * a.nface; i++) {
    m.faces[i] = a.faces[i];
    m.faces[3 * a.nface + i] = a.faces[i] + a.nvert;
  }
  test_mesh_free(&a);
  return m;
}

int main(void) {
  test_mesh m = two_grids();
  const int nv = m.nvert, nf = m.nface, half = nv / 2, halff = nf / 2;
  uint32_t *part = malloc(sizeof(uint32_t) * (size_t)nv);
  unsigned char *mask = malloc((size_t)nf);
  ss_rigid_count cnt;

  /* both pieces rigid, on different parts: both carried */
  for (int v = 0; v < nv; v++) part[v] = v < half ? 1 : 2;
  memset(mask, 1, (unsigned)nf);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, NULL, part, mask, &cnt) == SS_OK);
  CHECK(cnt.npiece == 2 && cnt.npiece_carried == 2 && cnt.nface_carried == nf);
  for (int f = 0; f < nf; f++) CHECK(mask[f] == 0);

  /* one vertex of the second piece deforms (blended): only the first carried */
  part[nv - 1] = 0;
  memset(mask, 1, (unsigned)nf);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, NULL, part, mask, &cnt) == SS_OK);
  CHECK(cnt.npiece == 2 && cnt.npiece_carried == 1 && cnt.nface_carried == halff);
  for (int f = 0; f < nf; f++) CHECK(mask[f] == (f < halff ? 0 : 1));

  /* a piece spanning two parts (a joint) is simulated */
  for (int v = 0; v < nv; v++) part[v] = v < half ? 1 : 2;
  part[0] = 3;
  memset(mask, 1, (unsigned)nf);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, NULL, part, mask, &cnt) == SS_OK);
  CHECK(cnt.npiece_carried == 1 && cnt.nface_carried == halff);
  for (int f = 0; f < nf; f++) CHECK(mask[f] == (f < halff ? 1 : 0));

  /* seam copies join: vertex 0 of the second piece welded with the first's
   * last vertex makes one piece of two parts, simulated whole */
  for (int v = 0; v < nv; v++) part[v] = v < half ? 1 : 2;
  int *weld = malloc(sizeof(int) * (size_t)nv);
  for (int v = 0; v < nv; v++) weld[v] = v;
  weld[half] = half - 1;
  memset(mask, 1, (unsigned)nf);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, weld, part, mask, &cnt) == SS_OK);
  CHECK(cnt.npiece == 1 && cnt.npiece_carried == 0 && cnt.nface_carried == 0);
  for (int f = 0; f < nf; f++) CHECK(mask[f] == 1);

  /* faces already masked stay masked; bad arguments are refused */
  memset(mask, 0, (unsigned)nf);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, weld, part, mask, &cnt) == SS_OK);
  for (int f = 0; f < nf; f++) CHECK(mask[f] == 0);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, NULL, NULL, mask, &cnt) == SS_E_ARG);
  m.faces[4] = nv;
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, NULL, part, mask, &cnt) == SS_E_ARG);
  m.faces[4] = 1;
  CHECK(ss_mesh_rigid_pieces(0, 0, NULL, NULL, NULL, NULL, &cnt) == SS_OK && cnt.npiece == 0);

  /* a skin with the mask: piece a rigid (part 1), piece b deforming (0). The
   * body moves a rigidly (rotated and translated) and stretches b; the skin
   * of a stays on the body to round-off, b is simulated (its unknowns). */
  for (int v = 0; v < nv; v++) part[v] = v < half ? 1 : 0;
  memset(mask, 1, (unsigned)nf);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, NULL, part, mask, &cnt) == SS_OK);
  CHECK(cnt.nface_carried == halff);
  ss_sim_settings set = ss_sim_default_settings();
  set.threads = 1;
  set.face_mask = mask;
  ss_sim *sim = NULL;
  char err[256] = "";
  CHECK(ss_sim_create(&sim, nv, m.pos, nf, m.faces, NULL, &set, err, sizeof err) == SS_OK);
  if (sim) {
    CHECK(ss_sim_ndof(sim) == half);
    double *pose = malloc(sizeof(double) * 3 * (size_t)nv);
    double worst = 0.0;
    for (int step = 1; step <= 30; step++) {
      double t = step / 30.0, c = cos(t), s = sin(t);
      for (int v = 0; v < nv; v++) {
        const double *p = m.pos + 3 * v;
        double *q = pose + 3 * v;
        if (v < half) { /* rotation about z and a lift */
          q[0] = c * p[0] - s * p[1] + 0.3 * t;
          q[1] = s * p[0] + c * p[1];
          q[2] = p[2] + 0.5 * t;
        } else { /* stretched along x */
          q[0] = 3.0 + (p[0] - 3.0) * (1.0 + 0.2 * t);
          q[1] = p[1];
          q[2] = p[2];
        }
      }
      ss_sim_stats st;
      CHECK(ss_sim_step(sim, pose, 1.0 / 30.0, &st, err, sizeof err) == SS_OK);
      const double *x = ss_sim_skin_positions(sim);
      for (int v = 0; v < half; v++)
        for (int d = 0; d < 3; d++) worst = fmax(worst, fabs(x[3 * v + d] - pose[3 * v + d]));
    }
    CHECK_MSG(worst < 1e-12, "rigid piece off its body by %g", worst);
    /* the simulated piece lags its stretching body: it moved, but not onto it */
    const double *x = ss_sim_skin_positions(sim);
    double lag = 0.0;
    for (int v = half; v < nv; v++) lag = fmax(lag, fabs(x[3 * v] - pose[3 * v]));
    CHECK(lag > 1e-6 && lag < 0.5);
    free(pose);
  }
  ss_sim_destroy(sim);

  /* everything carried: no unknowns, the skin is the body */
  for (int v = 0; v < nv; v++) part[v] = v < half ? 1 : 2;
  memset(mask, 1, (unsigned)nf);
  CHECK(ss_mesh_rigid_pieces(nv, nf, m.faces, NULL, part, mask, &cnt) == SS_OK);
  sim = NULL;
  CHECK(ss_sim_create(&sim, nv, m.pos, nf, m.faces, NULL, &set, err, sizeof err) == SS_OK);
  if (sim) {
    CHECK(ss_sim_ndof(sim) == 0);
    double *pose = malloc(sizeof(double) * 3 * (size_t)nv);
    for (int i = 0; i < 3 * nv; i++) pose[i] = m.pos[i] + 0.25;
    ss_sim_stats st;
    CHECK(ss_sim_step(sim, pose, 1.0 / 30.0, &st, err, sizeof err) == SS_OK);
    CHECK(st.iterations == 0);
    const double *x = ss_sim_skin_positions(sim);
    double worst = 0.0;
    for (int i = 0; i < 3 * nv; i++) worst = fmax(worst, fabs(x[i] - pose[i]));
    CHECK_MSG(worst < 1e-12, "carried skin off its body by %g", worst);
    free(pose);
  }
  ss_sim_destroy(sim);
  free(weld);
  free(part);
  free(mask);
  test_mesh_free(&m);
  return ss_test_finish("test_rigid_pieces");
}
