/* The orientation term: skin that lies on a body cannot turn over.
 *
 * The membrane (2D Stable Neo-Hookean, membrane.c) sees only the metric of a
 * skin triangle, F^T F: a triangle rotated half a turn about one of its edges
 * (turned face down onto the body) has exactly the energy of the same
 * triangle face up. A sheet folded flat over itself (a Z crease) therefore
 * costs nothing, and on a triangle mesh its fold lines can only move by
 * bending a triangle across its interior, which the membrane resists: the
 * crease locks. That is why skin dragged into a crease during a motion did
 * not come home after it (rest error 0.7 edge lengths on the demo avatar with
 * any tether) and why faces were seen turned over at full area.
 *
 * Real skin lies on its body, face up. The term compares each simulated skin
 * face with the body's normal n under it (ss_sim_orient_normal: halfway
 * between the normal where it is anchored and the normal of the body face it
 * was bound to, each leaning on the faces under its corners where the body
 * under its barycenter is crushed: normal_under), in the current substep pose
 * (fixed during a solve, like the anchors):
 *   s = sign_f ((x1 - x0) x (x2 - x0)) . n / (2 A_f),
 * the face's area projected on the body's tangent plane over its rest area,
 * signed: 1 at rest, 0 standing on edge, -1 turned over. sign_f is +1, or -1
 * for a skin of its own wound the other way at rest (0: not judged). Energy
 *   E_f = orient A_f psi(s),  psi(s) = (s0 - s)^2 / 2 for s < s0, else 0,
 * s0 = SS_ORIENT_S0: zero for faces lying within ~80 degrees of the body's
 * tangent plane at their rest area (the usual state of a skin), so it leaves
 * the ordinary skin alone and pushes back on a face as it tilts past that,
 * harder the further it turns. orient (N/m, energy per rest area, as young).
 * s is linear in each corner: ds/dx1 = c (x2 - x0) x n, ds/dx2 = c n x
 * (x1 - x0), ds/dx0 = -(ds/dx1 + ds/dx2), c = sign_f / (2 A_f).
 * Hessian: the Gauss-Newton part orient A_f grad(s) grad(s)^T where s < s0
 * (PSD; the dropped psi'(s) Hess(s) is constant and indefinite).
 *
 * The same body cannot be entered either: a free vertex v deeper than its
 * anchor a_v under the body's surface, d = -(x_v - a_v) . n_v > 0 (n_v
 * halfway between the normals of its anchor's face and of the face it was
 * bound to), pays SS_ORIENT_DEPTH orient A_v (d / l)^2 / 2, l the mean rest
 * edge length, Hessian SS_ORIENT_DEPTH orient A_v / l^2 n n^T. Without it a
 * vertex at a convex tip (the demo's hand and sole) pushed through the plane
 * of its neighbours stays there: the mirrored cap has the same edge lengths,
 * so the membrane holds it and the soft anchor spring (orient A / l^2 is
 * ~200x the anchor stiffness 1e3 at the demo's 3 cm edges) cannot pull it back.
 *
 * Measured (`skinsim run --avatar demo --motion all --frames 720 --settle 3`):
 * orient 0: rest error rms/max 0.070 / 0.71 edges (tether 0), 0.030 / 0.73
 * (tether 3); orient 200: 0.0026 / 0.019 (tether 0), 0.0014 / 0.016 (tether 3).
 *
 * Sums in face order: deterministic. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "isa.h"
#include "sim_internal.h"
#include "ss_body_normal.h"
#include "ss_err.h"

/* The body's normal under skin face f, from `face` (the anchors now, or as
 * bound at rest): ss_body_normal.h. Inlined: out of line, its three stores
 * were read back by ss_sim_orient_normal two at a time, a load that could not
 * be forwarded, on every face of every substep. */
static inline SS_ALWAYS_INLINE void normal_under(const ss_model *m, const ss_frames *fr, const int *face, int f,
                         double n[3]) {
  body_normal_under(fr->normal, fr->area, m->body_area0, face, m->faces, m->nvert, m->nanchor, f, n);
}

/* 1 if skin face f's anchors (barycenter and corners) are all on the body
 * faces they were bound to: then both normals of ss_sim_orient_normal are the same. */
