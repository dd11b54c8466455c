/* The dynamic skin over a moving body (a built-in scene, an avatar),
 * measured (see ss_run.h). The
 * measurements are taken outside the timed step and never change the
 * simulation: a run with and without them gives the same bits. */
#include "skin_sim/ss_run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "snag.h"
#include "ss_err.h"
#include "ss_util.h"

#define AREA_RATIO_MIN 0.05
#define AREA_RATIO_MAX 20.0

ss_run_settings ss_run_default_settings(void) {
  ss_run_settings s;
  s.sim = ss_sim_default_settings();
  s.frames = 0;
  s.snag_factor = 3.0;
  s.skin = NULL;
  return s;
}

unsigned long long ss_hash_bytes(const void *data, size_t n) {
  const unsigned char *p = data;
  unsigned long long h = 1469598103934665603ULL;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}


static int scene_pose(void *user, double frame, double *pos) {
  ss_scene_pose(user, frame, pos);
  return SS_OK;
}

ss_body ss_body_of_scene(const ss_scene *scene) {
  ss_body b;
  b.nvert = ss_scene_nvert(scene);
  b.nface = ss_scene_nface(scene);
  b.rest = ss_scene_rest(scene);
  b.faces = ss_scene_faces(scene);
  b.frames = ss_scene_default_frames(scene);
  b.fps = ss_scene_fps(scene);
  b.pose = scene_pose;
  b.user = (void *)scene; /* posing does not change a scene */
  return b;
}

int ss_run_scene(const ss_scene *scene, const ss_run_settings *settings, ss_frame_fn on_frame,
                 void *frame_user, ss_progress_fn progress, void *progress_user,
                 ss_run_stats *stats, char *err, int err_sz) {
  if (!scene) return ss_fail(err, err_sz, SS_E_ARG, "run: NULL scene");
  ss_body body = ss_body_of_scene(scene);
  return ss_run_body(&body, settings, on_frame, frame_user, progress, progress_user, stats, err,
                     err_sz);
}

