/* Contact: the skin kept outside the body where the body is clean
 * (doc/model.md, "Contact"; setting collide, off by default).
 *
 * A projection, not an energy. After the solve of the last substep of each
 * step every free skin vertex behind the body's surface is moved out along
 * the surface's normal (a thickness in front), and its velocity loses its
 * part into the body (inelastic, frictionless): the position-based contact
 * of Houdini Vellum and of Bridson et al.'s post-solve collision pass. Why not a
 * penalty or a barrier in the implicit energy: the real-time solver is two
 * L-BFGS iterations a substep on a constant, isotropic matrix that holds no
 * contact stiffness. A penalty stiff enough to hold the skin within 0.05
 * edge (a hundred times the orient term's depth springs) makes its full
 * steps far too long where the contacts are, and the line search's halvings
 * (each a whole energy evaluation) cost more than the whole projection; an
 * IPC-style log barrier needs a line search bounded by continuous collision
 * detection and converged Newton solves to stay feasible, which the budget
 * does not buy. After every substep instead of the last only, the pass cost
 * four times as much and the next solve pushed the skin straight back in
 * (more iterations, no shallower). What is measured is the skin a step
 * leaves, and that is what the pass corrects.
 *
 * Where, cheap first (collide_surface.c). 1. Each vertex descends over the
 * body's faces to a local nearest point of the surface (from the face its
 * last descent ended on, else its anchor face: across the edge or around
 * the corner the nearest point lies on, while that is nearer; usually one
 * face or two, by the faces' frame records, walk.h). A vertex within
 * SS_COLLIDE_NEAR of it is no deeper and is left (over 40% of the 19k
 * quadruped's skin in motion); one in front of it and within
 * SS_COLLIDE_FRONT is left too: it can be no deeper than that behind
 * another part. One further in front is left if no face within that
 * distance has it behind the face's plane (collide_behind.c: a plane test a
 * face): it is then in front of the surface at its nearest point, whichever
 * face that is (39 in 40 of them on the 19k quadruped; the skin's gap off
 * the body). 2. The rest (behind the local surface, or in front of it with
 * another part or the far wall of a crease near) search the body's tree for
 * the nearest point within the distance the descent found, starting at the
 * leaf of the face it found and going up (the boxes a search from the root
 * tests, but not the root's way down). A descent, not a look at the anchor
 * face and its neighbours: that leaves half the skin on their rim (the
 * anchors lag), and so searched. Behind the surface (by the
 * pseudo-normal at the nearest point: the normals of the faces nearest
 * there summed, one face's inside it, an edge's two, a corner's ring;
 * Baerentzen and Aanaes 2005), the vertex moves out along that normal by
 * its depth, and again from where it lands (up to SS_COLLIDE_PASSES times,
 * then onto the nearest point): in a crushed crease the faces' planes
 * cross, and one move along one normal left the skin half an edge inside
 * the next face.
 *
 * Not against the body where it passes through itself: the nearest face of
 * a vertex moved further than SS_COLLIDE_SHALLOW, and its anchor face, must
 * be on the body's clean surface, the winding number of the whole body at
 * their centroids 1/2 (inside.h), as the inside measure judges; a face
 * lying inside another part of the body (a leg through the belly) or turned
 * inside out by the pose is not collided against, so the skin is not
 * pushed into the body's own artefacts by more than SS_COLLIDE_SHALLOW.
 * A clean face's result is kept some steps, a buried one's only in the
 * step it was found (a face the pose has just freed must not keep the skin
 * in), and the winding-number moments are refitted with the tree's boxes
 * in one sweep.
 *
 * No move squeezes or stretches a skin face (collide_move.c): a move
 * that would is made with its neighbours', with its ring, or in part. The
 * vertices a move carried with its ring are looked at again from where
 * they are: one carried across a narrow gap (between two toes) into the
 * other part is behind that part's surface, and moved out on its own.
 *
 * Deterministic: the refit per subtree of the tree (inside.c), the
 * descents and searches per vertex alone and the clean-surface tests per
 * face alone (on the threads; the face a vertex's descent ended on is its
 * own, where its next starts), their results applied and the moves made
 * in vertex order on one thread. */
