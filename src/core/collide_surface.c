/* The body's surface near a skin vertex, for the contact pass (collide.c,
 * "Where, cheap first"): a local nearest point by descent over the faces,
 * and the signed distance along the pseudo-normal there. Reads the faces'
 * frame records (walk.h) and the body's welded vertex rings; allocates
 * nothing. */
#include "collide_surface.h"

#include <math.h>
#include <string.h>

#include "collide_behind.h"

#define SS_COLLIDE_DESCENT 32 /* faces a descent crosses at most */

/* The faces nearest to x at c, the nearest point of face nf to x (at uv,
 * squared distance d2): nf alone if c is inside it, else the faces around
 * nf's corners at the same distance (an edge's or a corner's faces), each
 * once. Their normals summed into n (if not NULL); the lowest of them other
 * than nf into *other (if not NULL; -1 if none). */
static void faces_at(const ss_collide_in *in, int nf, const double uv[2], const double x[3], double d2,
                     double n[3], int *other) {
  const ss_topo *t = in->topo;
  const ss_frames *fr = in->fr;
  const double eps = 1e-9;
  if (other) *other = -1;
  if (uv[0] > eps && uv[1] > eps && 1.0 - uv[0] - uv[1] > eps) {
    if (n) memcpy(n, fr->normal + 3 * nf, 3 * sizeof(double));
    return;
  }
  const double tie = d2 + 1e-12 * in->reach * in->reach;
  const int *fv = t->face_vert + 3 * nf;
  if (n) n[0] = n[1] = n[2] = 0.0;
  for (int c = 0; c < 3; c++) {
    const int w = t->vert_weld[fv[c]];
    for (int i = t->vf_start[w]; i < t->vf_start[w + 1]; i++) {
      const int g = t->vf_face[i];
      const int *gv = t->face_vert + 3 * g;
      int seen = 0; /* met around an earlier corner of nf */
      for (int e = 0; e < c && !seen; e++) {
        const int we = t->vert_weld[fv[e]];
        seen = t->vert_weld[gv[0]] == we || t->vert_weld[gv[1]] == we || t->vert_weld[gv[2]] == we;
      }
      if (seen || t->face_degenerate[g] || !(fr->area[g] > 0.0)) continue;
      double guv[2];
      if (g == nf || ss_collide_tri_dist2(in, g, x, guv) <= tie) {
        if (n)
          for (int k = 0; k < 3; k++) n[k] += fr->normal[3 * g + k];
        if (other && g != nf && (*other < 0 || g < *other)) *other = g;
      }
    }
  }
}

/* The pseudo-normal of the body at the nearest point of face nf to x
 * (Baerentzen and Aanaes 2005: the sum of the normals of the faces nearest
 * there; one face's inside it, an edge's two, a corner's ring). */
static int pseudo_normal(const ss_collide_in *in, int nf, const double uv[2], const double x[3],
                         double d2, double n[3]) {
  faces_at(in, nf, uv, x, d2, n, NULL);
  const double len = sqrt(dot3(n, n));
  if (!(len > 0.0)) return 0;
  for (int k = 0; k < 3; k++) n[k] /= len;
  return 1;
}

/* Squared distance from p to body face g (its nearest point at uv), or
 * infinity for a face with no area. */
static double face_dist2(const ss_collide_in *in, int g, const double p[3], double uv[2]) {
  const ss_topo *t = in->topo;
  if (g < 0 || t->face_degenerate[g] || !(in->fr->area[g] > 0.0)) return INFINITY;
  return ss_collide_tri_dist2(in, g, p, uv);
}

/* (collide_surface.h) Each move lowers the distance, so the descent never
 * returns to a face; SS_COLLIDE_DESCENT bounds its length all the same. */
int ss_collide_descend(const ss_collide_in *in, int f, const double p[3], double uv[2], double *d2,
                       int *settled) {
  const ss_topo *t = in->topo;
  const double eps = 1e-9;
  *settled = 1;
  *d2 = face_dist2(in, f, p, uv);
  if (!(*d2 < INFINITY)) return -1;
  for (int s = 0; s < SS_COLLIDE_DESCENT; s++) {
    const double w[3] = {1.0 - uv[0] - uv[1], uv[0], uv[1]}; /* at corners 0, 1, 2 */
    const int z0 = w[0] <= eps, z1 = w[1] <= eps, z2 = w[2] <= eps;
    if (!(z0 || z1 || z2)) return f; /* inside the face: a local nearest point */
    int next = -1;
    double nuv[2], guv[2];
    if (z0 + z1 + z2 == 1) {
      /* on edge k (corners k, k + 1), the corner k + 2 opposite it */
      const int k = z0 ? 1 : z1 ? 2 : 0;
      const int g = t->face_adj[3 * f + k];
      const double e = face_dist2(in, g, p, guv);
      if (e < *d2) next = g, *d2 = e, nuv[0] = guv[0], nuv[1] = guv[1];
    } else {
      /* at a corner: the faces around it */
      const int c = !z0 ? 0 : !z1 ? 1 : 2;
      const int wv = t->vert_weld[t->face_vert[3 * f + c]];
      for (int i = t->vf_start[wv]; i < t->vf_start[wv + 1]; i++) {
        const int g = t->vf_face[i];
        if (g == f) continue;
        const double e = face_dist2(in, g, p, guv);
        if (e < *d2) next = g, *d2 = e, nuv[0] = guv[0], nuv[1] = guv[1];
      }
    }
    if (next < 0) return f;
    f = next, uv[0] = nuv[0], uv[1] = nuv[1];
  }
  *settled = 0;
  return f;
}

/* (collide_surface.h) */
int ss_collide_surface_at(const ss_collide_in *in, int nf, const double uv[2], const double p[3], double d2,
                          double n[3], double c[3], double *sd) {
  if (!pseudo_normal(in, nf, uv, p, d2, n)) return 0;
  const int *fv = in->topo->face_vert + 3 * nf;
  const double *p0 = in->body + 3 * fv[0], *p1 = in->body + 3 * fv[1], *p2 = in->body + 3 * fv[2];
  double rel[3];
  for (int k = 0; k < 3; k++) {
    c[k] = p0[k] + uv[0] * (p1[k] - p0[k]) + uv[1] * (p2[k] - p0[k]);
    rel[k] = p[k] - c[k];
  }
  *sd = dot3(rel, n);
  return 1;
}

/* (collide_surface.h) */
int ss_collide_tied_face(const ss_collide_in *in, int nf, const double p[3]) {
  double uv[2];
  const double d2 = ss_collide_tri_dist2(in, nf, p, uv);
  int other;
  faces_at(in, nf, uv, p, d2, NULL, &other);
  return other;
}
