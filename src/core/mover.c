/* One interface for the three ways of moving an anchor (mover.h): holds
 * the per-pose canonical frames and the scratch memory of the chosen method,
 * all allocated at create, so that moving anchors allocates nothing. */
#include <math.h>
#include <stdlib.h>

#include "bvh.h"
#include "closest.h"
#include "mover.h"
#include "ss_err.h"

struct ss_mover {
  ss_mover_settings settings;
  const ss_topo *topo;
  const double *pos; /* the pose of the last ss_mover_set_pose (caller's memory) */
  ss_frames *frames;
  ss_walker *walker;
  ss_bvh *bvh;     /* project only */
  ss_nring *nring; /* nring only */
};

/* ss_mover_default_settings(): from the settings table (settings.c). */

int ss_mover_create(ss_mover **out, const ss_topo *topo, const ss_mover_settings *settings,
                    const ss_bvh *bvh_shape, char *err, int err_sz) {
  if (!out || !topo || !settings) return ss_fail(err, err_sz, SS_E_ARG, "mover: NULL argument");
  *out = NULL;
  if (!ss_method_name(settings->method))
    return ss_fail(err, err_sz, SS_E_ARG,
                   "unknown anchor method %d (expected walk, project or nring)",
                   settings->method);
  if (settings->walk_max_steps < 0)
    return ss_fail(err, err_sz, SS_E_ARG, "walk_max_steps must be >= 0, got %d",
                   settings->walk_max_steps);
  if (settings->nring_rings < 0)
    return ss_fail(err, err_sz, SS_E_ARG, "nring rings must be >= 0, got %d",
                   settings->nring_rings);
  ss_mover *m = calloc(1, sizeof *m);
  if (!m) return ss_fail(err, err_sz, SS_E_NOMEM, "mover: out of memory");
  m->settings = *settings;
  m->topo = topo;
  int status = ss_frames_create(&m->frames, topo->nface);
  if (!status) status = ss_walker_create(&m->walker, topo->nface);
  if (!status && settings->method == SS_METHOD_PROJECT)
    status = bvh_shape ? ss_bvh_create_on(&m->bvh, bvh_shape) : ss_bvh_create(&m->bvh, topo);
  if (!status && settings->method == SS_METHOD_NRING) status = ss_nring_create(&m->nring, topo);
  if (status) {
    ss_mover_destroy(m);
    return ss_fail(err, err_sz, status, "mover: out of memory for %d faces", topo->nface);
  }
  *out = m;
  return SS_OK;
}

void ss_mover_destroy(ss_mover *m) {
  if (!m) return;
  ss_frames_destroy(m->frames);
  ss_walker_destroy(m->walker);
  ss_bvh_destroy(m->bvh);
  ss_nring_destroy(m->nring);
  free(m);
}

void ss_mover_set_pose(ss_mover *m, const double *pos) { ss_mover_set_pose_threads(m, pos, 1); }

void ss_mover_set_pose_threads(ss_mover *m, const double *pos, int nthread) {
  m->pos = pos;
  ss_frames_update_threads(m->frames, m->topo, pos, nthread);
  if (m->bvh) ss_bvh_refit(m->bvh, pos);
}

const ss_frames *ss_mover_frames(const ss_mover *m) { return m->frames; }

void ss_mover_set_isa(ss_mover *m, int isa) { m->frames->isa = isa; }

void ss_mover_move(ss_mover *m, int face, const double uv[2], const double target[3],
                   ss_walk_result *res) {
  if (m->settings.method == SS_METHOD_NRING && m->pos &&
      isfinite(target[0]) && isfinite(target[1]) && isfinite(target[2])) {
    res->stop = SS_STOP_INSIDE;
    res->steps = 0;
    res->length = 0.0;
    ss_nring_closest(m->nring, m->topo, m->pos, face, m->settings.nring_rings, target, &res->face,
                     res->uv);
    return;
  }
  ss_mover_walk_with(m, m->walker, face, uv, target, res); /* walk and project */
}

int ss_mover_method(const ss_mover *m) { return m->settings.method; }

void ss_mover_walk_with(const ss_mover *m, ss_walker *walker, int face, const double uv[2],
                        const double target[3], ss_walk_result *res) {
  if (m->settings.method == SS_METHOD_WALK || !m->pos ||
      !(isfinite(target[0]) && isfinite(target[1]) && isfinite(target[2]))) {
    /* the walk also handles a non-finite target: it leaves the anchor in place */
    ss_walk(walker, m->topo, m->frames, face, uv, target, m->settings.walk_max_steps, res);
    return;
  }
  res->stop = SS_STOP_INSIDE;
  res->steps = 0;
  res->length = 0.0;
  ss_bvh_closest(m->bvh, m->pos, target, &res->face, res->uv); /* project: read-only */
}
