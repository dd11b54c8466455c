/* skinsim: one measured run of the dynamic skin, optionally against its
 * reference (ss_reference.h) — shared by `skinsim run` and `skinsim bench` —
 * and its fields, written as JSON or as a CSV line. */
#ifndef SKINSIM_MEASURE_H
#define SKINSIM_MEASURE_H

#include "cli.h"
#include "ss_reference.h"
#include "ss_run.h"

typedef struct measure_result {
  ss_run_stats st;
  double fps;                /* the body's frame rate */
  int has_reference;
  double error_vs_reference; /* mean edge lengths */
  int reference_cache_hit, reference_cache_rejected;
  int reference_substeps;
  double reference_ms;       /* computing or reading the reference */
  unsigned long long reference_key;
  int has_truth;
  double error_vs_truth;     /* against the truth (ss_truth_settings), mean edge lengths */
  int truth_cache_hit;
  double truth_ms;
  unsigned long long truth_key;
  int has_base;
  double error_vs_base_reference; /* against the reference of the base model (see measure_run) */
} measure_result;

/* The cache folder: dir if given, else $XDG_CACHE_HOME/skin_sim or
 * $HOME/.cache/skin_sim; created if missing (with its parents). Returns 0,
 * or -1 with a message on stderr. */
int measure_cache_dir(const char *dir, char *out, int out_sz);

/* Runs s over body. With cache_dir non-NULL the run is compared with its
 * reference (computed or read from cache_dir first), and with base non-NULL
 * also with the reference of the model base (e.g. the default model, to see
 * what an option changes), and with truth non-zero also with the truth
 * (ss_truth_settings: walk, Newton converged, 16 substeps; the same for every
 * method and solver setting). on_frame (may be NULL)
 * is called after each frame as ss_run_body does. Returns SS_OK or an error
 * with a message in err. */
int measure_run(const ss_body *body, const ss_run_settings *s, const ss_run_settings *base,
                const char *cache_dir, int truth,
                ss_frame_fn on_frame, void *frame_user, ss_progress_fn progress_fn,
                void *progress_user, measure_result *res, char *err, int err_sz);

/* Every field of a run (JSON object, CSV header or CSV row: see csv_begin).
 * The caller has begun j and ends it. */
void measure_fields(json_out *j, const char *scene, const ss_run_settings *s,
                    const measure_result *r);

#endif
