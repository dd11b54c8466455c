/* URDF primitives (box, sphere, cylinder) as closed triangle meshes, so that
 * a robot built of them (or mixing them with meshes) has a body for the skin.
 *
 * The skin's membrane wants triangles of even size and shape, so each
 * primitive is gridded at about the target edge length:
 * - box: a regular grid on each face, quads split along alternating
 *   diagonals;
 * - sphere: the cube projected onto the sphere with equal angles (grid
 *   coordinate u -> tan(u pi/4) before normalising), which keeps the cells
 *   within a factor of about 1.5 of each other in size; quads split along the
 *   shorter diagonal;
 * - cylinder (along z): a grid on the side; each cap is concentric rings,
 *   ring k of 6k vertices (radius k/M of the cap's), joined ring to ring in
 *   angle order, so cap triangles are near equilateral and the outer ring
 *   meets the side's 6M columns.
 * Vertices shared between faces are computed by the same expression from the
 * same grid index, so they are bit-identical and are merged exactly; every
 * face is then turned to point away from the centre (all three are convex
 * and centred), which makes the winding consistently outward. */
#include "skin_sim/ssa_avatar.h"
#include "ssa_util.h"
#include "ss_mesh_build.h"

#define PRIM_DEFAULT_EDGE 0.02
#define PRIM_MAX_SEG 512
#define PRIM_MAX_TRIS 200000.0

static int segments(double length, double edge, int min) {
  double n = ceil(length / edge - 1e-9);
  if (!(n >= min)) n = min;
  if (n > PRIM_MAX_SEG) n = PRIM_MAX_SEG;
  return (int)n;
}

/* Grid coordinate i of n across [-h, h] (ends exact). */
static double lin(double h, int i, int n) {
  if (i == 0) return -h;
  if (i == n) return h;
  return -h + 2.0 * h * i / n;
}

/* Equal-angle cube coordinate i of n across [-1, 1] (ends exact). */
static double tan_grid(int i, int n) {
  if (i == 0) return -1.0;
  if (i == n) return 1.0;
  return tan(-SSA_PI / 4 + (SSA_PI / 2) * i / n);
}

static double d2(const double *a, const double *b) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

/* Six gridded faces of a box (half sizes h) or, with sphere_r > 0, of the
 * cube projected onto a sphere of that radius. n: cells per face axis. */
static void cube_faces(ss_mb *b, const double *h, const int *n, double sphere_r) {
  for (int a = 0; a < 3; a++)
    for (int s = -1; s <= 1; s += 2) {
      const int u = (a + 1) % 3, v = (a + 2) % 3, nu = n[u], nv = n[v];
      const int base = b->nv;
      for (int i = 0; i <= nu; i++)
        for (int j = 0; j <= nv; j++) {
          double p[3];
          if (sphere_r > 0) {
            p[a] = s;
            p[u] = tan_grid(i, nu);
            p[v] = tan_grid(j, nv);
            double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            for (int k = 0; k < 3; k++) p[k] = sphere_r * p[k] / len;
          } else {
            p[a] = s * h[a];
            p[u] = lin(h[u], i, nu);
            p[v] = lin(h[v], j, nv);
          }
          ss_mb_vert(b, p[0], p[1], p[2]);
        }
      if (b->failed) return;
      for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
          int v00 = base + i * (nv + 1) + j, v01 = v00 + 1, v10 = v00 + nv + 1, v11 = v10 + 1;
          int diag; /* 0: split along v00-v11 */
          if (sphere_r > 0)
            diag = d2(b->pos + 3 * v00, b->pos + 3 * v11) > d2(b->pos + 3 * v01, b->pos + 3 * v10);
          else
            diag = (i + j) & 1;
          if (!diag) {
            ss_mb_tri(b, v00, v10, v11);
            ss_mb_tri(b, v00, v11, v01);
          } else {
            ss_mb_tri(b, v00, v10, v01);
            ss_mb_tri(b, v10, v11, v01);
          }
        }
    }
}

