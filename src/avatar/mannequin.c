/* The built-in demo avatar: a humanoid mannequin made entirely here.
 *
 * Its skeleton is a URDF (the text below, kept equal to urdf/mannequin.urdf
 * by a test). Its body is an implicit surface, a smooth union (polynomial
 * smooth minimum) of capsules and ellipsoids laid along the links in the
 * URDF's zero pose (a T pose), polygonised by marching tetrahedra on a
 * regular grid (six tetrahedra per cube sharing one diagonal, so that
 * neighbouring cubes agree and the surface is closed and manifold; each
 * vertex lies on a grid edge and is shared through a hash of that edge, so
 * the mesh is welded). The grid spacing is chosen, in up to four passes,
 * so that the triangle count is near the request. Marching tetrahedra leaves
 * slivers; a few passes of tangential Laplacian smoothing, each followed by
 * Newton steps back onto the surface, even the triangles out. Every triangle
 * is oriented counter-clockwise seen from outside (its normal along the
 * field's gradient). */
#include <stdint.h>

#include "skin_sim/ssa_avatar.h"
#include "ssa_util.h"

static const char mannequin_urdf[] =
    "<?xml version=\"1.0\"?>\n"
    "<!-- skin_sim's built-in demo avatar: a humanoid mannequin made by the project\n"
    "     (no downloaded asset). Metres, Z up, facing +X, T pose at zero. Its body\n"
    "     mesh is generated in code (ssa_mannequin_mesh); this file is the same text\n"
    "     as ssa_mannequin_urdf() and a test keeps the two equal. Joint signs:\n"
    "     shoulder_abduct > 0 swings the arm down (1.57 hangs it, more presses it\n"
    "     into the torso), elbow > 0 bends the forearm forward, hip > 0 lifts the\n"
    "     thigh forward, knee > 0 bends the shin back. -->\n"
    "<robot name=\"mannequin\">\n"
    "  <link name=\"pelvis\"/>\n"
    "  <link name=\"torso\"/>\n"
    "  <link name=\"neck\"/>\n"
    "  <link name=\"head\"/>\n"
    "  <link name=\"l_upper_arm\"/>\n"
    "  <link name=\"l_forearm\"/>\n"
    "  <link name=\"r_upper_arm\"/>\n"
    "  <link name=\"r_forearm\"/>\n"
    "  <link name=\"l_thigh\"/>\n"
    "  <link name=\"l_shin\"/>\n"
    "  <link name=\"r_thigh\"/>\n"
    "  <link name=\"r_shin\"/>\n"
    "  <joint name=\"torso_twist\" type=\"revolute\">\n"
    "    <parent link=\"pelvis\"/><child link=\"torso\"/>\n"
    "    <origin xyz=\"0 0 0.10\" rpy=\"0 0 0\"/><axis xyz=\"0 0 1\"/>\n"
    "    <limit lower=\"-0.9\" upper=\"0.9\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"neck_twist\" type=\"revolute\">\n"
    "    <parent link=\"torso\"/><child link=\"neck\"/>\n"
    "    <origin xyz=\"0 0 0.42\" rpy=\"0 0 0\"/><axis xyz=\"0 0 1\"/>\n"
    "    <limit lower=\"-1.0\" upper=\"1.0\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"head_nod\" type=\"revolute\">\n"
    "    <parent link=\"neck\"/><child link=\"head\"/>\n"
    "    <origin xyz=\"0 0 0.10\" rpy=\"0 0 0\"/><axis xyz=\"0 1 0\"/>\n"
    "    <limit lower=\"-0.5\" upper=\"0.6\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"l_shoulder_abduct\" type=\"revolute\">\n"
    "    <parent link=\"torso\"/><child link=\"l_upper_arm\"/>\n"
    "    <origin xyz=\"0 0.17 0.36\" rpy=\"0 0 0\"/><axis xyz=\"-1 0 0\"/>\n"
    "    <limit lower=\"-0.6\" upper=\"1.8\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"l_elbow\" type=\"revolute\">\n"
    "    <parent link=\"l_upper_arm\"/><child link=\"l_forearm\"/>\n"
    "    <origin xyz=\"0 0.28 0\" rpy=\"0 0 0\"/><axis xyz=\"0 0 -1\"/>\n"
    "    <limit lower=\"0\" upper=\"2.6\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"r_shoulder_abduct\" type=\"revolute\">\n"
    "    <parent link=\"torso\"/><child link=\"r_upper_arm\"/>\n"
    "    <origin xyz=\"0 -0.17 0.36\" rpy=\"0 0 0\"/><axis xyz=\"1 0 0\"/>\n"
    "    <limit lower=\"-0.6\" upper=\"1.8\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"r_elbow\" type=\"revolute\">\n"
    "    <parent link=\"r_upper_arm\"/><child link=\"r_forearm\"/>\n"
    "    <origin xyz=\"0 -0.28 0\" rpy=\"0 0 0\"/><axis xyz=\"0 0 1\"/>\n"
    "    <limit lower=\"0\" upper=\"2.6\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"l_hip\" type=\"revolute\">\n"
    "    <parent link=\"pelvis\"/><child link=\"l_thigh\"/>\n"
    "    <origin xyz=\"0 0.10 -0.06\" rpy=\"0 0 0\"/><axis xyz=\"0 -1 0\"/>\n"
    "    <limit lower=\"-0.5\" upper=\"1.6\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"l_knee\" type=\"revolute\">\n"
    "    <parent link=\"l_thigh\"/><child link=\"l_shin\"/>\n"
    "    <origin xyz=\"0 0 -0.42\" rpy=\"0 0 0\"/><axis xyz=\"0 1 0\"/>\n"
    "    <limit lower=\"0\" upper=\"2.2\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"r_hip\" type=\"revolute\">\n"
    "    <parent link=\"pelvis\"/><child link=\"r_thigh\"/>\n"
    "    <origin xyz=\"0 -0.10 -0.06\" rpy=\"0 0 0\"/><axis xyz=\"0 -1 0\"/>\n"
    "    <limit lower=\"-0.5\" upper=\"1.6\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "  <joint name=\"r_knee\" type=\"revolute\">\n"
    "    <parent link=\"r_thigh\"/><child link=\"r_shin\"/>\n"
    "    <origin xyz=\"0 0 -0.42\" rpy=\"0 0 0\"/><axis xyz=\"0 1 0\"/>\n"
    "    <limit lower=\"0\" upper=\"2.2\" effort=\"100\" velocity=\"5\"/>\n"
    "  </joint>\n"
    "</robot>\n";

