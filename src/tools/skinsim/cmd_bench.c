/* skinsim bench: speed against accuracy (doc/benchmarks.md). Runs a sweep of
 * configurations over the built-in scenes and the avatars, each compared with
 * its reference (ss_reference.h, cached), writes results.csv (one row per run,
 * every field of `skinsim run --json` after the sweep's own columns) and draws
 * the charts with scripts/plot_bench.py (matplotlib).
 *
 * The sweep is a base configuration (the defaults: quasi-Newton, 4 substeps of 2
 * iterations, walk) varied one axis at a time, not the cartesian product:
 *  - methods:  every body x {walk, project, nring 1, 2, 4}          (stability, Pareto)
 *  - solvers:  a few scenes x {newton, quasi-newton} x iterations {1, 2, 4, 8, converged},
 *              at one substep
 *  - substeps: the same scenes x substeps {2, 4} at 8 iterations (slide is a rate: the
 *              same physics)
 *  - scaling:  the quadruped at growing sizes, walk and project (no reference)
 *  - options:  a few scenes: barycenter anchors off, bending on, gravity on, a region
 *              mask, a coarser skin than the body
 *  - rest:     every scene and the demo x tether {0, 1, 3, 10} /s x {walk, project}, with
 *              a 3 s settle after the motion (rest return; no reference)
 * Every run with a reference is also measured against the truth (ss_truth_settings:
 * one per body, motion and physical settings, whatever the method).
 * --quick shrinks sizes and frame counts (and the lists) to finish in minutes;
 * --sweeps runs only the named sweeps (one chart's data in minutes, e.g. after a
 * change to an option). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "avatar_body.h"
#include "cli.h"
#include "commands.h"
#include "measure.h"
#include "ss_scene.h"

#ifndef SS_SOURCE_DIR
#define SS_SOURCE_DIR "."
#endif

#define BCN_ASSET "/usr/share/assimp/models/X/BCN_Epileptic.X"

enum { OPT_NONE, OPT_NO_BARY, OPT_BENDING, OPT_GRAVITY, OPT_REGION, OPT_COARSE, OPT_STIFF,
       OPT_COLLIDE };
static const char *const option_names[] = {"base", "no-barycenters", "bending", "gravity",
                                           "region", "coarse-skin", "stiff-compression",
                                           "collide"};

/* One run of the sweep. */
typedef struct bench_case {
  const char *sweep;  /* methods, solvers, substeps, scaling, options */
  const char *body;   /* scene name, "demo" or the asset path */
  int avatar;         /* 0 scene, 1 demo mannequin, 2 asset */
  int tris;           /* scene / mannequin size */
  int frames;
  int method, rings, solver, iterations, substeps;
  double tol;
  int option;
  int reference;
  const char *variant; /* short label of what was varied */
  double tether;       /* 1/s (the default; the rest sweep varies it) */
  double settle;       /* s: rest return measured after the motion (rest sweep); 0 none */
} bench_case;

typedef struct case_list {
  bench_case *c;
  int n, cap;
} case_list;

static int add_case(case_list *l, bench_case c) {
  if (l->n == l->cap) {
    int cap = l->cap ? 2 * l->cap : 64;
    bench_case *bigger = realloc(l->c, sizeof *bigger * (size_t)cap);
    if (!bigger) return -1;
    l->c = bigger;
    l->cap = cap;
  }
  l->c[l->n++] = c;
  return 0;
}

static bench_case base_case(const char *sweep, const char *body, int avatar, int tris,
                            int frames) {
  ss_sim_settings d = ss_sim_default_settings();
  bench_case c = {sweep, body, avatar, tris, frames, SS_METHOD_WALK, d.mover.nring_rings,
                  d.solver, d.iterations, d.substeps, d.tol, OPT_NONE, 1, "base", d.tether, 0.0};
  return c;
}

