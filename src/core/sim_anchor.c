/* The anchor pass of a substep (sim.c, stage 4) and the anchors' positions.
 *
 * After the solve, the spring force drags each anchor of a free point (a
 * vertex, or a face barycenter with a spring) towards the skin point it
 * holds, a* = a0 + slide_frac (p - a0), and the mover carries its (face, u, v)
 * over the body to a* (the walk: 2D ray tracing, walk.c; or projection or
 * n-ring, mover.h); then the tether takes tether_frac of the way back home
 * (doc/model.md, "The walk", "The tether"). Each anchor's move is independent
 * of the others': with threads they share the anchors, each thread with its
 * own walker, and the bits do not depend on the thread count. */
#include <math.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "closest.h" /* the tether's home stretch */
#include "isa.h"
#include "sim_internal.h"
#include "ss_vec.h"
#include "walk_step.h"

/* Anchor positions in the body pose `pose`, which the mover holds. An anchor
 * without a face (a vertex in no face of a skin copied from the body) follows
 * its body vertex. */
static inline void anchor_position(ss_sim *sim, const ss_frames *fr, const double *pose, int a) {
  if (sim->anchor_face[a] >= 0)
    ss_anchor_position(fr, sim->anchor_face[a], sim->anchor_uv + 2 * a, sim->anchor_pos + 3 * a);
  else if (a < sim->m->nvert)
    memcpy(sim->anchor_pos + 3 * a, pose + 3 * a, 3 * sizeof(double));
}

void ss_sim_anchor_positions_update(ss_sim *sim, const double *pose) {
  const ss_frames *fr = ss_mover_frames(sim->mover);
  const int nanchor = sim->m->nanchor;
#ifdef _OPENMP
  if (sim->nthread > 1) {
#pragma omp parallel for schedule(static) num_threads(sim->nthread)
    for (int a = 0; a < nanchor; a++) anchor_position(sim, fr, pose, a);
    return;
  }
#endif
  for (int a = 0; a < nanchor; a++) anchor_position(sim, fr, pose, a);
}


/* 1 if body faces f and g share a corner (welded). */
static int share_corner(const ss_topo *t, int f, int g) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      if (t->vert_weld[t->face_vert[3 * f + i]] == t->vert_weld[t->face_vert[3 * g + j]]) return 1;
  return 0;
}

/* The tether's home stretch: the anchor goes to the point of home face h
 * closest to `target` (robust on slivers and degenerate faces). */
static void home_stretch(const ss_frames *fr, int h, const double target[3], double uv[2]) {
  const double *o = ss_frames_origin(fr, h), *e = ss_frames_edges(fr, h);
  const double b[3] = {o[0] + e[0], o[1] + e[1], o[2] + e[2]};
  const double c[3] = {o[0] + e[3], o[1] + e[4], o[2] + e[5]};
  ss_closest_point_triangle(target, o, b, c, uv);
}

void ss_sim_clear_anchor_measures(ss_sim *sim) {
  memset(sim->anchor_pull, 0, (size_t)sim->m->nanchor * sizeof(double));
  memset(sim->anchor_path, 0, (size_t)sim->m->nanchor * sizeof(double));
}

typedef struct anchor_counts {
  long long moved, steps, boundary, crease, step_limit;
} anchor_counts;

/* What the anchor pass reads of the sim, read once per pass into a local
 * copy (a value, never addressed): through sim, every field was loaded again
 * for each anchor, since the stores into anchor_face and anchor_uv might
 * have changed them for all the compiler knew. */
typedef struct anchor_pass {
  ss_sim *sim;
  const ss_frames *fr; /* the mover's frames */
  const double *x, *anchor_pos, *k_vert, *k_face, *anchor_uv0;
  const int *dof, *faces, *anchor_face0;
  int *anchor_face;
  double *anchor_uv;
  double slide, tether; /* this substep's fractions of the way */
  int nv, nanchor, max_steps;
  int walks;   /* the mover's method is the walk */
  int measure; /* ss_sim_measure_anchors */
} anchor_pass;

