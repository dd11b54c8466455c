/* ss_sim: the dynamic skin of the paper (Kautzman, Cameron, Kim 2018,
 * sections 1 and 3; doc/model.md, "The skin model"). One step, read top to
 * bottom: ss_sim_step, then its four stages in the order they run.
 *
 * A step of length dt runs `substeps` substeps of h = dt / substeps, each the
 * stages below in order, on the sim's data and one const ss_substep (its
 * pose, h and the anchors' fractions of the way), the model read only:
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
 *               one relaxation), then the mover carries (face, u, v) over the
 *               body to a* (walk / project / nring), and the tether walks it
 *               towards home (sim_anchor.c).
 * A solve that meets a non-finite value keeps the last finite state and is
 * counted in the statistics; nothing non-finite ever enters the state.
 * Create, destroy and the model / data split: sim_model.c; the thread count
 * of the next step: sim_threads.c. */
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
#include "skin_sim/ss_settings.h"

/* What a substep's solve leaves for the stages after it. */
typedef struct substep_result {
  int status; /* the solver's: SS_OK or SS_E_SOLVER (ends the step after the guard) */
  int converged, stalled, nonfinite;
} substep_result;

static void stage_pose(ss_sim *sim, const ss_substep *in, ss_sim_stats *st);
static void stage_solve(ss_sim *sim, const ss_substep *in, ss_sim_stats *st, substep_result *out);
static void stage_guard(ss_sim *sim, const ss_substep *in, ss_sim_stats *st, substep_result *out);
static void stage_anchors(ss_sim *sim, const ss_substep *in, ss_sim_stats *st);
static int check_pose(ss_sim *sim, const double *body_pos, double dt, char *err, int err_sz);
static void area_ratios(const ss_sim *sim, ss_sim_stats *st);
static void warn(ss_sim *sim, ss_warning_kind kind, long long step, int info);

int ss_sim_step(ss_sim *sim, const double *body_pos, double dt, ss_sim_stats *stats, char *err,
                int err_sz) {
  ss_sim_stats local;
  ss_sim_stats *st = stats ? stats : &local;
  memset(st, 0, sizeof *st);
  if (!sim || !body_pos) return ss_fail(err, err_sz, SS_E_ARG, "sim or body positions are NULL");
  if (dt <= 0.0) dt = sim->set.dt;
  int status = check_pose(sim, body_pos, dt, err, err_sz);
  if (status != SS_OK) return status;
  double t_start = ss_now_ms();
  if (sim->measure_anchors) ss_sim_clear_anchor_measures(sim);
  /* a skin whose every vertex follows the body (a rigid robot's, carried) has
   * nothing between the poses to resolve: one substep */
  const int substeps = sim->m->ndof > 0 ? sim->set.substeps : 1;
  const double h = dt / substeps;
  st->converged = 1;
  for (int s = 1; s <= substeps && status == SS_OK; s++) {
    st->substeps++;
    const ss_substep in = {
        .body_pos = body_pos,
        .w = (double)s / substeps,
        .first = s == 1,
        .last = s == substeps,
        .h = h,
        .slide_frac = sim->set.slide > 0.0 ? -expm1(-sim->set.slide * h) : 0.0,
        .tether_frac = sim->set.tether > 0.0 ? -expm1(-sim->set.tether * h) : 0.0,
    };
    substep_result out = {SS_OK, 1, 0, 0};
    stage_pose(sim, &in, st);
    stage_solve(sim, &in, st, &out);
    stage_guard(sim, &in, st, &out);
    if (out.status == SS_OK) stage_anchors(sim, &in, st);
    status = out.status;
  }
  memcpy(sim->body_prev, body_pos, 3 * (size_t)sim->m->nbvert * sizeof(double));
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
  if (status != SS_OK)
    return ss_fail(err, err_sz, status, "the linear solver failed (CHOLMOD status %d); last good state kept",
                   sim->cc.status);
  return SS_OK;
}

/* ---- 1. pose ---- */

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

static void stage_pose(ss_sim *sim, const ss_substep *in, ss_sim_stats *st) {
  const size_t nv3 = 3 * (size_t)sim->m->nvert, nb3 = 3 * (size_t)sim->m->nbvert;
  const double *body_pos = in->body_pos;
  const double w = in->w;
  for (size_t i = 0; i < nb3; i++) sim->body_sub[i] = sim->body_prev[i] + w * (body_pos[i] - sim->body_prev[i]);
  if (in->last) memcpy(sim->body_sub, body_pos, nb3 * sizeof(double));
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
  ss_sim_anchor_positions_update(sim, sim->body_sub);
  st->pose_ms += ss_now_ms() - t0;
  memcpy(sim->x_prev, sim->x, nv3 * sizeof(double));
  const ss_frames *fr = ss_mover_frames(sim->mover);
  for (int v = 0; v < sim->m->nvert; v++)
    if (sim->m->dof[v] < 0) follow(sim, fr, v);
  memcpy(sim->xfull_t, sim->x, nv3 * sizeof(double));
}

/* ---- 2. solve ----
 * Starts from the skin carried along by its anchors (fewer iterations than
 * the inertial prediction x + h v when the body leads: about 40% fewer on
 * twist and boundary, 60% on armpit; ~5% more on fold). */
static void stage_solve(ss_sim *sim, const ss_substep *in, ss_sim_stats *st, substep_result *out) {
  if (sim->m->ndof == 0) return;
  const double t0 = ss_now_ms();
  ss_sim_energy_begin(sim, in->h);
  st->orient_ms += ss_now_ms() - t0;
  for (int k = 0; k < sim->m->ndof; k++) {
    int v = sim->m->dof_vert[k];
    for (int i = 0; i < 3; i++)
      sim->xd[3 * k + i] = sim->x_prev[3 * v + i] + (sim->anchor_pos[3 * v + i] - sim->guess[3 * k + i]);
  }
  out->status = ss_solver_solve(sim, in, st, sim->xd, &out->converged, &out->stalled, &out->nonfinite);
}

