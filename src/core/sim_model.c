/* ss_sim's model and data (sim_internal.h, "model and data"): their arenas,
 * create and destroy, and several sims on one model.
 *
 * ss_sim_create = model_new (counts, arena, inputs, body topology) +
 * model_build on the new sim (anchors bound, vertex kinds, masses, hinges,
 * pattern, energy layout, symbolic analysis, rest orientation) + the sim's data (mover, walkers,
 * arena, state at rest) + its solver. ss_sim_create_from_model skips the
 * model's two steps and takes a reference to it instead. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "collide.h"
#include "energy.h"
#include "isa.h"
#include "sim_internal.h"
#include "ss_err.h"
#include "ss_vec.h"
#include "skin_sim/ss_settings.h" /* ss_sim_default_settings() and every range check */

#ifdef _OPENMP
/* threads 0: every core the process may use, on a skin big enough for a
 * second thread to pay for its barriers (below SS_AUTO_THREADS_MIN_FACES
 * faces one thread was as fast), and only while they pay: see
 * choose_threads. */
#define SS_AUTO_THREADS_MIN_FACES 4000
static int auto_threads(int nface) {
  if (nface < SS_AUTO_THREADS_MIN_FACES) return 1;
  int n = omp_get_num_procs();
  return n < 1 ? 1 : n > 64 ? 64 : n;
}
#endif

#ifdef _OPENMP
/* Runs the kinds of parallel loops stepping uses, so that the OpenMP runtime
 * has made its team and work-share records before the first step: stepping
 * then allocates nothing. */
static void openmp_warm_up(int nthread) {
  if (nthread <= 1) return;
  for (int round = 0; round < 3; round++) {
    long long sum = 0;
#pragma omp parallel for schedule(static) num_threads(nthread) reduction(+ : sum)
    for (int i = 0; i < 64 * nthread; i++) sum += i;
    double sink[64];
#pragma omp parallel for schedule(static) num_threads(nthread)
    for (int i = 0; i < 64; i++) sink[i] = (double)(i + sum);
    __asm__ volatile("" : : "r"(sink) : "memory"); /* keep the stores */
  }
}
#endif

/* ---- arenas: the field lists of sim_internal.h laid out in one block ---- */

typedef struct arena_cursor {
  char *base; /* NULL: sizing pass */
  size_t off;
} arena_cursor;

/* The next count elements of size bytes, at a 64-byte boundary. */
static void *arena_take(arena_cursor *c, size_t count, size_t size) {
  c->off = (c->off + 63) & ~(size_t)63;
  void *p = c->base ? c->base + c->off : NULL;
  c->off += count * size;
  return p;
}

#define SS_ARENA_PLACE(name, type, count, shape) owner->name = arena_take(&c, (count), sizeof(type));

/* Allocates the zeroed arena *arena for the fields placed by `place` (the
 * list run twice: sizes, then places). */
#define SS_ARENA_ALLOC(arena, bytes, place)                           \
  do {                                                                \
    arena_cursor c = {NULL, 0};                                       \
    place;                                                            \
    const size_t size = c.off ? (c.off + 63) & ~(size_t)63 : 64;      \
    c.base = aligned_alloc(64, size);                                 \
    if (!c.base) return SS_E_NOMEM;                                   \
    memset(c.base, 0, size);                                          \
    c.off = 0;                                                        \
    place;                                                            \
    (arena) = c.base;                                                 \
    (bytes) = size;                                                   \
  } while (0)

static int model_arena(ss_model *m) {
  ss_model *owner = m;
  SS_ARENA_ALLOC(m->arena, m->arena_bytes, SS_MODEL_ARRAYS(SS_ARENA_PLACE));
  return SS_OK;
}

static int data_arena(ss_sim *sim) {
  const ss_model *m = sim->m;
  ss_sim *owner = sim;
  SS_ARENA_ALLOC(sim->arena, sim->arena_bytes, SS_DATA_ARRAYS(SS_ARENA_PLACE));
  return SS_OK;
}

/* ---- model ---- */

int ss_sim_in_model(size_t offset) {
  static const size_t model_settings[] = {
      offsetof(ss_sim_settings, young),   offsetof(ss_sim_settings, poisson),
      offsetof(ss_sim_settings, density), offsetof(ss_sim_settings, anchor_stiffness),
      offsetof(ss_sim_settings, bending), offsetof(ss_sim_settings, barycenter_anchors),
      offsetof(ss_sim_settings, orient),  offsetof(ss_sim_settings, compression)};
  for (size_t i = 0; i < sizeof model_settings / sizeof model_settings[0]; i++)
    if (model_settings[i] == offset) return 1;
  return 0;
}

