/* Tests of the assembled incremental potential (src/core/sim_energy.c,
 * model_pattern.c) through the internal interface: the total gradient against
 * central differences of the total energy, and the sparse Newton matrix
 * (pattern, slot map, upper-triangle storage) against central differences of
 * the gradient, with every term on (inertia, damping, gravity, vertex and
 * barycenter springs, membrane, hinges) and a face mask with pinned and
 * following vertices. The matrix is compared where the projected element
 * Hessians are exact: a uniformly stretched pose (membrane Hessian PSD,
 * dihedral angles at rest, so the hinge's Gauss-Newton Hessian is exact). */
#include <string.h>

#include "sim_fixtures.h"
#include "sim_internal.h"
#include "ss_test.h"

static void upper_matvec(const ss_sim *sim, const double *vals, const double *v, double *out) {
  int n3 = 3 * sim->m->ndof;
  const int *p = sim->m->colp3, *ri = sim->H->i;
  memset(out, 0, (size_t)n3 * sizeof *out);
  for (int c = 0; c < n3; c++)
    for (int q = p[c]; q < p[c + 1]; q++) {
      int r = ri[q];
      out[r] += vals[q] * v[c];
      if (r != c) out[c] += vals[q] * v[r];
    }
}

static void test_assembly(void) {
  fx_mesh g = fx_grid(8, 7, 1.0, 0.9, 0.25);
  unsigned char *mask = malloc((size_t)g.nface);
  for (int f = 0; f < g.nface; f++) mask[f] = (f / 2) % 7 != 0; /* first column of cells off */
  ss_sim_settings set = ss_sim_default_settings();
  set.solver = SS_SOLVER_NEWTON;
  set.bending = 0.05;
  set.damping = 2.0;
  set.gravity[1] = -3.0;
  set.gravity[2] = -9.81;
  set.young = 20.0;
  set.face_mask = mask;
  char err[256];
  ss_sim *sim = NULL;
  CHECK_EQ_INT(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err), SS_OK);
  free(mask);
  if (!sim) return;
  CHECK(sim->m->nhinge > 0);
  CHECK(sim->m->ndof > 0 && sim->m->ndof < g.nvert);
  /* Move once so that anchors and velocities are not trivial. */
  double *pose = malloc(3 * (size_t)g.nvert * sizeof(double));
  fx_pose(&g, 0.05, pose);
  CHECK_EQ_INT(ss_sim_step(sim, pose, 0.0, NULL, NULL, 0), SS_OK);
  /* A substep set up by hand: fixed vertices in place, a given h. */
  memcpy(sim->x_prev, sim->x, 3 * (size_t)g.nvert * sizeof(double));
  memcpy(sim->xfull_t, sim->x, 3 * (size_t)g.nvert * sizeof(double));
  ss_sim_energy_begin(sim, 0.02);
  int n3 = 3 * sim->m->ndof;
  double *x0 = malloc((size_t)n3 * sizeof(double)), *gr = malloc((size_t)n3 * sizeof(double));
  double *gp = malloc((size_t)n3 * sizeof(double)), *gm = malloc((size_t)n3 * sizeof(double));
  double *xs = malloc((size_t)n3 * sizeof(double)), *dirv = calloc((size_t)n3, sizeof(double));
  double *hv = malloc((size_t)n3 * sizeof(double));
  double *full = malloc(3 * (size_t)g.nvert * sizeof(double));
  unsigned long long rng = 42;

  /* 1. gradient against differences of the energy, at a random pose. */
  memcpy(full, sim->x, 3 * (size_t)g.nvert * sizeof(double));
  for (int k = 0; k < sim->m->ndof; k++)
    for (int i = 0; i < 3; i++)
      x0[3 * k + i] = sim->x[3 * sim->m->dof_vert[k] + i] + 0.05 * (2.0 * ss_test_rand(&rng) - 1.0);
  ss_sim_scatter(sim, x0, full);
  ss_sim_energy(sim, full, gr);
  double worst = 0.0, scale = 0.0;
  for (int q = 0; q < n3; q++) {
    const double eps = 1e-6;
    memcpy(xs, x0, (size_t)n3 * sizeof(double));
    xs[q] += eps;
    ss_sim_scatter(sim, xs, full);
    double ep = ss_sim_energy(sim, full, NULL);
    xs[q] -= 2 * eps;
    ss_sim_scatter(sim, xs, full);
    double em = ss_sim_energy(sim, full, NULL);
    worst = fmax(worst, fabs((ep - em) / (2 * eps) - gr[q]));
    scale = fmax(scale, fabs(gr[q]));
  }
  CHECK_MSG(worst <= 1e-6 * scale, "total gradient vs FD: %g (scale %g)", worst, scale);

  /* 2. the sparse matrix against differences of the gradient, uniformly
   * stretched about the centroid (all element Hessians exact there). */
  double c[3] = {0, 0, 0};
  for (int v = 0; v < g.nvert; v++)
    for (int i = 0; i < 3; i++) c[i] += g.pos[3 * v + i] / g.nvert;
  for (int v = 0; v < g.nvert; v++)
    for (int i = 0; i < 3; i++) full[3 * v + i] = c[i] + 1.05 * (g.pos[3 * v + i] - c[i]);
  for (int k = 0; k < sim->m->ndof; k++) memcpy(x0 + 3 * k, full + 3 * sim->m->dof_vert[k], 3 * sizeof(double));
  ss_sim_scatter(sim, x0, full);
  double *vals = malloc((size_t)sim->m->nnz3 * sizeof(double));
  ss_sim_constant_hessian(sim, vals);
  ss_sim_add_elastic_hessian(sim, full, vals, 0);
  for (int trial = 0; trial < 3; trial++) {
    for (int q = 0; q < n3; q++) dirv[q] = 2.0 * ss_test_rand(&rng) - 1.0;
    upper_matvec(sim, vals, dirv, hv);
    const double eps = 1e-6;
    for (int q = 0; q < n3; q++) xs[q] = x0[q] + eps * dirv[q];
    ss_sim_scatter(sim, xs, full);
    ss_sim_energy(sim, full, gp);
    for (int q = 0; q < n3; q++) xs[q] = x0[q] - eps * dirv[q];
    ss_sim_scatter(sim, xs, full);
    ss_sim_energy(sim, full, gm);
    worst = 0.0, scale = 0.0;
    for (int q = 0; q < n3; q++) {
      worst = fmax(worst, fabs((gp[q] - gm[q]) / (2 * eps) - hv[q]));
      scale = fmax(scale, fabs(hv[q]));
    }
    CHECK_MSG(worst <= 1e-5 * scale, "H v vs FD of the gradient: %g (scale %g)", worst, scale);
  }
  /* 2b. the exact Hessian (Newton's first choice) where the projected one is
   * not exact: the skin compressed to 0.9 and sheared (indefinite membrane
   * Hessians, dihedral angles off their rest values). Hinges keep their
   * Gauss-Newton Hessian, so bending is compared separately: here it is the
   * membrane part that must match. */
  {
    ss_sim_settings set2 = set;
    set2.bending = 0.0;
    unsigned char *m2 = malloc((size_t)g.nface);
    for (int f = 0; f < g.nface; f++) m2[f] = (f / 2) % 7 != 0;
    set2.face_mask = m2;
    ss_sim *s2 = NULL;
    CHECK_EQ_INT(ss_sim_create(&s2, g.nvert, g.pos, g.nface, g.faces, NULL, &set2, err, sizeof err), SS_OK);
    free(m2);
    if (s2) {
      memcpy(s2->x_prev, s2->x, 3 * (size_t)g.nvert * sizeof(double));
      ss_sim_energy_begin(s2, 0.02);
      double *f2 = malloc(3 * (size_t)g.nvert * sizeof(double));
      for (int v = 0; v < g.nvert; v++) {
        const double *p0 = g.pos + 3 * v;
        f2[3 * v] = c[0] + 0.9 * (p0[0] - c[0]) + 0.05 * (p0[1] - c[1]);
        f2[3 * v + 1] = c[1] + 0.9 * (p0[1] - c[1]);
        f2[3 * v + 2] = c[2] + 0.9 * (p0[2] - c[2]);
      }
      int m3 = 3 * s2->m->ndof;
      double *y0 = malloc((size_t)m3 * sizeof(double)), *ys = malloc((size_t)m3 * sizeof(double));
      double *v2 = calloc((size_t)m3, sizeof(double)), *hv2 = malloc((size_t)m3 * sizeof(double));
      double *g1 = malloc((size_t)m3 * sizeof(double)), *g2 = malloc((size_t)m3 * sizeof(double));
      for (int k = 0; k < s2->m->ndof; k++) memcpy(y0 + 3 * k, f2 + 3 * s2->m->dof_vert[k], 3 * sizeof(double));
      double *v3 = malloc((size_t)s2->m->nnz3 * sizeof(double)), *vp = malloc((size_t)s2->m->nnz3 * sizeof(double));
      ss_sim_constant_hessian(s2, v3);
      memcpy(vp, v3, (size_t)s2->m->nnz3 * sizeof(double));
      ss_sim_add_elastic_hessian(s2, f2, v3, 1);
      ss_sim_add_elastic_hessian(s2, f2, vp, 0);
      for (int q = 0; q < m3; q++) v2[q] = 2.0 * ss_test_rand(&rng) - 1.0;
      upper_matvec(s2, v3, v2, hv2);
      const double eps = 1e-6;
      for (int q = 0; q < m3; q++) ys[q] = y0[q] + eps * v2[q];
      ss_sim_scatter(s2, ys, f2);
      ss_sim_energy(s2, f2, g1);
      for (int q = 0; q < m3; q++) ys[q] = y0[q] - eps * v2[q];
      ss_sim_scatter(s2, ys, f2);
      ss_sim_energy(s2, f2, g2);
      double w2 = 0.0, sc2 = 0.0, differs = 0.0;
      for (int q = 0; q < m3; q++) {
        w2 = fmax(w2, fabs((g1[q] - g2[q]) / (2 * eps) - hv2[q]));
        sc2 = fmax(sc2, fabs(hv2[q]));
      }
      for (int q = 0; q < s2->m->nnz3; q++) differs = fmax(differs, fabs(v3[q] - vp[q]));
      CHECK_MSG(w2 <= 1e-5 * sc2, "exact H v vs FD of the gradient: %g (scale %g)", w2, sc2);
      CHECK_MSG(differs > 1e-3, "compressed: exact and projected Hessians should differ (%g)", differs);
      free(y0), free(ys), free(v2), free(hv2), free(g1), free(g2), free(v3), free(vp), free(f2);
      ss_sim_destroy(s2);
    }
  }
  /* 3. the scalar matrix is symmetric positive definite and its diagonal
   * holds inertia + springs + Laplacian (>= inertia). */
  double *sv = malloc((size_t)sim->m->nblock * sizeof(double));
  ss_sim_scalar_matrix(sim, sv);
  for (int k = 0; k < sim->m->ndof; k++) CHECK(sv[sim->m->bcolp[k + 1] - 1] >= sim->mi[k]);
  free(sv);
  free(vals);
  free(x0), free(gr), free(gp), free(gm), free(xs), free(dirv), free(hv), free(full), free(pose);
  ss_sim_destroy(sim);
  fx_free(&g);
}

int main(void) {
  test_assembly();
  return ss_test_finish("test_sim_assembly");
}
