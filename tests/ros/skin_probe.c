/* skin_probe: drives skin_sim_node and avatar_node through a real master for
 * tests/ros/test_skin_node.sh and test_avatar_node.sh (no mocks).
 *
 *   skin_probe stream N HZ   publishes N kinematic meshes (a waving sheet) at HZ with
 *                            stamps 1/HZ apart; every skin_mesh must come back once, in
 *                            order, with the same stamp, frame and triangles; skin_stats
 *                            for each; skin_marker (TRIANGLE_LIST, a colour per point).
 *                            Prints the latency (publish to skin_mesh arrival).
 *   skin_probe burst N       N meshes back to back: the newest is stepped last, and
 *                            every mesh is either stepped or counted as skipped (the
 *                            node was busy) or dropped (lost before the node got it).
 *   skin_probe await NS T    waits (T s at most) for the skin_stats stamped NS: a replay's
 *                            last frame has been stepped.
 *   skin_probe bad           good meshes interleaved with every kind of bad one (sizes
 *                            disagree, index out of range, NaN, Inf, empty, topology
 *                            changed without a new id): every good one comes back, no bad
 *                            one does, skin_stats counts each bad one as rejected.
 *   skin_probe jump          time goes backwards, then jumps forward by more than
 *                            max_gap: both reset the skin (counted), output continues.
 *   skin_probe joints        joint_states for avatar_node: good ones, arrays that
 *                            disagree, NaN, only unknown names (rejected, counted in
 *                            avatar_stats), known plus unknown names (used; the unknown
 *                            ones counted); kinematic_mesh comes back for the good ones.
 *   skin_probe reset [CMD]   streams the waving sheet (the skin lags the body), calls
 *                            ~reset (std_srvs/Empty, through rosc, or by running CMD,
 *                            e.g. rosservice call /skin_sim/reset): the next skin_mesh
 *                            is the body's pose itself and skin_stats counts one reset.
 *   skin_probe badstream S HZ  S seconds of NaN meshes at HZ (for /diagnostics tests).
 * Exit 0 when every check passes. */
#include "node_msg.h" /* the nodes' typed topics (src/nodes) */
#include "rosc_test.h" /* rosc/rosc.h and the calls only tests make */
#include "ss_test.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SIDE 24 /* sheet: SIDE x SIDE vertices */
#define NV (SIDE * SIDE)
#define NT (2 * (SIDE - 1) * (SIDE - 1))
#define MAX_MSG 1024
#define FRAME "probe_frame"

typedef struct got {
  int64_t stamp_ns[MAX_MSG];
  double wall[MAX_MSG];
  int n;
  int bad_frame, bad_tri, bad_size;
  float first_pos[MAX_MSG][3];
  uint32_t topo[MAX_MSG];
  /* stats */
  int nstats;
  ss_msg_skin_stats last_stats;
  int64_t stats_stamp_ns[MAX_MSG];
  /* marker */
  int nmarker, marker_ok;
  /* what was sent */
  const uint32_t *tri;
  size_t ntri;
  float *last_in_pos;   /* positions of the last good mesh sent */
  float *last_out_pos;  /* positions of the last skin_mesh received */
} got;

static float g_pos[3 * NV + 3];
static uint32_t g_tri[3 * NT];

static void make_sheet(double t)
{
  for (int j = 0; j < SIDE; j++)
    for (int i = 0; i < SIDE; i++) {
      float *p = g_pos + 3 * (j * SIDE + i);
      double x = 0.5 * i / (SIDE - 1), y = 0.5 * j / (SIDE - 1);
      p[0] = (float)x;
      p[1] = (float)y;
      p[2] = (float)(0.03 * sin(8.0 * x + 3.0 * t) * cos(5.0 * y));
    }
  int k = 0;
  for (int j = 0; j + 1 < SIDE; j++)
    for (int i = 0; i + 1 < SIDE; i++) {
      uint32_t a = (uint32_t)(j * SIDE + i), b = a + 1, c = a + SIDE, d = c + 1;
      g_tri[k++] = a; g_tri[k++] = b; g_tri[k++] = d;
      g_tri[k++] = a; g_tri[k++] = d; g_tri[k++] = c;
    }
}