static anchor_pass anchor_pass_of(ss_sim *sim, const ss_substep *in) {
  anchor_pass P = {
      .sim = sim,
      .fr = ss_mover_frames(sim->mover),
      .x = sim->x,
      .anchor_pos = sim->anchor_pos,
      .k_vert = sim->m->k_vert,
      .k_face = sim->m->k_face,
      .anchor_uv0 = sim->m->anchor_uv0,
      .dof = sim->m->dof,
      .faces = sim->m->faces,
      .anchor_face0 = sim->m->anchor_face0,
      .anchor_face = sim->anchor_face,
      .anchor_uv = sim->anchor_uv,
      .slide = in->slide_frac,
      .tether = in->tether_frac,
      .nv = sim->m->nvert,
      .nanchor = sim->m->nanchor,
      .max_steps = sim->set.mover.walk_max_steps,
      .walks = ss_mover_method(sim->mover) == SS_METHOD_WALK,
      .measure = sim->measure_anchors,
  };
  return P;
}

/* The walk of an anchor, its path's length summed only where measured
 * (ss_sim_measure_anchors). */
static inline void walk_anchor(const anchor_pass *P, ss_walker *walker, int face, const double uv[2],
                               const double target[3], ss_walk_result *res) {
  ss_walker *wk = walker ? walker : P->sim->walkers[0];
  if (P->measure)
    ss_walk(wk, P->sim->m->btopo, P->fr, face, uv, target, P->max_steps, res);
  else
    ss_walk_unmeasured(wk, P->sim->m->btopo, P->fr, face, uv, target, P->max_steps, res);
}

/* The tether of an anchor out of its home face: walk back along the surface
 * towards where it was bound (always the walk, whatever the method: it
 * cannot jump a gap). Updates res; returns 1 if the anchor moved. */
static int tether_from_afar(const anchor_pass *P, int a, ss_walker *walker, ss_walk_result *res,
                            anchor_counts *c) {
  ss_sim *sim = P->sim;
  const ss_frames *fr = P->fr;
  double here[3], home[3], target[3];
  ss_anchor_position(fr, res->face, res->uv, here);
  ss_anchor_position(fr, P->anchor_face0[a], P->anchor_uv0 + 2 * a, home);
  /* The step: tether_frac of the way, along the surface: the chord to
   * home turned into the body's tangent plane here (kept at its length).
   * The chord itself dives into the body where home is far round it, and
   * half a turn round a capsule it points straight in: an anchor there
   * walked nowhere (twist: 6 anchors half a turn from home for good). */
  double d[3], d2 = 0.0, dn = 0.0;
  const double *n = fr->normal + 3 * res->face;
  for (int i = 0; i < 3; i++) {
    d[i] = home[i] - here[i];
    d2 += d[i] * d[i];
    dn += d[i] * n[i];
  }
  double t2 = 0.0;
  for (int i = 0; i < 3; i++) {
    d[i] -= dn * n[i];
    t2 += d[i] * d[i];
  }
  const double scale = t2 > 0.0 ? P->tether * sqrt(d2 / t2) : 0.0;
  double pull2 = 0.0;
  for (int i = 0; i < 3; i++) {
    target[i] = here[i] + scale * d[i];
    pull2 += (target[i] - here[i]) * (target[i] - here[i]);
  }
  const int h = P->anchor_face0[a];
  if (pull2 > 0.0 && share_corner(sim->m->btopo, res->face, h)) {
    /* Next to home (its face shares a corner with the home face): the
     * rest of the way in the home face's own frame. A bind point is often
     * a body vertex (a skin copied from the body), where the faces around
     * meet at angles: walking onto it, the face the walk ends in - and the
     * plane it projects on - would flip with the last bits of the skin's
     * position, and Newton and quasi-Newton (or a copied and a bound skin)
     * would part ways within frames (0.4 edge lengths on quadruped). */
    home_stretch(fr, h, target, res->uv);
    res->face = h;
    if (P->measure) sim->anchor_pull[a] += sqrt(pull2);
    return 1;
  }
  if (pull2 > 0.0) {
    const int face = res->face;
    const double uv[2] = {res->uv[0], res->uv[1]};
    ss_walk_result back;
    walk_anchor(P, walker, face, uv, target, &back);
    res->face = back.face;
    res->uv[0] = back.uv[0];
    res->uv[1] = back.uv[1];
    if (P->measure) {
      sim->anchor_pull[a] += sqrt(pull2);
      sim->anchor_path[a] += back.length;
    }
    c->steps += back.steps;
    return 1;
  }
  return 0;
}

