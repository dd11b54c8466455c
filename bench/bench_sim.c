/* bench_sim: times ss_sim on a built-in scene (a benchmark, not a test).
 *
 *   bench_sim [scene] [tris] [frames] [solver] [substeps] [iterations] [tol] [method] [threads] [orient] [anchors] [tether] [collide]
 *   defaults:  twist   19000  60      quasi-newton 1  8   1e-4  walk   (ss_sim_default_settings) 0  (default) 0
 *
 * Prints one line of medians per frame (ms): total, pose (body frames, anchor
 * positions), walk (anchor updates), assemble, factor, solve; mean iterations,
 * energy evaluations per iteration (the first of each substep included), failures, stalls, area
 * ratio range over all frames, and an FNV-1a hash of the final positions.
 * "cpu" is the median CPU time of the process per step (all threads): on a
 * shared, loaded machine the figure to compare between builds at one thread,
 * where wall-clock times mostly measure the other jobs.
 *
 * anchors 1 adds a per-anchor comparison of the walk and BVH projection on the
 * same queries (not part of the step's times): after each step, every anchor's
 * move of that step is replayed from where it was before the step towards the
 * same target a* = a0 + slide_frac (p - a0) the skin gave it (p its skin point,
 * a0 its position in the new pose), once by the walk and once by the exact
 * closest point on the body (the BVH), each over all anchors in one timed loop
 * (CPU time), and prints the per-frame medians in ns per anchor, their ratio,
 * and how many replayed walks ended where the skin's own walk did (all of them
 * at 1 substep and no tether). The walk compared with projection sums its
 * path's length (as the mover's does); unmeasured_walk_ns times the same walks
 * as the sim walks them (ss_walk_unmeasured: no length unless
 * ss_sim_measure_anchors), after the projections. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <time.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "mover.h"
#include "ss_util.h"
#include "ss_vec.h"

static double cpu_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

/* The per-anchor comparison of walk and projection (anchors 1). */
typedef struct probe {
  ss_mover *walk, *project;
  int nanchor, nskinvert;
  int *face0, *face;       /* (nanchor) before the step / replayed walk result */
  double *uv0, *target;    /* (nanchor x 2), (nanchor x 3) */
  double *walk_ns, *project_ns; /* (frames) per anchor */
  double *bare_ns;              /* (frames) per anchor: the walk without its length, as the sim walks */
  ss_walker *walker;            /* for those */
  long long same, compared, steps;
  int walked; /* anchors replayed per frame */
} probe;

static int probe_create(probe *pr, const ss_sim *sim, int frames, char *err, int err_sz) {
  memset(pr, 0, sizeof *pr);
  ss_mover_settings ms = ss_sim_get_settings(sim)->mover;
  ms.method = SS_METHOD_WALK;
  if (ss_mover_create(&pr->walk, ss_sim_body_topo(sim), &ms, NULL, err, err_sz)) return 1;
  ms.method = SS_METHOD_PROJECT;
  if (ss_mover_create(&pr->project, ss_sim_body_topo(sim), &ms, NULL, err, err_sz)) return 1;
  pr->nanchor = ss_sim_nanchors(sim);
  pr->nskinvert = ss_sim_skin_nvert(sim);
  size_t n = (size_t)pr->nanchor;
  pr->face0 = malloc(n * sizeof(int));
  pr->face = malloc(n * sizeof(int));
  pr->uv0 = malloc(2 * n * sizeof(double));
  pr->target = malloc(3 * n * sizeof(double));
  pr->walk_ns = malloc((size_t)frames * sizeof(double));
  pr->project_ns = malloc((size_t)frames * sizeof(double));
  pr->bare_ns = malloc((size_t)frames * sizeof(double));
  if (!pr->face0 || !pr->face || !pr->uv0 || !pr->target || !pr->walk_ns || !pr->project_ns || !pr->bare_ns ||
      ss_walker_create(&pr->walker, ss_sim_body_topo(sim)->nface) != SS_OK) {
    snprintf(err, (size_t)err_sz, "out of memory for the anchor probe");
    return 1;
  }
  return 0;
}

static void probe_destroy(probe *pr) {
  ss_mover_destroy(pr->walk);
  ss_mover_destroy(pr->project);
  free(pr->face0), free(pr->face), free(pr->uv0), free(pr->target);
  free(pr->walk_ns), free(pr->project_ns), free(pr->bare_ns);
  ss_walker_destroy(pr->walker);
}

/* Before a step: where the anchors are. */
static void probe_before(probe *pr, const ss_sim *sim) {
  memcpy(pr->face0, ss_sim_anchor_faces(sim), (size_t)pr->nanchor * sizeof(int));
  memcpy(pr->uv0, ss_sim_anchor_uv(sim), 2 * (size_t)pr->nanchor * sizeof(double));
}