static void model_release(ss_model *m) {
  if (!m || --m->refs > 0) return;
  if (m->cc_started) {
    cholmod_free_factor(&m->sym_qn, &m->cc);
    cholmod_free_factor(&m->sym_newton, &m->cc);
    cholmod_finish(&m->cc);
  }
  ss_bvh_destroy(m->bvh_rest);
  ss_topo_destroy(m->btopo);
  free(m->arena);
  free(m);
}

void ss_model_destroy(ss_model *model) { model_release(model); }

/* The model's counts, arena, inputs and body topology (the rest is built by
 * model_build on a sim). */
static int model_new(ss_model **out, int body_nvert, const double *body_rest, int body_nface,
                     const int *body_faces, const ss_sim_mesh *skin, const ss_sim_settings *set,
                     char *err, int err_sz) {
  ss_model *m = calloc(1, sizeof *m);
  if (!m) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  m->refs = 1;
  m->set = *set;
  m->nbvert = body_nvert;
  m->nbface = body_nface;
  m->nvert = skin ? skin->nvert : body_nvert;
  m->nface = skin ? skin->nface : body_nface;
  const int nv = m->nvert, nf = m->nface;
  m->nanchor = nv + (set->barycenter_anchors ? nf : 0);
  m->follow_offset = skin != NULL;
  /* a hinge is an edge with exactly two of the 3 nface half-edges */
  m->nhinge_max = set->bending > 0.0 ? (int)(3LL * nf / 2) : 0;
  int status = ss_topo_create(&m->btopo, body_nvert, body_rest, body_nface, body_faces, -1.0, err, err_sz);
  if (status == SS_OK && model_arena(m) != SS_OK)
    status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  if (status != SS_OK) {
    model_release(m);
    return status;
  }
  memcpy(m->faces, skin ? skin->faces : body_faces, 3 * (size_t)nf * sizeof(int));
  memcpy(m->rest, skin ? skin->pos : body_rest, 3 * (size_t)nv * sizeof(double));
  memcpy(m->body_rest, body_rest, 3 * (size_t)body_nvert * sizeof(double));
  for (int f = 0; f < body_nface; f++) {
    /* the formula of ss_frames' area, so that a body at rest has r = 1 exactly (orient.c) */
    const double *v0 = body_rest + 3 * body_faces[3 * f], *v1 = body_rest + 3 * body_faces[3 * f + 1],
                 *v2 = body_rest + 3 * body_faces[3 * f + 2];
    m->body_area0[f] = 0.5 * sqrt(tri_cross2(v0, v1, v2));
  }
  for (int f = 0; f < nf; f++) m->mask[f] = set->face_mask ? set->face_mask[f] != 0 : 1;
  m->set.face_mask = m->mask;
  *out = m;
  return SS_OK;
}

/* The symbolic analysis of the model's pattern for the solver of its
 * settings (sim_internal.h, "symbolic analysis"): once here, not once per
 * sim, so that a second sim on the model (ss_sim_create_from_model) copies
 * it instead of ordering the matrix again. */
static int model_analyze(ss_model *m, char *err, int err_sz) {
  cholmod_start(&m->cc);
  m->cc_started = 1;
  m->cc.print = 0; /* the core never prints: errors come back as status */
  if (m->ndof == 0) return SS_OK;
  return m->set.solver == SS_SOLVER_NEWTON ? ss_solver_newton_analyze(m, err, err_sz)
                                           : ss_solver_qn_analyze(m, err, err_sz);
}

int ss_sim_model_bvh(ss_model *m, const double *body_rest) {
  if (m->bvh_rest) return SS_OK;
  int status = ss_bvh_create(&m->bvh_rest, m->btopo);
  if (status == SS_OK) ss_bvh_refit(m->bvh_rest, body_rest);
  return status;
}

/* The rest of the model, on the sim being created with it: anchors bound,
 * vertex kinds, masses, hinges, pattern, energy layout, symbolic analysis. */
static int model_build(ss_sim *sim, const ss_sim_mesh *skin, char *err, int err_sz) {
  int status = ss_sim_bind(sim, skin, sim->m->body_rest, err, err_sz);
  if (status == SS_OK) status = ss_sim_build_model(sim, err, err_sz);
  if (status == SS_OK) status = ss_sim_build_pattern(sim, err, err_sz);
  if (status == SS_OK) status = ss_sim_energy_layout(sim, err, err_sz);
  if (status == SS_OK) ss_sim_diag_const(sim);
  if (status == SS_OK) status = model_analyze(sim->m, err, err_sz);
  if (status == SS_OK && sim->set.mover.method == SS_METHOD_PROJECT &&
      ss_sim_model_bvh(sim->m, sim->m->body_rest) != SS_OK)
    status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the body's BVH");
  return status;
}

