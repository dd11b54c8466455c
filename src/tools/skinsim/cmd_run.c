/* skinsim run: the dynamic skin over a built-in scene, with its JSON summary
 * and, with --out, a PLY file of the skin (and of the body) at every frame. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "avatar_body.h"
#include "cli.h"
#include "measure.h"
#include "commands.h"
#include "ss_run.h"

/* Binary little-endian PLY of float positions and int triangles; with
 * anchor_face (one a vertex, or NULL) an int vertex property of that name:
 * the body face each skin vertex is anchored on, which tells a reader such
 * as bench/inside_view.py the skin anchored where the body passes through
 * itself, as the run's inside measure does. */
static int write_ply(const char *path, int nvert, const double *pos, int nface, const int *faces,
                     const int *anchor_face) {
  FILE *f = fopen(path, "wb");
  if (!f) return -1;
  fprintf(f,
          "ply\nformat binary_little_endian 1.0\ncomment skin_sim\nelement vertex %d\n"
          "property float x\nproperty float y\nproperty float z\n%selement face %d\n"
          "property list uchar int vertex_indices\nend_header\n",
          nvert, anchor_face ? "property int anchor_face\n" : "", nface);
  for (int v = 0; v < nvert; v++) {
    float p[3] = {(float)pos[3 * v], (float)pos[3 * v + 1], (float)pos[3 * v + 2]};
    fwrite(p, sizeof p, 1, f);
    if (anchor_face) fwrite(anchor_face + v, sizeof(int), 1, f);
  }
  for (int t = 0; t < nface; t++) {
    unsigned char three = 3;
    fwrite(&three, 1, 1, f);
    fwrite(faces + 3 * t, sizeof(int), 3, f);
  }
  int bad = ferror(f);
  return (fclose(f) != 0 || bad) ? -1 : 0;
}

typedef struct frame_writer {
  const char *dir;
  const ss_body *body;
  char error[4400];
} frame_writer;

static int write_frame(void *user, int frame, const ss_sim *sim, const double *body_pos) {
  frame_writer *w = user;
  char path[4096];
  snprintf(path, sizeof path, "%s/skin_%04d.ply", w->dir, frame);
  /* the vertex anchors come first among the sim's anchors */
  if (write_ply(path, ss_sim_skin_nvert(sim), ss_sim_skin_positions(sim), ss_sim_skin_nface(sim),
                ss_sim_skin_faces(sim), ss_sim_anchor_faces(sim))) {
    snprintf(w->error, sizeof w->error, "cannot write '%s': %s", path, strerror(errno));
    return 1;
  }
  snprintf(path, sizeof path, "%s/body_%04d.ply", w->dir, frame);
  if (write_ply(path, w->body->nvert, body_pos, w->body->nface, w->body->faces, NULL)) {
    snprintf(w->error, sizeof w->error, "cannot write '%s': %s", path, strerror(errno));
    return 1;
  }
  return 0;
}

/* --out DIR: an existing folder we may write into, or one we can create; checked
 * before the first step so a bad path costs nothing. One message on failure. */
static int check_out_dir(const char *dir) {
  struct stat st;
  if (stat(dir, &st) == 0) {
    if (!S_ISDIR(st.st_mode)) {
      cli_error("--out '%s' is not a folder (a file of that name exists)", dir);
      return -1;
    }
  } else if (mkdir(dir, 0777) != 0) {
    cli_error("--out: cannot create the folder '%s': %s", dir, strerror(errno));
    return -1;
  }
  if (access(dir, W_OK | X_OK) != 0) {
    cli_error("--out: cannot write into the folder '%s': %s", dir, strerror(errno));
    return -1;
  }
  return 0;
}