static inline int anchored_at_home(const ss_sim *sim, int f) {
  const int *now = sim->anchor_face, *home = sim->m->anchor_face0, *fv = sim->m->faces + 3 * f;
  const int nv = sim->m->nvert;
  if (sim->m->nanchor > nv && now[nv + f] != home[nv + f]) return 0;
  return now[fv[0]] == home[fv[0]] && now[fv[1]] == home[fv[1]] && now[fv[2]] == home[fv[2]];
}

/* The body's "out" under skin face f: the normal where the face is anchored
 * and the normal (in this pose) of the body face it was bound to, halfway
 * between (unit). One alone misleads: an anchor walking home near a sharp
 * edge settles on the neighbouring face, at the projection of home onto its
 * plane (110 degrees off on the demo's hand), and skin slid around a rim
 * thinner than an edge is anchored on the far side while its home is on the
 * near side. Returns 0 (not judged) where the two disagree by more than 120
 * degrees: the body turns over within the face's reach. */
int ss_sim_orient_normal(const ss_sim *sim, const ss_frames *fr, int f, double n[3]) {
  double a[3], h[3];
  normal_under(sim->m, fr, sim->anchor_face, f, a);
  if (anchored_at_home(sim, f)) /* the same inputs: the same bits */
    memcpy(h, a, sizeof h);
  else
    normal_under(sim->m, fr, sim->m->anchor_face0, f, h);
  for (int k = 0; k < 3; k++) n[k] = a[k] + h[k];
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 1.0)) return 0;
  for (int k = 0; k < 3; k++) n[k] /= len;
  return 1;
}

/* c = sign_f / (2 A_f) of face f (its rest_area > 0). */
static inline double face_c(const ss_model *m, int f) {
  return m->orient_sign[f] / (2.0 * m->rest_area[f]);
}

/* s of face f at positions xfull against the unit normal n, c = face_c; with s < S0 (the
 * only faces the term acts on) also its gradient (9, corners in face order).
 * Bit for bit the s and gradient of the formula at the head of this file. */
static inline double face_ratio(const ss_model *m, const double *xfull, int f, const double n[3],
                                double c, double grad[9]) {
  /* scalars, not arrays: no trip through the stack between the products */
  const int *fv = m->faces + 3 * f;
  const double *p0 = xfull + 3 * fv[0], *p1 = xfull + 3 * fv[1], *p2 = xfull + 3 * fv[2];
  const double a0 = p1[0] - p0[0], a1 = p1[1] - p0[1], a2 = p1[2] - p0[2]; /* e1 */
  const double b0 = p2[0] - p0[0], b1 = p2[1] - p0[1], b2 = p2[2] - p0[2]; /* e2 */
  const double n0 = n[0], n1 = n[1], n2 = n[2];
  const double d10 = b1 * n2 - b2 * n1, d11 = b2 * n0 - b0 * n2, d12 = b0 * n1 - b1 * n0; /* e2 x n */
  const double s = c * (a0 * d10 + a1 * d11 + a2 * d12);
  if (!(s < SS_ORIENT_S0)) return s;
  const double d20 = n1 * a2 - n2 * a1, d21 = n2 * a0 - n0 * a2, d22 = n0 * a1 - n1 * a0; /* n x e1 */
  grad[3] = c * d10, grad[4] = c * d11, grad[5] = c * d12;
  grad[6] = c * d20, grad[7] = c * d21, grad[8] = c * d22;
  grad[0] = -grad[3] - grad[6], grad[1] = -grad[4] - grad[7], grad[2] = -grad[5] - grad[8];
  return s;
}

/* The depth spring: SS_ORIENT_DEPTH orient per rest area, the depth in mean
 * edge lengths (a vertex one edge length deep pays a tenth of a face turned
 * on edge). Stiffer springs cost line-search halvings in the quasi-Newton
 * solve (its constant preconditioner does not hold them) and bring the skin
 * home no better. */
static double depth_weight(const ss_sim *sim, int q) {
  return SS_ORIENT_DEPTH * sim->set.orient * sim->m->vert_area[sim->m->dof_vert[q]] / (sim->m->edge_len * sim->m->edge_len);
}

