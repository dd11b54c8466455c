/* Determinism against fixed values (after Box2D's test/test_determinism.c):
 * a built-in scene stepped with the quasi-Newton solver, and the anchor walk
 * alone over a built-in scene, each hashed (FNV-1a, ss_hash_bytes) after the
 * last frame and compared with a value written here.
 *
 * Neither path goes through the BLAS (quasi-Newton factors a scalar matrix with
 * CHOLMOD's simplicial method; the walk is plain C), so the bits depend only on
 * IEEE double arithmetic and libm, and the values hold across builds (release,
 * sanitizer) and these machines. test_sim_threads checks run against run; this
 * test also fails when a change moves the result by one bit. A change that is
 * meant to change the numbers (a new energy term, another summation order)
 * updates the values below in the same commit, saying so: the test prints the
 * hash it got. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_run.h"
#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"
#include "walk.h"

/* twist, 2000 triangles, 30 frames, default settings with quasi-Newton (the value
 * changes, on purpose, with a default that changes the physics: orient 200,
 * tether 3; with a change of the arithmetic: the residual judged across
 * the skin; with the walk's stop at a crease and the tether's
 * step along the surface; with the quasi-Newton line search's step
 * memory and secant backtracking; with the compression-soft membrane,
 * compression 0.1; with the tether's step in the home face's own (u, v),
 * the same in exact arithmetic; and with the default budget of 2 substeps of
 * 3 iterations; and with the orient term's body normal leaning on the
 * faces under a skin face's corners where the body under its barycenter
 * has lost area; and with the quasi-Newton line search's first trial at the
 * depth springs' model, ss_sim_orient_line_step; and with the solver's dots
 * and the energy's sums taken by blocks of SS_PAR_BLOCK terms, par.h; and
 * with each block's sum in SS_PAR_LANES interleaved partial sums; and with
 * each face's barycenter spring added to its membrane energy and gradient
 * in the membrane's pass; and with barycenters and the barycenter springs'
 * shares as products by SS_THIRD, not quotients by 3; and with the
 * quasi-Newton matrix factored LDL', not LL'; and with the walk's slide of
 * an anchor on the tether's leash kept in its home face where the target is
 * within reach, ss_slide_in_face; and with the default budget of 4
 * substeps of 2 iterations; and with that slide's nearest point found in
 * the face's own metric, not by the general closest point) */
static const unsigned long long EXPECT_SIM_QN = 0x47d0dd9cdb9c2717ULL;
/* twist, 2000 triangles, 30 frames: one anchor per face barycenter walked to its
 * last world position lifted 0.1 mean edge lengths along the normal (changed
 * on purpose with the walk's stop at a crease: the point of the edge
 * nearest the target) */
static const unsigned long long EXPECT_WALK = 0xcf014d8c35056d78ULL;

enum { TRIS = 2000, FRAMES = 30 };

static unsigned long long sim_hash(const ss_scene *sc, int threads) {
  ss_sim_settings set = ss_sim_default_settings();
  set.solver = SS_SOLVER_QUASI_NEWTON;
  set.threads = threads;
  ss_sim *sim = NULL;
  char err[256] = "";
  int nv = ss_scene_nvert(sc);
  CHECK_MSG(ss_sim_create(&sim, nv, ss_scene_rest(sc), ss_scene_nface(sc), ss_scene_faces(sc),
                          NULL, &set, err, sizeof err) == SS_OK,
            "%s", err);
  if (!sim) return 0;
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  CHECK(pose != NULL);
  for (int f = 1; pose && f <= FRAMES; f++) {
    ss_scene_pose(sc, f, pose);
    CHECK_MSG(ss_sim_step(sim, pose, 0.0, NULL, err, sizeof err) == SS_OK, "frame %d: %s", f,
              err);
  }
  unsigned long long h =
      ss_hash_bytes(ss_sim_skin_positions(sim), 3 * (size_t)ss_sim_skin_nvert(sim) * sizeof(double));
  free(pose);
  ss_sim_destroy(sim);
  return h;
}

