/* ss_input.h: checks of received meshes, stamp classification, step splitting,
 * slide distances and colours. */
#include "ss_input.h"
#include "ss_test.h"

#include <limits.h>
#include <math.h>
#include <string.h>

static const float POS[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const uint32_t TRI[6] = {0, 1, 2, 0, 3, 1};

static void test_mesh_check(void)
{
  char err[256];
  CHECK(ss_input_mesh_check(12, POS, 6, TRI, err, sizeof err) == SS_OK);
  CHECK(ss_input_mesh_check(0, POS, 6, TRI, err, sizeof err) == SS_E_MESH);
  CHECK(strstr(err, "empty") != NULL);
  CHECK(ss_input_mesh_check(12, POS, 0, TRI, err, sizeof err) == SS_E_MESH);
  CHECK(ss_input_mesh_check(11, POS, 6, TRI, err, sizeof err) == SS_E_MESH);
  CHECK(strstr(err, "multiple of 3") != NULL);
  CHECK(ss_input_mesh_check(12, POS, 5, TRI, err, sizeof err) == SS_E_MESH);
  uint32_t bad[6] = {0, 1, 2, 0, 4, 1};
  CHECK(ss_input_mesh_check(12, POS, 6, bad, err, sizeof err) == SS_E_MESH);
  CHECK(strstr(err, "triangle 1") != NULL);
  float p[12];
  memcpy(p, POS, sizeof p);
  p[7] = NAN;
  CHECK(ss_input_mesh_check(12, p, 6, TRI, err, sizeof err) == SS_E_NONFINITE);
  CHECK(strstr(err, "vertex 2") != NULL);
  p[7] = INFINITY;
  CHECK(ss_input_mesh_check(12, p, 6, TRI, NULL, 0) == SS_E_NONFINITE);
  CHECK(ss_input_mesh_check(12, NULL, 6, TRI, NULL, 0) == SS_E_MESH);
}

static void test_topology(void)
{
  char err[256];
  int faces[6] = {0, 1, 2, 0, 3, 1};
  CHECK(ss_input_same_topology(12, 6, TRI, 4, 2, faces, err, sizeof err) == 1);
  CHECK(ss_input_same_topology(15, 6, TRI, 4, 2, faces, err, sizeof err) == 0);
  CHECK(strstr(err, "5 vertices") != NULL);
  CHECK(ss_input_same_topology(12, 3, TRI, 4, 2, faces, err, sizeof err) == 0);
  uint32_t other[6] = {0, 1, 2, 0, 1, 3};
  CHECK(ss_input_same_topology(12, 6, other, 4, 2, faces, err, sizeof err) == 0);
  CHECK(strstr(err, "triangle 1") != NULL);
}

static void test_time(void)
{
  double dt = -1;
  const int64_t s = 1000000000;
  CHECK(ss_input_classify_time(0, 0, 5 * s, 0.5, &dt) == SS_TIME_FIRST && dt == 0.0);
  CHECK(ss_input_classify_time(1, 5 * s, 4 * s, 0.5, &dt) == SS_TIME_BACKWARDS);
  CHECK(ss_input_classify_time(1, 5 * s, 5 * s, 0.5, &dt) == SS_TIME_SAME);
  CHECK(ss_input_classify_time(1, 5 * s, 6 * s, 0.5, &dt) == SS_TIME_GAP);
  /* 1/30 s rounded to nanoseconds either way gives one bit-identical dt */
  double a = 0, b = 0;
  CHECK(ss_input_classify_time(1, 0, 33333333, 0.5, &a) == SS_TIME_STEP);
  CHECK(ss_input_classify_time(1, 33333333, 66666667, 0.5, &b) == SS_TIME_STEP);
  CHECK(a == b);
  CHECK_NEAR(a, 0.033333, 1e-15);
  CHECK(ss_input_classify_time(1, 0, 300, 0.5, &dt) == SS_TIME_SAME);
  CHECK(strcmp(ss_input_time_name(SS_TIME_GAP), "gap") == 0);
  CHECK(strcmp(ss_input_time_name(42), "?") == 0);
}

static void test_split(void)
{
  CHECK(ss_input_split_steps(0.0333, 0.05, 8) == 1);
  CHECK(ss_input_split_steps(0.05, 0.05, 8) == 1);
  CHECK(ss_input_split_steps(0.0667, 0.05, 8) == 2);
  CHECK(ss_input_split_steps(0.1, 0.05, 8) == 2);
  CHECK(ss_input_split_steps(10.0, 0.05, 8) == 8);
  CHECK(ss_input_split_steps(1.0, 0.0, 8) == 1);
  CHECK(ss_input_split_steps(NAN, 0.05, 8) == 1);
}

static void test_slide(void)
{
  /* two triangles of a unit square */
  const double body[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const int faces[6] = {0, 1, 2, 0, 2, 3};
  int face0[3] = {0, 0, 1}, face[3] = {0, 1, 5};
  double uv0[6] = {0, 0, 0.5, 0.25, 0, 0}, uv[6] = {0.5, 0, 0.5, 0.25, 0, 0};
  double out[3];
  double worst = ss_input_slide(3, face, uv, face0, uv0, body, 4, faces, 2, out);
  CHECK_NEAR(out[0], 0.5, 1e-12); /* half an edge along x */
  /* face 0 (0.5, 0.25) = (0.75, 0.25); face 1 (0.5, 0.25) = (0.5, 0.75) */
  CHECK_NEAR(out[1], sqrt(0.3125), 1e-12);
  CHECK(out[2] == 0.0); /* face out of range */
  CHECK_NEAR(worst, sqrt(0.3125), 1e-12);
  CHECK(ss_input_slide(0, NULL, NULL, NULL, NULL, body, 4, faces, 2, NULL) == 0.0);
  float c[4];
  ss_input_slide_color(0.0, 0.02, c); /* blue, a third white */
  CHECK(c[2] > 0.99f && fabsf(c[0] - 0.35f) < 1e-6f && c[0] == c[1] && c[3] == 1.0f);
  ss_input_slide_color(0.01, 0.02, c); /* half the scale: green */
  CHECK(c[1] > 0.99f && c[0] == c[2] && c[0] < 0.36f);
  ss_input_slide_color(0.05, 0.02, c); /* beyond the scale: red */
  CHECK(c[0] > 0.99f && fabsf(c[2] - 0.35f) < 1e-6f && c[1] == c[2]);
  ss_input_slide_color(NAN, 0.02, c);
  CHECK(c[2] > 0.9f);
  ss_input_slide_color(0.01, 0.0, c);
  CHECK(c[2] > 0.9f);
}

/* The marker's colours: stretch, area ratios and the light term that makes the shape read */
static void test_marker_colors(void)
{
  float c[4];
  ss_input_stretch_color(1.0, c); /* at rest: grey */
  CHECK(fabsf(c[0] - c[1]) < 1e-6f && fabsf(c[1] - c[2]) < 1e-6f && c[0] > 0.5f && c[3] == 1.0f);
  ss_input_stretch_color(2.0, c); /* twice its area: red */
  CHECK(c[0] > 0.99f && c[1] < 0.01f && c[2] < 0.01f);
  ss_input_stretch_color(0.25, c); /* below half: blue */
  CHECK(c[2] > 0.99f && c[0] < 0.01f);
  ss_input_stretch_color(0.0, c);
  CHECK(fabsf(c[0] - c[2]) < 1e-6f);
  ss_input_stretch_color(NAN, c);
  CHECK(fabsf(c[0] - c[2]) < 1e-6f);

  /* two triangles of a unit square; the second stretched to twice its area; vertex 4 in no face */
  const double rest[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 5, 5, 5};
  const double pos[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 2, 0, 5, 5, 5};
  const int faces[6] = {0, 1, 2, 0, 2, 3};
  double area[10], ratio[5];
  ss_input_vertex_area_ratio(5, pos, rest, 2, faces, area, ratio);
  CHECK_NEAR(ratio[1], 1.0, 1e-12);  /* only in the first face */
  CHECK_NEAR(ratio[3], 2.0, 1e-12);  /* only in the second */
  CHECK_NEAR(ratio[0], 1.5, 1e-12);  /* both: (0.5 + 1) / (0.5 + 0.5) */
  CHECK_NEAR(ratio[4], 1.0, 1e-12);  /* in no face */

  /* shading: a face towards the light is brighter than one away from it, never black,
   * never brighter than its colour; a vertex in no face keeps its colour */
  const double tri[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 9, 9, 9};
  const int up[3] = {0, 1, 2}, down[3] = {0, 2, 1};
  float rgba[16];
  double nrm[12];
  for (int i = 0; i < 16; i++) rgba[i] = 0.5f;
  ss_input_shade(4, tri, 1, up, nrm, rgba);
  float lit = rgba[0];
  CHECK(lit > 0.3f && lit <= 0.5f && rgba[3] == 0.5f && rgba[12] == 0.5f);
  CHECK(rgba[0] == rgba[4] && rgba[4] == rgba[8]); /* one normal: one shade */
  for (int i = 0; i < 16; i++) rgba[i] = 0.5f;
  ss_input_shade(4, tri, 1, down, nrm, rgba);
  CHECK(rgba[0] < lit && rgba[0] >= (float)(0.5 * SS_SHADE_AMBIENT) - 1e-6f);
  /* a degenerate face: colours unchanged */
  const double flat[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  for (int i = 0; i < 12; i++) rgba[i] = 0.5f;
  ss_input_shade(3, flat, 1, up, nrm, rgba);
  CHECK(rgba[0] == 0.5f && rgba[4] == 0.5f);
}

/* A regular 30 Hz stream (stamps rounded to ns: 33333333 or 33333334 apart) */
static int64_t stamp30(int i) { return (int64_t)1000000000 * 100 + ((int64_t)i * 1000000000 + 15) / 30; }

static void test_stream(void)
{
  ss_input_stream s;
  memset(&s, 0, sizeof s);
  CHECK(ss_input_stream_arrive(&s, 5, stamp30(0), 0.5) == SS_TIME_FIRST);
  for (int i = 1; i <= 20; i++) CHECK(ss_input_stream_arrive(&s, 5 + (uint32_t)i, stamp30(i), 0.5) == SS_TIME_STEP);
  CHECK(s.period_us == 33333);
  CHECK(s.lost == 0);
  /* 3 messages lost in transport (seq gap): counted; the stamp gap is theirs, not a jump */
  CHECK(ss_input_stream_arrive(&s, 29, stamp30(24), 0.5) == SS_TIME_STEP);
  CHECK(s.lost == 3);
  CHECK(s.period_us == 33333);
  /* 20 lost over 0.7 s: 0.033 s per publication, no jump even if over max_gap */
  CHECK(ss_input_stream_arrive(&s, 50, stamp30(45), 0.5) == SS_TIME_STEP);
  CHECK(s.lost == 23);
  /* consecutive messages 0.6 s apart: a real jump */
  CHECK(ss_input_stream_arrive(&s, 51, stamp30(63), 0.5) == SS_TIME_GAP);
  /* 1 lost, 2 s apart: 1 s per publication > 0.5: a real jump */
  CHECK(ss_input_stream_arrive(&s, 53, stamp30(123), 0.5) == SS_TIME_GAP);
  CHECK(ss_input_stream_arrive(&s, 54, stamp30(123), 0.5) == SS_TIME_SAME);
  CHECK(ss_input_stream_arrive(&s, 55, stamp30(100), 0.5) == SS_TIME_BACKWARDS);
  /* a new publisher (smaller seq): nothing counted lost */
  CHECK(ss_input_stream_arrive(&s, 0, stamp30(101), 0.5) == SS_TIME_STEP);
  CHECK(s.lost == 24);
  /* the period follows a new rate, but not jitter under 10% */
  memset(&s, 0, sizeof s);
  int64_t t = 0;
  ss_input_stream_arrive(&s, 0, t, 0.5);
  const int jitter_us[6] = {16667, 17500, 15900, 16667, 16100, 17200};
  for (int i = 1; i <= 30; i++) {
    t += 1000 * (int64_t)jitter_us[i % 6];
    ss_input_stream_arrive(&s, (uint32_t)i, t, 0.5);
    if (i == 10) CHECK(s.period_us >= 15900 && s.period_us <= 17500);
  }
  int64_t p60 = s.period_us;
  for (int i = 31; i <= 36; i++) {
    t += 1000 * (int64_t)jitter_us[i % 6];
    ss_input_stream_arrive(&s, (uint32_t)i, t, 0.5);
    CHECK(s.period_us == p60); /* one value under jitter: one factorisation */
  }
  for (int i = 37; i <= 60; i++) {
    t += 33333000;
    ss_input_stream_arrive(&s, (uint32_t)i, t, 0.5);
  }
  CHECK(s.period_us == 33333);
}

static void test_plan(void)
{
  ss_input_stream s;
  memset(&s, 0, sizeof s);
  for (int i = 0; i <= 10; i++) ss_input_stream_arrive(&s, (uint32_t)i, stamp30(i), 0.5);
  ss_input_plan p;
  CHECK(ss_input_plan_step(&s, 0, 0, stamp30(10), 0, 0, 0.05, 8, &p) == SS_TIME_FIRST);
  CHECK(p.skin_ns == stamp30(10));
  int64_t skin = stamp30(10);
  /* one frame: one period, one substep */
  CHECK(ss_input_plan_step(&s, 1, skin, stamp30(11), 0, 0, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.periods == 1 && p.substeps == 1 && p.dt == 33333e-6);
  skin = p.skin_ns;
  /* the node fell 18 frames behind (0.6 s, over max_gap): 18 periods in
   * ONE step of the same substep count, never a reset; dt a whole number of periods */
  CHECK(ss_input_plan_step(&s, 1, skin, stamp30(29), 0, 0, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.periods == 18 && p.substeps == 1);
  CHECK(p.dt == 1e-6 * (18 * 33333));
  /* the skin's clock keeps the remainder: within half a period of the stamps */
  int64_t off = stamp30(29) - p.skin_ns;
  CHECK(off >= -16667000 && off <= 16667000);
  skin = p.skin_ns;
  /* many steps later the clock has not drifted */
  int last = 29;
  for (int i = 32; i < 3000; i += 3) {
    CHECK(ss_input_plan_step(&s, 1, skin, stamp30(i), 0, 0, 0.05, 8, &p) == SS_TIME_STEP);
    CHECK(p.periods == 3 && p.dt == 1e-6 * (3 * 33333));
    skin = p.skin_ns;
    last = i;
  }
  off = stamp30(last) - skin;
  CHECK(off >= -16667000 && off <= 16667000);
  /* at or behind the skin's clock: nothing to step */
  CHECK(ss_input_plan_step(&s, 1, skin, skin, 0, 0, 0.05, 8, &p) == SS_TIME_SAME && p.skin_ns == skin);
  CHECK(ss_input_plan_step(&s, 1, skin, skin - 5, 0, 0, 0.05, 8, &p) == SS_TIME_SAME);
  CHECK(ss_input_plan_step(&s, 1, skin, skin + 1000000, 0, 0, 0.05, 8, &p) == SS_TIME_SAME);
  /* a real discontinuity carried over: reset on the stepped message */
  CHECK(ss_input_plan_step(&s, 1, skin, skin + 33333000, SS_TIME_GAP, 0, 0.05, 8, &p) == SS_TIME_GAP);
  CHECK(p.skin_ns == skin + 33333000);
  CHECK(ss_input_plan_step(&s, 1, skin, skin - 1000, SS_TIME_BACKWARDS, 0, 0.05, 8, &p) ==
        SS_TIME_BACKWARDS);
  /* substeps from the input's period: 10 Hz input with max_step 0.05 -> 2, late or not */
  memset(&s, 0, sizeof s);
  for (int i = 0; i <= 5; i++) ss_input_stream_arrive(&s, (uint32_t)i, (int64_t)i * 100000000, 0.5);
  CHECK(ss_input_plan_step(&s, 1, 500000000, 600000000, 0, 0, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.substeps == 2 && p.periods == 1);
  CHECK(ss_input_plan_step(&s, 1, 500000000, 1400000000, 0, 0, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.substeps == 2 && p.periods == 9);
  CHECK(ss_input_plan_step(&s, 1, 500000000, 600000000, 0, 0, 0.01, 4, &p) == SS_TIME_STEP);
  CHECK(p.substeps == 4);
  /* hysteresis: the last step's periods are kept while the skin's clock stays within
   * tol = max(1, k/4) periods of the stamps, nudged by one within 2 tol, else rounded */
  memset(&s, 0, sizeof s);
  for (int i = 0; i <= 10; i++) ss_input_stream_arrive(&s, (uint32_t)i, stamp30(i), 0.5);
  const int64_t T = 33333000; /* ns */
  CHECK(ss_input_plan_step(&s, 1, 0, 13 * T / 2, 0, 6, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 6);
  CHECK(ss_input_plan_step(&s, 1, 0, 13 * T / 2, 0, 0, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 7);
  CHECK(ss_input_plan_step(&s, 1, 0, 8 * T, 0, 6, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 7);
  CHECK(ss_input_plan_step(&s, 1, 0, 10 * T, 0, 6, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 10);
  CHECK(ss_input_plan_step(&s, 1, 0, 4 * T, 0, 6, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 5);
  CHECK(ss_input_plan_step(&s, 1, 0, 19 * T / 10, 0, 1, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 1);
  CHECK(ss_input_plan_step(&s, 1, 0, 22 * T / 10, 0, 1, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 2);
  CHECK(ss_input_plan_step(&s, 1, 0, 3 * T / 10, 0, 1, 0.05, 8, &p) == SS_TIME_STEP && p.periods == 1);
  /* a node 6 and 7 frames behind in turn (rounding would change dt every step): at
   * most one step in four changes dt, and the clock stays within 2 periods */
  {
    int64_t clock = 0, stamp = 0;
    int prev = 0, changes = 0;
    int64_t worst = 0;
    for (int i = 0; i < 200; i++) {
      stamp += (i % 2) ? 7 * T : 6 * T;
      CHECK(ss_input_plan_step(&s, 1, clock, stamp, 0, prev, 0.05, 8, &p) == SS_TIME_STEP);
      if (i > 0 && p.periods != prev) changes++;
      prev = p.periods;
      clock = p.skin_ns;
      int64_t d = stamp - clock;
      if (d < 0) d = -d;
      if (d > worst) worst = d;
    }
    CHECK_MSG(changes * 4 <= 200, "%d dt changes in 200 steps", changes);
    CHECK_MSG(worst <= 2 * T, "clock within %lld ns of the stamps", (long long)worst);
  }
  /* extreme stamps: no overflow (UBSan), sane answers */
  memset(&s, 0, sizeof s);
  CHECK(ss_input_stream_arrive(&s, 0, INT64_MIN, 0.5) == SS_TIME_FIRST);
  CHECK(ss_input_stream_arrive(&s, 1, INT64_MAX, 0.5) == SS_TIME_GAP);
  CHECK(ss_input_stream_arrive(&s, 2, INT64_MIN, 0.5) == SS_TIME_BACKWARDS);
  CHECK(ss_input_stream_arrive(&s, 3, INT64_MIN + 1, 1e30) == SS_TIME_SAME); /* both clamped */
  CHECK(ss_input_stream_arrive(&s, 4, INT64_MAX, 1e30) == SS_TIME_STEP);
  CHECK(s.period_us > 0);
  CHECK(ss_input_plan_step(&s, 1, INT64_MIN, INT64_MAX, 0, INT32_MAX, 0.05, 8, &p) == SS_TIME_GAP);
  CHECK(ss_input_plan_step(&s, 1, 0, ((int64_t)1 << 59), 0, INT32_MAX, 0.05, 8, &p) == SS_TIME_GAP);
  CHECK(ss_input_plan_step(&s, 1, INT64_MAX - 5, INT64_MAX, 0, INT32_MAX, 0.05, 8, &p) ==
        SS_TIME_SAME);
  memset(&s, 0, sizeof s);
  ss_input_stream_arrive(&s, 0, 0, 1e30);
  ss_input_stream_arrive(&s, 1, (int64_t)1 << 55, 1e30); /* a period of 1.1 years */
  CHECK(ss_input_plan_step(&s, 1, 0, (int64_t)1 << 59, 0, INT32_MAX, 0.05, 8, &p) == SS_TIME_GAP);
  CHECK(ss_input_plan_step(&s, 1, 0, (int64_t)1 << 53, 0, INT32_MAX, 0.05, 8, &p) == SS_TIME_SAME);
  /* period unknown (one message so far): the elapsed time is one period */
  memset(&s, 0, sizeof s);
  ss_input_stream_arrive(&s, 0, 0, 0.5);
  CHECK(ss_input_plan_step(&s, 1, 0, 40000000, 0, 0, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.periods == 1 && p.dt == 0.04);
  CHECK(ss_input_plan_step(NULL, 1, 0, 40000400, 0, 0, 0.05, 8, &p) == SS_TIME_STEP && p.dt == 0.04);
}

static void test_time_wild(void);
static void test_plan_wild(void);
static void test_health(void);

/* Layout ids: equal layouts equal, any change of counts, triangles or rigid parts
 * another id, never 0. */
static void test_topology_id(void)
{
  const int faces[6] = {0, 1, 2, 2, 1, 3};
  int other[6] = {0, 1, 2, 2, 3, 1};
  const uint32_t part[4] = {1, 1, 2, 2}, part2[4] = {1, 1, 2, 0};
  uint32_t a = ss_input_topology_id(4, 2, faces, NULL);
  CHECK(a != 0 && a == ss_input_topology_id(4, 2, faces, NULL));
  CHECK(a != ss_input_topology_id(5, 2, faces, NULL));
  CHECK(a != ss_input_topology_id(4, 2, other, NULL));
  CHECK(a != ss_input_topology_id(4, 2, faces, part));
  CHECK(ss_input_topology_id(4, 2, faces, part) != ss_input_topology_id(4, 2, faces, part2));
  CHECK(ss_input_topology_id(0, 0, NULL, NULL) != 0);
}

int main(void)
{
  test_mesh_check();
  test_topology();
  test_time();
  test_split();
  test_slide();
  test_marker_colors();
  test_stream();
  test_plan();
  test_time_wild();
  test_plan_wild();
  test_health();
  test_topology_id();
  return ss_test_finish("test_input");
}

/* Regression (issue 14, found by fuzzing): a wild stamp difference overflowed
 * signed arithmetic (UBSan: 9223372036854775807 + 500 in the rounding to
 * microseconds). Any pair of stamps is now classified without UB. */
/* Regression (issue 34, found by a harness of the stream planner): the last step's
 * periods nudged by one at INT_MAX overflowed int (UBSan: 2147483647 + 1; 22 crafted
 * messages killed the sanitizer-built node). Now the periods are counted in 64 bits
 * and clamped to INT_MAX, the skin's clock advanced by as many. */
static void test_plan_wild(void)
{
  ss_input_stream s;
  memset(&s, 0, sizeof s);
  s.period_us = 1; /* a 1 us input period */
  ss_input_plan p;
  /* elapsed INT_MAX + 3/8 INT_MAX periods: off 3/8 INT_MAX, tol INT_MAX / 4: one more */
  int64_t elapsed_us = (int64_t)INT_MAX + 3 * ((int64_t)INT_MAX / 8);
  CHECK(ss_input_plan_step(&s, 1, 0, 1000 * elapsed_us, 0, INT_MAX, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.periods == INT_MAX);
  CHECK(p.skin_ns == 1000 * (int64_t)INT_MAX);
  CHECK(p.dt == 1e-6 * (double)INT_MAX);
  /* one fewer at INT_MIN's side cannot happen (periods >= 1): the smallest nudge */
  CHECK(ss_input_plan_step(&s, 1, 0, 1000 * ((int64_t)INT_MAX - 3 * ((int64_t)INT_MAX / 8)), 0,
                           INT_MAX, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.periods == INT_MAX - 1);
  /* an input period of 290,000 years (a huge ~max_gap let it be measured) and a skin's
   * clock at the stamps' bound: the clock advanced by one such period overflowed int64 */
  s.period_us = (int64_t)9000000000000000; /* 9e15 us */
  int64_t top = (int64_t)1 << 62;
  CHECK(ss_input_plan_step(&s, 1, top - 2000000000, top, 0, 1, 0.05, 8, &p) == SS_TIME_STEP);
  CHECK(p.periods >= 1 && p.skin_ns > top - 2000000000 && isfinite(p.dt) && p.dt > 0.0);
}

static void test_time_wild(void)
{
  double dt = -1.0;
  CHECK(ss_input_classify_time(1, 0, INT64_MAX, 1e30, &dt) == SS_TIME_STEP);
  CHECK(isfinite(dt) && dt > 9.2e9 && dt < 9.3e9);
  CHECK(ss_input_classify_time(1, INT64_MIN, INT64_MAX, 1e30, &dt) == SS_TIME_STEP);
  CHECK(isfinite(dt) && dt > 1.8e10 && dt < 1.9e10);
  CHECK(ss_input_classify_time(1, INT64_MIN, INT64_MAX, INFINITY, &dt) == SS_TIME_STEP);
  CHECK(ss_input_classify_time(1, INT64_MIN, INT64_MAX, 0.5, &dt) == SS_TIME_GAP && dt == 0.0);
  CHECK(ss_input_classify_time(1, INT64_MAX, INT64_MIN, 0.5, &dt) == SS_TIME_BACKWARDS);
  CHECK(ss_input_classify_time(1, -1, INT64_MAX, 0.5, &dt) == SS_TIME_GAP);
  CHECK(ss_input_classify_time(1, INT64_MAX - 1499, INT64_MAX, 0.5, &dt) == SS_TIME_STEP);
  CHECK(dt == 1e-6);
  CHECK(ss_input_classify_time(1, INT64_MAX - 499, INT64_MAX, 0.5, &dt) == SS_TIME_SAME);
  /* a NaN gap bound lets no stamp through as a step */
  CHECK(ss_input_classify_time(1, 0, 33333333, NAN, &dt) == SS_TIME_GAP);
}

/* The level of a diagnostics window from its figures (doc/ros.md, "Health on
 * /diagnostics"). */
static void test_health(void)
{
  char msg[128];
  ss_input_window w = {30, 30, 0, 0, 0, 0, 0, 5.0, 33.3, 0, 0};
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_OK);
  CHECK(strcmp(msg, "stepping normally") == 0);
  w.step_ms_mean = 30.0; /* over 80% of the period */
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_WARN);
  CHECK(strstr(msg, "step 30.0 ms") != NULL);
  w.step_ms_mean = 70.0; /* over twice the period */
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_ERROR);
  CHECK(strstr(msg, "cannot keep up") != NULL);
  w.period_ms = 0.0; /* unknown period: step time not judged */
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_OK);
  w.period_ms = 33.3;
  w.step_ms_mean = 5.0;
  w.skipped = 2;
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_WARN);
  CHECK(strstr(msg, "2 skipped") != NULL);
  w.skipped = 0;
  w.resets = 1;
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_WARN);
  CHECK(strstr(msg, "reset 1") != NULL);
  w.resets = 0;
  w.lowered = 12; /* a step budget traded accuracy for time */
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_WARN);
  CHECK(strstr(msg, "accuracy traded for time: 12 of 30") != NULL);
  w.lowered = 0;
  w.rejected = 3; /* some rejected, some stepped */
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_WARN);
  CHECK(strstr(msg, "3 inputs rejected") != NULL);
  w.stepped = 0; /* every one rejected */
  w.step_ms_mean = 0.0;
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_ERROR);
  CHECK(strstr(msg, "every input rejected") != NULL);
  w.stepped = 27;
  w.failures = 1; /* a failure outranks everything */
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_ERROR);
  CHECK(strstr(msg, "failed") != NULL);
  /* a topology_id changing on every message (issue 34): each input creates the skin
   * again, none steps it; the status said OK "stepping normally" */
  ss_input_window recreated = {.arrived = 10, .stepped = 10, .period_ms = 100.0, .not_stepped = 10};
  CHECK(ss_input_health(&recreated, msg, sizeof msg) == SS_HEALTH_WARN);
  CHECK(strstr(msg, "none stepped the skin") != NULL && strstr(msg, "topology_id") != NULL);
  recreated.not_stepped = 9; /* one stepped: not this warning */
  CHECK(ss_input_health(&recreated, msg, sizeof msg) == SS_HEALTH_OK);
  recreated.stepped = recreated.not_stepped = 2; /* a start: the first creates */
  CHECK(ss_input_health(&recreated, msg, sizeof msg) == SS_HEALTH_OK);
  ss_input_window none = {0, 0, 0, 0, 0, 0, 0, 0.0, 0.0, 0, 0};
  CHECK(ss_input_health(&none, NULL, 0) == SS_HEALTH_WARN);
  CHECK(ss_input_health(&none, msg, sizeof msg) == SS_HEALTH_WARN);
  CHECK(strstr(msg, "no kinematic_mesh") != NULL);
  w.failures = 0;
  w.step_ms_mean = NAN; /* a NaN step time is not judged (no crash, no false alarm) */
  w.rejected = 0;
  CHECK(ss_input_health(&w, msg, sizeof msg) == SS_HEALTH_OK);
  /* a step still running: ERROR after twice a known input period, never while it is unknown */
  CHECK(ss_input_busy_error_s(33.3) == 2e-3 * 33.3);
  CHECK(ss_input_busy_error_s(0.0) == 0.0);
  CHECK(ss_input_busy_error_s(-5.0) == 0.0);
  CHECK(ss_input_busy_error_s(NAN) == 0.0);
  CHECK(ss_input_busy_error_s(INFINITY) == 0.0);
  /* the status said meanwhile: WARN, ERROR past that bound, a last ERROR kept */
  char val[16];
  CHECK(ss_input_busy(0.05, 33.3, SS_HEALTH_OK, msg, sizeof msg, val, sizeof val) == SS_HEALTH_WARN);
  CHECK(strcmp(msg, "step in progress for 0.1 s") == 0 && strcmp(val, "0.1") == 0);
  CHECK(ss_input_busy(0.07, 33.3, SS_HEALTH_OK, msg, sizeof msg, NULL, 0) == SS_HEALTH_ERROR);
  CHECK(ss_input_busy(9.0, 0.0, SS_HEALTH_WARN, msg, sizeof msg, NULL, 0) == SS_HEALTH_WARN);
  CHECK(ss_input_busy(0.01, 0.0, SS_HEALTH_ERROR, NULL, 0, NULL, 0) == SS_HEALTH_ERROR);
  CHECK(ss_input_busy(0.01, 0.0, 3, NULL, 0, NULL, 0) == SS_HEALTH_WARN); /* 3: stale, none */
}