int ss_model_orient_init(ss_model *m, char *err, int err_sz) {
  /* orient_sign: the model's arena, zeroed. The body's frames at rest, where
   * every anchor is on the face it was bound to (ss_sim_orient_normal's two
   * normals are then one: n = (a + a) / |a + a|, the same bits as a sim's
   * at rest). */
  ss_frames *fr = NULL;
  if (ss_frames_create(&fr, m->btopo->nface) != SS_OK)
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the body's frames at rest");
  ss_frames_update(fr, m->btopo, m->body_rest);
  const double min_area = SS_ORIENT_MIN_AREA * m->edge_len * m->edge_len;
  for (int f = 0; f < m->nface; f++) {
    /* judged: faces held on the body by a spring (not a free flap), not
     * slivers: s of a sliver swings with the smallest move of its apex, and
     * so would its stiffness (the slivers scene: aspect ~300) */
    const int *fv = m->faces + 3 * f;
    if (!(m->rest_area[f] >= min_area)) continue;
    if (m->k_face[f] == 0.0 && m->k_vert[fv[0]] == 0.0 && m->k_vert[fv[1]] == 0.0 &&
        m->k_vert[fv[2]] == 0.0)
      continue;
    double a[3], n[3], g[9];
    normal_under(m, fr, m->anchor_face0, f, a);
    for (int k = 0; k < 3; k++) n[k] = a[k] + a[k];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 1.0)) continue;
    for (int k = 0; k < 3; k++) n[k] /= len;
    m->orient_sign[f] = 1;
    double s = face_ratio(m, m->rest, f, n, face_c(m, f), g);
    m->orient_sign[f] = (signed char)(s > 0.0 ? 1 : s < 0.0 ? -1 : 0);
  }
  ss_frames_destroy(fr);
  return SS_OK;
}

/* What the term reads that is fixed during a solve, in orient_n: per
 * simulated face q (simface order) its unit body normal and, if judged,
 * face_c (else 0, with a zero normal: face_c of a judged face is not 0), and per dof k at 4 (nface + k) its vertex's
 * normal and 1 if its depth is judged. The same bits as computing them in
 * each evaluation: the anchors and the body pose do not move in a solve. */
static inline void face_normal_begin(const ss_sim *sim, const ss_frames *fr, int q) {
  const int f = sim->m->simface[q];
  double *n = sim->orient_n + 4 * (size_t)q;
  n[0] = n[1] = n[2] = n[3] = 0.0;
  if (!sim->m->orient_sign[f]) return;
  if (ss_sim_orient_normal(sim, fr, f, n)) n[3] = face_c(sim->m, f);
  else n[0] = n[1] = n[2] = 0.0;
}

#define SS_ORIENT_LANES 8

/* The length of each lane's vector nn and nn over it, in lanes (every lane
 * divided, whatever its length: the callers take only the lanes they judge). */
static inline SS_ALWAYS_INLINE void unit_lanes(const double nn[3][SS_ORIENT_LANES],
                                               double len[SS_ORIENT_LANES],
                                               double u[3][SS_ORIENT_LANES]) {
  enum { L = SS_ORIENT_LANES };
#ifdef _OPENMP
#pragma omp simd
#endif
  for (int l = 0; l < L; l++) len[l] = sqrt(nn[0][l] * nn[0][l] + nn[1][l] * nn[1][l] + nn[2][l] * nn[2][l]);
#ifdef _OPENMP
#pragma omp simd
#endif
  for (int l = 0; l < L; l++)
    for (int i = 0; i < 3; i++) u[i][l] = nn[i][l] / len[l];
}

/* face_normal_begin for faces [q0, q1) and dofs [k0, k1), SS_ORIENT_LANES at a time
 * in vector lanes: inputs gathered into lanes, one elementwise loop (the
 * same operations in the same order as face_normal_begin, and for a dof as
 * one at a time, so the same bits at any width), written back. A face
 * off the usual case (not judged, its barycenter or a corner without an
 * anchor face, or anchored away from home: two normals) is done again by
 * face_normal_begin. One face at a time, the chain of two square roots and
 * seven divisions per face, every substep, was a tenth of a 4 x 2 frame. */
