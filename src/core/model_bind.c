/* The skin's model, built once at create: anchors bound to the body at rest,
 * the face mask's split of vertices into free / pinned / followers, lumped
 * masses, anchor spring stiffnesses, membrane rest data and bending hinges.
 *
 * Binding (doc/model.md, "Anchor springs"): a skin that is a copy of the body
 * anchors each vertex at its own corner of the first body face using it that
 * is not a sliver (else the first at all)
 * (canonical coordinates (0,0), (1,0) or (0,1)) and each face barycenter at
 * (1/3, 1/3) of the same face: exact, no search. A separate skin mesh is bound
 * by Euclidean closest point on the body at rest (the BVH), once.
 *
 * Stiffness is per rest area: a vertex spring gets k A_v, a barycenter spring
 * k A_f, where A_v is the lumped area (a third of each adjacent face). With
 * barycenter anchors on, both halve, so that the total stiffness of a patch
 * stays k times its area. Masses are lumped the same way: density A_v.
 *
 * Hinges (bending on): each interior skin edge shared by two faces of
 * opposite orientation along it, at least one of them simulated and a free
 * vertex among the four (so the border of a masked region is clamped to the
 * body, not hinged); weight = k |e|^2 / (A_0 + A_1) at rest and theta0 the
 * rest dihedral angle, so a curved rest shape has no bending stress. */
#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "energy.h"
#include "model.h"
#include "ss_err.h"

/* A separate skin's vertex v, bound by closest point: its rest offset from its
 * anchor in the anchor face's frame (ss_sim_face_frame), so that a vertex
 * that follows the body (outside the simulated region, or on a rigid piece)
 * keeps its height over it instead of dropping onto it. */
static void follow_offset(ss_model *m, const double *body_rest, int v) {
  double *off = m->follow_off + 3 * v, t1[3], t2[3], n[3], a[3];
  off[0] = off[1] = off[2] = 0.0;
  const int f = m->anchor_face0[v];
  if (f < 0) return;
  const int *c = m->btopo->face_vert + 3 * f;
  const double *p0 = body_rest + 3 * c[0], *p1 = body_rest + 3 * c[1], *p2 = body_rest + 3 * c[2];
  double e1[3], e2[3];
  for (int i = 0; i < 3; i++) e1[i] = p1[i] - p0[i], e2[i] = p2[i] - p0[i];
  if (!ss_sim_face_frame(e1, e2, t1, t2, n)) return;
  const double *uv = m->anchor_uv0 + 2 * v;
  for (int i = 0; i < 3; i++) a[i] = m->rest[3 * v + i] - (p0[i] + uv[0] * e1[i] + uv[1] * e2[i]);
  off[0] = a[0] * t1[0] + a[1] * t1[1] + a[2] * t1[2];
  off[1] = a[0] * t2[0] + a[1] * t2[1] + a[2] * t2[2];
  off[2] = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
}

int ss_sim_face_frame(const double e1[3], const double e2[3], double t1[3], double t2[3],
                      double n[3]) {
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  if (!(ln > 0.0) || !(l1 > 0.0) || !isfinite(ln)) return 0;
  for (int i = 0; i < 3; i++) n[i] /= ln, t1[i] = e1[i] / l1;
  t2[0] = n[1] * t1[2] - n[2] * t1[1];
  t2[1] = n[2] * t1[0] - n[0] * t1[2];
  t2[2] = n[0] * t1[1] - n[1] * t1[0];
  return 1;
}

