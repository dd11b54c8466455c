/* ss_sim's model and data (sim_internal.h, "model and data"): their arenas,
 * create and destroy, and several sims on one model.
 *
 * A model is built alone and then frozen: model_new (counts, arena, inputs,
 * body topology) + model_build (anchors bound, vertex kinds, masses, hinges,
 * pattern, energy layout, symbolic analysis, rest orientation). Nothing
 * writes it afterwards: sims hold it as `const ss_model *`, and a live change
 * of its material (ss_sim_set_settings) derives a new model (model_derive)
 * that shares the old one's body topology, rest BVH and symbolic analysis.
 * ss_sim_create = a new model + a sim on it: the sim's data (mover, walkers,
 * arena, state at rest) + its solver. ss_sim_create_from_model takes a
 * reference to a model instead. */
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

/* A reference to a model: the count is the one thing about a frozen model
 * that changes, atomically, so sims on other threads may share it. */
static void model_retain(const ss_model *m) {
  atomic_fetch_add_explicit(&((ss_model *)m)->refs, 1, memory_order_relaxed);
}

static void model_release(const ss_model *cm) {
  if (!cm) return;
  ss_model *m = (ss_model *)cm; /* the last reference owns it */
  if (atomic_fetch_sub_explicit(&m->refs, 1, memory_order_acq_rel) > 1) return;
  if (m->cc_started) {
    cholmod_free_factor(&m->sym_qn, &m->cc);
    cholmod_free_factor(&m->sym_newton, &m->cc);
    cholmod_finish(&m->cc);
  }
  if (m->shape) {
    model_release(m->shape);
  } else {
    ss_bvh_destroy(m->bvh_rest);
    ss_topo_destroy(m->btopo);
  }
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
  atomic_init(&m->refs, 1);
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

/* The rest of the model: anchors bound, vertex kinds, masses, hinges,
 * pattern, energy layout, symbolic analysis, rest orientation. */
static int model_build(ss_model *m, const ss_sim_mesh *skin, char *err, int err_sz) {
  int status = ss_model_bind(m, skin, m->body_rest, err, err_sz);
  if (status == SS_OK) status = ss_model_build_kinds(m, err, err_sz);
  if (status == SS_OK) status = ss_model_build_pattern(m, err, err_sz);
  if (status == SS_OK) status = ss_model_energy_layout(m, err, err_sz);
  if (status == SS_OK) ss_model_diag_const(m);
  if (status == SS_OK) status = model_analyze(m, err, err_sz);
  if (status == SS_OK && m->set.mover.method == SS_METHOD_PROJECT &&
      ss_sim_model_bvh(m, m->body_rest) != SS_OK)
    status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the body's BVH");
  if (status == SS_OK) status = ss_model_orient_init(m, err, err_sz);
  return status;
}

/* A model with the material of `set` (its model settings) on m's structure:
 * m's arrays copied (the same counts, so the same layout), the material
 * rebuilt; the body topology, rest BVH and symbolic analysis borrowed from
 * m's owner, whose reference it holds. Hinge weights scale with the bending
 * stiffness (bending turned on or off changes the structure: refused by
 * ss_sim_set_settings before). */
static int model_derive(const ss_model *m, const ss_sim_settings *set, ss_model **out, char *err,
                        int err_sz) {
  ss_model *d = malloc(sizeof *d);
  if (!d) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  memcpy(d, m, sizeof *d);
  atomic_init(&d->refs, 1);
  d->cc_started = 0; /* the analysis is the owner's */
  d->sym_qn = d->sym_newton = NULL;
  d->shape = m->shape ? m->shape : (ss_model *)m;
  d->sym_qn = d->shape->sym_qn;
  d->sym_newton = d->shape->sym_newton;
  if (model_arena(d) != SS_OK) {
    free(d);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  }
  memcpy(d->arena, m->arena, m->arena_bytes);
  model_retain(d->shape);
  const double old_bending = m->set.bending;
  const unsigned char *mask = d->mask;
  d->set = *set;
  d->set.face_mask = mask;
  ss_model_build_material(d);
  ss_model_energy_springs(d); /* k_face into the membrane records */
  if (old_bending > 0.0 && d->set.bending != old_bending)
    for (int e = 0; e < d->nhinge; e++) d->hinge_weight[e] = d->hinge_weight[e] / old_bending * d->set.bending;
  ss_model_diag_const(d);
  *out = d;
  return SS_OK;
}

/* 0 if the model settings of set are the model's (a sim on a shared model
 * cannot have a material of its own), else an error naming the first that
 * differs. */
static int model_settings_agree(const ss_model *m, const ss_sim_settings *set, char *err,
                                int err_sz) {
  int n = 0;
  const ss_setting *table = ss_settings_table(&n);
  for (int i = 0; i < n; i++)
    if (table[i].scope == SS_SCOPE_MODEL && !ss_setting_equal(&table[i], &m->set, set))
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

/* The contact pass's scratch (collide.c: the body's bounding volume tree,
 * its winding-number sums, per-vertex candidates), made where contact is on
 * (at create, or by ss_sim_set_settings turning it on), and kept: without
 * contact it is a ninth of the sim's memory on the 19k quadruped. Made
 * before it is first run, it holds what one made at create would. */
int ss_sim_collider_ensure(ss_sim *sim) {
  if (sim->collider) return SS_OK;
  return ss_collider_create(&sim->collider, sim->m->btopo, sim->m->body_rest, sim->m->nvert, sim->m->nface,
                            sim->m->faces)
             ? SS_E_NOMEM
             : SS_OK;
}

/* The data of sim on its model: mover, threads and walkers, the arena, the
 * state at rest. */
static int sim_data(ss_sim *sim, char *err, int err_sz) {
  int status = ss_mover_create(&sim->mover, sim->m->btopo, &sim->set.mover, sim->m->bvh_rest, err, err_sz);
  if (status != SS_OK) return status;
  if (sim->set.collide && ss_sim_collider_ensure(sim) != SS_OK) return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
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
 * its data and its solver. */
static int sim_make(ss_sim **out, const ss_model *m, const ss_sim_settings *set, char *err,
                    int err_sz) {
  ss_sim *sim = calloc(1, sizeof *sim);
  if (!sim) {
    model_release(m);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory");
  }
  sim->m = m;
  sim->set = *set;
  sim->set.face_mask = m->mask;
  int status = sim_data(sim, err, err_sz);
  if (status == SS_OK) status = sim_solver(sim, err, err_sz);
  if (status != SS_OK) {
    ss_sim_destroy(sim);
    return status;
  }
  *out = sim;
  return SS_OK;
}

/* Checks the arguments of ss_sim_create / ss_model_create and builds a model. */
static int model_create(ss_model **out, int body_nvert, const double *body_rest, int body_nface,
                        const int *body_faces, const ss_sim_mesh *skin,
                        const ss_sim_settings *set, char *err, int err_sz) {
  if (!body_rest || !body_faces) return ss_fail(err, err_sz, SS_E_ARG, "body positions or faces are NULL");
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
  if (status == SS_OK) status = model_build(m, skin, err, err_sz);
  if (status != SS_OK) {
    model_release(m);
    return status;
  }
  *out = m;
  return SS_OK;
}

int ss_sim_create(ss_sim **out, int body_nvert, const double *body_rest, int body_nface,
                  const int *body_faces, const ss_sim_mesh *skin,
                  const ss_sim_settings *settings, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "out is NULL");
  *out = NULL;
  ss_sim_settings def = ss_sim_default_settings();
  const ss_sim_settings *set = settings ? settings : &def;
  ss_model *m = NULL;
  int status = model_create(&m, body_nvert, body_rest, body_nface, body_faces, skin, set, err, err_sz);
  if (status != SS_OK) return status;
  return sim_make(out, m, set, err, err_sz);
}

int ss_model_create(ss_model **out, int body_nvert, const double *body_rest, int body_nface,
                    const int *body_faces, const ss_sim_mesh *skin,
                    const ss_sim_settings *settings, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "out is NULL");
  *out = NULL;
  ss_sim_settings def = ss_sim_default_settings();
  return model_create(out, body_nvert, body_rest, body_nface, body_faces, skin,
                      settings ? settings : &def, err, err_sz);
}

int ss_sim_create_from_model(ss_sim **out, const ss_model *model, const ss_sim_settings *settings,
                             char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "out is NULL");
  *out = NULL;
  if (!model) return ss_fail(err, err_sz, SS_E_ARG, "model is NULL");
  const ss_sim_settings *set = settings ? settings : &model->set;
  int status = ss_settings_check(set, err, err_sz);
  if (status == SS_OK) status = model_settings_agree(model, set, err, err_sz);
  if (status != SS_OK) return status;
  model_retain(model);
  return sim_make(out, model, set, err, err_sz);
}

int ss_sim_rematerial(ss_sim *sim, const ss_sim_settings *set, char *err, int err_sz) {
  ss_model *d = NULL;
  int status = model_derive(sim->m, set, &d, err, err_sz);
  if (status != SS_OK) return status;
  model_release(sim->m);
  sim->m = d;
  return SS_OK;
}

const ss_model *ss_sim_model(const ss_sim *sim) { return sim ? sim->m : NULL; }
int ss_model_body_nvert(const ss_model *model) { return model->nbvert; }
int ss_model_body_nface(const ss_model *model) { return model->nbface; }
