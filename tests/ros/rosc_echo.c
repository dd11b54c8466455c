/* rosc_echo: the two ends of tests/ros/test_rosc.sh, through a real master.
 *
 *   rosc_echo relay [ROS args]   subscribes mesh_in, stats_in, joints_in, marker_in,
 *                                string_in and republishes each message unchanged on
 *                                mesh_out, ... (the script remaps them); exits 0 when
 *                                the string "quit" arrives or on SIGINT.
 *   rosc_echo check [ROS args]   the test: parameters (private from the command line,
 *                                global set here, defaults, wrong types), then publishes
 *                                SkinMesh / SkinStats / JointState / Marker / String
 *                                messages on *_a, receives them back from the relay on
 *                                *_b (TCP, another process) and from itself on *_a
 *                                (roscpp's in-process path), and compares every byte;
 *                                latching, rejected inputs, time, rate, logging.
 *
 *   rosc_echo ping N HZ VERTICES  round trips of big SkinMesh messages through the relay
 *                                at a fixed rate: all must come back, in order, intact.
 *   rosc_echo listen N TIMEOUT_S prints the SkinMesh messages arriving on mesh_in (sent
 *                                by tests/ros/pub_mesh.py: rospy, not rosc).
 *
 * The script passes the check's private parameters as _p_double:=2.5 _p_int:=7
 * _p_str:=hello _p_bool:=true _p_int_as_double:=3.0 (see test_rosc.sh).
 */
#include "node_log.h"  /* the nodes' throttled logging (src/nodes) */
#include "node_msg.h" /* the nodes' typed topics (src/nodes) */
#include "ss_dynreconf.h"
#include "rosc_test.h" /* rosc/rosc.h and the calls only tests make */
#include "ss_test.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N_MSG 6        /* messages of each type */
#define BIG_VERTS 100000

/* A std_msgs/String holding text (NULL: no view, refused). */
static int publish_string(msg_pub *p, const char *text)
{
  ss_msg_string m = {text};
  return msg_publish(p, SS_MSG_STRING, text != NULL ? &m : NULL);
}

/* ------------------------------------------------------------------ relay */
typedef struct relay {
  msg_pub *mesh, *stats, *joints, *marker, *string;
  int quit;
  unsigned long relayed;
} relay;

static void relay_mesh(const void *msg, void *u)
{
  const ss_msg_skin_mesh *m = msg;
  relay *r = u;
  if (msg_publish(r->mesh, SS_MSG_SKIN_MESH, m) == ROSC_OK) r->relayed++;
}
static void relay_stats(const void *msg, void *u)
{
  const ss_msg_skin_stats *m = msg;
  relay *r = u;
  if (msg_publish(r->stats, SS_MSG_SKIN_STATS, m) == ROSC_OK) r->relayed++;
}
static void relay_joints(const void *msg, void *u)
{
  const ss_msg_joint_state *m = msg;
  relay *r = u;
  if (msg_publish(r->joints, SS_MSG_JOINT_STATE, m) == ROSC_OK) r->relayed++;
}
static void relay_marker(const void *msg, void *u)
{
  const ss_msg_marker *m = msg;
  relay *r = u;
  if (msg_publish(r->marker, SS_MSG_MARKER, m) == ROSC_OK) r->relayed++;
}
static void relay_string(const void *msg, void *u)
{
  const ss_msg_string *m = msg;
  relay *r = u;
  if (strcmp(m->data, "quit") == 0) {
    r->quit = 1;
    return;
  }
  if (publish_string(r->string, m->data) == ROSC_OK) r->relayed++;
}

static int run_relay(int argc, char **argv)
{
  int st = rosc_init(&argc, argv, "rosc_relay", 0, 10.0);
  if (st != ROSC_OK) {
    fprintf(stderr, "relay: rosc_init: %s\n", rosc_strerror(st));
    return 1;
  }
  relay r;
  memset(&r, 0, sizeof r);
  msg_sub *subs[5] = {NULL};
  int ok = 1;
  /* the mesh queues hold a whole ping burst (see run_ping) */
  ok &= msg_pub_create(&r.mesh, SS_MSG_SKIN_MESH, "mesh_out", 128, 0) == ROSC_OK;
  ok &= msg_pub_create(&r.stats, SS_MSG_SKIN_STATS, "stats_out", 20, 0) == ROSC_OK;
  ok &= msg_pub_create(&r.joints, SS_MSG_JOINT_STATE, "joints_out", 20, 0) == ROSC_OK;
  ok &= msg_pub_create(&r.marker, SS_MSG_MARKER, "marker_out", 20, 0) == ROSC_OK;
  ok &= msg_pub_create(&r.string, SS_MSG_STRING, "string_out", 20, 0) == ROSC_OK;
  ok &= msg_subscribe(&subs[0], SS_MSG_SKIN_MESH, "mesh_in", 128, relay_mesh, NULL, &r) == ROSC_OK;
  ok &= msg_subscribe(&subs[1], SS_MSG_SKIN_STATS, "stats_in", 20, relay_stats, NULL, &r) == ROSC_OK;
  ok &= msg_subscribe(&subs[2], SS_MSG_JOINT_STATE, "joints_in", 20, relay_joints, NULL, &r) == ROSC_OK;
  ok &= msg_subscribe(&subs[3], SS_MSG_MARKER, "marker_in", 20, relay_marker, NULL, &r) == ROSC_OK;
  ok &= msg_subscribe(&subs[4], SS_MSG_STRING, "string_in", 20, relay_string, NULL, &r) == ROSC_OK;
  /* A SIGINT during set-up (roslaunch stopping a node that is still starting, e.g.
   * on a loaded machine) makes roscpp refuse new publishers: a clean stop, exit 0. */
  int interrupted = !ok && !rosc_ok();
  if (!ok && !interrupted) fprintf(stderr, "relay: could not create publishers/subscribers\n");
  if (ok) {
    ROSC_INFO("relay ready");
    while (rosc_ok() && !r.quit) rosc_spin_once(0.1);
    ROSC_INFO("relay: %lu messages relayed, quitting", r.relayed);
  }
  for (int i = 0; i < 5; ++i) msg_sub_destroy(subs[i]);
  msg_pub_destroy(r.mesh);
  msg_pub_destroy(r.stats);
  msg_pub_destroy(r.joints);
  msg_pub_destroy(r.marker);
  msg_pub_destroy(r.string);
  /* no rosc_shutdown(): the shim's atexit handler must stop the node cleanly (a
   * sanitizer build checks that for leaks and use after free) */
  if (!ok && !interrupted) return 1;
  return 0;   /* "quit" arrived, or SIGINT (roscpp's handler) stopped the node */
}

/* ------------------------------------------------------------------ deep copies */
typedef struct mesh_copy {
  ss_msg_header h;
  uint32_t topo;
  float *pos;
  size_t npos;
  uint32_t *tri;
  size_t ntri;
  uint32_t *rigid;
  size_t nrigid;
} mesh_copy;

typedef struct joints_copy {
  ss_msg_header h;
  char **name;
  size_t nname;
  double *pos, *vel, *eff;
  size_t npos, nvel, neff;
} joints_copy;

typedef struct marker_copy {
  ss_msg_marker m;   /* arrays below, m's pointers unused */
  float *points, *colors;
  char *text, *res;
} marker_copy;

static void *dup_bytes(const void *p, size_t n)
{
  void *q = malloc(n > 0 ? n : 1);
  if (q == NULL) abort();
  if (n > 0) memcpy(q, p, n);
  return q;
}

static char *dup_str(const char *s) { return dup_bytes(s, strlen(s) + 1); }