static void cylinder(ss_mb *b, double r, double len, double edge) {
  const int m = segments(2 * SSA_PI * r / 6.0, edge, 4); /* rings per cap: >= 24 columns */
  const int nt = 6 * m;                                  /* columns around */
  const int nz = segments(len, edge, 1);
  const double hz = 0.5 * len;
  const int side = b->nv;
  for (int i = 0; i <= nz; i++)
    for (int j = 0; j < nt; j++) {
      double t = 2.0 * SSA_PI * j / nt;
      ss_mb_vert(b, r * cos(t), r * sin(t), lin(hz, i, nz));
    }
  if (b->failed) return;
  for (int i = 0; i < nz; i++)
    for (int j = 0; j < nt; j++) {
      int a = side + i * nt + j, c = side + i * nt + (j + 1) % nt;
      ss_mb_tri(b, a, c, c + nt);
      ss_mb_tri(b, a, c + nt, a + nt);
    }
  for (int s = -1; s <= 1; s += 2) {
    const double z = s * hz;
    int prev = ss_mb_vert(b, 0.0, 0.0, z), nprev = 1; /* ring 0: the centre */
    for (int k = 1; k <= m && !b->failed; k++) {
      const int n1 = 6 * k;
      int ring = b->nv;
      if (k == m) { /* the side's end ring: the same vertices */
        ring = side + (s < 0 ? 0 : nz * nt);
      } else {
        const double rk = r * k / m;
        for (int q = 0; q < n1; q++) {
          double t = 2.0 * SSA_PI * q / n1;
          ss_mb_vert(b, rk * cos(t), rk * sin(t), z);
        }
      }
      int i0 = 0, i1 = 0;
      while (!b->failed && (i1 < n1 || (nprev > 1 && i0 < nprev))) {
        /* advance on the ring whose next vertex comes first by angle */
        const int outer = i1 < n1 && (nprev == 1 || i0 >= nprev ||
                                      (double)(i1 + 1) / n1 <= (double)(i0 + 1) / nprev);
        if (outer) {
          ss_mb_tri(b, prev + i0 % nprev, ring + i1 % n1, ring + (i1 + 1) % n1);
          i1++;
        } else {
          ss_mb_tri(b, prev + i0 % nprev, ring + i1 % n1, prev + (i0 + 1) % nprev);
          i0++;
        }
      }
      prev = ring;
      nprev = n1;
    }
  }
}

typedef struct keyed {
  double x, y, z;
  int i;
} keyed;

static int cmp_keyed(const void *pa, const void *pb) {
  const keyed *a = pa, *b = pb;
  if (a->x != b->x) return a->x < b->x ? -1 : 1;
  if (a->y != b->y) return a->y < b->y ? -1 : 1;
  if (a->z != b->z) return a->z < b->z ? -1 : 1;
  return a->i - b->i;
}

