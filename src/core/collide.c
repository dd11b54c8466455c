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
 * Where, cheap first: the anchor face and its edge neighbours give a point
 * of the surface near the vertex. A vertex within SS_COLLIDE_NEAR of it can
 * be no deeper (it is shallower than the depth that counts), and one in
 * front of those faces is out; the rest (about a third of the 19k
 * quadruped's skin in motion, whose anchors lag behind it) search the
 * body's tree for the nearest point, within the distance already known
 * (the tree's boxes further away are not visited). Not only the ring of the
 * anchor face: the deepest skin left by a ring search was where the anchor
 * lags more than a ring behind, or in front of its own face's plane and
 * behind a neighbour's (a crushed crease, the cap of a limb), or under a
 * face crushed by the pose. Behind the surface (by the pseudo-normal at the
 * nearest point: the normals of the faces nearest there summed, one face's
 * inside it, an edge's two, a corner's ring; Baerentzen and Aanaes 2005), it
 * moves out along that normal by its depth, and again from where it lands
 * (up to SS_COLLIDE_PASSES times, then onto the nearest point): in a crushed
 * crease the faces' planes cross, and one move along one normal left the
 * skin half an edge inside the next face.
 *
 * Not against the body where it passes through itself: the nearest face of
 * a vertex found deep behind the surface, and its anchor face, must be on
 * the body's clean surface, the winding number of the whole body at their
 * centroids 1/2 (inside.h), as the inside measure judges; a face lying
 * inside another part of the body (a leg through the belly) or turned inside
 * out by the pose is not collided against, so the skin is never pushed into
 * the body's own artefacts. The test runs only for moves longer than
 * SS_COLLIDE_SHALLOW, each face's result kept a few steps, and sums the
 * faces exactly within SS_COLLIDE_WIND_BETA node radii of the centroid only
 * (the measure's 3 radii cost twice as much; telling 1/2 from 0 or 1 does
 * not need them).
 *
 * No move squeezes a skin face: a move that would leave a face of the
 * vertex under SS_COLLIDE_SQUEEZE of its rest area, or turn it over, is
 * halved (twice), else not made; vertices of one face pushed out of a
 * crushed crease towards one line of the body made frames fail.
 *
 * Deterministic: the search per vertex alone (on the threads; the face a
 * search found bounds the vertex's next search, its speed and never its
 * result), the tests and the moves in vertex order on one thread. */
#include "collide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "closest.h"
#include "inside.h"
#include "sim_internal.h"
#include "ss_free.h"

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
  int *hint;                   /* (nvert) body face nearest to the vertex at its last search, or
                                  -1: bounds the next search (its speed, never its result) */
  int *vf_start, *vf_face;     /* (nvert + 1), (3 nface) CSR: the skin's faces around each
                                  vertex, for the squeeze guard */
};

int ss_collider_create(ss_collider **out, const ss_topo *btopo, const double *body_rest,
                       int nvert, int nface, const int *faces) {
  if (!out || !btopo || !body_rest || nvert < 0 || nface < 0 || (nface > 0 && !faces)) return SS_E_ARG;
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
  c->hint = malloc(sizeof(int) * ((size_t)nvert + 1));
  if (c->hint)
    for (int v = 0; v <= nvert; v++) c->hint[v] = -1;
  c->vf_start = calloc((size_t)nvert + 2, sizeof(int));
  c->vf_face = malloc(sizeof(int) * (3 * (size_t)nface + 1));
  if (c->vf_start && c->vf_face) {
    for (int i = 0; i < 3 * nface; i++) c->vf_start[faces[i] + 2]++;
    for (int v = 0; v < nvert; v++) c->vf_start[v + 2] += c->vf_start[v + 1];
    for (int i = 0; i < 3 * nface; i++) c->vf_face[c->vf_start[faces[i] + 1]++] = i / 3;
  }
  if (!status && !(c->face_step && c->face_buried && c->cand_face && c->cand_x && c->cand_n && c->hint &&
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
  SS_FREE_ALL(c->face_step, c->face_buried, c->cand_face, c->cand_x, c->cand_n, c->hint, c->vf_start,
              c->vf_face, c);
}

/* A move of at most this many edge lengths does not ask whether the face is
 * on the clean surface: the skin lying on the body sits a rounding error or
 * a chord's sag behind it almost everywhere (half the skin of a tube), and
 * the test is the pass's cost; a face buried in the body takes no harm from
 * it either. */
#define SS_COLLIDE_SHALLOW 0.05
/* A vertex this close to its anchor (edge lengths, less the thickness) is
 * not looked at: the anchor is a point of the body's surface, so the vertex
 * is no deeper than its distance to it, and shallower than the depth that
 * counts. Most of the skin is skipped so, before any search. */
#define SS_COLLIDE_NEAR 0.03
/* Steps a face's clean-surface test is kept: a clean face 8, a buried one 2
 * (the quadruped's legs leave the belly within a few frames, and skin kept
 * in by a stale test stayed a quarter of an edge deep). */
#define SS_COLLIDE_RECHECK 8
#define SS_COLLIDE_RECHECK_BURIED 2
/* The clean-surface test's near field (node radii; inside.h's measure uses
 * SS_WIND_BETA, 3): it only tells 1/2 from 0, 1 or 3/2, by 1/4, and at 2
 * radii the first-order far field stays within a few hundredths of the
 * exact sum (test_inside) while about half the faces are summed exactly. */
#define SS_COLLIDE_WIND_BETA 2.0
#define SS_COLLIDE_PASSES 4  /* moves along normals before one onto the nearest point */
#define SS_COLLIDE_SQUEEZE 0.2 /* least area ratio a move may leave a skin face at */

/* The pseudo-normal of the body at c, the nearest point of face nf to x
 * (Baerentzen and Aanaes 2005: the sum of the normals of the faces nearest
 * there; one face's inside it, an edge's two, a corner's ring). */
static int pseudo_normal(const ss_collide_in *in, int nf, const double uv[2], const double x[3],
                         double d2, double n[3]) {
  const ss_topo *t = in->topo;
  const ss_frames *fr = in->fr;
  const double eps = 1e-9;
  if (uv[0] > eps && uv[1] > eps && 1.0 - uv[0] - uv[1] > eps) {
    memcpy(n, fr->normal + 3 * nf, 3 * sizeof(double));
  } else {
    /* the faces around nf's corners at the same distance (an edge's or a
     * corner's faces), each once */
    const double tie = d2 + 1e-12 * in->reach * in->reach;
    const int *fv = t->face_vert + 3 * nf;
    n[0] = n[1] = n[2] = 0.0;
    for (int c = 0; c < 3; c++) {
      const int w = t->vert_weld[fv[c]];
      for (int i = t->vf_start[w]; i < t->vf_start[w + 1]; i++) {
        const int g = t->vf_face[i];
        const int *gv = t->face_vert + 3 * g;
        int seen = 0; /* met around an earlier corner of nf */
        for (int e = 0; e < c && !seen; e++) {
          const int we = t->vert_weld[fv[e]];
          seen = t->vert_weld[gv[0]] == we || t->vert_weld[gv[1]] == we || t->vert_weld[gv[2]] == we;
        }
        if (seen || t->face_degenerate[g] || !(fr->area[g] > 0.0)) continue;
        double guv[2];
        const double *p0 = in->body + 3 * gv[0], *p1 = in->body + 3 * gv[1], *p2 = in->body + 3 * gv[2];
        if (g == nf || ss_closest_point_triangle(x, p0, p1, p2, guv) <= tie)
          for (int k = 0; k < 3; k++) n[k] += fr->normal[3 * g + k];
      }
    }
  }
  const double len = sqrt(dot3(n, n));
  if (!(len > 0.0)) return 0;
  for (int k = 0; k < 3; k++) n[k] /= len;
  return 1;
}

/* Vertex v at x: the nearest body face if x is behind the surface there
 * (and where it goes into out, along nout), -2 - that face if the move is
 * shallow, else -1. */
/* Face g's clean-surface test, kept SS_COLLIDE_RECHECK steps (the body's
 * self-intersections move far slower than a step: a leg through the belly
 * takes a tenth of a second), each face's age its own so that the tests of
 * a step are few; the winding numbers refitted in a step that tests. */
static int fresh(const ss_collider *c, long long step, int g) {
  const long long keep = c->face_buried[g] ? SS_COLLIDE_RECHECK_BURIED : SS_COLLIDE_RECHECK;
  return c->face_step[g] >= 0 && step - c->face_step[g] < keep && step >= c->face_step[g];
}

static int buried(ss_collider *c, const ss_collide_in *in, long long step, int g) {
  if (!fresh(c, step, g)) {
    if (c->step_refit != step) {
      ss_wind_refit(c->wind, in->body);
      c->step_refit = step;
    }
    c->face_step[g] = step;
    c->face_buried[g] = (unsigned char)ss_wind_face_buried_beta(c->wind, in->body, g, SS_COLLIDE_WIND_BETA);
  }
  return c->face_buried[g];
}

/* The nearest point to p among the anchor face fa and its edge neighbours:
 * its face (-1 if none), uv and squared distance; *inner 1 if the point is
 * not on the outer rim of those faces (in fa, or inside a neighbour, or on
 * its edge with fa), where nearer faces may lie beyond. */
static int local_nearest(const ss_collide_in *in, int fa, const double p[3], double uv[2], double *d2,
                         int *inner) {
  const ss_topo *t = in->topo;
  int best = -1, best_k = -1;
  *d2 = INFINITY;
  for (int k = -1; k < 3; k++) {
    const int g = k < 0 ? fa : t->face_adj[3 * fa + k];
    if (g < 0 || t->face_degenerate[g] || !(in->fr->area[g] > 0.0)) continue;
    const int *gv = t->face_vert + 3 * g;
    double guv[2];
    const double d = ss_closest_point_triangle(p, in->body + 3 * gv[0], in->body + 3 * gv[1],
                                               in->body + 3 * gv[2], guv);
    if (d < *d2) *d2 = d, best = g, best_k = k, uv[0] = guv[0], uv[1] = guv[1];
  }
  const double eps = 1e-9;
  *inner = best_k < 0 || (uv[0] > eps && uv[1] > eps && 1.0 - uv[0] - uv[1] > eps);
  if (!*inner && best >= 0) {
    /* on the edge it shares with fa: within the patch */
    const int e = t->face_adj_edge[3 * fa + best_k];
    const double w[3] = {1.0 - uv[0] - uv[1], uv[0], uv[1]}; /* at corners 0, 1, 2 */
    if (e >= 0) *inner = w[(e + 2) % 3] <= eps; /* edge e joins corners e and e + 1 */
  }
  return best;
}

/* Where point p is against the body's surface near face nf (its nearest
 * point there at uv, squared distance d2): the signed distance along the
 * pseudo-normal n and the nearest point c. 0 if no normal. */
static int surface_at(const ss_collide_in *in, int nf, const double uv[2], const double p[3], double d2,
                      double n[3], double c[3], double *sd) {
  if (!pseudo_normal(in, nf, uv, p, d2, n)) return 0;
  const int *fv = in->topo->face_vert + 3 * nf;
  const double *p0 = in->body + 3 * fv[0], *p1 = in->body + 3 * fv[1], *p2 = in->body + 3 * fv[2];
  double rel[3];
  for (int k = 0; k < 3; k++) {
    c[k] = p0[k] + uv[0] * (p1[k] - p0[k]) + uv[1] * (p2[k] - p0[k]);
    rel[k] = p[k] - c[k];
  }
  *sd = dot3(rel, n);
  return 1;
}

/* Vertex v at x: the nearest body face if x is deeper behind the surface
 * there than SS_COLLIDE_NEAR (and where it goes into out, along nout), -2 -
 * that face if the move is shallow, else -1. */
static int judge_vertex(ss_collider *col, const ss_collide_in *in, long long step, int v,
                        const double x[3], double out[3], double nout[3]) {
  const int fa = in->anchor_face[v];
  if (fa < 0) return -1;
  /* anchored on a face known to be buried (skin inside a leg that passes
   * through the belly): not moved, whatever its depth, and not searched */
  if (fresh(col, step, fa) && col->face_buried[fa]) return -1;
  const double tiny = 1e-9 * in->reach; /* a point put on a plane is behind it half the time */
  /* the cheap look, around the anchor: the anchor face and its neighbours */
  double uv[2], d2, n[3], cp[3], sd;
  int inner;
  const int lf = local_nearest(in, fa, x, uv, &d2, &inner);
  if (lf < 0) return -1;
  const double near = SS_COLLIDE_NEAR * in->reach - in->thickness;
  /* no deeper than the distance to a point of the surface */
  if (near > 0.0 && d2 <= near * near) return -1;
  /* in front of the surface around the anchor, away from its rim (on the
   * rim the search below decides, whatever the side) */
  if (inner && (!surface_at(in, lf, uv, x, d2, n, cp, &sd) || !(sd < in->thickness - tiny))) return -1;
  double p[3] = {x[0], x[1], x[2]};
  const int hf = col->hint[v];
  if (hf >= 0 && hf != lf) {
    const int *hv = in->topo->face_vert + 3 * hf;
    double huv[2];
    const double h2 = ss_closest_point_triangle(x, in->body + 3 * hv[0], in->body + 3 * hv[1],
                                                in->body + 3 * hv[2], huv);
    if (h2 < d2) d2 = h2;
  }
  int first = -1;
  double bound2 = d2;
  for (int it = 0; it < SS_COLLIDE_PASSES; it++) {
    /* the nearest body point, within the bound known: a search that
     * visits the few boxes around the vertex */
    int nf;
    const double e2 = ss_bvh_closest_within(col->bvh, in->body, p, bound2 * (1.0 + 1e-9) + 1e-300, &nf, uv);
    if (nf >= 0 && it == 0) col->hint[v] = nf;
    if (nf < 0 || !surface_at(in, nf, uv, p, e2, n, cp, &sd)) break;
    if (!(sd < in->thickness - tiny)) break;
    if (first < 0) {
      if (near > 0.0 && e2 <= near * near) return -1;
      first = nf;
    }
    memcpy(nout, n, 3 * sizeof(double));
    if (it == SS_COLLIDE_PASSES - 1) {
      /* still behind after moves along normals (a crushed crease, whose
       * faces' planes cross): onto the nearest point */
      for (int k = 0; k < 3; k++) p[k] = cp[k] + in->thickness * n[k];
      break;
    }
    /* along the pseudo-normal by the depth, not onto the nearest point:
     * vertices deep under a corner or an edge would all land on that one
     * point and their faces collapse */
    for (int k = 0; k < 3; k++) p[k] += (in->thickness - sd) * n[k];
    const double pc[3] = {p[0] - cp[0], p[1] - cp[1], p[2] - cp[2]}; /* cp: on the surface */
    bound2 = dot3(pc, pc);
  }
  if (first < 0) return -1;
  memcpy(out, p, 3 * sizeof(double));
  /* the clean-surface test only for a vertex a move would carry far */
  const double dx[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]};
  if (dot3(dx, dx) <= SS_COLLIDE_SHALLOW * SS_COLLIDE_SHALLOW * in->reach * in->reach) return -2 - first;
  return first;
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

/* 1 if moving vertex v to p would squeeze one of its skin faces below
 * SS_COLLIDE_SQUEEZE of its rest area or turn it over: vertices of one
 * face pushed out of a crushed crease towards one line of the body (and the
 * solver then iterating to its cap on the squeezed faces). Such a vertex
 * stays, its neighbours go out. */
static int squeezes(const ss_collider *c, const ss_collide_in *in, int v, const double *x,
                    const double p[3]) {
  if (!in->faces) return 0;
  for (int i = c->vf_start[v]; i < c->vf_start[v + 1]; i++) {
    const int f = c->vf_face[i];
    if (!(in->rest_area[f] > 0.0)) continue;
    const int *fv = in->faces + 3 * f;
    const double *q[3], *o[3];
    for (int j = 0; j < 3; j++) o[j] = q[j] = x + 3 * fv[j];
    for (int j = 0; j < 3; j++)
      if (fv[j] == v) q[j] = p;
    double e1[3], e2[3], n0[3], n1[3];
    for (int k = 0; k < 3; k++) e1[k] = o[1][k] - o[0][k], e2[k] = o[2][k] - o[0][k];
    cross3(e1, e2, n0);
    for (int k = 0; k < 3; k++) e1[k] = q[1][k] - q[0][k], e2[k] = q[2][k] - q[0][k];
    cross3(e1, e2, n1);
    const double a1 = 0.5 * sqrt(dot3(n1, n1));
    if (dot3(n0, n1) <= 0.0 || (a1 < SS_COLLIDE_SQUEEZE * in->rest_area[f] && dot3(n1, n1) < dot3(n0, n0)))
      return 1;
  }
  return 0;
}

int ss_collider_run(ss_collider *c, const ss_collide_in *in, int ndof, const int *dof_vert,
                    int nthread, long long step, double *x, double *vel) {
  ss_bvh_refit(c->bvh, in->body);
  int ncand = 0;
#ifdef _OPENMP
  if (nthread > 1 && ndof > 1024) {
#pragma omp parallel for schedule(static) num_threads(nthread) reduction(+ : ncand)
    for (int k = 0; k < ndof; k++) {
      const int v = dof_vert[k];
      c->cand_face[k] = judge_vertex(c, in, step, v, x + 3 * v, c->cand_x + 3 * k, c->cand_n + 3 * k);
      ncand += c->cand_face[k] != -1;
    }
  } else
#endif
  {
    (void)nthread;
    for (int k = 0; k < ndof; k++) {
      const int v = dof_vert[k];
      c->cand_face[k] = judge_vertex(c, in, step, v, x + 3 * v, c->cand_x + 3 * k, c->cand_n + 3 * k);
      ncand += c->cand_face[k] != -1;
    }
  }
  if (ncand == 0) return 0;
  /* a deep move only out of the clean surface: neither the nearest face nor
   * the anchor's buried in the body (as the inside measure judges) */
  int moved = 0;
  for (int k = 0; k < ndof; k++) {
    const int g = c->cand_face[k];
    const int v = dof_vert[k];
    if (g == -1) continue;
    if (g >= 0) {
      const int fa = in->anchor_face[v];
      if (buried(c, in, step, g) || (fa != g && buried(c, in, step, fa))) continue;
    }
    /* the whole move, else half, else a quarter, if one squeezes none */
    double *q = c->cand_x + 3 * k;
    const double x0[3] = {x[3 * v], x[3 * v + 1], x[3 * v + 2]};
    int ok = 0;
    for (int h = 0; h < 3 && !(ok = !squeezes(c, in, v, x, q)); h++)
      for (int i = 0; i < 3; i++) q[i] = 0.5 * (x0[i] + q[i]);
    if (!ok) continue;
    move(c, k, v, x, vel);
    moved++;
  }
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