/* Builds the sweep. Returns 0 or -1 (out of memory). */
static int build_sweep(case_list *l, int quick, int have_asset) {
  const int scene_tris = quick ? 300 : 1000, frames = quick ? 6 : 40;
  const int demo_tris = 3000, avatar_frames = quick ? 1 : 15;
  int bad = 0;
  /* methods: every body */
  const int nscene = ss_scene_count();
  for (int b = 0; b < nscene + 2; b++) {
    int avatar = b < nscene ? 0 : b - nscene + 1;
    if (avatar == 2 && !have_asset) continue;
#ifndef SS_HAVE_AVATAR
    if (avatar) continue;
#endif
    const char *name = avatar == 0 ? ss_scene_name(b) : avatar == 1 ? "demo" : BCN_ASSET;
    int tris = avatar == 0 ? scene_tris : avatar == 1 ? demo_tris : 0;
    int fr = avatar ? avatar_frames : frames;
    static const struct { int method, rings; const char *label; } methods[] = {
        {SS_METHOD_WALK, 0, "walk"},     {SS_METHOD_PROJECT, 0, "project"},
        {SS_METHOD_NRING, 1, "nring1"},  {SS_METHOD_NRING, 2, "nring2"},
        {SS_METHOD_NRING, 4, "nring4"}};
    for (int m = 0; m < 5; m++) {
      bench_case c = base_case("methods", name, avatar, tris, fr);
      c.method = methods[m].method;
      if (c.method == SS_METHOD_NRING) c.rings = methods[m].rings;
      c.variant = methods[m].label;
      bad |= add_case(l, c);
    }
  }
  /* solvers and iterations; substeps */
  static const char *const solver_scenes_full[] = {"elbow", "armpit", "quadruped"};
  static const char *const solver_scenes_quick[] = {"elbow"};
  const char *const *ss = quick ? solver_scenes_quick : solver_scenes_full;
  const int nss = quick ? 1 : 3;
  static const int iters[] = {1, 2, 4, 8, 0};
  static const char *const iter_labels[] = {"1", "2", "4", "8", "converged"};
  for (int i = 0; i < nss; i++) {
    for (int solver = 0; solver < 2; solver++) {
      for (int k = 0; k < 5; k++) {
        if (quick && (k == 1 || k == 2)) continue;
        bench_case c = base_case("solvers", ss[i], 0, scene_tris, frames);
        c.solver = solver;
        c.substeps = 1;
        c.iterations = iters[k] ? iters[k] : 500;
        if (!iters[k]) c.tol = 1e-6;
        c.variant = iter_labels[k];
        bad |= add_case(l, c);
      }
    }
    for (int sub = 2; sub <= 4; sub *= 2) {
      bench_case c = base_case("substeps", ss[i], 0, scene_tris, frames);
      c.substeps = sub;
      c.iterations = 8;
      c.variant = sub == 2 ? "2" : "4";
      bad |= add_case(l, c);
    }
  }
  /* scaling: the quadruped at growing sizes, no reference */
  static const int sizes_full[] = {1000, 2000, 4000, 8000, 19000, 38000};
  static const int sizes_quick[] = {300, 600, 1200};
  const int *sizes = quick ? sizes_quick : sizes_full;
  const int nsizes = quick ? 3 : 6;
  for (int i = 0; i < nsizes; i++) {
    for (int m = 0; m < 2; m++) {
      bench_case c = base_case("scaling", "quadruped", 0, sizes[i], quick ? 6 : 20);
      c.method = m ? SS_METHOD_PROJECT : SS_METHOD_WALK;
      c.reference = 0;
      c.variant = m ? "project" : "walk";
      bad |= add_case(l, c);
    }
  }
  /* options */
  static const char *const opt_scenes_full[] = {"elbow", "armpit", "quadruped"};
  static const char *const opt_scenes_quick[] = {"elbow"};
  const char *const *os = quick ? opt_scenes_quick : opt_scenes_full;
  for (int i = 0; i < (quick ? 1 : 3); i++) {
    for (int o = OPT_NONE; o <= OPT_COLLIDE; o++) {
      bench_case c = base_case("options", os[i], 0, scene_tris, frames);
      c.option = o;
      c.variant = option_names[o];
      bad |= add_case(l, c);
    }
  }
  /* rest return against the tether, with and without the walk */
  static const double tethers[] = {0.0, 1.0, 3.0, 10.0};
  static const char *const tether_labels[] = {"tether 0", "tether 1", "tether 3", "tether 10"};
  for (int b = 0; b < nscene + 1; b++) {
    const int avatar = b == nscene;
#ifndef SS_HAVE_AVATAR
    if (avatar) continue;
#endif
    if (quick && !avatar && strcmp(ss_scene_name(b), "elbow") != 0) continue;
    for (int t = 0; t < 4; t++) {
      if (quick && (t == 1 || t == 3)) continue;
      for (int m = 0; m < 2; m++) {
        bench_case c = base_case("rest", avatar ? "demo" : ss_scene_name(b), avatar,
                                 avatar ? demo_tris : scene_tris,
                                 avatar ? (quick ? 1 : 120) : frames);
        c.method = m ? SS_METHOD_PROJECT : SS_METHOD_WALK;
        c.reference = 0;
        c.tether = tethers[t];
        c.settle = quick ? 1.0 : 3.0;
        c.variant = tether_labels[t];
        bad |= add_case(l, c);
      }
    }
  }
  return bad ? -1 : 0;
}

