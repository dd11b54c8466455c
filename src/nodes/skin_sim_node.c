/* skin_sim_node: the sliding skin as a ROS 1 node (glue only).
 *
 * Subscribes kinematic_mesh (skin_sim/SkinMesh, the moving body), steps an
 * ss_sim for the time between stamps and publishes, with the input's stamp and
 * frame: skin_mesh (SkinMesh), skin_stats (SkinStats) and, at ~marker_rate,
 * skin_marker (visualization_msgs/Marker TRIANGLE_LIST for rviz, coloured by
 * ~marker_color: how far the skin has slid from where it was bound, how far it
 * is stretched, or one colour; shaded from its normals, as rviz draws such a
 * marker unlit).
 *
 * The skin is the received body welded at ~weld_tol (seam copies are one skin
 * vertex), published in the body's own vertex layout, every copy from its
 * welded vertex, so no seam can open.
 *
 * The simulation is created on the first good mesh (its pose is the rest
 * shape) and again when topology_id changes, or the INPUT's time goes
 * backwards (a bag looping) or jumps forward by more than ~max_gap between
 * consecutively published messages (ss_input_stream_arrive). The step length
 * comes from the stamps, never from the wall clock, so a replayed bag gives
 * the same output bit for bit: whole input periods since the skin's clock, in
 * the substeps of one period (ss_input_plan_step). A node that falls behind
 * steps the newest mesh once: the frames it skipped neither add substeps nor
 * reset the skin. Bad messages (see ss_input.h) are rejected with a throttled
 * log line and counted; the last good state is kept. Received meshes wait in a
 * ring of ~queue_size slots (default 1: only the newest); when it is full the
 * oldest is skipped (inputs_skipped), so nothing queues without bound.
 * roscpp's own queue holds ~queue_size + 2 (it only fills during one step, as
 * the node spins between steps; deeper, a stall would fill it with serialized
 * meshes, a high-water mark the allocator keeps);
 * meshes lost before the callback show as gaps in header.seq and are counted as
 * inputs_dropped. The shim sizes each message before anything is allocated for it
 * (~max_vertices, ~max_triangles: refused unread and counted as rejected), and a
 * mesh of more than 8 MB hands its memory back once processed.
 *
 * Health goes to /diagnostics every ~diagnostic_period (the level judged by the
 * core from the window's figures: ss_input_health), and while one step takes
 * longer, from the shim's own thread: "step in progress for N s" (rosc_diag_busy,
 * ss_input_busy); the ~reset service
 * (std_srvs/Empty) makes the next mesh create the skin again on its pose.
 *
 * Parameters: see doc/ros.md and launch/skin.launch. */
#include "skin_node.h"

/* ------------------------------------------------------------------ input */
static int grow(void **buf, size_t *cap, size_t n, size_t elem)
{
  if (n <= *cap) return 1;
  void *q = realloc(*buf, n * elem);
  if (!q) return 0;
  *buf = q;
  *cap = n;
  return 1;
}

static void on_mesh(const void *msg, void *user)
{
  const ss_msg_skin_mesh *m = msg;
  node *nd = user;
  inbox *q = &nd->in;
  nd->frames_in++;
  /* roscpp numbers the messages of a publisher (header.seq): a gap means meshes lost
   * before they reached this callback (roscpp's queue overflowing during a stall, or
   * the publisher's): counted as dropped. A smaller seq is a new publisher. Every
   * arrival is judged against the previous one in publication order: only a jump
   * between consecutively published messages (or time going backwards) is the
   * input's own and resets the skin; it is carried over the messages the node skips,
   * to the one it steps. */
  int kind = ss_input_stream_arrive(&nd->stream, m->header.seq, ss_msg_time_to_ns(m->header.stamp),
                                    nd->p.max_gap);
  int disc = (kind == SS_TIME_GAP || kind == SS_TIME_BACKWARDS) ? kind : 0;
  if (q->count == q->cap) { /* full: the oldest was never stepped: skipped */
    int carry = q->slot[q->head].disc;
    q->head = (q->head + 1) % q->cap;
    q->count--;
    nd->skipped++;
    if (carry && q->count && !q->slot[q->head].disc) q->slot[q->head].disc = carry;
    else if (carry && !q->count && !disc) disc = carry;
  }
  mailbox *b = &q->slot[(q->head + q->count) % q->cap];
  if (!grow((void **)&b->pos, &b->cap_pos, m->n_positions, sizeof(float)) ||
      !grow((void **)&b->tri, &b->cap_tri, m->n_triangles, sizeof(uint32_t)) ||
      !grow((void **)&b->rigid, &b->cap_rigid, m->n_rigid_part, sizeof(uint32_t))) {
    NODE_ERROR_THROTTLE(2.0, "out of memory for a mesh of %zu values", m->n_positions);
    nd->dropped++;
    if (disc) nd->carry_disc = disc;
    return;
  }
  if (m->n_positions) memcpy(b->pos, m->positions, m->n_positions * sizeof(float));
  if (m->n_triangles) memcpy(b->tri, m->triangles, m->n_triangles * sizeof(uint32_t));
  if (m->n_rigid_part) memcpy(b->rigid, m->rigid_part, m->n_rigid_part * sizeof(uint32_t));
  b->nrigid = m->n_rigid_part;
  b->npos = m->n_positions;
  b->ntri = m->n_triangles;
  b->header = m->header;
  b->topology_id = m->topology_id;
  b->disc = disc;
  q->count++;
}