/* 0 if the model settings of set are the model's (a sim on a shared model
 * cannot have a material of its own), else an error naming the first that
 * differs. */
static int model_settings_agree(const ss_model *m, const ss_sim_settings *set, char *err,
                                int err_sz) {
  int n = 0;
  const ss_setting *table = ss_settings_table(&n);
  for (int i = 0; i < n; i++)
    if (ss_sim_in_model(table[i].offset) && !ss_setting_equal(&table[i], &m->set, set))
      return ss_fail(err, err_sz, SS_E_ARG,
                     "setting %s is %g, the model's is %g: sims on one model share its material "
                     "(ss_sim_create_from_model)",
                     table[i].name, ss_setting_get(&table[i], set, 0),
                     ss_setting_get(&table[i], &m->set, 0));
  for (int f = 0; f < m->nface; f++)
    if ((set->face_mask ? set->face_mask[f] != 0 : 1) != m->mask[f])
      return ss_fail(err, err_sz, SS_E_ARG,
                     "face_mask differs from the model's at face %d: sims on one model share it", f);
  return SS_OK;
}

/* ---- data ---- */

/* The kernels' vector instruction set (sim->isa and the frame update's). */
void ss_sim_set_isa(ss_sim *sim, int isa) {
  sim->isa = isa;
  ss_mover_set_isa(sim->mover, isa);
}

/* The data of sim on its model: mover, threads and walkers, the arena, the
 * state at rest. */
static int sim_data(ss_sim *sim, char *err, int err_sz) {
  int status = ss_mover_create(&sim->mover, sim->m->btopo, &sim->set.mover, sim->m->bvh_rest, err, err_sz);
  if (status != SS_OK) return status;
  if (ss_collider_create(&sim->collider, sim->m->btopo, sim->m->body_rest, sim->m->nvert))
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  /* one walker per thread; the team is started here, so that stepping
   * allocates nothing (the OpenMP runtime keeps its threads) */
  sim->nthread = 1;
  sim->thread_probe = -1;
#ifdef _OPENMP
  sim->nthread = sim->set.threads > 0 ? sim->set.threads : auto_threads(sim->m->nface);
  openmp_warm_up(sim->nthread);
#endif
  sim->nthread_max = sim->nthread;
  if (sim->set.threads == 0 && sim->nthread_max > 1) { /* the probe: one thread first */
    sim->thread_probe = 0;
    sim->probe_period = SS_PROBE_PERIOD;
    sim->probe_ms[0] = sim->probe_ms[1] = 0.0;
    sim->nthread = 1;
  }
  ss_sim_set_isa(sim, ss_isa_best());
  status = data_arena(sim);
  for (int t = 0; t < sim->nthread_max && !status; t++)
    status = ss_walker_create(&sim->walkers[t], sim->m->btopo->nface);
  if (status != SS_OK) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  ss_sim_reset(sim);
  return SS_OK;
}

static int sim_solver(ss_sim *sim, char *err, int err_sz) {
  cholmod_start(&sim->cc);
  sim->cc_started = 1;
  sim->cc.print = 0; /* the core never prints: errors come back as status */
  if (sim->m->ndof == 0) return SS_OK;
  return ss_solver_create(sim, err, err_sz);
}

void ss_sim_destroy(ss_sim *sim) {
  if (!sim) return;
  if (sim->cc_started) {
    cholmod_free_sparse(&sim->H, &sim->cc);
    cholmod_free_factor(&sim->LH, &sim->cc);
    cholmod_free_dense(&sim->nb, &sim->cc);
    cholmod_free_dense(&sim->nx, &sim->cc);
    cholmod_free_dense(&sim->ny, &sim->cc);
    cholmod_free_dense(&sim->ne, &sim->cc);
    cholmod_free_sparse(&sim->A, &sim->cc);
    cholmod_free_factor(&sim->LA, &sim->cc);
    cholmod_free_dense(&sim->qb, &sim->cc);
    cholmod_free_dense(&sim->qx, &sim->cc);
    cholmod_free_dense(&sim->qy, &sim->cc);
    cholmod_free_dense(&sim->qe, &sim->cc);
    cholmod_free_dense(&sim->qx_xy, &sim->cc);
    cholmod_free_dense(&sim->qy_xy, &sim->cc);
    cholmod_free_dense(&sim->qe_xy, &sim->cc);
    cholmod_finish(&sim->cc);
  }
  if (sim->cc_z_started) {
    cholmod_free_dense(&sim->qx_z, &sim->cc_z);
    cholmod_free_dense(&sim->qy_z, &sim->cc_z);
    cholmod_free_dense(&sim->qe_z, &sim->cc_z);
    cholmod_finish(&sim->cc_z);
  }
  ss_mover_destroy(sim->mover);
  ss_collider_destroy(sim->collider);
  if (sim->walkers)
    for (int t = 0; t < sim->nthread_max; t++) ss_walker_destroy(sim->walkers[t]);
  free(sim->arena);
  model_release(sim->m);
  free(sim);
}