/* ---- 3. guard ---- */

static int all_finite(const double *a, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(a[i])) return 0;
  return 1;
}

static void stage_guard(ss_sim *sim, const ss_substep *in, ss_sim_stats *st, substep_result *out) {
  if (sim->m->ndof > 0) {
    if (out->status != SS_OK || out->nonfinite == 1 || !all_finite(sim->xd, 3 * (size_t)sim->m->ndof)) {
      /* Keep the last good state of the free vertices, at rest. */
      for (int k = 0; k < sim->m->ndof; k++) {
        int v = sim->m->dof_vert[k];
        memcpy(sim->xd + 3 * k, sim->x_prev + 3 * v, 3 * sizeof(double));
        memset(sim->v + 3 * v, 0, 3 * sizeof(double));
      }
      if (out->status == SS_OK) out->nonfinite = 1;
      out->converged = 0;
    }
    ss_sim_scatter(sim, sim->xd, sim->x);
  }
  st->converged &= out->converged;
  st->stalled += out->stalled;
  st->failures += out->nonfinite != 0;
  /* velocities, never Inf in the state (only reachable after ss_sim_set_state) */
  const size_t nv3 = 3 * (size_t)sim->m->nvert;
  int v_overflow = 0;
  for (size_t i = 0; i < nv3; i++) {
    sim->v[i] = (sim->x[i] - sim->x_prev[i]) / in->h;
    if (!isfinite(sim->v[i])) sim->v[i] = 0.0, v_overflow = 1;
  }
  st->failures += v_overflow;
  /* contact: the skin out of the clean body, its velocity into it dropped */
  if (sim->set.collide && in->last && sim->m->ndof > 0 && out->nonfinite == 0) ss_sim_collide(sim);
}

/* ---- 4. anchors (sim_anchor.c) ---- */

static void stage_anchors(ss_sim *sim, const ss_substep *in, ss_sim_stats *st) {
  double t0 = ss_now_ms();
  ss_sim_move_anchors(sim, in, st);
  st->walk_ms += ss_now_ms() - t0;
}

/* ---- around the step ---- */

/* The pose is refused before anything of the state changes: a non-finite
 * coordinate, or a move whose velocity would overflow. */
static int check_pose(ss_sim *sim, const double *body_pos, double dt, char *err, int err_sz) {
  if (!isfinite(dt)) return ss_fail(err, err_sz, SS_E_ARG, "dt is not finite");
  for (int v = 0; v < sim->m->nbvert; v++)
    for (int i = 0; i < 3; i++)
      if (!isfinite(body_pos[3 * v + i])) {
        warn(sim, SS_WARN_REFUSED, sim->nstep + 1, v);
        return ss_fail(err, err_sz, SS_E_NONFINITE, "body vertex %d has a non-finite coordinate", v);
      }
  /* Vertices that follow the body take its velocity (a convex combination
   * of vertex moves / h). */
  const double h_sub = dt / sim->set.substeps, lim = 0.25 * DBL_MAX * h_sub;
  for (size_t i = 0; i < 3 * (size_t)sim->m->nbvert; i++)
    if (!isfinite(body_pos[i] - sim->body_prev[i]) || !(fabs(body_pos[i] - sim->body_prev[i]) <= lim)) {
      warn(sim, SS_WARN_REFUSED, sim->nstep + 1, (int)(i / 3));
      return ss_fail(err, err_sz, SS_E_NONFINITE,
                     "body vertex %d moves %g in %g s: its velocity overflows; step refused",
                     (int)(i / 3), body_pos[i] - sim->body_prev[i], dt);
    }
  return SS_OK;
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

static void warn(ss_sim *sim, ss_warning_kind kind, long long step, int info) {
  ss_warning *w = sim->warning + kind;
  w->number++;
  w->last_step = step;
  w->last_info = info;
}

/* ---- state and settings ---- */

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
    ss_sim_anchor_positions_update(sim, sim->m->body_rest);
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
  /* contact turned on: its scratch made now, not while stepping */
  if (settings->collide && ss_sim_collider_ensure(sim) != SS_OK)
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for contact");
  int n = 0, refactor = 0, material = 0;
  const ss_setting *table = ss_settings_table(&n);
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
    material |= d->scope == SS_SCOPE_MODEL;
  }
  /* The model is a value: a new material is a new model (on the old one's
   * structure), this sim's alone; other sims on the old model keep it. */
  if (material) {
    status = ss_sim_rematerial(sim, settings, err, err_sz);
    if (status != SS_OK) return status;
  }
  const unsigned char *mask = sim->m->mask;
  sim->set = *settings;
  sim->set.face_mask = mask; /* the region stays */
  if (refactor) {
    sim->a_h = 0.0;       /* quasi-Newton: factor A again on the next substep */
    sim->h_const_h = 0.0; /* Newton: rebuild the constant Hessian */
  }
  return SS_OK;
}

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
  if (on && !sim->measure_anchors) ss_sim_clear_anchor_measures(sim); /* zeros, not what an earlier step left */
  sim->measure_anchors = on != 0;
}
const ss_topo *ss_sim_body_topo(const ss_sim *sim) { return sim->m->btopo; }

void ss_sim_anchor_positions(const ss_sim *sim, double *out) {
  memcpy(out, sim->anchor_pos, 3 * (size_t)sim->m->nanchor * sizeof(double));
}
