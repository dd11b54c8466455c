/* Bounding volume hierarchy over the body's faces, for the exact Euclidean
 * closest point of the "projection springs" baseline.
 *
 * Built once per topology from the rest pose: a binary tree of axis-aligned
 * boxes, split at the median face centroid along the longest axis of the
 * centroids' box, leaves of at most LEAF_SIZE faces. Nodes are stored in
 * depth-first order (a parent before its children), so ss_bvh_refit updates
 * every box for a new pose in one reverse sweep without recursion or
 * allocation. The tree shape stays that of the rest pose; boxes always bound
 * the current faces, so queries stay exact however the body deforms (only
 * their speed depends on how well the shape still fits).
 *
 * Query: depth-first, nearer child first, pruning a box whose squared
 * distance exceeds the best found. Boxes at exactly the best distance are
 * still visited so that ties go to the lowest face index, as promised. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "closest.h"
#include "ss_free.h"

#define LEAF_SIZE 4
#define MAX_DEPTH 96

struct ss_bvh {
  const ss_topo *topo;
  int nnode;        /* 0 until the first refit builds the tree */
  double *box;      /* (nnode x 6) lo xyz, hi xyz */
  int *left;        /* (nnode) first child, -1 for a leaf */
  int *right;       /* (nnode) second child, -1 for a leaf */
  int *first;       /* (nnode) leaf: first slot in face_order */
  int *count;       /* (nnode) leaf: number of faces */
  int *face_order;  /* (nface) faces, each leaf's faces contiguous */
  int borrowed;     /* left, right, first, count, face_order are another BVH's */
  double *centroid; /* (nface x 3) scratch of the build */
  int *stack;       /* (3 x max nodes) scratch of the build */
};

/* Is face a before face b along axis (ties by index, for determinism)? */
static int less_face(const double *centroid, int axis, int a, int b) {
  double ca = centroid[3 * a + axis], cb = centroid[3 * b + axis];
  return ca < cb || (ca == cb && a < b);
}

/* Quickselect: puts the element of rank nth (by centroid[axis]) of idx[0..n)
 * at nth, smaller ones before it and larger ones after. */
static void nth_element(int *idx, int n, int nth, const double *centroid, int axis) {
  int lo = 0, hi = n - 1;
  while (lo < hi) {
    int a = idx[lo], b = idx[lo + (hi - lo) / 2], c = idx[hi];
    int pivot; /* median of three */
    if (less_face(centroid, axis, a, b))
      pivot = less_face(centroid, axis, b, c) ? b : (less_face(centroid, axis, a, c) ? c : a);
    else
      pivot = less_face(centroid, axis, a, c) ? a : (less_face(centroid, axis, b, c) ? c : b);
    int i = lo, j = hi;
    while (i <= j) {
      while (less_face(centroid, axis, idx[i], pivot)) i++;
      while (less_face(centroid, axis, pivot, idx[j])) j--;
      if (i <= j) {
        int t = idx[i];
        idx[i] = idx[j];
        idx[j] = t;
        i++;
        j--;
      }
    }
    if (nth <= j) hi = j;
    else if (nth >= i) lo = i;
    else return;
  }
}

/* The box of face f: the smaller and larger coordinate of its corners (a
 * NaN corner coordinate is passed over, as fmin and fmax do; written as
 * comparisons, which the compiler keeps inline). */
static void face_box(const ss_topo *topo, const double *pos, int f, double box[6]) {
  for (int c = 0; c < 3; c++) box[c] = INFINITY, box[3 + c] = -INFINITY;
  for (int k = 0; k < 3; k++) {
    const double *p = pos + 3 * topo->face_vert[3 * f + k];
    for (int c = 0; c < 3; c++) {
      if (p[c] < box[c]) box[c] = p[c];
      if (p[c] > box[3 + c]) box[3 + c] = p[c];
    }
  }
}

/* A median split of more than LEAF_SIZE faces leaves at least one face per
 * leaf, so a tree has at most nface leaves and 2 nface - 1 nodes. */
