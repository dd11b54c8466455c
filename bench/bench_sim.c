/* bench_sim: times ss_sim on a built-in scene (a benchmark, not a test).
 *
 *   bench_sim [scene] [tris] [frames] [solver] [substeps] [iterations] [tol] [method] [threads] [orient]
 *   defaults:  twist   19000  60      quasi-newton 1  8   1e-4  walk   (ss_sim_default_settings)
 *
 * Prints one line of medians per frame (ms): total, pose (body frames, anchor
 * positions), walk (anchor updates), assemble, factor, solve; mean iterations,
 * energy evaluations per iteration (the first of each substep included), failures, stalls, area
 * ratio range over all frames, and an FNV-1a hash of the final positions.
 * "cpu" is the median CPU time of the process per step (all threads): on a
 * shared, loaded machine the figure to compare between builds at one thread,
 * where wall-clock times mostly measure the other jobs. */
#define _POSIX_C_SOURCE 200809L
#include <time.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "skin_sim/ss_scene.h"
#include "skin_sim/ss_sim.h"

static double cpu_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_d);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  double *t_total = malloc((size_t)frames * sizeof(double)), *t_walk = malloc((size_t)frames * sizeof(double));
  double *t_asm = malloc((size_t)frames * sizeof(double)), *t_fac = malloc((size_t)frames * sizeof(double));
  double *t_sol = malloc((size_t)frames * sizeof(double));
  double *t_pose = malloc((size_t)frames * sizeof(double));
  double *t_cpu = malloc((size_t)frames * sizeof(double));
  double it_sum = 0.0, ev_sum = 0.0, amin = 1e300, amax = 0.0, res_sum = 0.0, rms_sum = 0.0;
  int failures = 0, stalls = 0, unconverged = 0;
  double dt = 1.0 / ss_scene_fps(scene);
  for (int f = 0; f < frames; f++) {
    ss_scene_pose(scene, f + 1, pose);
    ss_sim_stats st;
    double c0 = cpu_ms();
    if (ss_sim_step(sim, pose, dt, &st, err, sizeof err) != SS_OK) {
      fprintf(stderr, "bench_sim: frame %d: %s\n", f, err);
      return 1;
    }
    t_cpu[f] = cpu_ms() - c0;
    t_total[f] = st.total_ms, t_walk[f] = st.walk_ms, t_asm[f] = st.assemble_ms;
    t_fac[f] = st.factor_ms, t_sol[f] = st.solve_ms, t_pose[f] = st.pose_ms;
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
         "ms/frame total %.2f cpu %.2f pose %.2f walk %.2f assemble %.2f factor %.2f solve %.2f (medians); "
         "iterations %.2f/frame, energy evaluations %.2f/iteration, residual mean %.2g (rms %.2g), unconverged %d, stalled %d, failures %d, area ratio [%.3f, %.3f], hash %016llx\n",
         scene_name, nf, nv, ss_sim_ndof(sim), solver, ss_method_name(set.mover.method), set.substeps, frames,
         median(t_total, frames), median(t_cpu, frames), median(t_pose, frames), median(t_walk, frames), median(t_asm, frames), median(t_fac, frames),
         median(t_sol, frames), it_sum / frames, it_sum > 0 ? ev_sum / it_sum : 0.0, res_sum / frames, rms_sum / frames, unconverged, stalls, failures, amin, amax, hash);
  ss_sim_destroy(sim);
  ss_scene_destroy(scene);
  free(pose), free(t_total), free(t_walk), free(t_asm), free(t_fac), free(t_sol), free(t_pose), free(t_cpu);
  return 0;
}
