/* The skin's membrane energy: 2D Stable Neo-Hookean on each triangle, with its
 * gradient and a positive semi-definite Hessian (doc/model.md, "Membrane").
 *
 * Model (Smith, de Goes, Kim, "Stable Neo-Hookean Flesh Simulation", ACM TOG
 * 2018, restricted to a surface in 3D as in Kim's HOBAK shells):
 *   F = [x1-x0, x2-x0] Dm^-1 (3x2, columns f0, f1), I_C = |f0|^2 + |f1|^2,
 *   J = |f0 x f1| (the area ratio, always >= 0 in 3D),
 *   Psi = mu/2 (I_C - 2) + lam/2 (J - alpha)^2,  alpha = 1 + mu/lam,
 *   energy = rest_area * (Psi - Psi_rest),  Psi_rest = lam/2 (1 - alpha)^2 = mu^2 / (2 lam):
 * the constant makes the energy of the rest state 0 (energies in statistics
 * and line searches then mean "stored elastic energy"); it changes no
 * derivative.
 * Without the paper's -mu/2 log(I_C + 1) term, alpha = 1 + mu/lam makes the
 * rest state stress free: dPsi/dF = mu F + lam (J - alpha) dJ/dF, and at
 * F = [I; 0] dJ/dF = F, so the stress is (mu + lam (1 - alpha)) F = 0.
 *
 * Lamé parameters. Linearising Psi at rest (F = I + G in the plane) gives
 *   Psi ~ mu |sym G|^2 + (lam - mu)/2 (tr G)^2,
 * i.e. linear elasticity with shear modulus mu and first Lamé parameter
 * lam - mu (the 2D analogue of Smith et al. 2018, section 3.4). So to match a
 * thin sheet of Young's modulus E and Poisson ratio nu in plane stress
 * (mu = E / (2 (1 + nu)), lambda = E nu / (1 - nu^2)) we pass lam = lambda + mu.
 *
 * Gradient: dJ/df0 = f1 x n, dJ/df1 = n x f0 (n the unit normal), mapped to
 * the 9 coordinates through dF/dx (constant: the rows of Dm^-1).
 *
 * Hessian: Psi is invariant under rotations on both sides of F, so with the
 * SVD F = U S V^T (U completed by u2 = u0 x u1 = n, V a rotation) its
 * Hessian in F-space is Q H' Q^T, Q = V (x) U, where H' is the Hessian at
 * F' = diag(s0, s1) padded with a zero row. H' splits into 1x1 and 2x2 blocks
 * with closed-form eigenpairs (k = lam (J - alpha), J = s0 s1):
 *   out-of-plane f0z:  mu + k s1/s0;     out-of-plane f1z:  mu + k s0/s1;
 *   twist (f0y - f1x)/sqrt2: mu + k;    flip (f0y + f1x)/sqrt2: mu - k;
 *   two scaling modes: eigenpairs of [[mu + lam s1^2, lam (2J - alpha)],
 *                                     [lam (2J - alpha), mu + lam s0^2]] on (f0x, f1y).
 * Negative eigenvalues are clamped to 0 and the six rank-one terms are mapped
 * to the 9x9 Hessian through dF/dx, which keeps it PSD. The out-of-plane
 * eigenvalues that blow up like 1/s as the triangle collapses are negative
 * then (J < alpha), so the clamp also keeps them finite.
 *
 * Degenerate current triangles (J = 0: collinear or coincident points): n is
 * undefined; a deterministic normal perpendicular to the longest stretched
 * direction is used (any unit n gives a valid subgradient of |f0 x f1| there),
 * and everything stays finite. "Inverted" triangles in 3D are flipped normals,
 * which J (an unsigned area ratio) does not see: the energy is symmetric. */
#include <math.h>
#include <string.h>

#include "energy.h"
#include "isa.h"
#include "ss_vec.h"

void ss_membrane_lame(double young, double poisson, double *mu, double *lam) {
  double m = young / (2.0 * (1.0 + poisson));
  double lambda_plane_stress = young * poisson / (1.0 - poisson * poisson);
  if (mu) *mu = m;
  if (lam) *lam = lambda_plane_stress + m;
}

int ss_membrane_rest(const double x0[3], const double x1[3], const double x2[3],
                     double dm_inv[4], double *area) {
  double e1[3], e2[3], c[3];
  for (int i = 0; i < 3; i++) {
    e1[i] = x1[i] - x0[i];
    e2[i] = x2[i] - x0[i];
  }
  c[0] = e1[1] * e2[2] - e1[2] * e2[1];
  c[1] = e1[2] * e2[0] - e1[0] * e2[2];
  c[2] = e1[0] * e2[1] - e1[1] * e2[0];
  double len1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  double len2sq = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  double twice_area = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  /* Relative test: a sliver with sin(angle) ~ 1e-13 has no usable 2D frame. */
  if (!(isfinite(twice_area) && isfinite(len2sq)) || len1 == 0.0 ||
      twice_area <= 1e-13 * (len1 * len1 + len2sq)) {
    dm_inv[0] = 1.0, dm_inv[1] = 0.0, dm_inv[2] = 0.0, dm_inv[3] = 1.0;
    *area = 0.0;
    return -1;
  }
  /* Own 2D frame: a along e1, b = n x a in the plane. Then
   * Dm = [[|e1|, e2.a], [0, e2.b]] with e2.b = 2 area / |e1|. */
  double e2a = (e2[0] * e1[0] + e2[1] * e1[1] + e2[2] * e1[2]) / len1;
  double e2b = twice_area / len1;
  double det = len1 * e2b; /* = twice_area > 0 */
  dm_inv[0] = e2b / det;
  dm_inv[1] = -e2a / det;
  dm_inv[2] = 0.0;
  dm_inv[3] = len1 / det;
  *area = 0.5 * twice_area;
  return 0;
}