static unsigned long long walk_hash(const ss_scene *sc) {
  int nv = ss_scene_nvert(sc), nf = ss_scene_nface(sc);
  ss_topo *topo = NULL;
  ss_frames *fr = NULL;
  ss_walker *walker = NULL;
  char err[256] = "";
  CHECK_MSG(ss_topo_create(&topo, nv, ss_scene_rest(sc), nf, ss_scene_faces(sc), -1.0, err,
                           sizeof err) == SS_OK,
            "%s", err);
  if (!topo) return 0;
  CHECK(ss_frames_create(&fr, nf) == SS_OK);
  CHECK(ss_walker_create(&walker, nf) == SS_OK);
  double *pos = malloc(3 * (size_t)nv * sizeof(double));
  int *face = malloc((size_t)nf * sizeof(int));
  double *uv = malloc(2 * (size_t)nf * sizeof(double));
  double *target = malloc(3 * (size_t)nf * sizeof(double));
  unsigned long long h = 0;
  if (fr && walker && pos && face && uv && target) {
    const double lift = 0.1 * topo->mean_edge_length;
    long long steps = 0;
    for (int i = 0; i < nf; i++) {
      face[i] = i;
      uv[2 * i] = uv[2 * i + 1] = 1.0 / 3.0;
    }
    ss_scene_pose(sc, 0.0, pos);
    ss_frames_update(fr, topo, pos);
    for (int frame = 1; frame <= FRAMES; frame++) {
      for (int i = 0; i < nf; i++) { /* where the skin was: the last pose, lifted */
        ss_anchor_position(fr, face[i], uv + 2 * i, target + 3 * i);
        for (int c = 0; c < 3; c++) target[3 * i + c] += lift * fr->normal[3 * face[i] + c];
      }
      ss_scene_pose(sc, frame, pos);
      ss_frames_update(fr, topo, pos);
      for (int i = 0; i < nf; i++) {
        ss_walk_result res;
        ss_walk(walker, topo, fr, face[i], uv + 2 * i, target + 3 * i, 512, &res);
        face[i] = res.face;
        uv[2 * i] = res.uv[0];
        uv[2 * i + 1] = res.uv[1];
        steps += res.steps;
      }
    }
    CHECK_MSG(steps > (long long)nf * FRAMES, "the walk must cross faces (%lld steps)", steps);
    h = ss_hash_bytes(uv, 2 * (size_t)nf * sizeof(double)) ^
        (ss_hash_bytes(face, (size_t)nf * sizeof(int)) * 31u);
  }
  free(pos), free(face), free(uv), free(target);
  ss_walker_destroy(walker);
  ss_frames_destroy(fr);
  ss_topo_destroy(topo);
  return h;
}

int main(void) {
  char err[256] = "";
  ss_scene *sc = NULL;
  CHECK_MSG(ss_scene_create(&sc, "twist", TRIS, err, sizeof err) == SS_OK, "%s", err);
  if (!sc) return ss_test_finish("test_determinism");

  unsigned long long qn = sim_hash(sc, 1);
  printf("quasi-Newton, twist %d tris, %d frames: %016llx\n", TRIS, FRAMES, qn);
  CHECK_MSG(qn == EXPECT_SIM_QN, "quasi-Newton hash %016llx, expected %016llx", qn,
            EXPECT_SIM_QN);
  unsigned long long qn2 = sim_hash(sc, 2);
  CHECK_MSG(qn2 == qn, "2 threads: %016llx, 1 thread: %016llx", qn2, qn);

  unsigned long long walk = walk_hash(sc);
  printf("walk, twist %d tris, %d frames: %016llx\n", TRIS, FRAMES, walk);
  CHECK_MSG(walk == EXPECT_WALK, "walk hash %016llx, expected %016llx", walk, EXPECT_WALK);

  ss_scene_destroy(sc);
  return ss_test_finish("test_determinism");
}
