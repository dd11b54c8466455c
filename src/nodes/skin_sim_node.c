/* skin_sim_node: the sliding skin as a ROS 1 node (glue only).
 *
 * Subscribes kinematic_mesh (skin_sim/SkinMesh, the moving body), steps an
 * ss_sim for the time between stamps and publishes, with the input's stamp and
 * frame: skin_mesh (SkinMesh), skin_stats (SkinStats) and, at ~marker_rate,
 * skin_marker (visualization_msgs/Marker TRIANGLE_LIST coloured by how far
 * the skin has slid from where it was bound).
 *
 * The simulation is created on the first good mesh (its pose is the rest
 * shape) and again when topology_id changes, time goes backwards (a bag
 * looping) or the stamps jump forward by more than ~max_gap. The step length
 * comes from the stamps, never from the wall clock, so a replayed bag gives
 * the same output bit for bit. Bad messages (see ss_input.h) are rejected
 * with a throttled log line and counted; the last good state is kept. Received
 * meshes wait in a ring of ~queue_size slots (default 1: only the newest);
 * when it is full the oldest is dropped (counted), so nothing queues without
 * bound. roscpp's own queue holds ~queue_size + 32 (it only fills during one
 * step, as the node spins between steps); meshes it drops silently show as gaps
 * in header.seq and are counted too.
 *
 * Parameters: see README.md ("ROS nodes") and launch/skin.launch. */
#include "rosc/rosc.h"
#include "skin_sim/ss_input.h"
#include "skin_sim/ss_sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ERR_SZ 512

typedef struct params {
  ss_sim_settings set;
  double max_gap;     /* s */
  double max_step;    /* s */
  int max_split;
  double marker_rate; /* Hz; 0 off; < 0 every frame */
  double slide_scale; /* m: red at this slide */
  int queue_size;
  int have_box;
  double box[6];      /* xmin ymin zmin xmax ymax zmax */
} params;

typedef struct mailbox {
  rosc_header header;
  uint32_t topology_id;
  float *pos;
  size_t npos, cap_pos;
  uint32_t *tri;
  size_t ntri, cap_tri;
} mailbox;

/* Received meshes waiting to be stepped: a ring of ~queue_size slots; when it is
 * full the oldest is dropped (counted). Slots keep their buffers, so a steady
 * stream does not allocate. */
typedef struct inbox {
  mailbox *slot;
  int cap, head, count;
} inbox;

typedef struct node {
  params p;
  inbox in;
  rosc_pub *pub_mesh, *pub_stats, *pub_marker;
  /* simulation and its topology */
  ss_sim *sim;
  uint32_t topology_id;
  int nvert, nface;
  int *faces;             /* (nface x 3) as received */
  uint32_t *tri_out;      /* (nface x 3) */
  unsigned char *mask;    /* (nface) or NULL */
  int nanchor;
  int *face0;             /* (nanchor) anchors as bound at create */
  double *uv0;            /* (nanchor x 2) */
  double *slide;          /* (nanchor) */
  double *body, *body_prev, *body_sub; /* (nvert x 3) */
  float *pos_out;         /* (nvert x 3) */
  float *mk_pts, *mk_col; /* (nface x 3 x 3), (nface x 3 x 4) */
  int64_t prev_ns;
  int have_prev;
  /* counters */
  uint32_t rejected, dropped, resets;
  uint32_t last_seq;
  int have_seq;
  unsigned long frames_in, frames_out, steps;
  double last_marker_wall;
} node;

