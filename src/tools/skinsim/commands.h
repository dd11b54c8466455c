/* skinsim's subcommands: each takes its own argv (argv[0] is its name) and
 * returns the process exit code. */
#ifndef SKINSIM_COMMANDS_H
#define SKINSIM_COMMANDS_H

#include <stdio.h>

#include "ss_run.h"
#include "ss_track.h"

int cmd_scenes(int argc, char **argv);
int cmd_track(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_run(int argc, char **argv);
int cmd_bench(int argc, char **argv);
/* skinsim bench --truth-doubling MAX (cmd_bench_truth.c): asset NULL if absent; sim the
 * physical settings (solver and method settings are the truth's); bodies NULL (all) or a
 * comma-separated list of body names (scenes, demo, the asset's file name); truth_tol > 0
 * replaces the truth's Newton tolerance. */
int bench_truth_doubling(const char *out_dir, const char *cache_dir, int max_substeps, int quick,
                         const char *asset, const ss_sim_settings *sim, const char *bodies,
                         double truth_tol);
int cmd_settings(int argc, char **argv);

void track_json(FILE *f, const char *scene, const ss_track_settings *s, const ss_track_stats *st);

#endif