int ss_model_bind(ss_model *m, const ss_sim_mesh *skin, const double *body_rest, char *err,
                int err_sz) {
  int nv = m->nvert, nf = m->nface;
  for (int a = 0; a < m->nanchor; a++) {
    m->anchor_face0[a] = -1;
    m->anchor_uv0[2 * a] = m->anchor_uv0[2 * a + 1] = 0.0;
  }
  if (!skin) {
    static const double corner_uv[3][2] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
    /* A vertex is bound at its corner of the first body face using it that
     * is not a sliver (rest area at least SS_ORIENT_MIN_AREA mean squared
     * edges; else the first face at all). The point is the same whichever
     * face; the face is where the tether walks it home, and a sliver's
     * plane swings with the last bits of its apex: anchors going home into
     * one landed at coordinates that differed by 5e-6 between Newton and
     * quasi-Newton after two frames (slivers scene, aspect ~300), and the
     * two solvers parted by 3e-3 edge lengths within ten frames. */
    double *area = malloc((size_t)(nf ? nf : 1) * sizeof *area);
    if (!area) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory binding the skin");
    double e2 = 0.0;
    for (int f = 0; f < nf; f++) {
      const double *p0 = body_rest + 3 * m->faces[3 * f], *p1 = body_rest + 3 * m->faces[3 * f + 1],
                   *p2 = body_rest + 3 * m->faces[3 * f + 2];
      double u[3], w[3], n[3];
      for (int i = 0; i < 3; i++) u[i] = p1[i] - p0[i], w[i] = p2[i] - p0[i];
      n[0] = u[1] * w[2] - u[2] * w[1], n[1] = u[2] * w[0] - u[0] * w[2], n[2] = u[0] * w[1] - u[1] * w[0];
      area[f] = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int i = 0; i < 3; i++) e2 += (u[i] * u[i] + w[i] * w[i] + (w[i] - u[i]) * (w[i] - u[i])) / 3.0;
    }
    const double min_area = SS_ORIENT_MIN_AREA * (nf ? e2 / nf : 0.0);
    for (int pass = 0; pass < 2; pass++)
      for (int f = 0; f < nf; f++) {
        if (pass == 0 && !(area[f] >= min_area)) continue;
        for (int c = 0; c < 3; c++) {
          int v = m->faces[3 * f + c];
          if (m->anchor_face0[v] >= 0) continue;
          m->anchor_face0[v] = f;
          m->anchor_uv0[2 * v] = corner_uv[c][0];
          m->anchor_uv0[2 * v + 1] = corner_uv[c][1];
        }
      }
    free(area);
    if (m->set.barycenter_anchors)
      for (int f = 0; f < nf; f++) {
        m->anchor_face0[nv + f] = f;
        m->anchor_uv0[2 * (nv + f)] = m->anchor_uv0[2 * (nv + f) + 1] = 1.0 / 3.0;
      }
    return SS_OK;
  }
  int status = ss_sim_model_bvh(m, body_rest);
  if (status != SS_OK) return ss_fail(err, err_sz, status, "cannot build the body's BVH to bind the skin");
  const ss_bvh *bvh = m->bvh_rest;
  for (int a = 0; a < m->nanchor; a++) {
    double p[3];
    if (a < nv) {
      memcpy(p, m->rest + 3 * a, sizeof p);
    } else {
      const int *fv = m->faces + 3 * (a - nv);
      for (int i = 0; i < 3; i++)
        p[i] = (m->rest[3 * fv[0] + i] + m->rest[3 * fv[1] + i] + m->rest[3 * fv[2] + i]) / 3.0;
    }
    ss_bvh_closest(bvh, body_rest, p, &m->anchor_face0[a], m->anchor_uv0 + 2 * a);
    if (a < nv) follow_offset(m, body_rest, a);
  }
  return SS_OK;
}

/* Hinges from sorted half-edges: key (min, max) vertex, then face. */
typedef struct {
  int lo, hi, face, corner;
} half_edge;

static int cmp_half_edge(const void *pa, const void *pb) {
  const half_edge *a = pa, *b = pb;
  if (a->lo != b->lo) return (a->lo > b->lo) - (a->lo < b->lo);
  if (a->hi != b->hi) return (a->hi > b->hi) - (a->hi < b->hi);
  return (a->face > b->face) - (a->face < b->face);
}

static int build_hinges(ss_model *m, char *err, int err_sz) {
  int nf = m->nface;
  half_edge *he = malloc(3 * (size_t)(nf ? nf : 1) * sizeof *he);
  if (!he) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory building hinges");
  int nhe = 0;
  for (int f = 0; f < nf; f++) {
    if (m->rest_area[f] <= 0.0) continue;
    for (int c = 0; c < 3; c++) {
      int a = m->faces[3 * f + c], b = m->faces[3 * f + (c + 1) % 3];
      if (a == b) continue;
      he[nhe].lo = a < b ? a : b;
      he[nhe].hi = a < b ? b : a;
      he[nhe].face = f;
      he[nhe].corner = c;
      nhe++;
    }
  }
  qsort(he, (size_t)nhe, sizeof *he, cmp_half_edge);
  /* Count, then fill: an edge with exactly two opposite half-edges. */
  int count = 0;
  for (int pass = 0; pass < 2; pass++) {
    int e = 0;
    for (int q = 0; q < nhe;) {
      int r = q + 1;
      while (r < nhe && he[r].lo == he[q].lo && he[r].hi == he[q].hi) r++;
      if (r - q == 2) {
        const half_edge *h0 = &he[q], *h1 = &he[q + 1];
        const int *f0 = m->faces + 3 * h0->face, *f1 = m->faces + 3 * h1->face;
        int e0 = f0[h0->corner], e1 = f0[(h0->corner + 1) % 3], o0 = f0[(h0->corner + 2) % 3];
        int opposite = f1[h1->corner] == e1 && f1[(h1->corner + 1) % 3] == e0;
        int o1 = f1[(h1->corner + 2) % 3];
        int any_free = m->dof[e0] >= 0 || m->dof[e1] >= 0 || m->dof[o0] >= 0 || m->dof[o1] >= 0;
        int simulated = m->mask[h0->face] || m->mask[h1->face];
        if (opposite && any_free && simulated && o0 != o1) {
          if (pass == 1) {
            int *hv = m->hinge_vert + 4 * e;
            hv[0] = e0, hv[1] = e1, hv[2] = o0, hv[3] = o1;
            double x12[12];
            for (int c = 0; c < 4; c++) memcpy(x12 + 3 * c, m->rest + 3 * hv[c], 3 * sizeof(double));
            double el2 = 0.0;
            for (int i = 0; i < 3; i++) el2 += (x12[3 + i] - x12[i]) * (x12[3 + i] - x12[i]);
            m->hinge_theta0[e] = ss_hinge_angle(x12);
            m->hinge_weight[e] =
                m->set.bending * el2 / (m->rest_area[h0->face] + m->rest_area[h1->face]);
          }
          e++;
        }
      }
      q = r;
    }
    if (pass == 0) {
      count = e;
      m->nhinge = count; /* <= nhinge_max, the hinge arrays' size (sim_internal.h) */
      assert(count <= m->nhinge_max);
    }
  }
  free(he);
  return SS_OK;
}