#include "collide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "closest.h"
#include "collide_behind.h"
#include "collide_pass.h"
#include "collide_surface.h"
#include "inside.h"
#include "sim_internal.h"
#include "ss_free.h"

/* struct ss_collider: collide_pass.h */

/* A move of at most this many edge lengths does not ask whether the face is
 * on the clean surface: the test is a large part of the pass's cost, and
 * such a move out of a buried face (inside another part, or turned over)
 * leaves the skin within a seventh of an edge of where it was, inside that
 * part anyway. At 0.05 edge it made three times the tests on the
 * quadruped, and the skin no shallower. */
#define SS_COLLIDE_SHALLOW 0.15
/* A vertex this close to the surface (edge lengths, less the thickness) is
 * not looked at further: it is no deeper than its distance to a point of
 * the surface, and no deeper than the depth that counts (0.05 edge). */
#define SS_COLLIDE_NEAR 0.045
/* A vertex in front of its local nearest point and this close to it (edge
 * lengths, less the thickness) is not searched for a nearer face it is
 * behind: another part of the body, or the far wall of a crease, that it
 * has cut into by at most that. The knob between cost and depth: at 0.2,
 * the mannequin's deepest clean vertex was such a one, 0.19 edge in (the
 * target is 0.1), and 0.1 costs 1.6 times the quadruped's searches (about
 * a millisecond a frame of its 19k faces). */
#define SS_COLLIDE_FRONT 0.1
/* Steps a face's clean-surface test is kept: a clean face 16, a buried one
 * only the step it was made in (the quadruped's legs leave the belly within
 * a few frames, and skin kept in by a stale test stayed a quarter of an
 * edge deep; kept 2 steps it still left the mannequin's skin a quarter of
 * an edge deep for a frame). A vertex anchored on a buried face is looked
 * at like any other: the test of its anchor face is made only if it is to
 * move. */
#define SS_COLLIDE_RECHECK 16
#define SS_COLLIDE_RECHECK_BURIED 1
/* The clean-surface test's near field (node radii; inside.h's measure uses
 * SS_WIND_BETA, 3): it only tells 1/2 from 0, 1 or 3/2, by 1/4, and at 1.5
 * radii the first-order far field stays within 0.13 of the exact sum on the
 * faces the four bodies of bench/inside.sh test (at 2 radii 0.07, at 1.2
 * 0.22, at 1 0.29) while it visits two thirds of the nodes of 2. */
#define SS_COLLIDE_WIND_BETA 1.5
#define SS_COLLIDE_PASSES 4  /* moves along normals before one onto the nearest point */
#define SS_COLLIDE_STACK (2 * 96 + 2) /* a search's stack: bvh.c's MAX_DEPTH 96, two children a level */

