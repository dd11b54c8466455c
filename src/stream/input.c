/* skin_sim core: checks of meshes and stamps arriving from outside (ss_input.h).
 *
 * Plain loops over flat arrays; nothing allocates. Written for the ROS skin
 * node, which rejects a bad SkinMesh before it reaches ss_sim, and for any
 * other caller receiving meshes as float arrays. */
#include "ss_input.h"
#include "ss_vec.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>

#define SS_INPUT_ERR(...) \
  do { if (err && err_sz > 0) snprintf(err, (size_t)err_sz, __VA_ARGS__); } while (0)

int ss_input_mesh_check(size_t npos, const float *pos, size_t ntri, const uint32_t *tri,
                        char *err, int err_sz)
{
  if (npos == 0 || ntri == 0) {
    SS_INPUT_ERR("empty mesh (%zu position values, %zu triangle indices)", npos, ntri);
    return SS_E_MESH;
  }
  if (npos % 3 != 0) {
    SS_INPUT_ERR("%zu position values is not a multiple of 3 (xyz per vertex)", npos);
    return SS_E_MESH;
  }
  if (ntri % 3 != 0) {
    SS_INPUT_ERR("%zu triangle indices is not a multiple of 3", ntri);
    return SS_E_MESH;
  }
  if (!pos || !tri) {
    SS_INPUT_ERR("missing arrays");
    return SS_E_MESH;
  }
  size_t nvert = npos / 3;
  if (nvert > (size_t)INT_MAX || ntri / 3 > (size_t)INT_MAX) {
    SS_INPUT_ERR("mesh too large (%zu vertices, %zu triangles)", nvert, ntri / 3);
    return SS_E_MESH;
  }
  for (size_t i = 0; i < ntri; i++) {
    if ((size_t)tri[i] >= nvert) {
      SS_INPUT_ERR("triangle %zu uses vertex %u but there are only %zu vertices", i / 3,
                   (unsigned)tri[i], nvert);
      return SS_E_MESH;
    }
  }
  for (size_t i = 0; i < npos; i++) {
    if (!isfinite(pos[i])) {
      SS_INPUT_ERR("vertex %zu has a non-finite coordinate (%g)", i / 3, (double)pos[i]);
      return SS_E_NONFINITE;
    }
  }
  return SS_OK;
}

int ss_input_same_topology(size_t npos, size_t ntri, const uint32_t *tri, int nvert, int nface,
                           const int *faces, char *err, int err_sz)
{
  if (npos != 3 * (size_t)nvert) {
    SS_INPUT_ERR("%zu vertices where the topology has %d", npos / 3, nvert);
    return 0;
  }
  if (ntri != 3 * (size_t)nface) {
    SS_INPUT_ERR("%zu triangles where the topology has %d", ntri / 3, nface);
    return 0;
  }
  for (size_t i = 0; i < ntri; i++) {
    if (faces[i] < 0 || (uint32_t)faces[i] != tri[i]) {
      SS_INPUT_ERR("triangle %zu differs from the topology's", i / 3);
      return 0;
    }
  }
  return 1;
}

const char *ss_input_time_name(int kind)
{
  switch (kind) {
  case SS_TIME_FIRST: return "first";
  case SS_TIME_STEP: return "step";
  case SS_TIME_SAME: return "same";
  case SS_TIME_BACKWARDS: return "backwards";
  case SS_TIME_GAP: return "gap";
  default: return "?";
  }
}

int ss_input_classify_time(int have_prev, int64_t prev_ns, int64_t now_ns, double max_gap_s,
                           double *dt)
{
  if (dt) *dt = 0.0;
  if (!have_prev) return SS_TIME_FIRST;
  if (now_ns < prev_ns) return SS_TIME_BACKWARDS;
  if (now_ns == prev_ns) return SS_TIME_SAME;
  /* now > prev, so the difference is exact in unsigned 64 bits whatever the
   * stamps (a signed difference or rounding can overflow: UB); a NaN max_gap
   * lets nothing through. */
  uint64_t d_ns = (uint64_t)now_ns - (uint64_t)prev_ns;
  double d = 1e-9 * (double)d_ns;
  if (!(d <= max_gap_s)) return SS_TIME_GAP;
  uint64_t us = d_ns / 1000 + (d_ns % 1000 >= 500);
  if (us == 0) return SS_TIME_SAME; /* under half a microsecond: nothing to step */
  if (dt) *dt = 1e-6 * (double)us;
  return SS_TIME_STEP;
}