static inline SS_ALWAYS_INLINE void normals_kernel(const ss_sim *sim, const ss_frames *fr, int q0, int q1,
                                                   int k0, int k1) {
  enum { L = SS_ORIENT_LANES };
  const ss_model *m = sim->m;
  const int nv = m->nvert, bary = m->nanchor > nv;
  const int *af = sim->anchor_face, *af0 = m->anchor_face0;
  const double *bn = fr->normal, *ba = fr->area;
  /* The lane loops are short and each its own: a value chosen by a select
   * is stored before it is divided by, and every division's result stored
   * on every lane, the choices left to the write-back. A division under a
   * condition is not if-converted for AVX2 (it might trap), and GCC sinks a
   * division into the branch of a select that alone uses it. */
  for (int qb = q0; qb < q1; qb += L) {
    const int cnt = q1 - qb < L ? q1 - qb : L;
    double nb[3][L], nc[3][3][L], ar[L], ar0[L], r[L], w[L], sg[L], ra[L], ok[L];
    double sv[3][L], sd[L], t[3][L], nn[3][L], len[L], u[3][L], c[L];
    for (int l = 0; l < L; l++) {
      ok[l] = 0.0;
      int b = 0, c3[3] = {0, 0, 0};
      sg[l] = 1.0, ra[l] = 1.0;
      if (l < cnt && bary) {
        const int q = qb + l, f = m->simface[q];
        const int *fv = m->faces + 3 * f;
        b = af[nv + f];
        c3[0] = af[fv[0]], c3[1] = af[fv[1]], c3[2] = af[fv[2]];
        /* anchored_at_home, every anchor on a face */
        if (m->orient_sign[f] && b >= 0 && c3[0] >= 0 && c3[1] >= 0 && c3[2] >= 0 && b == af0[nv + f] &&
            c3[0] == af0[fv[0]] && c3[1] == af0[fv[1]] && c3[2] == af0[fv[2]]) {
          ok[l] = 1.0;
          sg[l] = m->orient_sign[f], ra[l] = m->rest_area[f];
        } else {
          b = c3[0] = c3[1] = c3[2] = 0;
        }
      }
      for (int i = 0; i < 3; i++) nb[i][l] = bn[3 * (size_t)b + i];
      for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) nc[k][i][l] = bn[3 * (size_t)c3[k] + i];
      const double area0 = m->body_area0[b];
      ar[l] = ba[b], ar0[l] = area0 > 0.0 ? area0 : 1.0, w[l] = area0 > 0.0 ? 0.0 : 1.0;
    }
    /* normal_under's weight of the corners, crush_share (ss_body_normal.h):
     * its division in lanes, its branches after (w already 1 where the rest
     * area is not > 0, divided by 1.0 instead) */
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) r[l] = ar[l] / ar0[l];
    for (int l = 0; l < L; l++) w[l] = w[l] != 0.0 ? 1.0 : r[l] >= 1.0 ? 0.0 : r[l] > 0.0 ? 1.0 - r[l] : 1.0;
    /* normal_under (ss_body_normal.h): the barycenter's normal and the
     * corners' weighted, normalised where the sum is not zero */
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) {
      for (int i = 0; i < 3; i++) sv[i][l] = ((nb[i][l] + w[l] * nc[0][i][l]) + w[l] * nc[1][i][l]) + w[l] * nc[2][i][l];
      const double sl = sqrt(sv[0][l] * sv[0][l] + sv[1][l] * sv[1][l] + sv[2][l] * sv[2][l]);
      sd[l] = sl > 0.0 ? sl : 1.0; /* x / 1.0 is x: the sum as it is */
    }