/* ---- small vector helpers ---------------------------------------------- */

/* A deterministic unit vector perpendicular to the unit vector u. */
static void perpendicular_unit(const double u[3], double out[3]) {
  double axis[3] = {0.0, 0.0, 0.0};
  double ax = fabs(u[0]), ay = fabs(u[1]), az = fabs(u[2]);
  if (ax <= ay && ax <= az)
    axis[0] = 1.0;
  else if (ay <= az)
    axis[1] = 1.0;
  else
    axis[2] = 1.0;
  cross3(u, axis, out);
  double len = sqrt(dot3(out, out));
  for (int i = 0; i < 3; i++) out[i] /= len;
}

/* What every evaluation needs: F, its invariants, and the unit normal. */
typedef struct {
  double f[2][3]; /* columns f0, f1 of F */
  double c[3];    /* f0 x f1 */
  double ic, j;   /* I_C, J */
  double n[3];    /* unit normal (fallback when J = 0) */
} membrane_state;

/* F = Ds Dm^-1, Ds = [x1-x0, x2-x0]. */
static void membrane_state_init(const double x[9], const double dm_inv[4], membrane_state *s) {
  double e1[3], e2[3];
  for (int i = 0; i < 3; i++) {
    e1[i] = x[3 + i] - x[i];
    e2[i] = x[6 + i] - x[i];
  }
  for (int i = 0; i < 3; i++) {
    s->f[0][i] = e1[i] * dm_inv[0] + e2[i] * dm_inv[2];
    s->f[1][i] = e1[i] * dm_inv[1] + e2[i] * dm_inv[3];
  }
  cross3(s->f[0], s->f[1], s->c);
  s->ic = dot3(s->f[0], s->f[0]) + dot3(s->f[1], s->f[1]);
  s->j = sqrt(dot3(s->c, s->c));
  if (s->j > 1e-280) {
    for (int i = 0; i < 3; i++) s->n[i] = s->c[i] / s->j;
  } else {
    /* Collinear or coincident: perpendicular to the longer column, or e_z. */
    const double *longest = dot3(s->f[0], s->f[0]) >= dot3(s->f[1], s->f[1]) ? s->f[0] : s->f[1];
    double len = sqrt(dot3(longest, longest));
    if (len > 1e-280) {
      double u[3] = {longest[0] / len, longest[1] / len, longest[2] / len};
      perpendicular_unit(u, s->n);
    } else {
      s->n[0] = 0.0, s->n[1] = 0.0, s->n[2] = 1.0;
    }
  }
}

/* The coefficients of dF/dx: f_j = sum_a d[a][j] x_a. */
static void shape_derivatives(const double dm_inv[4], double d[3][2]) {
  for (int j = 0; j < 2; j++) {
    d[1][j] = dm_inv[0 * 2 + j];
    d[2][j] = dm_inv[1 * 2 + j];
    d[0][j] = -d[1][j] - d[2][j];
  }
}

static double alpha_of(double mu, double lam) { return lam > 0.0 ? 1.0 + mu / lam : 1.0; }

/* Energy and (optionally) gradient; shared by both evaluations. */
static double energy_and_gradient(const membrane_state *s, const double d[3][2],
                                  double rest_area, double mu, double lam, double *grad) {
  double alpha = alpha_of(mu, lam);
  /* The constant -lam/2 (1 - alpha)^2 = -mu^2 / (2 lam) makes the rest energy
   * exactly 0 (it changes no derivative). */
  double rest_offset = lam > 0.0 ? 0.5 * mu * mu / lam : 0.0;
  double psi = 0.5 * mu * (s->ic - 2.0) + 0.5 * lam * (s->j - alpha) * (s->j - alpha) - rest_offset;
  if (grad) {
    /* P = dPsi/dF = mu F + lam (J - alpha) [f1 x n, n x f0]. */
    double dj0[3], dj1[3], p[2][3];
    cross3(s->f[1], s->n, dj0);
    cross3(s->n, s->f[0], dj1);
    double k = lam * (s->j - alpha);
    for (int i = 0; i < 3; i++) {
      p[0][i] = mu * s->f[0][i] + k * dj0[i];
      p[1][i] = mu * s->f[1][i] + k * dj1[i];
    }
    for (int a = 0; a < 3; a++)
      for (int i = 0; i < 3; i++)
        grad[3 * a + i] = rest_area * (d[a][0] * p[0][i] + d[a][1] * p[1][i]);
  }
  return rest_area * psi;
}

/* hess += w * g g^T for a mode of F given as (df0, df1), mapped to x. */
static void add_mode(const double d[3][2], const double df[2][3], double w, double *hess) {
  double g[9];
  for (int a = 0; a < 3; a++)
    for (int i = 0; i < 3; i++) g[3 * a + i] = d[a][0] * df[0][i] + d[a][1] * df[1][i];
  for (int r = 0; r < 9; r++) {
    double wr = w * g[r];
    for (int col = r; col < 9; col++) hess[9 * r + col] += wr * g[col];
  }
}

/* The SVD of F through the eigen-decomposition of C = F^T F = [[p, q], [q, r]]:
 * V = [v0, v1] a rotation, s0 >= s1 >= 0, s1 = J / s0 so that s0 s1 = J
 * exactly, u0 = F v0 / s0 in the face's plane and u1 = n x u0. */
