/* The contact pass's pre-test of a skin vertex further in front of its
 * local nearest point of the body's surface than the pass's front skip
 * (collide.c, "Where, cheap first"; doc/model.md, "Contact").
 *
 * Such a vertex is behind the surface at its nearest body point only if
 * some face within its distance has it behind the face's plane: the
 * pseudo-normal there is a normalised sum of the normals of the faces at
 * that point, each of which has the vertex at least lim in front of its
 * plane otherwise, so the sum does too, whichever face is nearest. The
 * test is a plane's a face, a nearest point (from the face's frame record,
 * as the descents take it) only for the faces it flags, and it stops at
 * the first face within the distance that is flagged: 39
 * in 40 such vertices on the 19k quadruped (the skin's gap off the body)
 * are left without the full nearest-point search, at the same result. */
#include "collide_behind.h"

#include <math.h>

#define SS_BEHIND_STACK (2 * 96 + 2) /* bvh.c's MAX_DEPTH 96, two children a level */

/* 1 if box b meets the box lo hi (a ball's: six comparisons, which pass
 * over fewer boxes than the ball's own distance test but cost far less) */
static inline int box_meets(const double *b, const double lo[3], const double hi[3]) {
  return b[0] <= hi[0] && b[3] >= lo[0] && b[1] <= hi[1] && b[4] >= lo[1] && b[2] <= hi[2] && b[5] >= lo[2];
}

/* 1 if a face of the subtree of node within bound of p (its ball's box lo
 * hi) has p less than lim in front of its plane. */
static int subtree_behind(const ss_bvh_shape *s, const double *box, int node, const ss_collide_in *in,
                          const double p[3], const double lo[3], const double hi[3], double bound, double lim) {
  const double far2 = bound * (1.0 + 1e-6);
  int stack[SS_BEHIND_STACK];
  int top = 0;
  stack[top++] = node;
  while (top > 0) {
    const int q = stack[--top];
    if (s->left[q] >= 0) {
      if (top + 2 > SS_BEHIND_STACK) return 1; /* never on trees bvh.c builds */
      const int l = s->left[q], r = s->right[q];
      if (box_meets(box + 6 * (size_t)l, lo, hi)) stack[top++] = l;
      if (box_meets(box + 6 * (size_t)r, lo, hi)) stack[top++] = r;
      continue;
    }
    for (int i = s->first[q]; i < s->first[q] + s->count[q]; i++) {
      const int f = s->face_order[i];
      const double *o = ss_frames_origin(in->fr, f), *nf = in->fr->normal + 3 * f;
      const double h = nf[0] * (p[0] - o[0]) + nf[1] * (p[1] - o[1]) + nf[2] * (p[2] - o[2]);
      if (h >= lim || h * h > far2) continue; /* in front, or its plane (so the face) too far */
      double uv[2];
      /* the margin far above rounding: a face at the bound's edge counts */
      if (ss_collide_tri_dist2(in, f, p, uv) <= far2) return 1;
    }
  }
  return 0;
}

int ss_collide_behind(const ss_bvh_shape *s, const double *box, const int *parent, int leaf,
                      const ss_collide_in *in, const double p[3], double bound, double lim) {
  if (s->nnode <= 0 || leaf < 0) return 0;
  const double r = sqrt(bound * (1.0 + 1e-6));
  const double lo[3] = {p[0] - r, p[1] - r, p[2] - r}, hi[3] = {p[0] + r, p[1] + r, p[2] + r};
  int node = leaf;
  if (subtree_behind(s, box, node, in, p, lo, hi, bound, lim)) return 1;
  while (node > 0) {
    const int up = parent[node];
    const int other = s->left[up] == node ? s->right[up] : s->left[up];
    if (box_meets(box + 6 * (size_t)other, lo, hi) && subtree_behind(s, box, other, in, p, lo, hi, bound, lim))
      return 1;
    node = up;
  }
  return 0;
}