int ss_collider_create(ss_collider **out, const ss_topo *btopo, const double *body_rest,
                       int nvert, int nface, const int *faces) {
  if (!out || !btopo || !body_rest || nvert < 0 || nface < 0 || (nface > 0 && !faces)) return SS_E_ARG;
  *out = NULL;
  ss_collider *c = calloc(1, sizeof *c);
  if (!c) return SS_E_NOMEM;
  c->topo = btopo;
  c->nbface = btopo->nface;
  int status = ss_bvh_create(&c->bvh, btopo);
  if (!status) {
    ss_bvh_refit(c->bvh, body_rest); /* builds the tree: nothing to allocate later */
    status = ss_wind_create(&c->wind, c->bvh, btopo);
  }
  if (!status) {
    const ss_bvh_shape sh = ss_bvh_get_shape(c->bvh);
    c->shape = sh;
    c->parent = malloc(sizeof(int) * ((size_t)sh.nnode + 1));
    c->leaf_of = malloc(sizeof(int) * ((size_t)btopo->nface + 1));
    if (c->parent && c->leaf_of) {
      for (int q = 0; q < sh.nnode; q++) c->parent[q] = -1;
      for (int q = 0; q < sh.nnode; q++) {
        if (sh.left[q] >= 0) c->parent[sh.left[q]] = c->parent[sh.right[q]] = q;
        else
          for (int i = sh.first[q]; i < sh.first[q] + sh.count[q]; i++) c->leaf_of[sh.face_order[i]] = q;
      }
    } else {
      status = SS_E_NOMEM;
    }
  }
  c->face_step = malloc(((size_t)btopo->nface + 1) * sizeof *c->face_step);
  if (c->face_step)
    for (int f = 0; f < btopo->nface; f++) c->face_step[f] = -1;
  c->face_buried = calloc((size_t)btopo->nface + 1, 1);
  c->test_face = malloc(sizeof(int) * ((size_t)btopo->nface + 1));
  c->cand_face = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->move_k = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->cand_x = malloc(sizeof(double) * 3 * ((size_t)nvert + 1));
  c->cand_n = malloc(sizeof(double) * 3 * ((size_t)nvert + 1));
  c->hint = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->look_face = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->look_d2 = malloc(sizeof(double) * ((size_t)nvert + 1));
  c->nvert = nvert;
  c->dof_of = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->carried = calloc((size_t)nvert + 1, 1);
  c->relook_k = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->tie_face = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->joint_of = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->joint_old = malloc(sizeof(double) * 3 * ((size_t)nvert + 1));
  if (c->joint_of)
    for (int v = 0; v <= nvert; v++) c->joint_of[v] = -1;
  if (c->hint)
    for (int v = 0; v <= nvert; v++) c->hint[v] = -1;
  c->vf_start = calloc((size_t)nvert + 2, sizeof(int));
  c->vf_face = malloc(sizeof(int) * (3 * (size_t)nface + 1));
  if (c->vf_start && c->vf_face) {
    for (int i = 0; i < 3 * nface; i++) c->vf_start[faces[i] + 2]++;
    for (int v = 0; v < nvert; v++) c->vf_start[v + 2] += c->vf_start[v + 1];
    for (int i = 0; i < 3 * nface; i++) c->vf_face[c->vf_start[faces[i] + 1]++] = i / 3;
  }
  if (!status && !(c->face_step && c->face_buried && c->test_face && c->cand_face && c->move_k &&
                   c->cand_x && c->cand_n && c->hint && c->look_face && c->look_d2 && c->dof_of && c->carried && c->relook_k && c->tie_face && c->joint_of && c->joint_old &&
                   c->vf_start && c->vf_face))
    status = SS_E_NOMEM;
  if (status) {
    ss_collider_destroy(c);
    return status;
  }
  *out = c;
  return SS_OK;
}

void ss_collider_destroy(ss_collider *c) {
  if (!c) return;
  ss_wind_destroy(c->wind);
  ss_bvh_destroy(c->bvh);
  SS_FREE_ALL(c->face_step, c->face_buried, c->test_face, c->cand_face, c->move_k, c->cand_x, c->cand_n,
              c->hint, c->vf_start, c->vf_face, c->look_face, c->look_d2, c->dof_of, c->carried, c->relook_k, c->tie_face, c->joint_of, c->joint_old, c->parent, c->leaf_of,
              c);
}

/* Leaf node's faces against p: the nearest within best (ties to the lower
 * face) into face, uv. */
static double leaf_nearest(const ss_collider *c, const ss_collide_in *in, int node, const double p[3],
                           double best, int *face, double uv[2]) {
  const ss_bvh_shape *s = &c->shape;
  for (int i = s->first[node]; i < s->first[node] + s->count[node]; i++) {
    const int f = s->face_order[i];
    double fuv[2];
    const double d2 = ss_collide_tri_dist2(in, f, p, fuv);
    if (d2 < best || (d2 == best && f < *face)) best = d2, *face = f, uv[0] = fuv[0], uv[1] = fuv[1];
  }
  return best;
}