/* A mesh whose arrays exceed this many bytes gives its memory back once processed. */
#define RELEASE_BYTES ((size_t)8 << 20)

/* After a large mesh: its slot's buffers are freed and the C library is asked to hand
 * freed memory back to the system. glibc keeps freed blocks in its heaps (its mmap
 * threshold grows to 32 MB after a large block is freed), so without this one 96 MB
 * message left the node's RSS at 111 MB for good (17 MB before). A stream of large
 * meshes pays one allocation more per message; roscpp allocates each one afresh anyway. */
static void release_large(mailbox *b)
{
  size_t bytes = b->cap_pos * sizeof(float) + (b->cap_tri + b->cap_rigid) * sizeof(uint32_t);
  if (bytes <= RELEASE_BYTES) return;
  free(b->pos);
  free(b->tri);
  free(b->rigid);
  b->pos = NULL;
  b->tri = b->rigid = NULL;
  b->cap_pos = b->cap_tri = b->cap_rigid = 0;
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

/* A kinematic_mesh's bytes, sized before anything is allocated for them (ss_wire.h):
 * one whose length is beyond the message's bytes, or beyond ~max_vertices /
 * ~max_triangles, is refused unread, counted as received and rejected, with a
 * throttled error naming the field and sizes. */
static int check_mesh(const uint8_t *buf, size_t len, void *user)
{
  node *nd = user;
  ss_wire_limits lim = {(uint64_t)nd->p.max_vertices, (uint64_t)nd->p.max_triangles};
  char why[320];
  if (ss_wire_skin_mesh_check(buf, len, &lim, NULL, why, sizeof why)) return 1;
  nd->frames_in++;
  nd->rejected++;
  NODE_LOG_EVERY(&nd->reject_log[REJECT_SIZE], ROSC_LOG_ERROR, 1.0,
                 "rejected kinematic_mesh unread: %s (%u rejected so far)", why,
                 (unsigned)nd->rejected);
  return 0;
}

/* Counts a rejected message and logs why, at most once a second per kind of
 * problem (kind: REJECT_*), so that different problems each show. */
static void reject(node *nd, int kind, const char *why)
{
  nd->rejected++;
  NODE_LOG_EVERY(&nd->reject_log[kind], ROSC_LOG_WARN, 1.0,
                 "rejected kinematic_mesh: %s (%u rejected so far)", why, (unsigned)nd->rejected);
}

/* ------------------------------------------------------------------ simulation */
static void free_sim(node *nd)
{
  ss_sim_destroy(nd->sim);
  nd->sim = NULL;
  free(nd->vert_weld);
  nd->vert_weld = NULL;
  nd->nweld = 0;
  free(nd->bfaces); free(nd->faces); free(nd->tri_out); free(nd->mask); free(nd->face0);
  free(nd->uv0); free(nd->carried);
  free(nd->slide); free(nd->body); free(nd->body_prev); free(nd->body_sub);
  free(nd->pos_out); free(nd->mk_pts); free(nd->mk_col); free(nd->mk_vcol); free(nd->mk_work);
  nd->bfaces = NULL; nd->faces = NULL; nd->tri_out = NULL; nd->mask = NULL; nd->face0 = NULL;
  nd->uv0 = NULL; nd->carried = NULL;
  nd->slide = NULL; nd->body = NULL; nd->body_prev = NULL; nd->body_sub = NULL;
  nd->pos_out = NULL; nd->mk_pts = NULL; nd->mk_col = NULL; nd->mk_vcol = NULL; nd->mk_work = NULL;
  nd->nvert = nd->nface = nd->nbvert = nd->nbface = nd->nanchor = 0;
}

/* Reads ~skin_mesh (a file or package:// URI, through the avatar layer's guarded
 * import) and welds it; 1 on success, else 0 after one error naming the file. */
static int load_skin_file(node *nd)
{
  const params *p = &nd->p;
  char path[4096], err[ERR_SZ] = "";
  if (ssa_resolve_uri(p->skin_mesh, NULL, p->package_path[0] ? p->package_path : NULL, path,
                      sizeof path, err, sizeof err) != SS_OK) {
    ROSC_ERROR("~skin_mesh '%s': %s", p->skin_mesh, err);
    return 0;
  }
  ssa_asset_opts opts = ssa_asset_default_opts();
  opts.z_up = 0;           /* the skin is in the body's frame: coordinates as written */
  opts.ignore_up_axis = 1;
  ssa_asset *a = NULL;
  int st = ssa_asset_load(&a, path, &opts, err, sizeof err);
  if (st == SS_OK && (a->nvert <= 0 || a->nface <= 0)) {
    snprintf(err, sizeof err, "it has no triangles");
    st = SS_E_MESH;
  }
  if (st == SS_OK)
    st = ss_weld_create(&nd->skin.weld, a->nvert, a->rest_pos, a->nface, a->faces, p->weld_tol,
                        err, sizeof err);
  if (st == SS_OK) {
    nd->skin.faces = malloc(3 * (size_t)a->nface * sizeof(int));
    if (nd->skin.faces) memcpy(nd->skin.faces, a->faces, 3 * (size_t)a->nface * sizeof(int));
    else snprintf(err, sizeof err, "out of memory"), st = SS_E_NOMEM;
  }
  if (st == SS_OK) {
    nd->skin.topology_id = ss_input_topology_id(a->nvert, a->nface, a->faces, NULL);
    ROSC_INFO("~skin_mesh %s: %d vertices (%d after welding), %d triangles", path, a->nvert,
              nd->skin.weld->nweld, a->nface);
  } else {
    ROSC_ERROR("~skin_mesh %s: %s", path, err);
  }
  ssa_asset_destroy(a);
  return st == SS_OK;
}

/* The face mask of a skin over the received body: ~mask_box by face centroid (pos: the
 * skin's own vertices in the body's rest frame). */
static void box_mask(node *nd, int nf, const int *faces, const double *pos)
{
  const double *bx = nd->p.box;
  int nin = 0;
  for (int f = 0; f < nf; f++) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++) c[d] += pos[3 * (size_t)faces[3 * f + k] + d] / 3.0;
    int in = c[0] >= bx[0] && c[1] >= bx[1] && c[2] >= bx[2] && c[0] <= bx[3] && c[1] <= bx[4] &&
             c[2] <= bx[5];
    nd->mask[f] = (unsigned char)in;
    nin += in;
  }
  ROSC_INFO("~mask_box: %d of %d faces simulated", nin, nf);
}