const char *ssa_mannequin_urdf(void) { return mannequin_urdf; }

/* ---------------------------------------------------------------- the implicit body */

typedef struct prim {
  int kind;      /* 0 capsule, 1 ellipsoid */
  double a[3];   /* capsule start or ellipsoid centre */
  double b[3];   /* capsule end or ellipsoid radii */
  double r0, r1; /* capsule radius at a and at b */
} prim;

/* In the zero pose, world = pelvis frame. See urdf/mannequin.urdf. */
static const prim body_prims[] = {
    /* torso: chest and belly/pelvis */
    {1, {0.0, 0.0, 0.33}, {0.115, 0.175, 0.20}, 0, 0},
    {1, {0.0, 0.0, 0.03}, {0.115, 0.155, 0.17}, 0, 0},
    /* neck and head */
    {0, {0.0, 0.0, 0.47}, {0.0, 0.0, 0.62}, 0.05, 0.048},
    {1, {0.01, 0.0, 0.71}, {0.10, 0.085, 0.115}, 0, 0},
    /* arms: shoulder (inside the chest) to elbow, elbow to wrist, hand */
    {0, {0.0, 0.12, 0.45}, {0.0, 0.45, 0.46}, 0.055, 0.042},
    {0, {0.0, 0.45, 0.46}, {0.0, 0.70, 0.46}, 0.042, 0.034},
    {1, {0.0, 0.76, 0.46}, {0.035, 0.07, 0.045}, 0, 0},
    {0, {0.0, -0.12, 0.45}, {0.0, -0.45, 0.46}, 0.055, 0.042},
    {0, {0.0, -0.45, 0.46}, {0.0, -0.70, 0.46}, 0.042, 0.034},
    {1, {0.0, -0.76, 0.46}, {0.035, 0.07, 0.045}, 0, 0},
    /* legs: hip to knee, knee to ankle, foot */
    {0, {0.0, 0.10, -0.04}, {0.0, 0.10, -0.48}, 0.075, 0.052},
    {0, {0.0, 0.10, -0.48}, {0.0, 0.10, -0.88}, 0.052, 0.04},
    {1, {0.05, 0.10, -0.92}, {0.11, 0.05, 0.04}, 0, 0},
    {0, {0.0, -0.10, -0.04}, {0.0, -0.10, -0.48}, 0.075, 0.052},
    {0, {0.0, -0.10, -0.48}, {0.0, -0.10, -0.88}, 0.052, 0.04},
    {1, {0.05, -0.10, -0.92}, {0.11, 0.05, 0.04}, 0, 0},
};
#define NPRIM ((int)(sizeof body_prims / sizeof body_prims[0]))
static const double BLEND = 0.025; /* smooth-union width, metres */
static const double BOX_LO[3] = {-0.20, -0.90, -1.02};
static const double BOX_HI[3] = {0.25, 0.90, 0.90};

