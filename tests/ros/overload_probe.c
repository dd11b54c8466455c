/* overload_probe: a kinematic_mesh stream faster than skin_sim_node can step, for
 * tests/ros/test_skin_overload.sh (real node, real master, no mocks).
 *
 *   overload_probe SECONDS HZ [check]
 *
 * Publishes for SECONDS a tube of 19,200 triangles whose seam column is duplicated
 * (as a UV seam: the copies at bit-identical positions), bending and swaying, at HZ
 * with regular stamps (ROS time at start + i / HZ), then listens 3 s more. Receives
 * skin_mesh and skin_stats (stats only from a node of this build: an older SkinStats
 * does not connect). Prints: input and output rates, the input frames between
 * consecutive skin_mesh (median, max), latency (ROS time at arrival minus stamp) median
 * and 95th percentile, and the node's counters (resets, inputs_skipped,
 * inputs_dropped, failures, latency_ms). With "check", exits 1 unless: skin_mesh came,
 * every one finite, in the body's layout and with every seam closed (copies equal),
 * the skin answered at least every 60 input frames plus two of its longest steps
 * (skin_stats total_ms; a slow machine is not judged, idling is), and 0 resets
 * and inputs_skipped > 0 (the overload was real). No wall-clock threshold is judged. */
#include "node_msg.h" /* the nodes' typed topics (src/nodes) */
#include "rosc_test.h" /* rosc/rosc.h and the calls only tests make */
#include "ss_test.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NU 96              /* around; column NU duplicates column 0 */
#define NL 101             /* along */
#define NV ((NU + 1) * NL)
#define NT (2 * NU * (NL - 1))
#define MAX_OUT 20000
#define MAX_GAP_FRAMES 60
#define SS_PI 3.14159265358979323846

static float g_pos[3 * NV];
static uint32_t g_tri[3 * NT];

static void make_tube(double t)
{
  for (int j = 0; j < NL; j++) {
    double z = (double)j / (NL - 1);
    /* bending and swaying: the tube's axis moves in x and y */
    double ax = 0.15 * sin(SS_PI * z) * sin(2.0 * SS_PI * 0.8 * t);
    double ay = 0.08 * z * z * sin(2.0 * SS_PI * 1.3 * t + 1.0);
    double r = 0.08 + 0.02 * sin(6.0 * z + 3.0 * t);
    for (int i = 0; i <= NU; i++) {
      double a = 2.0 * SS_PI * (double)(i % NU) / NU;
      float *p = g_pos + 3 * (j * (NU + 1) + i);
      p[0] = (float)(ax + r * cos(a));
      p[1] = (float)(ay + r * sin(a));
      p[2] = (float)z;
    }
  }
}

static void make_triangles(void)
{
  int k = 0;
  for (int j = 0; j + 1 < NL; j++)
    for (int i = 0; i < NU; i++) {
      uint32_t a = (uint32_t)(j * (NU + 1) + i), b = a + 1, c = a + NU + 1, d = c + 1;
      g_tri[k++] = a; g_tri[k++] = b; g_tri[k++] = d;
      g_tri[k++] = a; g_tri[k++] = d; g_tri[k++] = c;
    }
}

typedef struct got {
  int n;
  int64_t stamp_ns[MAX_OUT];
  double latency_ms[MAX_OUT];
  int nonfinite, bad_layout, open_seams;
  int nstats;
  double max_step_ms;  /* longest step reported in skin_stats */
  ss_msg_skin_stats last;
  double stats_latency[MAX_OUT];
} got;
static got g;

static void on_skin(const void *msg, void *u)
{
  const ss_msg_skin_mesh *m = msg;
  (void)u;
  if (g.n >= MAX_OUT) return;
  rosc_time now;
  rosc_now(&now);
  g.stamp_ns[g.n] = ss_msg_time_to_ns(m->header.stamp);
  g.latency_ms[g.n] = 1e-6 * (double)(rosc_time_to_ns(now) - g.stamp_ns[g.n]);
  g.n++;
  if (m->n_positions != 3 * NV || m->n_triangles != 3 * NT ||
      memcmp(m->triangles, g_tri, sizeof g_tri) != 0) {
    g.bad_layout++;
    return;
  }
  for (size_t i = 0; i < m->n_positions; i++)
    if (!isfinite(m->positions[i])) {
      g.nonfinite++;
      return;
    }
  for (int j = 0; j < NL; j++) {
    const float *a = m->positions + 3 * (j * (NU + 1)), *b = a + 3 * NU;
    if (a[0] != b[0] || a[1] != b[1] || a[2] != b[2]) {
      g.open_seams++;
      return;
    }
  }
}