static void mesh_copy_set(mesh_copy *c, const ss_msg_skin_mesh *m)
{
  c->h = m->header;
  c->topo = m->topology_id;
  c->npos = m->n_positions;
  c->pos = dup_bytes(m->positions, m->n_positions * sizeof(float));
  c->ntri = m->n_triangles;
  c->tri = dup_bytes(m->triangles, m->n_triangles * sizeof(uint32_t));
  c->nrigid = m->n_rigid_part;
  c->rigid = dup_bytes(m->rigid_part, m->n_rigid_part * sizeof(uint32_t));
}
static void mesh_copy_free(mesh_copy *c)
{
  free(c->pos);
  free(c->tri);
  free(c->rigid);
}

static void joints_copy_set(joints_copy *c, const ss_msg_joint_state *m)
{
  c->h = m->header;
  c->nname = m->n_name;
  c->name = malloc((m->n_name > 0 ? m->n_name : 1) * sizeof(char *));
  if (c->name == NULL) abort();
  for (size_t i = 0; i < m->n_name; ++i) c->name[i] = dup_str(m->name[i]);
  c->npos = m->n_position;
  c->pos = dup_bytes(m->position, m->n_position * sizeof(double));
  c->nvel = m->n_velocity;
  c->vel = dup_bytes(m->velocity, m->n_velocity * sizeof(double));
  c->neff = m->n_effort;
  c->eff = dup_bytes(m->effort, m->n_effort * sizeof(double));
}
static void joints_copy_free(joints_copy *c)
{
  for (size_t i = 0; i < c->nname; ++i) free(c->name[i]);
  free(c->name);
  free(c->pos);
  free(c->vel);
  free(c->eff);
}

static void marker_copy_set(marker_copy *c, const ss_msg_marker *m)
{
  c->m = *m;
  c->points = dup_bytes(m->points, m->n_points * 3 * sizeof(float));
  c->colors = dup_bytes(m->colors, m->n_colors * 4 * sizeof(float));
  c->text = dup_str(m->text);
  c->res = dup_str(m->mesh_resource);
  c->m.points = NULL;
  c->m.colors = NULL;
  c->m.text = NULL;
  c->m.mesh_resource = NULL;
}
static void marker_copy_free(marker_copy *c)
{
  free(c->points);
  free(c->colors);
  free(c->text);
  free(c->res);
}

/* What arrived on one path (relay or in-process). */
typedef struct inbox {
  mesh_copy mesh[N_MSG];
  int n_mesh;
  ss_msg_skin_stats stats[N_MSG];
  int n_stats;
  joints_copy joints[N_MSG];
  int n_joints;
  marker_copy marker[N_MSG];
  int n_marker;
  char *string[N_MSG];
  int n_string;
  int overflow;
} inbox;

static void in_mesh(const void *msg, void *u)
{
  inbox *b = u;
  if (b->n_mesh < N_MSG) mesh_copy_set(&b->mesh[b->n_mesh++], msg);
  else b->overflow++;
}
static void in_stats(const void *msg, void *u)
{
  inbox *b = u;
  if (b->n_stats < N_MSG) b->stats[b->n_stats++] = *(const ss_msg_skin_stats *)msg;
  else b->overflow++;
}
static void in_joints(const void *msg, void *u)
{
  inbox *b = u;
  if (b->n_joints < N_MSG) joints_copy_set(&b->joints[b->n_joints++], msg);
  else b->overflow++;
}
static void in_marker(const void *msg, void *u)
{
  inbox *b = u;
  if (b->n_marker < N_MSG) marker_copy_set(&b->marker[b->n_marker++], msg);
  else b->overflow++;
}
static void in_string(const void *msg, void *u)
{
  const ss_msg_string *m = msg;
  inbox *b = u;
  if (b->n_string < N_MSG) b->string[b->n_string++] = dup_str(m->data);
  else b->overflow++;
}

static int inbox_full(const inbox *b)
{
  return b->n_mesh == N_MSG && b->n_stats == N_MSG && b->n_joints == N_MSG &&
         b->n_marker == N_MSG && b->n_string == N_MSG;
}

static void inbox_free(inbox *b)
{
  for (int i = 0; i < b->n_mesh; ++i) mesh_copy_free(&b->mesh[i]);
  for (int i = 0; i < b->n_joints; ++i) joints_copy_free(&b->joints[i]);
  for (int i = 0; i < b->n_marker; ++i) marker_copy_free(&b->marker[i]);
  for (int i = 0; i < b->n_string; ++i) free(b->string[i]);
}

/* ------------------------------------------------------------------ what is sent */
typedef struct outbox {
  mesh_copy mesh[N_MSG];
  ss_msg_skin_stats stats[N_MSG];
  joints_copy joints[N_MSG];
  marker_copy marker[N_MSG];
  char *string[N_MSG];
} outbox;

static void make_header(ss_msg_header *h, int i, const char *what)
{
  memset(h, 0, sizeof *h);
  h->seq = 1000u + (uint32_t)i;   /* roscpp overwrites it on the wire */
  static const uint32_t secs[N_MSG] = {0u, 1u, 1700000000u, 4294967295u, 12u, 99u};
  static const uint32_t nsecs[N_MSG] = {0u, 999999999u, 123456789u, 1u, 500000000u, 7u};
  h->stamp.sec = secs[i];
  h->stamp.nsec = nsecs[i];
  if (i == 4) {   /* the longest frame_id the struct holds */
    memset(h->frame_id, 'f', SS_MSG_FRAME_ID_MAX - 1);
    h->frame_id[SS_MSG_FRAME_ID_MAX - 1] = '\0';
  } else if (i != 0) {   /* message 0: empty frame_id */
    snprintf(h->frame_id, sizeof h->frame_id, "%s_frame_%d/ü", what, i);
  }
}