static void on_skin(const void *msg, void *u)
{
  const ss_msg_skin_mesh *m = msg;
  got *g = u;
  if (g->n >= MAX_MSG) return;
  g->stamp_ns[g->n] = ss_msg_time_to_ns(m->header.stamp);
  rosc_wall_now_s(&g->wall[g->n]);
  g->topo[g->n] = m->topology_id;
  if (strcmp(m->header.frame_id, FRAME) != 0) g->bad_frame++;
  if (m->n_triangles != g->ntri || memcmp(m->triangles, g->tri, g->ntri * sizeof(uint32_t)) != 0)
    g->bad_tri++;
  if (m->n_positions >= 3) memcpy(g->first_pos[g->n], m->positions, 3 * sizeof(float));
  if (g->last_out_pos && m->n_positions == 3 * NV)
    memcpy(g->last_out_pos, m->positions, 3 * NV * sizeof(float));
  else
    g->bad_size++;
  g->n++;
}

static void on_stats(const void *msg, void *u)
{
  const ss_msg_skin_stats *m = msg;
  got *g = u;
  if (g->nstats < MAX_MSG) g->stats_stamp_ns[g->nstats] = ss_msg_time_to_ns(m->header.stamp);
  g->nstats++;
  g->last_stats = *m;
}

static void on_marker(const void *msg, void *u)
{
  const ss_msg_marker *m = msg;
  got *g = u;
  g->nmarker++;
  int ok = m->type == SS_MSG_MARKER_TRIANGLE_LIST && m->n_points == g->ntri &&
           m->n_colors == m->n_points && strcmp(m->header.frame_id, FRAME) == 0;
  for (size_t i = 0; ok && i < 4 * m->n_colors; i++)
    ok = m->colors[i] >= 0.0f && m->colors[i] <= 1.0f;
  if (ok) g->marker_ok++;
}

static msg_pub *g_pub;
static msg_sub *g_sub_mesh, *g_sub_stats, *g_sub_marker;

static int g_argc;
static char **g_argv;

static int setup_skin(got *g, const char *name)
{
  (void)g;
  int st = rosc_init(&g_argc, g_argv, name, ROSC_INIT_NO_ROSOUT, 10.0);
  if (st != ROSC_OK) fprintf(stderr, "skin_probe: rosc_init: %s\n", rosc_strerror(st));
  return st == ROSC_OK;
}

static int connect_skin(got *g, int want_marker)
{
  if (msg_pub_create(&g_pub, SS_MSG_SKIN_MESH, "kinematic_mesh", 64, 0) != ROSC_OK ||
      msg_subscribe(&g_sub_mesh, SS_MSG_SKIN_MESH, "skin_mesh", 100, on_skin, NULL, g) != ROSC_OK ||
      msg_subscribe(&g_sub_stats, SS_MSG_SKIN_STATS, "skin_stats", 100, on_stats, NULL, g) != ROSC_OK ||
      (want_marker && msg_subscribe(&g_sub_marker, SS_MSG_MARKER, "skin_marker", 10, on_marker, NULL, g) != ROSC_OK))
    return 0;
  for (int i = 0; i < 200; i++) { /* up to 10 s for the skin node */
    unsigned a = 0, b = 0, c = 0;
    rosc_pub_num_subscribers(g_pub->pub, &a);
    rosc_sub_num_publishers(g_sub_mesh->sub, &b);
    rosc_sub_num_publishers(g_sub_stats->sub, &c);
    if (a >= 1 && b >= 1 && c >= 1) {
      rosc_spin_for(0.3);
      return 1;
    }
    rosc_spin_for(0.05);
  }
  fprintf(stderr, "skin_probe: the skin node did not connect in 10 s\n");
  return 0;
}

/* The start of each run against the skin node: the sheet at rest, g set to
 * receive the skin (the last positions into out_pos, unless NULL), this probe
 * named name and connected (also to the marker when want_marker). 0 on failure. */
static int start_skin_run(got *g, float *out_pos, const char *name, int want_marker)
{
  g->last_out_pos = out_pos;
  make_sheet(0.0);
  g->tri = g_tri;
  g->ntri = 3 * NT;
  return setup_skin(g, name) && connect_skin(g, want_marker);
}

static int finish(void)
{
  msg_pub_destroy(g_pub);
  msg_sub_destroy(g_sub_mesh);
  msg_sub_destroy(g_sub_stats);
  msg_sub_destroy(g_sub_marker);
  rosc_shutdown();
  return ss_test_finish("skin_probe");
}

