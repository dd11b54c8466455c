/* The contact pass's moves (collide.c finds them): no move squeezes or
 * stretches a skin face (doc/model.md, "Contact").
 *
 * A move that would leave a face of the vertex under SS_COLLIDE_SQUEEZE of
 * its rest area, or turn it over, or stretch it past SS_COLLIDE_STRETCH
 * times it, waits for its neighbours' moves. Those still waiting are then
 * moved all at once, each to where it goes, and those whose faces that
 * squeezes, stretches or turns are put back (until none does): a cluster
 * of vertices a fast leg has gone through lies an edge deep, and each
 * vertex's move alone turns the faces it shares with the neighbours left
 * behind. Then the vertex moves with its ring carried along (its own faces
 * move whole), unless that squeezes, stretches or turns a face of the
 * patch; else it is halved (twice), and what is left of the move is tried
 * again in the next sweep, the neighbours moved meanwhile (up to
 * SS_COLLIDE_SWEEPS). Vertices of one face pushed out of a crushed crease
 * towards one line of the body made frames fail; moves only halved left
 * the skin in the folds at the quadruped's paws, the elbow's crease and
 * the Fox's legs a quarter to a half edge deep. The vertices around a
 * paw's pole, pushed out along normals that part there, stretched the
 * small faces of its fan 18 to 23 times for a frame: a spike of skin, and
 * past 20 times a failed frame. All in vertex order, on one thread. */
#include <math.h>
#include <string.h>

#include "collide_pass.h"
#include "collide_surface.h"
#include "ss_vec.h"

/* Least and most area ratio (to the rest area) a move may leave a skin face
 * at, if it makes the face smaller or larger. A tenth: a fifth kept skin a
 * fifth to two thirds of an edge deep in the elbow's crease, the 19k
 * mannequin's folds and the 5k quadruped's; below a twentieth the faces
 * so squeezed made frames fail. Ten times: short of the twenty that makes
 * a frame fail, and above what the skin stretches without contact (under
 * two times). */
#define SS_COLLIDE_SQUEEZE 0.1
#define SS_COLLIDE_STRETCH 10.0
#define SS_COLLIDE_PATCH 32 /* vertices a patch move carries at most (a vertex and its ring) */
#define SS_COLLIDE_SWEEPS 4 /* sweeps over the moves (a move made part of the way tries the rest) */

/* Candidate k (vertex v) to where it goes; its velocity loses the part
 * into the body (an inelastic contact). The move itself is not turned into
 * velocity: a move of half an edge in a substep of 1/480 s launched the
 * skin off the body at 16 substeps. */
static void move_to(const ss_collider *c, int k, int v, const double p[3], double *x, double *vel) {
  memcpy(x + 3 * v, p, 3 * sizeof(double));
  if (!vel) return;
  const double *n = c->cand_n + 3 * k;
  double *u = vel + 3 * v;
  const double un = dot3(u, n);
  if (un < 0.0)
    for (int i = 0; i < 3; i++) u[i] -= un * n[i];
}

/* The (area-scaled) normals of a skin face whose corners were at o and are
 * at q: what the squeeze and turn tests of a move compare. */
static void move_normals(const double *const o[3], const double *const q[3], double n0[3], double n1[3]) {
  double e1[3], e2[3];
  for (int k = 0; k < 3; k++) e1[k] = o[1][k] - o[0][k], e2[k] = o[2][k] - o[0][k];
  cross3(e1, e2, n0);
  for (int k = 0; k < 3; k++) e1[k] = q[1][k] - q[0][k], e2[k] = q[2][k] - q[0][k];
  cross3(e1, e2, n1);
}

/* squeezed() of a face of rest area a0 by its move_normals n0 (before), n1 (after). */
static int squeezed_normals(double a0, const double n0[3], const double n1[3]) {
  const double a1 = 0.5 * sqrt(dot3(n1, n1)), grows = dot3(n1, n1) > dot3(n0, n0);
  return dot3(n0, n1) <= 0.0 || (a1 < SS_COLLIDE_SQUEEZE * a0 && !grows) ||
         (a1 > SS_COLLIDE_STRETCH * a0 && grows);
}

/* 1 if a skin face of rest area a0 whose corners were at o and are at q
 * is squeezed below SS_COLLIDE_SQUEEZE of its rest area by the move (and
 * smaller than it was), stretched past SS_COLLIDE_STRETCH times it (and
 * larger than it was), or turned over. */
static int squeezed(double a0, const double *const o[3], const double *const q[3]) {
  double n0[3], n1[3];
  move_normals(o, q, n0, n1);
  return squeezed_normals(a0, n0, n1);
}

/* 1 if moving vertex v to p would squeeze one of its skin faces below
 * SS_COLLIDE_SQUEEZE of its rest area, stretch one past SS_COLLIDE_STRETCH
 * times it, or turn one over (squeezed()): vertices of one face pushed out
 * of a crushed crease towards one line of the body (and the solver then
 * iterating to its cap on the squeezed faces), or out of a paw's pole along
 * parting normals. Such a vertex is moved with its ring (move_patch), else
 * by less. */
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
    if (squeezed(in->rest_area[f], o, q)) return 1;
  }
  return 0;
}

