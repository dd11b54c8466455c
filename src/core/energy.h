/* Internal: per-element energies of the skin (doc/model.md, "The skin model").
 *
 * Each function evaluates one element on flat arrays of its vertex positions
 * and returns the element's energy; gradient and Hessian are written where the
 * pointers are non-NULL. Hessians are dense, row-major, in the element's own
 * vertex order (xyz of vertex 0, then vertex 1, ...), symmetric, and projected
 * to positive semi-definite (negative eigenvalues clamped to zero) so that the
 * Newton system is always positive definite together with inertia.
 * None of them allocates; all are deterministic and NaN-free for finite input
 * (degenerate and inverted elements included). */
#ifndef SKIN_SIM_ENERGY_H
#define SKIN_SIM_ENERGY_H

#include "ss_vec.h" /* SS_THIRD */

/* ---- membrane: 2D Stable Neo-Hookean (Smith, de Goes, Kim 2018) ----------
 * F = [x1-x0, x2-x0] Dm^-1 (3x2), I_C = tr(F^T F), J = sqrt(det(F^T F)),
 * Psi = mu/2 (I_C - 2) + lam/2 (J - alpha)^2, alpha = 1 + mu/lam,
 * energy = rest_area (Psi - mu^2 / (2 lam)): the constant makes the rest
 * state's energy exactly 0 and changes no derivative. */

/* Lamé parameters for the stable form from Young's modulus E (Pa, as energy
 * per rest area here: thickness folded in) and Poisson ratio nu (plane stress,
 * lambda + mu as the stable form wants). */
void ss_membrane_lame(double young, double poisson, double *mu, double *lam);

/* Rest data of a triangle: Dm^-1 (2x2 row-major) of its rest edges in the
 * triangle's own 2D frame, and its rest area. Returns 0, or -1 if the rest
 * triangle is degenerate (then dm_inv is the identity and area 0). */
int ss_membrane_rest(const double x0[3], const double x1[3], const double x2[3],
                     double dm_inv[4], double *area);

/* x: 9 doubles (three vertices). grad: 9, hess: 81 (PSD). compression >= 1:
 * the Stable Neo-Hookean membrane; < 1: the compression-soft membrane
 * (membrane.c), c times as stiff where it is compressed. */
double ss_membrane_eval(const double x[9], const double dm_inv[4], double rest_area,
                        double mu, double lam, double compression, double *grad, double *hess);

/* ---- membrane, many faces at once (the stepping kernel) -------------------
 * Energy and gradient of the faces of `face` (n records, one 64-byte line
 * each: the offsets 3 v of the corners into the position array, Dm^-1 and
 * the rest area) at the positions x: energy[q] and the gradient
 * grad[9 q .. 9 q + 8] (corner-major, as ss_membrane_eval).
 * Faces are evaluated SS_MEMBRANE_LANES at a time by one loop the compiler
 * vectorises (no reassociation: every lane computes exactly what
 * ss_membrane_eval computes, bit for bit; a collapsed face, J = 0, is handed
 * to ss_membrane_eval). */
#define SS_MEMBRANE_LANES 8
typedef struct ss_membrane_face {
  int xo[3];      /* 3 * vertex index of each corner */
  int anchor;     /* 3 * index of its barycenter spring's anchor in bary_anchor */
  double dm_inv[4];
  double area;    /* rest area */
  double k_bary;  /* stiffness of its barycenter spring */
} ss_membrane_face;
/* Faces [q0, q1) of face (q0 a multiple of SS_MEMBRANE_LANES) in the
 * vectors of isa (isa.h; one the CPU runs): the same bits from every one.
 * With bary_anchor (else NULL), each face's barycenter spring is added to
 * its energy and to each corner's gradient, in the same pass over the same
 * gathered corners: a zero-length spring of stiffness k_bary from the
 * face's barycenter b to its anchor a = bary_anchor + anchor,
 * e = 0.5 k |b - a|^2, each corner's gradient (k / 3) (b - a) (computed as
 * ss_bary_spring). The gradients go to grad (9 per face, corner-major) if
 * not NULL; and to dof_grad if not NULL: each corner's added to
 * dof_grad[3 k ..] in face order, k = dof_of[vertex] (corners with
 * dof_of < 0 skipped): one thread adding them face by face gives each dof
 * the sum a gather of the per-face gradients in face order gives. */
