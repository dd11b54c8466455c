/* Determinism against fixed values (after Box2D's test/test_determinism.c):
 * a built-in scene stepped with the quasi-Newton solver, another with
 * contact on as well, and the anchor walk alone over a built-in scene, each
 * hashed (FNV-1a, ss_hash_bytes) after the
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

/* twist, 2000 triangles, 30 frames, quasi-Newton with the fixed settings of
 * sim_settings below (the value changes only with the arithmetic or the
 * physics of a setting there; each change says why in its commit message) */
static const unsigned long long EXPECT_SIM_QN = 0x4e00a6e172c386f6ULL;
/* elbow, 2000 triangles, 30 frames, the same settings with contact on
 * (collide: the skin moved out of the clean body after each step) */
static const unsigned long long EXPECT_SIM_COLLIDE = 0x471cf64424ce6c73ULL;
/* twist, 2000 triangles, 30 frames: one anchor per face barycenter walked to its
 * last world position lifted 0.1 mean edge lengths along the normal */
static const unsigned long long EXPECT_WALK = 0xcf014d8c35056d78ULL;

enum { TRIS = 2000, FRAMES = 30 };

/* Every setting written out, not ss_sim_default_settings(): a change of a
 * default does not move the hash (tests of the defaults' behaviour are
 * test_stability, test_rest_return and the bench's error against the truth). */
static ss_sim_settings sim_settings(int threads, int collide) {
  return (ss_sim_settings){
      .solver = SS_SOLVER_QUASI_NEWTON,
      .dt = 1.0 / 30.0,
      .substeps = 4,
      .iterations = 2,
      .tol = 1e-4,
      .safety_residual = 0.05,
      .iterations_max = 32,
      .lbfgs_history = 6,
      .young = 50.0,
      .poisson = 0.3,
      .density = 1.0,
      .anchor_stiffness = 1e3,
      .barycenter_anchors = 1,
      .bending = 0.0,
      .gravity = {0.0, 0.0, 0.0},
      .damping = 0.0,
      .slide = 30.0 * 0.69314718055994530942,
      .tether = 3.0,
      .orient = 200.0,
      .compression = 0.1,
      .collide = collide,
      .collide_thickness = 0.0,
      .mover = {.method = SS_METHOD_WALK, .walk_max_steps = 512, .nring_rings = 2},
      .threads = threads,
      .face_mask = NULL,
  };
}

static unsigned long long sim_hash(const ss_scene *sc, int threads, int collide) {
  ss_sim_settings set = sim_settings(threads, collide);
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

  unsigned long long qn = sim_hash(sc, 1, 0);
  printf("quasi-Newton, twist %d tris, %d frames: %016llx\n", TRIS, FRAMES, qn);
  CHECK_MSG(qn == EXPECT_SIM_QN, "quasi-Newton hash %016llx, expected %016llx", qn,
            EXPECT_SIM_QN);
  unsigned long long qn2 = sim_hash(sc, 2, 0);
  CHECK_MSG(qn2 == qn, "2 threads: %016llx, 1 thread: %016llx", qn2, qn);

  ss_scene *elbow = NULL;
  CHECK_MSG(ss_scene_create(&elbow, "elbow", TRIS, err, sizeof err) == SS_OK, "%s", err);
  if (elbow) {
    unsigned long long co = sim_hash(elbow, 1, 1);
    printf("quasi-Newton with contact, elbow %d tris, %d frames: %016llx\n", TRIS, FRAMES, co);
    CHECK_MSG(co == EXPECT_SIM_COLLIDE, "contact hash %016llx, expected %016llx", co, EXPECT_SIM_COLLIDE);
    unsigned long long co2 = sim_hash(elbow, 2, 1);
    CHECK_MSG(co2 == co, "contact, 2 threads: %016llx, 1 thread: %016llx", co2, co);
    CHECK_MSG(sim_hash(elbow, 1, 0) != co, "contact must move the elbow's skin");
    ss_scene_destroy(elbow);
  }

  unsigned long long walk = walk_hash(sc);
  printf("walk, twist %d tris, %d frames: %016llx\n", TRIS, FRAMES, walk);
  CHECK_MSG(walk == EXPECT_WALK, "walk hash %016llx, expected %016llx", walk, EXPECT_WALK);

  ss_scene_destroy(sc);
  return ss_test_finish("test_determinism");
}