/* After step f (one substep, body pose `pose`): replays the anchors' moves. */
static void probe_after(probe *pr, const ss_sim *sim, const double *pose, double dt, int f) {
  const ss_sim_settings *set = ss_sim_get_settings(sim);
  /* the sim's own arithmetic (sim.c: h, slide_frac, barycenters by SS_THIRD),
   * so that the replayed targets are the skin's to the bit */
  const double h = dt / set->substeps;
  const double frac = set->slide > 0.0 ? -expm1(-set->slide * h) : 0.0;
  const double *x = ss_sim_skin_positions(sim);
  const int *faces = ss_sim_skin_faces(sim), nv = pr->nskinvert;
  ss_mover_set_pose(pr->walk, pose);
  ss_mover_set_pose(pr->project, pose);
  const ss_frames *fr = ss_mover_frames(pr->walk);
  int n = 0;
  for (int a = 0; a < pr->nanchor; a++) {
    if (pr->face0[a] < 0) continue;
    double p[3], a0[3];
    if (a < nv) {
      memcpy(p, x + 3 * a, sizeof p);
    } else {
      const int *fv = faces + 3 * (a - nv);
      for (int i = 0; i < 3; i++) p[i] = (x[3 * fv[0] + i] + x[3 * fv[1] + i] + x[3 * fv[2] + i]) * SS_THIRD;
    }
    ss_anchor_position(fr, pr->face0[a], pr->uv0 + 2 * a, a0);
    for (int i = 0; i < 3; i++) pr->target[3 * a + i] = a0[i] + frac * (p[i] - a0[i]);
    n++;
  }
  ss_walk_result res;
  double c0 = cpu_ms();
  for (int a = 0; a < pr->nanchor; a++) {
    if (a + SS_WALK_PREFETCH < pr->nanchor) ss_frames_prefetch(fr, pr->face0[a + SS_WALK_PREFETCH]);
    if (pr->face0[a] < 0) continue;
    ss_mover_move(pr->walk, pr->face0[a], pr->uv0 + 2 * a, pr->target + 3 * a, &res);
    pr->face[a] = res.face;
    pr->steps += res.steps;
  }
  double c1 = cpu_ms();
  for (int a = 0; a < pr->nanchor; a++) {
    if (pr->face0[a] < 0) continue;
    ss_mover_move(pr->project, pr->face0[a], pr->uv0 + 2 * a, pr->target + 3 * a, &res);
  }
  double c2 = cpu_ms();
  /* the sim's own walk: its length not summed (ss_sim_measure_anchors off) */
  const ss_topo *topo = ss_sim_body_topo(sim);
  const int max_steps = set->mover.walk_max_steps;
  for (int a = 0; a < pr->nanchor; a++) {
    if (a + SS_WALK_PREFETCH < pr->nanchor) ss_frames_prefetch(fr, pr->face0[a + SS_WALK_PREFETCH]);
    if (pr->face0[a] < 0) continue;
    ss_walk_unmeasured(pr->walker, topo, fr, pr->face0[a], pr->uv0 + 2 * a, pr->target + 3 * a, max_steps, &res);
  }
  double c3 = cpu_ms();
  pr->walked = n;
  pr->walk_ns[f] = n ? 1e6 * (c1 - c0) / n : 0.0;
  pr->project_ns[f] = n ? 1e6 * (c2 - c1) / n : 0.0;
  pr->bare_ns[f] = n ? 1e6 * (c3 - c2) / n : 0.0;
  const int *face_sim = ss_sim_anchor_faces(sim);
  for (int a = 0; a < pr->nanchor; a++) {
    if (pr->face0[a] < 0) continue;
    pr->compared++;
    pr->same += pr->face[a] == face_sim[a];
  }
}