static int max_nodes(int nface) { return 2 * nface + 1; }

int ss_bvh_create(ss_bvh **out, const ss_topo *topo) {
  if (!out || !topo) return SS_E_ARG;
  *out = NULL;
  const int nface = topo->nface, maxnode = max_nodes(nface);
  ss_bvh *b = calloc(1, sizeof *b);
  if (!b) return SS_E_NOMEM;
  b->topo = topo;
  b->box = malloc(sizeof(double) * 6 * (size_t)maxnode);
  b->left = malloc(sizeof(int) * (size_t)maxnode);
  b->right = malloc(sizeof(int) * (size_t)maxnode);
  b->first = malloc(sizeof(int) * (size_t)maxnode);
  b->count = malloc(sizeof(int) * (size_t)maxnode);
  b->face_order = malloc(sizeof(int) * (size_t)nface);
  b->centroid = malloc(sizeof(double) * 3 * (size_t)nface);
  b->stack = malloc(sizeof(int) * 3 * (size_t)maxnode);
  if (!b->box || !b->left || !b->right || !b->first || !b->count || !b->face_order ||
      !b->centroid || !b->stack) {
    ss_bvh_destroy(b);
    return SS_E_NOMEM;
  }
  *out = b;
  return SS_OK;
}

int ss_bvh_create_on(ss_bvh **out, const ss_bvh *shape) {
  if (!out || !shape || shape->nnode == 0) return SS_E_ARG;
  *out = NULL;
  ss_bvh *b = calloc(1, sizeof *b);
  if (!b) return SS_E_NOMEM;
  *b = *shape;
  b->borrowed = 1;
  b->centroid = NULL; /* the build's scratch: never built again */
  b->stack = NULL;
  b->box = malloc(sizeof(double) * 6 * (size_t)shape->nnode);
  if (!b->box) {
    free(b);
    return SS_E_NOMEM;
  }
  memcpy(b->box, shape->box, sizeof(double) * 6 * (size_t)shape->nnode);
  *out = b;
  return SS_OK;
}

void ss_bvh_destroy(ss_bvh *b) {
  if (!b) return;
  free(b->box);
  if (!b->borrowed) {
    SS_FREE_ALL(b->left, b->right, b->first, b->count, b->face_order);
  }
  free(b->centroid);
  free(b->stack);
  free(b);
}

/* Builds the tree shape on pose pos (the first refit's): depth-first with an
 * explicit stack, so nodes come out parent before children. */
static void build(ss_bvh *b, const double *pos) {
  const ss_topo *topo = b->topo;
  for (int f = 0; f < topo->nface; f++) {
    b->face_order[f] = f;
    for (int c = 0; c < 3; c++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++) s += pos[3 * topo->face_vert[3 * f + k] + c];
      b->centroid[3 * f + c] = isfinite(s) ? s / 3.0 : 0.0;
    }
  }
  int top = 0;
  b->nnode = 1;
  b->stack[0] = 0, b->stack[1] = 0, b->stack[2] = topo->nface;
  top = 1;
  while (top > 0) {
    top--;
    const int node = b->stack[3 * top], first = b->stack[3 * top + 1],
              count = b->stack[3 * top + 2];
    b->first[node] = first;
    b->count[node] = count;
    if (count <= LEAF_SIZE) {
      b->left[node] = b->right[node] = -1;
      continue;
    }
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = first; i < first + count; i++)
      for (int c = 0; c < 3; c++) {
        lo[c] = fmin(lo[c], b->centroid[3 * b->face_order[i] + c]);
        hi[c] = fmax(hi[c], b->centroid[3 * b->face_order[i] + c]);
      }
    int axis = 0;
    for (int c = 1; c < 3; c++)
      if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
    const int half = count / 2;
    nth_element(b->face_order + first, count, half, b->centroid, axis);
    const int l = b->nnode++, r = b->nnode++;
    b->left[node] = l;
    b->right[node] = r;
    /* push right first so the left subtree is numbered (and refit) first */
    b->stack[3 * top] = r, b->stack[3 * top + 1] = first + half,
    b->stack[3 * top + 2] = count - half;
    top++;
    b->stack[3 * top] = l, b->stack[3 * top + 1] = first, b->stack[3 * top + 2] = half;
    top++;
  }
}