int ss_input_split_steps(double dt, double max_step, int max_count)
{
  if (max_count < 1) max_count = 1;
  if (!(max_step > 0.0) || !(dt > max_step)) return 1;
  double k = ceil(dt / max_step - 1e-9);
  if (!(k < (double)max_count)) return max_count;
  return k < 1.0 ? 1 : (int)k;
}

/* Stamps are clamped to +-2^62 ns (+-146 years around the epoch; ROS time is
 * below 2^32 s < 2^62 ns), so that differences and clocks never overflow. */
#define SS_STAMP_MAX ((int64_t)1 << 62)
static int64_t clamp_stamp(int64_t t)
{
  return t > SS_STAMP_MAX ? SS_STAMP_MAX : t < -SS_STAMP_MAX ? -SS_STAMP_MAX : t;
}

int ss_input_stream_arrive(ss_input_stream *s, uint32_t seq, int64_t stamp_ns, double max_gap_s)
{
  stamp_ns = clamp_stamp(stamp_ns);
  if (!s->have_prev) {
    s->have_prev = 1;
    s->prev_seq = seq;
    s->prev_ns = stamp_ns;
    return SS_TIME_FIRST;
  }
  uint32_t lost = 0;
  if (seq > s->prev_seq + 1u && seq - s->prev_seq <= 1000000u) lost = seq - s->prev_seq - 1u;
  s->lost += lost;
  int64_t prev = s->prev_ns;
  s->prev_seq = seq;
  s->prev_ns = stamp_ns;
  if (stamp_ns < prev) return SS_TIME_BACKWARDS;
  if (stamp_ns == prev) return SS_TIME_SAME;
  uint64_t dn = (uint64_t)stamp_ns - (uint64_t)prev; /* in (0, 2^63]: clamped stamps */
  double d = 1e-9 * (double)dn;
  if (d > max_gap_s * ((double)lost + 1.0)) return SS_TIME_GAP;
  if (lost == 0) {
    int64_t us = (int64_t)((dn + 500u) / 1000u);
    if (us > 0) {
      s->diff_us[s->diff_head] = us;
      s->diff_head = (s->diff_head + 1) % SS_INPUT_PERIOD_WINDOW;
      if (s->ndiff < SS_INPUT_PERIOD_WINDOW) s->ndiff++;
      int64_t sorted[SS_INPUT_PERIOD_WINDOW];
      for (int i = 0; i < s->ndiff; i++) { /* insertion sort of at most 15 */
        int64_t v = s->diff_us[i];
        int j = i;
        for (; j > 0 && sorted[j - 1] > v; j--) sorted[j] = sorted[j - 1];
        sorted[j] = v;
      }
      int64_t med = sorted[s->ndiff / 2];
      int64_t dev = med > s->period_us ? med - s->period_us : s->period_us - med;
      if (s->period_us <= 0 || 10 * dev > s->period_us) s->period_us = med;
    }
  }
  return SS_TIME_STEP;
}