static void membrane_svd(const membrane_state *s, double v0[2], double v1[2], double *s0_out,
                         double *s1_out, double u0[3], double u1[3]) {
  double p = dot3(s->f[0], s->f[0]), r = dot3(s->f[1], s->f[1]), q = dot3(s->f[0], s->f[1]);
  double phi = 0.5 * atan2(2.0 * q, p - r);
  v0[0] = cos(phi), v0[1] = sin(phi);
  v1[0] = -v0[1], v1[1] = v0[0];
  double half_diff = 0.5 * (p - r);
  double lambda0 = 0.5 * (p + r) + sqrt(half_diff * half_diff + q * q);
  double s0 = sqrt(lambda0);
  double s1 = s0 > 1e-280 ? s->j / s0 : 0.0;
  if (s1 > s0) s1 = s0; /* round-off only */
  if (s0 > 1e-280) {
    for (int i = 0; i < 3; i++) u0[i] = (s->f[0][i] * v0[0] + s->f[1][i] * v0[1]) / s0;
    /* Remove the round-off component along n, renormalise. */
    double along = dot3(u0, s->n);
    for (int i = 0; i < 3; i++) u0[i] -= along * s->n[i];
    double len = sqrt(dot3(u0, u0));
    if (len > 0.5) {
      for (int i = 0; i < 3; i++) u0[i] /= len;
    } else {
      perpendicular_unit(s->n, u0);
    }
  } else {
    perpendicular_unit(s->n, u0);
  }
  cross3(s->n, u0, u1); /* u0 x u1 = n */
  *s0_out = s0;
  *s1_out = s1;
}

/* The six eigenpairs of an isotropic Psi(s0, s1)'s Hessian in F-space, mapped
 * to the 9x9 hess (zeroed here, symmetric on return): out-of-plane n v0^T
 * (ev[0]) and n v1^T (ev[1]); twist (u1 v0^T - u0 v1^T)/sqrt2 (ev[2]) and flip
 * (u1 v0^T + u0 v1^T)/sqrt2 (ev[3]); the two scaling modes on (u0 v0^T, u1
 * v1^T) from the 2x2 [[ha, hb], [hb, hd]] (ev[4..6] = ha, hd, hb). project:
 * modes of eigenvalue <= 0 are left out (PSD); else all are added (the exact
 * Hessian). */
static void membrane_modes(const double d[3][2], const double n[3], const double v0[2],
                           const double v1[2], const double u0[3], const double u1[3],
                           const double ev[7], double w, int project, double *hess) {
  memset(hess, 0, 81 * sizeof(double));
  double df[2][3];
  if (ev[0] > 0.0 || !project) {
    for (int i = 0; i < 3; i++) df[0][i] = v0[0] * n[i], df[1][i] = v0[1] * n[i];
    add_mode(d, df, w * ev[0], hess);
  }
  if (ev[1] > 0.0 || !project) {
    for (int i = 0; i < 3; i++) df[0][i] = v1[0] * n[i], df[1][i] = v1[1] * n[i];
    add_mode(d, df, w * ev[1], hess);
  }
  const double inv_sqrt2 = 0.70710678118654752440;
  if (ev[2] > 0.0 || !project) {
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 2; j++) df[j][i] = inv_sqrt2 * (v0[j] * u1[i] - v1[j] * u0[i]);
    add_mode(d, df, w * ev[2], hess);
  }
  if (ev[3] > 0.0 || !project) {
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 2; j++) df[j][i] = inv_sqrt2 * (v0[j] * u1[i] + v1[j] * u0[i]);
    add_mode(d, df, w * ev[3], hess);
  }
  /* Scaling modes on (f0x, f1y). */
  double ha = ev[4], hd = ev[5], hb = ev[6];
  double mean = 0.5 * (ha + hd), hdiff = 0.5 * (ha - hd);
  double radius = sqrt(hdiff * hdiff + hb * hb);
  double psi_angle = 0.5 * atan2(hb, hdiff);
  double cs = cos(psi_angle), sn = sin(psi_angle);
  double e = mean + radius;
  if (e > 0.0 || !project) {
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 2; j++) df[j][i] = cs * v0[j] * u0[i] + sn * v1[j] * u1[i];
    add_mode(d, df, w * e, hess);
  }
  e = mean - radius;
  if (e > 0.0 || !project) {
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 2; j++) df[j][i] = -sn * v0[j] * u0[i] + cs * v1[j] * u1[i];
    add_mode(d, df, w * e, hess);
  }
  for (int row = 0; row < 9; row++)
    for (int col = 0; col < row; col++) hess[9 * row + col] = hess[9 * col + row];
}

