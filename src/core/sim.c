/* ss_sim: the dynamic skin of the paper (Kautzman, Cameron, Kim 2018,
 * sections 1 and 3; doc/model.md, "The skin model").
 *
 * A step of length dt runs `substeps` substeps of h = dt / substeps, each the
 * stages below in order (ss_stage, the `stages` table before ss_sim_step):
 *   1. pose     the body at the linearly interpolated pose; per-face frames
 *               (and BVH) updated once through the mover; anchor positions;
 *               vertices outside the simulated region put on their anchors;
 *   2. solve    implicit Euler as minimisation (sim_energy.c), starting from
 *               the skin carried along by its anchors, by Newton or L-BFGS
 *               directions in one loop (solver.c);
 *   3. guard    a solve that met a non-finite value keeps the last finite
 *               state; velocities v = (x - x_n) / h;
 *   4. anchors  the spring force drags each anchor of a free point towards the
 *               skin point it holds: a* = a0 + (1 - exp(-slide h)) (p - a0)
 *               (slide a rate per second, so any substep count converges to
 *               one relaxation), then the mover
 *               carries (face, u, v) over the body to a* (walk / project /
 *               nring, mover.h).
 * A solve that meets a non-finite value keeps the last finite state and is
 * counted in the statistics; nothing non-finite ever enters the state.
 * Create, destroy and the model / data split: sim_model.c. */
#include <float.h>
#include <stddef.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "collide.h"
#include "sim_internal.h"
#include "ss_err.h"
#include "ss_vec.h"
#include "closest.h" /* the tether's home stretch */
#include "isa.h"
#include "walk_step.h"
#include "skin_sim/ss_settings.h"

static const char *const solver_names[] = {"newton", "quasi-newton"};

const char *ss_solver_name(int solver) {
  if (solver < 0 || solver > SS_SOLVER_QUASI_NEWTON) return NULL;
  return solver_names[solver];
}

int ss_solver_parse(const char *name) {
  if (!name) return -1;
  for (int i = 0; i <= SS_SOLVER_QUASI_NEWTON; i++)
    if (strcmp(name, solver_names[i]) == 0) return i;
  return -1;
}

/* Anchor positions in the body pose `pose`, which the mover holds. An anchor
 * without a face (a vertex in no face of a skin copied from the body) follows
 * its body vertex. */
static inline void anchor_position(ss_sim *sim, const ss_frames *fr, const double *pose, int a) {
  if (sim->anchor_face[a] >= 0)
    ss_anchor_position(fr, sim->anchor_face[a], sim->anchor_uv + 2 * a, sim->anchor_pos + 3 * a);
  else if (a < sim->m->nvert)
    memcpy(sim->anchor_pos + 3 * a, pose + 3 * a, 3 * sizeof(double));
}