static const char *const sweep_names[] = {"methods", "solvers", "substeps", "scaling",
                                          "options", "rest"};
#define NSWEEP ((int)(sizeof sweep_names / sizeof sweep_names[0]))

/* Parses --sweeps' comma-separated names into want[NSWEEP]. Returns 0, or -1
 * after printing which name is unknown. */
static int parse_sweeps(const char *list, int want[NSWEEP]) {
  for (int k = 0; k < NSWEEP; k++) want[k] = 0;
  const char *p = list;
  for (;;) {
    const char *comma = strchr(p, ',');
    const size_t len = comma ? (size_t)(comma - p) : strlen(p);
    int found = -1;
    for (int k = 0; k < NSWEEP; k++)
      if (strlen(sweep_names[k]) == len && strncmp(p, sweep_names[k], len) == 0) found = k;
    if (found < 0) {
      cli_error("bench: unknown sweep '%.*s' in --sweeps (methods, solvers, substeps, scaling, "
                "options, rest)", (int)len, p);
      return -1;
    }
    want[found] = 1;
    if (!comma) return 0;
    p = comma + 1;
  }
}

/* Keeps the cases of the wanted sweeps, in order. */
static void keep_sweeps(case_list *l, const int want[NSWEEP]) {
  int n = 0;
  for (int i = 0; i < l->n; i++)
    for (int k = 0; k < NSWEEP; k++)
      if (want[k] && strcmp(l->c[i].sweep, sweep_names[k]) == 0) {
        l->c[n++] = l->c[i];
        break;
      }
  l->n = n;
}

/* ---- running one case ------------------------------------------------------- */

/* Faces whose rest centroid has x >= the median x: half of the body. */
static unsigned char *half_mask(const ss_body *body) {
  unsigned char *mask = calloc((size_t)body->nface, 1);
  double *cx = malloc(sizeof(double) * (size_t)body->nface);
  double *sorted = malloc(sizeof(double) * (size_t)body->nface);
  if (!mask || !cx || !sorted) {
    free(mask);
    free(cx);
    free(sorted);
    return NULL;
  }
  for (int f = 0; f < body->nface; f++) {
    cx[f] = 0.0;
    for (int k = 0; k < 3; k++) cx[f] += body->rest[3 * body->faces[3 * f + k]] / 3.0;
    sorted[f] = cx[f];
  }
  /* median by partial selection sort would be slow: sort */
  for (int gap = body->nface / 2; gap > 0; gap /= 2) /* shell sort */
    for (int i = gap; i < body->nface; i++)
      for (int j = i; j >= gap && sorted[j - gap] > sorted[j]; j -= gap) {
        double t = sorted[j];
        sorted[j] = sorted[j - gap];
        sorted[j - gap] = t;
      }
  double median = sorted[body->nface / 2];
  for (int f = 0; f < body->nface; f++) mask[f] = cx[f] >= median;
  free(cx);
  free(sorted);
  return mask;
}