/* ------------------------------------------------------------------ parameters */
static int get_params(params *p)
{
  char buf[256];
  int ok = 1;
  p->set = ss_sim_default_settings();
  rosc_param_get_string("~solver", buf, sizeof buf, ss_solver_name(p->set.solver), NULL);
  if ((p->set.solver = ss_solver_parse(buf)) < 0) {
    ROSC_ERROR("~solver: unknown solver '%s' (newton, quasi-newton)", buf);
    ok = 0;
  }
  rosc_param_get_string("~method", buf, sizeof buf, ss_method_name(p->set.mover.method), NULL);
  if ((p->set.mover.method = ss_method_parse(buf)) < 0) {
    ROSC_ERROR("~method: unknown anchor method '%s' (walk, project, nring)", buf);
    ok = 0;
  }
  rosc_param_get_int("~rings", &p->set.mover.nring_rings, p->set.mover.nring_rings, NULL);
  rosc_param_get_int("~walk_max_steps", &p->set.mover.walk_max_steps, p->set.mover.walk_max_steps, NULL);
  rosc_param_get_double("~stiffness", &p->set.anchor_stiffness, p->set.anchor_stiffness, NULL);
  rosc_param_get_double("~young", &p->set.young, p->set.young, NULL);
  rosc_param_get_double("~poisson", &p->set.poisson, p->set.poisson, NULL);
  rosc_param_get_double("~density", &p->set.density, p->set.density, NULL);
  rosc_param_get_double("~slide", &p->set.slide, p->set.slide, NULL);
  rosc_param_get_double("~tether", &p->set.tether, p->set.tether, NULL);
  rosc_param_get_int("~substeps", &p->set.substeps, p->set.substeps, NULL);
  rosc_param_get_int("~iterations", &p->set.iterations, p->set.iterations, NULL);
  rosc_param_get_double("~tol", &p->set.tol, p->set.tol, NULL);
  rosc_param_get_int("~lbfgs_history", &p->set.lbfgs_history, p->set.lbfgs_history, NULL);
  rosc_param_get_double("~bending", &p->set.bending, p->set.bending, NULL);
  rosc_param_get_double("~damping", &p->set.damping, p->set.damping, NULL);
  rosc_param_get_bool("~barycenters", &p->set.barycenter_anchors, p->set.barycenter_anchors, NULL);
  rosc_param_get_string("~gravity", buf, sizeof buf, "0 0 0", NULL);
  if (sscanf(buf, "%lf %lf %lf", &p->set.gravity[0], &p->set.gravity[1], &p->set.gravity[2]) != 3) {
    ROSC_ERROR("~gravity: '%s' is not three numbers 'x y z' (m/s^2)", buf);
    ok = 0;
  }
  rosc_param_get_string("~mask_box", buf, sizeof buf, "", NULL);
  p->have_box = 0;
  if (buf[0]) {
    double *b = p->box;
    if (sscanf(buf, "%lf %lf %lf %lf %lf %lf", b, b + 1, b + 2, b + 3, b + 4, b + 5) != 6) {
      ROSC_ERROR("~mask_box: '%s' is not six numbers 'xmin ymin zmin xmax ymax zmax' (m)", buf);
      ok = 0;
    } else {
      p->have_box = 1;
    }
  }
  rosc_param_get_double("~max_gap", &p->max_gap, 0.5, NULL);
  rosc_param_get_double("~max_step", &p->max_step, 0.05, NULL);
  rosc_param_get_int("~max_split", &p->max_split, 8, NULL);
  rosc_param_get_double("~marker_rate", &p->marker_rate, 10.0, NULL);
  rosc_param_get_double("~slide_scale", &p->slide_scale, 0.05, NULL);
  rosc_param_get_int("~queue_size", &p->queue_size, 1, NULL);
  if (p->queue_size < 1) p->queue_size = 1;
  if (p->queue_size > 1000) p->queue_size = 1000;
  if (p->max_split < 1) p->max_split = 1;
  if (!(p->max_gap > 0.0)) {
    ROSC_ERROR("~max_gap must be > 0 s");
    ok = 0;
  }
  if (ok) {
    /* the core judges its settings: try them on a tetrahedron */
    static const double tv[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const int tf[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    char err[ERR_SZ] = "";
    ss_sim *t = NULL;
    int st = ss_sim_create(&t, 4, tv, 4, tf, NULL, &p->set, err, sizeof err);
    ss_sim_destroy(t);
    if (st == SS_E_ARG) {
      ROSC_ERROR("bad skin parameters: %s", err);
      ok = 0;
    }
  }
  return ok;
}

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

static void on_mesh(const rosc_skin_mesh *m, void *user)
{
  node *nd = user;
  inbox *q = &nd->in;
  nd->frames_in++;
  /* roscpp numbers the messages of a publisher (header.seq): a gap means meshes lost
   * before they reached this callback (roscpp's queue overflowing during a stall, or
   * the publisher's): counted as dropped too. A smaller seq is a new publisher. */
  uint32_t seq = m->header.seq;
  if (nd->have_seq && seq > nd->last_seq + 1 && seq - nd->last_seq <= 1000000u)
    nd->dropped += seq - nd->last_seq - 1;
  nd->last_seq = seq;
  nd->have_seq = 1;
  if (q->count == q->cap) { /* full: the oldest was never stepped */
    q->head = (q->head + 1) % q->cap;
    q->count--;
    nd->dropped++;
  }
  mailbox *b = &q->slot[(q->head + q->count) % q->cap];
  if (!grow((void **)&b->pos, &b->cap_pos, m->n_positions, sizeof(float)) ||
      !grow((void **)&b->tri, &b->cap_tri, m->n_triangles, sizeof(uint32_t))) {
    ROSC_ERROR_THROTTLE(2.0, "out of memory for a mesh of %zu values", m->n_positions);
    nd->dropped++;
    return;
  }
  if (m->n_positions) memcpy(b->pos, m->positions, m->n_positions * sizeof(float));
  if (m->n_triangles) memcpy(b->tri, m->triangles, m->n_triangles * sizeof(uint32_t));
  b->npos = m->n_positions;
  b->ntri = m->n_triangles;
  b->header = m->header;
  b->topology_id = m->topology_id;
  q->count++;
}

/* Counts a rejected message and logs why, at most once a second per kind of
 * problem (key), so that different problems each show. */
static void reject(node *nd, const char *key, const char *why)
{
  nd->rejected++;
  rosc_log_at(ROSC_LOG_WARN, __FILE__, __LINE__, __func__, 1.0, key,
              "rejected kinematic_mesh: %s (%u rejected so far)", why, (unsigned)nd->rejected);
}

/* ------------------------------------------------------------------ simulation */
static void free_sim(node *nd)
{
  ss_sim_destroy(nd->sim);
  nd->sim = NULL;
  free(nd->faces); free(nd->tri_out); free(nd->mask); free(nd->face0); free(nd->uv0);
  free(nd->slide); free(nd->body); free(nd->body_prev); free(nd->body_sub);
  free(nd->pos_out); free(nd->mk_pts); free(nd->mk_col);
  nd->faces = NULL; nd->tri_out = NULL; nd->mask = NULL; nd->face0 = NULL; nd->uv0 = NULL;
  nd->slide = NULL; nd->body = NULL; nd->body_prev = NULL; nd->body_sub = NULL;
  nd->pos_out = NULL; nd->mk_pts = NULL; nd->mk_col = NULL;
  nd->nvert = nd->nface = nd->nanchor = 0;
  nd->have_prev = 0;
}

/* Creates the simulation with the mailbox's mesh as rest shape. 1 on success. */
static int create_sim(node *nd, const mailbox *b)
{
  free_sim(nd);
  int nv = (int)(b->npos / 3), nf = (int)(b->ntri / 3);
  size_t n3 = 3 * (size_t)nv, f3 = 3 * (size_t)nf;
  nd->faces = malloc(f3 * sizeof(int));
  nd->tri_out = malloc(f3 * sizeof(uint32_t));
  nd->body = malloc(n3 * sizeof(double));
  nd->body_prev = malloc(n3 * sizeof(double));
  nd->body_sub = malloc(n3 * sizeof(double));
  nd->pos_out = malloc(n3 * sizeof(float));
  nd->mk_pts = malloc(3 * f3 * sizeof(float));
  nd->mk_col = malloc(4 * f3 * sizeof(float));
  if (nd->p.have_box) nd->mask = malloc((size_t)nf);
  if (!nd->faces || !nd->tri_out || !nd->body || !nd->body_prev || !nd->body_sub ||
      !nd->pos_out || !nd->mk_pts || !nd->mk_col || (nd->p.have_box && !nd->mask)) {
    ROSC_ERROR("out of memory for a skin of %d vertices", nv);
    free_sim(nd);
    return 0;
  }
  for (size_t i = 0; i < f3; i++) {
    nd->faces[i] = (int)b->tri[i];
    nd->tri_out[i] = b->tri[i];
  }
  for (size_t i = 0; i < n3; i++) nd->body[i] = (double)b->pos[i];
  ss_sim_settings set = nd->p.set;
  set.face_mask = NULL;
  if (nd->mask) {
    const double *bx = nd->p.box;
    int nin = 0;
    for (int f = 0; f < nf; f++) {
      double c[3] = {0, 0, 0};
      for (int k = 0; k < 3; k++)
        for (int d = 0; d < 3; d++) c[d] += nd->body[3 * (size_t)nd->faces[3 * f + k] + d] / 3.0;
      int in = c[0] >= bx[0] && c[1] >= bx[1] && c[2] >= bx[2] && c[0] <= bx[3] &&
               c[1] <= bx[4] && c[2] <= bx[5];
      nd->mask[f] = (unsigned char)in;
      nin += in;
    }
    ROSC_INFO("~mask_box: %d of %d faces simulated", nin, nf);
    set.face_mask = nd->mask;
  }
  char err[ERR_SZ] = "";
  double t0 = 0, t1 = 0;
  rosc_wall_now_s(&t0);
  int st = ss_sim_create(&nd->sim, nv, nd->body, nf, nd->faces, NULL, &set, err, sizeof err);
  rosc_wall_now_s(&t1);
  if (st != SS_OK) {
    char why[ERR_SZ + 64];
    snprintf(why, sizeof why, "cannot simulate it: %s", err);
    free_sim(nd);
    reject(nd, "skin_sim.create", why);
    return 0;
  }
  nd->nvert = nv;
  nd->nface = nf;
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
  memcpy(nd->body_prev, nd->body, n3 * sizeof(double));
  nd->topology_id = b->topology_id;
  ROSC_INFO("skin created: %d vertices, %d triangles, %d anchors, %d unknowns (topology %u, "
            "%.1f ms)", nv, nf, nd->nanchor, ss_sim_ndof(nd->sim), (unsigned)b->topology_id,
            1e3 * (t1 - t0));
  return 1;
}

/* ------------------------------------------------------------------ output */
static void publish(node *nd, const rosc_header *hdr, const ss_sim_stats *acc, double total_ms,
                    int substeps)
{
  const double *x = ss_sim_skin_positions(nd->sim);
  size_t n3 = 3 * (size_t)nd->nvert;
  for (size_t i = 0; i < n3; i++) nd->pos_out[i] = (float)x[i];
  rosc_skin_mesh out;
  memset(&out, 0, sizeof out);
  out.header = *hdr;
  out.topology_id = nd->topology_id;
  out.positions = nd->pos_out;
  out.n_positions = n3;
  out.triangles = nd->tri_out;
  out.n_triangles = 3 * (size_t)nd->nface;
  if (rosc_publish_skin_mesh(nd->pub_mesh, &out) == ROSC_OK) nd->frames_out++;

  double max_slide =
      ss_input_slide(nd->nanchor, ss_sim_anchor_faces(nd->sim), ss_sim_anchor_uv(nd->sim),
                     nd->face0, nd->uv0, nd->body, nd->nvert, nd->faces, nd->nface, nd->slide);
  rosc_skin_stats s;
  memset(&s, 0, sizeof s);
  s.header = *hdr;
  s.total_ms = (float)total_ms;
  s.walk_ms = (float)acc->walk_ms;
  s.assemble_ms = (float)acc->assemble_ms;
  s.solve_ms = (float)(acc->factor_ms + acc->solve_ms);
  s.iterations = (uint32_t)acc->iterations;
  s.residual = (float)acc->residual;
  s.substeps = (uint32_t)substeps;
  s.anchors_at_boundary = (uint32_t)acc->anchors_boundary;
  s.anchors_at_crease = (uint32_t)acc->anchors_crease;
  s.max_slide = (float)max_slide;
  s.inputs_rejected = nd->rejected;
  s.inputs_dropped = nd->dropped;
  s.resets = nd->resets;
  rosc_publish_skin_stats(nd->pub_stats, &s);

  if (nd->p.marker_rate == 0.0) return;
  double now = 0;
  rosc_wall_now_s(&now);
  if (nd->p.marker_rate > 0.0 && now - nd->last_marker_wall < 1.0 / nd->p.marker_rate) return;
  unsigned nsub = 0;
  rosc_pub_num_subscribers(nd->pub_marker, &nsub);
  if (nsub == 0) return;
  nd->last_marker_wall = now;
  for (int f = 0; f < nd->nface; f++) {
    for (int k = 0; k < 3; k++) {
      int v = nd->faces[3 * f + k];
      size_t c = 3 * (size_t)f + (size_t)k;
      for (int d = 0; d < 3; d++) nd->mk_pts[3 * c + d] = nd->pos_out[3 * (size_t)v + d];
      /* vertex anchors come first: anchor v belongs to skin vertex v */
      ss_input_slide_color(nd->slide[v], nd->p.slide_scale, nd->mk_col + 4 * c);
    }
  }
  rosc_marker mk;
  rosc_marker_init_triangle_list(&mk);
  mk.header = *hdr;
  snprintf(mk.ns, sizeof mk.ns, "skin");
  mk.id = 0;
  mk.points = nd->mk_pts;
  mk.n_points = 3 * (size_t)nd->nface;
  mk.colors = nd->mk_col;
  mk.n_colors = 3 * (size_t)nd->nface;
  rosc_publish_marker(nd->pub_marker, &mk);
}

static void process(node *nd, const mailbox *b)
{
  char err[ERR_SZ] = "";
  int chk = ss_input_mesh_check(b->npos, b->pos, b->ntri, b->tri, err, sizeof err);
  if (chk != SS_OK) {
    reject(nd, chk == SS_E_NONFINITE ? "skin_sim.nonfinite" : "skin_sim.malformed", err);
    return;
  }
  int64_t now_ns = rosc_time_to_ns(b->header.stamp);
  if (nd->sim && b->topology_id == nd->topology_id &&
      !ss_input_same_topology(b->npos, b->ntri, b->tri, nd->nvert, nd->nface, nd->faces, err,
                              sizeof err)) {
    char why[ERR_SZ + 64];
    snprintf(why, sizeof why, "topology changed without a new topology_id (%s)", err);
    reject(nd, "skin_sim.topology", why);
    return;
  }
  double dt = 0.0;
  int kind = ss_input_classify_time(nd->sim != NULL, nd->prev_ns, now_ns, nd->p.max_gap, &dt);
  ss_sim_stats acc;
  memset(&acc, 0, sizeof acc);
  double t0 = 0, t1 = 0;
  rosc_wall_now_s(&t0);
  int nsplit = 0;
  if (!nd->sim || b->topology_id != nd->topology_id || kind == SS_TIME_BACKWARDS ||
      kind == SS_TIME_GAP) {
    if (nd->sim && b->topology_id != nd->topology_id)
      ROSC_INFO("topology_id %u -> %u: new skin", (unsigned)nd->topology_id,
                (unsigned)b->topology_id);
    else if (nd->sim) {
      nd->resets++;
      ROSC_WARN_THROTTLE(1.0, "time %s (%.3f s after %.3f s): skin reset (%u resets so far)",
                         kind == SS_TIME_GAP ? "jumped forward" : "went backwards",
                         1e-9 * (double)now_ns, 1e-9 * (double)nd->prev_ns, (unsigned)nd->resets);
    }
    if (!create_sim(nd, b)) return;
  } else if (kind == SS_TIME_STEP) {
    size_t n3 = 3 * (size_t)nd->nvert;
    for (size_t i = 0; i < n3; i++) nd->body[i] = (double)b->pos[i];
    nsplit = ss_input_split_steps(dt, nd->p.max_step, nd->p.max_split);
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
          ROSC_ERROR_THROTTLE(1.0, "skin step failed, last good state kept: %s", err);
          break;
        }
        /* input the core refused: the state is untouched */
        memcpy(nd->body, nd->body_prev, n3 * sizeof(double));
        reject(nd, "skin_sim.step", err);
        return;
      }
      acc.pose_ms += st.pose_ms; acc.walk_ms += st.walk_ms; acc.assemble_ms += st.assemble_ms;
      acc.factor_ms += st.factor_ms; acc.solve_ms += st.solve_ms;
      acc.substeps += st.substeps; acc.iterations += st.iterations;
      acc.residual = st.residual;
      acc.anchors_boundary += st.anchors_boundary; acc.anchors_crease += st.anchors_crease;
      acc.failures += st.failures;
      nd->steps++;
    }
    if (acc.failures)
      ROSC_WARN_THROTTLE(1.0, "%d substeps met non-finite values (last good state kept)",
                         acc.failures);
    memcpy(nd->body_prev, nd->body, n3 * sizeof(double));
  }
  /* SS_TIME_SAME: nothing to step; the state is published again */
  nd->prev_ns = now_ns;
  rosc_wall_now_s(&t1);
  publish(nd, &b->header, &acc, 1e3 * (t1 - t0), acc.substeps);
}