#ifdef _OPENMP
#pragma omp simd
#endif
    for (int l = 0; l < L; l++) {
      for (int i = 0; i < 3; i++) t[i][l] = sv[i][l] / sd[l];
      c[l] = sg[l] / (2.0 * ra[l]); /* face_c */
    }
    /* where the barycenter's body face keeps its area (w 0), its own unit
     * normal as it is; then ss_sim_orient_normal at home, halfway between it
     * and itself (the select on its own: in a lane loop it too was made a
     * branch) */
    for (int l = 0; l < L; l++)
      for (int i = 0; i < 3; i++) {
        const double a = w[l] > 0.0 ? t[i][l] : nb[i][l];
        nn[i][l] = a + a;
      }
    unit_lanes(nn, len, u);
    for (int l = 0; l < cnt; l++) {
      if (ok[l] == 0.0) {
        face_normal_begin(sim, fr, qb + l);
        continue;
      }
      double *n = sim->orient_n + 4 * (size_t)(qb + l);
      if (len[l] > 1.0)
        n[0] = u[0][l], n[1] = u[1][l], n[2] = u[2][l], n[3] = c[l];
      else
        n[0] = n[1] = n[2] = n[3] = 0.0;
    }
  }
  /* The unit normal free vertex q (dof) is judged against for its depth
   * under the body surface at its anchor, -(x - a) . n: halfway between its
   * anchor's face and the face it was bound to. 0 (not judged) where they
   * disagree by over 120 degrees, where it has no anchor face or no spring,
   * or where either face is a sliver (its normal swings with the smallest
   * move of its corners: not trusted). */
  const double min_area = SS_ORIENT_MIN_AREA * m->edge_len * m->edge_len;
  double *nd = sim->orient_n + 4 * (size_t)m->nface;
  for (int kb = k0; kb < k1; kb += L) {
    const int cnt = k1 - kb < L ? k1 - kb : L;
    double nn[3][L], len[L], u[3][L], ok[L];
    for (int l = 0; l < L; l++) {
      int fa = 0, fh = 0;
      ok[l] = 0.0;
      if (l < cnt) {
        const int v = m->dof_vert[kb + l];
        if (af[v] >= 0 && af0[v] >= 0 && m->k_vert[v] != 0.0 && ba[af[v]] >= min_area && ba[af0[v]] >= min_area)
          ok[l] = 1.0, fa = af[v], fh = af0[v];
      }
      for (int i = 0; i < 3; i++) nn[i][l] = bn[3 * (size_t)fa + i] + bn[3 * (size_t)fh + i];
    }
    unit_lanes(nn, len, u);
    for (int l = 0; l < cnt; l++) {
      double *n = nd + 4 * (size_t)(kb + l);
      if (ok[l] != 0.0 && len[l] > 1.0)
        n[0] = u[0][l], n[1] = u[1][l], n[2] = u[2][l], n[3] = 1.0;
      else
        n[0] = n[1] = n[2] = n[3] = 0.0;
    }
  }
}

SS_ISA_VARIANTS(normals, (const ss_sim *sim, const ss_frames *fr, int q0, int q1, int k0, int k1),
                normals_kernel(sim, fr, q0, q1, k0, k1);)

/* Each face and dof its own: on the sim's threads with the same bits (once
 * per substep, a share of a frame worth both cores), in blocks of lanes.
 * Nothing with orient 0. */
void ss_sim_orient_begin(ss_sim *sim) {
  /* without the term nothing reads them (its energy and line model return
   * first); a new orient takes effect at the next substep, which calls this */
  if (!(sim->set.orient > 0.0)) return;
  const ss_frames *fr = ss_mover_frames(sim->mover);
  const int nsim = sim->m->nsimface, ndof = sim->m->ndof;
#ifdef _OPENMP
  if (sim->nthread > 1 && nsim + ndof > 256) {
    enum { B = 64 * SS_ORIENT_LANES };
    const int nbf = (nsim + B - 1) / B, nbd = (ndof + B - 1) / B;
#pragma omp parallel for schedule(static) num_threads(sim->nthread)
    for (int b = 0; b < nbf + nbd; b++) {
      if (b < nbf)
        SS_ISA_CALL(sim->isa, normals, (sim, fr, b * B, (b + 1) * B < nsim ? (b + 1) * B : nsim, 0, 0));
      else
        SS_ISA_CALL(sim->isa, normals,
                    (sim, fr, 0, 0, (b - nbf) * B, (b - nbf + 1) * B < ndof ? (b - nbf + 1) * B : ndof));
    }
    return;
  }
#endif
  SS_ISA_CALL(sim->isa, normals, (sim, fr, 0, nsim, 0, ndof));
}

