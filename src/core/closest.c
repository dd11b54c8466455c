/* Closest points on triangles, and the n-ring baseline of the anchor update.
 *
 * ss_closest_point_triangle follows Ericson, "Real-Time Collision Detection",
 * section 5.1.5: the Voronoi regions of the three vertices, then of the three
 * edges, else the face interior. On a degenerate triangle (zero area:
 * collinear or coincident corners) the interior case has no meaning and the
 * region tests can divide by zero, so there the closest point of the three
 * edge segments is taken instead: finite for every finite input.
 *
 * Every path writes uv. Coordinates are brought near 1 by an exact power-of-
 * two scale before any subtraction or product when they are large enough for
 * a squared distance to overflow (a far but finite query point), so the region
 * tests stay meaningful and only the returned squared distance may round to
 * infinity; a non-finite corner or query point gets uv = the barycenter and
 * an infinite distance (never nearer than any finite candidate).
 *
 * The n-ring search ("geodesic distance in a limited N-ring", the paper's
 * section 1, after Saito and Yuen 2017) takes the Euclidean closest point
 * among the faces within N vertex rings of the anchor's face. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "closest.h"
#include "ss_vec.h"

/* Closest point of segment a + t (b - a), t in [0, 1]: returns t. */
static double segment_param(const double p[3], const double a[3], const double b[3]) {
  double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  double l2 = dot3(ab, ab);
  if (!(l2 > 0.0)) return 0.0;
  double t = dot3(ap, ab) / l2;
  return t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
}

static double dist2_at(const double p[3], const double a[3], const double b[3],
                       const double c[3], double u, double v) {
  double d2 = 0.0;
  for (int i = 0; i < 3; i++) {
    double x = a[i] + u * (b[i] - a[i]) + v * (c[i] - a[i]) - p[i];
    d2 += x * x;
  }
  return d2;
}

/* Closest point over the three edges of the triangle, as canonical (u, v). */
static double closest_on_edges(const double p[3], const double a[3], const double b[3],
                               const double c[3], double uv[2]) {
  double t0 = segment_param(p, a, b), t1 = segment_param(p, b, c), t2 = segment_param(p, c, a);
  double cand[3][2] = {{t0, 0.0}, {1.0 - t1, t1}, {0.0, 1.0 - t2}};
  double best = INFINITY;
  uv[0] = cand[0][0];
  uv[1] = cand[0][1];
  for (int k = 0; k < 3; k++) {
    double d2 = dist2_at(p, a, b, c, cand[k][0], cand[k][1]);
    if (k == 0 || d2 < best) {
      best = d2;
      uv[0] = cand[k][0];
      uv[1] = cand[k][1];
    }
  }
  return best;
}

static double closest_unscaled(const double p[3], const double a[3], const double b[3],
                               const double c[3], double uv[2]);

/* Above this magnitude a coordinate difference squared can overflow. */
#define SS_CLOSEST_BIG 0x1p+500

double ss_closest_point_triangle(const double p[3], const double a[3], const double b[3],
                                 const double c[3], double uv[2]) {
  /* The usual case in one pass of comparisons without branches: every
   * coordinate finite and at most SS_CLOSEST_BIG (a NaN compares false),
   * where the checks below would take the same path. */
  int usual = 1;
  for (int i = 0; i < 3; i++)
    usual &= (fabs(p[i]) <= SS_CLOSEST_BIG) & (fabs(a[i]) <= SS_CLOSEST_BIG) & (fabs(b[i]) <= SS_CLOSEST_BIG) &
             (fabs(c[i]) <= SS_CLOSEST_BIG);
  if (usual) return closest_unscaled(p, a, b, c, uv);
  /* Here some coordinate is not finite or is beyond SS_CLOSEST_BIG. */
  double m = 0.0;
  for (int i = 0; i < 3; i++) {
    m = max_keep(m, fabs(p[i]));
    m = max_keep(m, fabs(a[i]));
    m = max_keep(m, fabs(b[i]));
    m = max_keep(m, fabs(c[i]));
  }
  int finite = isfinite(m);
  for (int i = 0; i < 3 && finite; i++) /* max_keep drops NaN: check each */
    finite = isfinite(p[i]) && isfinite(a[i]) && isfinite(b[i]) && isfinite(c[i]);
  if (!finite) {
    uv[0] = uv[1] = 1.0 / 3.0;
    return INFINITY;
  }
  int e; /* all finite, so m > SS_CLOSEST_BIG: scale it near 1 */
  frexp(m, &e);
  double sp[3], sa[3], sb[3], sc[3];
  for (int i = 0; i < 3; i++) { /* exact: scaling by a power of two */
    sp[i] = ldexp(p[i], -e);
    sa[i] = ldexp(a[i], -e);
    sb[i] = ldexp(b[i], -e);
    sc[i] = ldexp(c[i], -e);
  }
  return ldexp(closest_unscaled(sp, sa, sb, sc, uv), 2 * e);
}

