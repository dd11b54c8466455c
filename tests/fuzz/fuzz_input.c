/* libFuzzer harness: what a node checks before it trusts a received mesh and
 * its stamp (src/stream/ss_input.h): ss_input_mesh_check and
 * ss_input_same_topology on arbitrary arrays, ss_input_classify_time on any
 * pair of stamps (issue 14: a wild difference overflowed signed arithmetic),
 * ss_input_split_steps, ss_input_slide and its colours. Asserts the documented
 * results: a mesh accepted has every index in range and every value finite; a
 * step has a finite positive dt; splits are in [1, max_count]. */
#include <assert.h>

#include "fuzz_util.h"
#include "ss_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fz f = {data, size};
  char err[128];
  /* stamps */
  int64_t prev = (int64_t)fz_u64(&f), now = (int64_t)fz_u64(&f);
  if (fz_u8(&f) & 1) now = (int64_t)((uint64_t)prev + fz_u32(&f) % 100000000u); /* near (wraps, no UB) */
  double max_gap = fz_double(&f, 1.0), dt = -1.0;
  int kind = ss_input_classify_time(fz_u8(&f) & 1, prev, now, max_gap, &dt);
  assert(kind >= SS_TIME_FIRST && kind <= SS_TIME_GAP);
  assert(kind == SS_TIME_STEP ? (isfinite(dt) && dt > 0.0) : dt == 0.0);
  (void)ss_input_time_name(kind);
  int maxc = fz_int(&f, -3, 64);
  int k = ss_input_split_steps(fz_double(&f, 0.1), fz_double(&f, 0.05), maxc);
  assert(k >= 1 && k <= (maxc < 1 ? 1 : maxc));
  /* a received mesh */
  size_t npos = (size_t)fz_int(&f, 0, 40), ntri = (size_t)fz_int(&f, 0, 40);
  float *pos = malloc((npos ? npos : 1) * sizeof(float));
  uint32_t *tri = malloc((ntri ? ntri : 1) * sizeof(uint32_t));
  for (size_t i = 0; i < npos; i++) { /* out of float range: +-inf, as a sender's cast gives */
    double d = fz_double(&f, 1.0);
    pos[i] = fabs(d) > 3.4e38 ? (float)copysign(INFINITY, d) : (float)d;
  }
  for (size_t i = 0; i < ntri; i++) tri[i] = (fz_u8(&f) & 0x80) ? fz_u32(&f) : fz_u8(&f) % 16u;
  int st = ss_input_mesh_check(npos, pos, ntri, tri, err, sizeof err);
  if (st == SS_OK) {
    assert(npos % 3 == 0 && ntri % 3 == 0 && npos > 0 && ntri > 0);
    for (size_t i = 0; i < ntri; i++) assert(tri[i] < npos / 3);
    for (size_t i = 0; i < npos; i++) assert(isfinite(pos[i]));
    int nface = (int)(ntri / 3);
    int *faces = malloc(ntri * sizeof(int));
    for (size_t i = 0; i < ntri; i++) faces[i] = (fz_u8(&f) & 7) ? (int)tri[i] : fz_int(&f, -2, 20);
    (void)ss_input_same_topology(npos, ntri, tri, (int)(npos / 3) + fz_int(&f, -1, 1),
                                 nface + fz_int(&f, -1, 1) * (fz_u8(&f) & 1), faces, err, sizeof err);
    /* slide over that mesh, with anchors in and out of range */
    double *dpos = malloc(npos * sizeof(double));
    for (size_t i = 0; i < npos; i++) dpos[i] = pos[i];
    int n = fz_int(&f, 0, 8);
    int fa[8], fb[8];
    double uva[16], uvb[16], out[8];
    for (int i = 0; i < n; i++) {
      fa[i] = fz_int(&f, -1, nface);
      fb[i] = fz_int(&f, -1, nface);
      for (int j = 0; j < 2; j++) uva[2 * i + j] = fz_double(&f, 1.0), uvb[2 * i + j] = fz_double(&f, 1.0);
    }
    double w = ss_input_slide(n, fa, uva, fb, uvb, dpos, (int)(npos / 3), faces, nface, out);
    assert(isfinite(w) && w >= 0.0);
    for (int i = 0; i < n; i++) assert(isfinite(out[i]) && out[i] <= w);
    float rgba[4];
    ss_input_slide_color(w, fz_double(&f, 0.05), rgba);
    for (int i = 0; i < 4; i++) assert(rgba[i] >= 0.0f && rgba[i] <= 1.0f);
    free(dpos);
    free(faces);
  }
  free(pos);
  free(tri);
  return 0;
}