void ss_bvh_refit(ss_bvh *b, const double *pos) {
  if (b->nnode == 0) build(b, pos);
  /* children have larger indices than their parent: one reverse sweep */
  for (int node = b->nnode - 1; node >= 0; node--) {
    double *box = b->box + 6 * node;
    if (b->left[node] < 0) {
      for (int c = 0; c < 3; c++) box[c] = INFINITY, box[3 + c] = -INFINITY;
      for (int i = b->first[node]; i < b->first[node] + b->count[node]; i++) {
        double fb[6];
        face_box(b->topo, pos, b->face_order[i], fb);
        for (int c = 0; c < 3; c++) {
          if (fb[c] < box[c]) box[c] = fb[c];
          if (fb[3 + c] > box[3 + c]) box[3 + c] = fb[3 + c];
        }
      }
    } else {
      const double *l = b->box + 6 * b->left[node], *r = b->box + 6 * b->right[node];
      for (int c = 0; c < 3; c++) {
        box[c] = l[c] < r[c] ? l[c] : r[c];
        box[3 + c] = l[3 + c] > r[3 + c] ? l[3 + c] : r[3 + c];
      }
    }
  }
}

/* The search from a bound best (squared) and a face that holds it. Each
 * node's box distance is computed once, by its parent, and kept on the
 * stack with it. */
static double closest_from(const ss_bvh *b, const double *pos, const double p[3], double best,
                           int *face, double uv[2]) {
  const ss_topo *topo = b->topo;
  if (b->nnode == 0) return best;
  if (!(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))) return best; /* no closest point */
  int stack[MAX_DEPTH * 2 + 2];
  double sdist[MAX_DEPTH * 2 + 2];
  int top = 0;
  stack[top] = 0, sdist[top++] = ss_bvh_box_dist2(b->box, p);
  while (top > 0) {
    --top;
    const int node = stack[top];
    if (sdist[top] > best) continue;
    if (b->left[node] < 0) {
      for (int i = b->first[node]; i < b->first[node] + b->count[node]; i++) {
        const int f = b->face_order[i];
        const int *fv = topo->face_vert + 3 * f;
        double fuv[2];
        double d2 = ss_closest_point_triangle(p, pos + 3 * fv[0], pos + 3 * fv[1],
                                              pos + 3 * fv[2], fuv);
        if (d2 < best || (d2 == best && f < *face)) {
          best = d2;
          *face = f;
          uv[0] = fuv[0];
          uv[1] = fuv[1];
        }
      }
      continue;
    }
    const int l = b->left[node], r = b->right[node];
    ss_bvh_push_children(stack, sdist, &top, l, ss_bvh_box_dist2(b->box + 6 * l, p), r,
                         ss_bvh_box_dist2(b->box + 6 * r, p), best);
  }
  return best;
}

double ss_bvh_closest(const ss_bvh *b, const double *pos, const double p[3], int *face,
                      double uv[2]) {
  *face = 0;
  uv[0] = uv[1] = 1.0 / 3.0;
  return closest_from(b, pos, p, INFINITY, face, uv);
}

double ss_bvh_closest_within(const ss_bvh *b, const double *pos, const double p[3], double bound2,
                             int *face, double uv[2]) {
  *face = -1;
  uv[0] = uv[1] = 1.0 / 3.0;
  return closest_from(b, pos, p, bound2, face, uv);
}

ss_bvh_shape ss_bvh_get_shape(const ss_bvh *b) {
  ss_bvh_shape s = {b->nnode, b->left, b->right, b->first, b->count, b->face_order};
  return s;
}

const double *ss_bvh_boxes(const ss_bvh *b) { return b->box; }

double *ss_bvh_boxes_write(ss_bvh *b) { return b->box; }