int ss_input_plan_step(const ss_input_stream *s, int have_skin, int64_t skin_ns, int64_t stamp_ns,
                       int discontinuity, int prev_periods, double max_step, int max_split,
                       ss_input_plan *plan)
{
  skin_ns = clamp_stamp(skin_ns);
  stamp_ns = clamp_stamp(stamp_ns);
  plan->periods = 0;
  plan->substeps = 0;
  plan->dt = 0.0;
  plan->skin_ns = stamp_ns;
  if (!have_skin) return plan->kind = SS_TIME_FIRST;
  if (discontinuity == SS_TIME_BACKWARDS || discontinuity == SS_TIME_GAP)
    return plan->kind = discontinuity;
  plan->skin_ns = skin_ns;
  if (stamp_ns <= skin_ns) return plan->kind = SS_TIME_SAME; /* at or behind the skin's clock */
  int64_t elapsed_us = (int64_t)(((uint64_t)stamp_ns - (uint64_t)skin_ns + 500u) / 1000u);
  if (elapsed_us > ((int64_t)1 << 48)) /* over 8 years: no step but a jump (and no overflow) */
    return plan->kind = SS_TIME_GAP;
  /* a measured period over 8 years (a huge max_gap lets one through) is none: the
   * skin's clock then moves by at most a few times 2^48 us, and never overflows */
  int64_t period_us = s && s->period_us > 0 && s->period_us <= ((int64_t)1 << 48) ? s->period_us
                                                                                  : elapsed_us;
  if (period_us <= 0) return plan->kind = SS_TIME_SAME; /* under half a microsecond */
  /* whole periods: the last step's while the skin's clock stays within tol =
   * max(1, k/4) periods of the stamps (one dt, no refactorisation); one more or
   * one fewer within 2 tol (the clock drifts back without overshooting); else
   * the elapsed time rounded (the clock within half a period) */
  int64_t k = (elapsed_us + period_us / 2) / period_us;
  if (prev_periods >= 1 && (int64_t)prev_periods <= 2 * k + 2) {
    int64_t tol_us = period_us * (prev_periods >= 4 ? prev_periods : 4) / 4;
    int64_t off_us = elapsed_us - (int64_t)prev_periods * period_us;
    int64_t a_us = off_us < 0 ? -off_us : off_us;
    if (a_us <= tol_us) k = prev_periods;
    else if (a_us <= 2 * tol_us) k = (int64_t)prev_periods + (off_us > 0 ? 1 : -1); /* INT_MAX + 1 */
  }
  if (k < 1) return plan->kind = SS_TIME_SAME;
  if (k > INT_MAX) k = INT_MAX;
  plan->periods = (int)k;
  plan->dt = 1e-6 * (double)(k * period_us);
  plan->substeps = ss_input_split_steps(1e-6 * (double)period_us, max_step, max_split);
  plan->skin_ns = skin_ns + 1000 * k * period_us;
  return plan->kind = SS_TIME_STEP;
}

static uint32_t fnv_u32(uint32_t h, uint32_t v)
{
  for (int k = 0; k < 4; k++) {
    h ^= (v >> (8 * k)) & 255u;
    h *= 16777619u;
  }
  return h;
}

uint32_t ss_input_topology_id(int nvert, int nface, const int *faces, const uint32_t *rigid_part)
{
  uint32_t h = fnv_u32(fnv_u32(2166136261u, (uint32_t)nvert), (uint32_t)nface);
  for (size_t i = 0; faces && i < 3 * (size_t)(nface > 0 ? nface : 0); i++)
    h = fnv_u32(h, (uint32_t)faces[i]);
  for (size_t i = 0; rigid_part && i < (size_t)(nvert > 0 ? nvert : 0); i++)
    h = fnv_u32(h, rigid_part[i]);
  return h ? h : 1u;
}

static void anchor_point(const double *pos, int nvert, const int *faces, int nface, int f,
                         const double uv[2], double out[3])
{
  out[0] = out[1] = out[2] = 0.0;
  if (f < 0 || f >= nface) return;
  const int *c = faces + 3 * (size_t)f;
  if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= nvert || c[1] >= nvert || c[2] >= nvert) return;
  const double *a = pos + 3 * (size_t)c[0], *b = pos + 3 * (size_t)c[1], *d = pos + 3 * (size_t)c[2];
  for (int k = 0; k < 3; k++) out[k] = a[k] + uv[0] * (b[k] - a[k]) + uv[1] * (d[k] - a[k]);
}

double ss_input_slide(int n, const int *face, const double *uv, const int *face0,
                      const double *uv0, const double *body_pos, int body_nvert,
                      const int *body_faces, int body_nface, double *out)
{
  double worst = 0.0;
  for (int i = 0; i < n; i++) {
    double p[3], q[3], s = 0.0;
    if (face[i] >= 0 && face[i] < body_nface && face0[i] >= 0 && face0[i] < body_nface) {
      anchor_point(body_pos, body_nvert, body_faces, body_nface, face[i], uv + 2 * (size_t)i, p);
      anchor_point(body_pos, body_nvert, body_faces, body_nface, face0[i], uv0 + 2 * (size_t)i, q);
      s = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
               (p[2] - q[2]) * (p[2] - q[2]));
      if (!isfinite(s)) s = 0.0;
    }
    if (out) out[i] = s;
    if (s > worst) worst = s;
  }
  return worst;
}