typedef struct bench_ctx {
  const char *cache_dir;
  FILE *csv;
  int header_done;
} bench_ctx;

static void case_columns(json_out *j, const bench_case *c) {
  json_str(j, "sweep", c->sweep);
  json_str(j, "variant", c->variant);
  json_str(j, "option", option_names[c->option]);
  json_str(j, "body_kind", c->avatar == 0 ? "scene" : "avatar");
}

/* Runs one case and writes its row. Returns 0, 1 when it ran but some frames
 * failed (row written, the sweep goes on), or -1 after printing why. */
static int run_case(bench_ctx *ctx, const bench_case *c, int index, int count, double t0) {
  char err[512] = "";
  ss_scene *scene = NULL, *coarse = NULL;
  avatar_body *ab = NULL;
  unsigned char *mask = NULL;
  ss_body body;
  ss_run_settings s = ss_run_default_settings();
  s.frames = c->frames;
  s.sim.mover.method = c->method;
  s.sim.mover.nring_rings = c->rings;
  s.sim.solver = c->solver;
  s.sim.iterations = c->iterations;
  s.sim.tol = c->tol;
  s.sim.substeps = c->substeps;
  s.sim.tether = c->tether;
  s.settle = c->settle;
  int status = SS_OK;
  const char *label = c->body;
  if (c->avatar == 0) {
    status = ss_scene_create(&scene, c->body, c->tris, err, sizeof err);
    if (!status) body = ss_body_of_scene(scene);
  } else {
#ifdef SS_HAVE_AVATAR
    avatar_args av = {0};
    if (c->avatar == 1) av.avatar = "demo";
    else av.asset = c->body;
    av.avatar_tris = c->tris;
    const unsigned char *unused = NULL;
    status = avatar_body_open(&ab, &av, &body, &unused, err, sizeof err);
    if (c->avatar == 2) {
      const char *slash = strrchr(c->body, '/');
      label = slash ? slash + 1 : c->body;
    }
#else
    snprintf(err, sizeof err, "avatars are not built (urdfdom or assimp missing)");
    status = SS_E_UNSUPPORTED;
#endif
  }
  ss_sim_mesh skin;
  if (!status) {
    switch (c->option) {
      case OPT_NO_BARY: s.sim.barycenter_anchors = 0; break;
      case OPT_BENDING: s.sim.bending = 1e-3; break;
      case OPT_GRAVITY: s.sim.gravity[2] = -9.81; break;
      case OPT_STIFF: s.sim.compression = 1.0; break; /* the Stable Neo-Hookean membrane */
      case OPT_COLLIDE: s.sim.collide = 1; break;     /* contact with the clean body */
      case OPT_REGION:
        mask = half_mask(&body);
        if (!mask) status = SS_E_NOMEM;
        s.sim.face_mask = mask;
        break;
      case OPT_COARSE: /* the same scene with about a quarter of the triangles */
        status = ss_scene_create(&coarse, c->body, c->tris / 4 > 100 ? c->tris / 4 : 100, err,
                                 sizeof err);
        if (!status) {
          skin.nvert = ss_scene_nvert(coarse);
          skin.pos = ss_scene_rest(coarse);
          skin.nface = ss_scene_nface(coarse);
          skin.faces = ss_scene_faces(coarse);
          s.skin = &skin;
        }
        break;
      default: break;
    }
  }
  measure_result res;
  /* options: also against the default model's reference (what the option changes) */
  ss_run_settings base = s;
  base.skin = NULL;
  base.sim.barycenter_anchors = ss_sim_default_settings().barycenter_anchors;
  base.sim.bending = 0.0;
  base.sim.gravity[2] = 0.0;
  base.sim.face_mask = NULL;
  if (!status)
    status = measure_run(&body, &s, c->sweep[0] == 'o' ? &base : NULL,
                         c->reference ? ctx->cache_dir : NULL, c->reference, NULL, NULL, NULL, NULL, &res, err,
                         sizeof err);
  int rc = 0;
  if (status) {
    fprintf(stderr, "[%d/%d] %s %s %s: FAILED: %s\n", index, count, c->sweep, label, c->variant,
            err);
    rc = -1;
  } else {
    json_out j;
    if (!ctx->header_done) {
      csv_begin(&j, ctx->csv, CSV_HEADER);
      case_columns(&j, c);
      measure_fields(&j, label, &s, &res);
      json_end(&j);
      ctx->header_done = 1;
    }
    csv_begin(&j, ctx->csv, CSV_ROW);
    case_columns(&j, c);
    measure_fields(&j, label, &s, &res);
    json_end(&j);
    char errtext[64] = "";
    if (res.has_reference)
      snprintf(errtext, sizeof errtext, ", error %.3g%s", res.error_vs_reference,
               res.reference_cache_hit ? "" : " (reference computed)");
    fprintf(stderr,
            "[%d/%d] %-8s %-10s %-9s %-12s %-7s %6d tris: %8.2f ms/frame, %lld snags, %lld "
            "failures%s  [%.0f s]\n",
            index, count, c->sweep, label, c->variant, ss_solver_name(c->solver),
            ss_method_name(c->method), res.st.triangles, res.st.ms_per_frame_median,
            res.st.snags, res.st.failures, errtext, (ss_now_ms() - t0) / 1000.0);
    if (res.st.failures > 0) rc = 1; /* ran and was measured, but some frames failed */
  }
  free(mask);
  ss_scene_destroy(coarse);
  ss_scene_destroy(scene);
  avatar_body_close(ab);
  return rc;
}

