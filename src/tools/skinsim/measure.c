/* skinsim: a measured run against its reference (see measure.h). */
#include "measure.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int measure_cache_dir(const char *dir, char *out, int out_sz) {
  const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
  if (dir && *dir) snprintf(out, (size_t)out_sz, "%s", dir);
  else if (xdg && *xdg) snprintf(out, (size_t)out_sz, "%s/skin_sim", xdg);
  else if (home && *home) snprintf(out, (size_t)out_sz, "%s/.cache/skin_sim", home);
  else {
    cli_error("no cache folder: give --cache DIR (neither XDG_CACHE_HOME nor HOME is set)");
    return -1;
  }
  /* mkdir -p */
  for (char *p = out + 1;; p++) {
    char c = *p;
    if (c == '/' || c == '\0') {
      *p = '\0';
      int bad = mkdir(out, 0777) != 0 && errno != EEXIST;
      *p = c;
      if (bad) {
        cli_error("cannot create cache folder '%s': %s", out, strerror(errno));
        return -1;
      }
    }
    if (c == '\0') break;
  }
  struct stat sb;
  if (stat(out, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
    cli_error("cache folder '%s' is not a folder", out);
    return -1;
  }
  return 0;
}

int measure_run(const ss_body *body, const ss_run_settings *s, const ss_run_settings *base,
                const char *cache_dir, int truth, ss_frame_fn on_frame, void *frame_user,
                ss_progress_fn progress_fn, void *progress_user, measure_result *res, char *err,
                int err_sz) {
  memset(res, 0, sizeof *res);
  res->fps = body->fps;
  if (!cache_dir)
    return ss_run_body(body, s, on_frame, frame_user, progress_fn, progress_user, &res->st, err,
                       err_sz);
  /* the run, its reference and its truth run on one model, built once
   * (ss_reference_settings keeps it where it is the reference's) */
  ss_model *model = NULL;
  ss_run_settings shared = *s;
  if (!s->model) {
    int st = ss_run_model_create(&model, body, s, err, err_sz);
    if (st) return st;
    shared.model = model;
  }
  s = &shared;
  ss_reference *ref = NULL, *base_ref = NULL, *truth_ref = NULL;
  int status = ss_reference_get(&ref, body, s, cache_dir, NULL, NULL, err, err_sz);
  if (!status && base)
    status = ss_reference_get(&base_ref, body, base, cache_dir, NULL, NULL, err, err_sz);
  if (!status && truth) {
    /* the truth is the reference of its own settings (their reference is themselves) */
    const ss_run_settings ts = ss_truth_settings(s);
    status = ss_reference_get(&truth_ref, body, &ts, cache_dir, NULL, NULL, err, err_sz);
  }
  if (status) {
    ss_reference_destroy(ref);
    ss_reference_destroy(base_ref);
    ss_model_destroy(model);
    return status;
  }
  if (truth_ref) {
    res->has_truth = 1;
    res->truth_cache_hit = truth_ref->cache_hit;
    res->truth_ms = truth_ref->ms;
    res->truth_key = truth_ref->key;
  }
  res->has_reference = 1;
  res->has_base = base != NULL;
  res->reference_cache_hit = ref->cache_hit;
  res->reference_cache_rejected = ref->cache_rejected;
  res->reference_ms = ref->ms;
  res->reference_key = ref->key;
  res->reference_substeps = ss_reference_settings(s).sim.substeps;
  /* the three errors in one pass (a NULL reference: error 0) */
  const ss_reference *refs[3] = {ref, base_ref, truth_ref};
  double errors[3];
  status = ss_run_ref_errors(body, s, refs, 3, errors, on_frame, frame_user, progress_fn,
                             progress_user, &res->st, err, err_sz);
  res->error_vs_reference = errors[0];
  res->error_vs_base_reference = errors[1];
  res->error_vs_truth = errors[2];
  ss_reference_destroy(truth_ref);
  ss_reference_destroy(ref);
  ss_reference_destroy(base_ref);
  ss_model_destroy(model);
  return status;
}