void ss_input_slide_color(double d, double scale, float rgba[4])
{
  double t = (scale > 0.0 && isfinite(d)) ? d / scale : 0.0;
  if (t < 0.0) t = 0.0;
  if (t > 1.0) t = 1.0;
  /* blue -> green -> red, light (a third white) so that shading (ss_input_shade) reads
   * on every hue: saturated blue is too dark to show it */
  double r, g, b;
  if (t < 0.5) { r = 0.0; g = 2.0 * t; b = 1.0 - 2.0 * t; }
  else { r = 2.0 * t - 1.0; g = 2.0 - 2.0 * t; b = 0.0; }
  rgba[0] = (float)(0.35 + 0.65 * r);
  rgba[1] = (float)(0.35 + 0.65 * g);
  rgba[2] = (float)(0.35 + 0.65 * b);
  rgba[3] = 1.0f;
}

void ss_input_stretch_color(double ratio, float rgba[4])
{
  /* log2 of the ratio: -1 (half the area) blue, 0 grey, +1 (twice) red */
  double t = (ratio > 0.0 && isfinite(ratio)) ? log2(ratio) : 0.0;
  if (t < -1.0) t = -1.0;
  if (t > 1.0) t = 1.0;
  const double grey = 0.8;
  double r = grey, g = grey, b = grey;
  if (t < 0.0) { r = grey * (1.0 + t); g = r; b = grey + (1.0 - grey) * -t; }
  else { r = grey + (1.0 - grey) * t; g = grey * (1.0 - t); b = g; }
  rgba[0] = (float)r;
  rgba[1] = (float)g;
  rgba[2] = (float)b;
  rgba[3] = 1.0f;
}

static int face_ok(const int *f, int nvert)
{
  return f[0] >= 0 && f[1] >= 0 && f[2] >= 0 && f[0] < nvert && f[1] < nvert && f[2] < nvert;
}

void ss_input_vertex_area_ratio(int nvert, const double *pos, const double *rest, int nface,
                                const int *faces, double *area, double *ratio)
{
  for (int v = 0; v < 2 * nvert; v++) area[v] = 0.0;
  for (int f = 0; f < nface; f++) {
    const int *t = faces + 3 * (size_t)f;
    if (!face_ok(t, nvert)) continue;
    double a[3], a0[3]; /* twice the areas: only their ratios are used */
    tri_area_vector(pos + 3 * (size_t)t[0], pos + 3 * (size_t)t[1], pos + 3 * (size_t)t[2], a);
    tri_area_vector(rest + 3 * (size_t)t[0], rest + 3 * (size_t)t[1], rest + 3 * (size_t)t[2], a0);
    double now = sqrt(dot3(a, a)), at_rest = sqrt(dot3(a0, a0));
    for (int k = 0; k < 3; k++) {
      area[2 * (size_t)t[k]] += now;
      area[2 * (size_t)t[k] + 1] += at_rest;
    }
  }
  for (int v = 0; v < nvert; v++) {
    double now = area[2 * (size_t)v], at_rest = area[2 * (size_t)v + 1];
    ratio[v] = at_rest > 0.0 && isfinite(now / at_rest) ? now / at_rest : 1.0;
  }
}

void ss_input_shade(int nvert, const double *pos, int nface, const int *faces, double *normal,
                    float *rgba)
{
  const double light_in[3] = SS_SHADE_LIGHT;
  double len = sqrt(dot3(light_in, light_in));
  const double light[3] = {light_in[0] / len, light_in[1] / len, light_in[2] / len};
  for (size_t i = 0; i < 3 * (size_t)nvert; i++) normal[i] = 0.0;
  for (int f = 0; f < nface; f++) {
    const int *t = faces + 3 * (size_t)f;
    if (!face_ok(t, nvert)) continue;
    double a[3];
    tri_area_vector(pos + 3 * (size_t)t[0], pos + 3 * (size_t)t[1], pos + 3 * (size_t)t[2], a);
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++) normal[3 * (size_t)t[k] + d] += a[d];
  }
  for (int v = 0; v < nvert; v++) {
    const double *n = normal + 3 * (size_t)v;
    double nn = sqrt(dot3(n, n));
    if (!(nn > 0.0) || !isfinite(nn)) continue;
    double h = 0.5 + 0.5 * dot3(n, light) / nn; /* half-Lambert: 0 facing away, 1 facing */
    double shade = SS_SHADE_AMBIENT + (1.0 - SS_SHADE_AMBIENT) * h * h;
    for (int c = 0; c < 3; c++) rgba[4 * (size_t)v + c] = (float)(shade * rgba[4 * (size_t)v + c]);
  }
}