/* The subtree of node (its box within best of p) searched for the nearest
 * body point within best: nearer child first, a box farther than the best
 * so far passed over. */
static double subtree_nearest(const ss_collider *c, const ss_collide_in *in, int node, double dnode,
                              const double p[3], double best, int *face, double uv[2]) {
  const ss_bvh_shape *s = &c->shape;
  const double *box = ss_bvh_boxes(c->bvh);
  int stack[SS_COLLIDE_STACK];
  double sdist[SS_COLLIDE_STACK];
  int top = 0;
  stack[top] = node, sdist[top++] = dnode;
  while (top > 0) {
    --top;
    const int q = stack[top];
    if (sdist[top] > best) continue;
    if (s->left[q] < 0) {
      best = leaf_nearest(c, in, q, p, best, face, uv);
      continue;
    }
    const int l = s->left[q], r = s->right[q];
    if (top + 2 > (int)(sizeof stack / sizeof stack[0])) continue; /* never on trees bvh.c builds */
    ss_bvh_push_children(stack, sdist, &top, l, ss_bvh_box_dist2(box + 6 * (size_t)l, p), r,
                         ss_bvh_box_dist2(box + 6 * (size_t)r, p), best);
  }
  return best;
}

/* The nearest body point to p within best (squared; face -1 and best if
 * there is none; ties to the lower face, as ss_bvh_closest_within), the
 * search starting at the leaf of face f0, a face near p: up from it, each
 * ancestor's other child searched where its box is within the best so far.
 * The boxes it passes by are those a search from the root would test, and
 * the root's way down to f0 is not taken. */
static double tree_nearest(const ss_collider *c, const ss_collide_in *in, int f0, const double p[3],
                           double best, int *face, double uv[2]) {
  const ss_bvh_shape *s = &c->shape;
  const double *box = ss_bvh_boxes(c->bvh);
  *face = -1;
  uv[0] = uv[1] = 1.0 / 3.0;
  if (s->nnode <= 0) return best;
  int node = c->leaf_of[f0];
  best = leaf_nearest(c, in, node, p, best, face, uv);
  while (node > 0) {
    const int up = c->parent[node];
    const int other = s->left[up] == node ? s->right[up] : s->left[up];
    const double d = ss_bvh_box_dist2(box + 6 * (size_t)other, p);
    if (d <= best) best = subtree_nearest(c, in, other, d, p, best, face, uv);
    node = up;
  }
  return best;
}

/* Face g's clean-surface test, kept SS_COLLIDE_RECHECK steps (the body's
 * self-intersections move far slower than a step: a leg through the belly
 * takes a tenth of a second), each face's age its own so that the tests of
 * a step are few. */
static int fresh(const ss_collider *c, long long step, int g) {
  const long long keep = c->face_buried[g] ? SS_COLLIDE_RECHECK_BURIED : SS_COLLIDE_RECHECK;
  return c->face_step[g] >= 0 && step - c->face_step[g] < keep && step >= c->face_step[g];
}

/* Face g to be tested in this step (its test not fresh): listed once, its
 * step set so that it is fresh from now on. */
static void to_test(ss_collider *c, long long step, int g, int *n) {
  if (fresh(c, step, g)) return;
  c->face_step[g] = step;
  c->test_face[(*n)++] = g;
}

/* Face g's clean-surface test (inside.h), kept in face_buried. */
static void test_face(ss_collider *c, const ss_collide_in *in, int g) {
  c->face_buried[g] = (unsigned char)ss_wind_face_buried_beta(c->wind, in->body, g, SS_COLLIDE_WIND_BETA);
}

/* The tests of the n faces listed (on the threads where nthread > 1: each
 * reads the body and the tree alone and writes its own face's result). */