/* Moves anchor a (if it holds a free point) with walker (NULL: one thread;
 * the walk then takes walkers[0], projection and n-ring the mover's own
 * scratch). */
static inline SS_ALWAYS_INLINE void move_anchor(const anchor_pass *P, int a, ss_walker *walker,
                                                anchor_counts *c, const int walks, const int measure,
                                                const int leashed) {
  const ss_frames *fr = P->fr;
  if (a + SS_WALK_PREFETCH < P->nanchor) {
    ss_frames_prefetch(fr, P->anchor_face[a + SS_WALK_PREFETCH]);
  }
  double p[3];
  if (a < P->nv) {
    if (P->dof[a] < 0 || P->k_vert[a] == 0.0) return;
    memcpy(p, P->x + 3 * a, sizeof p);
  } else {
    int f = a - P->nv;
    if (P->k_face[f] == 0.0) return;
    const int *fv = P->faces + 3 * f;
    for (int i = 0; i < 3; i++)
      p[i] = (P->x[3 * fv[0] + i] + P->x[3 * fv[1] + i] + P->x[3 * fv[2] + i]) * SS_THIRD;
  }
  const int face = P->anchor_face[a];
  if (face < 0) return;
  const double slide = P->slide;
  const int home = P->anchor_face0[a];
  const double *a0 = P->anchor_pos + 3 * a;
  double *uv = P->anchor_uv + 2 * a;
  double target[3];
  ss_walk_result res = {0};
  res.face = face;
  res.uv[0] = uv[0];
  res.uv[1] = uv[1];
  const int slides = leashed || slide > 0.0, tethered = leashed || P->tether > 0.0;
  int moved = slides; /* glued (slide 0) and at home: not moved */
  if (slides) {
    for (int i = 0; i < 3; i++) target[i] = a0[i] + slide * (p[i] - a0[i]);
    if (walks && tethered && face == home && /* face >= 0 here */
        ss_slide_in_face_inline(fr, home, uv, target, measure, &res)) {
      /* On the leash, in its home face and sliding to a point within its
       * reach: the home face's point nearest the target (most anchors, most
       * of the time). Walked out onto a neighbour, the tether below would
       * put it back there every substep (the home stretch): an anchor at
       * the edge of its home face would cross the edge and be put back on
       * it again each substep, and many anchors sit there. The walk's alone:
       * projection and n-ring jump where they jump (their snags are what
       * they are compared for). */
    } else {
      if (walks) /* the walk itself, not through the mover */
        walk_anchor(P, walker, face, uv, target, &res);
      else if (walker)
        ss_mover_walk_with(P->sim->mover, walker, face, uv, target, &res);
      else
        ss_mover_move(P->sim->mover, face, uv, target, &res);
      c->steps += res.steps;
      c->boundary += res.stop == SS_STOP_BOUNDARY;
      c->crease += res.stop == SS_STOP_CREASE;
      c->step_limit += res.stop == SS_STOP_STEP_LIMIT;
    }
    if (measure) {
      double pull2 = 0.0;
      for (int i = 0; i < 3; i++) pull2 += (target[i] - a0[i]) * (target[i] - a0[i]);
      P->sim->anchor_pull[a] += sqrt(pull2);
      P->sim->anchor_path[a] += res.length;
    }
  }
  if (tethered && res.face == home) {
    /* The tether of an anchor in its home face (most anchors, most of the
     * time): tether_frac of the way home in the face's own (u, v), which is
     * affine in space. It is the step of tether_from_afar in exact
     * arithmetic (the chord lies in the face's plane, so turning it into the
     * tangent plane keeps it; the target lies inside the face, so it is its
     * own closest point), without two positions, the normal, two square
     * roots and a closest-point search. */
    const double *uv0 = P->anchor_uv0 + 2 * a;
    const double du = P->tether * (uv0[0] - res.uv[0]);
    const double dv = P->tether * (uv0[1] - res.uv[1]);
    if (du != 0.0 || dv != 0.0) {
      if (measure) {
        const double *e = ss_frames_edges(fr, res.face);
        const double x = du * e[0] + dv * e[3], y = du * e[1] + dv * e[4], z = du * e[2] + dv * e[5];
        P->sim->anchor_pull[a] += sqrt(x * x + y * y + z * z);
      }
      res.uv[0] += du;
      res.uv[1] += dv;
      moved = 1;
    }
  } else if (tethered && home >= 0) {
    moved |= tether_from_afar(P, a, walker, &res, c);
  }
  P->anchor_face[a] = res.face;
  uv[0] = res.uv[0];
  uv[1] = res.uv[1];
  c->moved += moved;
}

