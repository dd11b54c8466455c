/* The built-in scenes: sizes, mesh validity, motion, and that each scene is
 * hard in the way it claims (self-intersection, thin fold, fast twist,
 * slivers and zero-area faces, open boundary, legs through the belly). */
#include <stdint.h>
#include <string.h>

#include "ss_scene.h"
#include "ss_test.h"

static int cmp_ll(const void *a, const void *b) {
  long long x = *(const long long *)a, y = *(const long long *)b;
  return (x > y) - (x < y);
}

static int has_key(const long long *keys, int n, long long k) {
  return bsearch(&k, keys, (size_t)n, sizeof k, cmp_ll) != NULL;
}

/* Directed half-edges a*nv+b, sorted. */
static long long *half_edges(const ss_scene *s) {
  int nf = ss_scene_nface(s), nv = ss_scene_nvert(s);
  const int *f = ss_scene_faces(s);
  long long *keys = malloc(sizeof(long long) * 3 * (size_t)nf);
  for (int i = 0; i < nf; i++)
    for (int k = 0; k < 3; k++)
      keys[3 * i + k] = (long long)f[3 * i + k] * nv + f[3 * i + (k + 1) % 3];
  qsort(keys, 3 * (size_t)nf, sizeof *keys, cmp_ll);
  return keys;
}

static void sub(const double *a, const double *b, double *o) {
  for (int c = 0; c < 3; c++) o[c] = a[c] - b[c];
}
static void cross(const double *a, const double *b, double *o) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double dist(const double *a, const double *b) {
  double d[3];
  sub(a, b, d);
  return sqrt(dot(d, d));
}

static double mean_edge(const ss_scene *s, const double *pos) {
  const int *f = ss_scene_faces(s);
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < ss_scene_nface(s); i++)
    for (int k = 0; k < 3; k++) {
      int a = f[3 * i + k], b = f[3 * i + (k + 1) % 3];
      sum += dist(pos + 3 * a, pos + 3 * b); /* interior edges twice: same mean */
      n++;
    }
  return sum / n;
}

/* Ray (origin o, direction d) against triangle (Moller-Trumbore); t > eps. */
static int ray_hits(const double *o, const double *d, const double *a, const double *b,
                    const double *c) {
  double e1[3], e2[3], pv[3], tv[3], qv[3];
  sub(b, a, e1);
  sub(c, a, e2);
  cross(d, e2, pv);
  double det = dot(e1, pv);
  if (fabs(det) < 1e-14) return 0;
  sub(o, a, tv);
  double u = dot(tv, pv) / det;
  if (u < 0.0 || u > 1.0) return 0;
  cross(tv, e1, qv);
  double v = dot(d, qv) / det;
  if (v < 0.0 || u + v > 1.0) return 0;
  return dot(e2, qv) / det > 1e-9;
}

/* Vertices whose ray along their outward vertex normal crosses the mesh an odd
 * number of times (faces touching the vertex excluded): vertices inside
 * another part of the body. */
static int vertices_inside(const ss_scene *s, const double *pos) {
  int nv = ss_scene_nvert(s), nf = ss_scene_nface(s);
  const int *f = ss_scene_faces(s);
  double *vn = calloc(3 * (size_t)nv, sizeof(double));
  for (int i = 0; i < nf; i++) {
    double e1[3], e2[3], n[3];
    sub(pos + 3 * f[3 * i + 1], pos + 3 * f[3 * i], e1);
    sub(pos + 3 * f[3 * i + 2], pos + 3 * f[3 * i], e2);
    cross(e1, e2, n);
    for (int k = 0; k < 3; k++)
      for (int c = 0; c < 3; c++) vn[3 * f[3 * i + k] + c] += n[c];
  }
  int inside = 0;
  for (int v = 0; v < nv; v++) {
    /* tilt the ray a little so it does not run exactly along mesh edges */
    double *d = vn + 3 * v, len = sqrt(dot(d, d));
    const double tilt[3] = {0.0123, 0.0311, -0.0217};
    for (int c = 0; c < 3; c++) d[c] = d[c] / len + tilt[c];
    int hits = 0;
    for (int i = 0; i < nf; i++) {
      const int *t = f + 3 * i;
      if (t[0] == v || t[1] == v || t[2] == v) continue;
      hits += ray_hits(pos + 3 * v, vn + 3 * v, pos + 3 * t[0], pos + 3 * t[1], pos + 3 * t[2]);
    }
    inside += hits & 1;
  }
  free(vn);
  return inside;
}