static void test_listed(ss_collider *c, const ss_collide_in *in, int n, int nthread) {
#ifdef _OPENMP
  if (nthread > 1 && n > 1) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthread)
    for (int i = 0; i < n; i++) test_face(c, in, c->test_face[i]);
    return;
  }
#endif
  (void)nthread;
  for (int i = 0; i < n; i++) test_face(c, in, c->test_face[i]);
}

/* Vertex v at x, first look: the face of a local nearest point of the
 * surface (its squared distance into *d2) if the vertex may be deeper than
 * SS_COLLIDE_NEAR behind the surface, else -1. */
static int look_local(ss_collider *col, const ss_collide_in *in, int v, const double x[3], double *d2) {
  const int fa = in->anchor_face[v];
  if (fa < 0) return -1;
  /* a local nearest point of the surface, by descent from the face the
   * last one ended on (else, or if that face has no area in this pose, from
   * the anchor face): an upper bound of the distance to the surface */
  double uv[2];
  int settled = 0, lf = -1;
  const int hf = col->hint[v];
  if (hf >= 0) lf = ss_collide_descend(in, hf, x, uv, d2, &settled);
  if (lf < 0 && hf != fa) lf = ss_collide_descend(in, fa, x, uv, d2, &settled);
  if (lf < 0) return -1;
  col->hint[v] = lf;
  const double near = SS_COLLIDE_NEAR * in->reach - in->thickness;
  /* no deeper than the distance to a point of the surface */
  if (near > 0.0 && *d2 <= near * near) return -1;
  /* in front of the surface there, and too near it to be deeper than
   * SS_COLLIDE_FRONT behind another part of the body */
  const double front = SS_COLLIDE_FRONT * in->reach - in->thickness;
  double n[3], cp[3], sd;
  if (!settled) return lf;
  const int infront = !ss_collide_surface_at(in, lf, uv, x, *d2, n, cp, &sd) ? -1 : !(sd < in->thickness - 1e-9 * in->reach);
  if (infront != 0 && front > 0.0 && *d2 <= front * front) return -1;
  /* further in front: searched only if some face within its distance has
   * it behind the face's plane (or less than the thickness in front), as
   * few in the skin's mere gap off the body are */
  if (infront == 1 && !ss_collide_behind(&col->shape, ss_bvh_boxes(col->bvh), col->parent, col->leaf_of[lf], in, x,
                                          *d2 * (1.0 + 1e-9) + 1e-300, in->thickness + 1e-9 * in->reach))
    return -1;
  return lf;
}

/* Vertex v at x, looked at further (lf, d2: look_local's): the nearest
 * body face if x is deeper behind the surface there than SS_COLLIDE_NEAR
 * (and where it goes into out, along nout), -2 - that face if the move is
 * shallow, else -1. */
static int look_global(const ss_collider *col, const ss_collide_in *in, int lf, double d2,
                       const double x[3], double out[3], double nout[3]) {
  const double tiny = 1e-9 * in->reach; /* a point put on a plane is behind it half the time */
  const double near = SS_COLLIDE_NEAR * in->reach - in->thickness;
  double p[3] = {x[0], x[1], x[2]}, uv[2], n[3], cp[3], sd;
  int first = -1;
  double bound2 = d2;
  int from = lf;
  for (int it = 0; it < SS_COLLIDE_PASSES; it++) {
    /* the nearest body point, within the bound known */
    int nf;
    const double e2 = tree_nearest(col, in, from, p, bound2 * (1.0 + 1e-9) + 1e-300, &nf, uv);
    if (nf < 0 || !ss_collide_surface_at(in, nf, uv, p, e2, n, cp, &sd)) break;
    if (!(sd < in->thickness - tiny)) break;
    from = nf;
    if (first < 0) {
      if (near > 0.0 && e2 <= near * near) return -1;
      first = nf;
    }
    memcpy(nout, n, 3 * sizeof(double));
    if (it == SS_COLLIDE_PASSES - 1) {
      /* still behind after moves along normals (a crushed crease, whose
       * faces' planes cross): onto the nearest point */
      for (int q = 0; q < 3; q++) p[q] = cp[q] + in->thickness * n[q];
      break;
    }
    /* along the pseudo-normal by the depth, not onto the nearest point:
     * vertices deep under a corner or an edge would all land on that one
     * point and their faces collapse */
    for (int q = 0; q < 3; q++) p[q] += (in->thickness - sd) * n[q];
    const double pc[3] = {p[0] - cp[0], p[1] - cp[1], p[2] - cp[2]}; /* cp: on the surface */
    bound2 = dot3(pc, pc);
    /* on the surface itself: behind no face by more than nothing */
    if (!(bound2 > tiny * tiny)) break;
  }
  if (first < 0) return -1;
  memcpy(out, p, 3 * sizeof(double));
  /* the clean-surface test only for a vertex a move would carry far */
  const double dx[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]};
  if (dot3(dx, dx) <= SS_COLLIDE_SHALLOW * SS_COLLIDE_SHALLOW * in->reach * in->reach) return -2 - first;
  return first;
}