/* Merges bit-identical vertices, keeps the first of each; turns faces outward. */
static int finish(ss_mb *b) {
  keyed *key = malloc(sizeof(keyed) * (size_t)(b->nv > 0 ? b->nv : 1));
  int *order = malloc(sizeof(int) * (size_t)(b->nv > 0 ? b->nv : 1));
  int *remap = malloc(sizeof(int) * (size_t)(b->nv > 0 ? b->nv : 1));
  if (!key || !order || !remap) {
    free(key);
    free(order);
    free(remap);
    return 0;
  }
  for (int i = 0; i < b->nv; i++) {
    key[i].x = b->pos[3 * i];
    key[i].y = b->pos[3 * i + 1];
    key[i].z = b->pos[3 * i + 2];
    key[i].i = i;
  }
  qsort(key, (size_t)b->nv, sizeof(keyed), cmp_keyed);
  for (int k = 0; k < b->nv; k++) {
    int i = key[k].i;
    remap[i] = i;
    if (k > 0 && key[k].x == key[k - 1].x && key[k].y == key[k - 1].y && key[k].z == key[k - 1].z)
      remap[i] = remap[key[k - 1].i];
  }
  free(key);
  /* compact in first-seen order */
  int *newidx = order; /* reuse */
  int n = 0;
  for (int i = 0; i < b->nv; i++) {
    if (remap[i] == i) {
      newidx[i] = n;
      memmove(b->pos + 3 * n, b->pos + 3 * i, 3 * sizeof(double));
      n++;
    }
  }
  for (int f = 0; f < 3 * b->nf; f++) b->tri[f] = newidx[remap[b->tri[f]]];
  b->nv = n;
  free(order);
  free(remap);
  for (int f = 0; f < b->nf; f++) {
    int *t = b->tri + 3 * f;
    const double *p0 = b->pos + 3 * t[0], *p1 = b->pos + 3 * t[1], *p2 = b->pos + 3 * t[2];
    double e1[3], e2[3], nrm[3], g[3];
    for (int k = 0; k < 3; k++) {
      e1[k] = p1[k] - p0[k];
      e2[k] = p2[k] - p0[k];
      g[k] = (p0[k] + p1[k] + p2[k]) / 3.0;
    }
    nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
    if (nrm[0] * g[0] + nrm[1] * g[1] + nrm[2] * g[2] < 0) {
      int x = t[1];
      t[1] = t[2];
      t[2] = x;
    }
  }
  return 1;
}

int ssa_primitive_mesh(int kind, const double *size, double edge, double **pos, int *nvert,
                       int **faces, int *nface, char *err, int err_sz) {
  if (!pos || !nvert || !faces || !nface || !size)
    return ss_fail(err, err_sz, SS_E_ARG, "primitive: missing arguments");
  *pos = NULL;
  *faces = NULL;
  *nvert = *nface = 0;
  if (!(edge > 0) || !isfinite(edge)) edge = PRIM_DEFAULT_EDGE;
  const int nsize = kind == SSA_VISUAL_BOX ? 3 : kind == SSA_VISUAL_CYLINDER ? 2
                    : kind == SSA_VISUAL_SPHERE ? 1 : 0;
  if (!nsize) return ss_fail(err, err_sz, SS_E_ARG, "primitive: unknown kind %d", kind);
  static const char *const what[] = {"", "sphere radius", "box size", "cylinder radius/length"};
  for (int k = 0; k < nsize; k++)
    if (!(size[k] > 0) || !isfinite(size[k]))
      return ss_fail(err, err_sz, SS_E_ARG, "primitive: %s %g is not a positive finite length",
                     what[kind], size[k]);
  /* at most about PRIM_MAX_TRIS triangles: a huge primitive gets longer edges */
  const double area = kind == SSA_VISUAL_BOX
                          ? 2 * (size[0] * size[1] + size[1] * size[2] + size[2] * size[0])
                      : kind == SSA_VISUAL_SPHERE
                          ? 4 * SSA_PI * size[0] * size[0]
                          : 2 * SSA_PI * size[0] * (size[0] + size[1]);
  if (2.0 * area / (edge * edge) > PRIM_MAX_TRIS) edge = sqrt(2.0 * area / PRIM_MAX_TRIS);
  ss_mb b = {0};
  if (kind == SSA_VISUAL_BOX) {
    double h[3];
    int n[3];
    for (int k = 0; k < 3; k++) {
      h[k] = 0.5 * size[k];
      n[k] = segments(size[k], edge, 1);
    }
    cube_faces(&b, h, n, 0.0);
  } else if (kind == SSA_VISUAL_SPHERE) {
    const int n1 = segments(0.5 * SSA_PI * size[0], edge, 6); /* a quarter turn per cube face */
    const int n[3] = {n1, n1, n1};
    cube_faces(&b, NULL, n, size[0]);
  } else {
    cylinder(&b, size[0], size[1], edge);
  }
  if (b.failed || !finish(&b)) {
    free(b.pos);
    free(b.tri);
    return ss_fail(err, err_sz, SS_E_NOMEM, "primitive: out of memory");
  }
  *pos = b.pos;
  *faces = b.tri;
  *nvert = b.nv;
  *nface = b.nf;
  return SS_OK;
}
