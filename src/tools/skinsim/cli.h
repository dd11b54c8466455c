/* skinsim: helpers shared by the subcommands — argument parsing with clear
 * errors, a small JSON object writer, and a progress bar for terminals. */
#ifndef SKINSIM_CLI_H
#define SKINSIM_CLI_H

#include <stdio.h>

/* Exit codes: 0 ok, 1 the run failed, 2 bad usage or input. */
enum { EXIT_RUN_FAILED = 1, EXIT_USAGE = 2 };

/* Prints "skinsim: <message>" to stderr. */
void cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Parse the value of option `opt`; on error print one message and return -1. */
int cli_int(const char *opt, const char *text, long min, long max, int *out);
int cli_double(const char *opt, const char *text, double min, double max, double *out);

/* The anchor-method options shared by track and run: --method walk|project|nring,
 * --rings N, --max-steps N. Returns 1 if argv[*i] was one (value consumed,
 * *i advanced), 0 if it is some other option, -1 on a bad value (message
 * printed). */
struct ss_mover_settings;
int cli_mover_option(int argc, char **argv, int *i, struct ss_mover_settings *mover);

/* A simulation setting from the table (ss_settings.h) given as `--FLAG VALUE`:
 * returns 1 if argv[*i] is one (value parsed and range-checked into *sim, *i
 * advanced), 0 if it is no setting flag, -1 on a bad value (one message naming
 * the flag, the value and the range). --gravity also takes one number G for
 * 0 0 -G; --no-barycenters is --barycenters false. */
struct ss_sim_settings;
int cli_setting_option(int argc, char **argv, int *i, struct ss_sim_settings *sim);
/* The settings flags, one per line ("  --young N/m ..."), for the help text. */
void cli_settings_help(FILE *f);

/* Returns the value after argv[*i] (advancing *i), or NULL with a message. */
const char *cli_value(int argc, char **argv, int *i);

/* A flat JSON object written as it goes; the same calls write one CSV line
 * instead (csv_begin: the keys as a header line, or the values as a row). */
enum { JSON_OBJECT = 0, CSV_HEADER = 1, CSV_ROW = 2 };
typedef struct json_out {
  FILE *f;
  int count;
  int mode;
} json_out;
void json_begin(json_out *j, FILE *f);
void csv_begin(json_out *j, FILE *f, int mode); /* CSV_HEADER or CSV_ROW; json_end ends the line */
void json_str(json_out *j, const char *key, const char *value);
void json_int(json_out *j, const char *key, long long value);
void json_num(json_out *j, const char *key, double value); /* non-finite -> null (CSV: empty) */
void json_null(json_out *j, const char *key);
void json_hex(json_out *j, const char *key, unsigned long long value);
void json_end(json_out *j);

/* Checks, before a run, that the --json destination can be written: "-", an
 * existing writable file, or a new name in an existing writable folder.
 * 0, or -1 with a message naming the file and the cause (exit 2). */
int cli_check_json(const char *path);
/* Opens the --json destination: "-" is stdout. Returns NULL with a message. */
FILE *cli_open_json(const char *path);
void cli_close_json(FILE *f);

/* Progress bar on stderr, drawn only when stderr is a terminal. */
typedef struct progress {
  int enabled;
  const char *label;
  double start_ms;
} progress;
void progress_begin(progress *p, const char *label);
int progress_update(void *p, int done, int total); /* an ss_progress_fn */
void progress_end(progress *p);

#endif