/* ---- compression-soft membrane (compression < 1) --------------------------
 * Skin pushed together wrinkles at a scale far below a simulation edge: a
 * mesh that resists compression as it resists stretch can only buckle in
 * folds one edge wide, which stand up from the body and turn over where the
 * body under them is crushed (linear blend skinning's inner elbow and knees).
 * With compression c < 1 the membrane is, in its principal stretches s0, s1
 * (the singular values of F) and J = s0 s1,
 *   Psi = mu_0 (s0 - 1)^2 + mu_1 (s1 - 1)^2 + l_J/2 (J - 1)^2,
 *   mu_i = mu where s_i >= 1, c mu where s_i < 1,
 *   l_J = lam - mu where J >= 1, c (lam - mu) where J < 1,
 * isotropic, zero and stress free at rest, positive elsewhere, and to first
 * order the same linear membrane as the Stable Neo-Hookean one (shear
 * modulus mu, plane-stress first Lame parameter lam - mu, see the Lame
 * parameters above) in tension, c times it in compression. Continuous first
 * derivatives (each term's slope is 0 where its modulus switches), piecewise
 * constant second ones. Gradient P = Psi_0 u0 v0^T + Psi_1 u1 v1^T; Hessian
 * from the eigensystem of an isotropic energy (Smith, de Goes, Kim 2019,
 * "Analytic Eigensystems for Isotropic Distortion Energies", restricted to a
 * surface): out-of-plane Psi_i / s_i, twist (Psi_0 + Psi_1) / (s0 + s1), flip
 * (Psi_0 - Psi_1) / (s0 - s1) (Psi_00 - Psi_01 where s0 = s1), scaling the
 * 2x2 Hessian in (s0, s1). c = 1 is the Stable Neo-Hookean membrane itself. */
typedef struct comp_law {
  double psi, p0, p1;   /* Psi, dPsi/ds0, dPsi/ds1 */
  double h00, h11, h01; /* second derivatives */
} comp_law;

static void comp_eval_law(double s0, double s1, double j, double mu, double lam, double c,
                          comp_law *o) {
  const double lj = lam - mu;
  const double m0 = s0 >= 1.0 ? mu : c * mu, m1 = s1 >= 1.0 ? mu : c * mu;
  const double lJ = j >= 1.0 ? lj : c * lj;
  o->psi = m0 * (s0 - 1.0) * (s0 - 1.0) + m1 * (s1 - 1.0) * (s1 - 1.0) + 0.5 * lJ * (j - 1.0) * (j - 1.0);
  o->p0 = 2.0 * m0 * (s0 - 1.0) + lJ * (j - 1.0) * s1;
  o->p1 = 2.0 * m1 * (s1 - 1.0) + lJ * (j - 1.0) * s0;
  o->h00 = 2.0 * m0 + lJ * s1 * s1;
  o->h11 = 2.0 * m1 + lJ * s0 * s0;
  o->h01 = lJ * (2.0 * j - 1.0);
}

/* Psi and the stress P = dPsi/dF (its columns P0, P1) of the compression-soft
 * membrane at F = [f0, f1] with J = |f0 x f1| > 0: one flat body, so that the
 * stepping kernel vectorises it; the scalar evaluation calls the same code
 * (the same bits). s0^2 is the larger eigenvalue of C = F^T F = [[p, q], [q,
 * r]], s1 = J / s0, v0 its unit eigenvector; P = F M with M = (Psi_1/s1) I +
 * (Psi_0/s0 - Psi_1/s1) v0 v0^T (= Psi_0 u0 v0^T + Psi_1 u1 v1^T). */
typedef struct comp_out {
  double psi;
  double p0x, p0y, p0z, p1x, p1y, p1z; /* the columns P0, P1 of P */
} comp_out;

static inline SS_ALWAYS_INLINE comp_out comp_stress(double f0x, double f0y, double f0z, double f1x,
                                                    double f1y, double f1z, double j, double mu,
                                                    double lam, double c) {
  /* No branch and no selection (the vectoriser gives up on several): the
   * moduli by 0/1 factors, V from the sum of the eigenvector's two
   * expressions (parallel, never opposite; zero only where C is isotropic,
   * where any V is one and the v0 term below has a zero weight). Needs J >
   * 0 (so s0 > 0); comp_eval handles collapsed faces. */
  const double p = f0x * f0x + f0y * f0y + f0z * f0z, r = f1x * f1x + f1y * f1y + f1z * f1z;
  const double q = f0x * f1x + f0y * f1y + f0z * f1z;
  const double hd = 0.5 * (p - r), rad = sqrt(hd * hd + q * q);
  const double s0 = sqrt(0.5 * (p + r) + rad);
  const double is0 = 1.0 / s0;
  const double s1 = j * is0, is1 = s0 / j;
  const double ea = hd + rad + q, eb = q + rad - hd;
  const double iel = 1.0 / sqrt(ea * ea + eb * eb + 1e-300);
  const double v0x = ea * iel, v0y = eb * iel;
  const double lj = lam - mu, cm = c * mu, cl = c * lj;
  /* 1 where stretched (x - 1 >= 0, +0 included), else 0 */
  const double t0 = 0.5 + copysign(0.5, s0 - 1.0), t1 = 0.5 + copysign(0.5, s1 - 1.0),
               tj = 0.5 + copysign(0.5, j - 1.0);
  const double m0 = cm + (mu - cm) * t0, m1 = cm + (mu - cm) * t1, lJ = cl + (lj - cl) * tj;
  comp_out o;
  o.psi = m0 * (s0 - 1.0) * (s0 - 1.0) + m1 * (s1 - 1.0) * (s1 - 1.0) + 0.5 * lJ * (j - 1.0) * (j - 1.0);
  const double d0 = 2.0 * m0 * (s0 - 1.0) + lJ * (j - 1.0) * s1;
  const double d1 = 2.0 * m1 * (s1 - 1.0) + lJ * (j - 1.0) * s0;
  /* P = F M, M = (d1/s1) I + (d0/s0 - d1/s1) v0 v0^T */
  const double a = d1 * is1, b = d0 * is0 - a;
  const double m00 = a + b * v0x * v0x, m01 = b * v0x * v0y, m11 = a + b * v0y * v0y;
  o.p0x = f0x * m00 + f1x * m01, o.p0y = f0y * m00 + f1y * m01, o.p0z = f0z * m00 + f1z * m01;
  o.p1x = f0x * m01 + f1x * m11, o.p1y = f0y * m01 + f1y * m11, o.p1z = f0z * m01 + f1z * m11;
  return o;
}

