/* ss_input.h: checks of received meshes, stamp classification, step splitting,
 * slide distances and colours. */
#include "skin_sim/ss_input.h"
#include "ss_test.h"

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
  ss_input_slide_color(0.0, 0.02, c);
  CHECK(c[2] > 0.9f && c[0] < 0.2f && c[3] == 1.0f);
  ss_input_slide_color(0.05, 0.02, c);
  CHECK(c[0] > 0.9f && c[2] < 0.2f);
  ss_input_slide_color(NAN, 0.02, c);
  CHECK(c[2] > 0.9f);
  ss_input_slide_color(0.01, 0.0, c);
  CHECK(c[2] > 0.9f);
}

static void test_time_wild(void);

int main(void)
{
  test_mesh_check();
  test_topology();
  test_time();
  test_split();
  test_slide();
  test_time_wild();
  return ss_test_finish("test_input");
}

/* Regression (issue 14, found by fuzzing): a wild stamp difference overflowed
 * signed arithmetic (UBSan: 9223372036854775807 + 500 in the rounding to
 * microseconds). Any pair of stamps is now classified without UB. */
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