void measure_fields(json_out *j, const char *scene, const ss_run_settings *s,
                    const measure_result *r) {
  const ss_run_stats *st = &r->st;
  json_str(j, "scene", scene);
  json_int(j, "region_faces", st->region_faces);
  json_str(j, "method", ss_method_name(s->sim.mover.method));
  if (s->sim.mover.method == SS_METHOD_NRING) json_int(j, "nring_rings", s->sim.mover.nring_rings);
  else if (j->mode != JSON_OBJECT) json_null(j, "nring_rings"); /* a CSV column for every row */
  json_str(j, "solver", ss_solver_name(s->sim.solver));
  json_int(j, "triangles", st->triangles);
  json_int(j, "skin_triangles", st->skin_triangles);
  json_int(j, "vertices", st->vertices);
  json_int(j, "anchors", st->anchors);
  json_int(j, "dof", st->dof);
  json_int(j, "frames", st->frames);
  json_num(j, "dt", r->fps > 0.0 ? 1.0 / r->fps : 0.0); /* frame time step */
  json_int(j, "substeps", s->sim.substeps);
  json_int(j, "threads", s->sim.threads);
  json_int(j, "iterations", s->sim.iterations);
  json_num(j, "tol", s->sim.tol);
  json_num(j, "ms_per_frame_median", st->ms_per_frame_median);
  json_num(j, "walk_ms_per_frame_median", st->walk_ms_per_frame_median);
  json_num(j, "walk_share", st->walk_share);
  json_num(j, "walk_steps_per_update", st->walk_steps_per_update);
  json_num(j, "assemble_ms_per_frame_median", st->assemble_ms_per_frame_median);
  json_num(j, "factor_ms_per_frame_median", st->factor_ms_per_frame_median);
  json_num(j, "solve_ms_per_frame_median", st->solve_ms_per_frame_median);
  json_num(j, "iterations_mean", st->iterations_mean);
  json_int(j, "snags", st->snags);
  json_int(j, "failures", st->failures);
  json_int(j, "stalled", st->stalled);
  json_int(j, "unconverged_frames", st->unconverged);
  json_int(j, "anchors_at_boundary", st->anchors_at_boundary);
  json_int(j, "anchors_at_crease", st->anchors_at_crease);
  json_int(j, "anchors_at_step_limit", st->anchors_at_step_limit);
  json_num(j, "min_area_ratio", st->min_area_ratio);
  json_num(j, "max_area_ratio", st->max_area_ratio);
  json_num(j, "hug_rms", st->hug_rms);
  json_num(j, "hug_max", st->hug_max);
  json_num(j, "mean_edge_length", st->mean_edge_length);
  json_int(j, "inverted_faces_max", st->inverted_faces_max);
  json_int(j, "inverted_over_folds_max", st->inverted_over_folds_max);
  json_int(j, "faces_turned_max", st->faces_turned_max);
  json_int(j, "hug_far_max", st->hug_far_max);
  json_int(j, "triangles_simulated", st->region_faces);
  json_int(j, "triangles_carried", st->triangles_carried);
  json_int(j, "body_folds_max", st->body_folds_max);
  json_num(j, "inside_max", st->inside_max);
  json_int(j, "inside_every", s->inside_every);
  json_int(j, "inside_samples", st->inside_samples);
  json_num(j, "inside_mean", st->inside_mean);
  json_int(j, "inside_count_max", st->inside_count_max);
  json_num(j, "inside_buried_max", st->inside_buried_max);
  json_num(j, "inside_clean_max", st->inside_clean_max);
  json_int(j, "inside_clean_over_005_max", st->inside_clean_over_005_max);
  json_int(j, "inside_clean_over_01_max", st->inside_clean_over_01_max);
  json_int(j, "inside_clean_worst_frame", st->inside_clean_worst_frame);
  json_num(j, "slide_max", st->slide_max);
  json_num(j, "slide_max_m", st->slide_max_m);
  json_num(j, "settle", s->settle);
  if (s->settle > 0.0) {
    json_int(j, "settle_frames", st->settle_frames);
    json_num(j, "rest_error_rms", st->rest_error_rms);
    json_num(j, "rest_error_max", st->rest_error_max);
    json_num(j, "rest_error_max_m", st->rest_error_max_m);
    json_num(j, "rest_slide_max", st->rest_slide_max);
  } else if (j->mode != JSON_OBJECT) {
    json_null(j, "settle_frames");
    json_null(j, "rest_error_rms");
    json_null(j, "rest_error_max");
    json_null(j, "rest_error_max_m");
    json_null(j, "rest_slide_max");
  }
  json_num(j, "young", s->sim.young);
  json_num(j, "poisson", s->sim.poisson);
  json_num(j, "anchor_stiffness", s->sim.anchor_stiffness);
  json_int(j, "barycenter_anchors", s->sim.barycenter_anchors);
  json_num(j, "bending", s->sim.bending);
  json_num(j, "gravity", s->sim.gravity[2] != 0.0 ? -s->sim.gravity[2] : 0.0);
  json_num(j, "damping", s->sim.damping);
  json_num(j, "slide", s->sim.slide);
  json_num(j, "tether", s->sim.tether);
  json_num(j, "orient", s->sim.orient);
  json_num(j, "compression", s->sim.compression);
  json_hex(j, "final_hash", st->final_hash);
  if (r->has_reference) {
    json_num(j, "error_vs_reference", r->error_vs_reference);
    json_int(j, "reference_cache_hit", r->reference_cache_hit);
    json_int(j, "reference_cache_rejected", r->reference_cache_rejected);
    json_int(j, "reference_substeps", r->reference_substeps);
    json_num(j, "reference_ms", r->reference_ms);
    json_hex(j, "reference_key", r->reference_key);
    if (r->has_base) json_num(j, "error_vs_base_reference", r->error_vs_base_reference);
    else json_null(j, "error_vs_base_reference");
    if (r->has_truth) {
      json_num(j, "error_vs_truth", r->error_vs_truth);
      json_int(j, "truth_cache_hit", r->truth_cache_hit);
      json_num(j, "truth_ms", r->truth_ms);
      json_hex(j, "truth_key", r->truth_key);
    } else if (j->mode != JSON_OBJECT) {
      json_null(j, "error_vs_truth");
      json_null(j, "truth_cache_hit");
      json_null(j, "truth_ms");
      json_null(j, "truth_key");
    }
  } else if (j->mode != JSON_OBJECT) {
    json_null(j, "error_vs_reference");
    json_null(j, "reference_cache_hit");
    json_null(j, "reference_cache_rejected");
    json_null(j, "reference_substeps");
    json_null(j, "reference_ms");
    json_null(j, "reference_key");
    json_null(j, "error_vs_base_reference");
    json_null(j, "error_vs_truth");
    json_null(j, "truth_cache_hit");
    json_null(j, "truth_ms");
    json_null(j, "truth_key");
  }
}