/* Energy, gradient and (projected, or exact if !project) Hessian of the
 * compression-soft membrane on face state s: energy and gradient from
 * comp_stress, the Hessian from the SVD and comp_eval_law. */
static double comp_eval(const membrane_state *s, const double d[3][2], double rest_area, double mu,
                        double lam, double c, double *grad, double *hess, int project) {
  /* the SVD (trigonometry) and the law's second derivatives only where they
   * are used: the Hessian, and the stress of a collapsed face */
  const int collapsed = !(s->j > 1e-280);
  double v0[2], v1[2], s0 = 0.0, s1 = 0.0, u0[3], u1[3];
  comp_law law = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  if (hess || collapsed) {
    membrane_svd(s, v0, v1, &s0, &s1, u0, u1);
    comp_eval_law(s0, s1, s->j, mu, lam, c, &law);
  }
  double psi, P[6];
  if (!collapsed) { /* the stepping kernel's arithmetic (the same bits) */
    const comp_out o = comp_stress(s->f[0][0], s->f[0][1], s->f[0][2], s->f[1][0], s->f[1][1],
                                   s->f[1][2], s->j, mu, lam, c);
    psi = o.psi;
    P[0] = o.p0x, P[1] = o.p0y, P[2] = o.p0z, P[3] = o.p1x, P[4] = o.p1y, P[5] = o.p1z;
  } else { /* collapsed: P = Psi_0 u0 v0^T + Psi_1 u1 v1^T, u1 = n x u0 (no 1/s1) */
    psi = law.psi;
    for (int i = 0; i < 3; i++) {
      P[i] = law.p0 * u0[i] * v0[0] + law.p1 * u1[i] * v1[0];
      P[3 + i] = law.p0 * u0[i] * v0[1] + law.p1 * u1[i] * v1[1];
    }
  }
  if (grad)
    for (int a = 0; a < 3; a++)
      for (int i = 0; i < 3; i++) grad[3 * a + i] = rest_area * (d[a][0] * P[i] + d[a][1] * P[3 + i]);
  if (hess) {
    double ev[7];
    ev[0] = s0 > 1e-280 ? law.p0 / s0 : law.h00;
    ev[1] = s1 > 0.0 ? law.p1 / s1 : (project ? 0.0 : -INFINITY);
    ev[2] = s0 + s1 > 1e-280 ? (law.p0 + law.p1) / (s0 + s1) : law.h00;
    ev[3] = s0 - s1 > 1e-8 * (s0 > 1.0 ? s0 : 1.0) ? (law.p0 - law.p1) / (s0 - s1) : law.h00 - law.h01;
    ev[4] = law.h00, ev[5] = law.h11, ev[6] = law.h01;
    membrane_modes(d, s->n, v0, v1, u0, u1, ev, rest_area, project, hess);
  }
  return rest_area * psi;
}

double ss_membrane_eval(const double x[9], const double dm_inv[4], double rest_area, double mu,
                        double lam, double compression, double *grad, double *hess) {
  membrane_state s;
  double d[3][2];
  membrane_state_init(x, dm_inv, &s);
  shape_derivatives(dm_inv, d);
  if (compression < 1.0) return comp_eval(&s, d, rest_area, mu, lam, compression, grad, hess, 1);
  double energy = energy_and_gradient(&s, d, rest_area, mu, lam, grad);
  if (!hess) return energy;
  double v0[2], v1[2], s0, s1, u0[3], u1[3];
  membrane_svd(&s, v0, v1, &s0, &s1, u0, u1);
  double alpha = alpha_of(mu, lam);
  double k = lam * (s.j - alpha);
  double ev[7];
  /* Out-of-plane f0z: mu + k s1/s0 (s1/s0 in [0, 1]; 1 in the limit F = 0). */
  double ratio01 = s0 > 1e-280 ? s1 / s0 : 1.0;
  ev[0] = mu + k * ratio01;
  /* Out-of-plane f1z: mu + k s0/s1, evaluated as (mu s1 + k s0) / s1 so that
   * s1 -> 0 (where k < 0) clamps without dividing by zero. */
  double numer = mu * s1 + k * s0;
  ev[1] = numer > 0.0 && s1 > 0.0 ? numer / s1 : 0.0;
  /* Twist and flip on (f0y, f1x). */
  ev[2] = mu + k;
  ev[3] = mu - k;
  /* Scaling modes on (f0x, f1y). */
  ev[4] = mu + lam * s1 * s1, ev[5] = mu + lam * s0 * s0, ev[6] = lam * (2.0 * s.j - alpha);
  membrane_modes(d, s.n, v0, v1, u0, u1, ev, rest_area, 1, hess);
  return energy;
}

/* The exact F-space Hessian, assembled directly (not through the SVD):
 *   d2Psi/dF2 = mu I6 + lam gJ gJ^T + lam (J - alpha) d2J/dF2,
 *   d2J/dF2 = A^T (I - n n^T) A / J + [[0, -[n]x], [[n]x, 0]],
 * A = [-[f1]x, [f0]x] (dc/dF for c = f0 x f1), gJ = [f1 x n; n x f0]. */
