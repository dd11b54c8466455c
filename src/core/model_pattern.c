/* Sparsity pattern of the skin's system matrices, built once per topology.
 *
 * Two vertices of the unknowns interact when they share a simulated face (the
 * membrane and barycenter springs) or a hinge (bending). The pattern is kept
 * per vertex pair ("block"), upper triangle, in compressed columns: block
 * column j lists its block rows i <= j in increasing order, the diagonal last.
 * The scalar n x n matrix of the quasi-Newton solver is exactly this pattern;
 * the 3n x 3n Newton matrix expands each block into 3x3 entries (only the
 * upper triangle of diagonal blocks), in the column order CHOLMOD expects
 * (sorted rows, stype = 1).
 *
 * Every element then stores, for each pair of its corners, the rank of the
 * block in its column: together with the column starts that gives the slot
 * of any element Hessian entry in the values array without a search, so that
 * assembly is a scatter (MuJoCo's engine_util_solve does the same). */
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "ss_err.h"

static int cmp_ll(const void *a, const void *b) {
  long long x = *(const long long *)a, y = *(const long long *)b;
  return (x > y) - (x < y);
}

/* Rank of block row i in block column j, or -1 if not there. */
static int block_rank(const ss_model *m, int i, int j) {
  int lo = m->bcolp[j], hi = m->bcolp[j + 1] - 1;
  while (lo <= hi) {
    int mid = lo + (hi - lo) / 2;
    if (m->brow[mid] == i) return mid - m->bcolp[j];
    if (m->brow[mid] < i)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

/* Fills ranks for the corners verts[0..n-1] into rank[n x n]. */
static void element_ranks(const ss_model *m, const int *verts, int n, int *rank) {
  for (int a = 0; a < n; a++) {
    for (int b = 0; b < n; b++) {
      int i = m->dof[verts[a]], j = m->dof[verts[b]];
      if (i < 0 || j < 0) {
        rank[n * a + b] = -1;
        continue;
      }
      int lo = i < j ? i : j, hi = i < j ? j : i;
      rank[n * a + b] = block_rank(m, lo, hi);
    }
  }
}

int ss_model_build_pattern(ss_model *m, char *err, int err_sz) {
  int n = m->ndof;
  /* Candidate pairs: diagonal, simulated faces' corner pairs, hinges. */
  size_t cap = (size_t)n + 3 * (size_t)m->nface + 6 * (size_t)m->nhinge;
  long long *key = malloc((cap ? cap : 1) * sizeof *key);
  if (!key) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory building the sparsity pattern");
  size_t nk = 0;
  for (int k = 0; k < n; k++) key[nk++] = (long long)k * n + k;
  for (int f = 0; f < m->nface; f++) {
    const int *fv = m->faces + 3 * f;
    for (int a = 0; a < 3; a++) {
      int i = m->dof[fv[a]], j = m->dof[fv[(a + 1) % 3]];
      if (i < 0 || j < 0 || i == j) continue;
      if (i > j) {
        int t = i;
        i = j;
        j = t;
      }
      key[nk++] = (long long)j * n + i;
    }
  }
  for (int e = 0; e < m->nhinge; e++) {
    const int *hv = m->hinge_vert + 4 * e;
    for (int a = 0; a < 4; a++)
      for (int b = a + 1; b < 4; b++) {
        int i = m->dof[hv[a]], j = m->dof[hv[b]];
        if (i < 0 || j < 0 || i == j) continue;
        if (i > j) {
          int t = i;
          i = j;
          j = t;
        }
        key[nk++] = (long long)j * n + i;
      }
  }
  qsort(key, nk, sizeof *key, cmp_ll);
  size_t nu = 0;
  for (size_t q = 0; q < nk; q++)
    if (nu == 0 || key[q] != key[nu - 1]) key[nu++] = key[q];
  m->nblock = (int)nu;
  /* bcolp, colp3 (zeroed), brow (nu <= cap), face_rank, hinge_rank: the model's arena */
  /* Keys sorted by (column, row): the CSC order directly. */
  for (size_t q = 0; q < nu; q++) {
    int j = (int)(key[q] / n), i = (int)(key[q] % n);
    m->brow[q] = i;
    m->bcolp[j + 1]++;
  }
  free(key);
  for (int j = 0; j < n; j++) m->bcolp[j + 1] += m->bcolp[j];
  /* 3n columns: block column j with nb blocks (the diagonal last) gives
   * columns of 3 (nb - 1) + 1, + 2, + 3 entries. */
  long long nnz3 = 0;
  for (int j = 0; j < n; j++) {
    int nb = m->bcolp[j + 1] - m->bcolp[j];
    for (int b = 0; b < 3; b++) {
      m->colp3[3 * j + b] = (int)nnz3;
      nnz3 += 3LL * (nb - 1) + b + 1;
    }
  }
  if (nnz3 > 2000000000LL)
    return ss_fail(err, err_sz, SS_E_ARG, "skin too large: %lld matrix entries", nnz3);
  m->colp3[3 * n] = (int)nnz3;
  m->nnz3 = (int)nnz3;
  for (int f = 0; f < m->nface; f++) element_ranks(m, m->faces + 3 * f, 3, m->face_rank + 9 * f);
  for (int e = 0; e < m->nhinge; e++)
    element_ranks(m, m->hinge_vert + 4 * e, 4, m->hinge_rank + 16 * e);
  return SS_OK;
}
