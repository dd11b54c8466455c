/* Eigen-decomposition of small symmetric matrices and projection to positive
 * semi-definite, for the per-element Hessians of the Newton solver.
 *
 * Algorithm: the cyclic Jacobi method (Golub & Van Loan, "Matrix
 * Computations", 4th ed., section 8.5): sweeps over all off-diagonal pairs
 * (p, q) in a fixed order, each annihilating a_pq by a plane rotation chosen
 * with the smaller rotation angle (numerically stable form of Rutishauser).
 * It converges quadratically, computes small eigenvalues to high relative
 * accuracy, and, since the order of operations is fixed, it is bit-for-bit
 * deterministic. For the n <= 12 of an element Hessian a handful of sweeps
 * suffice; everything lives on the stack. */
#include <math.h>
#include <string.h>

#include "energy.h"

#define SS_PSD_MAX_N 12
#define SS_JACOBI_MAX_SWEEPS 60

void ss_sym_eigen(const double *m, int n, double *evals, double *evecs) {
  double a[SS_PSD_MAX_N * SS_PSD_MAX_N];
  if (n <= 0) return;
  if (n > SS_PSD_MAX_N) n = SS_PSD_MAX_N; /* documented limit; callers never pass more */
  /* Work on the symmetric part so that round-off asymmetry in m is harmless. */
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) a[i * n + j] = 0.5 * (m[i * n + j] + m[j * n + i]);
  for (int i = 0; i < n * n; i++) evecs[i] = 0.0;
  for (int i = 0; i < n; i++) evecs[i * n + i] = 1.0;

  double total = 0.0;
  for (int i = 0; i < n * n; i++) total += a[i] * a[i];
  for (int sweep = 0; sweep < SS_JACOBI_MAX_SWEEPS; sweep++) {
    double off = 0.0;
    for (int p = 0; p < n; p++)
      for (int q = p + 1; q < n; q++) off += a[p * n + q] * a[p * n + q];
    /* Off-diagonal mass below round-off of the whole matrix: done. */
    if (off <= 1e-34 * total || off == 0.0) break;
    for (int p = 0; p < n; p++) {
      for (int q = p + 1; q < n; q++) {
        double apq = a[p * n + q];
        if (apq == 0.0) continue;
        double app = a[p * n + p], aqq = a[q * n + q];
        double theta = (aqq - app) / (2.0 * apq);
        double t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
        if (!isfinite(theta)) t = 0.5 / theta; /* |theta| huge: t ~ 1/(2 theta) */
        double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
        /* A <- J^T A J with J the rotation in the (p, q) plane. */
        for (int k = 0; k < n; k++) {
          double akp = a[k * n + p], akq = a[k * n + q];
          a[k * n + p] = c * akp - s * akq;
          a[k * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; k++) {
          double apk = a[p * n + k], aqk = a[q * n + k];
          a[p * n + k] = c * apk - s * aqk;
          a[q * n + k] = s * apk + c * aqk;
        }
        a[p * n + q] = a[q * n + p] = 0.0;
        for (int k = 0; k < n; k++) {
          double vkp = evecs[k * n + p], vkq = evecs[k * n + q];
          evecs[k * n + p] = c * vkp - s * vkq;
          evecs[k * n + q] = s * vkp + c * vkq;
        }
      }
    }
  }
  for (int i = 0; i < n; i++) evals[i] = a[i * n + i];
}

void ss_project_psd(double *m, int n) {
  double evals[SS_PSD_MAX_N], evecs[SS_PSD_MAX_N * SS_PSD_MAX_N];
  if (n <= 0 || n > SS_PSD_MAX_N) return;
  ss_sym_eigen(m, n, evals, evecs);
  int any_negative = 0;
  for (int i = 0; i < n; i++) any_negative |= evals[i] < 0.0;
  /* Already PSD: leave the matrix exactly as it was (projection is idempotent). */
  if (!any_negative) return;
  for (int i = 0; i < n; i++) {
    for (int j = i; j < n; j++) {
      double sum = 0.0;
      for (int k = 0; k < n; k++)
        if (evals[k] > 0.0) sum += evecs[i * n + k] * evals[k] * evecs[j * n + k];
      m[i * n + j] = m[j * n + i] = sum;
    }
  }
}