/* Depth of dof q's vertex under the body at its anchor, against its cached
 * normal n (judged: n[3] != 0). */
static inline double dof_depth(const ss_sim *sim, int q, const double *xfull, const double *n) {
  const int v = sim->m->dof_vert[q];
  const double *x = xfull + 3 * v, *a = sim->anchor_pos + 3 * v;
  double d = 0.0;
  for (int k = 0; k < 3; k++) d -= (x[k] - a[k]) * n[k];
  return d;
}

static inline double judged_ratio(const ss_sim *sim, const double *xfull, const double *n, int q) {
  double gs[9];
  return n[3] == 0.0 ? SS_ORIENT_S0 : face_ratio(sim->m, xfull, sim->m->simface[q], n, n[3], gs);
}

/* s of every judged face (S0 for the rest) into orient_s: each face its own,
 * so on the sim's threads with the same bits. */
static void face_ratios(const ss_sim *sim, const double *xfull, double *os) {
  const double *on = sim->orient_n;
  const int nsim = sim->m->nsimface;
#ifdef _OPENMP
  if (sim->nthread > 1 && nsim > 256) {
#pragma omp parallel for schedule(static) num_threads(sim->nthread)
    for (int q = 0; q < nsim; q++) os[q] = judged_ratio(sim, xfull, on + 4 * (size_t)q, q);
    return;
  }
#endif
  for (int q = 0; q < nsim; q++) os[q] = judged_ratio(sim, xfull, on + 4 * (size_t)q, q);
}

typedef struct depth_ctx {
  const ss_sim *sim;
  const double *xfull;
  double *g;
} depth_ctx;

/* The depth springs of dofs [q0, q1): energy into sums[0], gradient into g. */
static void depth_block(void *ctx, int q0, int q1, double *sums) {
  const depth_ctx *c = ctx;
  const ss_sim *sim = c->sim;
  const double *nd = sim->orient_n + 4 * (size_t)sim->m->nface;
  double e = 0.0;
  for (int q = q0; q < q1; q++) {
    const double *n = nd + 4 * (size_t)q;
    if (n[3] == 0.0) continue;
    const double depth = dof_depth(sim, q, c->xfull, n);
    if (!(depth > 0.0)) continue;
    const double w = depth_weight(sim, q);
    e += 0.5 * w * depth * depth;
    if (c->g)
      for (int i = 0; i < 3; i++) c->g[3 * q + i] -= w * depth * n[i];
  }
  sums[0] = e;
}

double ss_sim_orient_energy(const ss_sim *sim, const double *xfull, double *g, int s_ready) {
  const double k = sim->set.orient;
  if (!(k > 0.0)) return 0.0;
  const double *on = sim->orient_n;
  double e = 0.0;
  /* s of all faces first (on the threads; or already, by the membrane's
   * pass over the same corners, s_ready), then, in face order on one
   * thread, the few below S0: their energy and gradient (computed again
   * with s, the same bits), summed as before */
  if (!s_ready) face_ratios(sim, xfull, sim->orient_s);
  for (int q = 0; q < sim->m->nsimface; q++) {
    if (!(sim->orient_s[q] < SS_ORIENT_S0)) continue;
    const double *n = on + 4 * (size_t)q;
    const int f = sim->m->simface[q];
    double gs[9];
    const double s = face_ratio(sim->m, xfull, f, n, n[3], gs);
    if (!(s < SS_ORIENT_S0)) continue; /* never (s is orient_s[q]): tells the compiler gs is set */
    const double w = k * sim->m->rest_area[f], d = SS_ORIENT_S0 - s;
    e += 0.5 * w * d * d;
    if (!g) continue;
    const int *fv = sim->m->faces + 3 * f;
    for (int c = 0; c < 3; c++) {
      const int j = sim->m->dof[fv[c]];
      if (j < 0) continue;
      for (int i = 0; i < 3; i++) g[3 * j + i] -= w * d * gs[3 * c + i];
    }
  }
  /* no free vertex below the body surface at its anchor: each dof its own,
   * the energy summed by blocks (par.h) */
  depth_ctx dc = {sim, xfull, g};
  double depth_e;
  ss_par_sum(sim->nthread, sim->m->ndof, 1, depth_block, &dc, sim->par_part, &depth_e);
  return e + depth_e;
}

