/* skinsim: the skin_sim core from the command line, no ROS needed.
 * One subcommand per job; each parses its own options (see usage()). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"

static void usage(FILE *f) {
  fputs(
      "usage: skinsim COMMAND [options]\n"
      "\n"
      "commands:\n"
      "  scenes                      list the built-in scenes: name, triangles, frames, what it stresses\n"
      "  track --scene NAME [--method walk|project|nring] [--rings N] [--tris N] [--frames N]\n"
      "        [--max-steps N] [--lift L] [--json FILE|-]\n"
      "                              the anchor experiment without dynamics: anchors ride on the\n"
      "                              moving body, are pulled towards where they were (lifted L mean\n"
      "                              edge lengths off the surface, default 0.1) and moved there by\n"
      "                              the method; counts snags and failures\n"
      "  compare [--frames N]        every scene with every method: the table of where methods snag\n"
      "  run BODY [--frames N] [SETTINGS] [--settle SECONDS] [--truth] [--inside-every N]\n"
      "        [--reference [--cache DIR]] [--json FILE|-] [--out DIR]\n"
      "                              the dynamic skin over a scene: one step per frame; JSON\n"
      "                              summary (speed, snags, failures, hugging, area ratios,\n"
      "                              final_hash); --out writes skin_NNNN.ply and body_NNNN.ply;\n"
      "                              --reference adds error_vs_reference: RMS distance to a\n"
      "                              reference run (16 substeps, Newton to tol 1e-6), cached in\n"
      "                              --cache DIR (default $XDG_CACHE_HOME/skin_sim or\n"
      "                              ~/.cache/skin_sim), divided by the mean edge length\n"      "        BODY is a built-in scene: --scene NAME [--tris N]\n"
#ifdef SS_HAVE_AVATAR
      "        or an avatar:  --avatar demo [--avatar-tris N] [--motion arms|elbows|twist|all|CSV]\n"
      "                       --urdf FILE [--mesh FILE] --motion CSV|sweep|NAME\n"
      "                              [--package-path NAME=DIR,...]  (sweep: every joint swings)\n"
      "                              [--mesh-up-axis ignore|file] [--primitive-edge M]\n"
      "                       --asset FILE [--anim NAME|INDEX] [--asset-scale M]\n"
      "                       [--region LINK,...]  simulate only the skin of these links\n"
      "                       [--max-file-mb MB] [--import-timeout S] [--import-mem-mb MB]\n"
      "                                            mesh files over MB (256) are refused; an import\n"
      "                                            runs in a child stopped after S s (60) or MB\n"
      "                                            more memory (4096)\n"
      "                       [--strict-limits]    joint values outside the URDF limits are an\n"
      "                                            error (else clamped with one warning)\n"
      "        [--skin FILE [--skin-max-distance M]]  a skin mesh of its own over the body (in\n"
      "                              its frame and units at rest), bound by closest point; a\n"
      "                              vertex farther than M (0.05 m) is refused. Skin pieces over\n"
      "                              one rigid link (and, without --skin, the body's own) are\n"
      "                              carried with it, not simulated (JSON triangles_carried)\n"
#endif

      "  bench --out DIR [--quick] [--sweeps S,...] [--cache DIR] [--no-plot] [--plot-script FILE]\n"
      "        [--python EXE]\n"
      "                              speed against accuracy: a sweep of methods, solvers,\n"
      "                              iterations, substeps, sizes and options over the scenes\n"
      "                              and avatars; DIR/results.csv and charts (pareto, stability,\n"
      "                              scaling, breakdown, options .png; stability.md, options.md).\n"
      "                              --quick: small sizes, a few minutes; full: under 30 minutes;\n"
      "                              --sweeps: only these of methods, solvers, substeps,\n"
      "                              scaling, options, rest (and only their charts)\n"
      "  bench --out DIR --truth-doubling MAX [--bodies B,...] [--truth-tol TOL] [SETTINGS]\n"
      "                              is the truth converged? per body of the sweep the truth at\n"
      "                              16, 32, .. MAX substeps, each doubling's RMS difference\n"
      "                              against the smallest error of walk/project/nring 2\n"
      "                              (DIR/truth_doubling.csv, .md)\n"
      "  settings [--tsv|--markdown] the simulation settings: name (the node's ~parameter),\n"
      "                              flag, type, default, range, unit, how a live change\n"
      "                              applies (step, refactor, recreate), help; --tsv for\n"
      "                              scripts, --markdown the manual's table\n"
      "  help                        this text\n"
      "\n"
      "exit status: 0 ok, 1 the run failed, 2 bad usage or input\n"
      "\n"
      "SETTINGS of run (from the settings table; --no-barycenters = --barycenters false):\n",
      f);
  cli_settings_help(f);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    usage(stderr);
    return EXIT_USAGE;
  }
  const char *cmd = argv[1];
  if (strcmp(cmd, "help") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0) {
    usage(stdout);
    return 0;
  }
  if (strcmp(cmd, "scenes") == 0) return cmd_scenes(argc - 1, argv + 1);
  if (strcmp(cmd, "track") == 0) return cmd_track(argc - 1, argv + 1);
  if (strcmp(cmd, "compare") == 0) return cmd_compare(argc - 1, argv + 1);
  if (strcmp(cmd, "run") == 0) return cmd_run(argc - 1, argv + 1);
  if (strcmp(cmd, "bench") == 0) return cmd_bench(argc - 1, argv + 1);
  if (strcmp(cmd, "settings") == 0) return cmd_settings(argc - 1, argv + 1);
  cli_error("unknown command '%s' (try: skinsim help)", cmd);
  return EXIT_USAGE;
}