static void make_messages(outbox *o)
{
  unsigned long long rng = 0x9e3779b97f4a7c15ULL;
  for (int i = 0; i < N_MSG; ++i) {
    /* SkinMesh: empty, small, large; odd values (NaN payload, -0, inf, denormal) */
    size_t nv = i == 0 ? 0 : (i == 3 ? BIG_VERTS : (size_t)(5 + 11 * i));
    size_t nt = i == 0 ? 0 : nv;   /* nv triangles' worth of indices x 3 */
    float *pos = malloc((3 * nv + 1) * sizeof(float));
    uint32_t *tri = malloc((3 * nt + 1) * sizeof(uint32_t));
    if (pos == NULL || tri == NULL) abort();
    for (size_t k = 0; k < 3 * nv; ++k) pos[k] = (float)((ss_test_rand(&rng) - 0.5) * 4.0);
    for (size_t k = 0; k < 3 * nt; ++k) tri[k] = (uint32_t)(ss_test_rand(&rng) * nv);
    if (nv >= 2) {
      uint32_t nan_bits = 0x7fc12345u, neg_zero = 0x80000000u, denorm = 0x00000001u;
      memcpy(&pos[0], &nan_bits, 4);
      memcpy(&pos[1], &neg_zero, 4);
      memcpy(&pos[2], &denorm, 4);
      pos[3] = INFINITY;
      tri[0] = 0xffffffffu;
    }
    mesh_copy *m = &o->mesh[i];
    make_header(&m->h, i, "mesh");
    m->topo = 77u + (uint32_t)i;
    m->pos = pos;
    m->npos = 3 * nv;
    m->tri = tri;
    m->ntri = 3 * nt;
    /* rigid_part: one a vertex in odd sets, none (unknown) in even ones */
    m->nrigid = i % 2 ? nv : 0;
    m->rigid = malloc((nv > 0 ? nv : 1) * sizeof(uint32_t));
    if (m->rigid == NULL) abort();
    for (size_t v = 0; v < nv; ++v) m->rigid[v] = (uint32_t)(v % 3 == 0 ? 0u : 1u + v % 7);

    /* SkinStats */
    ss_msg_skin_stats *s = &o->stats[i];
    memset(s, 0, sizeof *s);
    make_header(&s->header, i, "stats");
    s->total_ms = 1.25f * (float)i;
    s->walk_ms = 0.1f + (float)i;
    s->assemble_ms = 2.5f;
    s->solve_ms = 3.75f + (float)i;
    s->iterations = 10u + (uint32_t)i;
    s->residual = 1e-7f * (float)(i + 1);
    s->substeps = 1u + (uint32_t)i;
    s->anchors_at_boundary = 3u * (uint32_t)i;
    s->anchors_at_crease = 5u * (uint32_t)i;
    s->max_slide = 0.01f * (float)i;
    s->inputs_rejected = 4294967295u - (uint32_t)i;
    s->inputs_dropped = (uint32_t)i;
    s->resets = 2u * (uint32_t)i;
    s->inputs_skipped = 7u * (uint32_t)i + 1u;
    s->failures = 4294967294u - (uint32_t)i;
    s->latency_ms = 0.5f + 3.25f * (float)i;
    s->triangles_simulated = 19000u + (uint32_t)i;
    s->triangles_carried = 4294967295u - 3u * (uint32_t)i;
    s->iterations_per_substep = 2u + (uint32_t)i;
    s->step_budget_ms = 33.3f + (float)i;
    s->faces_turned = 11u * (uint32_t)i;
    s->vertices_far = 13u * (uint32_t)i + 1u;

    /* JointState: names (UTF-8, empty name), arrays of different lengths */
    joints_copy *j = &o->joints[i];
    memset(j, 0, sizeof *j);
    make_header(&j->h, i, "joints");
    j->nname = i == 0 ? 0 : (size_t)(2 * i + 1);
    j->name = malloc((j->nname + 1) * sizeof(char *));
    if (j->name == NULL) abort();
    for (size_t k = 0; k < j->nname; ++k) {
      char buf[64];
      if (k == 1) buf[0] = '\0';
      else snprintf(buf, sizeof buf, "joint_%d_%zu_é", i, k);
      j->name[k] = dup_str(buf);
    }
    j->npos = j->nname;
    j->nvel = i % 2 ? j->nname : 0;
    j->neff = i == 2 ? 1 : 0;
    j->pos = malloc((j->npos + 1) * sizeof(double));
    j->vel = malloc((j->nvel + 1) * sizeof(double));
    j->eff = malloc((j->neff + 1) * sizeof(double));
    if (j->pos == NULL || j->vel == NULL || j->eff == NULL) abort();
    for (size_t k = 0; k < j->npos; ++k) j->pos[k] = (ss_test_rand(&rng) - 0.5) * 6.283185307179586;
    for (size_t k = 0; k < j->nvel; ++k) j->vel[k] = ss_test_rand(&rng) * 1e-300;
    for (size_t k = 0; k < j->neff; ++k) j->eff[k] = -1.0e300;

    /* Marker: TRIANGLE_LIST with per-vertex colours (i == 5: DELETEALL, empty) */
    marker_copy *mk = &o->marker[i];
    memset(mk, 0, sizeof *mk);
    mk->m.type = SS_MSG_MARKER_TRIANGLE_LIST;
    mk->m.scale[0] = mk->m.scale[2] = 1.0;
    mk->m.color[0] = mk->m.color[1] = mk->m.color[2] = 1.0f;
    make_header(&mk->m.header, i, "marker");
    snprintf(mk->m.ns, sizeof mk->m.ns, "skin_%d", i);
    mk->m.id = -3 + i;
    if (i == 5) mk->m.action = SS_MSG_MARKER_DELETEALL;
    mk->m.position[0] = 0.5 * i;
    mk->m.orientation[2] = 0.7071067811865476;
    mk->m.orientation[3] = 0.7071067811865476;
    mk->m.scale[1] = 2.0;
    mk->m.color[3] = 0.5f;
    mk->m.lifetime[0] = i;
    mk->m.lifetime[1] = 250000000 * (i % 4);
    mk->m.frame_locked = i % 2;
    size_t np = i == 5 ? 0 : (i == 3 ? 3 * 20000 : (size_t)(3 * (i + 1)));
    size_t nc = (i == 2 || i == 5) ? 0 : np;   /* message 2: one colour for all */
    mk->points = malloc((3 * np + 1) * sizeof(float));
    mk->colors = malloc((4 * nc + 1) * sizeof(float));
    if (mk->points == NULL || mk->colors == NULL) abort();
    for (size_t k = 0; k < 3 * np; ++k) mk->points[k] = (float)((ss_test_rand(&rng) - 0.5) * 2.0);
    for (size_t k = 0; k < 4 * nc; ++k) mk->colors[k] = (float)ss_test_rand(&rng);
    mk->m.n_points = np;
    mk->m.n_colors = nc;
    mk->text = dup_str(i == 1 ? "hello, rviz" : "");
    mk->res = dup_str(i == 4 ? "package://skin_sim/meshes/x.dae" : "");
    mk->m.mesh_use_embedded_materials = i == 4;

    /* String */
    char sbuf[64];
    if (i == 0) sbuf[0] = '\0';
    else snprintf(sbuf, sizeof sbuf, "message %d: ünïcödé", i);
    o->string[i] = dup_str(sbuf);
  }
}

static void outbox_free(outbox *o)
{
  for (int i = 0; i < N_MSG; ++i) {
    mesh_copy_free(&o->mesh[i]);
    joints_copy_free(&o->joints[i]);
    marker_copy_free(&o->marker[i]);
    free(o->string[i]);
  }
}

/* The views of message i of each type with arrays (over o's copies). */
static void views_of(const outbox *o, int i, ss_msg_skin_mesh *m, ss_msg_joint_state *j,
                     ss_msg_marker *k)
{
  const mesh_copy *mc = &o->mesh[i];
  const joints_copy *jc = &o->joints[i];
  *m = (ss_msg_skin_mesh){.header = mc->h, .topology_id = mc->topo, .positions = mc->pos,
                          .n_positions = mc->npos, .triangles = mc->tri, .n_triangles = mc->ntri,
                          .rigid_part = mc->nrigid ? mc->rigid : NULL, .n_rigid_part = mc->nrigid};
  *j = (ss_msg_joint_state){.header = jc->h, .name = (const char *const *)jc->name,
                            .n_name = jc->nname, .position = jc->pos, .n_position = jc->npos,
                            .velocity = jc->vel, .n_velocity = jc->nvel, .effort = jc->eff,
                            .n_effort = jc->neff};
  *k = o->marker[i].m;
  k->points = o->marker[i].points;
  k->colors = o->marker[i].colors;
  k->text = o->marker[i].text;
  k->mesh_resource = o->marker[i].res;
}

static int publish_all(outbox *o, int i, msg_pub *pm, msg_pub *ps, msg_pub *pj, msg_pub *pk,
                       msg_pub *pstr)
{
  ss_msg_skin_mesh m;
  ss_msg_joint_state j;
  ss_msg_marker k;
  views_of(o, i, &m, &j, &k);
  int st = 0;
  st |= msg_publish(pm, SS_MSG_SKIN_MESH, &m);
  st |= msg_publish(ps, SS_MSG_SKIN_STATS, &o->stats[i]);
  st |= msg_publish(pj, SS_MSG_JOINT_STATE, &j);
  st |= msg_publish(pk, SS_MSG_MARKER, &k);
  st |= publish_string(pstr, o->string[i]);
  return st;
}

/* ------------------------------------------------------------------ comparisons */
static int same_header(const ss_msg_header *a, const ss_msg_header *b)
{
  return a->stamp.sec == b->stamp.sec && a->stamp.nsec == b->stamp.nsec &&
         strcmp(a->frame_id, b->frame_id) == 0;
}

static int same_bytes(const void *a, const void *b, size_t n) { return n == 0 || memcmp(a, b, n) == 0; }