void ss_membrane_eval_batch_isa(int isa, const ss_membrane_face *face, int q0, int q1,
                                const double *x, const double *bary_anchor, double mu, double lam,
                                double compression, double *energy, double *grad,
                                double *dof_grad, const int *dof_of);
/* The same, and with orient_s (else NULL) each face q's orient ratio s
 * (orient.c's face_ratio, bit for bit) from the corners it gathered: into
 * orient_s[q], from orient_n + 4 q (the unit normal and face_c; face_c 0:
 * not judged, s = orient_s0). */
void ss_membrane_eval_batch_orient_isa(int isa, const ss_membrane_face *face, int q0, int q1,
                                       const double *x, const double *bary_anchor, double mu, double lam,
                                       double compression, double *energy, double *grad,
                                       double *dof_grad, const int *dof_of, const double *orient_n,
                                       double orient_s0, double *orient_s);
/* One barycenter spring as the batch computes it: corners x (9), anchor a,
 * stiffness k; returns its energy, its gradient per corner into g3. */
static inline double ss_bary_spring(const double x[9], const double a[3], double k, double g3[3]) {
  const double dx = (x[0] + x[3] + x[6]) * SS_THIRD - a[0];
  const double dy = (x[1] + x[4] + x[7]) * SS_THIRD - a[1];
  const double dz = (x[2] + x[5] + x[8]) * SS_THIRD - a[2];
  const double k3 = k * SS_THIRD;
  g3[0] = k3 * dx, g3[1] = k3 * dy, g3[2] = k3 * dz;
  return 0.5 * k * (dx * dx + dy * dy + dz * dz);
}

/* ---- bending: dihedral hinge ------------------------------------------------
 * x: 12 doubles, vertices (e0, e1, o0, o1): the shared edge e0-e1 and the two
 * opposite vertices, o0 in the face (e0, e1, o0) and o1 in (e1, e0, o1).
 * energy = k (theta - theta0)^2 |e|^2 / A_e with theta the signed dihedral
 * angle from atan2 and A_e the rest area of the two faces (precomputed in
 * `weight` = k |e_rest|^2 / A_e). The Hessian is the Gauss-Newton part
 * 2 weight grad(theta) grad(theta)^T only (PSD by construction, exact where
 * theta = theta0); the indefinite 2 weight (theta - theta0) Hess(theta) is
 * left out (see hinge.c for why). */
double ss_hinge_angle(const double x[12]);
double ss_hinge_eval(const double x[12], double theta0, double weight, double *grad,
                     double *hess);

/* ---- projection of a small symmetric matrix to PSD ------------------------
 * In place, n <= 12, by a Jacobi eigen-decomposition (clamps eigenvalues < 0). */
void ss_project_psd(double *m, int n);

/* Eigen-decomposition of a symmetric n x n matrix (n <= 12, row-major; only
 * its symmetric part is used) by the cyclic Jacobi method: evals[n] (not
 * sorted), evecs[n*n] row-major with eigenvector k in column k. Deterministic. */
void ss_sym_eigen(const double *m, int n, double *evals, double *evecs);

/* As ss_membrane_eval, but the Hessian is the exact second derivative, NOT
 * projected (it may be indefinite): Newton's first choice (projection on
 * demand) and the tests' reference. It needs a non-degenerate current
 * triangle (J > 0): the exact Hessian of J = |f0 x f1| grows like 1/J. */
double ss_membrane_eval_raw(const double x[9], const double dm_inv[4], double rest_area,
                            double mu, double lam, double compression, double *grad, double *hess);

#endif
