/* One model, several sims (ss_model_create, ss_sim_create_from_model): a sim
 * on a shared model gets the bits of a sim made alone with the same settings
 * (ss_sim_create), whatever the other sims on the model do between its steps;
 * stepping never writes the model; the model outlives its creator's
 * reference while a sim runs on it; a sim's model settings must be the
 * model's; a live change of a model setting moves that sim onto a model
 * derived from the shared one (which the other sims keep, unwritten), with
 * the bits of a model built with it;
 * and a reference and a truth run (src/lab/reference.c) on the run's model
 * are the ones computed alone. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim_internal.h"
#include "ss_reference.h"
#include "ss_run.h"
#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

enum { TRIS = 800, FRAMES = 10 };

static unsigned long long positions_hash(const ss_sim *sim) {
  return ss_hash_bytes(ss_sim_skin_positions(sim), 3 * (size_t)ss_sim_skin_nvert(sim) * sizeof(double));
}

static unsigned long long model_hash(const ss_model *m) {
  return ss_hash_bytes(m->arena, m->arena_bytes) ^ ss_hash_bytes(&m->mu, sizeof m->mu) ^
         ss_hash_bytes(&m->lam, sizeof m->lam);
}

/* Steps the sims of list (n) through the scene's frames, interleaved. */
static void step_all(const ss_scene *sc, ss_sim **list, int n) {
  double *pose = malloc(3 * (size_t)ss_scene_nvert(sc) * sizeof(double));
  CHECK(pose != NULL);
  char err[256] = "";
  for (int f = 1; pose && f <= FRAMES; f++) {
    ss_scene_pose(sc, f, pose);
    for (int i = 0; i < n; i++)
      CHECK_MSG(ss_sim_step(list[i], pose, 0.0, NULL, err, sizeof err) == SS_OK, "sim %d frame %d: %s",
                i, f, err);
  }
  free(pose);
}