/* Connected components of the faces: comp[v] for every vertex (a root id);
 * returns the number of components. */
static int find_root(int *up, int v) {
  while (up[v] != v) v = up[v] = up[up[v]];
  return v;
}
static int components(const ss_scene *s, int *comp) {
  int nv = ss_scene_nvert(s), nf = ss_scene_nface(s), n = nv;
  const int *f = ss_scene_faces(s);
  for (int v = 0; v < nv; v++) comp[v] = v;
  for (int i = 0; i < nf; i++)
    for (int k = 1; k < 3; k++) {
      int a = find_root(comp, f[3 * i]), b = find_root(comp, f[3 * i + k]);
      if (a != b) {
        comp[a] = b;
        n--;
      }
    }
  for (int v = 0; v < nv; v++) comp[v] = find_root(comp, v);
  return n;
}

/* Whether point p lies inside the closed component `part` (ray parity against
 * its faces only, along a direction no mesh edge follows: nearly straight up,
 * so faces further than 5 cm aside in x or y are skipped; the ray drifts
 * < 5 cm sideways within a body of < 1.5 m). */
static int inside_part(const ss_scene *s, const int *comp, int part, const double *pos,
                       const double *p) {
  static const double d[3] = {0.0123, 0.0311, 0.9993};
  const int *f = ss_scene_faces(s);
  int hits = 0;
  for (int i = 0; i < ss_scene_nface(s); i++) {
    const int *t = f + 3 * i;
    if (comp[t[0]] != part) continue;
    int aside = 0;
    for (int c = 0; c < 2; c++) {
      double a = pos[3 * t[0] + c], b = pos[3 * t[1] + c], e = pos[3 * t[2] + c];
      aside |= fmax(a, fmax(b, e)) < p[c] - 0.05 || fmin(a, fmin(b, e)) > p[c] + 0.05;
    }
    if (!aside) hits += ray_hits(p, d, pos + 3 * t[0], pos + 3 * t[1], pos + 3 * t[2]);
  }
  return hits & 1;
}

/* The quadruped's hind legs pass through its belly: leg vertices that lie
 * outside the torso at rest lie inside it at the peak of every stride. */
static void check_quadruped(const ss_scene *s, int frames) {
  int nv = ss_scene_nvert(s);
  const double *rest = ss_scene_rest(s);
  int *comp = malloc(sizeof(int) * (size_t)nv), *size = calloc((size_t)nv, sizeof(int));
  double *cen = calloc(3 * (size_t)nv, sizeof(double)), *pos = malloc(sizeof(double) * 3 * nv);
  int ncomp = components(s, comp), torso = 0;
  for (int v = 0; v < nv; v++) {
    size[comp[v]]++;
    for (int c = 0; c < 3; c++) cen[3 * comp[v] + c] += rest[3 * v + c];
  }
  for (int v = 0; v < nv; v++)
    if (size[v] > size[torso]) torso = v; /* the biggest part */
  double zmin = INFINITY;
  for (int v = 0; v < nv; v++)
    if (comp[v] == torso) zmin = fmin(zmin, rest[3 * v + 2]);
  /* legs: parts whose centroid lies below the torso; hind: behind its centroid */
  int legs = 0, hind = 0;
  unsigned char *is_hind = calloc((size_t)nv, 1);
  for (int r = 0; r < nv; r++) {
    if (!size[r]) continue;
    double z = cen[3 * r + 2] / size[r], x = cen[3 * r] / size[r];
    if (z < zmin) {
      legs++;
      if (x < cen[3 * torso] / size[torso]) {
        hind++;
        is_hind[r] = 1;
      }
    }
  }
  printf("  quadruped: %d closed parts, %d legs (%d hind)\n", ncomp, legs, hind);
  CHECK_EQ_INT(legs, 4);
  CHECK_EQ_INT(hind, 2);
  /* hind-leg vertices outside the torso at rest */
  unsigned char *out = calloc((size_t)nv, 1);
  int nout = 0, nhind = 0;
  for (int v = 0; v < nv; v++)
    if (is_hind[comp[v]]) {
      nhind++;
      out[v] = !inside_part(s, comp, torso, rest, rest + 3 * v);
      nout += out[v];
    }
  CHECK(nout > nhind / 2);
  /* it happens in the first stride after the ramp (frames 6-17), and again at
   * the same phase of every later stride (the gallop repeats every 12 frames) */
  int peak_all = 0, peak_frame = 6;
  for (int k = 6; k < 18; k++) {
    ss_scene_pose(s, k, pos);
    int in = 0;
    for (int v = 0; v < nv; v++)
      if (out[v]) in += inside_part(s, comp, torso, pos, pos + 3 * v);
    if (in > peak_all) {
      peak_all = in;
      peak_frame = k;
    }
  }
  CHECK_MSG(peak_all >= nhind / 10, "quadruped: only %d of %d hind-leg vertices in the torso",
            peak_all, nhind);
  for (int k = peak_frame + 12; k <= frames; k += 12) {
    ss_scene_pose(s, k, pos);
    int in = 0;
    for (int v = 0; v < nv; v++)
      if (out[v]) in += inside_part(s, comp, torso, pos, pos + 3 * v);
    CHECK_MSG(abs(in - peak_all) <= 2 + peak_all / 50,
              "quadruped: frame %d: %d hind-leg vertices in the torso, not %d", k,
              in, peak_all);
  }
  printf("  quadruped: up to %d of %d hind-leg vertices pass into the torso (frame %d)\n",
         peak_all, nhind, peak_frame);
  free(comp);
  free(size);
  free(cen);
  free(pos);
  free(is_hind);
  free(out);
}

