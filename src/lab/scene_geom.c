/* Procedural mesh building blocks and joint rotations for the built-in scenes
 * (see scene.c for the scenes themselves). */
#include "scene_geom.h"

#include <math.h>
#include <stdlib.h>

/* ------------------------------------------------------------- capsule */

int ss_capsule_rings(double r, double hc, double h) {
  double lm = SS_PI * r + 2.0 * hc; /* meridian length, pole to pole */
  int n = (int)lround(lm / (0.8660254037844386 * h)) - 1; /* equilateral rows */
  return n < 1 ? 1 : n;
}

int ss_capsule_segs(double r, double h) {
  int n = (int)lround(2.0 * SS_PI * r / h);
  return n < 6 ? 6 : n;
}

/* The capsule's meridian at arc length s from the south pole: axial
 * coordinate *a and radius *rho. */
static void meridian(double r, double hc, double s, double *a, double *rho) {
  double cap = 0.5 * SS_PI * r;
  if (s < cap) {
    double b = s / r;
    *a = -hc - r * cos(b);
    *rho = r * sin(b);
  } else if (s < cap + 2.0 * hc) {
    *a = -hc + (s - cap);
    *rho = r;
  } else {
    double b = (s - cap - 2.0 * hc) / r;
    *a = hc + r * sin(b);
    *rho = r * cos(b);
  }
}

/* Local (cos, sin, axial) to world: a cyclic permutation, so orientation holds. */
static int capsule_vert(ss_mb *mb, const double center[3], int axis, double l0, double l1,
                        double la) {
  double w[3];
  w[axis] = la;
  w[(axis + 1) % 3] = l0;
  w[(axis + 2) % 3] = l1;
  return ss_mb_vert(mb, center[0] + w[0], center[1] + w[1], center[2] + w[2]);
}

void ss_mb_capsule(ss_mb *mb, const double center[3], int axis, double r, double hc, int nseg,
                   int nring) {
  double lm = SS_PI * r + 2.0 * hc;
  int south = capsule_vert(mb, center, axis, 0.0, 0.0, -hc - r);
  int first = mb->nv;
  for (int i = 1; i <= nring; i++) {
    double a, rho;
    meridian(r, hc, lm * i / (nring + 1), &a, &rho);
    for (int j = 0; j < nseg; j++) { /* odd rings turned half a segment */
      double al = 2.0 * SS_PI * (j + 0.5 * (i & 1)) / nseg;
      capsule_vert(mb, center, axis, rho * cos(al), rho * sin(al), a);
    }
  }
  int north = capsule_vert(mb, center, axis, 0.0, 0.0, hc + r);
  for (int j = 0; j < nseg; j++) {
    int j1 = (j + 1) % nseg;
    ss_mb_tri(mb, south, first + j1, first + j);
    for (int i = 0; i + 1 < nring; i++) {
      /* rows i and i + 1 (rings i + 1 and i + 2, counted from 1 above) */
      int a = first + i * nseg + j, b = first + i * nseg + j1;
      int c = b + nseg, d = a + nseg;
      if (!(i & 1)) { /* lower turned: upper j1 lies between lower j and j1 */
        ss_mb_tri(mb, a, b, c);
        ss_mb_tri(mb, a, c, d);
      } else { /* upper turned: upper j lies between lower j and j1 */
        ss_mb_tri(mb, a, b, d);
        ss_mb_tri(mb, b, c, d);
      }
    }
    int top = first + (nring - 1) * nseg;
    ss_mb_tri(mb, top + j, top + j1, north);
  }
}

/* --------------------------------------------------------------- plate */