double ss_membrane_eval_raw(const double x[9], const double dm_inv[4], double rest_area,
                            double mu, double lam, double compression, double *grad, double *hess) {
  membrane_state s;
  double d[3][2];
  membrane_state_init(x, dm_inv, &s);
  shape_derivatives(dm_inv, d);
  if (compression < 1.0) return comp_eval(&s, d, rest_area, mu, lam, compression, grad, hess, 0);
  double energy = energy_and_gradient(&s, d, rest_area, mu, lam, grad);
  if (!hess) return energy;

  double alpha = alpha_of(mu, lam);
  double k = lam * (s.j - alpha);
  double hf[6][6];
  double gj[6], a[3][6], pa[3][6];
  cross3(s.f[1], s.n, gj);
  cross3(s.n, s.f[0], gj + 3);
  /* A = [-[f1]x, [f0]x]; [v]x has rows (0,-v2,v1), (v2,0,-v0), (-v1,v0,0). */
  for (int blk = 0; blk < 2; blk++) {
    const double *v = blk == 0 ? s.f[1] : s.f[0];
    double sign = blk == 0 ? -1.0 : 1.0;
    double m[3][3] = {{0.0, -v[2], v[1]}, {v[2], 0.0, -v[0]}, {-v[1], v[0], 0.0}};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) a[i][3 * blk + j] = sign * m[i][j];
  }
  for (int col = 0; col < 6; col++) {
    double na = s.n[0] * a[0][col] + s.n[1] * a[1][col] + s.n[2] * a[2][col];
    for (int i = 0; i < 3; i++) pa[i][col] = a[i][col] - s.n[i] * na;
  }
  double nx[3][3] = {{0.0, -s.n[2], s.n[1]}, {s.n[2], 0.0, -s.n[0]}, {-s.n[1], s.n[0], 0.0}};
  for (int r = 0; r < 6; r++) {
    for (int c = 0; c < 6; c++) {
      double apa = a[0][r] * pa[0][c] + a[1][r] * pa[1][c] + a[2][r] * pa[2][c];
      double bilinear = 0.0;
      if (r < 3 && c >= 3) bilinear = -nx[r][c - 3];
      if (r >= 3 && c < 3) bilinear = nx[r - 3][c];
      hf[r][c] = (r == c ? mu : 0.0) + lam * gj[r] * gj[c] + k * (apa / s.j + bilinear);
    }
  }
  /* H_x[a i][b l] = sum_{j,m} d[a][j] d[b][m] hf[3j + i][3m + l]. */
  for (int pa_ = 0; pa_ < 3; pa_++)
    for (int i = 0; i < 3; i++)
      for (int pb = 0; pb < 3; pb++)
        for (int l = 0; l < 3; l++) {
          double sum = 0.0;
          for (int j = 0; j < 2; j++)
            for (int m = 0; m < 2; m++) sum += d[pa_][j] * d[pb][m] * hf[3 * j + i][3 * m + l];
          hess[9 * (3 * pa_ + i) + 3 * pb + l] = rest_area * sum;
        }
  return energy;
}

/* ---- the batch kernel ------------------------------------------------------
 * The same arithmetic as membrane_state_init + energy_and_gradient, in the
 * same order, on SS_MEMBRANE_LANES faces per loop: gathered into lanes, one
 * `omp simd` loop (elementwise only: vectorising changes no bit), results
 * written per lane. The normal n = c / J of a collapsed face (J <= 1e-280)
 * needs the fallback of membrane_state_init: such lanes are recomputed by
 * ss_membrane_eval. */
/* The kernel, specialised by the constant `soft` (compression-soft when 1;
 * then compression is c): the Stable Neo-Hookean body as it was, or
 * comp_stress; and by `bary` (1: each face's barycenter spring added, as
 * ss_bary_spring, from the corners already gathered). */