static int all_finite(const double *p, int n) {
  for (int i = 0; i < n; i++)
    if (!isfinite(p[i])) return 0;
  return 1;
}

/* Signed volume enclosed by the faces at pos. */
static double volume(const ss_scene *s, const double *pos) {
  const int nf = ss_scene_nface(s);
  const int *f = ss_scene_faces(s);
  double vol = 0.0;
  for (int i = 0; i < nf; i++) {
    double c[3];
    cross(pos + 3 * f[3 * i + 1], pos + 3 * f[3 * i + 2], c);
    vol += dot(pos + 3 * f[3 * i], c) / 6.0;
  }
  return vol;
}

static void check_scene(int index) {
  const char *name = ss_scene_name(index);
  char err[256] = "";
  ss_scene *s = NULL;
  int status = ss_scene_create(&s, name, 0, err, sizeof err);
  CHECK_MSG(status == SS_OK && s, "%s: %s", name, err);
  if (status) return;
  CHECK(strcmp(ss_scene_get_name(s), name) == 0);
  CHECK(ss_scene_about(index) && strlen(ss_scene_about(index)) > 10);
  const int nv = ss_scene_nvert(s), nf = ss_scene_nface(s), frames = ss_scene_default_frames(s);
  const int *f = ss_scene_faces(s);
  const double *rest = ss_scene_rest(s);
  const int closed = strcmp(name, "slivers") != 0 && strcmp(name, "boundary") != 0;
  const int quad = strcmp(name, "quadruped") == 0;
  printf("%-9s default: %5d triangles %5d vertices %3d frames\n", name, nf, nv, frames);
  if (quad) /* the paper's raccoon: 18,929 triangles */
    CHECK_MSG(nf >= 17000 && nf <= 21000, "%s: default %d triangles", name, nf);
  else
    CHECK_MSG(nf >= 1500 && nf <= 5000, "%s: default %d triangles", name, nf);
  CHECK(frames >= 30 && frames <= 120);
  CHECK_NEAR(ss_scene_fps(s), 30.0, 0.0);
  int bad = 0;
  for (int i = 0; i < 3 * nf; i++) bad += f[i] < 0 || f[i] >= nv;
  CHECK_EQ_INT(bad, 0);
  CHECK(all_finite(rest, 3 * nv));

  /* rest == frame 0, bit for bit; poses finite and deterministic */
  double *pos = malloc(sizeof(double) * 3 * (size_t)nv);
  double *pos2 = malloc(sizeof(double) * 3 * (size_t)nv);
  ss_scene_pose(s, 0.0, pos);
  CHECK(memcmp(pos, rest, sizeof(double) * 3 * (size_t)nv) == 0);
  int finite = 1, moved = 0;
  for (int k = 0; k <= frames + 10; k++) {
    ss_scene_pose(s, k, pos);
    finite &= all_finite(pos, 3 * nv);
    if (k > 0) moved |= memcmp(pos, rest, sizeof(double) * 3 * (size_t)nv) != 0;
    ss_scene_pose(s, k + 0.37, pos);
    finite &= all_finite(pos, 3 * nv);
  }
  const double odd_frames[] = {-3.0, 1e-9, 1e4, 1e300, NAN, INFINITY};
  for (int k = 0; k < 6; k++) {
    ss_scene_pose(s, odd_frames[k], pos);
    finite &= all_finite(pos, 3 * nv);
  }
  CHECK_MSG(finite, "%s: a pose is not finite", name);
  CHECK_MSG(moved, "%s: the body never moves", name);
  ss_scene_pose(s, 17.25, pos);
  ss_scene_pose(s, 17.25, pos2);
  CHECK(memcmp(pos, pos2, sizeof(double) * 3 * (size_t)nv) == 0);
  /* smooth in time: a small step in frame moves the body a little */
  ss_scene_pose(s, 17.26, pos2);
  double jump = 0.0;
  for (int v = 0; v < nv; v++) jump = fmax(jump, dist(pos + 3 * v, pos2 + 3 * v));
  const double edge = mean_edge(s, rest);
  CHECK_MSG(jump < 0.2 * edge, "%s: pose jumps %g in 0.01 frame", name, jump);

  /* the settle's way back to rest (ss_scene_pose_toward_rest): w 0 is the
   * frame's pose and w 1 rest, bit for bit; on the way the body keeps its
   * shape: no edge stretched or shrunk, and (closed bodies) the volume not
   * changed, more than during the motion itself (+ 2%); a blend of the
   * positions fails this on armpit, elbow, twist, slivers and boundary */
  {
    double motion_dev = 0.0, way_dev = 0.0, lin_dev = 0.0;
    double motion_vol = 0.0, way_vol = 0.0, lin_vol = 0.0;
    const double vol0 = volume(s, rest);
    double *last = malloc(sizeof(double) * 3 * (size_t)nv);
    double *lin = malloc(sizeof(double) * 3 * (size_t)nv);
    ss_scene_pose(s, frames, last);
    ss_scene_pose_toward_rest(s, frames, 0.0, pos);
    CHECK_MSG(memcmp(pos, last, sizeof(double) * 3 * (size_t)nv) == 0, "%s: w 0 is not the pose", name);
    ss_scene_pose_toward_rest(s, frames, 1.0, pos);
    CHECK_MSG(memcmp(pos, rest, sizeof(double) * 3 * (size_t)nv) == 0, "%s: w 1 is not rest", name);
    for (int k = 0; k <= frames + 8; k++) {
      const double w = k > frames ? (k - frames) / 8.0 : -1.0;
      if (w < 0.0) ss_scene_pose(s, k, pos);
      else ss_scene_pose_toward_rest(s, frames, w, pos);
      for (int i = 0; w >= 0.0 && i < 3 * nv; i++) lin[i] = last[i] + w * (rest[i] - last[i]);
      double dev = 0.0, dev_lin = 0.0;
      for (int i = 0; i < nf; i++)
        for (int c = 0; c < 3; c++) {
          const int a = f[3 * i + c], b = f[3 * i + (c + 1) % 3];
          const double l0 = dist(rest + 3 * a, rest + 3 * b);
          if (!(l0 > 0.0)) continue;
          dev = fmax(dev, fabs(dist(pos + 3 * a, pos + 3 * b) / l0 - 1.0));
          if (w >= 0.0) dev_lin = fmax(dev_lin, fabs(dist(lin + 3 * a, lin + 3 * b) / l0 - 1.0));
        }
      const double vdev = closed ? fabs(volume(s, pos) / vol0 - 1.0) : 0.0;
      if (w < 0.0) {
        motion_dev = fmax(motion_dev, dev);
        motion_vol = fmax(motion_vol, vdev);
      } else {
        way_dev = fmax(way_dev, dev);
        way_vol = fmax(way_vol, vdev);
        lin_dev = fmax(lin_dev, dev_lin);
        if (closed) lin_vol = fmax(lin_vol, fabs(volume(s, lin) / vol0 - 1.0));
      }
    }
    printf("%-9s largest change of an edge / of the volume: motion %.3f / %.3f, way back to rest "
           "%.3f / %.3f (positions blended: %.3f / %.3f)\n",
           name, motion_dev, motion_vol, way_dev, way_vol, lin_dev, lin_vol);
    CHECK_MSG(way_dev <= motion_dev + 0.02, "%s: the way back to rest changes an edge by %.3f, the "
              "motion by %.3f", name, way_dev, motion_dev);
    CHECK_MSG(way_vol <= motion_vol + 0.02, "%s: the way back to rest changes the volume by %.3f, "
              "the motion by %.3f", name, way_vol, motion_vol);
    free(last);
    free(lin);
  }

  /* topology: closed meshes are watertight and consistently oriented */
  long long *keys = half_edges(s);
  int dup = 0, open = 0;
  for (int i = 0; i < 3 * nf; i++) {
    if (i > 0 && keys[i] == keys[i - 1]) dup++;
    long long a = keys[i] / nv, b = keys[i] % nv;
    if (!has_key(keys, 3 * nf, b * nv + a)) open++;
  }
  CHECK_MSG(dup == 0, "%s: %d repeated directed edges (non-manifold or flipped faces)", name, dup);
  if (closed) {
    CHECK_MSG(open == 0, "%s: %d edges without a twin", name, open);
    double vol = 0.0;
    for (int i = 0; i < nf; i++) {
      double c[3];
      cross(rest + 3 * f[3 * i + 1], rest + 3 * f[3 * i + 2], c);
      vol += dot(rest + 3 * f[3 * i], c) / 6.0;
    }
    CHECK_MSG(vol > 0.0, "%s: signed volume %g", name, vol);
    /* no duplicate vertices */
    long long *vk = malloc(sizeof(long long) * (size_t)nv);
    for (int v = 0; v < nv; v++) {
      long long q[3];
      for (int c = 0; c < 3; c++) q[c] = llround(rest[3 * v + c] * 1e5) + 400000; /* +-4 m */
      vk[v] = (q[0] * 800001LL + q[1]) * 800001LL + q[2];
    }
    qsort(vk, (size_t)nv, sizeof *vk, cmp_ll);
    int same = 0;
    for (int v = 1; v < nv; v++) same += vk[v] == vk[v - 1];
    CHECK_MSG(same == 0, "%s: %d duplicate vertices", name, same);
    free(vk);
  } else {
    CHECK_MSG(open > 0, "%s: an open sheet should have boundary edges", name);
  }
  free(keys);

  /* what each scene is for */
  if (strcmp(name, "armpit") == 0) {
    CHECK_EQ_INT(vertices_inside(s, rest), 0);
    ss_scene_pose(s, frames, pos);
    int in = vertices_inside(s, pos);
    printf("  armpit: %d vertices inside the body at frame %d\n", in, frames);
    CHECK_MSG(in >= 10, "armpit: only %d vertices inside at the peak", in);
  } else if (strcmp(name, "elbow") == 0) {
    int tip = 0;
    for (int v = 0; v < nv; v++)
      if (rest[3 * v] > rest[3 * tip]) tip = v;
    ss_scene_pose(s, frames, pos);
    double bend = atan2(pos[3 * tip + 2], pos[3 * tip]) * 180.0 / 3.14159265358979;
    CHECK_MSG(bend > 120.0, "elbow: bent %g degrees", bend);
  } else if (strcmp(name, "fold") == 0) {
    double zmin = INFINITY, zmax = -INFINITY;
    for (int v = 0; v < nv; v++) {
      zmin = fmin(zmin, rest[3 * v + 2]);
      zmax = fmax(zmax, rest[3 * v + 2]);
    }
    double thick = zmax - zmin, speed = 0.0;
    CHECK_MSG(thick < 0.6 * edge, "fold: thickness %g, mean edge %g", thick, edge);
    for (int k = 1; k <= frames; k++) {
      ss_scene_pose(s, k - 1, pos);
      ss_scene_pose(s, k, pos2);
      for (int v = 0; v < nv; v++) speed = fmax(speed, dist(pos + 3 * v, pos2 + 3 * v));
    }
    printf("  fold: thickness %.4f, mean edge %.4f, peak speed %.4f per frame\n", thick, edge,
           speed);
    CHECK_MSG(speed > 3.0 * thick, "fold: peak speed %g, thickness %g", speed, thick);
  } else if (strcmp(name, "twist") == 0) {
    ss_scene_pose(s, frames - 1, pos);
    ss_scene_pose(s, frames, pos2);
    double *d = malloc(sizeof(double) * (size_t)nv);
    for (int v = 0; v < nv; v++) d[v] = dist(pos + 3 * v, pos2 + 3 * v);
    int fast = 0;
    for (int v = 0; v < nv; v++) fast += d[v] > 2.0 * edge;
    printf("  twist: %d of %d vertices move over 2 edges per frame\n", fast, nv);
    CHECK_MSG(fast > nv / 2, "twist: %d of %d vertices fast", fast, nv);
    free(d);
  } else if (strcmp(name, "slivers") == 0) {
    for (int pass = 0; pass < 2; pass++) {
      const double *p = rest;
      if (pass) {
        ss_scene_pose(s, 30.0, pos);
        p = pos;
      }
      double worst = 0.0;
      int zero = 0;
      for (int i = 0; i < nf; i++) {
        const int *t = f + 3 * i;
        double e1[3], e2[3], n[3];
        sub(p + 3 * t[1], p + 3 * t[0], e1);
        sub(p + 3 * t[2], p + 3 * t[0], e2);
        cross(e1, e2, n);
        double area2 = sqrt(dot(n, n));
        double lmax = fmax(dist(p + 3 * t[0], p + 3 * t[1]),
                           fmax(dist(p + 3 * t[1], p + 3 * t[2]), dist(p + 3 * t[2], p + 3 * t[0])));
        if (area2 == 0.0 && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) zero++;
        if (area2 > 0.0) worst = fmax(worst, lmax * lmax / area2);
      }
      if (!pass) printf("  slivers: worst aspect %.0f, %d zero-area faces\n", worst, zero);
      CHECK_MSG(worst > 100.0, "slivers: worst aspect ratio %g", worst);
      CHECK_MSG(zero > 0, "slivers: no zero-area face (pass %d)", pass);
    }
  } else if (quad) {
    check_quadruped(s, frames);
  }
  free(pos);
  free(pos2);
  ss_scene_destroy(s);

  /* sizes */
  const int sizes[] = {3000, 20000, 1000, 60000};
  for (int k = 0; k < (quad ? 4 : 2); k++) {
    ss_scene *t = NULL;
    status = ss_scene_create(&t, name, sizes[k], err, sizeof err);
    CHECK_MSG(status == SS_OK, "%s %d: %s", name, sizes[k], err);
    if (status) continue;
    int n = ss_scene_nface(t);
    CHECK_MSG(fabs((double)n - sizes[k]) <= 0.25 * sizes[k], "%s: asked %d triangles, got %d", name,
              sizes[k], n);
    ss_scene_destroy(t);
  }
}

