/* Small meshes built in code for the core's tests: flat grids (optionally
 * jittered), a cube with split (seamed) faces, and helpers to check them. */
#ifndef SKIN_SIM_TEST_MESH_H
#define SKIN_SIM_TEST_MESH_H

#include <stdlib.h>

#include "ss_test.h"

typedef struct test_mesh {
  int nvert, nface;
  double *pos; /* (nvert x 3) */
  int *faces;  /* (nface x 3) */
} test_mesh;

static inline void test_mesh_free(test_mesh *m) {
  free(m->pos);
  free(m->faces);
  m->pos = NULL;
  m->faces = NULL;
}

/* An (nx x ny)-cell grid in the plane z = 0 over [0, nx] x [0, ny], two
 * triangles a cell, counter-clockwise seen from +z. Interior vertices are
 * moved by up to `jitter` cells in x and y (seeded), which gives triangles of
 * different shapes; up to jitter 0.3 every triangle keeps its orientation
 * (a valid planar mesh), beyond that some fold over. */
static inline test_mesh test_grid(int nx, int ny, double jitter, unsigned long long seed) {
  test_mesh m;
  m.nvert = (nx + 1) * (ny + 1);
  m.nface = 2 * nx * ny;
  m.pos = malloc(sizeof(double) * 3 * (size_t)m.nvert);
  m.faces = malloc(sizeof(int) * 3 * (size_t)m.nface);
  unsigned long long s = seed ? seed : 1;
  for (int j = 0; j <= ny; j++)
    for (int i = 0; i <= nx; i++) {
      double *p = m.pos + 3 * (j * (nx + 1) + i);
      p[0] = i;
      p[1] = j;
      p[2] = 0.0;
      if (i > 0 && i < nx && j > 0 && j < ny) {
        p[0] += jitter * (2.0 * ss_test_rand(&s) - 1.0);
        p[1] += jitter * (2.0 * ss_test_rand(&s) - 1.0);
      }
    }
  int f = 0;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      int *t = m.faces + 3 * f;
      t[0] = a, t[1] = b, t[2] = d;
      t[3] = a, t[4] = d, t[5] = c;
      f += 2;
    }
  return m;
}

/* The unit cube [0,1]^3 with each side's 4 corners its own vertices (24
 * vertices, 12 triangles, outward counter-clockwise): a seam along every edge. */
static inline test_mesh test_seamed_cube(void) {
  static const int quads[6][4][3] = {
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, /* z = 0, normal -z */
      {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, /* z = 1 */
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, /* y = 0 */
      {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}, /* y = 1 */
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, /* x = 0 */
      {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, /* x = 1 */
  };
  test_mesh m;
  m.nvert = 24;
  m.nface = 12;
  m.pos = malloc(sizeof(double) * 3 * 24);
  m.faces = malloc(sizeof(int) * 3 * 12);
  for (int q = 0; q < 6; q++) {
    for (int k = 0; k < 4; k++)
      for (int c = 0; c < 3; c++) m.pos[3 * (4 * q + k) + c] = quads[q][k][c];
    int b = 4 * q;
    int *t = m.faces + 6 * q;
    t[0] = b, t[1] = b + 1, t[2] = b + 2;
    t[3] = b, t[4] = b + 2, t[5] = b + 3;
  }
  return m;
}

/* A closed box [lo, hi] whose every side is a grid x grid grid, wound
 * outwards, its sides' vertices not shared (seams, as mesh files have them):
 * TEST_BOX_NVERT(grid) vertices into pos, TEST_BOX_NFACE(grid) faces into
 * faces, indices from vbase. */
#define TEST_BOX_NVERT(grid) (6 * ((grid) + 1) * ((grid) + 1))
#define TEST_BOX_NFACE(grid) (12 * (grid) * (grid))
static inline void test_box(const double lo[3], const double hi[3], int grid, double *pos,
                            int *faces, int vbase) {
  int nv = 0, nf = 0;
  for (int a = 0; a < 3; a++)
    for (int side = 0; side < 2; side++) {
      const int u = (a + 1) % 3, v = (a + 2) % 3, v0 = nv;
      for (int j = 0; j <= grid; j++)
        for (int i = 0; i <= grid; i++) {
          double *p = pos + 3 * nv++;
          p[a] = side ? hi[a] : lo[a];
          p[u] = lo[u] + (hi[u] - lo[u]) * i / grid;
          p[v] = lo[v] + (hi[v] - lo[v]) * j / grid;
        }
      for (int j = 0; j < grid; j++)
        for (int i = 0; i < grid; i++) {
          const int p00 = vbase + v0 + j * (grid + 1) + i, p10 = p00 + 1;
          const int p01 = p00 + grid + 1, p11 = p01 + 1;
          /* e_u x e_v = e_a: counter-clockwise seen from +a on the high side */
          int t[6] = {p00, p10, p11, p00, p11, p01};
          if (!side) t[1] = p11, t[2] = p10, t[4] = p01, t[5] = p11;
          for (int k = 0; k < 6; k++) faces[3 * nf + k] = t[k];
          nf += 2;
        }
    }
}

#endif