static void compare(const char *path, const outbox *o, const inbox *b)
{
  CHECK_MSG(b->n_mesh == N_MSG && b->n_stats == N_MSG && b->n_joints == N_MSG &&
                b->n_marker == N_MSG && b->n_string == N_MSG,
            "%s: received %d meshes, %d stats, %d joint states, %d markers, %d strings of %d",
            path, b->n_mesh, b->n_stats, b->n_joints, b->n_marker, b->n_string, N_MSG);
  CHECK_MSG(b->overflow == 0, "%s: %d extra messages", path, b->overflow);
  for (int i = 0; i < b->n_mesh; ++i) {
    const mesh_copy *s = &o->mesh[i], *r = &b->mesh[i];
    CHECK_MSG(same_header(&s->h, &r->h), "%s: mesh %d header", path, i);
    CHECK_MSG(s->topo == r->topo, "%s: mesh %d topology_id", path, i);
    CHECK_MSG(s->npos == r->npos && same_bytes(s->pos, r->pos, s->npos * sizeof(float)),
              "%s: mesh %d positions (%zu vs %zu floats)", path, i, s->npos, r->npos);
    CHECK_MSG(s->ntri == r->ntri && same_bytes(s->tri, r->tri, s->ntri * sizeof(uint32_t)),
              "%s: mesh %d triangles", path, i);
    CHECK_MSG(s->nrigid == r->nrigid &&
              same_bytes(s->rigid, r->rigid, s->nrigid * sizeof(uint32_t)),
              "%s: mesh %d rigid_part (%zu vs %zu values)", path, i, s->nrigid, r->nrigid);
  }
  for (int i = 0; i < b->n_stats; ++i) {
    ss_msg_skin_stats s = o->stats[i], r = b->stats[i];
    CHECK_MSG(same_header(&s.header, &r.header), "%s: stats %d header", path, i);
    memset(&s.header, 0, sizeof s.header);
    memset(&r.header, 0, sizeof r.header);
    CHECK_MSG(memcmp(&s, &r, sizeof s) == 0, "%s: stats %d fields", path, i);
  }
  for (int i = 0; i < b->n_joints; ++i) {
    const joints_copy *s = &o->joints[i], *r = &b->joints[i];
    CHECK_MSG(same_header(&s->h, &r->h), "%s: joints %d header", path, i);
    int names = s->nname == r->nname;
    for (size_t k = 0; names && k < s->nname; ++k) names = strcmp(s->name[k], r->name[k]) == 0;
    CHECK_MSG(names, "%s: joints %d names", path, i);
    CHECK_MSG(s->npos == r->npos && same_bytes(s->pos, r->pos, s->npos * sizeof(double)) &&
                  s->nvel == r->nvel && same_bytes(s->vel, r->vel, s->nvel * sizeof(double)) &&
                  s->neff == r->neff && same_bytes(s->eff, r->eff, s->neff * sizeof(double)),
              "%s: joints %d arrays", path, i);
  }
  for (int i = 0; i < b->n_marker; ++i) {
    const marker_copy *s = &o->marker[i], *r = &b->marker[i];
    const ss_msg_marker *a = &s->m, *c = &r->m;
    CHECK_MSG(same_header(&a->header, &c->header), "%s: marker %d header", path, i);
    CHECK_MSG(strcmp(a->ns, c->ns) == 0 && a->id == c->id && a->type == c->type &&
                  a->action == c->action && a->frame_locked == c->frame_locked &&
                  a->lifetime[0] == c->lifetime[0] && a->lifetime[1] == c->lifetime[1] &&
                  a->mesh_use_embedded_materials == c->mesh_use_embedded_materials,
              "%s: marker %d scalars", path, i);
    CHECK_MSG(same_bytes(a->position, c->position, sizeof a->position) &&
                  same_bytes(a->orientation, c->orientation, sizeof a->orientation) &&
                  same_bytes(a->scale, c->scale, sizeof a->scale) &&
                  same_bytes(a->color, c->color, sizeof a->color),
              "%s: marker %d pose/scale/color", path, i);
    CHECK_MSG(a->n_points == c->n_points &&
                  same_bytes(s->points, r->points, 3 * a->n_points * sizeof(float)) &&
                  a->n_colors == c->n_colors &&
                  same_bytes(s->colors, r->colors, 4 * a->n_colors * sizeof(float)),
              "%s: marker %d points/colors", path, i);
    CHECK_MSG(strcmp(s->text, r->text) == 0 && strcmp(s->res, r->res) == 0,
              "%s: marker %d text/mesh_resource", path, i);
  }
  for (int i = 0; i < b->n_string; ++i)
    CHECK_MSG(strcmp(o->string[i], b->string[i]) == 0, "%s: string %d", path, i);
}

