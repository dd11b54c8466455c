/* The stepping kernels in each instruction set this CPU runs: the frame
 * update (per body face: its walk record, normal and area) and the
 * membrane's energy and gradient (per skin face), on a built-in scene's mesh
 * posed at a frame of its motion. Prints CPU time per face (median of the
 * rounds) for each set, and whether each set gives, bit for bit, what the
 * reference gives (the frame update one face at a time; the membrane in the
 * baseline build). A kernel the compiler did not vectorise for a set shows
 * there as no faster than the baseline (GCC if-converts some loops only with
 * AVX-512's masks, so a kernel can be scalar on AVX2 CPUs alone).
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
#include "ss_util.h"
#include "topo.h"
#include "ss_scene.h"
#include "skin_sim/ss_sim.h"
#include "walk.h"

static double cpu_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
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
  /* the membrane's outputs: the reference's energies then a set's, the same for gradients */
  const size_t nout_max = 9 * (size_t)nf > 3 * (size_t)nv ? 9 * (size_t)nf : 3 * (size_t)nv;
  double *energy = malloc(2 * (size_t)nf * sizeof(double)), *out = malloc(2 * nout_max * sizeof(double));
  int *dof_of = malloc((size_t)nv * sizeof(int));
  if (!pose || !times || !mface || !energy || !out || !dof_of ||
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
    printf("  %s: %.1f ns%s", name, ss_median(times, rounds), same ? "" : " (BITS DIFFER)");
  }
  printf("\n");

  /* the membrane's energy and gradient, as the sim's defaults set it, both
   * ways the sim runs it: each face's gradient written (as the threads do),
   * or added to its corners' in face order (as one thread does; every
   * vertex a dof here) */
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
  for (int v = 0; v < nv; v++) dof_of[v] = v;
  for (int to_vertices = 0; to_vertices < 2; to_vertices++) {
    const size_t nout = to_vertices ? 3 * (size_t)nv : 9 * (size_t)nf;
    double *ref_out = out, *got = out + nout;
    printf(to_vertices ? "  ... added to the vertices' gradients:" : "membrane energy and gradient (per skin face):");
    for (int isa = SS_ISA_BASE - 1; isa < SS_ISA_COUNT; isa++) { /* SS_ISA_BASE - 1: the reference, untimed */
      if (isa >= SS_ISA_BASE && !ss_isa_supported(isa)) {
        printf("  %s: not on this CPU", ss_isa_name(isa));
        continue;
      }
      double *o = isa < SS_ISA_BASE ? ref_out : got, *e = isa < SS_ISA_BASE ? energy : energy + nf;
      for (int r = 0; r < (isa < SS_ISA_BASE ? 1 : rounds); r++) {
        memset(o, 0, nout * sizeof(double)); /* added to, in the second way */
        const double t0 = cpu_ns();
        ss_membrane_eval_batch_isa(isa < SS_ISA_BASE ? SS_ISA_BASE : isa, mface, 0, nf, pose, NULL, mu, lam,
                                   set.compression, e, to_vertices ? NULL : o, to_vertices ? o : NULL,
                                   to_vertices ? dof_of : NULL);
        times[r] = (cpu_ns() - t0) / nf;
      }
      if (isa < SS_ISA_BASE) continue;
      const int same = memcmp(got, ref_out, nout * sizeof(double)) == 0 &&
                       memcmp(e, energy, (size_t)nf * sizeof(double)) == 0;
      printf("  %s: %.1f ns%s", ss_isa_name(isa), ss_median(times, rounds), same ? "" : " (BITS DIFFER)");
    }
    printf("\n");
  }
  ss_frames_destroy(ref);
  ss_frames_destroy(fr);
  ss_topo_destroy(topo);
  free(mface), free(energy), free(out), free(dof_of), free(pose), free(times);
  ss_scene_destroy(scene);
  return 0;
}