int cmd_run(int argc, char **argv) {
  const char *scene_name = NULL, *json_path = NULL, *out_dir = NULL, *cache_opt = NULL;
  const char *skin_path = NULL;
  double skin_max_distance = 0.05; /* m */
  int tris = 0, reference = 0, truth = 0;
  avatar_args av = {0};
  ss_run_settings s = ss_run_default_settings();
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
    /* every simulation setting: the table (ss_settings.h; skinsim help lists them) */
    const int set_opt = cli_setting_option(argc, argv, &i, &s.sim);
    if (set_opt < 0) return EXIT_USAGE;
    if (set_opt > 0) continue;
    if (strcmp(a, "--scene") == 0) {
      if (!(scene_name = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--tris") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_int(a, v, 1, 5000000, &tris)) return EXIT_USAGE;
    } else if (strcmp(a, "--frames") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_int(a, v, 1, 1000000, &s.frames))
        return EXIT_USAGE;
    } else if (strcmp(a, "--inside-every") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_int(a, v, 0, 1000000, &s.inside_every))
        return EXIT_USAGE;
    } else if (strcmp(a, "--avatar") == 0) {
      if (!(av.avatar = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--urdf") == 0) {
      if (!(av.urdf = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--mesh") == 0) {
      if (!(av.mesh = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--motion") == 0) {
      if (!(av.motion = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--asset") == 0) {
      if (!(av.asset = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--anim") == 0) {
      if (!(av.anim = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--region") == 0) {
      if (!(av.region = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--package-path") == 0) {
      if (!(av.package_path = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--avatar-tris") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_int(a, v, 3000, 5000000, &av.avatar_tris))
        return EXIT_USAGE;
    } else if (strcmp(a, "--asset-scale") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_double(a, v, 1e-9, 1e9, &av.asset_scale))
        return EXIT_USAGE;
    } else if (strcmp(a, "--strict-limits") == 0) {
      av.strict_limits = 1;
    } else if (strcmp(a, "--mesh-up-axis") == 0) {
      if (!(av.mesh_up_axis = cli_value(argc, argv, &i))) return EXIT_USAGE;
      if (strcmp(av.mesh_up_axis, "ignore") != 0 && strcmp(av.mesh_up_axis, "file") != 0) {
        cli_error("--mesh-up-axis expects ignore or file, got '%s'", av.mesh_up_axis);
        return EXIT_USAGE;
      }
    } else if (strcmp(a, "--primitive-edge") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_double(a, v, 1e-4, 10.0, &av.primitive_edge))
        return EXIT_USAGE;
    } else if (strcmp(a, "--max-file-mb") == 0) { /* hostile mesh files (safe_import.h) */
      if (!(v = cli_value(argc, argv, &i)) || cli_double(a, v, 1e-6, 1048576.0, &av.max_file_mb))
        return EXIT_USAGE;
    } else if (strcmp(a, "--import-timeout") == 0) {
      if (!(v = cli_value(argc, argv, &i)) ||
          cli_double(a, v, 0.1, 86400.0, &av.import_timeout_s))
        return EXIT_USAGE;
    } else if (strcmp(a, "--import-mem-mb") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_double(a, v, 16.0, 1048576.0, &av.import_mem_mb))
        return EXIT_USAGE;
    } else if (strcmp(a, "--settle") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_double(a, v, 0.0, 1e6, &s.settle))
        return EXIT_USAGE;
    } else if (strcmp(a, "--reference") == 0) {
      reference = 1;
    } else if (strcmp(a, "--truth") == 0) {
      reference = truth = 1;
    } else if (strcmp(a, "--cache") == 0) {
      if (!(cache_opt = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--json") == 0) {
      if (!(json_path = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--out") == 0) {
      if (!(out_dir = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--skin") == 0) {
      if (!(skin_path = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--skin-max-distance") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_double(a, v, 0.0, 1e9, &skin_max_distance))
        return EXIT_USAGE;
    } else {
      cli_error("run: unknown option '%s' (see skinsim help)", a);
      return EXIT_USAGE;
    }
  }
  const int avatar = avatar_args_given(&av);
  if (!scene_name == !avatar) {
    cli_error("run needs one body: --scene NAME (skinsim scenes lists them), or an avatar "
              "(--avatar demo, --urdf FILE --motion M, --asset FILE)");
    return EXIT_USAGE;
  }
  if (!avatar && (av.max_file_mb > 0.0 || av.import_timeout_s > 0.0 || av.import_mem_mb > 0.0)) {
    cli_error("--max-file-mb, --import-timeout and --import-mem-mb limit the reading of avatar "
              "files; a built-in scene reads none");
    return EXIT_USAGE;
  }
  if (avatar && tris) {
    cli_error("--tris sizes a built-in scene; for the demo avatar use --avatar-tris");
    return EXIT_USAGE;
  }
  if (skin_path && (av.region || reference)) {
    cli_error("--skin runs its own skin: it goes with neither --region (a mask of the body's "
              "faces) nor --reference/--truth (computed on the body's own skin)");
    return EXIT_USAGE;
  }
  if (json_path && cli_check_json(json_path)) return EXIT_USAGE; /* before the run, not after */
  if (out_dir && check_out_dir(out_dir)) return EXIT_USAGE;
  char cache_dir[4096] = "";
  if (reference && measure_cache_dir(cache_opt, cache_dir, sizeof cache_dir)) return EXIT_USAGE;
  char err[512] = "";
  ss_scene *scene = NULL;
  avatar_body *ab = NULL;
  ss_body body;
  const char *label = scene_name;
  if (scene_name) {
    if (ss_scene_create(&scene, scene_name, tris, err, sizeof err)) {
      cli_error("%s", err);
      return EXIT_USAGE;
    }
    body = ss_body_of_scene(scene);
  } else {
    int status = avatar_body_open(&ab, &av, &body, &s.sim.face_mask, err, sizeof err);
    if (status) {
      cli_error("%s", err);
      return status == SS_E_NOMEM || status == SS_E_SOLVER ? EXIT_RUN_FAILED : EXIT_USAGE;
    }
    label = av.asset ? av.asset : av.urdf ? av.urdf : "demo";
  }
  skin_file *sf = NULL;
  ss_sim_mesh skin_mesh;
  int skin_carried = 0;
  if (skin_path) {
    int status = skin_file_open(&sf, skin_path, &body, avatar_body_rigid_parts(ab),
                                skin_max_distance, &skin_mesh, &s.sim.face_mask, &skin_carried,
                                err, sizeof err);
    if (status) {
      cli_error("%s", err);
      avatar_body_close(ab);
      ss_scene_destroy(scene);
      return status == SS_E_NOMEM ? EXIT_RUN_FAILED : EXIT_USAGE;
    }
    s.skin = &skin_mesh;
  }
  frame_writer writer = {out_dir, &body, ""};
  progress bar;
  progress_begin(&bar, scene_name ? scene_name : "avatar");
  measure_result res;
  int status = measure_run(&body, &s, NULL, reference ? cache_dir : NULL, truth, out_dir ? write_frame : NULL,
                           &writer, progress_update, &bar, &res, err, sizeof err);
  res.st.triangles_carried = skin_path ? skin_carried : avatar_body_carried(ab);
  const ss_run_stats st = res.st;
  progress_end(&bar);
  ss_scene_destroy(scene);
  if (status) {
    skin_file_close(sf);
    avatar_body_close(ab);
    cli_error("run failed: %s", err);
    return status == SS_E_ARG ? EXIT_USAGE : EXIT_RUN_FAILED;
  }
  if (writer.error[0]) {
    skin_file_close(sf);
    avatar_body_close(ab);
    cli_error("%s", writer.error);
    return EXIT_RUN_FAILED;
  }
  if (json_path) {
    FILE *f = cli_open_json(json_path);
    if (!f) { /* as an uncreatable --out */
      avatar_body_close(ab);
      return EXIT_USAGE;
    }
    json_out j;
    json_begin(&j, f);
    measure_fields(&j, label, &s, &res);
    json_end(&j);
    cli_close_json(f);
  }
  if (!json_path || strcmp(json_path, "-") != 0)
    printf("%s/%s/%s: %d triangles, %d frames: %.2f ms/frame (median; walk %.3f ms, %.1f%%), "
           "%.1f iterations/frame, %lld snags, %lld failures, hug rms %.3f max %.3f edges, "
           "area ratio [%.3f, %.3f], hash %016llx\n",
           label, ss_method_name(s.sim.mover.method), ss_solver_name(s.sim.solver),
           st.triangles, st.frames, st.ms_per_frame_median, st.walk_ms_per_frame_median,
           100.0 * st.walk_share, st.iterations_mean, st.snags, st.failures, st.hug_rms,
           st.hug_max, st.min_area_ratio, st.max_area_ratio, st.final_hash);
  if (!json_path || strcmp(json_path, "-") != 0)
    printf("inverted faces max %d (%d more over body folds; body faces folded max %d; turned "
           "plainly max %d), inside max %.3f edges, slide max %.3f edges (%.4g m), vertices over "
           "an edge from the body max %d; triangles %d simulated, %d carried rigidly\n",
           st.inverted_faces_max, st.inverted_over_folds_max, st.body_folds_max,
           st.faces_turned_max, st.inside_max, st.slide_max, st.slide_max_m, st.hug_far_max,
           st.region_faces, st.triangles_carried);
  if (s.settle > 0.0 && (!json_path || strcmp(json_path, "-") != 0))
    printf("rest return after %.3g s settle (%d frames): rms %.4f max %.4f edges (%.4g m), "
           "anchors at most %.4f edges from home\n",
           s.settle, st.settle_frames, st.rest_error_rms, st.rest_error_max,
           st.rest_error_max_m, st.rest_slide_max);
  if (reference && (!json_path || strcmp(json_path, "-") != 0))
    printf("error vs reference %.4g mean edge lengths (reference %016llx, %s, %.0f ms)\n",
           res.error_vs_reference, res.reference_key,
           res.reference_cache_hit ? "from the cache" : "computed", res.reference_ms);
  if (truth && (!json_path || strcmp(json_path, "-") != 0))
    printf("error vs truth %.4g mean edge lengths (truth %016llx, %s, %.0f ms)\n",
           res.error_vs_truth, res.truth_key, res.truth_cache_hit ? "from the cache" : "computed",
           res.truth_ms);
  skin_file_close(sf);
  avatar_body_close(ab);
  if (st.failures > 0) {
    cli_error("run failed: %lld of %d frames failed (a non-finite value, a triangle squeezed or "
              "stretched past [0.05, 20] of its rest area, or a step error)",
              st.failures, st.frames);
    return EXIT_RUN_FAILED;
  }
  return 0;
}