/* ------------------------------------------------------------------ check */
static void check_params(int argc)
{
  int was = -1, iv = 0, bv = 0;
  double dv = 0.0;
  char buf[64];
  /* ROS arguments were consumed: only "rosc_echo check" remains */
  CHECK_EQ_INT(argc, 2);
  /* private, from the command line (_name:=value) */
  CHECK(rosc_param_get_double("~p_double", &dv, -1.0, &was) == ROSC_OK && dv == 2.5 && was == 1);
  CHECK(rosc_param_get_int("~p_int", &iv, -1, &was) == ROSC_OK && iv == 7 && was == 1);
  CHECK(rosc_param_get_string("~p_str", buf, sizeof buf, "def", &was) == ROSC_OK &&
        strcmp(buf, "hello") == 0 && was == 1);
  CHECK(rosc_param_get_bool("~p_bool", &bv, 0, &was) == ROSC_OK && bv == 1 && was == 1);
  CHECK(rosc_param_get_int("~p_int_as_double", &iv, -1, &was) == ROSC_OK && iv == 3 && was == 1);
  CHECK(rosc_param_get_double("~p_int", &dv, -1.0, &was) == ROSC_OK && dv == 7.0 && was == 1);
  /* not set: defaults, ROSC_OK, was_set 0 */
  CHECK(rosc_param_get_double("~missing", &dv, 0.125, &was) == ROSC_OK && dv == 0.125 && was == 0);
  CHECK(rosc_param_get_int("~missing", &iv, 42, &was) == ROSC_OK && iv == 42 && was == 0);
  CHECK(rosc_param_get_bool("~missing", &bv, 1, &was) == ROSC_OK && bv == 1 && was == 0);
  CHECK(rosc_param_get_string("~missing", buf, sizeof buf, "dflt", &was) == ROSC_OK &&
        strcmp(buf, "dflt") == 0 && was == 0);
  CHECK(rosc_param_get_string("~missing", buf, sizeof buf, NULL, NULL) == ROSC_OK && buf[0] == '\0');
  CHECK(rosc_param_get_double("/missing_global", &dv, 9.5, NULL) == ROSC_OK && dv == 9.5);
  /* wrong type: ROSC_E_TYPE and the default */
  CHECK(rosc_param_get_double("~p_str", &dv, 1.5, &was) == ROSC_E_TYPE && dv == 1.5 && was == 0);
  CHECK(rosc_param_get_int("~p_double", &iv, 5, &was) == ROSC_E_TYPE && iv == 5 && was == 0);
  CHECK(rosc_param_get_bool("~p_int", &bv, 0, &was) == ROSC_E_TYPE && bv == 0);
  CHECK(rosc_param_get_string("~p_int", buf, sizeof buf, "d", &was) == ROSC_E_TYPE &&
        strcmp(buf, "d") == 0);
  /* global set + get, relative names, has, delete */
  CHECK(rosc_param_set_double("/rosc_test/g_double", -0.75) == ROSC_OK);
  CHECK(rosc_param_set_int("/rosc_test/g_int", -12) == ROSC_OK);
  CHECK(rosc_param_set_bool("/rosc_test/g_bool", 1) == ROSC_OK);
  CHECK(rosc_param_set_string("/rosc_test/g_str", "global value") == ROSC_OK);
  CHECK(rosc_param_get_double("/rosc_test/g_double", &dv, 0, &was) == ROSC_OK && dv == -0.75 && was);
  CHECK(rosc_param_get_int("/rosc_test/g_int", &iv, 0, &was) == ROSC_OK && iv == -12 && was);
  CHECK(rosc_param_get_bool("/rosc_test/g_bool", &bv, 0, &was) == ROSC_OK && bv == 1 && was);
  CHECK(rosc_param_get_string("rosc_test/g_str", buf, sizeof buf, "", &was) == ROSC_OK &&
        strcmp(buf, "global value") == 0);
  CHECK(rosc_param_get_string("/rosc_test/g_str", buf, 7, "", &was) == ROSC_E_TRUNCATED &&
        strcmp(buf, "global") == 0 && was == 1);
  CHECK(rosc_param_set_int("~own", 5) == ROSC_OK);
  CHECK(rosc_param_get_int("/rosc_check/own", &iv, 0, NULL) == ROSC_OK && iv == 5);
  int has = -1;
  CHECK(rosc_param_has("/rosc_test/g_int", &has) == ROSC_OK && has == 1);
  CHECK(rosc_param_delete("/rosc_test/g_int") == ROSC_OK);
  CHECK(rosc_param_has("/rosc_test/g_int", &has) == ROSC_OK && has == 0);
  CHECK(rosc_param_delete("/rosc_test/g_int") == ROSC_OK);
  /* bad arguments */
  CHECK(rosc_param_get_double(NULL, &dv, 0, NULL) == ROSC_E_INVALID);
  CHECK(rosc_param_get_double("", &dv, 0, NULL) == ROSC_E_INVALID);
  CHECK(rosc_param_get_double("bad name!", &dv, 0, NULL) == ROSC_E_INVALID);
  CHECK(rosc_param_get_string("~p_str", NULL, 10, "", NULL) == ROSC_E_INVALID);

  /* robot_description: absent, then a 2 MB URDF-like string */
  char *urdf = NULL;
  size_t len = 0;
  rosc_param_delete("/robot_description");
  CHECK(rosc_robot_description(&urdf, &len) == ROSC_E_NOTFOUND && urdf == NULL);
  size_t big = 2u << 20;
  char *text = malloc(big + 1);
  if (text == NULL) abort();
  for (size_t k = 0; k < big; ++k) text[k] = (char)('a' + k % 26);
  memcpy(text, "<robot name=\"r\">", 16);
  text[big] = '\0';
  CHECK(rosc_param_set_string("/robot_description", text) == ROSC_OK);
  CHECK(rosc_robot_description(&urdf, &len) == ROSC_OK && urdf != NULL && len == big &&
        memcmp(urdf, text, big + 1) == 0);
  free(urdf);
  urdf = NULL;
  CHECK(rosc_param_get_string_alloc("~missing", &urdf, &len) == ROSC_E_NOTFOUND && urdf == NULL);
  CHECK(rosc_param_get_string_alloc("~p_int", &urdf, &len) == ROSC_E_TYPE && urdf == NULL);
  free(text);
  rosc_param_delete("/robot_description");

  char name[64];
  CHECK(rosc_node_name(name, sizeof name) == ROSC_OK && strcmp(name, "/rosc_check") == 0);
  CHECK(rosc_resolve_name("~x", name, sizeof name) == ROSC_OK && strcmp(name, "/rosc_check/x") == 0);
  CHECK(rosc_node_name(name, 3) == ROSC_E_TRUNCATED && strcmp(name, "/r") == 0);
}

static void check_time(void)
{
  rosc_time t, w;
  double ts = 0, ws = 0;
  CHECK(rosc_now(&t) == ROSC_OK && rosc_wall_now(&w) == ROSC_OK);
  CHECK(t.sec > 1600000000u && t.nsec < 1000000000u);   /* no sim time: wall clock */
  CHECK(rosc_now_s(&ts) == ROSC_OK && rosc_wall_now_s(&ws) == ROSC_OK);
  CHECK_NEAR(ts, ws, 5.0);
  CHECK(ss_msg_time_to_ns(ss_msg_time_from_ns(1234567890123456789LL)) == 1234567890123456789LL);
  ss_msg_time x = ss_msg_time_from_ns(12500000000LL);
  CHECK(x.sec == 12 && x.nsec == 500000000u);
  x = ss_msg_time_from_ns(-3);
  CHECK(x.sec == 0 && x.nsec == 0);
  x = ss_msg_time_from_ns(INT64_MAX);
  CHECK(x.sec == 4294967295u && x.nsec == 999999999u);
  CHECK(rosc_sleep(0.02) == ROSC_OK && rosc_wall_sleep(0.01) == ROSC_OK);
  CHECK(rosc_sleep(-1.0) == ROSC_E_INVALID);
  rosc_rate *rate = NULL;
  CHECK(rosc_rate_create(&rate, 0.0) == ROSC_E_INVALID);
  CHECK(rosc_rate_create(&rate, 50.0) == ROSC_OK && rate != NULL);
  double t0 = 0, t1 = 0;
  rosc_wall_now_s(&t0);
  int met = -1;
  for (int i = 0; i < 5; ++i) CHECK(rosc_rate_sleep(rate, &met) == ROSC_OK);
  rosc_wall_now_s(&t1);
  CHECK_MSG(t1 - t0 > 0.07 && t1 - t0 < 1.0, "5 cycles at 50 Hz took %.3f s", t1 - t0);
  CHECK(rosc_rate_reset(rate) == ROSC_OK);
  CHECK(rosc_rate_destroy(rate) == ROSC_OK && rosc_rate_destroy(NULL) == ROSC_OK);
}

static void check_rejects(msg_pub *pm, msg_pub *pj)
{
  ss_msg_skin_mesh m;
  memset(&m, 0, sizeof m);
  CHECK(msg_publish(pj, SS_MSG_SKIN_MESH, &m) == ROSC_E_INVALID);   /* wrong type */
  CHECK(msg_publish(NULL, SS_MSG_SKIN_MESH, &m) == ROSC_E_INVALID);
  CHECK(msg_publish(pm, SS_MSG_SKIN_MESH, NULL) == ROSC_E_INVALID);
  m.n_positions = 3;   /* NULL with a count */
  CHECK(msg_publish(pm, SS_MSG_SKIN_MESH, &m) == ROSC_E_INVALID);
  m.n_positions = 0;
  memset(m.header.frame_id, 'x', sizeof m.header.frame_id);   /* unterminated */
  CHECK(msg_publish(pm, SS_MSG_SKIN_MESH, &m) == ROSC_E_INVALID);
  m.header.frame_id[0] = '\0';
  m.header.stamp.nsec = 1000000000u;
  CHECK(msg_publish(pm, SS_MSG_SKIN_MESH, &m) == ROSC_E_INVALID);
  ss_msg_joint_state j;
  memset(&j, 0, sizeof j);
  const char *names[2] = {"a", NULL};
  j.name = names;
  j.n_name = 2;
  CHECK(msg_publish(pj, SS_MSG_JOINT_STATE, &j) == ROSC_E_INVALID);
  msg_pub *p = NULL;
  CHECK(msg_pub_create(&p, 99, "x", 1, 0) == ROSC_E_INVALID && p == NULL);
  CHECK(msg_pub_create(&p, SS_MSG_STRING, "x", 0, 0) == ROSC_E_INVALID);
  CHECK(msg_pub_create(&p, SS_MSG_STRING, "bad topic!", 1, 0) == ROSC_E_INVALID);
  CHECK(rosc_log(17, "bad level") == ROSC_E_INVALID);
  CHECK(strcmp(rosc_strerror(ROSC_E_TYPE), "parameter has another type") == 0);
}

/* The C field tables against the generated C++ messages: roscpp reads every message
 * the C encoder wrote and writes the same bytes back; the C decoder refuses a message
 * cut short or run on, naming the field. */