/* Vertex k of the pass (dof_vert[k] at x), first look: look_face, look_d2. */
static inline void look_local_k(ss_collider *c, const ss_collide_in *in, const int *dof_vert, const double *x,
                                int k) {
  const int v = dof_vert[k];
  c->look_face[k] = look_local(c, in, v, x + 3 * v, c->look_d2 + k);
}

/* Vertex k, looked at further: cand_face (and cand_x, cand_n); 1 if a
 * candidate. */
static inline int look_global_k(ss_collider *c, const ss_collide_in *in, const int *dof_vert, const double *x,
                                int k) {
  const int v = dof_vert[k], lf = c->look_face[k];
  c->cand_face[k] = lf < 0 ? -1 : look_global(c, in, lf, c->look_d2[k], x + 3 * v, c->cand_x + 3 * k,
                                              c->cand_n + 3 * k);
  return c->cand_face[k] != -1;
}

/* The candidates (cand_face of the n vertices of list, or of 0 .. n - 1 if
 * list is NULL) whose move is out of the clean surface, in vertex order
 * into move_k: neither the nearest face nor the anchor's buried in the
 * body (as the inside measure judges). The faces whose test is not fresh
 * are tested once each: the nearest faces first, then the faces tied with
 * buried nearest ones, then the anchor faces of the vertices whose nearest
 * face is clean: the faces a sweep in vertex order would test (it tests a
 * face only past the test before it), and each test reads only the body,
 * so on the threads too the results are those of that sweep. Returns how
 * many. */
static int pick_moves(ss_collider *c, const ss_collide_in *in, const int *dof_vert, const double *x, int nthread,
                      long long step, const int *list, int n) {
  int ntest = 0;
  for (int i = 0; i < n; i++) {
    const int k = list ? list[i] : i;
    if (c->cand_face[k] >= 0) to_test(c, step, c->cand_face[k], &ntest);
  }
  test_listed(c, in, ntest, nthread);
  /* a buried nearest face tied there with another (the vertex nearest to
   * the line where the body passes through itself): the other's test
   * decides, as for the inside measure, which may take either */
  ntest = 0;
  for (int i = 0; i < n; i++) {
    const int k = list ? list[i] : i, g = c->cand_face[k];
    c->tie_face[k] = g >= 0 && c->face_buried[g] ? ss_collide_tied_face(in, g, x + 3 * dof_vert[k]) : -1;
    if (c->tie_face[k] >= 0) to_test(c, step, c->tie_face[k], &ntest);
  }
  test_listed(c, in, ntest, nthread);
  for (int i = 0; i < n; i++) {
    const int k = list ? list[i] : i, h = c->tie_face[k];
    if (h >= 0 && !c->face_buried[h]) c->cand_face[k] = h;
  }
  ntest = 0;
  for (int i = 0; i < n; i++) {
    const int k = list ? list[i] : i;
    const int g = c->cand_face[k], fa = in->anchor_face[dof_vert[k]];
    if (g >= 0 && !c->face_buried[g] && fa != g) to_test(c, step, fa, &ntest);
  }
  test_listed(c, in, ntest, nthread);
  int nmove = 0;
  for (int i = 0; i < n; i++) {
    const int k = list ? list[i] : i;
    const int g = c->cand_face[k];
    if (g == -1) continue;
    const int fa = in->anchor_face[dof_vert[k]];
    if (g >= 0 && (c->face_buried[g] || (fa != g && c->face_buried[fa]))) c->cand_face[k] = -1;
    else c->move_k[nmove++] = k;
  }
  return nmove;
}