/* 1 if a skin face (corners fv; move_normals n0 before a move, n1 after
 * it) turns over against the body under it (its corners' anchor faces'
 * normals summed), as the count of faces turned off the body judges
 * (ss_sim_count_off_body). */
static int turns_off_body(const ss_collide_in *in, const int *fv, const double n0[3], const double n1[3]) {
  double nb[3] = {0.0, 0.0, 0.0};
  for (int j = 0; j < 3; j++) {
    const int a = in->anchor_face[fv[j]];
    if (a >= 0)
      for (int k = 0; k < 3; k++) nb[k] += in->fr->normal[3 * a + k];
  }
  const double b0 = dot3(n0, nb), b1 = dot3(n1, nb);
  return (b0 > 0.0 && b1 <= 0.0) || (b0 < 0.0 && b1 >= 0.0);
}

/* 1 if skin face f, its corners moved from o to q, is squeezed, stretched
 * or turned over (squeezed()), or turned off the body under it. */
static int spoils_face(const ss_collide_in *in, int f, const double *const o[3], const double *const q[3]) {
  double n0[3], n1[3];
  move_normals(o, q, n0, n1);
  return squeezed_normals(in->rest_area[f], n0, n1) || turns_off_body(in, in->faces + 3 * f, n0, n1);
}

/* Signed distance of p along the pseudo-normal of the local nearest point
 * of the surface a descent from face f finds (infinity if none). */
static double local_depth(const ss_collide_in *in, int f, const double p[3]) {
  double uv[2], d2, n[3], cp[3], sd;
  int settled;
  const int lf = f < 0 ? -1 : ss_collide_descend(in, f, p, uv, &d2, &settled);
  if (lf < 0 || !ss_collide_surface_at(in, lf, uv, p, d2, n, cp, &sd)) return INFINITY;
  return sd;
}

/* Vertex v moved to p with the free vertices of its ring carried by the
 * same displacement, for a move that would squeeze a face of v alone (a
 * fold of the skin at the body's surface, a face across the move's
 * direction): v's own faces move whole, and what strain there is falls on
 * the faces of the ring's outer edges. Not made (nothing moves) if that
 * squeezes, stretches or turns over a face of the patch, turns one off the
 * body under it, or carries a vertex of the ring deeper behind the surface
 * near it (across a crushed crease, into the far wall): in the quadruped's
 * crushed creases such patches more than doubled the faces turned off the
 * body. 1 if made. */
static int move_patch(ss_collider *c, const ss_collide_in *in, int v, const double p[3], double *x) {
  if (!in->faces) return 0;
  int pv[SS_COLLIDE_PATCH];
  double old[SS_COLLIDE_PATCH][3];
  int np = 0;
  pv[np++] = v;
  for (int i = c->vf_start[v]; i < c->vf_start[v + 1]; i++) {
    const int *fv = in->faces + 3 * c->vf_face[i];
    for (int j = 0; j < 3; j++) {
      const int u = fv[j];
      int seen = c->dof_of[u] < 0;
      for (int q = 0; q < np && !seen; q++) seen = pv[q] == u;
      if (seen) continue;
      if (np == SS_COLLIDE_PATCH) return 0;
      pv[np++] = u;
    }
  }
  const double dx[3] = {p[0] - x[3 * v], p[1] - x[3 * v + 1], p[2] - x[3 * v + 2]};
  for (int q = 0; q < np; q++)
    for (int k = 0; k < 3; k++) old[q][k] = x[3 * pv[q] + k], x[3 * pv[q] + k] += dx[k];
  int bad = 0;
  for (int q = 0; q < np && !bad; q++) {
    const int u = pv[q];
    for (int i = c->vf_start[u]; i < c->vf_start[u + 1] && !bad; i++) {
      const int f = c->vf_face[i];
      if (!(in->rest_area[f] > 0.0)) continue;
      const int *fv = in->faces + 3 * f;
      const double *o[3], *n[3];
      for (int j = 0; j < 3; j++) {
        n[j] = o[j] = x + 3 * fv[j];
        for (int r = 0; r < np; r++)
          if (pv[r] == fv[j]) o[j] = old[r];
      }
      bad = spoils_face(in, f, o, n);
    }
  }
  for (int q = 1; q < np && !bad; q++) {
    const int u = pv[q];
    const int f = c->hint[u] >= 0 ? c->hint[u] : in->anchor_face[u];
    const double sd = local_depth(in, f, x + 3 * u);
    bad = sd < in->thickness && sd < local_depth(in, f, old[q]);
  }
  if (bad)
    for (int q = 0; q < np; q++) memcpy(x + 3 * pv[q], old[q], 3 * sizeof(double));
  else
    for (int q = 1; q < np; q++) c->carried[c->dof_of[pv[q]]] = 1;
  return !bad;
}