int ss_run_body(const ss_body *body, const ss_run_settings *settings, ss_frame_fn on_frame,
                void *frame_user, ss_progress_fn progress, void *progress_user,
                ss_run_stats *stats, char *err, int err_sz) {
  if (!body || !settings || !stats) return ss_fail(err, err_sz, SS_E_ARG, "run: NULL argument");
  if (!body->pose || !(body->fps > 0.0 && isfinite(body->fps)))
    return ss_fail(err, err_sz, SS_E_ARG, "run: the body needs a pose function and fps > 0");
  if (!(settings->snag_factor > 0.0 && isfinite(settings->snag_factor)))
    return ss_fail(err, err_sz, SS_E_ARG, "run: snag factor must be a finite number > 0");
  if (settings->frames < 0) return ss_fail(err, err_sz, SS_E_ARG, "run: frames must be >= 0");
  memset(stats, 0, sizeof *stats);
  const int nvert = body->nvert, nface = body->nface;
  const int frames = settings->frames > 0 ? settings->frames : (body->frames > 0 ? body->frames : 1);
  const double dt = 1.0 / body->fps;

  ss_sim *sim = NULL;
  int status;
  if (settings->skin) {
    status = ss_sim_create(&sim, nvert, body->rest, nface, body->faces, settings->skin,
                           &settings->sim, err, err_sz);
  } else {
    /* welded skin (a no-op copy where the body has no seams) */
    ss_weld *weld = NULL;
    status = ss_weld_create(&weld, nvert, body->rest, nface, body->faces, -1.0, err, err_sz);
    if (status) return status;
    ss_sim_mesh skin = {weld->nweld, weld->pos, nface, weld->faces};
    status = ss_sim_create(&sim, nvert, body->rest, nface, body->faces, &skin, &settings->sim,
                           err, err_sz);
    ss_weld_destroy(weld);
  }
  if (status) return status;
  const ss_topo *topo = ss_sim_body_topo(sim);
  const int nanchor = ss_sim_nanchors(sim), skin_nvert = ss_sim_skin_nvert(sim);
  const int skin_nface = ss_sim_skin_nface(sim);
  ss_frames *fr = NULL;
  ss_bvh *bvh = NULL;
  snag_judge judge = {0};
  status = ss_frames_create(&fr, nface);
  if (!status) status = ss_bvh_create(&bvh, topo);
  if (!status) status = snag_judge_init(&judge, topo);
  double *pos = malloc(sizeof(double) * 3 * (size_t)nvert);
  int *old_face = malloc(sizeof(int) * (size_t)nanchor);
  double *old_uv = malloc(sizeof(double) * 2 * (size_t)nanchor);
  double *rest_area = malloc(sizeof(double) * (size_t)skin_nface);
  double *ms = malloc(sizeof(double) * 5 * (size_t)(frames > 0 ? frames : 1));
  if (!status && !(pos && old_face && old_uv && rest_area && ms))
    status = SS_E_NOMEM;
  if (status) {
    ss_fail(err, err_sz, status, "run: out of memory for %d anchors", nanchor);
    goto done;
  }
  double *ms_total = ms, *ms_walk = ms + frames, *ms_asm = ms + 2 * frames,
         *ms_factor = ms + 3 * frames, *ms_solve = ms + 4 * frames;

  stats->triangles = nface;
  stats->skin_triangles = skin_nface;
  stats->vertices = skin_nvert;
  stats->anchors = nanchor;
  stats->dof = ss_sim_ndof(sim);
  stats->region_faces = skin_nface;
  if (settings->sim.face_mask) {
    stats->region_faces = 0;
    for (int f = 0; f < skin_nface; f++) stats->region_faces += settings->sim.face_mask[f] != 0;
  }
  stats->mean_edge_length = topo->mean_edge_length;
  stats->min_area_ratio = INFINITY;
  stats->max_area_ratio = 0.0;
  const double edge = topo->mean_edge_length;
  const int *skin_faces = ss_sim_skin_faces(sim);
  const double *skin_rest = ss_sim_skin_rest(sim);
  for (int f = 0; f < skin_nface; f++) {
    const double *a = skin_rest + 3 * skin_faces[3 * f], *b = skin_rest + 3 * skin_faces[3 * f + 1],
                 *c = skin_rest + 3 * skin_faces[3 * f + 2];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    rest_area[f] = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }

  double hug_sum2 = 0.0;
  long long hug_count = 0, iterations = 0, walk_steps = 0, anchor_updates = 0;
  double walk_total = 0.0, step_total = 0.0;
  int done_frames = 0;
  for (int frame = 1; frame <= frames; frame++) {
    memcpy(old_face, ss_sim_anchor_faces(sim), sizeof(int) * (size_t)nanchor);
    memcpy(old_uv, ss_sim_anchor_uv(sim), sizeof(double) * 2 * (size_t)nanchor);
    status = body->pose(body->user, (double)frame, pos);
    if (status) {
      ss_fail(err, err_sz, status, "run: the body's pose at frame %d failed (%s)", frame,
              ss_status_string(status));
      break;
    }
    ss_sim_stats st;
    char step_err[256] = "";
    int step_status = ss_sim_step(sim, pos, dt, &st, step_err, sizeof step_err);
    int frame_failed = step_status != SS_OK || st.failures > 0;
    ms_total[done_frames] = st.total_ms;
    ms_walk[done_frames] = st.walk_ms;
    ms_asm[done_frames] = st.assemble_ms;
    ms_factor[done_frames] = st.factor_ms;
    ms_solve[done_frames] = st.solve_ms;
    walk_total += st.walk_ms;
    step_total += st.total_ms;
    iterations += st.iterations;
    walk_steps += st.walk_steps;
    anchor_updates += st.anchors_moved;
    stats->stalled += st.stalled;
    stats->unconverged += !st.converged;
    stats->anchors_at_boundary += st.anchors_boundary;
    stats->anchors_at_crease += st.anchors_crease;
    stats->anchors_at_step_limit += st.anchors_step_limit;

    /* untimed measurements in the new pose */
    ss_frames_update(fr, topo, pos);
    ss_bvh_refit(bvh, pos);
    const double *x = ss_sim_skin_positions(sim);
    for (int f = 0; f < skin_nface; f++) {
      /* faces outside the simulated region are the body's own: not judged */
      if (!(rest_area[f] > 0.0) || (settings->sim.face_mask && !settings->sim.face_mask[f]))
        continue;
      const double *a = x + 3 * skin_faces[3 * f], *b = x + 3 * skin_faces[3 * f + 1],
                   *c = x + 3 * skin_faces[3 * f + 2];
      double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
             e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                     e1[0] * e2[1] - e1[1] * e2[0]};
      double ratio = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / rest_area[f];
      if (!isfinite(ratio)) ratio = INFINITY;
      if (ratio < stats->min_area_ratio) stats->min_area_ratio = ratio;
      if (ratio > stats->max_area_ratio) stats->max_area_ratio = ratio;
      if (!(ratio >= AREA_RATIO_MIN && ratio <= AREA_RATIO_MAX)) frame_failed = 1;
    }
    for (int v = 0; v < skin_nvert; v++) {
      int face;
      double uv[2];
      double d2 = ss_bvh_closest(bvh, pos, x + 3 * v, &face, uv);
      double d = sqrt(d2) / edge;
      if (!isfinite(d)) frame_failed = 1;
      hug_sum2 += d * d;
      hug_count++;
      if (d > stats->hug_max) stats->hug_max = d;
    }
    const int *new_face = ss_sim_anchor_faces(sim);
    const double *new_uv = ss_sim_anchor_uv(sim);
    const double *pull = ss_sim_anchor_pull(sim), *path = ss_sim_anchor_path(sim);
    const int walked = settings->sim.mover.method == SS_METHOD_WALK;
    for (int i = 0; i < nanchor; i++) {
      if (new_face[i] == old_face[i] && new_uv[2 * i] == old_uv[2 * i] &&
          new_uv[2 * i + 1] == old_uv[2 * i + 1])
        continue;
      double limit = settings->snag_factor * pull[i] + edge;
      if (snag_is(&judge, topo, fr, pos, old_face[i], old_uv + 2 * i, new_face[i],
                  new_uv + 2 * i, walked ? path[i] : -1.0, limit))
        stats->snags++;
    }
    stats->failures += frame_failed;
    done_frames++;
    if (on_frame && on_frame(frame_user, frame, sim, pos)) break;
    if (progress && progress(progress_user, frame, frames)) break;
  }

  stats->frames = done_frames;
  stats->iterations_mean = done_frames ? (double)iterations / done_frames : 0.0;
  stats->walk_steps_per_update = anchor_updates ? (double)walk_steps / anchor_updates : 0.0;
  stats->walk_share = step_total > 0.0 ? walk_total / step_total : 0.0;
  stats->ms_per_frame_median = ss_median(ms_total, done_frames);
  stats->walk_ms_per_frame_median = ss_median(ms_walk, done_frames);
  stats->assemble_ms_per_frame_median = ss_median(ms_asm, done_frames);
  stats->factor_ms_per_frame_median = ss_median(ms_factor, done_frames);
  stats->solve_ms_per_frame_median = ss_median(ms_solve, done_frames);
  stats->hug_rms = hug_count ? sqrt(hug_sum2 / (double)hug_count) : 0.0;
  if (!isfinite(stats->min_area_ratio)) stats->min_area_ratio = 0.0;
  stats->final_hash =
      ss_hash_bytes(ss_sim_skin_positions(sim), sizeof(double) * 3 * (size_t)skin_nvert);

done:
  free(pos);
  free(old_face);
  free(old_uv);
  free(rest_area);
  free(ms);
  snag_judge_free(&judge);
  ss_bvh_destroy(bvh);
  ss_frames_destroy(fr);
  ss_sim_destroy(sim);
  return status;
}