static double prim_dist(const prim *p, const double *x) {
  if (p->kind == 0) {
    double d[3] = {p->b[0] - p->a[0], p->b[1] - p->a[1], p->b[2] - p->a[2]};
    double w[3] = {x[0] - p->a[0], x[1] - p->a[1], x[2] - p->a[2]};
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double t = (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
    double e[3] = {w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]};
    return sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) - (p->r0 + t * (p->r1 - p->r0));
  }
  double u[3], rmin = p->b[0];
  for (int c = 0; c < 3; c++) {
    u[c] = (x[c] - p->a[c]) / p->b[c];
    if (p->b[c] < rmin) rmin = p->b[c];
  }
  return (sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) - 1.0) * rmin;
}

/* Signed field: negative inside the body. */
static double body_field(const double *x) {
  double f = prim_dist(&body_prims[0], x);
  for (int i = 1; i < NPRIM; i++) {
    double g = prim_dist(&body_prims[i], x);
    double h = BLEND - fabs(f - g);
    f = (f < g ? f : g) - (h > 0 ? h * h / (4.0 * BLEND) : 0.0);
  }
  return f;
}

static void body_grad(const double *x, double *g) {
  const double e = 1e-5;
  for (int c = 0; c < 3; c++) {
    double a[3] = {x[0], x[1], x[2]}, b[3] = {x[0], x[1], x[2]};
    a[c] += e;
    b[c] -= e;
    g[c] = (body_field(a) - body_field(b)) / (2 * e);
  }
}

/* ---------------------------------------------------------------- marching tetrahedra */

typedef struct mt_out {
  int nvert, cap_v, nface, cap_f;
  double *pos;
  int *faces;
  /* edge hash: key (two grid point ids) -> vertex */
  int64_t *hkey;
  int *hval;
  int64_t hcap;
} mt_out;

static int mt_push_vert(mt_out *m, const double *p) {
  if (m->nvert == m->cap_v) {
    int nc = m->cap_v ? 2 * m->cap_v : 4096;
    double *np = realloc(m->pos, sizeof(double) * 3 * (size_t)nc);
    if (!np) return -1;
    m->pos = np;
    m->cap_v = nc;
  }
  memcpy(m->pos + 3 * m->nvert, p, 3 * sizeof(double));
  return m->nvert++;
}