int main(int argc, char **argv) {
  const char *scene_name = argc > 1 ? argv[1] : "twist";
  int tris = argc > 2 ? atoi(argv[2]) : 19000;
  int frames = argc > 3 ? atoi(argv[3]) : 60;
  const char *solver = argc > 4 ? argv[4] : "quasi-newton";
  ss_sim_settings set = ss_sim_default_settings();
  set.solver = ss_solver_parse(solver);
  if (argc > 5) set.substeps = atoi(argv[5]);
  if (argc > 6) set.iterations = atoi(argv[6]);
  if (argc > 7) set.tol = atof(argv[7]);
  if (argc > 8) set.mover.method = ss_method_parse(argv[8]);
  if (argc > 9) set.threads = atoi(argv[9]);
  if (argc > 10) set.orient = atof(argv[10]);
  const int anchors = argc > 11 ? atoi(argv[11]) : 0;
  if (argc > 12) set.tether = atof(argv[12]);
  if (argc > 13) set.collide = atoi(argv[13]);
  char err[256];
  ss_scene *scene = NULL;
  if (ss_scene_create(&scene, scene_name, tris, err, sizeof err) != SS_OK) {
    fprintf(stderr, "bench_sim: %s\n", err);
    return 1;
  }
  int nv = ss_scene_nvert(scene), nf = ss_scene_nface(scene);
  ss_sim *sim = NULL;
  if (ss_sim_create(&sim, nv, ss_scene_rest(scene), nf, ss_scene_faces(scene), NULL, &set, err,
                    sizeof err) != SS_OK) {
    fprintf(stderr, "bench_sim: %s\n", err);
    return 1;
  }
  probe pr;
  if (anchors && probe_create(&pr, sim, frames, err, sizeof err)) {
    fprintf(stderr, "bench_sim: %s\n", err);
    return 1;
  }
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  double *t_total = malloc((size_t)frames * sizeof(double)), *t_walk = malloc((size_t)frames * sizeof(double));
  double *t_asm = malloc((size_t)frames * sizeof(double)), *t_fac = malloc((size_t)frames * sizeof(double));
  double *t_sol = malloc((size_t)frames * sizeof(double));
  double *t_pose = malloc((size_t)frames * sizeof(double));
  double *t_ls = malloc((size_t)frames * sizeof(double)), *t_or = malloc((size_t)frames * sizeof(double));
  double *t_other = malloc((size_t)frames * sizeof(double));
  double *t_cpu = malloc((size_t)frames * sizeof(double));
  double it_sum = 0.0, ev_sum = 0.0, amin = 1e300, amax = 0.0, res_sum = 0.0, rms_sum = 0.0;
  int failures = 0, stalls = 0, unconverged = 0;
  double dt = 1.0 / ss_scene_fps(scene);
  for (int f = 0; f < frames; f++) {
    ss_scene_pose(scene, f + 1, pose);
    ss_sim_stats st;
    if (anchors) probe_before(&pr, sim);
    double c0 = cpu_ms();
    if (ss_sim_step(sim, pose, dt, &st, err, sizeof err) != SS_OK) {
      fprintf(stderr, "bench_sim: frame %d: %s\n", f, err);
      return 1;
    }
    t_cpu[f] = cpu_ms() - c0;
    if (anchors) probe_after(&pr, sim, pose, dt, f);
    t_total[f] = st.total_ms, t_walk[f] = st.walk_ms, t_asm[f] = st.assemble_ms;
    t_fac[f] = st.factor_ms, t_sol[f] = st.solve_ms, t_pose[f] = st.pose_ms;
    t_ls[f] = st.linesearch_ms, t_or[f] = st.orient_ms;
    t_other[f] = st.total_ms - st.pose_ms - st.walk_ms - st.assemble_ms - st.factor_ms - st.solve_ms -
                 st.linesearch_ms - st.orient_ms;
    it_sum += st.iterations;
    ev_sum += st.energy_evaluations;
    res_sum += st.residual;
    rms_sum += st.residual_rms;
    failures += st.failures;
    stalls += st.stalled;
    unconverged += !st.converged;
    if (st.min_area_ratio < amin) amin = st.min_area_ratio;
    if (st.max_area_ratio > amax) amax = st.max_area_ratio;
  }
  unsigned long long hash = 1469598103934665603ULL;
  const unsigned char *bytes = (const unsigned char *)ss_sim_skin_positions(sim);
  for (size_t i = 0; i < 3 * (size_t)nv * sizeof(double); i++) hash = (hash ^ bytes[i]) * 1099511628211ULL;
  printf("scene %s tris %d verts %d dofs %d solver %s method %s substeps %d frames %d: "
         "ms/frame total %.2f cpu %.2f pose %.2f walk %.2f assemble %.2f factor %.2f solve %.2f linesearch %.2f orient %.2f other %.2f (medians); "
         "iterations %.2f/frame, energy evaluations %.2f/iteration, residual mean %.2g (rms %.2g), unconverged %d, stalled %d, failures %d, area ratio [%.3f, %.3f], hash %016llx\n",
         scene_name, nf, nv, ss_sim_ndof(sim), solver, ss_method_name(set.mover.method), set.substeps, frames,
         ss_median(t_total, frames), ss_median(t_cpu, frames), ss_median(t_pose, frames), ss_median(t_walk, frames),
         ss_median(t_asm, frames), ss_median(t_fac, frames), ss_median(t_sol, frames), ss_median(t_ls, frames), ss_median(t_or, frames),
         ss_median(t_other, frames), it_sum / frames, it_sum > 0 ? ev_sum / it_sum : 0.0, res_sum / frames, rms_sum / frames, unconverged, stalls, failures, amin, amax, hash);
  if (anchors) {
    double w = ss_median(pr.walk_ns, frames), p = ss_median(pr.project_ns, frames);
    double b = ss_median(pr.bare_ns, frames);
    printf("anchors %d per frame (per anchor, same queries, CPU, medians): walk_ns %.1f project_ns %.1f "
           "project/walk %.1f unmeasured_walk_ns %.1f (walk %.2f ms per frame, %.3f edges crossed per walk); replayed walks "
           "ending in the skin's face %lld/%lld\n",
           pr.walked, w, p, w > 0.0 ? p / w : 0.0, b, 1e-6 * w * pr.walked,
           pr.compared ? (double)pr.steps / (double)pr.compared : 0.0, pr.same, pr.compared);
    probe_destroy(&pr);
  }
  ss_sim_destroy(sim);
  ss_scene_destroy(scene);
  free(pose), free(t_total), free(t_walk), free(t_asm), free(t_fac), free(t_sol), free(t_pose), free(t_cpu);
  free(t_ls), free(t_or), free(t_other);
  return 0;
}