void ss_model_build_material(ss_model *m) {
  const int nv = m->nvert, nf = m->nface;
  const ss_sim_settings *set = &m->set;
  ss_membrane_lame(set->young, set->poisson, &m->mu, &m->lam);
  double area_sum = 0.0;
  for (int f = 0; f < nf; f++) area_sum += m->rest_area[f];
  /* A vertex whose faces all have zero area still needs a little mass. */
  double mass_floor = 1e-6 * set->density * area_sum / nf;
  for (int v = 0; v < nv; v++) m->mass[v] = fmax(set->density * m->vert_area[v], mass_floor);
  /* Springs: vertices (free only) and barycenters of faces with a free corner. */
  double share = set->barycenter_anchors ? 0.5 : 1.0;
  for (int f = 0; f < nf; f++) {
    const int *fv = m->faces + 3 * f;
    int any_free = m->dof[fv[0]] >= 0 || m->dof[fv[1]] >= 0 || m->dof[fv[2]] >= 0;
    int has_area = m->rest_area[f] > 0.0;
    /* A zero-area face represents no skin: no spring. */
    m->k_face[f] = set->barycenter_anchors && any_free && has_area
                         ? share * set->anchor_stiffness * m->rest_area[f] : 0.0;
  }
  for (int v = 0; v < nv; v++)
    m->k_vert[v] = m->dof[v] >= 0 ? share * set->anchor_stiffness * m->vert_area[v] : 0.0;
}

int ss_model_build_kinds(ss_model *m, char *err, int err_sz) {
  int nv = m->nvert, nf = m->nface;
  const ss_sim_settings *set = &m->set;
  /* Rest data and lumped areas. */
  double edge_sum = 0.0, area_sum = 0.0;
  int edge_count = 0;
  memset(m->vert_area, 0, (size_t)nv * sizeof(double));
  for (int f = 0; f < nf; f++) {
    const int *fv = m->faces + 3 * f;
    const double *p0 = m->rest + 3 * fv[0], *p1 = m->rest + 3 * fv[1], *p2 = m->rest + 3 * fv[2];
    ss_membrane_rest(p0, p1, p2, m->dm_inv + 4 * f, &m->rest_area[f]);
    area_sum += m->rest_area[f];
    for (int c = 0; c < 3; c++) m->vert_area[fv[c]] += m->rest_area[f] / 3.0;
    for (int c = 0; c < 3; c++) {
      const double *a = m->rest + 3 * fv[c], *b = m->rest + 3 * fv[(c + 1) % 3];
      double d2 = 0.0;
      for (int i = 0; i < 3; i++) d2 += (a[i] - b[i]) * (a[i] - b[i]);
      edge_sum += sqrt(d2);
      edge_count++;
    }
  }
  m->edge_len = edge_count && edge_sum > 0.0 ? edge_sum / edge_count : 1.0;
  if (!(area_sum > 0.0)) return ss_fail(err, err_sz, SS_E_MESH, "the skin has no area at rest");

  /* Vertex kinds: free if it touches only simulated faces. */
  unsigned char *touch_in = m->kind; /* bit 1: simulated face, bit 2: other face */
  memset(touch_in, 0, (size_t)nv);
  for (int f = 0; f < nf; f++)
    for (int c = 0; c < 3; c++) touch_in[m->faces[3 * f + c]] |= m->mask[f] ? 1 : 2;
  m->ndof = 0;
  for (int v = 0; v < nv; v++) {
    unsigned char t = touch_in[v];
    m->kind[v] = t == 1 ? SS_VERT_FREE : (t & 1) ? SS_VERT_PINNED : SS_VERT_FOLLOWER;
    m->dof[v] = m->kind[v] == SS_VERT_FREE ? m->ndof++ : -1;
  }
  for (int v = 0; v < nv; v++)
    if (m->dof[v] >= 0) m->dof_vert[m->dof[v]] = v;

  /* Simulated faces. */
  m->nsimface = 0;
  for (int f = 0; f < nf; f++) {
    const int *fv = m->faces + 3 * f;
    int any_free = m->dof[fv[0]] >= 0 || m->dof[fv[1]] >= 0 || m->dof[fv[2]] >= 0;
    if (any_free && m->rest_area[f] > 0.0) m->simface[m->nsimface++] = f;
  }
  ss_model_build_material(m);
  if (set->bending > 0.0) return build_hinges(m, err, err_sz);
  m->nhinge = 0;
  return SS_OK;
}