/* A sim on model m, whose reference it takes over (released on failure):
 * the model built first if `build`, the solver made if `solver`. */
static int sim_make(ss_sim **out, ss_model *m, const ss_sim_settings *set,
                    const ss_sim_mesh *skin, int build, int solver, char *err, int err_sz) {
  ss_sim *sim = calloc(1, sizeof *sim);
  if (!sim) {
    model_release(m);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  }
  sim->m = m;
  sim->set = *set;
  sim->set.face_mask = m->mask;
  int status = build ? model_build(sim, skin, err, err_sz) : SS_OK;
  if (status == SS_OK) status = sim_data(sim, err, err_sz);
  if (status == SS_OK && build) status = ss_sim_orient_init(sim);
  if (status == SS_OK && solver) status = sim_solver(sim, err, err_sz);
  if (status != SS_OK) {
    ss_sim_destroy(sim);
    return status;
  }
  *out = sim;
  return SS_OK;
}

/* Checks the arguments of ss_sim_create / ss_model_create and creates a sim
 * with its own model (its solver only if `solver`). */
static int create(ss_sim **out, int body_nvert, const double *body_rest, int body_nface,
                  const int *body_faces, const ss_sim_mesh *skin, const ss_sim_settings *settings,
                  int solver, char *err, int err_sz) {
  if (!body_rest || !body_faces) return ss_fail(err, err_sz, SS_E_ARG, "body positions or faces are NULL");
  ss_sim_settings def = ss_sim_default_settings();
  const ss_sim_settings *set = settings ? settings : &def;
  int status = ss_settings_check(set, err, err_sz);
  if (status != SS_OK) return status;
  status = ss_mesh_check(body_nvert, body_rest, body_nface, body_faces, err, err_sz);
  if (status != SS_OK) return status;
  if (skin) {
    if (!skin->pos || !skin->faces) return ss_fail(err, err_sz, SS_E_ARG, "skin positions or faces are NULL");
    status = ss_mesh_check(skin->nvert, skin->pos, skin->nface, skin->faces, err, err_sz);
    if (status != SS_OK) return status;
  }
  ss_model *m = NULL;
  status = model_new(&m, body_nvert, body_rest, body_nface, body_faces, skin, set, err, err_sz);
  if (status != SS_OK) return status;
  return sim_make(out, m, set, skin, 1, solver, err, err_sz);
}

int ss_sim_create(ss_sim **out, int body_nvert, const double *body_rest, int body_nface,
                  const int *body_faces, const ss_sim_mesh *skin,
                  const ss_sim_settings *settings, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "out is NULL");
  *out = NULL;
  return create(out, body_nvert, body_rest, body_nface, body_faces, skin, settings, 1, err, err_sz);
}

int ss_model_create(ss_model **out, int body_nvert, const double *body_rest, int body_nface,
                    const int *body_faces, const ss_sim_mesh *skin,
                    const ss_sim_settings *settings, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "out is NULL");
  *out = NULL;
  /* built on a sim without a solver (the rest orientation needs anchors at
   * rest in the body's frames), which then lets it go */
  ss_sim *sim = NULL;
  int status = create(&sim, body_nvert, body_rest, body_nface, body_faces, skin, settings, 0, err, err_sz);
  if (status != SS_OK) return status;
  sim->m->refs++;
  *out = sim->m;
  ss_sim_destroy(sim);
  return SS_OK;
}

int ss_sim_create_from_model(ss_sim **out, ss_model *model, const ss_sim_settings *settings,
                             char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "out is NULL");
  *out = NULL;
  if (!model) return ss_fail(err, err_sz, SS_E_ARG, "model is NULL");
  const ss_sim_settings *set = settings ? settings : &model->set;
  int status = ss_settings_check(set, err, err_sz);
  if (status == SS_OK) status = model_settings_agree(model, set, err, err_sz);
  if (status != SS_OK) return status;
  model->refs++;
  return sim_make(out, model, set, NULL, 0, 1, err, err_sz);
}

ss_model *ss_sim_model(const ss_sim *sim) { return sim ? sim->m : NULL; }
int ss_model_body_nvert(const ss_model *model) { return model->nbvert; }
int ss_model_body_nface(const ss_model *model) { return model->nbface; }