static void send_mesh(int64_t stamp_ns, uint32_t topo, const float *pos, size_t npos,
                      const uint32_t *tri, size_t ntri)
{
  ss_msg_skin_mesh m;
  memset(&m, 0, sizeof m);
  m.header.stamp = ss_msg_time_from_ns(stamp_ns);
  snprintf(m.header.frame_id, sizeof m.header.frame_id, FRAME);
  m.topology_id = topo;
  m.positions = pos;
  m.n_positions = npos;
  m.triangles = tri;
  m.n_triangles = ntri;
  msg_publish(g_pub, SS_MSG_SKIN_MESH, &m);
}

/* Waits (spinning) until n skin meshes and n stats have arrived, at most timeout_s. */
/* Waits until n skin_mesh and n skin_stats have come, or none has come for timeout_s
 * (of the wall clock): a node still answering is waited for, however slow the machine
 * (a sanitizer build beside other work), up to 600 s in all. */
static void wait_for(got *g, int n, double timeout_s)
{
  double start = 0, last = 0, now = 0;
  rosc_wall_now_s(&start);
  last = start;
  int seen = g->n + g->nstats;
  while ((g->n < n || g->nstats < n) && now - last < timeout_s && now - start < 600.0) {
    rosc_spin_for(0.02);
    rosc_wall_now_s(&now);
    if (g->n + g->nstats != seen) {
      seen = g->n + g->nstats;
      last = now;
    }
  }
  rosc_spin_for(0.2); /* anything extra shows up too */
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static const int64_t T0 = (int64_t)1000 * 1000000000;

static int run_stream(int n, double hz)
{
  static got g;
  static float out_pos[3 * NV];
  if (n > MAX_MSG) n = MAX_MSG;
  if (!start_skin_run(&g, out_pos, "skin_probe_stream", 1)) return 1;
  static double sent_wall[MAX_MSG];
  int64_t period = (int64_t)(1e9 / hz + 0.5);
  double start = 0;
  rosc_wall_now_s(&start);
  for (int i = 0; i < n; i++) {
    make_sheet(i / hz);
    rosc_wall_now_s(&sent_wall[i]);
    send_mesh(T0 + i * period, 7, g_pos, 3 * NV, g_tri, 3 * NT);
    /* spin (not sleep) until the next frame is due, so arrivals are timed when they come */
    double now = sent_wall[i];
    while (now < start + (i + 1) / hz) {
      rosc_spin_once(start + (i + 1) / hz - now);
      rosc_wall_now_s(&now);
    }
  }
  wait_for(&g, n, 5.0);
  CHECK_MSG(g.n == n, "%d skin_mesh for %d kinematic_mesh", g.n, n);
  int in_order = 1;
  for (int i = 0; i < g.n && i < n; i++)
    if (g.stamp_ns[i] != T0 + i * period) in_order = 0;
  CHECK_MSG(in_order, "skin_mesh stamps are those of the kinematic meshes, in order");
  CHECK_MSG(g.bad_frame == 0, "%d skin_mesh with another frame_id", g.bad_frame);
  CHECK_MSG(g.bad_tri == 0, "%d skin_mesh with other triangles", g.bad_tri);
  CHECK_MSG(g.bad_size == 0, "%d skin_mesh with another vertex count", g.bad_size);
  CHECK_MSG(g.nstats == n, "%d skin_stats for %d frames", g.nstats, n);
  int stats_order = 1;
  for (int i = 0; i < g.nstats && i < n; i++)
    if (g.stats_stamp_ns[i] != T0 + i * period) stats_order = 0;
  CHECK_MSG(stats_order, "skin_stats stamps follow the frames");
  CHECK_MSG(g.last_stats.inputs_rejected == 0 && g.last_stats.inputs_dropped == 0 &&
                g.last_stats.inputs_skipped == 0 &&
                g.last_stats.resets == 0, "rejected %u dropped %u resets %u",
            g.last_stats.inputs_rejected, g.last_stats.inputs_dropped, g.last_stats.resets);
  CHECK_MSG(g.last_stats.iterations > 0 && g.last_stats.substeps >= 1, "stats of a real step");
  int finite = 1;
  for (int i = 0; i < 3 * NV; i++) finite &= isfinite(out_pos[i]);
  CHECK_MSG(finite, "skin positions finite");
  /* marker at ~10 Hz over n / hz seconds */
  CHECK_MSG(g.nmarker >= 3, "%d skin_marker received", g.nmarker);
  CHECK_MSG(g.marker_ok == g.nmarker, "%d of %d markers are well-formed TRIANGLE_LISTs",
            g.marker_ok, g.nmarker);
  CHECK_MSG(g.nmarker <= (int)(n / hz * 10.0 * 1.5) + 2, "marker rate-limited (%d)", g.nmarker);
  static double lat[MAX_MSG];
  int nl = 0;
  for (int i = 0; i < g.n; i++) { /* matched by stamp */
    int64_t k = (g.stamp_ns[i] - T0) / period;
    if (k >= 0 && k < n && g.stamp_ns[i] == T0 + k * period)
      lat[nl++] = 1e3 * (g.wall[i] - sent_wall[k]);
  }
  if (g.n != n) {
    printf("missing skin_mesh for kinematic_mesh");
    for (int k = 0, j = 0; k < n; k++) {
      while (j < g.n && g.stamp_ns[j] < T0 + k * period) j++;
      if (j >= g.n || g.stamp_ns[j] != T0 + k * period) printf(" %d", k);
    }
    printf(" (inputs_dropped %u)\n", g.last_stats.inputs_dropped);
  }
  qsort(lat, (size_t)nl, sizeof(double), cmp_double);
  if (nl > 0)
    printf("latency kinematic_mesh -> skin_mesh (%d x %d triangles at %g Hz): median %.2f ms, "
           "95%% %.2f ms, max %.2f ms; skin step %.2f ms (last)\n", nl, NT, hz, lat[nl / 2],
           lat[(nl * 95) / 100 < nl ? (nl * 95) / 100 : nl - 1], lat[nl - 1],
           g.last_stats.total_ms);
  printf("stream: %d in, %d skin_mesh, %d skin_stats, %d skin_marker\n", n, g.n, g.nstats,
         g.nmarker);
  return finish();
}

/* ---------------------------------------------------------------- burst */
/* n meshes published back to back: the node steps what it can, drops the oldest
 * of the rest (counted) and always ends on the newest. */
static int run_burst(int n)
{
  static got g;
  static float out_pos[3 * NV];
  if (n > 60) n = 60;
  if (!start_skin_run(&g, out_pos, "skin_probe_burst", 0)) return 1;
  int64_t period = 33333333;
  send_mesh(T0, 7, g_pos, 3 * NV, g_tri, 3 * NT); /* creates the skin */
  wait_for(&g, 1, 10.0);
  for (int i = 1; i <= n; i++) {
    make_sheet(i / 30.0);
    send_mesh(T0 + i * period, 7, g_pos, 3 * NV, g_tri, 3 * NT);
  }
  int64_t last = T0 + n * period;
  for (double t = 0; t < 20.0 && !(g.n > 0 && g.stamp_ns[g.n - 1] == last); t += 0.05)
    rosc_spin_for(0.05);
  rosc_spin_for(0.3);
  CHECK_MSG(g.n > 0 && g.stamp_ns[g.n - 1] == last, "the newest mesh is stepped last");
  uint32_t dropped = g.last_stats.inputs_dropped, skipped = g.last_stats.inputs_skipped;
  CHECK_MSG((uint32_t)g.n + dropped + skipped == (uint32_t)n + 1,
            "every mesh is either stepped (%d) or counted as skipped (%u) or dropped (%u), of %d",
            g.n, skipped, dropped, n + 1);
  CHECK_MSG(g.last_stats.resets == 0, "a burst is no jump: %u resets", g.last_stats.resets);
  int in_order = 1;
  for (int i = 1; i < g.n; i++) in_order &= g.stamp_ns[i] > g.stamp_ns[i - 1];
  CHECK_MSG(in_order, "what is stepped comes out in order");
  printf("burst: %d meshes back to back; %d stepped, %u skipped (oldest first), %u dropped\n",
         n + 1, g.n, skipped, dropped);
  return finish();
}

/* ---------------------------------------------------------------- bad input */
static int run_bad(void)
{
  static got g;
  static float out_pos[3 * NV];
  if (!start_skin_run(&g, out_pos, "skin_probe_bad", 0)) return 1;
  static float pos[3 * NV + 3];
  static uint32_t tri[3 * NT];
  int64_t period = 33333333;
  int64_t good[64];
  int ngood = 0, nbad = 0, k = 0;
  const char *kinds[] = {"positions not a multiple of 3", "triangles not a multiple of 3",
                         "index out of range", "NaN position", "Inf position", "empty mesh",
                         "triangles changed, same topology_id",
                         "vertex count changed, same topology_id"};
  int nkinds = (int)(sizeof kinds / sizeof kinds[0]);
  for (int round = 0; round <= nkinds; round++) {
    /* two good frames */
    for (int r = 0; r < 2; r++) {
      make_sheet(k / 30.0);
      int64_t s = T0 + (k++) * period;
      send_mesh(s, 7, g_pos, 3 * NV, g_tri, 3 * NT);
      good[ngood++] = s;
      rosc_spin_for(1.0 / 30);
    }
    if (round == nkinds) break;
    memcpy(pos, g_pos, sizeof pos);
    memcpy(tri, g_tri, sizeof tri);
    size_t npos = 3 * NV, ntri = 3 * NT;
    switch (round) {
    case 0: npos = 3 * NV - 1; break;
    case 1: ntri = 3 * NT - 2; break;
    case 2: tri[3 * 17 + 1] = NV + 5; break;
    case 3: pos[3 * 40 + 2] = NAN; break;
    case 4: pos[3 * 41] = INFINITY; break;
    case 5: npos = 0; ntri = 0; break;
    case 6: { uint32_t t = tri[0]; tri[0] = tri[1]; tri[1] = t; } break;
    case 7: npos = 3 * NV + 3; pos[3 * NV] = pos[3 * NV + 1] = pos[3 * NV + 2] = 0.1f; break;
    }
    send_mesh(T0 + (k++) * period, 7, pos, npos, tri, ntri);
    nbad++;
    rosc_spin_for(1.0 / 30);
  }
  wait_for(&g, ngood, 5.0);
  CHECK_MSG(g.n == ngood, "%d skin_mesh for %d good kinematic_mesh (%d bad ones)", g.n, ngood,
            nbad);
  int same = g.n == ngood;
  for (int i = 0; same && i < ngood; i++) same = g.stamp_ns[i] == good[i];
  CHECK_MSG(same, "exactly the good meshes came back, in order");
  CHECK_MSG(g.bad_tri == 0 && g.bad_frame == 0 && g.bad_size == 0, "output meshes intact");
  CHECK_MSG(g.last_stats.inputs_rejected == (uint32_t)nbad, "inputs_rejected %u, want %d",
            g.last_stats.inputs_rejected, nbad);
  CHECK_MSG(g.last_stats.resets == 0, "no reset (%u)", g.last_stats.resets);
  int finite = 1;
  for (int i = 0; i < 3 * NV; i++) finite &= isfinite(out_pos[i]);
  CHECK_MSG(finite, "skin positions finite after bad input");
  /* a real topology change, with a new id: a new skin, not a rejection */
  int n_before = g.n;
  float pos2[3 * (NV + 1)];
  memcpy(pos2, g_pos, sizeof g_pos);
  pos2[3 * NV] = 0.25f; pos2[3 * NV + 1] = 0.25f; pos2[3 * NV + 2] = 0.2f;
  g.last_out_pos = NULL; /* another size: not copied */
  send_mesh(T0 + (k++) * period, 8, pos2, 3 * (NV + 1), g_tri, 3 * NT);
  wait_for(&g, n_before + 1, 5.0);
  CHECK_MSG(g.n == n_before + 1 && g.topo[g.n - 1] == 8, "a new topology_id makes a new skin");
  CHECK_MSG(g.last_stats.inputs_rejected == (uint32_t)nbad, "and is not rejected (%u)",
            g.last_stats.inputs_rejected);
  printf("bad: %d good in, %d out; %d bad in, %u rejected\n", ngood + 1, g.n, nbad,
         g.last_stats.inputs_rejected);
  return finish();
}

/* ---------------------------------------------------------------- time jumps */
static int run_jump(void)
{
  static got g;
  static float out_pos[3 * NV];
  if (!start_skin_run(&g, out_pos, "skin_probe_jump", 0)) return 1;
  int64_t period = 33333333;
  int64_t stamps[64];
  int n = 0;
  int64_t base[3] = {T0 + 5 * (int64_t)1000000000, T0, T0 + 2 * (int64_t)1000000000};
  int checked_rest = 0, rest_exact = 0;
  for (int seg = 0; seg < 3; seg++) {
    for (int i = 0; i < 10; i++) {
      make_sheet(0.2 * seg + i / 30.0);
      stamps[n] = base[seg] + i * period;
      send_mesh(stamps[n], 7, g_pos, 3 * NV, g_tri, 3 * NT);
      n++;
      rosc_spin_for(1.0 / 30);
      if (i == 0 && seg > 0) {
        /* the frame after a reset: the skin starts afresh on this very pose */
        wait_for(&g, n, 3.0);
        checked_rest++;
        if (g.n == n && memcmp(out_pos, g_pos, sizeof out_pos) == 0) rest_exact++;
        CHECK_MSG(g.last_stats.resets == (uint32_t)seg, "resets %u after segment %d",
                  g.last_stats.resets, seg);
      }
    }
  }
  wait_for(&g, n, 5.0);
  CHECK_MSG(g.n == n, "%d skin_mesh for %d kinematic_mesh", g.n, n);
  int same = g.n == n;
  for (int i = 0; same && i < n; i++) same = g.stamp_ns[i] == stamps[i];
  CHECK_MSG(same, "every frame came back across the jumps, with its stamp");
  CHECK_MSG(rest_exact == checked_rest, "after a reset the skin restarts on the body (%d of %d)",
            rest_exact, checked_rest);
  CHECK_MSG(g.last_stats.resets == 2, "time backwards + gap: 2 resets (got %u)",
            g.last_stats.resets);
  CHECK_MSG(g.last_stats.inputs_rejected == 0, "nothing rejected (%u)",
            g.last_stats.inputs_rejected);
  printf("jump: %d in, %d out, %u resets\n", n, g.n, g.last_stats.resets);
  return finish();
}

/* ---------------------------------------------------------------- joint_states */
typedef struct jgot {
  int64_t stamp_ns[MAX_MSG];
  int n;
  int nstats;
  ss_msg_skin_stats last;
  char frame[SS_MSG_FRAME_ID_MAX];
  uint32_t topo;
  size_t npos;
} jgot;

static void on_kin(const void *msg, void *u)
{
  const ss_msg_skin_mesh *m = msg;
  jgot *g = u;
  if (g->n < MAX_MSG) g->stamp_ns[g->n++] = ss_msg_time_to_ns(m->header.stamp);
  snprintf(g->frame, sizeof g->frame, "%s", m->header.frame_id);
  g->topo = m->topology_id;
  g->npos = m->n_positions;
}
static void on_avstats(const void *msg, void *u)
{
  const ss_msg_skin_stats *m = msg;
  jgot *g = u;
  g->nstats++;
  g->last = *m;
}

static int run_joints(void)
{
  static jgot g;
  if (!setup_skin(NULL, "skin_probe_joints")) return 1;
  msg_pub *pub = NULL;
  msg_sub *s1 = NULL, *s2 = NULL;
  if (msg_pub_create(&pub, SS_MSG_JOINT_STATE, "joint_states", 10, 0) != ROSC_OK ||
      msg_subscribe(&s1, SS_MSG_SKIN_MESH, "kinematic_mesh", 100, on_kin, NULL, &g) != ROSC_OK ||
      msg_subscribe(&s2, SS_MSG_SKIN_STATS, "avatar_stats", 100, on_avstats, NULL, &g) != ROSC_OK)
    return 1;
  int up = 0;
  for (int i = 0; i < 400 && !up; i++) {
    unsigned a = 0, b = 0;
    rosc_pub_num_subscribers(pub->pub, &a);
    rosc_sub_num_publishers(s1->sub, &b);
    up = a >= 1 && b >= 1;
    rosc_spin_for(0.05);
  }
  CHECK_MSG(up, "avatar_node connected");
  if (!up) return ss_test_finish("skin_probe");
  rosc_spin_for(0.3);
  const char *good_names[] = {"l_elbow", "r_elbow", "torso_twist"};
  const char *mixed_names[] = {"l_elbow", "gripper_finger", "r_elbow", "wheel"};
  const char *unknown_names[] = {"gripper_finger", "wheel"};
  double v3[3] = {0.5, 0.7, 0.2}, v4[4] = {0.6, 0.1, 0.8, 3.0}, vnan[3] = {0.5, NAN, 0.1};
  int64_t good[16];
  int ngood = 0, nbad = 0;
  for (int i = 0; i < 9; i++) {
    ss_msg_joint_state js;
    memset(&js, 0, sizeof js);
    int64_t s = T0 + i * (int64_t)33333333;
    js.header.stamp = ss_msg_time_from_ns(s);
    int is_good = 1;
    switch (i % 9) {
    case 0: case 2: case 4: case 6: case 8:
      js.name = good_names; js.n_name = 3; js.position = v3; js.n_position = 3; break;
    case 1: /* arrays disagree */
      js.name = good_names; js.n_name = 3; js.position = v3; js.n_position = 2; is_good = 0; break;
    case 3: /* NaN */
      js.name = good_names; js.n_name = 3; js.position = vnan; js.n_position = 3; is_good = 0; break;
    case 5: /* only names the robot does not have */
      js.name = unknown_names; js.n_name = 2; js.position = v3; js.n_position = 2; is_good = 0; break;
    case 7: /* known and unknown names: used, the unknown ones counted */
      js.name = mixed_names; js.n_name = 4; js.position = v4; js.n_position = 4;
      js.velocity = v4; js.n_velocity = 4; break;
    }
    msg_publish(pub, SS_MSG_JOINT_STATE, &js);
    if (is_good) good[ngood++] = s; else nbad++;
    rosc_spin_for(1.0 / 30);
  }
  for (double t = 0; t < 5.0 && g.n < ngood; t += 0.02) rosc_spin_for(0.02);
  rosc_spin_for(0.3);
  CHECK_MSG(g.n == ngood, "%d kinematic_mesh for %d good joint_states", g.n, ngood);
  int same = g.n == ngood;
  for (int i = 0; same && i < ngood; i++) same = g.stamp_ns[i] == good[i];
  CHECK_MSG(same, "the good joint states came back with their stamps, in order");
  CHECK_MSG(strcmp(g.frame, "pelvis") == 0, "frame_id is the URDF root link ('%s')", g.frame);
  CHECK_MSG(g.npos > 0 && g.topo != 0, "a mesh with a topology id");
  CHECK_MSG(g.last.inputs_rejected == (uint32_t)nbad, "avatar_stats: %u rejected, want %d",
            g.last.inputs_rejected, nbad);
  CHECK_MSG(g.last.inputs_dropped == 2, "avatar_stats: %u unknown names ignored, want 2",
            g.last.inputs_dropped);
  printf("joints: %d good, %d bad sent; %d kinematic_mesh back; %u rejected, %u names ignored\n",
         ngood, nbad, g.n, g.last.inputs_rejected, g.last.inputs_dropped);
  msg_pub_destroy(pub);
  msg_sub_destroy(s1);
  msg_sub_destroy(s2);
  rosc_shutdown();
  return ss_test_finish("skin_probe");
}

/* ---------------------------------------------------------------- await */
/* Exits 0 once a skin_stats with stamp STAMP_NS arrives (a replay has been stepped to
 * its end), 1 after TIMEOUT_S. */
static int run_await(long long stamp_ns, double timeout_s)
{
  static got g;
  if (!setup_skin(&g, "skin_probe_await")) return 1;
  if (msg_subscribe(&g_sub_stats, SS_MSG_SKIN_STATS, "skin_stats", 1000, on_stats, NULL, &g) != ROSC_OK) return 1;
  int seen = 0;
  for (double t = 0; t < timeout_s && !seen; t += 0.05) {
    rosc_spin_for(0.05);
    for (int i = 0; i < g.nstats && i < MAX_MSG && !seen; i++) seen = g.stats_stamp_ns[i] == stamp_ns;
    if (g.nstats >= MAX_MSG) { g.nstats = 0; }
  }
  printf("await: %d skin_stats, stamp %lld %s; inputs_dropped %u\n", g.nstats, stamp_ns,
         seen ? "seen" : "NOT seen", g.last_stats.inputs_dropped);
  msg_sub_destroy(g_sub_stats);
  rosc_shutdown();
  return seen ? 0 : 1;
}

static double max_diff(const float *a, const float *b, int n)
{
  double m = 0.0;
  for (int i = 0; i < n; i++) {
    double d = fabs((double)a[i] - (double)b[i]);
    if (!(d <= m)) m = d;
  }
  return m;
}

/* cmd NULL: ~reset through rosc_call_empty; else system(cmd) does it (rosservice). */
static int run_reset(const char *cmd)
{
  static got g;
  static float out_pos[3 * NV];
  if (!start_skin_run(&g, out_pos, "skin_probe_reset", 0)) return 1;
  int64_t period = 33333333;
  int n = 45;
  for (int i = 0; i < n; i++) {
    make_sheet(i / 30.0);
    send_mesh(T0 + i * period, 1, g_pos, 3 * NV, g_tri, 3 * NT);
    rosc_spin_for(1.0 / 30.0);
  }
  wait_for(&g, n, 20.0);
  double before = max_diff(out_pos, g_pos, 3 * NV);
  uint32_t resets0 = g.last_stats.resets;
  printf("reset: %d skin_mesh before the call; skin - body %.3g m; resets %u\n", g.n, before,
         (unsigned)resets0);
  CHECK(g.n == n);
  CHECK(before > 1e-4); /* the skin lags and slides: not the body's pose */
  int st;
  if (cmd) {
    st = system(cmd);
    printf("reset: '%s' exited with %d\n", cmd, st);
    CHECK(st == 0);
  } else {
    st = rosc_call_empty("/skin_sim/reset", 10.0);
    printf("reset: rosc_call_empty(/skin_sim/reset): %s\n", rosc_strerror(st));
    CHECK(st == ROSC_OK);
  }
  make_sheet(n / 30.0);
  send_mesh(T0 + n * period, 1, g_pos, 3 * NV, g_tri, 3 * NT);
  wait_for(&g, n + 1, 20.0);
  double after = max_diff(out_pos, g_pos, 3 * NV);
  printf("reset: after the call %d skin_mesh; skin - body %.3g m; resets %u\n", g.n, after,
         (unsigned)g.last_stats.resets);
  CHECK(g.n == n + 1);
  CHECK(after < 1e-6); /* the skin is created again on the current pose: at rest on it */
  CHECK(g.last_stats.resets == resets0 + 1);
  /* stepping goes on from there, no further reset */
  for (int i = n + 1; i < n + 10; i++) {
    make_sheet(i / 30.0);
    send_mesh(T0 + i * period, 1, g_pos, 3 * NV, g_tri, 3 * NT);
    rosc_spin_for(1.0 / 30.0);
  }
  wait_for(&g, n + 10, 20.0);
  CHECK(g.n == n + 10);
  CHECK(g.last_stats.resets == resets0 + 1);
  CHECK(g.bad_frame == 0 && g.bad_tri == 0);
  /* a call while nothing is wrong with the service name resolves; a wrong one times out */
  CHECK(rosc_call_empty("/skin_sim/no_such_service", 0.5) == ROSC_E_TIMEOUT);
  return finish();
}

static int run_badstream(double seconds, double hz)
{
  static got g;
  if (!start_skin_run(&g, NULL, "skin_probe_badstream", 0)) return 1;
  g_pos[5] = NAN;
  int n = (int)(seconds * hz);
  for (int i = 0; i < n; i++) {
    send_mesh(T0 + (int64_t)(i * 1e9 / hz), 1, g_pos, 3 * NV, g_tri, 3 * NT);
    rosc_spin_for(1.0 / hz);
  }
  rosc_spin_for(0.5);
  /* a rejected mesh gets no skin_mesh nor skin_stats: /diagnostics is what shows it */
  printf("badstream: %d NaN meshes sent, %d skin_mesh and %d skin_stats back\n", n, g.n,
         g.nstats);
  CHECK(g.n == 0 && g.nstats == 0);
  return finish();
}

int main(int argc, char **argv)
{
  g_argc = argc;
  g_argv = argv;
  if (argc >= 4 && strcmp(argv[1], "stream") == 0) return run_stream(atoi(argv[2]), atof(argv[3]));
  if (argc >= 4 && strcmp(argv[1], "await") == 0) return run_await(atoll(argv[2]), atof(argv[3]));
  if (argc >= 3 && strcmp(argv[1], "burst") == 0) return run_burst(atoi(argv[2]));
  if (argc >= 2 && strcmp(argv[1], "bad") == 0) return run_bad();
  if (argc >= 2 && strcmp(argv[1], "jump") == 0) return run_jump();
  if (argc >= 2 && strcmp(argv[1], "joints") == 0) return run_joints();
  if (argc >= 2 && strcmp(argv[1], "reset") == 0) return run_reset(argc >= 3 ? argv[2] : NULL);
  if (argc >= 4 && strcmp(argv[1], "badstream") == 0)
    return run_badstream(atof(argv[2]), atof(argv[3]));
  fprintf(stderr, "usage: skin_probe stream N HZ | burst N | bad | jump | joints | reset [CMD] | "
          "badstream S HZ\n");
  return 2;
}