int main(void) {
  CHECK_EQ_INT(ss_scene_count(), 7);
  const char *names[] = {"armpit", "elbow", "fold", "twist", "slivers", "boundary", "quadruped"};
  for (int i = 0; i < 7; i++) CHECK(ss_scene_name(i) && strcmp(ss_scene_name(i), names[i]) == 0);
  CHECK(ss_scene_name(-1) == NULL && ss_scene_name(7) == NULL && ss_scene_about(7) == NULL);
  for (int i = 0; i < ss_scene_count(); i++) check_scene(i);

  /* bad arguments */
  char err[256];
  ss_scene *s = (ss_scene *)&err; /* must be reset to NULL */
  err[0] = 0;
  CHECK_EQ_INT(ss_scene_create(&s, "raccoon", 0, err, sizeof err), SS_E_ARG);
  CHECK(s == NULL);
  CHECK_MSG(strstr(err, "raccoon") && strstr(err, "armpit") && strstr(err, "boundary"), "%s", err);
  err[0] = 0;
  CHECK_EQ_INT(ss_scene_create(&s, NULL, 0, err, sizeof err), SS_E_ARG);
  CHECK(err[0] != 0);
  const int bad_sizes[] = {-1, 5, 99, 5000001, INT32_MAX};
  for (int k = 0; k < 5; k++) {
    err[0] = 0;
    CHECK_EQ_INT(ss_scene_create(&s, "fold", bad_sizes[k], err, sizeof err), SS_E_ARG);
    CHECK_MSG(err[0] != 0, "no message for %d triangles", bad_sizes[k]);
  }
  CHECK_EQ_INT(ss_scene_create(NULL, "fold", 0, NULL, 0), SS_E_ARG);
  CHECK_EQ_INT(ss_scene_create(&s, "fold", 3, NULL, 0), SS_E_ARG);
  /* small but valid sizes still make sound meshes */
  for (int i = 0; i < ss_scene_count(); i++) {
    CHECK_EQ_INT(ss_scene_create(&s, ss_scene_name(i), 100, err, sizeof err), SS_OK);
    if (s) {
      CHECK(ss_scene_nface(s) > 0 && ss_scene_nface(s) < 400);
      ss_scene_destroy(s);
    }
  }
  ss_scene_destroy(NULL);
  return ss_test_finish("test_scene");
}