void ss_sim_orient_hessian(const ss_sim *sim, const double *xfull, double *vals) {
  const double k = sim->set.orient;
  if (!(k > 0.0)) return;
  const double *on = sim->orient_n;
  for (int q = 0; q < sim->m->nsimface; q++) {
    const double *n = on + 4 * (size_t)q;
    if (n[3] == 0.0) continue;
    const int f = sim->m->simface[q];
    double gs[9];
    if (!(face_ratio(sim->m, xfull, f, n, n[3], gs) < SS_ORIENT_S0)) continue;
    const double w = k * sim->m->rest_area[f];
    /* the Gauss-Newton block w gs gs^T, scattered as the membrane's */
    double h81[81];
    for (int r = 0; r < 9; r++)
      for (int c = 0; c < 9; c++) h81[9 * r + c] = w * gs[r] * gs[c];
    ss_model_scatter_element(sim->m, sim->m->faces + 3 * f, 3, sim->m->face_rank + 9 * f, h81, vals);
  }
  const double *nd = on + 4 * (size_t)sim->m->nface;
  for (int q = 0; q < sim->m->ndof; q++) {
    const double *n = nd + 4 * (size_t)q;
    if (n[3] == 0.0) continue;
    if (!(dof_depth(sim, q, xfull, n) > 0.0)) continue;
    const double w = depth_weight(sim, q);
    const int diag_rank = sim->m->bcolp[q + 1] - sim->m->bcolp[q] - 1;
    for (int c1 = 0; c1 < 3; c1++)
      for (int c2 = c1; c2 < 3; c2++) vals[ss_model_slot3(sim->m, q, diag_rank, c1, c2)] += w * n[c1] * n[c2];
  }
}

/* The quasi-Newton line search's first trial (sim_internal.h). Why: the
 * solver's constant matrix A (solver_qn.c) is isotropic and holds no depth
 * spring, and the springs are one-sided and act on a third to a half of the
 * free vertices at any time on the 19k quadruped (convex body, skin in
 * tension: vertices sit a few hundredths to tenths of an edge under their
 * anchors). Along the smooth modes that A holds only by inertia and the
 * anchor springs (about 1.6 N/m against a depth spring's ~17 there), the
 * direction is 3-4 times too long: the full step was refused in 2 of 3
 * searches (accepted steps 0.27-0.42 of it), each refusal a whole energy
 * evaluation. Without the depth springs every full step is accepted, so
 * along dir the rest of E is modelled as the quadratic with E's slope at 0
 * less the springs' and its minimum at the full step,
 *   phi(a) = s_r a (1 - a / 2) + sum_v w_v / 2 max(0, d_v - a b_v)^2,
 * d_v the depth at xd, b_v = dir . n_v its rate, s_r = slope - the springs'
 * slope at 0. phi' is increasing (s_r < 0, each spring convex) and
 * piecewise linear: safeguarded Newton from a = 1 finds its root in a few
 * passes over the dofs, those out of reach of a full step (d_v <= 0 and
 * d_v - b_v <= 0: off on all of [0, 1]) skipped. */
typedef struct line_ctx {
  const ss_sim *sim;
  const double *xd, *dir;
  double a, prev; /* the step of this pass, of the last (prev < 0: none) */
} line_ctx;

/* The springs along the line of the dofs of block [q0, q1) into depth_line
 * from 3 q0 on, packed in dof order (depth, rate, stiffness), up to the
 * first of stiffness 0 or the block's end: a dof not judged or out of reach
 * of a full step (d_v and d_v - b_v both <= 0, so it stays off on all of
 * [0, 1]) is left out, and line_slope's passes, several per line search,
 * read only the springs that can act (a third to a half of the dofs); the
 * same terms in the same order, so the same sums. sums[0] the springs'
 * slope at 0. */
