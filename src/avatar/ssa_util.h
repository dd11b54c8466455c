/* Internal helpers of the avatar layer: strings, files and 4x4
 * row-major homogeneous matrices (16 doubles). */
#ifndef SKIN_SIM_AVATAR_SSA_UTIL_H
#define SKIN_SIM_AVATAR_SSA_UTIL_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "skin_sim/ss_common.h"
#include "ss_err.h" /* ss_fail: the one-sentence error, as in the core */

#define SSA_PI 3.14159265358979323846

/* Reads a whole text file (NUL-terminated; free()). NULL and a message naming
 * `what` and the path on failure (robot.c). */
char *ssa_read_text_file(const char *path, const char *what, char *err, int err_sz);

/* One sentence on joint j of robot r whose value v is outside its limits
 * (robot.c; r is a const ssa_robot *). */
struct ssa_robot;
void ssa_limit_sentence(const struct ssa_robot *r, int j, double v, char *msg, int msg_sz);

static inline char *ssa_strdup(const char *s) {
  if (!s) s = "";
  size_t n = strlen(s) + 1;
  char *p = malloc(n);
  if (p) memcpy(p, s, n);
  return p;
}

static inline void ssa_free_strs(char **s, int n) {
  if (!s) return;
  for (int i = 0; i < n; i++) free(s[i]);
  free(s);
}

/* 1 if path ends with ext (".fbx"), ignoring the case of path's letters (ext lower case). */
static inline int ssa_has_ext(const char *path, const char *ext) {
  size_t n = strlen(path), e = strlen(ext);
  if (n < e) return 0;
  for (size_t i = 0; i < e; i++) {
    char c = path[n - e + i];
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    if (c != ext[i]) return 0;
  }
  return 1;
}

static inline void m4_identity(double *m) {
  memset(m, 0, 16 * sizeof(double));
  m[0] = m[5] = m[10] = m[15] = 1.0;
}

/* c = a b (c may alias neither). */
static inline void m4_mul(const double *a, const double *b, double *c) {
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      c[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j] +
                     a[4 * i + 3] * b[12 + j];
}

/* a = a b */
static inline void m4_mul_inplace_right(double *a, const double *b) {
  double t[16];
  m4_mul(a, b, t);
  memcpy(a, t, sizeof t);
}

/* Rigid/affine transform of a point. */
static inline void m4_point(const double *m, const double *p, double *o) {
  double x = p[0], y = p[1], z = p[2];
  o[0] = m[0] * x + m[1] * y + m[2] * z + m[3];
  o[1] = m[4] * x + m[5] * y + m[6] * z + m[7];
  o[2] = m[8] * x + m[9] * y + m[10] * z + m[11];
}

/* General affine inverse (last row 0 0 0 1). Returns 0 if singular. */
static inline int m4_affine_inverse(const double *m, double *o) {
  double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
         k = m[10];
  double A = e * k - f * h, B = -(d * k - f * g), C = d * h - e * g;
  double det = a * A + b * B + c * C;
  if (!(fabs(det) > 1e-300)) return 0;
  double id = 1.0 / det;
  o[0] = A * id;
  o[1] = -(b * k - c * h) * id;
  o[2] = (b * f - c * e) * id;
  o[4] = B * id;
  o[5] = (a * k - c * g) * id;
  o[6] = -(a * f - c * d) * id;
  o[8] = C * id;
  o[9] = -(a * h - b * g) * id;
  o[10] = (a * e - b * d) * id;
  for (int i = 0; i < 3; i++)
    o[4 * i + 3] = -(o[4 * i] * m[3] + o[4 * i + 1] * m[7] + o[4 * i + 2] * m[11]);
  o[12] = o[13] = o[14] = 0.0;
  o[15] = 1.0;
  return 1;
}

/* Rotation from a unit quaternion (x, y, z, w), translation t, scale s (may be NULL). */
static inline void m4_from_tqs(const double *t, const double *q, const double *s, double *m) {
  double x = q[0], y = q[1], z = q[2], w = q[3];
  double n = x * x + y * y + z * z + w * w;
  double k = n > 0 ? 2.0 / n : 0.0;
  double sx = s ? s[0] : 1.0, sy = s ? s[1] : 1.0, sz = s ? s[2] : 1.0;
  m[0] = (1 - k * (y * y + z * z)) * sx;
  m[1] = (k * (x * y - z * w)) * sy;
  m[2] = (k * (x * z + y * w)) * sz;
  m[4] = (k * (x * y + z * w)) * sx;
  m[5] = (1 - k * (x * x + z * z)) * sy;
  m[6] = (k * (y * z - x * w)) * sz;
  m[8] = (k * (x * z - y * w)) * sx;
  m[9] = (k * (y * z + x * w)) * sy;
  m[10] = (1 - k * (x * x + y * y)) * sz;
  m[3] = t ? t[0] : 0.0;
  m[7] = t ? t[1] : 0.0;
  m[11] = t ? t[2] : 0.0;
  m[12] = m[13] = m[14] = 0.0;
  m[15] = 1.0;
}

/* Rotation by angle about a unit axis (Rodrigues), no translation. */
static inline void m4_axis_angle(const double *u, double angle, double *m) {
  double c = cos(angle), s = sin(angle), t = 1 - c;
  double x = u[0], y = u[1], z = u[2];
  m[0] = t * x * x + c;
  m[1] = t * x * y - s * z;
  m[2] = t * x * z + s * y;
  m[4] = t * x * y + s * z;
  m[5] = t * y * y + c;
  m[6] = t * y * z - s * x;
  m[8] = t * x * z - s * y;
  m[9] = t * y * z + s * x;
  m[10] = t * z * z + c;
  m[3] = m[7] = m[11] = 0.0;
  m[12] = m[13] = m[14] = 0.0;
  m[15] = 1.0;
}

#endif