static void check_codec(const outbox *o)
{
  ss_msg_buf buf = {0};
  for (int i = 0; i < N_MSG; ++i) {
    ss_msg_skin_mesh m;
    ss_msg_joint_state j;
    ss_msg_marker k;
    views_of(o, i, &m, &j, &k);
    ss_msg_string str = {o->string[i]};
    const void *views[5] = {&m, &o->stats[i], &j, &k, &str};
    const int types[5] = {SS_MSG_SKIN_MESH, SS_MSG_SKIN_STATS, SS_MSG_JOINT_STATE, SS_MSG_MARKER,
                          SS_MSG_STRING};
    for (int t = 0; t < 5; ++t) {
      int same = 0;
      CHECK(ss_msg_encode(types[t], views[t], &buf) == SS_MSG_OK);
      CHECK_MSG(rosc_test_reserialize(ss_msg_datatype(types[t]), buf.data, buf.len, &same) ==
                        ROSC_OK && same,
                "%s %d: roscpp does not read the C encoder's %zu bytes back the same",
                ss_msg_datatype(types[t]), i, buf.len);
    }
  }
  /* a mesh cut inside its positions, and one with a byte too many */
  ss_msg_skin_mesh m;
  memset(&m, 0, sizeof m);
  float pos[6] = {1, 2, 3, 4, 5, 6};
  m.positions = pos;
  m.n_positions = 6;
  CHECK(ss_msg_encode(SS_MSG_SKIN_MESH, &m, &buf) == SS_MSG_OK);
  ss_msg_scratch scratch = {{0}, {0}};
  ss_msg_skin_mesh got;
  char why[256];
  CHECK(ss_msg_decode(SS_MSG_SKIN_MESH, buf.data, buf.len, &got, &scratch, why, sizeof why) ==
            SS_MSG_OK && got.n_positions == 6 && memcmp(got.positions, pos, sizeof pos) == 0);
  CHECK(ss_msg_decode(SS_MSG_SKIN_MESH, buf.data, buf.len - 9, &got, &scratch, why, sizeof why) ==
            SS_MSG_E_MALFORMED && strstr(why, "positions") != NULL);
  uint8_t more[128];
  memcpy(more, buf.data, buf.len);
  more[buf.len] = 0;
  CHECK(ss_msg_decode(SS_MSG_SKIN_MESH, more, buf.len + 1, &got, &scratch, why, sizeof why) ==
            SS_MSG_E_MALFORMED && strstr(why, "1 bytes after") != NULL);
  ss_msg_scratch_free(&scratch);
  /* dynamic_reconfigure's messages as the nodes build them, and a request read back */
  static const char *const menu[] = {"a", "b", NULL};
  const ss_dr_param dp[4] = {{"i", SS_DR_INT, "an int", 1, 0, 10, NULL},
                             {"d", SS_DR_DOUBLE, "a double", 2, -INFINITY, INFINITY, NULL},
                             {"b", SS_DR_BOOL, NULL, 4, 0, 1, NULL},
                             {"s", SS_DR_STR, "a menu", 8, 0, 0, menu}};
  ss_dr_value dv[4] = {{3, ""}, {2.5, ""}, {1, ""}, {0, "b"}};
  ss_dr_value want[4] = {{-7, ""}, {1e-300, ""}, {0, ""}, {0, "a"}};
  int same = 0;
  CHECK(ss_dr_encode_config(dp, dv, 4, &buf) == SS_MSG_OK &&
        rosc_test_reserialize("dynamic_reconfigure/Config", buf.data, buf.len, &same) == ROSC_OK &&
        same);
  CHECK(ss_dr_encode_description(dp, dv, 4, &buf) == SS_MSG_OK &&
        rosc_test_reserialize("dynamic_reconfigure/ConfigDescription", buf.data, buf.len,
                              &same) == ROSC_OK && same);
  CHECK(ss_dr_encode_config(dp, want, 4, &buf) == SS_MSG_OK &&
        ss_dr_decode_request(dp, 4, buf.data, buf.len, dv, why, sizeof why) == SS_MSG_OK);
  for (int i = 0; i < 4; ++i) CHECK_MSG(!ss_dr_differ(dp[i].type, &dv[i], &want[i]), "request %d", i);
  CHECK(ss_dr_decode_request(dp, 4, buf.data, buf.len - 1, dv, why, sizeof why) ==
        SS_MSG_E_MALFORMED);
  ss_msg_buf_free(&buf);
  /* the shim serves only the types it knows, and bytes only */
  rosc_pub *raw = NULL;
  CHECK(rosc_pub_create(&raw, "skin_sim/NoSuchType", "x", 1, 0) == ROSC_E_INVALID && raw == NULL);
  CHECK(rosc_pub_create(&raw, NULL, "x", 1, 0) == ROSC_E_INVALID);
  CHECK(rosc_pub_create(&raw, "std_msgs/String", "raw_string", 1, 0) == ROSC_OK);
  CHECK(rosc_publish(raw, NULL, 4) == ROSC_E_INVALID);
  CHECK(rosc_publish(NULL, NULL, 0) == ROSC_E_INVALID);
  CHECK(rosc_pub_destroy(raw) == ROSC_OK);
}

static void latch_cb(const void *msg, void *u)
{
  const ss_msg_string *m = msg;
  *(int *)u = strcmp(m->data, "latched!") == 0 ? 1 : -1;
}

static void check_latch(void)
{
  msg_pub *p = NULL;
  msg_sub *s = NULL;
  int got = 0;
  CHECK(msg_pub_create(&p, SS_MSG_STRING, "latched", 1, 1) == ROSC_OK);
  CHECK(publish_string(p, "latched!") == ROSC_OK);
  CHECK(msg_subscribe(&s, SS_MSG_STRING, "latched", 1, latch_cb, NULL, &got) == ROSC_OK);
  double t0 = 0, t = 0;
  rosc_wall_now_s(&t0);
  while (got == 0 && rosc_wall_now_s(&t) == ROSC_OK && t - t0 < 10.0) rosc_spin_once(0.05);
  CHECK_MSG(got == 1, "latched message: got = %d", got);
  msg_sub_destroy(s);
  msg_pub_destroy(p);
}

static void check_logging(void)
{
  /* 1.2 s of a flood every ms, throttled to one per 0.25 s: about 5 lines reach
   * /rosout (test_rosc.sh counts them), the later ones saying how many were held */
  double t0 = 0, t = 0;
  int calls = 0, bad = 0;
  ss_throttle flood = SS_THROTTLE_INIT, hidden = SS_THROTTLE_INIT;
  rosc_wall_now_s(&t0);
  while (rosc_wall_now_s(&t) == ROSC_OK && t - t0 < 1.2) {
    bad |= NODE_LOG_EVERY(&flood, ROSC_LOG_WARN, 0.25, "flood %d", calls);
    NODE_WARN_THROTTLE(0.5, "macro flood %d", calls);
    bad |= NODE_LOG_EVERY(&hidden, ROSC_LOG_DEBUG, 0.25, "hidden debug %d", calls);
    ++calls;
    rosc_wall_sleep(0.001);
  }
  CHECK(bad == 0 && calls > 100);
  /* the count itself, on a clock of the test's own */
  ss_throttle th = SS_THROTTLE_INIT;
  uint64_t held = 9;
  CHECK(ss_throttle_pass(&th, 10.0, 1.0, &held) == 1 && held == 0);
  CHECK(ss_throttle_pass(&th, 10.5, 1.0, &held) == 0 && ss_throttle_pass(&th, 10.9, 1.0, &held) == 0);
  CHECK(ss_throttle_pass(&th, 11.0, 1.0, &held) == 1 && held == 2);
  CHECK(ss_throttle_pass(&th, 11.1, 0.0, &held) == 1 && held == 0);
  char longmsg[3000];
  memset(longmsg, 'x', sizeof longmsg - 1);
  longmsg[sizeof longmsg - 1] = '\0';
  CHECK(rosc_log(ROSC_LOG_INFO, "long:%s:end", longmsg) == ROSC_OK);
  CHECK(ROSC_INFO("info from %s", "rosc_echo") == ROSC_OK);
  CHECK(ROSC_ERROR("an error line (expected by the test)") == ROSC_OK);
}

