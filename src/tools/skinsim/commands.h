/* skinsim's subcommands: each takes its own argv (argv[0] is its name) and
 * returns the process exit code. */
#ifndef SKINSIM_COMMANDS_H
#define SKINSIM_COMMANDS_H

#include <stdio.h>

#include "skin_sim/ss_run.h"
#include "skin_sim/ss_track.h"

int cmd_scenes(int argc, char **argv);
int cmd_track(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_run(int argc, char **argv);
int cmd_bench(int argc, char **argv);
/* skinsim bench --truth-doubling MAX (cmd_bench_truth.c): asset NULL if absent. */
int bench_truth_doubling(const char *out_dir, const char *cache_dir, int max_substeps, int quick,
                         const char *asset);
int cmd_settings(int argc, char **argv);

void track_json(FILE *f, const char *scene, const ss_track_settings *s, const ss_track_stats *st);

#endif