/* Creates the simulation with the mailbox's mesh as the body at rest: the skin is
 * that mesh welded, or ~skin_mesh bound to it by closest point. Pieces that move
 * rigidly with one link (rigid_part) are carried with it. 1 on success. */
static int create_sim(node *nd, const mailbox *b)
{
  free_sim(nd);
  const ss_weld *file = nd->skin.weld;
  int nbv = (int)(b->npos / 3), nbf = (int)(b->ntri / 3);
  int nv = file ? file->nvert : nbv, nf = file ? file->nface : nbf;
  size_t n3 = 3 * (size_t)nv, f3 = 3 * (size_t)nf, b3 = 3 * (size_t)nbv;
  nd->bfaces = malloc(3 * (size_t)nbf * sizeof(int));
  nd->faces = malloc(f3 * sizeof(int));
  nd->tri_out = malloc(f3 * sizeof(uint32_t));
  nd->body = malloc(b3 * sizeof(double));
  nd->body_prev = malloc(b3 * sizeof(double));
  nd->body_sub = malloc(b3 * sizeof(double));
  nd->pos_out = malloc(n3 * sizeof(float));
  nd->mk_pts = malloc(3 * f3 * sizeof(float));
  nd->mk_col = malloc(4 * f3 * sizeof(float));
  nd->mask = malloc((size_t)nf);
  nd->carried = calloc((size_t)nv, 1);
  if (!nd->bfaces || !nd->faces || !nd->tri_out || !nd->body || !nd->body_prev ||
      !nd->body_sub || !nd->pos_out || !nd->mk_pts || !nd->mk_col || !nd->mask || !nd->carried) {
    ROSC_ERROR("out of memory for a skin of %d vertices", nv);
    free_sim(nd);
    return 0;
  }
  for (size_t i = 0; i < 3 * (size_t)nbf; i++) nd->bfaces[i] = (int)b->tri[i];
  for (size_t i = 0; i < b3; i++) nd->body[i] = (double)b->pos[i];
  ss_sim_settings set = nd->p.set;
  memset(nd->mask, 1, (size_t)nf);
  char err[ERR_SZ] = "";
  double t0 = 0, t1 = 0;
  rosc_wall_now_s(&t0);
  ss_weld *weld = NULL;
  ss_rigid_count rigid = {0, 0, 0};
  /* what each skin vertex moves with (rigid_part): the body vertex's, or for the file the
   * part of the body face it is bound to; over welded skin vertices for the file */
  uint32_t *skin_part = NULL;
  int st = SS_OK;
  if (!file) {
    /* the skin is the body welded: seam copies are one skin vertex, so no seam can open */
    if (nd->p.have_box) box_mask(nd, nf, nd->bfaces, nd->body);
    st = ss_weld_create(&weld, nbv, nd->body, nbf, nd->bfaces, nd->p.weld_tol, err, sizeof err);
    if (st == SS_OK && b->nrigid) {
      skin_part = malloc((size_t)nv * sizeof(uint32_t));
      if (skin_part) memcpy(skin_part, b->rigid, (size_t)nv * sizeof(uint32_t));
      else st = SS_E_NOMEM;
    }
  } else {
    /* the file's skin, its vertices in the layout of the file, bound to the body */
    if (nd->p.have_box) box_mask(nd, nf, file->faces, file->pos);
    ss_sim_mesh sm = {file->nweld, file->pos, file->nface, file->faces};
    uint32_t *wpart = malloc((size_t)file->nweld * sizeof(uint32_t));
    double *dist = malloc((size_t)file->nweld * sizeof(double));
    st = wpart && dist ? SS_OK : SS_E_NOMEM;
    if (st == SS_OK)
      st = ss_sim_skin_binding(nbv, nd->body, nbf, nd->bfaces, &sm, b->nrigid ? b->rigid : NULL,
                               wpart, dist, err, sizeof err);
    int far = -1;
    for (int w = 0; st == SS_OK && w < file->nweld; w++)
      if (far < 0 || dist[w] > dist[far]) far = w;
    if (st == SS_OK && far >= 0 && !(dist[far] <= nd->p.skin_max_distance)) {
      snprintf(err, sizeof err, "~skin_mesh %.300s: its vertex %d is %.4g m from the body, "
               "farther than ~skin_max_distance %.4g m (is it in the body's frame and rest pose?)",
               nd->p.skin_mesh, file->weld_rep[far], dist[far], nd->p.skin_max_distance);
      st = SS_E_MESH;
    }
    if (st == SS_OK && b->nrigid) skin_part = wpart, wpart = NULL;
    free(wpart);
    free(dist);
  }
  const int *vert_weld = file ? file->vert_weld : weld ? weld->vert_weld : NULL;
  if (st == SS_OK && skin_part) {
    /* pieces that move rigidly with one link are carried with it, not simulated */
    unsigned char *rigid_mask = malloc((size_t)nf);
    st = rigid_mask ? SS_OK : SS_E_NOMEM;
    if (st == SS_OK) {
      memset(rigid_mask, 1, (size_t)nf);
      st = file ? ss_mesh_rigid_pieces(file->nweld, nf, file->faces, NULL, skin_part, rigid_mask,
                                       &rigid)
                : ss_mesh_rigid_pieces(nv, nf, nd->bfaces, vert_weld, skin_part, rigid_mask,
                                       &rigid);
    }
    if (st != SS_OK) snprintf(err, sizeof err, "rigid pieces: out of memory");
    for (int f = 0; st == SS_OK && f < nf; f++)
      if (!rigid_mask[f]) {
        nd->mask[f] = 0;
        /* a received body's rigid piece is published as received */
        if (!file)
          for (int k = 0; k < 3; k++) nd->carried[nd->bfaces[3 * f + k]] = 1;
      }
    free(rigid_mask);
  }
  free(skin_part);
  set.face_mask = nd->mask;
  if (st == SS_OK) {
    ss_sim_mesh skin = file ? (ss_sim_mesh){file->nweld, file->pos, nf, file->faces}
                            : (ss_sim_mesh){weld->nweld, weld->pos, nf, weld->faces};
    st = ss_sim_create(&nd->sim, nbv, nd->body, nbf, nd->bfaces, &skin, &set, err, sizeof err);
    nd->nweld = skin.nvert;
    nd->vert_weld = malloc((size_t)nv * sizeof(int));
    if (st == SS_OK && !nd->vert_weld) {
      snprintf(err, sizeof err, "out of memory");
      st = SS_E_NOMEM;
    }
    if (nd->vert_weld) memcpy(nd->vert_weld, vert_weld, (size_t)nv * sizeof(int));
  }
  ss_weld_destroy(weld);
  rosc_wall_now_s(&t1);
  if (st != SS_OK) {
    char why[ERR_SZ + 64];
    snprintf(why, sizeof why, "cannot simulate it: %s", err);
    free_sim(nd);
    reject(nd, REJECT_CREATE, why);
    return 0;
  }
  /* the published layout: the received body's, or the file's own */
  memcpy(nd->faces, file ? nd->skin.faces : nd->bfaces, f3 * sizeof(int));
  for (size_t i = 0; i < f3; i++) nd->tri_out[i] = (uint32_t)nd->faces[i];
  nd->nbvert = nbv;
  nd->nbface = nbf;
  nd->nvert = nv;
  nd->nface = nf;
  nd->nface_carried = rigid.nface_carried;
  nd->nface_sim = 0;
  for (int f = 0; f < nf; f++) nd->nface_sim += nd->mask[f] != 0;
  nd->nanchor = ss_sim_nanchors(nd->sim);
  nd->face0 = malloc((size_t)nd->nanchor * sizeof(int));
  nd->uv0 = malloc(2 * (size_t)nd->nanchor * sizeof(double));
  nd->slide = malloc((size_t)nd->nanchor * sizeof(double));
  if (!nd->face0 || !nd->uv0 || !nd->slide) {
    ROSC_ERROR("out of memory for %d anchors", nd->nanchor);
    free_sim(nd);
    return 0;
  }
  memcpy(nd->face0, ss_sim_anchor_faces(nd->sim), (size_t)nd->nanchor * sizeof(int));
  memcpy(nd->uv0, ss_sim_anchor_uv(nd->sim), 2 * (size_t)nd->nanchor * sizeof(double));
  memcpy(nd->body_prev, nd->body, b3 * sizeof(double));
  nd->topology_id = b->topology_id;
  ss_budget_init(&nd->budget, nd->p.set.substeps, nd->p.set.iterations);
  nd->faces_turned = nd->vertices_far = 0;
  ROSC_INFO("skin created%s%s: %d vertices (%d published, welded at ~weld_tol %g), %d triangles: "
            "%d simulated, %d carried rigidly (%d of %d pieces move with one link)%s; %d anchors, "
            "%d unknowns (topology %u, %.1f ms)", file ? " from ~skin_mesh " : " as the body",
            file ? nd->p.skin_mesh : "", nd->nweld, nv, nd->p.weld_tol, nf, nd->nface_sim,
            nd->nface_carried, rigid.npiece_carried, rigid.npiece,
            b->nrigid ? "" : " [the input says nothing of rigid parts: all may deform]",
            nd->nanchor, ss_sim_ndof(nd->sim), (unsigned)b->topology_id, 1e3 * (t1 - t0));
  return 1;
}