static double closest_unscaled(const double p[3], const double a[3], const double b[3],
                               const double c[3], double uv[2]) {
  double ab[3], ac[3], ap[3], n[3];
  for (int i = 0; i < 3; i++) {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ap[i] = p[i] - a[i];
  }
  n[0] = ab[1] * ac[2] - ab[2] * ac[1];
  n[1] = ab[2] * ac[0] - ab[0] * ac[2];
  n[2] = ab[0] * ac[1] - ab[1] * ac[0];
  double n2 = dot3(n, n), l2 = dot3(ab, ab) + dot3(ac, ac);
  if (!(n2 > 1e-24 * l2 * l2)) return closest_on_edges(p, a, b, c, uv);

  double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) { /* vertex a */
    uv[0] = uv[1] = 0.0;
    return dot3(ap, ap);
  }
  double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) { /* vertex b */
    uv[0] = 1.0, uv[1] = 0.0;
    return dot3(bp, bp);
  }
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) { /* edge ab */
    uv[0] = d1 / (d1 - d3), uv[1] = 0.0;
    return dist2_at(p, a, b, c, uv[0], uv[1]);
  }
  double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) { /* vertex c */
    uv[0] = 0.0, uv[1] = 1.0;
    return dot3(cp, cp);
  }
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) { /* edge ac */
    uv[0] = 0.0, uv[1] = d2 / (d2 - d6);
    return dist2_at(p, a, b, c, uv[0], uv[1]);
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) { /* edge bc */
    double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    uv[0] = 1.0 - w, uv[1] = w;
    return dist2_at(p, a, b, c, uv[0], uv[1]);
  }
  double denom = 1.0 / (va + vb + vc); /* interior */
  double v = vb * denom, w = vc * denom;
  if (!(isfinite(v) && isfinite(w) && v >= 0.0 && w >= 0.0 && v + w <= 1.0 + 1e-12))
    return closest_on_edges(p, a, b, c, uv);
  uv[0] = v;
  uv[1] = w;
  if (v + w > 1.0) uv[0] = v / (v + w), uv[1] = w / (v + w);
  return dist2_at(p, a, b, c, uv[0], uv[1]);
}

/* ---- n-ring --------------------------------------------------------------- */

struct ss_nring {
  unsigned int stamp;
  unsigned int *face_seen; /* (nface) */
  int *queue;              /* (nface) faces found, in ring order */
};

int ss_nring_create(ss_nring **out, const ss_topo *topo) {
  if (!out || !topo) return SS_E_ARG;
  *out = NULL;
  ss_nring *r = calloc(1, sizeof *r);
  if (!r) return SS_E_NOMEM;
  r->face_seen = calloc((size_t)topo->nface, sizeof(unsigned int));
  r->queue = malloc(sizeof(int) * (size_t)topo->nface);
  if (!r->face_seen || !r->queue) {
    ss_nring_destroy(r);
    return SS_E_NOMEM;
  }
  *out = r;
  return SS_OK;
}

void ss_nring_destroy(ss_nring *r) {
  if (!r) return;
  free(r->face_seen);
  free(r->queue);
  free(r);
}

double ss_nring_closest(ss_nring *r, const ss_topo *topo, const double *pos, int face, int rings,
                        const double p[3], int *face_out, double uv[2]) {
  if (++r->stamp == 0) {
    memset(r->face_seen, 0, sizeof(unsigned int) * (size_t)topo->nface);
    r->stamp = 1;
  }
  /* breadth-first over faces: ring i+1 = faces sharing a welded vertex with ring i */
  int head = 0, tail = 0;
  r->queue[tail++] = face;
  r->face_seen[face] = r->stamp;
  for (int ring = 0; ring < rings; ring++) {
    const int ring_end = tail;
    for (; head < ring_end; head++) {
      const int f = r->queue[head];
      for (int c = 0; c < 3; c++) {
        const int w = topo->vert_weld[topo->face_vert[3 * f + c]];
        for (int i = topo->vf_start[w]; i < topo->vf_start[w + 1]; i++) {
          const int g = topo->vf_face[i];
          if (r->face_seen[g] == r->stamp) continue;
          r->face_seen[g] = r->stamp;
          r->queue[tail++] = g;
        }
      }
    }
    if (head == tail) break; /* the whole component is in */
  }
  double best = INFINITY;
  *face_out = face;
  uv[0] = uv[1] = 1.0 / 3.0;
  for (int i = 0; i < tail; i++) {
    const int f = r->queue[i];
    const int *fv = topo->face_vert + 3 * f;
    double fuv[2];
    double d2 = ss_closest_point_triangle(p, pos + 3 * fv[0], pos + 3 * fv[1], pos + 3 * fv[2],
                                          fuv);
    if (d2 < best || (d2 == best && f < *face_out)) {
      best = d2;
      *face_out = f;
      uv[0] = fuv[0];
      uv[1] = fuv[1];
    }
  }
  return best;
}