static void update_anchor_positions(ss_sim *sim, const double *pose) {
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

void ss_sim_reset(ss_sim *sim) {
  if (!sim) return;
  size_t nv3 = 3 * (size_t)sim->m->nvert;
  memcpy(sim->x, sim->m->rest, nv3 * sizeof(double));
  memcpy(sim->x_prev, sim->m->rest, nv3 * sizeof(double));
  memcpy(sim->xfull_t, sim->m->rest, nv3 * sizeof(double));
  memset(sim->v, 0, nv3 * sizeof(double));
  memcpy(sim->anchor_face, sim->m->anchor_face0, (size_t)sim->m->nanchor * sizeof(int));
  memcpy(sim->anchor_uv, sim->m->anchor_uv0, 2 * (size_t)sim->m->nanchor * sizeof(double));
  memcpy(sim->body_prev, sim->m->body_rest, 3 * (size_t)sim->m->nbvert * sizeof(double));
  if (sim->mover) {
    ss_mover_set_pose(sim->mover, sim->m->body_rest);
    update_anchor_positions(sim, sim->m->body_rest);
  }
}

int ss_sim_set_state(ss_sim *sim, const double *pos, const double *vel, char *err, int err_sz) {
  if (!sim || !pos) return ss_fail(err, err_sz, SS_E_ARG, "sim or positions are NULL");
  size_t nv3 = 3 * (size_t)sim->m->nvert;
  for (size_t i = 0; i < nv3; i++)
    if (!isfinite(pos[i]) || (vel && !isfinite(vel[i])))
      return ss_fail(err, err_sz, SS_E_NONFINITE, "skin vertex %d has a non-finite %s", (int)(i / 3),
                     isfinite(pos[i]) ? "velocity" : "position");
  memcpy(sim->x, pos, nv3 * sizeof(double));
  if (vel)
    memcpy(sim->v, vel, nv3 * sizeof(double));
  else
    memset(sim->v, 0, nv3 * sizeof(double));
  return SS_OK;
}

int ss_sim_set_settings(ss_sim *sim, const ss_sim_settings *settings, int *recreate, char *err,
                        int err_sz) {
  if (recreate) *recreate = 0;
  if (!sim || !settings) return ss_fail(err, err_sz, SS_E_ARG, "sim or settings are NULL");
  int status = ss_settings_check(settings, err, err_sz);
  if (status != SS_OK) return status;
  int n = 0, refactor = 0;
  const ss_setting *table = ss_settings_table(&n), *material = NULL;
  for (int i = 0; i < n; i++) {
    const ss_setting *d = &table[i];
    if (ss_setting_equal(d, &sim->set, settings)) continue;
    const int on_off = d->offset == offsetof(ss_sim_settings, bending) &&
                       (sim->set.bending > 0.0) != (settings->bending > 0.0);
    if (d->apply == SS_APPLY_RECREATE || on_off) {
      if (recreate) *recreate = 1;
      return ss_fail(err, err_sz, SS_OK, "%s %s: the simulation must be created again", d->name,
                     on_off ? "turned on or off" : "changed");
    }
    refactor |= d->apply == SS_APPLY_REFACTOR;
    if (!material && ss_sim_in_model(d->offset)) material = d;
  }
  /* A model shared with other sims is never written: the change is refused
   * (created again on a model of its own), not copied. */
  if (material && sim->m->refs > 1) {
    if (recreate) *recreate = 1;
    return ss_fail(err, err_sz, SS_OK,
                   "%s changed on a model shared by %d sims and references: the simulation must be "
                   "created again",
                   material->name, sim->m->refs);
  }
  const double old_bending = sim->set.bending;
  const unsigned char *mask = sim->set.face_mask;
  sim->set = *settings;
  sim->set.face_mask = mask; /* the region stays */
  if (material) {
    sim->m->set = sim->set;
    ss_sim_build_material(sim);
    ss_sim_energy_springs(sim); /* k_face into the membrane records */
    if (old_bending > 0.0 && sim->set.bending != old_bending)
      for (int e = 0; e < sim->m->nhinge; e++)
        sim->m->hinge_weight[e] = sim->m->hinge_weight[e] / old_bending * sim->set.bending;
    ss_sim_diag_const(sim);
  }
  if (refactor) {
    sim->a_h = 0.0;       /* quasi-Newton: factor A again on the next substep */
    sim->h_const_h = 0.0; /* Newton: rebuild the constant Hessian */
  }
  return SS_OK;
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

/* Each anchor's pull and path back to 0 (ss_sim_measure_anchors). */
static void clear_anchor_measures(ss_sim *sim) {
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

static anchor_pass anchor_pass_of(ss_sim *sim) {
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
      .slide = sim->slide_frac,
      .tether = sim->tether_frac,
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
static void move_anchors(ss_sim *sim, ss_sim_stats *st) {
  if (sim->slide_frac <= 0.0 && sim->tether_frac <= 0.0) return;
  const anchor_pass P = anchor_pass_of(sim);
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

static void area_ratios(const ss_sim *sim, ss_sim_stats *st) {
  double lo = INFINITY, hi = 0.0;
  for (int q = 0; q < sim->m->nsimface; q++) {
    int f = sim->m->simface[q];
    const int *fv = sim->m->faces + 3 * f;
    const double *x = sim->x;
    double r = 0.5 * sqrt(tri_cross2(x + 3 * fv[0], x + 3 * fv[1], x + 3 * fv[2])) / sim->m->rest_area[f];
    lo = min_keep(lo, r);
    hi = max_keep(hi, r);
  }
  st->min_area_ratio = sim->m->nsimface ? lo : 1.0;
  st->max_area_ratio = sim->m->nsimface ? hi : 1.0;
}

static int all_finite(const double *a, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(a[i])) return 0;
  return 1;
}

/* threads 0: whether all cores pay is measured, not guessed (on a machine
 * whose cores are busy, every barrier waits for a descheduled thread and two
 * threads can be several times slower than one). Each probe period starts
 * with SS_PROBE_STEPS steps on one thread, then up to SS_PROBE_STEPS on all;
 * the rest of the period uses the faster (sum of wall-clock step times).
 * One thread goes first and the all-threads steps stop as soon as their sum
 * passes the one-thread steps': beside a CPU hog a step on two threads can
 * take hundreds of times as long as on one, and several of them in a row
 * would leave a node seconds behind.
 * Each probe that one thread wins doubles the period (up to
 * SS_PROBE_PERIOD_MAX steps), so that a busy machine is not asked again
 * every 50 steps; one that all threads win sets it back. The bits do not
 * depend on the thread count, so switching changes no result. */
void ss_sim_choose_threads(ss_sim *sim, double step_ms) {
  int p = sim->thread_probe;
  if (p < 0) return;
  const int n = SS_PROBE_STEPS;
  if (p < n)
    sim->probe_ms[1] += step_ms; /* this step ran on one thread */
  else if (p < 2 * n)
    sim->probe_ms[0] += step_ms; /* on all */
  p++;
  if (p < n) {
    sim->nthread = 1;
  } else if (p < 2 * n) {
    if (p > n && sim->probe_ms[0] > sim->probe_ms[1]) p = 2 * n; /* lost already: decide now */
    else sim->nthread = sim->nthread_max;
  }
  if (p == 2 * n) {
    const int all = !(sim->probe_ms[0] > sim->probe_ms[1]);
    sim->nthread = all ? sim->nthread_max : 1;
    sim->probe_period = all ? SS_PROBE_PERIOD
                            : (2 * sim->probe_period < SS_PROBE_PERIOD_MAX ? 2 * sim->probe_period
                                                                           : SS_PROBE_PERIOD_MAX);
  }
  if (p >= sim->probe_period) { /* a new probe: one thread first */
    p = 0;
    sim->probe_ms[0] = sim->probe_ms[1] = 0.0;
    sim->nthread = 1;
  }
  sim->thread_probe = p;
}

/* ---- the stages of a substep, run in this order (as Box2D's solver.h lists
 * the stages of its step): see the head of this file. Each works on the
 * data of the sim and the substep's record; a solve that fails is kept by
 * the guard, and ends the step after it. */
typedef enum ss_stage {
  SS_STAGE_POSE,    /* body pose of the substep, frames, anchor positions */
  SS_STAGE_SOLVE,   /* implicit Euler as minimisation */
  SS_STAGE_GUARD,   /* nothing non-finite enters the state; velocities */
  SS_STAGE_ANCHORS, /* anchors slide towards the skin (and walk home) */
  SS_STAGE_COUNT
} ss_stage;

typedef struct substep {
  const double *body_pos; /* the pose at the end of the step */
  double w;               /* share of the way from body_prev to body_pos */
  int last;               /* the last substep: exactly body_pos */
  double h;               /* its length */
  int status;             /* the solver's: SS_OK or SS_E_SOLVER */
  int converged, stalled, nonfinite;
} substep;

static void warn(ss_sim *sim, ss_warning_kind kind, long long step, int info) {
  ss_warning *w = sim->warning + kind;
  w->number++;
  w->last_step = step;
  w->last_info = info;
}

/* Where free vertex k's anchor was in the previous pose (fr_prev). */
static inline void guess_position(ss_sim *sim, const ss_frames *fr_prev, int k) {
  const int v = sim->m->dof_vert[k];
  if (sim->anchor_face[v] >= 0)
    ss_anchor_position(fr_prev, sim->anchor_face[v], sim->anchor_uv + 2 * v, sim->guess + 3 * k);
  else
    memcpy(sim->guess + 3 * k, sim->anchor_pos + 3 * v, 3 * sizeof(double));
}

/* A vertex that follows the body: on its anchor, or for a separate skin at
 * its rest offset from it in the anchor face's frame (carried rigidly with
 * the face, so a rigid piece over a rigid link moves exactly with it). */
static inline void follow(ss_sim *sim, const ss_frames *fr, int v) {
  double *x = sim->x + 3 * v;
  const double *a = sim->anchor_pos + 3 * v;
  const int f = sim->anchor_face[v];
  double t1[3], t2[3], n[3];
  if (sim->m->follow_offset && f >= 0 &&
      ss_sim_face_frame(ss_frames_edges(fr, f), ss_frames_edges(fr, f) + 3, t1, t2, n)) {
    const double *o = sim->m->follow_off + 3 * v;
    for (int i = 0; i < 3; i++) x[i] = a[i] + o[0] * t1[i] + o[1] * t2[i] + o[2] * n[i];
    return;
  }
  memcpy(x, a, 3 * sizeof(double));
}

static void stage_pose(ss_sim *sim, substep *sub) {
  ss_sim_stats *st = sim->st;
  const size_t nv3 = 3 * (size_t)sim->m->nvert, nb3 = 3 * (size_t)sim->m->nbvert;
  const double *body_pos = sub->body_pos;
  const double w = sub->w;
  for (size_t i = 0; i < nb3; i++) sim->body_sub[i] = sim->body_prev[i] + w * (body_pos[i] - sim->body_prev[i]);
  if (sub->last) memcpy(sim->body_sub, body_pos, nb3 * sizeof(double));
  double t0 = ss_now_ms();
  /* Where the free vertices' anchors were in the previous pose: the start
   * of the solve moves each vertex along with its anchor. */
  const ss_frames *fr_prev = ss_mover_frames(sim->mover);
  const int ndof = sim->m->ndof;
#ifdef _OPENMP
  if (sim->nthread > 1) {
#pragma omp parallel for schedule(static) num_threads(sim->nthread)
    for (int k = 0; k < ndof; k++) guess_position(sim, fr_prev, k);
  } else
#endif
  {
    for (int k = 0; k < ndof; k++) guess_position(sim, fr_prev, k);
  }
  ss_mover_set_pose_threads(sim->mover, sim->body_sub, sim->nthread);
  update_anchor_positions(sim, sim->body_sub);
  st->pose_ms += ss_now_ms() - t0;
  memcpy(sim->x_prev, sim->x, nv3 * sizeof(double));
  const ss_frames *fr = ss_mover_frames(sim->mover);
  for (int v = 0; v < sim->m->nvert; v++)
    if (sim->m->dof[v] < 0) follow(sim, fr, v);
  memcpy(sim->xfull_t, sim->x, nv3 * sizeof(double));
}

/* Starts from the skin carried along by its anchors (fewer iterations than
 * the inertial prediction x + h v when the body leads: about 40% fewer on
 * twist and boundary, 60% on armpit; ~5% more on fold). */
static void stage_solve(ss_sim *sim, substep *sub) {
  if (sim->m->ndof == 0) return;
  ss_sim_energy_begin(sim, sub->h);
  for (int k = 0; k < sim->m->ndof; k++) {
    int v = sim->m->dof_vert[k];
    for (int i = 0; i < 3; i++)
      sim->xd[3 * k + i] = sim->x_prev[3 * v + i] + (sim->anchor_pos[3 * v + i] - sim->guess[3 * k + i]);
  }
  sub->status = ss_solver_solve(sim, sim->xd, &sub->converged, &sub->stalled, &sub->nonfinite);
}

static void stage_guard(ss_sim *sim, substep *sub) {
  ss_sim_stats *st = sim->st;
  if (sim->m->ndof > 0) {
    if (sub->status != SS_OK || sub->nonfinite == 1 || !all_finite(sim->xd, 3 * (size_t)sim->m->ndof)) {
      /* Keep the last good state of the free vertices, at rest. */
      for (int k = 0; k < sim->m->ndof; k++) {
        int v = sim->m->dof_vert[k];
        memcpy(sim->xd + 3 * k, sim->x_prev + 3 * v, 3 * sizeof(double));
        memset(sim->v + 3 * v, 0, 3 * sizeof(double));
      }
      if (sub->status == SS_OK) sub->nonfinite = 1;
      sub->converged = 0;
    }
    ss_sim_scatter(sim, sim->xd, sim->x);
    /* contact: the skin back out of the body before its velocity is taken */
    if (sim->set.collide && sub->last && sub->nonfinite == 0) ss_sim_collide(sim);
  }
  st->converged &= sub->converged;
  st->stalled += sub->stalled;
  st->failures += sub->nonfinite != 0;
  /* velocities, never Inf in the state (only reachable after ss_sim_set_state) */
  const size_t nv3 = 3 * (size_t)sim->m->nvert;
  int v_overflow = 0;
  for (size_t i = 0; i < nv3; i++) {
    sim->v[i] = (sim->x[i] - sim->x_prev[i]) / sub->h;
    if (!isfinite(sim->v[i])) sim->v[i] = 0.0, v_overflow = 1;
  }
  st->failures += v_overflow;
}

static void stage_anchors(ss_sim *sim, substep *sub) {
  if (sub->status != SS_OK) return;
  /* the fractions of the way of this substep */
  const double h = sub->h;
  sim->slide_frac = sim->set.slide > 0.0 ? -expm1(-sim->set.slide * h) : 0.0;
  sim->tether_frac = sim->set.tether > 0.0 ? -expm1(-sim->set.tether * h) : 0.0;
  double t0 = ss_now_ms();
  move_anchors(sim, sim->st);
  sim->st->walk_ms += ss_now_ms() - t0;
}

static void (*const stages[SS_STAGE_COUNT])(ss_sim *, substep *) = {
    [SS_STAGE_POSE] = stage_pose,
    [SS_STAGE_SOLVE] = stage_solve,
    [SS_STAGE_GUARD] = stage_guard,
    [SS_STAGE_ANCHORS] = stage_anchors,
};

int ss_sim_step(ss_sim *sim, const double *body_pos, double dt, ss_sim_stats *stats, char *err,
                int err_sz) {
  ss_sim_stats local;
  ss_sim_stats *st = stats ? stats : &local;
  memset(st, 0, sizeof *st);
  if (!sim || !body_pos) return ss_fail(err, err_sz, SS_E_ARG, "sim or body positions are NULL");
  if (dt <= 0.0) dt = sim->set.dt;
  if (!isfinite(dt)) return ss_fail(err, err_sz, SS_E_ARG, "dt is not finite");
  for (int v = 0; v < sim->m->nbvert; v++)
    for (int i = 0; i < 3; i++)
      if (!isfinite(body_pos[3 * v + i])) {
        warn(sim, SS_WARN_REFUSED, sim->nstep + 1, v);
        return ss_fail(err, err_sz, SS_E_NONFINITE, "body vertex %d has a non-finite coordinate", v);
      }
  {
    /* Vertices that follow the body take its velocity (a convex combination
     * of vertex moves / h): refuse a move whose velocity would overflow,
     * before anything of the state changes. */
    const double h_sub = dt / sim->set.substeps, lim = 0.25 * DBL_MAX * h_sub;
    for (size_t i = 0; i < 3 * (size_t)sim->m->nbvert; i++)
      if (!isfinite(body_pos[i] - sim->body_prev[i]) || !(fabs(body_pos[i] - sim->body_prev[i]) <= lim)) {
        warn(sim, SS_WARN_REFUSED, sim->nstep + 1, (int)(i / 3));
        return ss_fail(err, err_sz, SS_E_NONFINITE,
                       "body vertex %d moves %g in %g s: its velocity overflows; step refused",
                       (int)(i / 3), body_pos[i] - sim->body_prev[i], dt);
      }
  }
  double t_start = ss_now_ms();
  sim->st = st;
  if (sim->measure_anchors) clear_anchor_measures(sim);
  /* a skin whose every vertex follows the body (a rigid robot's, carried) has
   * nothing between the poses to resolve: one substep */
  int substeps = sim->m->ndof > 0 ? sim->set.substeps : 1;
  double h = dt / substeps;
  const size_t nb3 = 3 * (size_t)sim->m->nbvert;
  int status = SS_OK;
  st->converged = 1;
  for (int s = 1; s <= substeps && status == SS_OK; s++) {
    st->substeps++;
    substep sub = {body_pos, (double)s / substeps, s == substeps, h, SS_OK, 1, 0, 0};
    for (int k = 0; k < SS_STAGE_COUNT; k++) stages[k](sim, &sub);
    status = sub.status;
  }
  memcpy(sim->body_prev, body_pos, nb3 * sizeof(double));
  area_ratios(sim, st);
  const long long n = ++sim->nstep;
  if (status != SS_OK) warn(sim, SS_WARN_SOLVER, n, sim->cc.status);
  if (st->failures) warn(sim, SS_WARN_FAILURE, n, st->failures);
  if (st->stalled) warn(sim, SS_WARN_STALLED, n, st->stalled);
  if (!st->converged) warn(sim, SS_WARN_UNCONVERGED, n, st->substeps);
  if (st->anchors_step_limit) warn(sim, SS_WARN_STEP_LIMIT, n, st->anchors_step_limit);
  st->total_ms = ss_now_ms() - t_start;
  st->threads = sim->nthread;
  ss_sim_choose_threads(sim, st->total_ms);
  sim->st = NULL;
  if (status != SS_OK)
    return ss_fail(err, err_sz, status, "the linear solver failed (CHOLMOD status %d); last good state kept",
                   sim->cc.status);
  return SS_OK;
}

/* ---- warnings ---- */
const ss_warning *ss_sim_warnings(const ss_sim *sim) { return sim->warning; }
long long ss_sim_step_count(const ss_sim *sim) { return sim->nstep; }
void ss_sim_clear_warnings(ss_sim *sim) {
  if (sim) memset(sim->warning, 0, sizeof sim->warning);
}
const char *ss_warning_name(int kind) {
  static const char *const names[SS_NWARNING] = {
      [SS_WARN_REFUSED] = "refused", [SS_WARN_FAILURE] = "failure",
      [SS_WARN_SOLVER] = "solver", [SS_WARN_STALLED] = "stalled",
      [SS_WARN_UNCONVERGED] = "unconverged", [SS_WARN_STEP_LIMIT] = "step_limit"};
  return kind >= 0 && kind < SS_NWARNING ? names[kind] : "unknown";
}

/* ---- accessors ---- */
const ss_sim_settings *ss_sim_get_settings(const ss_sim *sim) { return &sim->set; }
int ss_sim_skin_nvert(const ss_sim *sim) { return sim->m->nvert; }
int ss_sim_skin_nface(const ss_sim *sim) { return sim->m->nface; }
const int *ss_sim_skin_faces(const ss_sim *sim) { return sim->m->faces; }
const double *ss_sim_skin_rest(const ss_sim *sim) { return sim->m->rest; }
const double *ss_sim_skin_positions(const ss_sim *sim) { return sim->x; }
const double *ss_sim_skin_velocities(const ss_sim *sim) { return sim->v; }
int ss_sim_ndof(const ss_sim *sim) { return sim->m->ndof; }
int ss_sim_body_nvert(const ss_sim *sim) { return sim->m->nbvert; }
int ss_sim_body_nface(const ss_sim *sim) { return sim->m->nbface; }
int ss_sim_nanchors(const ss_sim *sim) { return sim->m->nanchor; }
const int *ss_sim_anchor_faces(const ss_sim *sim) { return sim->anchor_face; }
const double *ss_sim_anchor_uv(const ss_sim *sim) { return sim->anchor_uv; }
const double *ss_sim_anchor_pull(const ss_sim *sim) { return sim->measure_anchors ? sim->anchor_pull : NULL; }
const double *ss_sim_anchor_path(const ss_sim *sim) { return sim->measure_anchors ? sim->anchor_path : NULL; }
void ss_sim_measure_anchors(ss_sim *sim, int on) {
  if (!sim) return;
  if (on && !sim->measure_anchors) clear_anchor_measures(sim); /* zeros, not what an earlier step left */
  sim->measure_anchors = on != 0;
}
const ss_topo *ss_sim_body_topo(const ss_sim *sim) { return sim->m->btopo; }

void ss_sim_anchor_positions(const ss_sim *sim, double *out) {
  memcpy(out, sim->anchor_pos, 3 * (size_t)sim->m->nanchor * sizeof(double));
}
