/* The anchor tracking experiment: the paper's anchor update, isolated from the
 * dynamics (see ss_track.h).
 *
 * Why this target: a skin vertex lags behind the body it sits on, so the
 * spring force drags its anchor back towards where the skin still is — the
 * anchor's world position of the frame before — and slightly off the surface.
 * Where the body folds onto itself (armpit, thin parts) that point can lie
 * closer to another part of the body than to the anchor's own sheet, and the
 * Euclidean closest point ("projection springs") jumps across the gap: a snag.
 * The walk never leaves the surface, so it cannot jump. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ss_track.h"
#include "mover.h"
#include "snag.h"
#include "ss_err.h"
#include "ss_util.h"

ss_track_settings ss_track_default_settings(void) {
  ss_track_settings s;
  s.mover = ss_mover_default_settings();
  s.frames = 0;
  s.lift = 0.1;
  s.snag_factor = 3.0;
  return s;
}


/* Seeds one anchor per vertex (on the first face around it, at that corner)
 * and one per face barycenter. */
static void seed_anchors(const ss_topo *topo, int *face, double *uv) {
  static const double corner_uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  int n = 0;
  for (int v = 0; v < topo->nvert; v++) {
    int w = topo->vert_weld[v];
    int f = topo->vf_face[topo->vf_start[w]];
    int k = 0;
    for (int c = 0; c < 3; c++)
      if (topo->vert_weld[topo->face_vert[3 * f + c]] == w) { k = c; break; }
    face[n] = f;
    uv[2 * n] = corner_uv[k][0];
    uv[2 * n + 1] = corner_uv[k][1];
    n++;
  }
  for (int f = 0; f < topo->nface; f++) {
    face[n] = f;
    uv[2 * n] = uv[2 * n + 1] = 1.0 / 3.0;
    n++;
  }
}

static int anchor_ok(const ss_topo *topo, int face, const double uv[2], const double x[3]) {
  const double tol = 1e-9;
  if (face < 0 || face >= topo->nface) return 0;
  if (!(isfinite(uv[0]) && isfinite(uv[1]))) return 0;
  if (uv[0] < -tol || uv[1] < -tol || uv[0] + uv[1] > 1.0 + tol) return 0;
  return isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]);
}

