/* The stepping kernels in each instruction set this CPU runs: the frame
 * update (per body face: its walk record, normal and area) and the
 * membrane's energy and gradient (per skin face), on a built-in scene's mesh
 * posed at a frame of its motion. Prints CPU time per face (median of the
 * rounds) for each set, and whether each set gives, bit for bit, what the
 * reference gives (the frame update one face at a time; the membrane in the
 * baseline build). A kernel the compiler did not vectorise for a set shows
 * there as no faster than the baseline: the frame update ran as scalar code
 * on AVX2 CPUs for a session unnoticed, on a machine with AVX-512 (README,
 * "Twelfth session").
 *
 *   bench_kernels [scene] [tris] [rounds]      e.g. bench_kernels quadruped 19000 21
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "energy.h"
#include "isa.h"
#include "skin_sim/ss_mesh.h"
#include "skin_sim/ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "walk.h"

static double cpu_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
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
  const char *scene_name = argc > 1 ? argv[1] : "quadruped";
  const int tris = argc > 2 ? atoi(argv[2]) : 19000;
  const int rounds = argc > 3 && atoi(argv[3]) > 0 ? atoi(argv[3]) : 21;
  char err[256];
  ss_scene *scene = NULL;
  if (ss_scene_create(&scene, scene_name, tris, err, sizeof err) != SS_OK) {
    fprintf(stderr, "bench_kernels: %s\n", err);
    return 1;
  }
  const int nv = ss_scene_nvert(scene), nf = ss_scene_nface(scene);
  const int *faces = ss_scene_faces(scene);
  const double *rest = ss_scene_rest(scene);
  double *pose = malloc(3 * (size_t)nv * sizeof(double));
  double *times = malloc((size_t)rounds * sizeof(double));
  ss_topo *topo = NULL;
  ss_frames *ref = NULL, *fr = NULL;
  ss_membrane_face *mface = aligned_alloc(64, sizeof(ss_membrane_face) * (size_t)nf);
  double *energy = malloc(2 * (size_t)nf * sizeof(double)), *grad = malloc(18 * (size_t)nf * sizeof(double));
  if (!pose || !times || !mface || !energy || !grad ||
      ss_topo_create(&topo, nv, rest, nf, faces, -1.0, err, sizeof err) != SS_OK ||
      ss_frames_create(&ref, nf) != SS_OK || ss_frames_create(&fr, nf) != SS_OK) {
    fprintf(stderr, "bench_kernels: %s\n", topo ? "out of memory" : err);
    return 1;
  }
  ss_scene_pose(scene, 0.5 * ss_scene_default_frames(scene), pose);
  printf("scene %s tris %d, CPU ns per face, median of %d rounds\n", scene_name, nf, rounds);

  /* the frame update */
  ref->isa = -1;
  ss_frames_update(ref, topo, pose);
  printf("frame update (per body face):");
  for (int isa = -1; isa < SS_ISA_COUNT; isa++) {
    const char *name = isa < 0 ? "one face at a time" : ss_isa_name(isa);
    if (isa >= 0 && !ss_isa_supported(isa)) {
      printf("  %s: not on this CPU", name);
      continue;
    }
    fr->isa = isa;
    for (int r = 0; r < rounds; r++) {
      const double t0 = cpu_ns();
      ss_frames_update(fr, topo, pose);
      times[r] = (cpu_ns() - t0) / nf;
    }
    const int same = memcmp(fr->walk, ref->walk, sizeof(double) * SS_FRAME_RECORD * (size_t)nf) == 0 &&
                     memcmp(fr->normal, ref->normal, sizeof(double) * 3 * (size_t)nf) == 0 &&
                     memcmp(fr->area, ref->area, sizeof(double) * (size_t)nf) == 0;
    printf("  %s: %.1f ns%s", name, median(times, rounds), same ? "" : " (BITS DIFFER)");
  }
  printf("\n");

  /* the membrane's energy and gradient, as the sim's defaults set it */
  const ss_sim_settings set = ss_sim_default_settings();
  double mu, lam;
  ss_membrane_lame(set.young, set.poisson, &mu, &lam);
  for (int f = 0; f < nf; f++) {
    ss_membrane_face *m = mface + f;
    memset(m, 0, sizeof *m);
    for (int c = 0; c < 3; c++) m->xo[c] = 3 * faces[3 * f + c];
    ss_membrane_rest(rest + 3 * faces[3 * f], rest + 3 * faces[3 * f + 1], rest + 3 * faces[3 * f + 2], m->dm_inv,
                     &m->area);
  }
  ss_membrane_eval_batch_isa(SS_ISA_BASE, mface, 0, nf, pose, NULL, mu, lam, set.compression, energy, grad, NULL,
                             NULL);
  printf("membrane energy and gradient (per skin face):");
  for (int isa = 0; isa < SS_ISA_COUNT; isa++) {
    if (!ss_isa_supported(isa)) {
      printf("  %s: not on this CPU", ss_isa_name(isa));
      continue;
    }
    double *e = energy + nf, *g = grad + 9 * (size_t)nf;
    for (int r = 0; r < rounds; r++) {
      const double t0 = cpu_ns();
      ss_membrane_eval_batch_isa(isa, mface, 0, nf, pose, NULL, mu, lam, set.compression, e, g, NULL, NULL);
      times[r] = (cpu_ns() - t0) / nf;
    }
    const int same = memcmp(e, energy, sizeof(double) * (size_t)nf) == 0 &&
                     memcmp(g, grad, sizeof(double) * 9 * (size_t)nf) == 0;
    printf("  %s: %.1f ns%s", ss_isa_name(isa), median(times, rounds), same ? "" : " (BITS DIFFER)");
  }
  printf("\n");
  /* the same, each face's gradient added to its corners' in face order (as
   * one thread runs it: every vertex a dof here) */
  printf("  ... added to the vertices' gradients:");
  double *ref_dof = calloc(3 * (size_t)nv, sizeof(double)), *dof = calloc(3 * (size_t)nv, sizeof(double));
  int *dof_of = malloc((size_t)nv * sizeof(int));
  if (!ref_dof || !dof || !dof_of) {
    fprintf(stderr, "bench_kernels: out of memory\n");
    return 1;
  }
  for (int v = 0; v < nv; v++) dof_of[v] = v;
  ss_membrane_eval_batch_isa(SS_ISA_BASE, mface, 0, nf, pose, NULL, mu, lam, set.compression, energy, NULL, ref_dof,
                             dof_of);
  for (int isa = 0; isa < SS_ISA_COUNT; isa++) {
    if (!ss_isa_supported(isa)) continue;
    for (int r = 0; r < rounds; r++) {
      memset(dof, 0, 3 * (size_t)nv * sizeof(double));
      const double t0 = cpu_ns();
      ss_membrane_eval_batch_isa(isa, mface, 0, nf, pose, NULL, mu, lam, set.compression, energy + nf, NULL, dof,
                                 dof_of);
      times[r] = (cpu_ns() - t0) / nf;
    }
    const int same = memcmp(dof, ref_dof, 3 * (size_t)nv * sizeof(double)) == 0;
    printf("  %s: %.1f ns%s", ss_isa_name(isa), median(times, rounds), same ? "" : " (BITS DIFFER)");
  }
  printf("\n");
  free(ref_dof), free(dof), free(dof_of);
  ss_frames_destroy(ref);
  ss_frames_destroy(fr);
  ss_topo_destroy(topo);
  free(mface), free(energy), free(grad), free(pose), free(times);
  ss_scene_destroy(scene);
  return 0;
}