/* Puts the run settings in force where they differ from the skin's (its
 * substeps, iterations and safety_residual: from the next step, nothing
 * allocated). */
static void apply_run(node *nd, const ss_sim_settings *run)
{
  const ss_sim_settings *cur = ss_sim_get_settings(nd->sim);
  if (cur->substeps == run->substeps && cur->iterations == run->iterations &&
      cur->safety_residual == run->safety_residual)
    return;
  ss_sim_settings want = *cur;
  want.substeps = run->substeps;
  want.iterations = run->iterations;
  want.safety_residual = run->safety_residual;
  char err[ERR_SZ] = "";
  int recreate = 0;
  if (ss_sim_set_settings(nd->sim, &want, &recreate, err, sizeof err) != SS_OK || recreate)
    NODE_WARN_THROTTLE(5.0, "step budget: cannot change substeps or iterations: %s", err);
}

/* The wall time a step may take, ms: ~step_budget, or the input's period (0: none
 * yet, or none asked for). */
static double step_budget_ms(const node *nd)
{
  if (nd->p.step_budget > 0.0) return 1e3 * nd->p.step_budget;
  if (nd->p.step_budget < 0.0) return 0.0;
  return 1e-3 * (double)nd->stream.period_us;
}

static void process(node *nd, const mailbox *b)
{
  char err[ERR_SZ] = "";
  int chk = ss_input_mesh_check(b->npos, b->pos, b->ntri, b->tri, err, sizeof err);
  if (chk != SS_OK) {
    if (b->disc) nd->carry_disc = b->disc;
    reject(nd, chk == SS_E_NONFINITE ? REJECT_NONFINITE : REJECT_MALFORMED, err);
    return;
  }
  int64_t now_ns = ss_msg_time_to_ns(b->header.stamp);
  if (nd->sim && b->topology_id == nd->topology_id &&
      !ss_input_same_topology(b->npos, b->ntri, b->tri, nd->nbvert, nd->nbface, nd->bfaces, err,
                              sizeof err)) {
    char why[ERR_SZ + 64];
    snprintf(why, sizeof why, "topology changed without a new topology_id (%s)", err);
    if (b->disc) nd->carry_disc = b->disc;
    reject(nd, REJECT_TOPOLOGY, why);
    return;
  }
  if (b->nrigid && b->nrigid != b->npos / 3) {
    char why[128];
    snprintf(why, sizeof why, "rigid_part has %zu values for %zu vertices (0 or one a vertex)",
             b->nrigid, b->npos / 3);
    if (b->disc) nd->carry_disc = b->disc;
    reject(nd, REJECT_RIGID_PART, why);
    return;
  }
  /* the step covers whole input periods since the skin's clock, in the substeps of
   * one period: frames the node skipped never add substeps nor reset the skin */
  int disc = b->disc ? b->disc : nd->carry_disc;
  nd->carry_disc = 0;
  ss_input_plan plan;
  int kind = ss_input_plan_step(&nd->stream, nd->sim != NULL, nd->skin_ns, now_ns, disc,
                                nd->prev_periods, nd->p.max_step, nd->p.max_split, &plan);
  double dt = plan.dt;
  ss_sim_stats acc;
  memset(&acc, 0, sizeof acc);
  double t0 = 0, t1 = 0;
  rosc_wall_now_s(&t0);
  int nsplit = 0;
  if (!nd->sim || b->topology_id != nd->topology_id || kind == SS_TIME_BACKWARDS ||
      kind == SS_TIME_GAP || nd->reset_req || nd->recreate_req) {
    if (nd->sim && nd->recreate_req && !nd->reset_req) {
      nd->resets++;
      ROSC_INFO("dynamic_reconfigure: skin created again with the new settings on the body's "
                "pose at %.3f s (%u resets so far)", 1e-9 * (double)now_ns, (unsigned)nd->resets);
    } else if (nd->sim && nd->reset_req) {
      nd->resets++;
      ROSC_INFO("~reset: skin created again on the body's pose at %.3f s (%u resets so far)",
                1e-9 * (double)now_ns, (unsigned)nd->resets);
    } else if (nd->sim && b->topology_id != nd->topology_id)
      ROSC_INFO("topology_id %u -> %u: new skin", (unsigned)nd->topology_id,
                (unsigned)b->topology_id);
    else if (nd->sim) {
      nd->resets++;
      NODE_WARN_THROTTLE(1.0, "the input's time %s before the stamp %.3f s: skin reset (%u resets "
                         "so far)", kind == SS_TIME_GAP ? "jumped forward" : "went backwards",
                         1e-9 * (double)now_ns, (unsigned)nd->resets);
    }
    nd->reset_req = nd->recreate_req = 0;
    if (!create_sim(nd, b)) return;
    nd->skin_ns = now_ns;
    nd->prev_periods = 0;
  } else if (kind == SS_TIME_STEP) {
    size_t n3 = 3 * (size_t)nd->nbvert;
    for (size_t i = 0; i < n3; i++) nd->body[i] = (double)b->pos[i];
    nsplit = plan.substeps;
    /* the work in force: the budget's substeps and iterations; a step that
     * catches up several periods gets no extra iterations for being late */
    nd->budget_ms = step_budget_ms(nd);
    ss_sim_settings run = nd->p.set;
    run.substeps = nd->budget.substeps;
    run.iterations = nd->budget.iterations;
    if (plan.periods > 1) run.safety_residual = 0.0;
    apply_run(nd, &run);
    for (int k = 1; k <= nsplit; k++) {
      const double *pose = nd->body;
      if (k < nsplit) {
        double w = (double)k / (double)nsplit;
        for (size_t i = 0; i < n3; i++)
          nd->body_sub[i] = nd->body_prev[i] + w * (nd->body[i] - nd->body_prev[i]);
        pose = nd->body_sub;
      }
      ss_sim_stats st;
      int rc = ss_sim_step(nd->sim, pose, dt / nsplit, &st, err, sizeof err);
      if (rc != SS_OK) {
        if (rc == SS_E_SOLVER) {
          NODE_ERROR_THROTTLE(1.0, "skin step failed, last good state kept: %s", err);
          break;
        }
        /* input the core refused: the state is untouched */
        memcpy(nd->body, nd->body_prev, n3 * sizeof(double));
        nd->carry_disc = disc;
        reject(nd, REJECT_STEP, err);
        return;
      }
      acc.pose_ms += st.pose_ms; acc.walk_ms += st.walk_ms; acc.assemble_ms += st.assemble_ms;
      acc.factor_ms += st.factor_ms; acc.solve_ms += st.solve_ms;
      acc.substeps += st.substeps; acc.iterations += st.iterations;
      acc.residual = st.residual;
      acc.anchors_boundary += st.anchors_boundary; acc.anchors_crease += st.anchors_crease;
      acc.failures += st.failures;
      nd->steps++;
      nd->steps_multi += st.threads > 1;
    }
    if (acc.failures) {
      nd->failures += (uint32_t)acc.failures;
      NODE_WARN_THROTTLE(1.0, "%d substeps met non-finite values (last good state kept; %u so "
                         "far)", acc.failures, (unsigned)nd->failures);
    }
    memcpy(nd->body_prev, nd->body, n3 * sizeof(double));
    nd->skin_ns = plan.skin_ns;
    nd->prev_periods = plan.periods;
    ss_sim_count_off_body(nd->sim, &nd->faces_turned, &nd->vertices_far);
  }
  /* SS_TIME_SAME: nothing to step; the state is published again */
  rosc_wall_now_s(&t1);
  nd->processed++;
  if (kind == SS_TIME_STEP && nsplit > 0) { /* creations are not steps: not timed here */
    double ms = 1e3 * (t1 - t0);
    nd->nstep_ms++;
    nd->step_ms_sum += ms;
    if (ms > nd->step_ms_max) nd->step_ms_max = ms;
  }
  node_publish(nd, &b->header, &acc, 1e3 * (t1 - t0), acc.substeps);
  if (kind == SS_TIME_STEP && nsplit > 0) {
    /* the budget judges the whole of a step, publishing included */
    double t2 = t1;
    rosc_wall_now_s(&t2);
    int before_s = nd->budget.substeps, before_i = nd->budget.iterations;
    if (ss_budget_update(&nd->budget, 1e3 * (t2 - t0), nd->budget_ms))
      NODE_LOG_THROTTLE(ROSC_LOG_INFO, 1.0, "~step_budget %.1f ms: %d x %d -> %d substeps x %d "
                        "iterations (the settings' %d x %d)", nd->budget_ms, before_s, before_i,
                        nd->budget.substeps, nd->budget.iterations, nd->p.set.substeps,
                        nd->p.set.iterations);
  }
}