static int mt_push_face(mt_out *m, int a, int b, int c) {
  if (m->nface == m->cap_f) {
    int nc = m->cap_f ? 2 * m->cap_f : 8192;
    int *nf = realloc(m->faces, sizeof(int) * 3 * (size_t)nc);
    if (!nf) return 0;
    m->faces = nf;
    m->cap_f = nc;
  }
  m->faces[3 * m->nface] = a;
  m->faces[3 * m->nface + 1] = b;
  m->faces[3 * m->nface + 2] = c;
  m->nface++;
  return 1;
}

static int hash_grow(mt_out *m) {
  int64_t nc = m->hcap ? 2 * m->hcap : 1 << 15;
  int64_t *nk = malloc(sizeof(int64_t) * (size_t)nc);
  int *nv = malloc(sizeof(int) * (size_t)nc);
  if (!nk || !nv) {
    free(nk);
    free(nv);
    return 0;
  }
  for (int64_t i = 0; i < nc; i++) nk[i] = -1;
  for (int64_t i = 0; i < m->hcap; i++) {
    if (m->hkey[i] < 0) continue;
    uint64_t h = ((uint64_t)m->hkey[i] * 0x9E3779B97F4A7C15ULL) >> 20;
    int64_t s = (int64_t)(h % (uint64_t)nc);
    while (nk[s] >= 0) s = (s + 1) % nc;
    nk[s] = m->hkey[i];
    nv[s] = m->hval[i];
  }
  free(m->hkey);
  free(m->hval);
  m->hkey = nk;
  m->hval = nv;
  m->hcap = nc;
  return 1;
}

/* The vertex on the grid edge (ga, gb), created at the field's zero. */
static int edge_vertex(mt_out *m, int64_t ga, int64_t gb, const double *pa, const double *pb,
                       double fa, double fb, int64_t npoint) {
  if (ga > gb) {
    int64_t t = ga;
    ga = gb;
    gb = t;
    const double *tp = pa;
    pa = pb;
    pb = tp;
    double tf = fa;
    fa = fb;
    fb = tf;
  }
  int64_t key = ga * npoint + gb;
  if (2 * (int64_t)m->nvert + 2 >= m->hcap && !hash_grow(m)) return -1;
  uint64_t h = ((uint64_t)key * 0x9E3779B97F4A7C15ULL) >> 20;
  int64_t s = (int64_t)(h % (uint64_t)m->hcap);
  while (m->hkey[s] >= 0) {
    if (m->hkey[s] == key) return m->hval[s];
    s = (s + 1) % m->hcap;
  }
  double t = fa / (fa - fb), p[3];
  for (int c = 0; c < 3; c++) p[c] = pa[c] + t * (pb[c] - pa[c]);
  int v = mt_push_vert(m, p);
  if (v < 0) return -1;
  m->hkey[s] = key;
  m->hval[s] = v;
  return v;
}

/* Adds triangle (a, b, c) oriented so that its normal points from in to out. */
static int add_oriented(mt_out *m, int a, int b, int c, const double *in_c, const double *out_c) {
  const double *p0 = m->pos + 3 * a, *p1 = m->pos + 3 * b, *p2 = m->pos + 3 * c;
  double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
  double d[3] = {out_c[0] - in_c[0], out_c[1] - in_c[1], out_c[2] - in_c[2]};
  if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < 0) return mt_push_face(m, a, c, b);
  return mt_push_face(m, a, b, c);
}

/* Kuhn triangulation of the unit cube: 6 tetrahedra around the diagonal 0-7
 * (corner bit 0 = x, bit 1 = y, bit 2 = z). */