static int plot(const char *python, const char *script, const char *out_dir) {
  pid_t pid = fork();
  if (pid < 0) {
    cli_error("cannot start %s: %s", python, strerror(errno));
    return -1;
  }
  if (pid == 0) {
    setenv("MPLBACKEND", "Agg", 1);
    execl(python, python, script, out_dir, (char *)NULL);
    fprintf(stderr, "skinsim: cannot run %s: %s\n", python, strerror(errno));
    _exit(127);
  }
  int wstatus = 0;
  while (waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0) {
    cli_error("the plotting script %s failed (exit %d): charts may be missing", script,
              WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1);
    return -1;
  }
  return 0;
}

int cmd_bench(int argc, char **argv) {
  const char *out_dir = NULL, *cache_opt = NULL, *python = "/usr/bin/python3";
  const char *script = SS_SOURCE_DIR "/scripts/plot_bench.py";
  int quick = 0, no_plot = 0, doubling = 0, nset = 0;
  const char *bodies = NULL, *sweeps = NULL;
  double truth_tol = 0.0; /* --truth-tol: the truth's Newton tolerance (0: SS_REFERENCE_TOL) */
  ss_sim_settings sim = ss_sim_default_settings(); /* --truth-doubling: physical settings */
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    const int set_opt = cli_setting_option(argc, argv, &i, &sim);
    if (set_opt < 0) return EXIT_USAGE;
    if (set_opt > 0) {
      nset++;
      continue;
    }
    if (strcmp(a, "--out") == 0) {
      if (!(out_dir = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--cache") == 0) {
      if (!(cache_opt = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--quick") == 0) {
      quick = 1;
    } else if (strcmp(a, "--truth-doubling") == 0) {
      const char *v = cli_value(argc, argv, &i);
      if (!v || cli_int(a, v, 2 * SS_REFERENCE_SUBSTEPS, 16 * SS_REFERENCE_SUBSTEPS, &doubling))
        return EXIT_USAGE;
    } else if (strcmp(a, "--truth-tol") == 0) {
      const char *v = cli_value(argc, argv, &i);
      if (!v || cli_double(a, v, 1e-14, 1.0, &truth_tol)) return EXIT_USAGE;
      nset++;
    } else if (strcmp(a, "--sweeps") == 0) {
      if (!(sweeps = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--bodies") == 0) {
      if (!(bodies = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--no-plot") == 0) {
      no_plot = 1;
    } else if (strcmp(a, "--python") == 0) {
      if (!(python = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--plot-script") == 0) {
      if (!(script = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else {
      cli_error("bench: unknown option '%s' (see skinsim help)", a);
      return EXIT_USAGE;
    }
  }
  if (!out_dir) {
    cli_error("bench needs --out DIR");
    return EXIT_USAGE;
  }
  int want[NSWEEP];
  if (sweeps && parse_sweeps(sweeps, want)) return EXIT_USAGE;
  if (sweeps && doubling) {
    cli_error("bench: --sweeps goes with the sweep, not with --truth-doubling");
    return EXIT_USAGE;
  }
  if (mkdir(out_dir, 0777) != 0 && errno != EEXIST) {
    cli_error("cannot create output folder '%s': %s", out_dir, strerror(errno));
    return EXIT_USAGE;
  }
  if (!no_plot && access(script, R_OK) != 0) {
    cli_error("plotting script '%s' not found (give --plot-script FILE or --no-plot)", script);
    return EXIT_USAGE;
  }
  char cache_dir[4096];
  if (measure_cache_dir(cache_opt, cache_dir, sizeof cache_dir)) return EXIT_USAGE;
  if ((nset || bodies) && !doubling) {
    cli_error("bench: --bodies and setting flags (--tether, ...) go with --truth-doubling; the "
              "sweep runs the defaults");
    return EXIT_USAGE;
  }
  if (doubling)
    return bench_truth_doubling(out_dir, cache_dir, doubling, quick,
                                access(BCN_ASSET, R_OK) == 0 ? BCN_ASSET : NULL, &sim, bodies,
                                truth_tol);
  char path[4200];
  snprintf(path, sizeof path, "%s/results.csv", out_dir);
  FILE *csv = fopen(path, "w");
  if (!csv) {
    cli_error("cannot write '%s': %s", path, strerror(errno));
    return EXIT_USAGE;
  }
  case_list l = {0};
  if (build_sweep(&l, quick, access(BCN_ASSET, R_OK) == 0)) {
    fclose(csv);
    free(l.c);
    cli_error("out of memory");
    return EXIT_RUN_FAILED;
  }
  if (sweeps) keep_sweeps(&l, want);
  fprintf(stderr, "skinsim bench: %d runs%s%s%s, references cached in %s\n", l.n,
          quick ? " (quick)" : "", sweeps ? ", sweeps " : "", sweeps ? sweeps : "", cache_dir);
  bench_ctx ctx = {cache_dir, csv, 0};
  const double t0 = ss_now_ms();
  int failed = 0, with_failures = 0;
  for (int i = 0; i < l.n; i++) {
    /* a run with failing frames is a result (kept in the CSV); the sweep goes on */
    const int rc = run_case(&ctx, &l.c[i], i + 1, l.n, t0);
    failed += rc < 0;
    with_failures += rc > 0;
  }
  free(l.c);
  int bad = ferror(csv);
  if (fclose(csv) != 0 || bad) {
    cli_error("cannot write '%s'", path);
    return EXIT_RUN_FAILED;
  }
  fprintf(stderr, "skinsim bench: %d runs in %.0f s, %d failed, %d had failing frames "
          "(their rows are in the CSV, failures column); %s written\n", l.n,
          (ss_now_ms() - t0) / 1000.0, failed, with_failures, path);
  if (!no_plot && plot(python, script, out_dir)) return EXIT_RUN_FAILED;
  return failed ? EXIT_RUN_FAILED : 0;
}
