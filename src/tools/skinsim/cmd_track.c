/* skinsim scenes | track: the built-in scenes and the anchor tracking experiment. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "ss_track.h"

int cmd_scenes(int argc, char **argv) {
  if (argc > 1) {
    cli_error("scenes takes no arguments (got '%s')", argv[1]);
    return EXIT_USAGE;
  }
  printf("%-10s %9s %7s  %s\n", "scene", "triangles", "frames", "stresses");
  for (int i = 0; i < ss_scene_count(); i++) {
    ss_scene *scene = NULL;
    char err[256] = "";
    if (ss_scene_create(&scene, ss_scene_name(i), 0, err, sizeof err)) {
      cli_error("scene %s: %s", ss_scene_name(i), err);
      return EXIT_RUN_FAILED;
    }
    printf("%-10s %9d %7d  %s\n", ss_scene_name(i), ss_scene_nface(scene),
           ss_scene_default_frames(scene), ss_scene_about(i));
    ss_scene_destroy(scene);
  }
  return 0;
}

void track_json(FILE *f, const char *scene, const ss_track_settings *s, const ss_track_stats *st) {
  json_out j;
  json_begin(&j, f);
  json_str(&j, "scene", scene);
  json_str(&j, "method", ss_method_name(s->mover.method));
  if (s->mover.method == SS_METHOD_NRING) json_int(&j, "nring_rings", s->mover.nring_rings);
  json_int(&j, "triangles", st->triangles);
  json_int(&j, "vertices", st->vertices);
  json_int(&j, "anchors", st->anchors);
  json_int(&j, "frames", st->frames);
  json_int(&j, "updates", st->updates);
  json_int(&j, "snags", st->snags);
  json_int(&j, "failures", st->failures);
  json_int(&j, "anchors_at_boundary", st->anchors_at_boundary);
  json_int(&j, "anchors_at_crease", st->anchors_at_crease);
  json_int(&j, "anchors_at_step_limit", st->anchors_at_step_limit);
  json_num(&j, "mean_walk_steps", st->mean_steps);
  json_num(&j, "ms_per_frame_median", st->ms_per_frame_median);
  json_num(&j, "ms_per_anchor_update_median", st->ms_per_anchor_update_median);
  json_num(&j, "mean_edge_length", st->mean_edge_length);
  json_num(&j, "lift", s->lift);
  json_num(&j, "snag_factor", s->snag_factor);
  json_int(&j, "walk_max_steps", s->mover.walk_max_steps);
  json_end(&j);
}

int cmd_track(int argc, char **argv) {
  const char *scene_name = NULL, *json_path = NULL;
  int tris = 0;
  ss_track_settings s = ss_track_default_settings();
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = NULL;
    const int mover_opt = cli_mover_option(argc, argv, &i, &s.mover);
    if (mover_opt < 0) return EXIT_USAGE;
    if (mover_opt > 0) continue;
    if (strcmp(a, "--scene") == 0) {
      if (!(scene_name = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else if (strcmp(a, "--tris") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_int(a, v, 1, 2000000, &tris)) return EXIT_USAGE;
    } else if (strcmp(a, "--frames") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_int(a, v, 1, 1000000, &s.frames))
        return EXIT_USAGE;
    } else if (strcmp(a, "--lift") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_double(a, v, 0, 100, &s.lift)) return EXIT_USAGE;
    } else if (strcmp(a, "--json") == 0) {
      if (!(json_path = cli_value(argc, argv, &i))) return EXIT_USAGE;
    } else {
      cli_error("track: unknown option '%s' (see skinsim help)", a);
      return EXIT_USAGE;
    }
  }
  if (!scene_name) {
    cli_error("track needs --scene NAME (skinsim scenes lists them)");
    return EXIT_USAGE;
  }
  if (json_path && cli_check_json(json_path)) return EXIT_USAGE; /* before the run, not after */
  char err[256] = "";
  ss_scene *scene = NULL;
  if (ss_scene_create(&scene, scene_name, tris, err, sizeof err)) {
    cli_error("%s", err);
    return EXIT_USAGE;
  }
  progress bar;
  progress_begin(&bar, scene_name);
  ss_track_stats st;
  int status = ss_track_run(scene, &s, progress_update, &bar, &st, err, sizeof err);
  progress_end(&bar);
  ss_scene_destroy(scene);
  if (status) {
    cli_error("track failed: %s", err);
    return EXIT_RUN_FAILED;
  }
  if (json_path) {
    FILE *f = cli_open_json(json_path);
    if (!f) return EXIT_USAGE; /* as an uncreatable --out */
    track_json(f, scene_name, &s, &st);
    cli_close_json(f);
  }
  if (!json_path || strcmp(json_path, "-") != 0)
    printf("%s/%s: %d triangles, %d anchors, %d frames: %lld snags, %lld failures, "
           "%.3f ms/frame (median), %.1f ns/anchor\n",
           scene_name, ss_method_name(s.mover.method), st.triangles, st.anchors, st.frames,
           st.snags, st.failures, st.ms_per_frame_median, st.ms_per_anchor_update_median * 1e6);
  return 0;
}
