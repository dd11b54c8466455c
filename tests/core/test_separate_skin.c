/* A separate skin over a body with a rigid piece and a deforming one:
 * ss_sim_skin_binding says how far each skin vertex is from the body and
 * which rigid part it rides; the skin's pieces over the rigid part are
 * carried with it exactly, at their height over it (not dropped onto it),
 * while the other piece is simulated. */
#include "skin_sim/ss_mesh.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"
#include "ss_test_mesh.h"

#include <math.h>
#include <string.h>

int main(void) {
  /* body: grid a at x in [0, 3] (rigid, part 5), grid b at x in [4, 7] (deforming) */
  test_mesh g = test_grid(3, 3, 0.0, 1);
  const int gv = g.nvert, gf = g.nface, nv = 2 * gv, nf = 2 * gf;
  double *body = malloc(sizeof(double) * 3 * (size_t)nv);
  int *faces = malloc(sizeof(int) * 3 * (size_t)nf);
  uint32_t *part = malloc(sizeof(uint32_t) * (size_t)nv);
  for (int v = 0; v < gv; v++) {
    memcpy(body + 3 * v, g.pos + 3 * v, 3 * sizeof(double));
    memcpy(body + 3 * (gv + v), g.pos + 3 * v, 3 * sizeof(double));
    body[3 * (gv + v)] += 4.0;
    part[v] = 5;
    part[gv + v] = 0;
  }
  for (int i = 0; i < 3 * gf; i++) faces[i] = g.faces[i], faces[3 * gf + i] = g.faces[i] + gv;
  /* skin: the same two grids 0.1 above the body */
  double *skin_pos = malloc(sizeof(double) * 3 * (size_t)nv);
  memcpy(skin_pos, body, sizeof(double) * 3 * (size_t)nv);
  for (int v = 0; v < nv; v++) skin_pos[3 * v + 2] += 0.1;
  ss_sim_mesh skin = {nv, skin_pos, nf, faces};

  uint32_t *skin_part = malloc(sizeof(uint32_t) * (size_t)nv);
  double *dist = malloc(sizeof(double) * (size_t)nv);
  char err[256] = "";
  CHECK(ss_sim_skin_binding(nv, body, nf, faces, &skin, part, skin_part, dist, err, sizeof err) ==
        SS_OK);
  for (int v = 0; v < nv; v++) {
    CHECK_NEAR(dist[v], 0.1, 1e-12);
    CHECK(skin_part[v] == (v < gv ? 5u : 0u));
  }
  unsigned char *mask = malloc((size_t)nf);
  memset(mask, 1, (unsigned)nf);
  ss_rigid_count cnt;
  CHECK(ss_mesh_rigid_pieces(nv, nf, faces, NULL, skin_part, mask, &cnt) == SS_OK);
  CHECK(cnt.npiece == 2 && cnt.npiece_carried == 1 && cnt.nface_carried == gf);

  ss_sim_settings set = ss_sim_default_settings();
  set.threads = 1;
  set.face_mask = mask;
  ss_sim *sim = NULL;
  CHECK(ss_sim_create(&sim, nv, body, nf, faces, &skin, &set, err, sizeof err) == SS_OK);
  if (sim) {
    CHECK(ss_sim_ndof(sim) == gv);
    double *pose = malloc(sizeof(double) * 3 * (size_t)nv), worst = 0.0;
    for (int step = 1; step <= 20; step++) {
      /* a rotates about x by t and rises; b stretches */
      double t = 0.05 * step, c = cos(t), s = sin(t);
      for (int v = 0; v < nv; v++) {
        const double *p = body + 3 * v;
        double *q = pose + 3 * v;
        if (v < gv) q[0] = p[0] + 0.2 * t, q[1] = c * p[1] - s * p[2], q[2] = s * p[1] + c * p[2] + t;
        else q[0] = 4.0 + (p[0] - 4.0) * (1.0 + 0.1 * t), q[1] = p[1], q[2] = p[2];
      }
      CHECK(ss_sim_step(sim, pose, 1.0 / 30.0, NULL, err, sizeof err) == SS_OK);
      const double *x = ss_sim_skin_positions(sim);
      for (int v = 0; v < gv; v++) {
        const double *p = skin_pos + 3 * v;
        double want[3] = {p[0] + 0.2 * t, c * p[1] - s * p[2], s * p[1] + c * p[2] + t};
        for (int d = 0; d < 3; d++) worst = fmax(worst, fabs(x[3 * v + d] - want[d]));
      }
    }
    CHECK_MSG(worst < 1e-12, "the carried skin is off its rigid motion by %g", worst);
    free(pose);
  }
  ss_sim_destroy(sim);

  /* bad input: no vertices, a NaN */
  ss_sim_mesh none = {0, NULL, 0, NULL};
  CHECK(ss_sim_skin_binding(nv, body, nf, faces, &none, NULL, NULL, NULL, err, sizeof err) == SS_E_MESH);
  skin_pos[4] = NAN;
  CHECK(ss_sim_skin_binding(nv, body, nf, faces, &skin, NULL, NULL, dist, err, sizeof err) ==
        SS_E_NONFINITE);
  CHECK(strstr(err, "skin vertex 1") != NULL);
  free(mask);
  free(dist);
  free(skin_part);
  free(skin_pos);
  free(part);
  free(faces);
  free(body);
  test_mesh_free(&g);
  return ss_test_finish("test_separate_skin");
}