static int wait_connections(msg_pub **pubs, unsigned want_subs, msg_sub **subs, double timeout)
{
  double t0 = 0, t = 0;
  rosc_wall_now_s(&t0);
  while (rosc_wall_now_s(&t) == ROSC_OK && t - t0 < timeout) {
    int ready = 1;
    for (int i = 0; i < 5; ++i) {
      unsigned n = 0;
      rosc_pub_num_subscribers(pubs[i]->pub, &n);
      ready &= n >= want_subs;
      rosc_sub_num_publishers(subs[i]->sub, &n);
      ready &= n >= 1;
    }
    if (ready) return 1;
    rosc_spin_once(0.05);
  }
  return 0;
}

static int run_check(int argc, char **argv)
{
  int st = rosc_init(&argc, argv, "rosc_check", 0, 10.0);
  if (st != ROSC_OK) {
    fprintf(stderr, "check: rosc_init: %s\n", rosc_strerror(st));
    return 1;
  }
  CHECK(rosc_init(&argc, argv, "again", 0, 1.0) == ROSC_E_STATE);
  CHECK(rosc_ok() == 1);
  check_params(argc);
  check_time();

  static outbox out;
  static inbox relayed, local;
  make_messages(&out);
  msg_pub *pubs[5] = {NULL};
  msg_sub *rsubs[5] = {NULL}, *lsubs[5] = {NULL};
  CHECK(msg_pub_create(&pubs[0], SS_MSG_SKIN_MESH, "mesh_a", 20, 0) == ROSC_OK);
  CHECK(msg_pub_create(&pubs[1], SS_MSG_SKIN_STATS, "stats_a", 20, 0) == ROSC_OK);
  CHECK(msg_pub_create(&pubs[2], SS_MSG_JOINT_STATE, "joints_a", 20, 0) == ROSC_OK);
  CHECK(msg_pub_create(&pubs[3], SS_MSG_MARKER, "marker_a", 20, 0) == ROSC_OK);
  CHECK(msg_pub_create(&pubs[4], SS_MSG_STRING, "string_a", 20, 0) == ROSC_OK);
  CHECK(msg_subscribe(&rsubs[0], SS_MSG_SKIN_MESH, "mesh_b", 20, in_mesh, NULL, &relayed) == ROSC_OK);
  CHECK(msg_subscribe(&rsubs[1], SS_MSG_SKIN_STATS, "stats_b", 20, in_stats, NULL, &relayed) == ROSC_OK);
  CHECK(msg_subscribe(&rsubs[2], SS_MSG_JOINT_STATE, "joints_b", 20, in_joints, NULL, &relayed) == ROSC_OK);
  CHECK(msg_subscribe(&rsubs[3], SS_MSG_MARKER, "marker_b", 20, in_marker, NULL, &relayed) == ROSC_OK);
  CHECK(msg_subscribe(&rsubs[4], SS_MSG_STRING, "string_b", 20, in_string, NULL, &relayed) == ROSC_OK);
  CHECK(msg_subscribe(&lsubs[0], SS_MSG_SKIN_MESH, "mesh_a", 20, in_mesh, NULL, &local) == ROSC_OK);
  CHECK(msg_subscribe(&lsubs[1], SS_MSG_SKIN_STATS, "stats_a", 20, in_stats, NULL, &local) == ROSC_OK);
  CHECK(msg_subscribe(&lsubs[2], SS_MSG_JOINT_STATE, "joints_a", 20, in_joints, NULL, &local) == ROSC_OK);
  CHECK(msg_subscribe(&lsubs[3], SS_MSG_MARKER, "marker_a", 20, in_marker, NULL, &local) == ROSC_OK);
  CHECK(msg_subscribe(&lsubs[4], SS_MSG_STRING, "string_a", 20, in_string, NULL, &local) == ROSC_OK);
  char topic[64];
  CHECK(rosc_pub_topic(pubs[0]->pub, topic, sizeof topic) == ROSC_OK && strcmp(topic, "/mesh_a") == 0);
  CHECK(rosc_sub_topic(rsubs[0]->sub, topic, sizeof topic) == ROSC_OK && strcmp(topic, "/mesh_b") == 0);

  /* the relay and this node both subscribe *_a; the relay publishes *_b */
  int connected = wait_connections(pubs, 2, rsubs, 15.0);
  CHECK_MSG(connected, "publishers and subscribers did not connect within 15 s");
  if (connected) {
    for (int i = 0; i < N_MSG; ++i) {
      CHECK_MSG(publish_all(&out, i, pubs[0], pubs[1], pubs[2], pubs[3], pubs[4]) == ROSC_OK,
                "publishing set %d", i);
      rosc_spin_once(0.005);
    }
    double t0 = 0, t = 0;
    rosc_wall_now_s(&t0);
    while (!(inbox_full(&relayed) && inbox_full(&local)) && rosc_wall_now_s(&t) == ROSC_OK &&
           t - t0 < 15.0)
      rosc_spin_once(0.05);
    rosc_spin_once(0.1);   /* anything extra would show as overflow */
    compare("relayed (TCP)", &out, &relayed);
    compare("in-process", &out, &local);
    for (int i = 0; i < 5; ++i)
      CHECK_MSG(rsubs[i]->dropped == 0 && lsubs[i]->dropped == 0, "subscriber %d dropped messages", i);
    /* roscpp numbers messages itself: consecutive on each connection */
    int seq_ok = 1;
    for (int i = 1; i < relayed.n_mesh; ++i)
      seq_ok &= relayed.mesh[i].h.seq == relayed.mesh[i - 1].h.seq + 1;
    CHECK(seq_ok);
  }
  check_codec(&out);
  check_rejects(pubs[0], pubs[2]);
  check_latch();
  check_logging();

  /* stop the relay */
  CHECK(publish_string(pubs[4], "quit") == ROSC_OK);
  rosc_spin_for(0.5);   /* lets the quit message and /rosout lines go out */
  CHECK(ROSC_INFO("rosc_check done") == ROSC_OK);
  rosc_spin_for(0.3);

  for (int i = 0; i < 5; ++i) {
    CHECK(msg_sub_destroy(rsubs[i]) == ROSC_OK);
    CHECK(msg_sub_destroy(lsubs[i]) == ROSC_OK);
    CHECK(msg_pub_destroy(pubs[i]) == ROSC_OK);
  }
  CHECK(rosc_shutdown() == ROSC_OK);
  CHECK(rosc_ok() == 0);
  CHECK(rosc_shutdown() == ROSC_OK);
  CHECK(rosc_spin_once(0.0) == ROSC_E_STATE);
  int dv = 0;
  CHECK(rosc_param_get_int("~p_int", &dv, 3, NULL) == ROSC_E_STATE && dv == 3);
  inbox_free(&relayed);
  inbox_free(&local);
  outbox_free(&out);
  return ss_test_finish("rosc_echo check");
}

/* ------------------------------------------------------------------ listen */
/* rosc_echo listen N TIMEOUT_S: prints each SkinMesh arriving on mesh_in (from a
 * publisher that is not rosc, e.g. rospy) and, at the end, how many the shim dropped.
 * Exits 0 after N messages, 1 on timeout. */