/* The candidates of move_k made or given up (cand_face -1) taken off the
 * list; returns how many are left. */
static int nmove_left(ss_collider *c, int nmove) {
  int left = 0;
  for (int i = 0; i < nmove; i++)
    if (c->cand_face[c->move_k[i]] != -1) c->move_k[left++] = c->move_k[i];
  return left;
}

/* The nmove candidates of move_k moved all at once, each to where it goes:
 * then each whose move squeezes, stretches or turns over a face of it
 * (against where the face's corners were), or turns one off the body
 * under it, is put back, until none does; the rest are made. A cluster of
 * vertices a fast leg has gone through is deeper than an edge, and each
 * vertex's move alone, or with its ring, turns faces its neighbours' moves
 * would turn back. Returns how many were made (their cand_face -1). */
static int move_jointly(ss_collider *c, const ss_collide_in *in, const int *dof_vert, int nmove, double *x,
                        double *vel) {
  if (!in->faces || nmove < 2) return 0;
  for (int j = 0; j < nmove; j++) {
    const int k = c->move_k[j], v = dof_vert[k];
    c->joint_of[v] = j;
    memcpy(c->joint_old + 3 * j, x + 3 * v, 3 * sizeof(double));
    memcpy(x + 3 * v, c->cand_x + 3 * k, 3 * sizeof(double));
  }
  int moving = nmove;
  for (int changed = 1; changed && moving > 0;) {
    changed = 0;
    for (int j = 0; j < nmove; j++) {
      const int k = c->move_k[j], v = dof_vert[k];
      if (c->joint_of[v] < 0) continue;
      int bad = 0;
      for (int i = c->vf_start[v]; i < c->vf_start[v + 1] && !bad; i++) {
        const int f = c->vf_face[i];
        if (!(in->rest_area[f] > 0.0)) continue;
        const int *fv = in->faces + 3 * f;
        const double *o[3], *q[3];
        for (int r = 0; r < 3; r++) {
          const int jr = c->joint_of[fv[r]];
          q[r] = x + 3 * fv[r];
          o[r] = jr >= 0 ? c->joint_old + 3 * jr : q[r];
        }
        bad = spoils_face(in, f, o, q);
      }
      if (!bad) continue;
      memcpy(x + 3 * v, c->joint_old + 3 * j, 3 * sizeof(double));
      c->joint_of[v] = -1;
      moving--, changed = 1;
    }
  }
  for (int j = 0; j < nmove; j++) {
    const int k = c->move_k[j], v = dof_vert[k];
    if (c->joint_of[v] < 0) continue;
    c->joint_of[v] = -1;
    c->cand_face[k] = -1;
    move_to(c, k, v, x + 3 * v, x, vel);
  }
  return moving;
}

/* The moves of the nmove candidates of move_k: the whole moves that squeeze
 * no skin face first; then (if carry) the rest all at once, those that
 * squeeze none of them; then, their neighbours moved meanwhile, the rest:
 * the whole move, else (if carry) the move carrying the vertex's ring
 * along, else half, else a quarter. A vertex moved only part of the way tries the
 * rest in the next sweep, its neighbours moved meanwhile (in vertex order
 * alone, a vertex that went before its neighbours had its move halved for
 * a face their moves then opened again, and stayed half as deep). Returns
 * how many were made. */
int ss_collide_sweep_moves(ss_collider *c, const ss_collide_in *in, const int *dof_vert, int nmove, int carry,
                           double *x, double *vel) {
  int moved = 0;
  for (int sweep = 0; sweep < SS_COLLIDE_SWEEPS && nmove > 0; sweep++) {
    for (int j = 0; j < nmove; j++) {
      const int k = c->move_k[j];
      const int v = dof_vert[k];
      const double x0[3] = {x[3 * v], x[3 * v + 1], x[3 * v + 2]};
      double q[3] = {c->cand_x[3 * k], c->cand_x[3 * k + 1], c->cand_x[3 * k + 2]};
      int ok = !squeezes(c, in, v, x, q);
      if (!ok && sweep == 0) continue;
      if (!ok && carry && move_patch(c, in, v, q, x)) {
        /* v is where it goes: its velocity as for a move of its own */
        c->cand_face[k] = -1;
        move_to(c, k, v, q, x, vel);
        moved++;
        continue;
      }
      int part = 0;
      for (int h = 0; h < 2 && !ok; h++, part = 1) {
        for (int i = 0; i < 3; i++) q[i] = 0.5 * (x0[i] + q[i]);
        ok = !squeezes(c, in, v, x, q);
      }
      const int last = !part || sweep == SS_COLLIDE_SWEEPS - 1;
      if (last) c->cand_face[k] = -1;
      if (!ok) continue;
      move_to(c, k, v, q, x, vel);
      moved += last;
    }
    if (sweep == 0 && carry) moved += move_jointly(c, in, dof_vert, nmove_left(c, nmove), x, vel);
    nmove = nmove_left(c, nmove);
  }
  return moved;
}
