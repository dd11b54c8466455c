/* skin_sim lab (src/lab, not installed): reference runs and the error of a run against its reference
 * (doc/model.md, "Accuracy").
 *
 * The reference of a run configuration is the same body, skin model and
 * anchor method stepped with a much smaller time step (SS_REFERENCE_SUBSTEPS
 * implicit Euler steps per frame, or the run's own substeps if more) by
 * Newton converged tightly (SS_REFERENCE_TOL, or the run's own tolerance if
 * tighter, within SS_REFERENCE_ITERATIONS iterations). `slide` acts per substep (ss_sim.h), so the reference slides
 * with the per-substep fraction that leaves an anchor the same share of its
 * way per frame: 1 - (1 - slide)^(substeps / reference substeps). A run
 * configured like its reference gets exactly its settings, hence error 0.
 *
 * Its skin positions at every frame are cached in a folder, one file per
 * reference named by a 64-bit key: the hash of a text describing everything
 * that determines them (the file format SS_REFERENCE_VERSION; SS_CODE_DIGEST,
 * the digest the build takes of the core's, the lab's and the public headers'
 * sources, so that a reference computed by other simulation code is never
 * reused; the body's rest mesh and its pose at every frame, the frame count
 * and rate, every setting of the reference's ss_sim_settings, the face mask).
 * A file is trusted only if its header (magic, version, key, sizes), its
 * exact size and the checksum of its contents all match; anything else is
 * recomputed and the file rewritten (through a temporary file and a rename).
 *
 * error_vs_reference = sqrt(mean over frames and skin vertices of
 * |x - x_ref|^2) / mean rest edge length of the body. A run whose skin is a
 * mesh of its own (settings->skin, e.g. coarser) is compared through points
 * of the reference skin: each of its vertices is bound at rest to the
 * closest point of the reference skin (face, barycentric) and that point is
 * followed through the reference frames. */
#ifndef SKIN_SIM_SS_REFERENCE_H
#define SKIN_SIM_SS_REFERENCE_H

#include "ss_run.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SS_REFERENCE_VERSION 11     /* the cache file's format */
#define SS_REFERENCE_SUBSTEPS 16
#define SS_REFERENCE_ITERATIONS 100
#define SS_REFERENCE_TOL 1e-6

/* The settings of the reference of run (skin NULL: the body's own welded skin). */
ss_run_settings ss_reference_settings(const ss_run_settings *run);

/* The TRUTH of run: one run per body, motion and physical settings that every
 * anchor method and solver setting is measured against (doc/model.md,
 * "Accuracy"): the paper's model at convergence, i.e. the reference of run
 * with the default `walk` anchor update (ss_mover_default_settings) and
 * exactly SS_REFERENCE_SUBSTEPS substeps, whatever the run's method, solver, iterations, tolerance and
 * substeps. It is a reference like any other (ss_reference_get of these
 * settings: the same key, cache file and checks), so the truth of a walk run
 * with 16 substeps or fewer is its own reference. */
ss_run_settings ss_truth_settings(const ss_run_settings *run);

typedef struct ss_reference {
  int frames;            /* frames 1..frames */
  int nvert, nface;      /* the reference skin */
  double *rest;          /* (nvert x 3) skin at rest */
  int *faces;            /* (nface x 3) */
  double *pos;           /* (frames x nvert x 3) skin after frame f at pos + (f-1) nvert 3 */
  double mean_edge_length; /* the body at rest */
  unsigned long long key;
  int cache_hit;         /* 1 if read from a valid cache file */
  int cache_rejected;    /* 1 if a cache file existed but was invalid (then recomputed) */
  double ms;             /* time to compute or read it */
  ss_run_stats stats;    /* of the reference run (zero when read from the cache) */
} ss_reference;

/* The cache key of the reference of run over body. SS_OK or an error (a
 * pose that fails). */
int ss_reference_key(const ss_body *body, const ss_run_settings *run, unsigned long long *key,
                     char *err, int err_sz);

/* The reference of run over body: read from cache_dir (an existing folder;
 * NULL: never cached) if a valid file is there, else computed and written
 * there. progress (may be NULL) reports the reference run's frames.
 * Returns SS_OK, or an error with a message (SS_E_IO: the file could not be
 * written; the computation's own errors). *out is NULL on error. */
int ss_reference_get(ss_reference **out, const ss_body *body, const ss_run_settings *run,
                     const char *cache_dir, ss_progress_fn progress, void *progress_user,
                     char *err, int err_sz);
void ss_reference_destroy(ss_reference *ref);

/* The running error of one run against a reference. */
typedef struct ss_ref_error ss_ref_error;
/* For a skin of nvert vertices (rest: nvert x 3, the run's skin at rest).
 * A skin identical to the reference's is compared vertex to vertex, any
 * other through closest points at rest (see above). */
int ss_ref_error_create(ss_ref_error **out, const ss_reference *ref, int nvert,
                        const double *rest, char *err, int err_sz);
void ss_ref_error_destroy(ss_ref_error *e);
/* Adds frame (1..ref->frames) of the run's skin positions (nvert x 3). */
void ss_ref_error_add(ss_ref_error *e, int frame, const double *pos);
/* RMS distance over the frames added, in mean edge lengths (0 if none). */
double ss_ref_error_value(const ss_ref_error *e);

/* Runs run over body (ss_run_body) and measures its skin against nref
 * references at once, frame by frame, so that no caller keeps its own frame
 * callback for it: errors[k] is ss_ref_error_value against refs[k] (0 for a
 * NULL refs[k]), set in every case, on an error over the frames run before
 * it. The run's own skin (ss_sim_skin_nvert / _rest at the first frame) is
 * compared, vertex to vertex if it is the reference's, else through closest
 * points (ss_ref_error_create). on_frame (may be NULL) is called after each
 * frame as by ss_run_body; progress (may be NULL) and stats are ss_run_body's.
 * Returns SS_OK or an error with a message: ss_run_body's, or that of
 * ss_ref_error_create (the run then stops at its first frame). */
int ss_run_ref_errors(const ss_body *body, const ss_run_settings *run,
                      const ss_reference *const *refs, int nref, double *errors,
                      ss_frame_fn on_frame, void *frame_user, ss_progress_fn progress,
                      void *progress_user, ss_run_stats *stats, char *err, int err_sz);

/* The RMS distance between two references a and b of the same body and
 * frames (e.g. the truth at 16 and at 32 substeps: is it converged?), in mean
 * edge lengths of b: a's skin positions added to an ss_ref_error of b at every
 * frame. NAN if a's skin cannot be bound to b's (ss_ref_error_create). */
double ss_ref_difference(const ss_reference *a, const ss_reference *b);

#ifdef __cplusplus
}
#endif
#endif
