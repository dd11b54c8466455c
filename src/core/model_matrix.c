/* The model's packed energy layout and its constant matrices (model.h):
 * built once with the model, read by every sim on it.
 *
 * The layout: the simulated faces' membrane records (mface) in simulated
 * face order and, per dof, the slots of the per-face gradients it sums
 * (grad_ptr, grad_slot), so that the energy's gradient is gathered without
 * atomics, the same bits on any thread count. The constant matrices: inertia
 * (given the sim's weights) and anchor springs, in the scalar n x n pattern
 * or the 3n x 3n one, and the rest membrane Laplacian of the quasi-Newton
 * matrix; their diagonals judge convergence (ss_sim_residual). */
#include <stdlib.h>
#include <string.h>

#include "model.h"

void ss_model_energy_springs(ss_model *m) {
  const int bary = m->set.barycenter_anchors;
  for (int q = 0; q < m->nsimface; q++) {
    const int f = m->simface[q];
    ss_membrane_face *r = m->mface + q;
    r->anchor = 3 * f;
    r->k_bary = bary ? m->k_face[f] : 0.0;
  }
}

int ss_model_energy_layout(ss_model *m, char *err, int err_sz) {
  const int nsim = m->nsimface, n = m->ndof;
  /* mface, grad_ptr (zeroed), grad_slot: the model's arena; face_grad: the data's */
  for (int q = 0; q < nsim; q++) {
    int f = m->simface[q];
    ss_membrane_face *r = m->mface + q;
    for (int c = 0; c < 3; c++) r->xo[c] = 3 * m->faces[3 * f + c];
    memcpy(r->dm_inv, m->dm_inv + 4 * f, 4 * sizeof(double));
    r->area = m->rest_area[f];
  }
  ss_model_energy_springs(m);
  /* Slots per dof in the order of the sum: the simulated faces' (membrane
   * and barycenter spring together) in simulated face order, each corner in
   * turn. */
  int *cnt = m->grad_ptr + 1;
  for (int pass = 0; pass < 2; pass++) {
    if (pass == 1) {
      for (int k = 0; k < n; k++) m->grad_ptr[k + 1] += m->grad_ptr[k];
      cnt = m->grad_ptr; /* in pass 1 grad_ptr[k] is the next free entry of dof k */
    }
    for (int q = 0; q < nsim; q++)
      for (int c = 0; c < 3; c++) {
        int k = m->dof[m->faces[3 * m->simface[q] + c]];
        if (k < 0) continue;
        if (pass == 0)
          cnt[k]++;
        else
          m->grad_slot[cnt[k]++] = 9 * q + 3 * c;
      }
  }
  /* pass 1 advanced grad_ptr[k] to the end of dof k, i.e. the start of k + 1 */
  memmove(m->grad_ptr + 1, m->grad_ptr, (size_t)n * sizeof(int));
  m->grad_ptr[0] = 0;
  (void)err, (void)err_sz;
  return SS_OK;
}

/* Adds w (x I3) to block (rank, column j): scalar != 0 in the n x n values,
 * else in the 3n x 3n values. */
static void add_iso(const ss_model *m, double *vals, int scalar, int j, int rank, double w) {
  if (scalar) {
    vals[m->bcolp[j] + rank] += w;
  } else {
    for (int c = 0; c < 3; c++) vals[ss_model_slot3(m, j, rank, c, c)] += w;
  }
}

void ss_model_scatter_element(const ss_model *m, const int *verts, int n, const int *elem_rank,
                              const double *he, double *vals) {
  ss_upper_pair pair[16];
  const int np = ss_model_upper_pairs(m, verts, n, elem_rank, pair), w = 3 * n;
  for (int p = 0; p < np; p++) {
    const ss_upper_pair *u = &pair[p];
    for (int c1 = 0; c1 < 3; c1++)
      for (int c2 = u->diag ? c1 : 0; c2 < 3; c2++)
        vals[ss_model_slot3(m, u->col, u->rank, c1, c2)] += he[w * (3 * u->a + c1) + 3 * u->b + c2];
  }
}

void ss_model_constant_terms(const ss_model *m, const double *mi, double *vals, int scalar) {
  size_t nnz = scalar ? (size_t)m->nblock : (size_t)m->nnz3;
  memset(vals, 0, nnz * sizeof *vals);
  for (int k = 0; k < m->ndof; k++) {
    int v = m->dof_vert[k];
    int diag_rank = m->bcolp[k + 1] - m->bcolp[k] - 1;
    add_iso(m, vals, scalar, k, diag_rank, (mi ? mi[k] : 0.0) + m->k_vert[v]);
  }
  if (m->set.barycenter_anchors) {
    for (int f = 0; f < m->nface; f++) {
      double kf = m->k_face[f];
      if (kf == 0.0) continue;
      ss_upper_pair pair[9];
      const int np = ss_model_upper_pairs(m, m->faces + 3 * f, 3, m->face_rank + 9 * f, pair);
      for (int p = 0; p < np; p++) add_iso(m, vals, scalar, pair[p].col, pair[p].rank, kf / 9.0);
    }
  }
}

static void rest_laplacian(const ss_model *m, double *vals);

void ss_model_scalar_matrix(const ss_model *m, const double *mi, double *vals) {
  ss_model_constant_terms(m, mi, vals, 1);
  rest_laplacian(m, vals);
}


void ss_model_diag_const(ss_model *m) {
  /* The scalar matrix without inertia (mi NULL) into a scratch of nblock
   * values: its diagonal, then the springs' alone. */
  double *vals = calloc((size_t)(m->nblock ? m->nblock : 1), sizeof *vals);
  if (!vals) {
    for (int k = 0; k < m->ndof; k++) m->diag_const[k] = m->diag_springs[k] = 0.0;
    return;
  }
  ss_model_scalar_matrix(m, NULL, vals);
  for (int k = 0; k < m->ndof; k++) m->diag_const[k] = vals[m->bcolp[k + 1] - 1];
  ss_model_constant_terms(m, NULL, vals, 1); /* the springs alone */
  for (int k = 0; k < m->ndof; k++) m->diag_springs[k] = vals[m->bcolp[k + 1] - 1];
  free(vals);
}

static void rest_laplacian(const ss_model *m, double *vals) {
  /* Rest membrane stiffness: (mu + lam) times the cotangent Laplacian, the
   * exact Hessian of (mu + lam)/2 A |F|^2. It lies between the rest
   * membrane's in-plane eigenvalues 2 mu (shear) and 2 lam (area). */
  double w = m->mu + m->lam;
  for (int q = 0; q < m->nsimface; q++) {
    int f = m->simface[q];
    const double *di = m->dm_inv + 4 * f;
    double d[3][2];
    for (int j = 0; j < 2; j++) {
      d[1][j] = di[j];
      d[2][j] = di[2 + j];
      d[0][j] = -d[1][j] - d[2][j];
    }
    ss_upper_pair pair[9];
    const int np = ss_model_upper_pairs(m, m->faces + 3 * f, 3, m->face_rank + 9 * f, pair);
    for (int p = 0; p < np; p++) {
      const int a = pair[p].a, b = pair[p].b;
      vals[m->bcolp[pair[p].col] + pair[p].rank] += w * m->rest_area[f] * (d[a][0] * d[b][0] + d[a][1] * d[b][1]);
    }
  }
}