/* ------------------------------------------------------------------ health */
int ss_input_health(const ss_input_window *w, char *msg, int msg_sz)
{
  char tmp[8];
  if (!msg || msg_sz <= 0) { msg = tmp; msg_sz = (int)sizeof tmp; }
  size_t n = (size_t)msg_sz;
  double period = (w->period_ms > 0.0 && isfinite(w->period_ms)) ? w->period_ms : 0.0;
  double step = (w->stepped > 0 && isfinite(w->step_ms_mean)) ? w->step_ms_mean : 0.0;
  /* errors first: the worst reason is the one named */
  if (w->failures > 0) {
    snprintf(msg, n, "%u substeps failed (non-finite values), last good state kept",
             (unsigned)w->failures);
    return SS_HEALTH_ERROR;
  }
  if (w->rejected > 0 && w->stepped == 0) {
    snprintf(msg, n, "every input rejected (%u), the skin is not stepped", (unsigned)w->rejected);
    return SS_HEALTH_ERROR;
  }
  if (period > 0.0 && step > 2.0 * period) {
    snprintf(msg, n, "step %.1f ms over twice the input period %.1f ms: cannot keep up", step,
             period);
    return SS_HEALTH_ERROR;
  }
  if (w->arrived == 0) {
    snprintf(msg, n, "no kinematic_mesh received");
    return SS_HEALTH_WARN;
  }
  if (w->rejected > 0) {
    snprintf(msg, n, "%u inputs rejected", (unsigned)w->rejected);
    return SS_HEALTH_WARN;
  }
  if (w->resets > 0) {
    snprintf(msg, n, "skin reset %u times", (unsigned)w->resets);
    return SS_HEALTH_WARN;
  }
  if (w->dropped + w->skipped > 0) {
    snprintf(msg, n, "%u inputs dropped, %u skipped (falling behind)", (unsigned)w->dropped,
             (unsigned)w->skipped);
    return SS_HEALTH_WARN;
  }
  if (w->stepped >= 3 && w->not_stepped >= w->stepped) {
    snprintf(msg, n, "%u inputs processed, none stepped the skin: it is created again on each "
             "(topology_id changing on every message?) or their stamps do not advance",
             (unsigned)w->stepped);
    return SS_HEALTH_WARN;
  }
  if (w->lowered > 0) {
    snprintf(msg, n, "accuracy traded for time: %u of %u steps with fewer substeps or iterations "
             "than the settings' to fit the step budget", (unsigned)w->lowered,
             (unsigned)w->stepped);
    return SS_HEALTH_WARN;
  }
  if (period > 0.0 && step > SS_HEALTH_BUDGET * period) {
    snprintf(msg, n, "step %.1f ms over %.0f%% of the input period %.1f ms", step,
             100.0 * SS_HEALTH_BUDGET, period);
    return SS_HEALTH_WARN;
  }
  snprintf(msg, n, "stepping normally");
  return SS_HEALTH_OK;
}

double ss_input_busy_error_s(double period_ms)
{
  if (!(period_ms > 0.0) || !isfinite(period_ms)) return 0.0;
  return 2e-3 * period_ms;
}

int ss_input_busy(double busy_s, double period_ms, int last_level, char *msg, int msg_sz,
                  char *value, int value_sz)
{
  double error_s = ss_input_busy_error_s(period_ms);
  int level = error_s > 0.0 && busy_s >= error_s ? SS_HEALTH_ERROR : SS_HEALTH_WARN;
  if (last_level == SS_HEALTH_ERROR) level = SS_HEALTH_ERROR;
  if (msg && msg_sz > 0) snprintf(msg, (size_t)msg_sz, "step in progress for %.1f s", busy_s);
  if (value && value_sz > 0) snprintf(value, (size_t)value_sz, "%.1f", busy_s);
  return level;
}