static const int kuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                               {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

static int polygonise(double h, mt_out *m) {
  int n[3];
  for (int c = 0; c < 3; c++) n[c] = (int)ceil((BOX_HI[c] - BOX_LO[c]) / h) + 1;
  int64_t npoint = (int64_t)n[0] * n[1] * n[2];
  double *f = malloc(sizeof(double) * (size_t)npoint);
  if (!f) return 0;
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++) {
        double x[3] = {BOX_LO[0] + i * h, BOX_LO[1] + j * h, BOX_LO[2] + k * h};
        double v = body_field(x);
        if (i == 0 || j == 0 || k == 0 || i == n[0] - 1 || j == n[1] - 1 || k == n[2] - 1)
          v = fabs(v) + h; /* outside at the box's border: the surface closes */
        if (v == 0.0) v = 1e-12; /* no grid point exactly on the surface */
        f[((int64_t)k * n[1] + j) * n[0] + i] = v;
      }
  int ok = 1;
  for (int k = 0; ok && k < n[2] - 1; k++)
    for (int j = 0; ok && j < n[1] - 1; j++)
      for (int i = 0; ok && i < n[0] - 1; i++) {
        int64_t g[8];
        double fv[8], p[8][3];
        int nin = 0;
        for (int c = 0; c < 8; c++) {
          int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
          g[c] = ((int64_t)(k + dk) * n[1] + (j + dj)) * n[0] + (i + di);
          fv[c] = f[g[c]];
          p[c][0] = BOX_LO[0] + (i + di) * h;
          p[c][1] = BOX_LO[1] + (j + dj) * h;
          p[c][2] = BOX_LO[2] + (k + dk) * h;
          nin += fv[c] < 0;
        }
        if (nin == 0 || nin == 8) continue;
        for (int t = 0; ok && t < 6; t++) {
          int in[4], out[4], ni = 0, no = 0;
          for (int c = 0; c < 4; c++) {
            int cc = kuhn[t][c];
            if (fv[cc] < 0)
              in[ni++] = cc;
            else
              out[no++] = cc;
          }
          if (ni == 0 || no == 0) continue;
          double ic[3] = {0, 0, 0}, oc[3] = {0, 0, 0};
          for (int q = 0; q < ni; q++)
            for (int c = 0; c < 3; c++) ic[c] += p[in[q]][c] / ni;
          for (int q = 0; q < no; q++)
            for (int c = 0; c < 3; c++) oc[c] += p[out[q]][c] / no;
#define EV(a, b) edge_vertex(m, g[a], g[b], p[a], p[b], fv[a], fv[b], npoint)
          if (ni == 1 || no == 1) {
            int lone = ni == 1 ? in[0] : out[0];
            int *others = ni == 1 ? out : in;
            int v0 = EV(lone, others[0]), v1 = EV(lone, others[1]), v2 = EV(lone, others[2]);
            ok = v0 >= 0 && v1 >= 0 && v2 >= 0 && add_oriented(m, v0, v1, v2, ic, oc);
          } else { /* two in, two out: a quad */
            int v0 = EV(in[0], out[0]), v1 = EV(in[0], out[1]);
            int v2 = EV(in[1], out[1]), v3 = EV(in[1], out[0]);
            ok = v0 >= 0 && v1 >= 0 && v2 >= 0 && v3 >= 0 && add_oriented(m, v0, v1, v2, ic, oc) &&
                 add_oriented(m, v0, v2, v3, ic, oc);
          }
#undef EV
        }
      }
  free(f);
  return ok;
}