int ss_collider_run(ss_collider *c, const ss_collide_in *in, int ndof, const int *dof_vert,
                    int nthread, long long step, double *x, double *vel) {
  /* the tree's boxes and winding-number moments in this pose, in one sweep (its
   * subtrees on the threads) */
  ss_wind_refit_boxes(c->wind, in->body, ss_bvh_boxes_write(c->bvh), nthread);
  /* 1. each vertex's local nearest point of the surface, by descent; 2. for
   * those it leaves, the nearest point of the body, and where they go (on
   * the threads where there are enough vertices; one thread calls no
   * OpenMP, which allocates). Scheduled dynamically: the searches are a
   * few hundred vertices gathered in the folds, and halves made in advance
   * left one thread idle; each vertex writes only its own slots, so any
   * schedule gives the same bits. */
  int ncand = 0;
#ifdef _OPENMP
  if (nthread > 1 && ndof > 1024) {
#pragma omp parallel for schedule(dynamic, 256) num_threads(nthread)
    for (int k = 0; k < ndof; k++) look_local_k(c, in, dof_vert, x, k);
#pragma omp parallel for schedule(dynamic, 64) num_threads(nthread) reduction(+ : ncand)
    for (int k = 0; k < ndof; k++) ncand += look_global_k(c, in, dof_vert, x, k);
  } else
#endif
  {
    (void)nthread;
    for (int k = 0; k < ndof; k++) look_local_k(c, in, dof_vert, x, k);
    for (int k = 0; k < ndof; k++) ncand += look_global_k(c, in, dof_vert, x, k);
  }
  if (ncand == 0) return 0;
  for (int v = 0; v < c->nvert; v++) c->dof_of[v] = -1;
  for (int k = 0; k < ndof; k++) c->dof_of[dof_vert[k]] = k;
  int moved = ss_collide_sweep_moves(c, in, dof_vert, pick_moves(c, in, dof_vert, x, nthread, step, NULL, ndof), 1, x, vel);
  /* the ring vertices patch moves carried, looked at again (moved on their
   * own: their own patches would carry further) */
  int nre = 0;
  for (int k = 0; k < ndof; k++)
    if (c->carried[k]) c->carried[k] = 0, c->relook_k[nre++] = k;
  int nrecand = 0;
  for (int i = 0; i < nre; i++) {
    look_local_k(c, in, dof_vert, x, c->relook_k[i]);
    nrecand += look_global_k(c, in, dof_vert, x, c->relook_k[i]);
  }
  if (nrecand > 0)
    moved += ss_collide_sweep_moves(c, in, dof_vert, pick_moves(c, in, dof_vert, x, nthread, step, c->relook_k, nre), 0, x, vel);
  return moved;
}

int ss_sim_collide(ss_sim *sim) {
  if (!sim->collider) return 0; /* made with collide on (ss_sim_collider_ensure) */
  const ss_model *m = sim->m;
  const double edge = m->edge_len;
  ss_collide_in in = {m->btopo, ss_mover_frames(sim->mover), sim->body_sub, sim->anchor_face,
                      sim->anchor_pos, m->faces, m->rest_area, sim->set.collide_thickness * edge, edge};
  return ss_collider_run(sim->collider, &in, m->ndof, m->dof_vert, sim->nthread, sim->nstep, sim->x,
                         sim->v);
}
