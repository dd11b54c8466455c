/* Small meshes for the ss_sim tests: a square grid patch (optionally bumpy)
 * and a motion for it. Header-only, static functions. */
#ifndef SKIN_SIM_TEST_SIM_FIXTURES_H
#define SKIN_SIM_TEST_SIM_FIXTURES_H

#include <math.h>
#include <stdlib.h>

typedef struct {
  int nvert, nface;
  double *pos; /* (nvert x 3) */
  int *faces;  /* (nface x 3) */
} fx_mesh;

/* n x m vertices over [0, w] x [0, hgt] in the xy-plane, z = bump * sin(pi x / w) sin(pi y / hgt),
 * faces counter-clockwise seen from +z. */
static fx_mesh fx_grid(int n, int m, double w, double hgt, double bump) {
  fx_mesh g;
  g.nvert = n * m;
  g.nface = 2 * (n - 1) * (m - 1);
  g.pos = malloc(3 * (size_t)g.nvert * sizeof(double));
  g.faces = malloc(3 * (size_t)g.nface * sizeof(int));
  for (int j = 0; j < m; j++)
    for (int i = 0; i < n; i++) {
      double x = w * i / (n - 1), y = hgt * j / (m - 1);
      double *p = g.pos + 3 * (j * n + i);
      p[0] = x, p[1] = y;
      p[2] = bump * sin(3.14159265358979 * x / w) * sin(3.14159265358979 * y / hgt);
    }
  int f = 0;
  for (int j = 0; j + 1 < m; j++)
    for (int i = 0; i + 1 < n; i++) {
      int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      int *t = g.faces + 3 * f;
      t[0] = a, t[1] = b, t[2] = d;
      t[3] = a, t[4] = d, t[5] = c;
      f += 2;
    }
  return g;
}

static void fx_free(fx_mesh *g) {
  free(g->pos);
  free(g->faces);
}

/* A pose of the grid at time t (s): a rigid slide and rotation about z plus
 * a travelling wave in z, so anchors must slide and the skin stretch. */
static void fx_pose(const fx_mesh *g, double t, double *out) {
  double ang = 0.3 * sin(2.0 * t), c = cos(ang), s = sin(ang);
  for (int v = 0; v < g->nvert; v++) {
    const double *p = g->pos + 3 * v;
    double x = p[0] - 0.5, y = p[1] - 0.5;
    out[3 * v] = c * x - s * y + 0.5 + 0.1 * t;
    out[3 * v + 1] = s * x + c * y + 0.5;
    out[3 * v + 2] = p[2] + 0.05 * sin(6.0 * p[0] - 4.0 * t);
  }
}

#endif