static inline SS_ALWAYS_INLINE void batch_kernel(const ss_membrane_face *face, int q0, int q1,
                                                 const double *x, const double *bary_anchor,
                                                 double mu, double lam, double compression,
                                                 double *energy, double *grad, double *dof_grad,
                                                 const int *dof_of, const double *orient_n,
                                                 double orient_s0, double *orient_s, const int soft,
                                                 const int bary, const int orient) {
  enum { L = SS_MEMBRANE_LANES };
  const double alpha = alpha_of(mu, lam);
  const double rest_offset = lam > 0.0 ? 0.5 * mu * mu / lam : 0.0;
  for (int qb = q0; qb < q1; qb += L) {
    const int m = q1 - qb < L ? q1 - qb : L;
    double xs[9][L], dm[4][L], area[L], en[L], gr[9][L];
    double as[3][L], kb[L], eb[L], gb[3][L]; /* barycenter springs (bary) */
    double jl[L]; /* J per lane: a flag array of ints would stop the vectoriser */
    double on[4][L], os[L]; /* the orient term's normal and face_c, its s (orient) */
    /* Gathered and scattered element by element, written out: at -O2 GCC
     * kept the loops over three coordinates as loops (a compare and a branch
     * per element, a sixth of the kernel's time in the sim). */
    /* Row by row, each row's lanes written together: GCC builds each row
     * of lanes in registers and stores it whole, where lane by lane it
     * stored scalars that the simd loop then read back as rows (2% of the
     * kernel's time on the 19k quadruped). */
    const double *xc[3][L], *ac[L];
    const ss_membrane_face *fl[L];
    for (int l = 0; l < L; l++) {
      const ss_membrane_face *fc = face + qb + (l < m ? l : 0);
      fl[l] = fc;
      xc[0][l] = x + fc->xo[0], xc[1][l] = x + fc->xo[1], xc[2][l] = x + fc->xo[2];
      if (bary) ac[l] = bary_anchor + fc->anchor;
    }
    for (int c = 0; c < 3; c++)
      for (int i = 0; i < 3; i++)
        for (int l = 0; l < L; l++) xs[3 * c + i][l] = xc[c][l][i];
    for (int i = 0; i < 4; i++)
      for (int l = 0; l < L; l++) dm[i][l] = fl[l]->dm_inv[i];
    for (int l = 0; l < L; l++) area[l] = fl[l]->area;
    if (bary) {
      for (int i = 0; i < 3; i++)
        for (int l = 0; l < L; l++) as[i][l] = ac[l][i];
      for (int l = 0; l < L; l++) kb[l] = fl[l]->k_bary;
    }
    if (orient) {
      const double *onb = orient_n + 4 * (size_t)qb;
      for (int i = 0; i < 4; i++)
        for (int l = 0; l < L; l++) on[i][l] = onb[4 * (l < m ? l : 0) + i];
    }
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) {
      /* no inner loops: the vectoriser wants one flat body */
      const double e1x = xs[3][l] - xs[0][l], e1y = xs[4][l] - xs[1][l], e1z = xs[5][l] - xs[2][l];
      const double e2x = xs[6][l] - xs[0][l], e2y = xs[7][l] - xs[1][l], e2z = xs[8][l] - xs[2][l];
      const double d10 = dm[0][l], d11 = dm[1][l], d20 = dm[2][l], d21 = dm[3][l];
      const double f0x = e1x * d10 + e2x * d20, f0y = e1y * d10 + e2y * d20, f0z = e1z * d10 + e2z * d20;
      const double f1x = e1x * d11 + e2x * d21, f1y = e1y * d11 + e2y * d21, f1z = e1z * d11 + e2z * d21;
      const double cx = f0y * f1z - f0z * f1y, cy = f0z * f1x - f0x * f1z, cz = f0x * f1y - f0y * f1x;
      const double ic = (f0x * f0x + f0y * f0y + f0z * f0z) + (f1x * f1x + f1y * f1y + f1z * f1z);
      const double j = sqrt(cx * cx + cy * cy + cz * cz);
      jl[l] = j;
      const double nx = cx / j, ny = cy / j, nz = cz / j;
      double psi, p0x, p0y, p0z, p1x, p1y, p1z;
      if (soft) {
        const comp_out o = comp_stress(f0x, f0y, f0z, f1x, f1y, f1z, j, mu, lam, compression);
        psi = o.psi, p0x = o.p0x, p0y = o.p0y, p0z = o.p0z, p1x = o.p1x, p1y = o.p1y, p1z = o.p1z;
      } else {
        psi = 0.5 * mu * (ic - 2.0) + 0.5 * lam * (j - alpha) * (j - alpha) - rest_offset;
        /* dJ/df0 = f1 x n, dJ/df1 = n x f0 */
        const double a0x = f1y * nz - f1z * ny, a0y = f1z * nx - f1x * nz, a0z = f1x * ny - f1y * nx;
        const double a1x = ny * f0z - nz * f0y, a1y = nz * f0x - nx * f0z, a1z = nx * f0y - ny * f0x;
        const double k = lam * (j - alpha);
        p0x = mu * f0x + k * a0x, p0y = mu * f0y + k * a0y, p0z = mu * f0z + k * a0z;
        p1x = mu * f1x + k * a1x, p1y = mu * f1y + k * a1y, p1z = mu * f1z + k * a1z;
      }
      const double d00 = -d10 - d20, d01 = -d11 - d21;
      const double ar = area[l];
      gr[0][l] = ar * (d00 * p0x + d01 * p1x);
      gr[1][l] = ar * (d00 * p0y + d01 * p1y);
      gr[2][l] = ar * (d00 * p0z + d01 * p1z);
      gr[3][l] = ar * (d10 * p0x + d11 * p1x);
      gr[4][l] = ar * (d10 * p0y + d11 * p1y);
      gr[5][l] = ar * (d10 * p0z + d11 * p1z);
      gr[6][l] = ar * (d20 * p0x + d21 * p1x);
      gr[7][l] = ar * (d20 * p0y + d21 * p1y);
      gr[8][l] = ar * (d20 * p0z + d21 * p1z);
      en[l] = ar * psi;
      if (orient) { /* orient.c's face_ratio: c ((x1 - x0) . ((x2 - x0) x n)) */
        const double n0 = on[0][l], n1 = on[1][l], n2 = on[2][l];
        const double w0 = e2y * n2 - e2z * n1, w1 = e2z * n0 - e2x * n2, w2 = e2x * n1 - e2y * n0;
        os[l] = on[3][l] * (e1x * w0 + e1y * w1 + e1z * w2);
      }
      if (bary) { /* ss_bary_spring's arithmetic */
        const double bx = (xs[0][l] + xs[3][l] + xs[6][l]) * SS_THIRD - as[0][l];
        const double by = (xs[1][l] + xs[4][l] + xs[7][l]) * SS_THIRD - as[1][l];
        const double bz = (xs[2][l] + xs[5][l] + xs[8][l]) * SS_THIRD - as[2][l];
        const double k = kb[l], k3 = k * SS_THIRD;
        const double gx = k3 * bx, gy = k3 * by, gz = k3 * bz;
        gb[0][l] = gx, gb[1][l] = gy, gb[2][l] = gz;
        eb[l] = 0.5 * k * (bx * bx + by * by + bz * bz);
        en[l] += eb[l];
        gr[0][l] += gx, gr[1][l] += gy, gr[2][l] += gz;
        gr[3][l] += gx, gr[4][l] += gy, gr[5][l] += gz;
        gr[6][l] += gx, gr[7][l] += gy, gr[8][l] += gz;
      }
    }
    for (int l = 0; l < m; l++) {
      if (!(jl[l] > 1e-280)) {
        const ss_membrane_face *fc = face + qb + l;
        double x9[9], g9[9];
        for (int c = 0; c < 3; c++)
          for (int i = 0; i < 3; i++) x9[3 * c + i] = x[fc->xo[c] + i];
        en[l] = ss_membrane_eval(x9, fc->dm_inv, fc->area, mu, lam, soft ? compression : 1.0, g9, NULL);
        for (int r = 0; r < 9; r++) gr[r][l] = g9[r];
        if (bary) {
          en[l] += eb[l];
          for (int r = 0; r < 9; r++) gr[r][l] += gb[r % 3][l];
        }
      }
      energy[qb + l] = en[l];
      if (orient) orient_s[qb + l] = on[3][l] == 0.0 ? orient_s0 : os[l]; /* not judged: s0 */
    }
    if (grad) {
      double *gout = grad + 9 * (size_t)qb;
      for (int l = 0; l < m; l++)
        for (int r = 0; r < 9; r++) gout[9 * l + r] = gr[r][l];
    }
    if (dof_grad)
      for (int l = 0; l < m; l++) {
        const ss_membrane_face *fc = face + qb + l;
        const int k0 = dof_of[fc->xo[0] / 3], k1 = dof_of[fc->xo[1] / 3], k2 = dof_of[fc->xo[2] / 3];
        if (k0 >= 0) {
          double *gk = dof_grad + 3 * (size_t)k0;
          gk[0] += gr[0][l], gk[1] += gr[1][l], gk[2] += gr[2][l];
        }
        if (k1 >= 0) {
          double *gk = dof_grad + 3 * (size_t)k1;
          gk[0] += gr[3][l], gk[1] += gr[4][l], gk[2] += gr[5][l];
        }
        if (k2 >= 0) {
          double *gk = dof_grad + 3 * (size_t)k2;
          gk[0] += gr[6][l], gk[1] += gr[7][l], gk[2] += gr[8][l];
        }
      }
  }
}