int main(void) {
  char err[256] = "";
  ss_scene *sc = NULL;
  CHECK_EQ_INT(ss_scene_create(&sc, "twist", TRIS, err, sizeof err), SS_OK);
  if (!sc) return ss_test_finish("test_sim_model");
  const int nv = ss_scene_nvert(sc), nf = ss_scene_nface(sc);
  const double *rest = ss_scene_rest(sc);
  const int *faces = ss_scene_faces(sc);

  /* run settings of two kinds on one material (bending on: hinges too) */
  ss_sim_settings a = ss_sim_default_settings();
  a.bending = 1e-4;
  a.threads = 1;
  ss_sim_settings b = a; /* a reference-like run: Newton, substeps, tight tol, project, tether */
  b.solver = SS_SOLVER_NEWTON;
  b.substeps = 2;
  b.iterations = 10;
  b.tol = 1e-6;
  b.mover.method = SS_METHOD_PROJECT;
  b.tether = 2.0;
  b.damping = 0.5;

  /* alone */
  ss_sim *alone_a = NULL, *alone_b = NULL;
  CHECK_MSG(ss_sim_create(&alone_a, nv, rest, nf, faces, NULL, &a, err, sizeof err) == SS_OK, "%s", err);
  CHECK_MSG(ss_sim_create(&alone_b, nv, rest, nf, faces, NULL, &b, err, sizeof err) == SS_OK, "%s", err);
  /* shared: a model built with a's settings, three sims on it */
  ss_model *model = NULL;
  CHECK_MSG(ss_model_create(&model, nv, rest, nf, faces, NULL, &a, err, sizeof err) == SS_OK, "%s", err);
  if (!alone_a || !alone_b || !model) return ss_test_finish("test_sim_model");
  ss_sim *on_a = NULL, *on_b = NULL, *on_null = NULL;
  CHECK_MSG(ss_sim_create_from_model(&on_a, model, &a, err, sizeof err) == SS_OK, "%s", err);
  CHECK_MSG(ss_sim_create_from_model(&on_b, model, &b, err, sizeof err) == SS_OK, "%s", err);
  CHECK_MSG(ss_sim_create_from_model(&on_null, model, NULL, err, sizeof err) == SS_OK, "%s", err);
  if (!on_a || !on_b || !on_null) return ss_test_finish("test_sim_model");
  CHECK(ss_sim_model(on_a) == model && ss_sim_model(on_b) == model);
  CHECK(ss_sim_model(alone_a) != model);
  CHECK(ss_sim_get_settings(on_b)->solver == SS_SOLVER_NEWTON);
  CHECK_EQ_INT(model->refs, 4);
  /* the symbolic analysis is the model's, for its solver: on_a copies it, on_b
   * (Newton on a quasi-Newton model) analyses its own matrix */
  CHECK(model->sym_qn != NULL && model->sym_newton == NULL);
  CHECK(ss_sim_model(alone_b)->sym_newton != NULL && ss_sim_model(alone_b)->sym_qn == NULL);
  CHECK(on_a->LA != NULL && on_a->LA != model->sym_qn && on_b->LH != NULL);
  /* the model of a sim made alone is the model ss_model_create builds */
  CHECK(model_hash(model) == model_hash(ss_sim_model(alone_a)));
  const unsigned long long before = model_hash(model);

  /* the creator's reference may go first: the sims keep the model */
  ss_model_destroy(model);
  CHECK_EQ_INT(model->refs, 3);
  ss_sim *shared[3] = {on_a, on_b, on_null};
  step_all(sc, shared, 3);
  ss_sim *single[2] = {alone_a, alone_b};
  step_all(sc, single, 2);
  CHECK_MSG(positions_hash(on_a) == positions_hash(alone_a), "quasi-Newton on a shared model: %016llx, alone %016llx",
            positions_hash(on_a), positions_hash(alone_a));
  CHECK_MSG(positions_hash(on_b) == positions_hash(alone_b), "Newton on a shared model: %016llx, alone %016llx",
            positions_hash(on_b), positions_hash(alone_b));
  CHECK(positions_hash(on_null) == positions_hash(alone_a));
  CHECK(positions_hash(on_a) != positions_hash(on_b)); /* the two runs did differ */
  CHECK_MSG(model_hash(model) == before, "stepping wrote the shared model");
  /* the body's BVH: kept by a model whose method is project (its sims' movers
   * borrow its tree), not built for a walking one (on_b builds its own) */
  CHECK(model->bvh_rest == NULL && ss_sim_model(alone_b)->bvh_rest != NULL);
  {
    ss_sim *p1 = NULL, *p2 = NULL;
    CHECK_MSG(ss_sim_create_from_model(&p1, ss_sim_model(alone_b), &b, err, sizeof err) == SS_OK, "%s", err);
    CHECK_MSG(ss_sim_create_from_model(&p2, ss_sim_model(alone_b), &b, err, sizeof err) == SS_OK, "%s", err);
    if (p1 && p2) {
      ss_sim *pair[2] = {p1, p2};
      step_all(sc, pair, 2);
      CHECK_MSG(positions_hash(p1) == positions_hash(alone_b) && positions_hash(p2) == positions_hash(alone_b),
                "project sims on the tree of their model: %016llx %016llx, alone %016llx", positions_hash(p1),
                positions_hash(p2), positions_hash(alone_b));
    }
    ss_sim_destroy(p1);
    ss_sim_destroy(p2);
  }
  printf("model arena %zu bytes, data arena %zu bytes (twist, %d triangles)\n", model->arena_bytes,
         on_a->arena_bytes, nf);

  /* a sim's model settings must be the model's */
  ss_sim *bad = NULL;
  ss_sim_settings c = a;
  c.young *= 2.0;
  CHECK_EQ_INT(ss_sim_create_from_model(&bad, ss_sim_model(on_a), &c, err, sizeof err), SS_E_ARG);
  CHECK_MSG(bad == NULL && strstr(err, "young"), "%s", err);
  c = a;
  c.barycenter_anchors = 0;
  CHECK_EQ_INT(ss_sim_create_from_model(&bad, ss_sim_model(on_a), &c, err, sizeof err), SS_E_ARG);
  CHECK_MSG(strstr(err, "barycenters"), "%s", err);
  unsigned char *mask = malloc((size_t)nf);
  CHECK(mask != NULL);
  if (mask) {
    memset(mask, 1, (size_t)nf);
    mask[nf / 2] = 0;
    c = a;
    c.face_mask = mask;
    CHECK_EQ_INT(ss_sim_create_from_model(&bad, ss_sim_model(on_a), &c, err, sizeof err), SS_E_ARG);
    CHECK_MSG(strstr(err, "face_mask"), "%s", err);
    free(mask);
  }
  CHECK_EQ_INT(ss_sim_create_from_model(&bad, NULL, &a, err, sizeof err), SS_E_ARG);

  /* live changes: a run setting changes on a shared model; a model setting
   * moves that sim onto a model of its own, derived from the shared one (its
   * structure borrowed), which is never written: the other sims keep it */
  int recreate = -1;
  c = a;
  c.tol = 1e-3;
  c.damping = 1.0;
  CHECK(ss_sim_set_settings(on_a, &c, &recreate, err, sizeof err) == SS_OK && recreate == 0);
  CHECK(ss_sim_get_settings(on_a)->tol == 1e-3);
  CHECK(ss_sim_model(on_a) == model);
  c.young = 80.0;
  const int refs_before = model->refs;
  CHECK_MSG(ss_sim_set_settings(on_a, &c, &recreate, err, sizeof err) == SS_OK && recreate == 0, "%s", err);
  CHECK(ss_sim_get_settings(on_a)->young == 80.0 && ss_sim_get_settings(on_a)->tol == 1e-3);
  const ss_model *derived = ss_sim_model(on_a);
  CHECK(derived != model && ss_sim_model(on_b) == model && ss_sim_model(on_null) == model);
  CHECK_MSG(model_hash(model) == before, "a material change wrote the shared model");
  CHECK(model_hash(derived) != before);
  /* on_a's reference moved to the derived model, which holds one on its shape */
  CHECK_EQ_INT(model->refs, refs_before);
  CHECK(derived->shape == model && derived->btopo == model->btopo && derived->sym_qn == model->sym_qn);
  /* a second change derives from the owner again: never a chain */
  c.density = 2.0;
  CHECK_MSG(ss_sim_set_settings(on_a, &c, &recreate, err, sizeof err) == SS_OK && recreate == 0, "%s", err);
  CHECK(ss_sim_model(on_a)->shape == model && ss_sim_model(on_a)->mass[0] == 2.0 * model->mass[0]);
  /* the other sims step on, released in any order; the derived model holds
   * the shared one's structure until it goes */
  ss_sim_destroy(on_b);
  ss_sim_destroy(on_null);
  CHECK_EQ_INT(model->refs, 1);
  step_all(sc, &on_a, 1);
  /* a derived material gives the bits of a model built with it: a sim made
   * with a and changed to young 80 at rest steps as one made with young 80 */
  {
    ss_sim_settings y = a;
    y.young = 80.0;
    ss_sim *built = NULL, *changed = NULL;
    CHECK_MSG(ss_sim_create(&built, nv, rest, nf, faces, NULL, &y, err, sizeof err) == SS_OK, "%s", err);
    CHECK_MSG(ss_sim_create(&changed, nv, rest, nf, faces, NULL, &a, err, sizeof err) == SS_OK, "%s", err);
    if (built && changed) {
      CHECK_MSG(ss_sim_set_settings(changed, &y, &recreate, err, sizeof err) == SS_OK && recreate == 0, "%s",
                err);
      CHECK(model_hash(ss_sim_model(changed)) == model_hash(ss_sim_model(built)));
      ss_sim *pair[2] = {built, changed};
      step_all(sc, pair, 2);
      CHECK_MSG(positions_hash(built) == positions_hash(changed), "derived material %016llx, built %016llx",
                positions_hash(changed), positions_hash(built));
    }
    ss_sim_destroy(built);
    ss_sim_destroy(changed);
  }

  ss_sim_destroy(on_a);
  ss_sim_destroy(alone_a);
  ss_sim_destroy(alone_b);

  /* the lab: a run's reference and truth (src/lab/reference.c) on the run's
   * model, built once (ss_run_model_create), are those computed alone */
  ss_body body = ss_body_of_scene(sc);
  ss_run_settings run = ss_run_default_settings();
  run.frames = 3;
  run.sim.mover.method = SS_METHOD_PROJECT; /* the truth walks: another run setting */
  ss_model *rm = NULL;
  CHECK_MSG(ss_run_model_create(&rm, &body, &run, err, sizeof err) == SS_OK, "%s", err);
  ss_run_settings on_model = run;
  on_model.model = rm;
  const ss_run_settings truth_alone = ss_truth_settings(&run), truth_shared = ss_truth_settings(&on_model);
  CHECK(ss_reference_settings(&on_model).model == rm && truth_shared.model == rm);
  const ss_run_settings *cases[2][2] = {{&run, &on_model}, {&truth_alone, &truth_shared}};
  for (int k = 0; rm && k < 2; k++) {
    ss_reference *r0 = NULL, *r1 = NULL;
    CHECK_MSG(ss_reference_get(&r0, &body, cases[k][0], NULL, NULL, NULL, err, sizeof err) == SS_OK, "%s", err);
    CHECK_MSG(ss_reference_get(&r1, &body, cases[k][1], NULL, NULL, NULL, err, sizeof err) == SS_OK, "%s", err);
    if (r0 && r1) {
      CHECK(r0->key == r1->key && r0->frames == r1->frames && r0->nvert == r1->nvert);
      CHECK_MSG(memcmp(r0->pos, r1->pos, sizeof(double) * 3 * (size_t)r0->nvert * (size_t)r0->frames) == 0,
                "%s on the run's model differs from the one computed alone", k ? "truth" : "reference");
    }
    ss_reference_destroy(r0);
    ss_reference_destroy(r1);
  }
  /* a custom skin's model is not the reference's (the welded body): dropped */
  ss_sim_mesh own = {nv, rest, nf, faces};
  on_model.skin = &own;
  CHECK(ss_reference_settings(&on_model).model == NULL);
  ss_model_destroy(rm);
  ss_scene_destroy(sc);
  return ss_test_finish("test_sim_model");
}
