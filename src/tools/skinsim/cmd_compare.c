/* skinsim compare: the built-in demo — every scene, every anchor method, one
 * table. Shows where projection and n-ring snag and the walk does not. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"

int cmd_compare(int argc, char **argv) {
  int frames = 0;
  for (int i = 1; i < argc; i++) {
    const char *v = NULL;
    if (strcmp(argv[i], "--frames") == 0) {
      if (!(v = cli_value(argc, argv, &i)) || cli_int(argv[i - 1], v, 1, 100000, &frames))
        return EXIT_USAGE;
    } else {
      cli_error("compare: unknown option '%s'", argv[i]);
      return EXIT_USAGE;
    }
  }
  static const int methods[] = {SS_METHOD_WALK, SS_METHOD_PROJECT, SS_METHOD_NRING};
  printf("Anchor tracking on every built-in scene (skinsim track): an update is a snag when it\n"
         "lands further along the surface than 3 |a* - a0| + one edge length from its start.\n\n");
  printf("%-10s %-8s %9s %8s %7s %9s %9s %9s %12s\n", "scene", "method", "triangles", "anchors",
         "frames", "snags", "failures", "creases", "ns/anchor");
  for (int si = 0; si < ss_scene_count(); si++) {
    for (int mi = 0; mi < 3; mi++) {
      char err[256] = "";
      ss_scene *scene = NULL;
      if (ss_scene_create(&scene, ss_scene_name(si), 0, err, sizeof err)) {
        cli_error("%s", err);
        return EXIT_RUN_FAILED;
      }
      ss_track_settings s = ss_track_default_settings();
      s.mover.method = methods[mi];
      s.frames = frames;
      progress bar;
      progress_begin(&bar, ss_scene_name(si));
      ss_track_stats st;
      int status = ss_track_run(scene, &s, progress_update, &bar, &st, err, sizeof err);
      progress_end(&bar);
      ss_scene_destroy(scene);
      if (status) {
        cli_error("%s/%s: %s", ss_scene_name(si), ss_method_name(methods[mi]), err);
        return EXIT_RUN_FAILED;
      }
      printf("%-10s %-8s %9d %8d %7d %9lld %9lld %9lld %12.1f\n", ss_scene_name(si),
             ss_method_name(methods[mi]), st.triangles, st.anchors, st.frames, st.snags,
             st.failures, st.anchors_at_crease, st.ms_per_anchor_update_median * 1e6);
      fflush(stdout);
    }
  }
  return 0;
}