/* The kernel in each vector width (isa.h), specialised by its three
 * constants: the same bits from each width. */
#define SS_BATCH_ARGS(soft, bary, orient)                                                                    \
  face, q0, q1, x, bary ? bary_anchor : NULL, mu, lam, soft ? compression : 1.0, energy, grad, dof_grad, dof_of, \
      orient_n, orient_s0, orient_s, soft, bary, orient
static inline SS_ALWAYS_INLINE void batch_dispatch(const ss_membrane_face *face, int q0, int q1,
                                                   const double *x, const double *bary_anchor,
                                                   double mu, double lam, double compression,
                                                   double *energy, double *grad, double *dof_grad,
                                                   const int *dof_of, const double *orient_n,
                                                   double orient_s0, double *orient_s) {
  const int soft = compression < 1.0, bary = bary_anchor != NULL;
  if (orient_s) {
    if (soft && bary) batch_kernel(SS_BATCH_ARGS(1, 1, 1));
    else if (soft) batch_kernel(SS_BATCH_ARGS(1, 0, 1));
    else if (bary) batch_kernel(SS_BATCH_ARGS(0, 1, 1));
    else batch_kernel(SS_BATCH_ARGS(0, 0, 1));
  } else {
    if (soft && bary) batch_kernel(SS_BATCH_ARGS(1, 1, 0));
    else if (soft) batch_kernel(SS_BATCH_ARGS(1, 0, 0));
    else if (bary) batch_kernel(SS_BATCH_ARGS(0, 1, 0));
    else batch_kernel(SS_BATCH_ARGS(0, 0, 0));
  }
}
SS_ISA_VARIANTS(batch,
                (const ss_membrane_face *face, int q0, int q1, const double *x, const double *bary_anchor,
                 double mu, double lam, double compression, double *energy, double *grad, double *dof_grad,
                 const int *dof_of, const double *orient_n, double orient_s0, double *orient_s),
                batch_dispatch(face, q0, q1, x, bary_anchor, mu, lam, compression, energy, grad, dof_grad,
                               dof_of, orient_n, orient_s0, orient_s);)

void ss_membrane_eval_batch_isa(int isa, const ss_membrane_face *face, int q0, int q1,
                                const double *x, const double *bary_anchor, double mu, double lam,
                                double compression, double *energy, double *grad,
                                double *dof_grad, const int *dof_of) {
  SS_ISA_CALL(isa, batch,
              (face, q0, q1, x, bary_anchor, mu, lam, compression, energy, grad, dof_grad, dof_of, NULL, 0.0, NULL));
}

void ss_membrane_eval_batch_orient_isa(int isa, const ss_membrane_face *face, int q0, int q1,
                                       const double *x, const double *bary_anchor, double mu, double lam,
                                       double compression, double *energy, double *grad,
                                       double *dof_grad, const int *dof_of, const double *orient_n,
                                       double orient_s0, double *orient_s) {
  SS_ISA_CALL(isa, batch,
              (face, q0, q1, x, bary_anchor, mu, lam, compression, energy, grad, dof_grad, dof_of, orient_n,
               orient_s0, orient_s));
}