int ss_track_run(const ss_scene *scene, const ss_track_settings *settings,
                 ss_progress_fn progress, void *user, ss_track_stats *stats, char *err,
                 int err_sz) {
  if (!scene || !settings || !stats) return ss_fail(err, err_sz, SS_E_ARG, "track: NULL argument");
  if (!(settings->lift >= 0.0 && isfinite(settings->lift)))
    return ss_fail(err, err_sz, SS_E_ARG, "track: lift must be a finite number >= 0");
  if (!(settings->snag_factor > 0.0 && isfinite(settings->snag_factor)))
    return ss_fail(err, err_sz, SS_E_ARG, "track: snag factor must be a finite number > 0");
  if (settings->frames < 0) return ss_fail(err, err_sz, SS_E_ARG, "track: frames must be >= 0");
  memset(stats, 0, sizeof *stats);
  const int nvert = ss_scene_nvert(scene), nface = ss_scene_nface(scene);
  const int frames = settings->frames > 0 ? settings->frames : ss_scene_default_frames(scene);

  ss_topo *topo = NULL;
  ss_mover *mover = NULL;
  snag_judge judge = {0};
  int status = ss_topo_create(&topo, nvert, ss_scene_rest(scene), nface, ss_scene_faces(scene),
                              -1.0, err, err_sz);
  if (status) return status;
  status = ss_mover_create(&mover, topo, &settings->mover, NULL, err, err_sz);
  if (!status) status = snag_judge_init(&judge, topo);
  const int nanchor = nvert + nface;
  double *pos = malloc(sizeof(double) * 3 * (size_t)nvert);
  int *anchor_face = malloc(sizeof(int) * (size_t)nanchor);
  double *anchor_uv = malloc(sizeof(double) * 2 * (size_t)nanchor);
  double *target = malloc(sizeof(double) * 3 * (size_t)nanchor);
  int *new_face = malloc(sizeof(int) * (size_t)nanchor);
  double *new_uv = malloc(sizeof(double) * 2 * (size_t)nanchor);
  unsigned char *new_stop = malloc((size_t)nanchor);
  double *new_path = malloc(sizeof(double) * (size_t)nanchor);
  double *frame_ms = malloc(sizeof(double) * (size_t)(frames > 0 ? frames : 1));
  if (!status && !(pos && anchor_face && anchor_uv && target && new_face && new_uv && new_stop &&
                   new_path && frame_ms))
    status = ss_fail(err, err_sz, SS_E_NOMEM, "track: out of memory for %d anchors", nanchor);
  if (status) goto done;

  stats->triangles = nface;
  stats->vertices = nvert;
  stats->anchors = nanchor;
  stats->mean_edge_length = topo->mean_edge_length;
  seed_anchors(topo, anchor_face, anchor_uv);

  const double edge = topo->mean_edge_length;
  const double lift = settings->lift * edge;
  long long total_steps = 0, walks = 0;
  int done_frames = 0;
  ss_scene_pose(scene, 0.0, pos);
  ss_mover_set_pose(mover, pos);
  for (int i = 0; i < nanchor; i++) {
    /* the skin starts at rest: its lagging target is where the anchor is now */
    const ss_frames *fr = ss_mover_frames(mover);
    ss_anchor_position(fr, anchor_face[i], anchor_uv + 2 * i, target + 3 * i);
    for (int c = 0; c < 3; c++) target[3 * i + c] += lift * fr->normal[3 * anchor_face[i] + c];
  }

  for (int frame = 1; frame <= frames; frame++) {
    ss_scene_pose(scene, (double)frame, pos);
    ss_mover_set_pose(mover, pos);
    const ss_frames *fr = ss_mover_frames(mover);

    /* timed: the anchor updates alone */
    double t0 = ss_now_ms();
    for (int i = 0; i < nanchor; i++) {
      ss_walk_result res;
      ss_mover_move(mover, anchor_face[i], anchor_uv + 2 * i, target + 3 * i, &res);
      new_face[i] = res.face;
      new_uv[2 * i] = res.uv[0];
      new_uv[2 * i + 1] = res.uv[1];
      new_stop[i] = (unsigned char)res.stop;
      new_path[i] = res.length;
      if (settings->mover.method == SS_METHOD_WALK) {
        total_steps += res.steps;
        walks++;
      }
    }
    frame_ms[done_frames] = ss_now_ms() - t0;

    /* untimed: judge each update, then make this frame's targets */
    for (int i = 0; i < nanchor; i++) {
      double a0[3], a1[3];
      ss_anchor_position(fr, anchor_face[i], anchor_uv + 2 * i, a0);
      ss_anchor_position(fr, new_face[i], new_uv + 2 * i, a1);
      stats->updates++;
      if (new_stop[i] == SS_STOP_BOUNDARY) stats->anchors_at_boundary++;
      if (new_stop[i] == SS_STOP_CREASE) stats->anchors_at_crease++;
      if (new_stop[i] == SS_STOP_STEP_LIMIT) stats->anchors_at_step_limit++;
      if (!anchor_ok(topo, new_face[i], new_uv + 2 * i, a1)) {
        stats->failures++;
        /* keep the anchor where it was so the run goes on measuring */
        new_face[i] = anchor_face[i];
        new_uv[2 * i] = anchor_uv[2 * i];
        new_uv[2 * i + 1] = anchor_uv[2 * i + 1];
        memcpy(a1, a0, sizeof a1);
      } else {
        double pull = 0.0;
        for (int c = 0; c < 3; c++) pull += (target[3 * i + c] - a0[c]) * (target[3 * i + c] - a0[c]);
        double limit = settings->snag_factor * sqrt(pull) + edge;
        if (snag_is(&judge, topo, fr, pos, anchor_face[i], anchor_uv + 2 * i, new_face[i],
                    new_uv + 2 * i,
                    settings->mover.method == SS_METHOD_WALK ? new_path[i] : -1.0, limit))
          stats->snags++;
      }
      anchor_face[i] = new_face[i];
      anchor_uv[2 * i] = new_uv[2 * i];
      anchor_uv[2 * i + 1] = new_uv[2 * i + 1];
      for (int c = 0; c < 3; c++) target[3 * i + c] = a1[c] + lift * fr->normal[3 * new_face[i] + c];
    }
    done_frames++;
    if (progress && progress(user, frame, frames)) break;
  }

  stats->frames = done_frames;
  stats->mean_steps = walks ? (double)total_steps / (double)walks : 0.0;
  stats->ms_per_frame_median = ss_median(frame_ms, done_frames);
  stats->ms_per_anchor_update_median = stats->ms_per_frame_median / (double)nanchor;

done:
  free(pos);
  free(anchor_face);
  free(anchor_uv);
  free(target);
  free(new_face);
  free(new_uv);
  free(new_stop);
  free(new_path);
  free(frame_ms);
  snag_judge_free(&judge);
  ss_mover_destroy(mover);
  ss_topo_destroy(topo);
  return status;
}