static void on_stats(const void *msg, void *u)
{
  const ss_msg_skin_stats *m = msg;
  (void)u;
  if (g.nstats < MAX_OUT) g.stats_latency[g.nstats] = m->latency_ms;
  g.nstats++;
  if (m->total_ms > g.max_step_ms) g.max_step_ms = m->total_ms;
  g.last = *m;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static double pct(double *v, int n, int p)
{
  if (n <= 0) return NAN;
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  int k = (n * p) / 100;
  return v[k < n ? k : n - 1];
}

int main(int argc, char **argv)
{
  if (argc < 3) {
    fprintf(stderr, "usage: overload_probe SECONDS HZ [check]\n");
    return 2;
  }
  double seconds = atof(argv[1]), hz = atof(argv[2]);
  int check = argc > 3 && strcmp(argv[3], "check") == 0;
  if (!(seconds > 0 && seconds < 600 && hz > 0 && hz <= 1000)) {
    fprintf(stderr, "overload_probe: SECONDS in (0, 600), HZ in (0, 1000]\n");
    return 2;
  }
  if (rosc_init(&argc, argv, "overload_probe", ROSC_INIT_NO_ROSOUT, 10.0) != ROSC_OK) {
    fprintf(stderr, "overload_probe: rosc_init failed\n");
    return 1;
  }
  msg_pub *pub = NULL;
  msg_sub *sm = NULL, *ss = NULL;
  if (msg_pub_create(&pub, SS_MSG_SKIN_MESH, "kinematic_mesh", 8, 0) != ROSC_OK ||
      msg_subscribe(&sm, SS_MSG_SKIN_MESH, "skin_mesh", 8, on_skin, NULL, NULL) != ROSC_OK ||
      msg_subscribe(&ss, SS_MSG_SKIN_STATS, "skin_stats", 50, on_stats, NULL, NULL) != ROSC_OK) {
    fprintf(stderr, "overload_probe: cannot advertise or subscribe\n");
    return 1;
  }
  int connected = 0;
  for (int i = 0; i < 300 && !connected; i++) { /* up to 15 s */
    unsigned a = 0, b = 0;
    rosc_pub_num_subscribers(pub->pub, &a);
    rosc_sub_num_publishers(sm->sub, &b);
    connected = a >= 1 && b >= 1;
    rosc_spin_for(0.05);
  }
  if (!connected) {
    fprintf(stderr, "overload_probe: the skin node did not connect in 15 s\n");
    return 1;
  }
  rosc_spin_for(0.3);
  make_triangles();
  rosc_time start;
  rosc_now(&start);
  int64_t t0_ns = rosc_time_to_ns(start);
  double w0 = 0, w = 0;
  rosc_wall_now_s(&w0);
  int nframes = (int)(seconds * hz);
  const int64_t period_ns = (int64_t)llround(1e9 / hz);
  for (int i = 0; i < nframes; i++) {
    make_tube(i / hz);
    ss_msg_skin_mesh m;
    memset(&m, 0, sizeof m);
    m.header.stamp = ss_msg_time_from_ns(t0_ns + i * period_ns);
    snprintf(m.header.frame_id, sizeof m.header.frame_id, "tube");
    m.topology_id = 3;
    m.positions = g_pos;
    m.n_positions = 3 * NV;
    m.triangles = g_tri;
    m.n_triangles = 3 * NT;
    msg_publish(pub, SS_MSG_SKIN_MESH, &m);
    /* paced by the wall clock; spinning meanwhile */
    do {
      rosc_spin_once(0.0);
      rosc_wall_now_s(&w);
      double due = w0 + (i + 1) / hz - w;
      if (due > 0.002) rosc_spin_for(due > 0.01 ? 0.005 : due - 0.001);
    } while (w < w0 + (i + 1) / hz);
  }
  double w_end = 0;
  rosc_wall_now_s(&w_end);
  rosc_spin_for(3.0);
  double secs = w_end - w0;

  /* input frames between consecutive outputs (from their stamps) */
  static double gaps[MAX_OUT], lat[MAX_OUT];
  int ngap = 0, max_gap = 0;
  for (int i = 1; i < g.n; i++) {
    int f = (int)llround((double)(g.stamp_ns[i] - g.stamp_ns[i - 1]) / (double)period_ns);
    gaps[ngap++] = f;
    if (f > max_gap) max_gap = f;
  }
  if (g.n > 0) {
    int f = (int)llround((double)(g.stamp_ns[0] - t0_ns) / (double)period_ns);
    if (f > max_gap) max_gap = f;
  }
  int out_in_run = 0;
  for (int i = 0; i < g.n; i++)
    if (g.stamp_ns[i] >= t0_ns) lat[out_in_run++] = g.latency_ms[i];
  printf("overload: %d kinematic_mesh of %d triangles (%d vertices, seam of %d copies) in %.1f s: "
         "input %.1f Hz; %d skin_mesh: output %.1f Hz\n", nframes, NT, NV, NL, secs,
         nframes / secs, g.n, g.n / secs);
  printf("overload: input frames between skin_mesh: median %.0f, max %d; not stepped %d of %d\n",
         pct(gaps, ngap, 50), max_gap, nframes - g.n, nframes);
  double lmed = pct(lat, out_in_run, 50), l95 = pct(lat, out_in_run, 95);
  printf("overload: latency (arrival - stamp): median %.0f ms, p95 %.0f ms\n", lmed, l95);
  if (g.nstats > 0) {
    int ns = g.nstats < MAX_OUT ? g.nstats : MAX_OUT;
    double smed = pct(g.stats_latency, ns, 50), s95 = pct(g.stats_latency, ns, 95);
    printf("overload: skin_stats: resets %u, inputs_skipped %u, inputs_dropped %u, failures %u, "
           "rejected %u; latency_ms median %.0f, p95 %.0f; longest step %.1f ms, last %u "
           "substeps\n", g.last.resets, g.last.inputs_skipped, g.last.inputs_dropped,
           g.last.failures, g.last.inputs_rejected, smed, s95, g.max_step_ms, g.last.substeps);
  } else {
    printf("overload: no skin_stats (an older SkinStats does not connect)\n");
  }
  printf("overload: skin_mesh not finite %d, not in the body's layout %d, with a seam open %d\n",
         g.nonfinite, g.bad_layout, g.open_seams);
  if (check) {
    CHECK_MSG(g.n >= 3, "skin_mesh came back (%d)", g.n);
    CHECK_MSG(g.nonfinite == 0 && g.bad_layout == 0, "every skin_mesh finite (%d not) and in the "
              "body's layout (%d not)", g.nonfinite, g.bad_layout);
    CHECK_MSG(g.open_seams == 0, "every seam closed in every skin_mesh (%d with one open)",
              g.open_seams);
    /* an answer after every step: the largest gap is at most about two of the longest
     * steps (the mesh waits for the step under way, then its own), never many steps
     * spent without an answer (a machine's speed is not judged) */
    int bound = MAX_GAP_FRAMES + (int)(2.0 * g.max_step_ms * 1e-3 * hz);
    CHECK_MSG(max_gap <= bound, "the skin answered at least every %d input frames (largest gap "
              "%d; longest step %.0f ms)", bound, max_gap, g.max_step_ms);
    CHECK_MSG(g.nstats > 0, "skin_stats came (%d)", g.nstats);
    CHECK_MSG(g.last.resets == 0, "0 resets under overload (%u)", g.last.resets);
    CHECK_MSG(g.last.inputs_skipped > 0, "the overload was real: inputs_skipped %u",
              g.last.inputs_skipped);
    CHECK_MSG(g.last.failures == 0, "no substep met a non-finite value (%u)", g.last.failures);
  }
  msg_pub_destroy(pub);
  msg_sub_destroy(sm);
  msg_sub_destroy(ss);
  rosc_shutdown();
  return check ? ss_test_finish("overload_probe") : 0;
}