int main(int argc, char **argv)
{
  int st = rosc_init(&argc, argv, "skin_sim", 0, -1.0);
  if (st != ROSC_OK) {
    fprintf(stderr, "skin_sim_node: rosc_init: %s\n", rosc_strerror(st));
    return 1;
  }
  node *nd = calloc(1, sizeof *nd);
  if (!nd) return 1;
  if (!get_params(&nd->p)) {
    free(nd);
    rosc_shutdown();
    return 2;
  }
  nd->in.cap = nd->p.queue_size;
  nd->in.slot = calloc((size_t)nd->in.cap, sizeof *nd->in.slot);
  if (!nd->in.slot) return 1;
  rosc_sub *sub = NULL;
  if (rosc_pub_create(&nd->pub_mesh, ROSC_MSG_SKIN_MESH, "skin_mesh", 4, 0) != ROSC_OK ||
      rosc_pub_create(&nd->pub_stats, ROSC_MSG_SKIN_STATS, "skin_stats", 10, 0) != ROSC_OK ||
      rosc_pub_create(&nd->pub_marker, ROSC_MSG_MARKER, "skin_marker", 1, 0) != ROSC_OK ||
      rosc_sub_skin_mesh(&sub, "kinematic_mesh", (unsigned)nd->p.queue_size + 32, on_mesh, nd) !=
          ROSC_OK) {
    ROSC_ERROR("cannot advertise or subscribe");
    rosc_shutdown();
    return 1;
  }
  ROSC_INFO("skin_sim: solver %s, method %s, stiffness %g N/m/m^2, young %g N/m, slide %g, "
            "substeps %d, iterations %d, marker %g Hz", ss_solver_name(nd->p.set.solver),
            ss_method_name(nd->p.set.mover.method), nd->p.set.anchor_stiffness, nd->p.set.young,
            nd->p.set.slide, nd->p.set.substeps, nd->p.set.iterations, nd->p.marker_rate);
  while (rosc_ok()) {
    /* callbacks only fill the inbox; one mesh is stepped between spins */
    rosc_spin_once(nd->in.count ? 0.0 : 0.1);
    if (nd->in.count) {
      process(nd, &nd->in.slot[nd->in.head]);
      nd->in.head = (nd->in.head + 1) % nd->in.cap;
      nd->in.count--;
    }
  }
  ROSC_INFO("skin_sim: %lu meshes in, %lu out, %u rejected, %u dropped, %u resets",
            nd->frames_in, nd->frames_out, (unsigned)nd->rejected, (unsigned)nd->dropped,
            (unsigned)nd->resets);
  rosc_sub_destroy(sub);
  rosc_pub_destroy(nd->pub_mesh);
  rosc_pub_destroy(nd->pub_stats);
  rosc_pub_destroy(nd->pub_marker);
  rosc_shutdown();
  free_sim(nd);
  for (int i = 0; i < nd->in.cap; i++) {
    free(nd->in.slot[i].pos);
    free(nd->in.slot[i].tri);
  }
  free(nd->in.slot);
  free(nd);
  return 0;
}