static void line_springs(void *ctx, int q0, int q1, double *sums) {
  const line_ctx *c = ctx;
  const ss_sim *sim = c->sim;
  const double *nd = sim->orient_n + 4 * (size_t)sim->m->nface;
  double *dl = sim->depth_line;
  double slope = 0.0;
  int j = q0; /* the next packed slot */
  for (int q = q0; q < q1; q++) {
    const double *n = nd + 4 * (size_t)q;
    if (n[3] == 0.0) continue;
    const double *x = c->xd + 3 * q, *a = sim->anchor_pos + 3 * (size_t)sim->m->dof_vert[q];
    const double *d = c->dir + 3 * q;
    const double depth = -((x[0] - a[0]) * n[0] + (x[1] - a[1]) * n[1] + (x[2] - a[2]) * n[2]);
    const double rate = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    if (!(depth > 0.0) && !(depth - rate > 0.0)) continue;
    const double w = depth_weight(sim, q);
    if (depth > 0.0) slope -= w * rate * depth;
    if (w == 0.0) continue; /* nothing along the line (line_slope's sums skip it) */
    dl[3 * j] = depth, dl[3 * j + 1] = rate, dl[3 * j + 2] = w;
    j++;
  }
  if (j < q1) dl[3 * j + 2] = 0.0; /* the end of the block's springs */
  sums[0] = slope;
}

/* At step a: sums[0] the springs' part of phi'(a), sums[1] of phi''(a),
 * sums[2] how many springs are on at a and were not at prev (or the other
 * way). */
static void line_slope(void *ctx, int q0, int q1, double *sums) {
  const line_ctx *c = ctx;
  const double *dl = c->sim->depth_line;
  double d1 = 0.0, d2 = 0.0, turned = 0.0;
  for (int q = q0; q < q1; q++) {
    const double w = dl[3 * q + 2];
    if (w == 0.0) break; /* the block's springs end (line_springs) */
    const double depth = dl[3 * q], rate = dl[3 * q + 1];
    const int on = depth - c->a * rate > 0.0;
    if (on) {
      d1 -= w * rate * (depth - c->a * rate);
      d2 += w * rate * rate;
    }
    turned += on != (depth - c->prev * rate > 0.0);
  }
  sums[0] = d1, sums[1] = d2, sums[2] = turned;
}

double ss_sim_orient_line_step(ss_sim *sim, const double *xd, const double *dir, double slope) {
  if (!(sim->set.orient > 0.0) || !(slope < 0.0)) return 1.0;
  const int ndof = sim->m->ndof;
  /* each dof its own, the sums by blocks (par.h): the same bits for any
   * thread count */
  line_ctx lc = {sim, xd, dir, 1.0, -1.0};
  double spring_slope;
  ss_par_sum(sim->nthread, ndof, 1, line_springs, &lc, sim->par_part, &spring_slope);
  const double rest_slope = slope - spring_slope;
  if (!(rest_slope < 0.0)) return 1.0; /* the springs alone drive the descent: no model */
  /* phi'(a) = s_r (1 - a) - sum_v w_v b_v max(0, d_v - a b_v); the root in
   * (0, 1) by Newton steps, each the root of the linear piece at a, kept
   * inside the bracket (else bisection). A step after which no spring
   * turned on or off landed on the root of its piece: that is the answer,
   * exact to rounding (a fixed tolerance would make the step, and the skin
   * with it, jump with the last bits of the input). */
  double lo = 0.0, hi = 1.0, a = 1.0, prev = -1.0;
  for (int it = 0; it < 64; it++) {
    double sums[3];
    lc.a = a, lc.prev = prev;
    ss_par_sum(sim->nthread, ndof, 3, line_slope, &lc, sim->par_part, sums);
    const double d1 = rest_slope * (1.0 - a) + sums[0], d2 = -rest_slope + sums[1]; /* phi', phi'' */
    if (prev >= 0.0 && sums[2] == 0.0) break; /* the last Newton step was exact */
    if (!(d1 > 0.0)) {
      if (it == 0) return 1.0; /* still descending at the full step */
      lo = a;
    } else {
      hi = a;
    }
    double next = a - d1 / d2;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi), prev = -1.0; /* bisection: no exact claim */
    else prev = a;
    a = next;
  }
  return a > 0.0 ? a : 1.0;
}