void ss_mb_plate(ss_mb *mb, double x0, double lx, double ly, double t, int nx, int ny) {
  int base[2];
  for (int side = 0; side < 2; side++) {
    base[side] = mb->nv;
    double z = side == 0 ? 0.5 * t : -0.5 * t;
    for (int j = 0; j <= ny; j++)
      for (int i = 0; i <= nx; i++)
        ss_mb_vert(mb, x0 + lx * i / nx, -0.5 * ly + ly * j / ny, z);
  }
  for (int side = 0; side < 2; side++) {
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        int a = base[side] + j * (nx + 1) + i, b = a + 1, c = b + nx + 1, d = a + nx + 1;
        if (side == 0) {
          ss_mb_tri(mb, a, b, c);
          ss_mb_tri(mb, a, c, d);
        } else {
          ss_mb_tri(mb, a, c, b);
          ss_mb_tri(mb, a, d, c);
        }
      }
  }
  /* the rim: walk the top grid's border counter-clockwise seen from +z */
  int m = 2 * (nx + ny);
  for (int k = 0; k < m; k++) {
    int loop[2];
    for (int q = 0; q < 2; q++) {
      int s = (k + q) % m, i, j;
      if (s < nx) {
        i = s;
        j = 0;
      } else if (s < nx + ny) {
        i = nx;
        j = s - nx;
      } else if (s < 2 * nx + ny) {
        i = nx - (s - nx - ny);
        j = ny;
      } else {
        i = 0;
        j = ny - (s - 2 * nx - ny);
      }
      loop[q] = j * (nx + 1) + i;
    }
    int t0 = base[0] + loop[0], t1 = base[0] + loop[1];
    int b0 = base[1] + loop[0], b1 = base[1] + loop[1];
    ss_mb_tri(mb, t1, t0, b0);
    ss_mb_tri(mb, t1, b0, b1);
  }
}

/* --------------------------------------------------------------- sheet */

void ss_mb_sheet(ss_mb *mb, const double *xs, int nx, const double *ys, int ny,
                 const unsigned char *tflag) {
  int base = mb->nv;
  for (int j = 0; j <= ny; j++)
    for (int i = 0; i <= nx; i++) ss_mb_vert(mb, xs[i], ys[j], 0.0);
  for (int j = 0; j < ny; j++)
    for (int c = 0; c < nx; c++) {
      int a = base + j * (nx + 1) + c, b = a + 1, cc = b + nx + 1, d = a + nx + 1;
      if (tflag && tflag[(size_t)j * (size_t)nx + (size_t)c]) {
        /* the midpoint shares x and z with a and d exactly: collinear for
         * any motion that maps points by their x and z alone */
        int m = ss_mb_vert(mb, xs[c], 0.5 * (ys[j] + ys[j + 1]), 0.0);
        ss_mb_tri(mb, a, b, m);
        ss_mb_tri(mb, m, b, cc);
        ss_mb_tri(mb, m, cc, d);
        ss_mb_tri(mb, a, m, d); /* zero area */
      } else {
        ss_mb_tri(mb, a, b, cc);
        ss_mb_tri(mb, a, cc, d);
      }
    }
}

/* ------------------------------------------------------------- lattice */

void ss_mb_lattice(ss_mb *mb, double x0, double lx, double y0, double ly, int nx, int ny) {
  int prev = -1, nprev = 0;
  for (int j = 0; j <= ny; j++) {
    int first = mb->nv, odd = j & 1;
    double y = y0 + ly * j / ny;
    ss_mb_vert(mb, x0, y, 0.0);
    for (int i = 0; i < nx; i++) /* odd rows: midpoints, then the far corner */
      ss_mb_vert(mb, odd ? x0 + lx * (i + 0.5) / nx : x0 + lx * (i + 1) / nx, y, 0.0);
    if (odd) ss_mb_vert(mb, x0 + lx, y, 0.0);
    int n = mb->nv - first;
    if (prev >= 0 && !mb->failed) {
      /* zip the strip between the rows, advancing along the lower row (l) or
       * the upper row (u), whichever's next vertex lies further left */
      int l = 0, u = 0;
      while (l + 1 < nprev || u + 1 < n) {
        int up;
        if (l + 1 >= nprev)
          up = 1;
        else if (u + 1 >= n)
          up = 0;
        else
          up = mb->pos[3 * (first + u + 1)] < mb->pos[3 * (prev + l + 1)];
        if (up) {
          ss_mb_tri(mb, prev + l, first + u + 1, first + u);
          u++;
        } else {
          ss_mb_tri(mb, prev + l, prev + l + 1, first + u);
          l++;
        }
      }
    }
    prev = first;
    nprev = n;
  }
}

/* ------------------------------------------------------------- motion */

double ss_smooth(double u) {
  if (!(u > 0.0)) return 0.0;
  if (u >= 1.0) return 1.0;
  return u * u * (3.0 - 2.0 * u);
}

void ss_rotate(double p[3], int axis, const double c[3], double a) {
  if (a == 0.0) return;
  int i = (axis + 1) % 3, j = (axis + 2) % 3;
  double ca = cos(a), sa = sin(a);
  double di = p[i] - c[i], dj = p[j] - c[j];
  p[i] = c[i] + ca * di - sa * dj;
  p[j] = c[j] + sa * di + ca * dj;
}
