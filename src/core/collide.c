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
 * (more iterations, no shallower).
 *
 * Where: each vertex is judged against the faces sharing a corner with the
 * body face its anchor is on (the anchors already know where on the body
 * each skin vertex is: no global search), at the nearest point c among
 * them, by the pseudo-normal there (the sum of the normals of the faces of
 * the ring that are nearest: one face's inside it, an edge's two, a
 * corner's ring; Baerentzen and Aanaes 2005): behind the surface when
 * (x - c) . n < thickness. A vertex in front of its anchor face's plane is
 * skipped (inside a convex body is behind every face's plane; in front of
 * one and behind its neighbour is a concave crease, which the skin bridges),
 * and what lies beyond the ring of a vertex whose anchor has lagged further
 * is not searched (a global search is what the anchors are there to avoid).
 *
 * Not against the body where it passes through itself: the nearest face of
 * a vertex found behind the surface must be on the body's clean surface,
 * the winding number of the whole body at its centroid 1/2 (inside.h); a
 * face lying inside another part of the body (a leg through the belly, an
 * elbow's crushed crease) or turned inside out by the pose is not collided
 * against, so the skin is never pushed into the body's own artefacts. The
 * test runs only for the faces of vertices more than SS_COLLIDE_SHALLOW
 * behind, kept for SS_COLLIDE_RECHECK steps per face, on a tree refitted
 * only in steps that test any.
 *
 * Deterministic: the search per vertex alone (on the threads), the test and
 * the moves in vertex order on one thread. */
#include "collide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "closest.h"
#include "inside.h"
#include "sim_internal.h"

struct ss_collider {
  const ss_topo *topo;
  ss_bvh *bvh;
  ss_wind *wind;
  int nbface;
  long long *face_step;        /* (nbface) step of the cached face_buried (-1: none) */
  unsigned char *face_buried;  /* (nbface) */
  long long step_refit;        /* the step the tree was last refitted in (-1: none) */
  int *cand_face;              /* (nvert) nearest face of a vertex behind the surface, or -1 */
  double *cand_x;              /* (nvert x 3) where it goes */
  double *cand_n;              /* (nvert x 3) the surface normal it goes along */
};

int ss_collider_create(ss_collider **out, const ss_topo *btopo, const double *body_rest,
                       int nvert) {
  if (!out || !btopo || !body_rest || nvert < 0) return SS_E_ARG;
  *out = NULL;
  ss_collider *c = calloc(1, sizeof *c);
  if (!c) return SS_E_NOMEM;
  c->topo = btopo;
  c->nbface = btopo->nface;
  c->step_refit = -1;
  int status = ss_bvh_create(&c->bvh, btopo);
  if (!status) {
    ss_bvh_refit(c->bvh, body_rest); /* builds the tree: nothing to allocate later */
    status = ss_wind_create(&c->wind, c->bvh, btopo);
  }
  c->face_step = malloc(((size_t)btopo->nface + 1) * sizeof *c->face_step);
  if (c->face_step)
    for (int f = 0; f < btopo->nface; f++) c->face_step[f] = -1;
  c->face_buried = calloc((size_t)btopo->nface + 1, 1);
  c->cand_face = malloc(sizeof(int) * ((size_t)nvert + 1));
  c->cand_x = malloc(sizeof(double) * 3 * ((size_t)nvert + 1));
  c->cand_n = malloc(sizeof(double) * 3 * ((size_t)nvert + 1));
  if (!status && !(c->face_step && c->face_buried && c->cand_face && c->cand_x && c->cand_n)) status = SS_E_NOMEM;
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
  free(c->face_step);
  free(c->face_buried);
  free(c->cand_face);
  free(c->cand_x);
  free(c->cand_n);
  free(c);
}

/* 1 if face g has a corner welded to one of the first `upto` corners of fa
 * (then the ring of an earlier corner already visited it). */
static inline int seen_before(const ss_topo *t, const int *fav, int upto, int g) {
  const int *gv = t->face_vert + 3 * g;
  for (int c = 0; c < upto; c++) {
    const int w = t->vert_weld[fav[c]];
    if (t->vert_weld[gv[0]] == w || t->vert_weld[gv[1]] == w || t->vert_weld[gv[2]] == w) return 1;
  }
  return 0;
}

/* A move of at most this many edge lengths does not ask whether the face is
 * on the clean surface: the skin lying on the body sits a rounding error or
 * a chord's sag behind it almost everywhere (half the skin of a tube), and
 * the test is the pass's cost; a face buried in the body takes no harm from
 * it either. */
#define SS_COLLIDE_SHALLOW 0.05
/* A body face under half its rest area is crushed by the pose (linear blend
 * skinning at a bent joint): its plane swings with the smallest move of its
 * corners, and skin pushed out of it squeezed the skin's own faces to 2-3%
 * of their area on the elbow and the mannequin. Not collided against, nor
 * from an anchor on such a face. */
#define SS_COLLIDE_CRUSHED 0.5
#define SS_COLLIDE_RING 64   /* faces of a ring looked at, at most */
#define SS_COLLIDE_RECHECK 8 /* steps a face's clean-surface test is kept */

/* Vertex v at x: its nearest face of the ring if it is behind the surface
 * there (and where it goes into out), -2 - that face if the move is
 * shallow, else -1. */
static int judge_vertex(const ss_collide_in *in, int v, const double x[3], double out[3],
                        double nout[3]) {
  const int fa = in->anchor_face[v];
  if (fa < 0) return -1;
  const ss_topo *t = in->topo;
  const ss_frames *fr = in->fr;
  const int *fav = t->face_vert + 3 * fa;
  const double *a0 = in->body + 3 * fav[0];
  const double above[3] = {x[0] - a0[0], x[1] - a0[1], x[2] - a0[2]};
  /* in front of its anchor face's plane: not looked at. Inside a convex
   * body means behind every face's plane, and that is where skin cuts in;
   * in front of it and behind a neighbour is a concave crease, which skin
   * bridges over (and where the body is crushed or passes through itself) */
  const double sa = dot3(above, fr->normal + 3 * fa);
  if (!(sa < in->thickness)) return -1;
  /* the faces of the ring and their distances, once; the nearest point,
   * then the pseudo-normal of the faces there */
  int ring[SS_COLLIDE_RING];
  double dist[SS_COLLIDE_RING], cp[3 * SS_COLLIDE_RING];
  int nring = 0;
  for (int c = 0; c < 3; c++) {
    const int w = t->vert_weld[fav[c]];
    for (int i = t->vf_start[w]; i < t->vf_start[w + 1] && nring < SS_COLLIDE_RING; i++) {
      const int g = t->vf_face[i];
      if (t->face_degenerate[g] || !(fr->area[g] > 0.0) || seen_before(t, fav, c, g)) continue;
      const int *gv = t->face_vert + 3 * g;
      const double *p0 = in->body + 3 * gv[0], *p1 = in->body + 3 * gv[1], *p2 = in->body + 3 * gv[2];
      double uv[2];
      dist[nring] = ss_closest_point_triangle(x, p0, p1, p2, uv);
      for (int k = 0; k < 3; k++)
        cp[3 * nring + k] = p0[k] + uv[0] * (p1[k] - p0[k]) + uv[1] * (p2[k] - p0[k]);
      ring[nring++] = g;
    }
  }
  int best = -1;
  for (int i = 0; i < nring; i++)
    if (best < 0 || dist[i] < dist[best]) best = i;
  if (best < 0) return -1;
  const int bf = ring[best];
  if (in->area0 && (!(fr->area[bf] >= SS_COLLIDE_CRUSHED * in->area0[bf]) ||
                    !(fr->area[fa] >= SS_COLLIDE_CRUSHED * in->area0[fa])))
    return -1;
  const double tie = dist[best] + 1e-12 * in->reach * in->reach; /* reach: an edge length */
  double n[3] = {0, 0, 0};
  for (int i = 0; i < nring; i++)
    if (dist[i] <= tie)
      for (int k = 0; k < 3; k++) n[k] += fr->normal[3 * ring[i] + k];
  const double len = sqrt(dot3(n, n));
  if (!(len > 0.0)) return -1;
  for (int k = 0; k < 3; k++) n[k] /= len;
  const double *bc = cp + 3 * best;
  const double rel[3] = {x[0] - bc[0], x[1] - bc[1], x[2] - bc[2]};
  const double sd = dot3(rel, n);
  if (!(sd < in->thickness)) return -1;
  /* along the pseudo-normal by the depth, not onto c: vertices deep under
   * a corner or an edge would all land on that one point and their faces
   * collapse (area ratios of 0.02 on the elbow) */
  for (int k = 0; k < 3; k++) out[k] = x[k] + (in->thickness - sd) * n[k], nout[k] = n[k];
  /* the clean-surface test only for a vertex a move would carry far */
  if (in->thickness - sd <= SS_COLLIDE_SHALLOW * in->reach) return -2 - bf;
  return bf;
}

/* Candidate k (vertex v) to where it goes; its velocity loses the part
 * into the body (an inelastic contact). The move itself is not turned into
 * velocity: a move of half an edge in a substep of 1/480 s launched the
 * skin off the body at 16 substeps. */
static void move(const ss_collider *c, int k, int v, double *x, double *vel) {
  memcpy(x + 3 * v, c->cand_x + 3 * k, 3 * sizeof(double));
  if (!vel) return;
  const double *n = c->cand_n + 3 * k;
  double *u = vel + 3 * v;
  const double un = dot3(u, n);
  if (un < 0.0)
    for (int i = 0; i < 3; i++) u[i] -= un * n[i];
}

int ss_collider_run(ss_collider *c, const ss_collide_in *in, int ndof, const int *dof_vert,
                    int nthread, long long step, double *x, double *vel) {
  int ncand = 0;
#ifdef _OPENMP
  if (nthread > 1 && ndof > 1024) {
#pragma omp parallel for schedule(static) num_threads(nthread) reduction(+ : ncand)
    for (int k = 0; k < ndof; k++) {
      const int v = dof_vert[k];
      c->cand_face[k] = judge_vertex(in, v, x + 3 * v, c->cand_x + 3 * k, c->cand_n + 3 * k);
      ncand += c->cand_face[k] != -1;
    }
  } else
#endif
  {
    (void)nthread;
    for (int k = 0; k < ndof; k++) {
      const int v = dof_vert[k];
      c->cand_face[k] = judge_vertex(in, v, x + 3 * v, c->cand_x + 3 * k, c->cand_n + 3 * k);
      ncand += c->cand_face[k] != -1;
    }
  }
  if (ncand == 0) return 0;
  /* the clean-surface test of the faces met, kept SS_COLLIDE_RECHECK steps
   * (the body's self-intersections move far slower than a step: a leg
   * through the belly takes a tenth of a second), each face's age its own so
   * that the tests of a step are few; the tree refitted in a step that tests */
  int moved = 0;
  for (int k = 0; k < ndof; k++) {
    int g = c->cand_face[k];
    if (g == -1) continue;
    if (g <= -2) { /* shallow */
      move(c, k, dof_vert[k], x, vel);
      moved++;
      continue;
    }
    if (c->face_step[g] < 0 || step - c->face_step[g] >= SS_COLLIDE_RECHECK || step < c->face_step[g]) {
      if (c->step_refit != step) {
        ss_bvh_refit(c->bvh, in->body);
        ss_wind_refit(c->wind, in->body);
        c->step_refit = step;
      }
      c->face_step[g] = step;
      c->face_buried[g] = (unsigned char)ss_wind_face_buried(c->wind, in->body, g);
    }
    if (c->face_buried[g]) continue;
    move(c, k, dof_vert[k], x, vel);
    moved++;
  }
  return moved;
}

int ss_sim_collide(ss_sim *sim) {
  const ss_model *m = sim->m;
  const double edge = m->edge_len;
  ss_collide_in in = {m->btopo, ss_mover_frames(sim->mover), sim->body_sub, sim->anchor_face,
                      m->body_area0, sim->set.collide_thickness * edge, edge};
  return ss_collider_run(sim->collider, &in, m->ndof, m->dof_vert, sim->nthread, sim->nstep, sim->x,
                         sim->v);
}
