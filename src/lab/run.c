/* The dynamic skin over a moving body (a built-in scene, an avatar),
 * measured (see ss_run.h). The
 * measurements are taken outside the timed step and never change the
 * simulation: a run with and without them gives the same bits. */
#include "ss_run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "inside.h"
#include "snag.h"
#include "ss_err.h"
#include "ss_util.h"
#include "ss_body_normal.h"
#include "ss_vec.h"

#define AREA_RATIO_MIN 0.05
#define AREA_RATIO_MAX 20.0

ss_run_settings ss_run_default_settings(void) {
  ss_run_settings s;
  s.sim = ss_sim_default_settings();
  s.frames = 0;
  s.snag_factor = 3.0;
  s.settle = 0.0;
  s.inside_every = 10;
  s.skin = NULL;
  s.model = NULL;
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

static int scene_pose_toward_rest(void *user, double frame, double w, double *pos) {
  ss_scene_pose_toward_rest(user, frame, w, pos);
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
  b.pose_toward_rest = scene_pose_toward_rest;
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

/* What the run measures outside the timed step, shared by the motion and the
 * settle frames. */
typedef struct run_meas {
  const ss_topo *topo;
  ss_frames *fr;
  ss_bvh *bvh;
  ss_wind *wind;            /* on bvh's tree: made at the first measured frame */
  long long inside_sum;     /* skin vertices inside, summed over measured frames */
  snag_judge judge;
  int nanchor, skin_nvert, skin_nface;
  const int *skin_faces;
  double *rest_area;        /* (skin_nface) */
  double *body_area0;       /* (body nface) area at rest */
  double *rest_dot;         /* (body nface x 3) n_f . n_g at rest across edge k (2: no neighbour) */
  unsigned char *folded;    /* (body nface) this frame: the body turned over at the face */
  signed char *face_sign;   /* (skin_nface) orientation of the skin face against the body at
                               rest: +1, -1 (a skin of its own wound the other way), 0 not judged */
  int *old_face, *face0;    /* (nanchor) before this frame; bound at create */
  double *old_uv, *uv0;     /* (nanchor x 2) */
  double edge;
  double hug_sum2;
  long long hug_count;
} run_meas;

/* The body's normal under skin face f for anchor faces af, as the orient
 * term judges it (ss_body_normal.h). */
static void normal_under(const run_meas *m, const ss_sim *sim, const int *af, int f, double n[3]) {
  body_normal_under(m->fr->normal, m->fr->area, m->body_area0, af, m->skin_faces, m->skin_nvert,
                    ss_sim_nanchors(sim), f, n);
}

/* Body faces the pose has folded over: a face turned more than 90 degrees
 * against a neighbour it faced the same way as at rest (n_f . n_g < 0 now,
 * > 0 at rest). Linear blend skinning does this where it crushes a crease
 * (the demo's wrist at frame 14: faces at 0.7-5% of their area, their
 * neighbours' normals at -0.96 to theirs), and a body that passes through
 * itself by design (elbow's inner crease) does it too. A thin part's rim,
 * whose sides face apart at rest, is not a fold. Returns the count. */
static int mark_folds(run_meas *m) {
  const ss_topo *t = m->topo;
  const double *n = m->fr->normal;
  int folds = 0;
  for (int f = 0; f < t->nface; f++) {
    unsigned char fo = 0;
    for (int k = 0; k < 3 && !fo; k++) {
      const int g = t->face_adj[3 * f + k];
      if (g < 0 || !(m->rest_dot[3 * f + k] > 0.0)) continue;
      fo = n[3 * f] * n[3 * g] + n[3 * f + 1] * n[3 * g + 1] + n[3 * f + 2] * n[3 * g + 2] < 0.0;
    }
    m->folded[f] = fo;
    folds += fo;
  }
  return folds;
}

/* 1 if a body face under skin face f - where its barycenter or one of its
 * corners is anchored, now or as bound - is folded over in this pose: within
 * the face's reach the body has no one "out" for it to point along. */
static int over_fold(const run_meas *m, const ss_sim *sim, int f) {
  const int nv = m->skin_nvert, *now = ss_sim_anchor_faces(sim);
  int a[4] = {m->skin_faces[3 * f], m->skin_faces[3 * f + 1], m->skin_faces[3 * f + 2], -1};
  if (ss_sim_nanchors(sim) > nv) a[3] = nv + f;
  for (int c = 0; c < 4 && a[c] >= 0; c++)
    if ((now[a[c]] >= 0 && m->folded[now[a[c]]]) || (m->face0[a[c]] >= 0 && m->folded[m->face0[a[c]]]))
      return 1;
  return 0;
}

/* The body normal skin face f is judged against: halfway between the normal
 * where it is anchored and the normal of the body face it was bound to (as
 * the orient term of the sim, orient.c, for the same reasons: near a sharp
 * edge an anchor settles on the neighbouring face, and skin slid around a
 * rim thinner than an edge is anchored on its far side). Zero (not judged)
 * where the two differ by more than 120 degrees. */
static void anchored_normal(const run_meas *m, const ss_sim *sim, int f, double n[3]) {
  double a[3], h[3];
  normal_under(m, sim, ss_sim_anchor_faces(sim), f, a);
  normal_under(m, sim, m->face0, f, h);
  for (int k = 0; k < 3; k++) n[k] = a[k] + h[k];
  if (!(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 1.0)) n[0] = n[1] = n[2] = 0.0;
}

/* Skin face f's (unnormalised) normal and its area ratio. */
static double face_normal(const run_meas *m, const double *x, int f, double n[3]) {
  const int *fv = m->skin_faces + 3 * f;
  tri_area_vector(x + 3 * fv[0], x + 3 * fv[1], x + 3 * fv[2], n);
  return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / m->rest_area[f];
}

/* The untimed measurements of a frame in the body pose pos; returns 1 if the
 * frame failed (area ratio out of range, non-finite distance). */
static int measure_frame(run_meas *m, const ss_sim *sim, const double *pos,
                         const ss_run_settings *settings, ss_run_stats *stats) {
  int frame_failed = 0;
  const ss_topo *topo = m->topo;
  const double edge = m->edge;
  ss_frames_update(m->fr, topo, pos);
  ss_bvh_refit(m->bvh, pos);
  const double *x = ss_sim_skin_positions(sim);
  const int folds = mark_folds(m);
  if (folds > stats->body_folds_max) stats->body_folds_max = folds;
  int inverted = 0, over_folds = 0;
  for (int f = 0; f < m->skin_nface; f++) {
    /* faces outside the simulated region are the body's own: not judged */
    if (!(m->rest_area[f] > 0.0) || (settings->sim.face_mask && !settings->sim.face_mask[f]))
      continue;
    double n[3], nb[3];
    double ratio = face_normal(m, x, f, n);
    if (!isfinite(ratio)) ratio = INFINITY;
    if (ratio < stats->min_area_ratio) stats->min_area_ratio = ratio;
    if (ratio > stats->max_area_ratio) stats->max_area_ratio = ratio;
    if (!(ratio >= AREA_RATIO_MIN && ratio <= AREA_RATIO_MAX)) frame_failed = 1;
    anchored_normal(m, sim, f, nb);
    if (m->face_sign[f] * (n[0] * nb[0] + n[1] * nb[1] + n[2] * nb[2]) < 0.0) {
      if (folds > 0 && over_fold(m, sim, f))
        over_folds++;
      else
        inverted++;
    }
  }
  if (inverted > stats->inverted_faces_max) stats->inverted_faces_max = inverted;
  if (over_folds > stats->inverted_over_folds_max) stats->inverted_over_folds_max = over_folds;
  int turned = 0, far = 0;
  ss_sim_count_off_body(sim, &turned, NULL);
  if (turned > stats->faces_turned_max) stats->faces_turned_max = turned;
  for (int v = 0; v < m->skin_nvert; v++) {
    int face;
    double uv[2], c[3];
    const double *p = x + 3 * v;
    double d2 = ss_bvh_closest(m->bvh, pos, p, &face, uv);
    double d = sqrt(d2) / edge;
    if (!isfinite(d)) frame_failed = 1;
    m->hug_sum2 += d * d;
    m->hug_count++;
    if (d > stats->hug_max) stats->hug_max = d;
    far += d > 1.0;
    /* below the surface: behind the closest face's plane */
    ss_anchor_position(m->fr, face, uv, c);
    const double *nf = m->fr->normal + 3 * face;
    double depth = -((p[0] - c[0]) * nf[0] + (p[1] - c[1]) * nf[1] + (p[2] - c[2]) * nf[2]) / edge;
    if (depth > stats->inside_max) stats->inside_max = depth;
  }
  if (far > stats->hug_far_max) stats->hug_far_max = far;
  const int *new_face = ss_sim_anchor_faces(sim);
  const double *new_uv = ss_sim_anchor_uv(sim);
  const double *pull = ss_sim_anchor_pull(sim), *path = ss_sim_anchor_path(sim);
  const int walked = settings->sim.mover.method == SS_METHOD_WALK;
  for (int i = 0; i < m->nanchor; i++) {
    if (new_face[i] == m->old_face[i] && new_uv[2 * i] == m->old_uv[2 * i] &&
        new_uv[2 * i + 1] == m->old_uv[2 * i + 1])
      continue;
    double limit = settings->snag_factor * pull[i] + edge;
    if (snag_is(&m->judge, topo, m->fr, pos, m->old_face[i], m->old_uv + 2 * i, new_face[i],
                new_uv + 2 * i, walked ? path[i] : -1.0, limit))
      stats->snags++;
  }
  /* slide: how far each anchor is from where it was bound, in this pose */
  for (int i = 0; i < m->nanchor; i++) {
    if (new_face[i] < 0 || m->face0[i] < 0) continue;
    double a[3], b[3];
    ss_anchor_position(m->fr, new_face[i], new_uv + 2 * i, a);
    ss_anchor_position(m->fr, m->face0[i], m->uv0 + 2 * i, b);
    double s = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                    (a[2] - b[2]) * (a[2] - b[2]));
    if (s > stats->slide_max_m) stats->slide_max_m = s;
  }
  return frame_failed;
}

/* The skin inside the body by winding number (inside.h), after
 * measure_frame refitted the BVH to this pose: counts and depths into stats.
 * A vertex on the surface (within 1e-6 edge: a carried piece, the rest pose)
 * is not inside, whatever the rounding of its winding number. */
static int measure_inside(run_meas *m, const ss_sim *sim, const double *pos, int frame,
                          ss_run_stats *stats) {
  if (!m->wind) {
    int status = ss_wind_create(&m->wind, m->bvh, m->topo);
    if (status) return status;
  }
  ss_wind_refit(m->wind, pos);
  const double *x = ss_sim_skin_positions(sim);
  const double edge = m->edge;
  const int *anchor_face = ss_sim_anchor_faces(sim); /* vertex anchors first */
  int inside = 0, over005 = 0, over01 = 0;
  for (int v = 0; v < m->skin_nvert; v++) {
    double depth;
    const int kind = ss_inside_classify(m->wind, m->bvh, pos, x + 3 * v, anchor_face[v], &depth);
    depth /= edge;
    if (kind == SS_INSIDE_OUT || !(depth > 1e-6)) continue;
    inside++;
    if (kind == SS_INSIDE_BURIED) {
      if (depth > stats->inside_buried_max) stats->inside_buried_max = depth;
      continue;
    }
    over005 += depth > 0.05;
    over01 += depth > 0.1;
    if (depth > stats->inside_clean_max) {
      stats->inside_clean_max = depth;
      stats->inside_clean_worst_frame = frame;
    }
  }
  stats->inside_samples++;
  m->inside_sum += inside;
  stats->inside_mean = (double)m->inside_sum / stats->inside_samples;
  if (inside > stats->inside_count_max) stats->inside_count_max = inside;
  if (over005 > stats->inside_clean_over_005_max) stats->inside_clean_over_005_max = over005;
  if (over01 > stats->inside_clean_over_01_max) stats->inside_clean_over_01_max = over01;
  return SS_OK;
}

/* Before a frame: the anchors as they are, for the snag test. */
static void remember_anchors(run_meas *m, const ss_sim *sim) {
  memcpy(m->old_face, ss_sim_anchor_faces(sim), sizeof(int) * (size_t)m->nanchor);
  memcpy(m->old_uv, ss_sim_anchor_uv(sim), sizeof(double) * 2 * (size_t)m->nanchor);
}

/* The run's sim (model NULL) or model (sim NULL): settings->skin, or else
 * the welded body (a no-op copy where the body has no seams). */
static int run_create(ss_sim **sim, ss_model **model, const ss_body *body,
                      const ss_run_settings *settings, char *err, int err_sz) {
  const int nvert = body->nvert, nface = body->nface;
  ss_sim_mesh skin;
  ss_weld *weld = NULL;
  if (settings->skin) {
    skin = *settings->skin;
  } else {
    int status = ss_weld_create(&weld, nvert, body->rest, nface, body->faces, -1.0, err, err_sz);
    if (status) return status;
    skin = (ss_sim_mesh){weld->nweld, weld->pos, nface, weld->faces};
  }
  int status = sim ? ss_sim_create(sim, nvert, body->rest, nface, body->faces, &skin,
                                   &settings->sim, err, err_sz)
                   : ss_model_create(model, nvert, body->rest, nface, body->faces, &skin,
                                     &settings->sim, err, err_sz);
  ss_weld_destroy(weld);
  return status;
}

int ss_run_model_create(ss_model **out, const ss_body *body, const ss_run_settings *settings,
                        char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "run: out is NULL");
  *out = NULL;
  if (!body || !settings || !body->rest || !body->faces)
    return ss_fail(err, err_sz, SS_E_ARG, "run: NULL argument");
  return run_create(NULL, out, body, settings, err, err_sz);
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
  if (settings->inside_every < 0) return ss_fail(err, err_sz, SS_E_ARG, "run: inside_every must be >= 0");
  if (!(settings->settle >= 0.0 && settings->settle <= 1e6))
    return ss_fail(err, err_sz, SS_E_ARG, "run: settle must be in [0, 1e6] s (got %g)",
                   settings->settle);
  memset(stats, 0, sizeof *stats);
  const int nvert = body->nvert, nface = body->nface;
  const int frames = settings->frames > 0 ? settings->frames : (body->frames > 0 ? body->frames : 1);
  const double dt = 1.0 / body->fps;

  ss_sim *sim = NULL;
  int status;
  if (settings->model) {
    if (ss_model_body_nvert(settings->model) != nvert || ss_model_body_nface(settings->model) != nface)
      return ss_fail(err, err_sz, SS_E_ARG, "run: the model is of another body (%d vertices, %d faces; "
                     "the body has %d, %d)", ss_model_body_nvert(settings->model),
                     ss_model_body_nface(settings->model), nvert, nface);
    status = ss_sim_create_from_model(&sim, settings->model, &settings->sim, err, err_sz);
  } else {
    status = run_create(&sim, NULL, body, settings, err, err_sz);
  }
  if (status) return status;
  ss_sim_measure_anchors(sim, 1); /* the snag test reads each anchor's pull and path */
  const ss_topo *topo = ss_sim_body_topo(sim);
  const int nanchor = ss_sim_nanchors(sim), skin_nvert = ss_sim_skin_nvert(sim);
  const int skin_nface = ss_sim_skin_nface(sim);
  /* settle: one second blending back to rest, then settle seconds at rest */
  const int blend_frames = settings->settle > 0.0 ? (int)ceil(body->fps - 1e-9) : 0;
  const int hold_frames = settings->settle > 0.0 ? (int)ceil(settings->settle * body->fps - 1e-9) : 0;
  run_meas m;
  memset(&m, 0, sizeof m);
  m.topo = topo;
  m.nanchor = nanchor;
  m.skin_nvert = skin_nvert;
  m.skin_nface = skin_nface;
  m.skin_faces = ss_sim_skin_faces(sim);
  m.edge = topo->mean_edge_length;
  status = ss_frames_create(&m.fr, nface);
  if (!status) status = ss_bvh_create(&m.bvh, topo);
  if (!status) status = snag_judge_init(&m.judge, topo);
  double *pos = malloc(sizeof(double) * 3 * (size_t)nvert);
  double *last = blend_frames ? malloc(sizeof(double) * 3 * (size_t)nvert) : NULL;
  m.old_face = malloc(sizeof(int) * (size_t)nanchor);
  m.old_uv = malloc(sizeof(double) * 2 * (size_t)nanchor);
  m.face0 = malloc(sizeof(int) * (size_t)nanchor);
  m.uv0 = malloc(sizeof(double) * 2 * (size_t)nanchor);
  m.rest_area = malloc(sizeof(double) * (size_t)skin_nface);
  m.rest_dot = malloc(sizeof(double) * 3 * (size_t)nface);
  m.body_area0 = malloc(sizeof(double) * (size_t)nface);
  m.folded = malloc((size_t)nface);
  m.face_sign = malloc((size_t)skin_nface + 1);
  double *ms = malloc(sizeof(double) * 5 * (size_t)(frames > 0 ? frames : 1));
  if (!status && !(pos && m.old_face && m.old_uv && m.face0 && m.uv0 && m.rest_area &&
                   m.rest_dot && m.body_area0 && m.folded && m.face_sign && ms && (last || !blend_frames)))
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
  const double *skin_rest = ss_sim_skin_rest(sim);
  memcpy(m.face0, ss_sim_anchor_faces(sim), sizeof(int) * (size_t)nanchor);
  memcpy(m.uv0, ss_sim_anchor_uv(sim), sizeof(double) * 2 * (size_t)nanchor);
  ss_frames_update(m.fr, topo, body->rest);
  memcpy(m.body_area0, m.fr->area, sizeof(double) * (size_t)nface);
  for (int f = 0; f < nface; f++)
    for (int k = 0; k < 3; k++) {
      const int g = topo->face_adj[3 * f + k];
      const double *nf = m.fr->normal + 3 * f, *ng = m.fr->normal + 3 * (g < 0 ? f : g);
      m.rest_dot[3 * f + k] = g < 0 ? 2.0 : nf[0] * ng[0] + nf[1] * ng[1] + nf[2] * ng[2];
    }
  for (int f = 0; f < skin_nface; f++) {
    double n[3], nb[3];
    m.rest_area[f] = 1.0;
    m.rest_area[f] = face_normal(&m, skin_rest, f, n);
    anchored_normal(&m, sim, f, nb);
    double d = n[0] * nb[0] + n[1] * nb[1] + n[2] * nb[2];
    m.face_sign[f] = (signed char)(d > 0.0 ? 1 : d < 0.0 ? -1 : 0);
    /* a sliver stands at any angle to the body without having turned over
     * (the slivers scene at tether 3: 235 of them "inverted" at ~90 degrees) */
    if (!(m.rest_area[f] >= SS_SLIVER_AREA * edge * edge)) m.face_sign[f] = 0;
  }

  long long iterations = 0, walk_steps = 0, anchor_updates = 0;
  double walk_total = 0.0, step_total = 0.0;
  int done_frames = 0, stopped = 0;
  for (int frame = 1; frame <= frames; frame++) {
    remember_anchors(&m, sim);
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

    frame_failed |= measure_frame(&m, sim, pos, settings, stats);
    if (settings->inside_every > 0 && frame % settings->inside_every == 0) {
      status = measure_inside(&m, sim, pos, frame, stats);
      if (status) {
        ss_fail(err, err_sz, status, "run: out of memory for the inside test");
        break;
      }
    }
    stats->failures += frame_failed;
    done_frames++;
    if (on_frame && on_frame(frame_user, frame, sim, pos)) { stopped = 1; break; }
    if (progress && progress(progress_user, frame, frames)) { stopped = 1; break; }
  }
  /* the skin after the motion (before any settling) */
  stats->final_hash =
      ss_hash_bytes(ss_sim_skin_positions(sim), sizeof(double) * 3 * (size_t)skin_nvert);
  if (!status && !stopped && done_frames == frames && blend_frames > 0) {
    /* settle: the body goes from its last pose back to rest over one
     * second, linearly in its joint angles where the body can (a blend of
     * the positions shrinks a bent part half way: on `elbow`, 135 degrees,
     * to 0.38 of its distance from the joint, and the skin crumples over
     * it), then holds still while the skin keeps stepping. Failures, snags,
     * inversions and depth are counted; slide, hug and times are the
     * motion's. */
    memcpy(last, pos, sizeof(double) * 3 * (size_t)nvert);
    const double slide_max_m = stats->slide_max_m, hug_max = stats->hug_max;
    const double hug_sum2 = m.hug_sum2;
    const long long hug_count = m.hug_count;
    for (int k = 1; k <= blend_frames + hold_frames && !status; k++) {
      double w = k >= blend_frames ? 1.0 : (double)k / blend_frames;
      if (k >= blend_frames) {
        memcpy(pos, body->rest, sizeof(double) * 3 * (size_t)nvert);
      } else if (body->pose_toward_rest) {
        status = body->pose_toward_rest(body->user, (double)frames, w, pos);
        if (status) {
          ss_fail(err, err_sz, status, "run: the body's pose on its way back to rest failed (%s)",
                  ss_status_string(status));
          break;
        }
      } else {
        for (int i = 0; i < 3 * nvert; i++) pos[i] = last[i] + w * (body->rest[i] - last[i]);
      }
      remember_anchors(&m, sim);
      ss_sim_stats st;
      char step_err[256] = "";
      int step_status = ss_sim_step(sim, pos, dt, &st, step_err, sizeof step_err);
      int frame_failed = step_status != SS_OK || st.failures > 0;
      stats->slide_max_m = 0.0;
      frame_failed |= measure_frame(&m, sim, pos, settings, stats);
      stats->failures += frame_failed;
      stats->settle_frames++;
      if (on_frame && on_frame(frame_user, frames + k, sim, pos)) break;
    }
    stats->rest_slide_max = stats->slide_max_m / edge; /* the last frame's: the anchors at rest */
    stats->slide_max_m = slide_max_m;
    stats->hug_max = hug_max;
    m.hug_sum2 = hug_sum2;
    m.hug_count = hug_count;
    const double *x = ss_sim_skin_positions(sim);
    double sum2 = 0.0, worst = 0.0;
    for (int v = 0; v < skin_nvert; v++) {
      const double *p = x + 3 * v, *r = skin_rest + 3 * v;
      double d2 = (p[0] - r[0]) * (p[0] - r[0]) + (p[1] - r[1]) * (p[1] - r[1]) +
                  (p[2] - r[2]) * (p[2] - r[2]);
      sum2 += d2;
      if (d2 > worst) worst = d2;
    }
    stats->rest_error_max_m = sqrt(worst);
    stats->rest_error_rms = skin_nvert ? sqrt(sum2 / skin_nvert) / edge : 0.0;
    stats->rest_error_max = stats->rest_error_max_m / edge;
  }
  stats->slide_max = stats->slide_max_m / edge;
  stats->hug_rms = m.hug_count ? sqrt(m.hug_sum2 / (double)m.hug_count) : 0.0;

  stats->frames = done_frames;
  stats->iterations_mean = done_frames ? (double)iterations / done_frames : 0.0;
  stats->walk_steps_per_update = anchor_updates ? (double)walk_steps / anchor_updates : 0.0;
  stats->walk_share = step_total > 0.0 ? walk_total / step_total : 0.0;
  stats->ms_per_frame_median = ss_median(ms_total, done_frames);
  stats->walk_ms_per_frame_median = ss_median(ms_walk, done_frames);
  stats->assemble_ms_per_frame_median = ss_median(ms_asm, done_frames);
  stats->factor_ms_per_frame_median = ss_median(ms_factor, done_frames);
  stats->solve_ms_per_frame_median = ss_median(ms_solve, done_frames);
  if (!isfinite(stats->min_area_ratio)) stats->min_area_ratio = 0.0;
done:
  free(pos);
  free(last);
  free(m.old_face);
  free(m.old_uv);
  free(m.face0);
  free(m.uv0);
  free(m.rest_area);
  free(m.rest_dot);
  free(m.body_area0);
  free(m.folded);
  free(m.face_sign);
  free(ms);
  snag_judge_free(&m.judge);
  ss_wind_destroy(m.wind);
  ss_bvh_destroy(m.bvh);
  ss_frames_destroy(m.fr);
  ss_sim_destroy(sim);
  return status;
}