static void listen_mesh(const void *msg, void *u)
{
  const ss_msg_skin_mesh *m = msg;
  int *n = u;
  printf("mesh frame_id=%s stamp=%u.%09u topology_id=%u positions=%zu triangles=%zu first=%.9g\n",
         m->header.frame_id, m->header.stamp.sec, m->header.stamp.nsec, m->topology_id,
         m->n_positions, m->n_triangles, m->n_positions > 0 ? (double)m->positions[0] : 0.0);
  fflush(stdout);
  ++*n;
}

static int run_listen(int argc, char **argv)
{
  int st = rosc_init(&argc, argv, "rosc_listen", 0, 10.0);
  if (st != ROSC_OK || argc < 4) {
    fprintf(stderr, "listen: rosc_init: %s (usage: rosc_echo listen N TIMEOUT_S)\n", rosc_strerror(st));
    return 2;
  }
  int want = atoi(argv[2]), got = 0;
  double timeout = atof(argv[3]), t0 = 0, t = 0;
  /* the drop's log line must reach rosout.log (test_rosc.sh looks for it there) */
  if (rosc_test_wait_rosout(timeout) != ROSC_OK)
    fprintf(stderr, "listen: /rosout did not subscribe within %g s\n", timeout);
  msg_sub *sub = NULL;
  if (msg_subscribe(&sub, SS_MSG_SKIN_MESH, "mesh_in", 10, listen_mesh, NULL, &got) != ROSC_OK) return 1;
  rosc_wall_now_s(&t0);
  while (got < want && rosc_ok() && rosc_wall_now_s(&t) == ROSC_OK && t - t0 < timeout)
    rosc_spin_once(0.05);
  /* roscpp hands log lines to /rosout from a queue of its own, which shutdown
   * drops: the drop's line, logged just before the good message came, is given a
   * second to leave */
  rosc_spin_for(1.0);
  printf("received=%d dropped=%llu\n", got, (unsigned long long)sub->dropped);
  msg_sub_destroy(sub);
  rosc_shutdown();
  return got >= want ? 0 : 1;
}

/* ------------------------------------------------------------------ ping */
/* rosc_echo ping N HZ VERTICES: publishes N SkinMesh messages of VERTICES vertices
 * (and twice as many triangles, as a closed mesh has) at HZ on mesh_a, stamped with the wall clock, and receives
 * them back on mesh_b (through the relay). Prints the round-trip latency; exits 0 if
 * every message came back intact and in order. */
typedef struct ping_state {
  int received, in_order, intact;
  size_t n_pos;
  float probe;
  double lat[1024];
} ping_state;

static void ping_back(const void *msg, void *u)
{
  const ss_msg_skin_mesh *m = msg;
  ping_state *p = u;
  double now = 0;
  rosc_wall_now_s(&now);
  if (p->received < 1024) p->lat[p->received] = now - 1e-9 * (double)ss_msg_time_to_ns(m->header.stamp);
  p->in_order &= m->topology_id == (uint32_t)p->received;
  p->intact &= m->n_positions == p->n_pos && m->n_positions > 0 &&
               m->positions[m->n_positions - 1] == p->probe + (float)m->topology_id;
  p->received++;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static int run_ping(int argc, char **argv)
{
  int st = rosc_init(&argc, argv, "rosc_ping", 0, 10.0);
  if (st != ROSC_OK || argc < 5) {
    fprintf(stderr, "ping: rosc_init: %s (usage: rosc_echo ping N HZ VERTICES)\n", rosc_strerror(st));
    return 2;
  }
  int n = atoi(argv[2]);
  double hz = atof(argv[3]);
  size_t nv = (size_t)atol(argv[4]);
  if (n < 1 || n > 1024 || !(hz > 0.0) || nv < 3) return 2;
  static ping_state ps;
  ps.in_order = ps.intact = 1;
  ps.n_pos = 3 * nv;
  ps.probe = 0.25f;
  float *pos = malloc(3 * nv * sizeof(float));
  uint32_t *tri = malloc(6 * nv * sizeof(uint32_t));   /* 2 triangles per vertex */
  if (pos == NULL || tri == NULL) abort();
  for (size_t k = 0; k < 3 * nv; ++k) pos[k] = (float)k * 1e-3f;
  for (size_t k = 0; k < 6 * nv; ++k) tri[k] = (uint32_t)((k * 7919u) % nv);
  msg_pub *pub = NULL;
  msg_sub *sub = NULL;
  /* Queues hold every message: what is checked is that the transport
   * delivers all of them intact and in order, also on a loaded machine
   * (sanitizer builds, parallel tests); the latencies are reported, never
   * asserted. */
  if (msg_pub_create(&pub, SS_MSG_SKIN_MESH, "mesh_a", (unsigned)n, 0) != ROSC_OK ||
      msg_subscribe(&sub, SS_MSG_SKIN_MESH, "mesh_b", (unsigned)n, ping_back, NULL, &ps) != ROSC_OK)
    return 1;
  double t0 = 0, t = 0;
  unsigned np = 0, ns = 0;
  rosc_wall_now_s(&t0);
  while ((np < 1 || ns < 1) && rosc_wall_now_s(&t) == ROSC_OK && t - t0 < 15.0) {
    rosc_pub_num_subscribers(pub->pub, &ns);
    rosc_sub_num_publishers(sub->sub, &np);
    rosc_spin_once(0.02);
  }
  ss_msg_skin_mesh m;
  memset(&m, 0, sizeof m);
  snprintf(m.header.frame_id, sizeof m.header.frame_id, "body");
  m.positions = pos;
  m.n_positions = 3 * nv;
  m.triangles = tri;
  m.n_triangles = 6 * nv;
  double next = 0;
  rosc_wall_now_s(&next);
  for (int i = 0; i < n && rosc_ok(); ++i) {
    pos[3 * nv - 1] = ps.probe + (float)i;
    m.topology_id = (uint32_t)i;
    rosc_time w;
    rosc_wall_now(&w);
    m.header.stamp.sec = w.sec;
    m.header.stamp.nsec = w.nsec;
    if (msg_publish(pub, SS_MSG_SKIN_MESH, &m) != ROSC_OK) break;
    next += 1.0 / hz;
    /* spin (not sleep) until the next period, so replies are timed when they arrive */
    while (rosc_wall_now_s(&t) == ROSC_OK && t < next) rosc_spin_once(next - t);
  }
  rosc_wall_now_s(&t0);
  while (ps.received < n && rosc_wall_now_s(&t) == ROSC_OK && t - t0 < 60.0) rosc_spin_once(0.02);
  int k = ps.received < 1024 ? ps.received : 1024;
  qsort(ps.lat, (size_t)k, sizeof(double), cmp_double);
  printf("ping: %d/%d SkinMesh of %zu vertices + %zu triangles (%.2f MB) at %.0f Hz came back, "
         "in order %d, intact %d; round trip ms: median %.2f, p95 %.2f, max %.2f\n",
         ps.received, n, nv, 2 * nv, (double)(3 * nv * 4 + 6 * nv * 4) / 1e6, hz, ps.in_order,
         ps.intact,
         k ? 1e3 * ps.lat[k / 2] : 0.0, k ? 1e3 * ps.lat[(k * 95) / 100 < k ? (k * 95) / 100 : k - 1] : 0.0,
         k ? 1e3 * ps.lat[k - 1] : 0.0);
  msg_sub_destroy(sub);
  msg_pub_destroy(pub);
  rosc_shutdown();
  free(pos);
  free(tri);
  return ps.received == n && ps.in_order && ps.intact ? 0 : 1;
}

int main(int argc, char **argv)
{
  if (argc >= 2 && strcmp(argv[1], "ping") == 0) return run_ping(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "listen") == 0) return run_listen(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "relay") == 0) return run_relay(argc, argv);
  if (argc >= 2 && strcmp(argv[1], "check") == 0) return run_check(argc, argv);
  fprintf(stderr, "usage: rosc_echo relay|check|ping|listen [ROS arguments]\n");
  return 2;
}
