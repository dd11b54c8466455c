/* skin_sim core: plain counts of what a user sees go wrong (ss_sim.h,
 * ss_sim_count_off_body). The solver's own measures judge only what they
 * can act on (the orient term leaves slivers out); these count every face
 * and vertex, so that a user's picture and the numbers agree. */
#include <math.h>

#include "closest.h"
#include "sim_internal.h"

/* Unnormalised normal of triangle (a, b, c) of flat arrays pos at indices. */
static void tri_normal(const double *pos, const int *t, double n[3]) {
  const double *a = pos + 3 * t[0], *b = pos + 3 * t[1], *c = pos + 3 * t[2];
  double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

/* The body's normal under skin face f in body pose `body` with anchors
 * `face` (its barycenter's anchor face, else the sum of its corners' unit
 * anchor face normals); 0 if there is none. */
static int body_normal_under(const ss_sim *sim, const double *body, const int *face, int f,
                             double n[3]) {
  const ss_model *m = sim->m;
  const int *bf = m->btopo->face_vert;
  n[0] = n[1] = n[2] = 0.0;
  if (m->nanchor > m->nvert && face[m->nvert + f] >= 0) {
    tri_normal(body, bf + 3 * face[m->nvert + f], n);
    return 1;
  }
  int any = 0;
  for (int k = 0; k < 3; k++) {
    int a = face[m->faces[3 * f + k]];
    if (a < 0) continue;
    double c[3];
    tri_normal(body, bf + 3 * a, c);
    double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (!(l > 0.0)) continue;
    for (int i = 0; i < 3; i++) n[i] += c[i] / l;
    any = 1;
  }
  return any;
}

void ss_sim_count_off_body(const ss_sim *sim, int *faces_turned, int *vertices_far) {
  const ss_model *m = sim->m;
  if (faces_turned) {
    int turned = 0;
    for (int f = 0; f < m->nface; f++) {
      double s0[3], b0[3], s1[3], b1[3];
      if (!body_normal_under(sim, m->body_rest, m->anchor_face0, f, b0)) continue;
      tri_normal(m->rest, m->faces + 3 * f, s0);
      double rest = s0[0] * b0[0] + s0[1] * b0[1] + s0[2] * b0[2];
      if (rest == 0.0 || !body_normal_under(sim, sim->body_prev, sim->anchor_face, f, b1)) continue;
      tri_normal(sim->x, m->faces + 3 * f, s1);
      double now = s1[0] * b1[0] + s1[1] * b1[1] + s1[2] * b1[2];
      turned += (rest > 0.0) ? now < 0.0 : now > 0.0;
    }
    *faces_turned = turned;
  }
  if (vertices_far) {
    /* the distance to the body near the anchor: its face and the faces across its
     * edges, asked only of vertices farther than the bound from the anchor itself */
    int far = 0;
    const double lim2 = m->edge_len * m->edge_len;
    const ss_topo *t = m->btopo;
    const double *body = sim->body_prev;
    for (int v = 0; v < m->nvert; v++) {
      const double *x = sim->x + 3 * v, *a = sim->anchor_pos + 3 * v;
      double d2 = (x[0] - a[0]) * (x[0] - a[0]) + (x[1] - a[1]) * (x[1] - a[1]) +
                  (x[2] - a[2]) * (x[2] - a[2]);
      const int f = sim->anchor_face[v];
      if (!(d2 > lim2) || f < 0) continue;
      for (int k = -1; k < 3 && d2 > lim2; k++) {
        const int g = k < 0 ? f : t->face_adj[3 * f + k];
        if (g < 0) continue;
        const int *c = t->face_vert + 3 * g;
        double uv[2];
        double e2 = ss_closest_point_triangle(x, body + 3 * c[0], body + 3 * c[1], body + 3 * c[2], uv);
        if (e2 < d2) d2 = e2;
      }
      far += d2 > lim2;
    }
    *vertices_far = far;
  }
}