/* Tangential smoothing, then Newton steps back onto the surface. */
static int relax(mt_out *m, int iters) {
  double *acc = malloc(sizeof(double) * 3 * (size_t)m->nvert);
  int *cnt = malloc(sizeof(int) * (size_t)m->nvert);
  if (!acc || !cnt) {
    free(acc);
    free(cnt);
    return 0;
  }
  for (int it = 0; it < iters; it++) {
    memset(acc, 0, sizeof(double) * 3 * (size_t)m->nvert);
    memset(cnt, 0, sizeof(int) * (size_t)m->nvert);
    for (int f = 0; f < m->nface; f++)
      for (int c = 0; c < 3; c++) {
        int a = m->faces[3 * f + c], b = m->faces[3 * f + (c + 1) % 3];
        for (int d = 0; d < 3; d++) {
          acc[3 * a + d] += m->pos[3 * b + d];
          acc[3 * b + d] += m->pos[3 * a + d];
        }
        cnt[a]++;
        cnt[b]++;
      }
    for (int v = 0; v < m->nvert; v++) {
      double *p = m->pos + 3 * v, g[3];
      if (cnt[v] == 0) continue;
      double d[3];
      for (int c = 0; c < 3; c++) d[c] = acc[3 * v + c] / cnt[v] - p[c];
      body_grad(p, g);
      double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
      if (gg > 0) {
        double dn = (d[0] * g[0] + d[1] * g[1] + d[2] * g[2]) / gg;
        for (int c = 0; c < 3; c++) d[c] -= dn * g[c];
      }
      for (int c = 0; c < 3; c++) p[c] += 0.5 * d[c];
      for (int s = 0; s < 3; s++) {
        double fv = body_field(p);
        body_grad(p, g);
        gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
        if (!(gg > 1e-12)) break;
        for (int c = 0; c < 3; c++) p[c] -= fv * g[c] / gg;
      }
    }
  }
  free(acc);
  free(cnt);
  return 1;
}

int ssa_mannequin_mesh(int target_tris, double **pos, int *nvert, int **faces, int *nface,
                       char *err, int err_sz) {
  if (!pos || !nvert || !faces || !nface)
    return ss_fail(err, err_sz, SS_E_ARG, "mannequin: missing output arguments");
  *pos = NULL;
  *faces = NULL;
  *nvert = *nface = 0;
  if (target_tris <= 0) target_tris = 5000;
  if (target_tris < 3000 || target_tris > 5000000)
    return ss_fail(err, err_sz, SS_E_ARG,
                   "mannequin: %d triangles is outside the supported range [3000, 5000000]",
                   target_tris);
  /* about 3.9 triangles per h^2 per m^2 of surface, about 1.45 m^2: calibrated below */
  double h = sqrt(1.45 * 3.9 / target_tris);
  mt_out m;
  memset(&m, 0, sizeof m);
  int ok = 1;
  for (int pass = 0; pass < 4; pass++) {
    free(m.pos);
    free(m.faces);
    free(m.hkey);
    free(m.hval);
    memset(&m, 0, sizeof m);
    if (!(ok = polygonise(h, &m))) break;
    double ratio = (double)m.nface / target_tris;
    if (fabs(ratio - 1.0) < 0.05) break;
    h *= sqrt(ratio);
  }
  free(m.hkey);
  free(m.hval);
  m.hkey = NULL;
  m.hval = NULL;
  if (!ok || m.nface == 0 || !relax(&m, 6)) {
    free(m.pos);
    free(m.faces);
    return ss_fail(err, err_sz, SS_E_NOMEM, "mannequin: out of memory generating the body");
  }
  *pos = m.pos;
  *faces = m.faces;
  *nvert = m.nvert;
  *nface = m.nface;
  return SS_OK;
}

int ssa_avatar_mannequin(ssa_avatar **out, int target_tris, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  ssa_robot *r = NULL;
  int st = ssa_robot_load_string(&r, mannequin_urdf, NULL, NULL, err, err_sz);
  if (st != SS_OK) return st;
  double *pos = NULL;
  int *faces = NULL, nv = 0, nf = 0;
  st = ssa_mannequin_mesh(target_tris, &pos, &nv, &faces, &nf, err, err_sz);
  if (st != SS_OK) {
    ssa_robot_destroy(r);
    return st;
  }
  ssa_avatar_opts o = ssa_avatar_default_opts();
  o.weld_tol = 0.0;
  st = ssa_avatar_from_robot_mesh(out, r, nv, pos, nf, faces, &o, err, err_sz);
  free(pos);
  free(faces);
  return st;
}