/* Anchors [a0, a1) with walker (NULL: one thread), in each instruction set
 * (isa.h): the pass's arithmetic is the leash's slide for most anchors. */
SS_ISA_VARIANTS(anchor_range, (const anchor_pass *P, int a0, int a1, ss_walker *walker, anchor_counts *c),
                const anchor_pass Q = *P; /* a value, never addressed in the loop */
                /* The usual pass (the walk on a leash, not measured) with those four
                 * facts as constants: a copy of the loop without their branches (the
                 * free walk has none: the walk itself is its time). */
                if (Q.walks && !Q.measure && Q.slide > 0.0 && Q.tether > 0.0)
                  for (int a = a0; a < a1; a++) move_anchor(&Q, a, walker, c, 1, 0, 1);
                else
                  for (int a = a0; a < a1; a++) move_anchor(&Q, a, walker, c, Q.walks, Q.measure, 0);)

/* Moves the anchors of free points (vertices, barycenters with a spring)
 * towards the skin points they hold. Each anchor's move is independent of
 * the others', so with threads the walks (and projections) share the
 * anchors, each thread with its own walker: the same bits whatever the
 * thread count. */
void ss_sim_move_anchors(ss_sim *sim, const ss_substep *in, ss_sim_stats *st) {
  if (in->slide_frac <= 0.0 && in->tether_frac <= 0.0) return;
  const anchor_pass P = anchor_pass_of(sim, in);
  const int nanchor = P.nanchor, isa = sim->isa;
  anchor_counts c = {0, 0, 0, 0, 0};
#ifdef _OPENMP
  if (sim->nthread > 1 && ss_mover_method(sim->mover) != SS_METHOD_NRING) {
    long long moved = 0, steps = 0, boundary = 0, crease = 0, step_limit = 0;
    /* in chunks taken as threads free up: anchors differ in cost (a walk
     * across faces, the tether's way home), so equal halves finished apart */
    enum { CHUNK = 1024 };
    const int nchunk = (nanchor + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(dynamic, 1) num_threads(sim->nthread) \
    reduction(+ : moved, steps, boundary, crease, step_limit)
    for (int k = 0; k < nchunk; k++) {
      anchor_counts ct = {0, 0, 0, 0, 0};
      const int a1 = (k + 1) * CHUNK < nanchor ? (k + 1) * CHUNK : nanchor;
      SS_ISA_CALL(isa, anchor_range, (&P, k * CHUNK, a1, P.sim->walkers[omp_get_thread_num()], &ct));
      moved += ct.moved, steps += ct.steps, boundary += ct.boundary;
      crease += ct.crease, step_limit += ct.step_limit;
    }
    c.moved = moved, c.steps = steps, c.boundary = boundary;
    c.crease = crease, c.step_limit = step_limit;
  } else
#endif
  {
    SS_ISA_CALL(isa, anchor_range, (&P, 0, nanchor, NULL, &c));
  }
  st->anchors_moved += (int)c.moved;
  st->walk_steps += (int)c.steps;
  st->anchors_boundary += (int)c.boundary;
  st->anchors_crease += (int)c.crease;
  st->anchors_step_limit += (int)c.step_limit;
}