int main(int argc, char **argv)
{
  if (argc == 2 && strcmp(argv[1], "--params-markdown") == 0) { /* the manual's rows */
    skin_params_markdown(stdout);
    return 0;
  }
  int st = rosc_init(&argc, argv, "skin_sim", 0, -1.0);
  if (st != ROSC_OK) {
    fprintf(stderr, "skin_sim_node: rosc_init: %s\n", rosc_strerror(st));
    return 1;
  }
  node *nd = calloc(1, sizeof *nd);
  if (!nd) return 1;
  if (!skin_params_read(&nd->p) || (nd->p.skin_mesh[0] && !load_skin_file(nd))) {
    ss_weld_destroy(nd->skin.weld);
    free(nd->skin.faces);
    free(nd);
    rosc_shutdown();
    return 2;
  }
  nd->in.cap = nd->p.queue_size;
  nd->in.slot = calloc((size_t)nd->in.cap, sizeof *nd->in.slot);
  msg_sub *sub = NULL;
  rosc_srv *srv_reset = NULL;
  int status = 1;
  if (!nd->in.slot) goto done;
  /* A SIGINT during set-up (roslaunch stopping a node still starting) makes roscpp
   * refuse new publishers: then a clean stop (exit 0) that destroys what was made. */
  if (msg_pub_create(&nd->pub_mesh, SS_MSG_SKIN_MESH, "skin_mesh", 4, 0) != ROSC_OK ||
      msg_pub_create(&nd->pub_stats, SS_MSG_SKIN_STATS, "skin_stats", 10, 0) != ROSC_OK ||
      msg_pub_create(&nd->pub_marker, SS_MSG_MARKER, "skin_marker", 1, 0) != ROSC_OK ||
      msg_subscribe(&sub, SS_MSG_SKIN_MESH, "kinematic_mesh", (unsigned)nd->p.queue_size + 2,
                    on_mesh, check_mesh, nd) != ROSC_OK) {
    if (rosc_ok()) ROSC_ERROR("cannot advertise or subscribe");
    else status = 0;
    goto done;
  }
  char node_name[256] = "skin_sim";
  rosc_node_name(node_name, sizeof node_name);
  if (rosc_srv_empty(&srv_reset, "~reset", node_on_reset, nd) != ROSC_OK ||
      rosc_diag_create(&nd->diag, node_name, "skin") != ROSC_OK) {
    if (rosc_ok()) ROSC_ERROR("cannot advertise ~reset or /diagnostics");
    else status = 0;
    goto done;
  }
  if (!node_serve_settings(nd)) {
    ROSC_ERROR("cannot serve dynamic_reconfigure (~set_parameters)");
    rosc_shutdown();
    return 1;
  }
  rosc_wall_now_s(&nd->diag_wall);
  ROSC_INFO("skin_sim: solver %s, method %s, stiffness %g N/m/m^2, young %g N/m, slide %g, "
            "substeps %d, iterations %d, marker %g Hz", ss_solver_name(nd->p.set.solver),
            ss_method_name(nd->p.set.mover.method), nd->p.set.anchor_stiffness, nd->p.set.young,
            nd->p.set.slide, nd->p.set.substeps, nd->p.set.iterations, nd->p.marker_rate);
  while (rosc_ok()) {
    /* callbacks only fill the inbox; one mesh is stepped between spins */
    rosc_spin_once(nd->in.count ? 0.0 : 0.1);
    if (nd->in.count) {
      /* /diagnostics goes on from the shim's own thread if this step takes long */
      nd->busy_period_ms = 1e-3 * (double)nd->stream.period_us;
      rosc_diag_busy(nd->diag, node_busy_status, nd);
      process(nd, &nd->in.slot[nd->in.head]);
      rosc_diag_busy(nd->diag, NULL, NULL);
      release_large(&nd->in.slot[nd->in.head]);
      nd->in.head = (nd->in.head + 1) % nd->in.cap;
      nd->in.count--;
    }
    node_diagnose(nd);
  }
  ROSC_INFO("skin_sim: %lu meshes in, %lu out, %u rejected, %u dropped, %u skipped, %u resets",
            nd->frames_in, nd->frames_out, (unsigned)nd->rejected,
            (unsigned)(nd->dropped + nd->stream.lost), (unsigned)nd->skipped, (unsigned)nd->resets);
  status = 0;
done:
  rosc_srv_destroy(srv_reset);
  node_dr_destroy(nd->dr);
  rosc_diag_destroy(nd->diag);
  msg_sub_destroy(sub);
  msg_pub_destroy(nd->pub_mesh);
  msg_pub_destroy(nd->pub_stats);
  msg_pub_destroy(nd->pub_marker);
  rosc_shutdown();
  free_sim(nd);
  for (int i = 0; nd->in.slot && i < nd->in.cap; i++) {
    free(nd->in.slot[i].pos);
    free(nd->in.slot[i].tri);
    free(nd->in.slot[i].rigid);
  }
  free(nd->in.slot);
  ss_weld_destroy(nd->skin.weld);
  free(nd->skin.faces);
  free(nd);
  return status;
}
