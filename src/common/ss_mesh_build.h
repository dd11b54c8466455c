/* Internal: a growable triangle mesh, for the code that generates meshes (the
 * lab's scenes, src/lab/scene_geom.c; the avatars' URDF primitives,
 * src/avatar/primitive.c): one builder, so that each generator only says
 * where its vertices and faces go. Positions (nv x 3) and faces (nf x 3). On
 * an allocation failure `failed` is set and further pushes are ignored; the
 * caller checks it once at the end. Start from an all-zero ss_mb. */
#ifndef SKIN_SIM_SS_MESH_BUILD_H
#define SKIN_SIM_SS_MESH_BUILD_H

#include <stdlib.h>

typedef struct ss_mb {
  double *pos;
  int *tri;
  int nv, nf, cap_v, cap_f;
  int failed;
} ss_mb;

static inline void ss_mb_free(ss_mb *mb) {
  free(mb->pos);
  free(mb->tri);
  mb->pos = NULL;
  mb->tri = NULL;
  mb->nv = mb->nf = mb->cap_v = mb->cap_f = 0;
}

/* Adds a vertex; returns its index (0 once failed). */
static inline int ss_mb_vert(ss_mb *mb, double x, double y, double z) {
  if (mb->failed) return 0;
  if (mb->nv == mb->cap_v) {
    int cap = mb->cap_v ? 2 * mb->cap_v : 1024;
    double *p = realloc(mb->pos, sizeof(double) * 3 * (size_t)cap);
    if (!p) {
      mb->failed = 1;
      return 0;
    }
    mb->pos = p;
    mb->cap_v = cap;
  }
  double *p = mb->pos + 3 * mb->nv;
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return mb->nv++;
}

/* Adds the face (a, b, c). */
static inline void ss_mb_tri(ss_mb *mb, int a, int b, int c) {
  if (mb->failed) return;
  if (mb->nf == mb->cap_f) {
    int cap = mb->cap_f ? 2 * mb->cap_f : 2048;
    int *t = realloc(mb->tri, sizeof(int) * 3 * (size_t)cap);
    if (!t) {
      mb->failed = 1;
      return;
    }
    mb->tri = t;
    mb->cap_f = cap;
  }
  int *t = mb->tri + 3 * mb->nf++;
  t[0] = a;
  t[1] = b;
  t[2] = c;
}

#endif
