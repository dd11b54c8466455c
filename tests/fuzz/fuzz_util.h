/* Reading a libFuzzer input as a stream of small values: every harness in
 * tests/fuzz draws its sizes, indices, doubles and settings from the bytes it
 * is given; an input that runs out reads zeros. Doubles come from a mix of
 * "ordinary" values (small grids, so coincident and collinear points are
 * common) and raw bit patterns (NaN, Inf, huge, subnormal). */
#ifndef SKIN_SIM_FUZZ_UTIL_H
#define SKIN_SIM_FUZZ_UTIL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct fz {
  const uint8_t *p;
  size_t n;
} fz;

static inline uint8_t fz_u8(fz *f) {
  if (f->n == 0) return 0;
  f->n--;
  return *f->p++;
}

static inline uint32_t fz_u32(fz *f) {
  uint32_t v = 0;
  for (int i = 0; i < 4; i++) v = v << 8 | fz_u8(f);
  return v;
}

static inline uint64_t fz_u64(fz *f) {
  return (uint64_t)fz_u32(f) << 32 | fz_u32(f);
}

/* an int in [lo, hi] */
static inline int fz_int(fz *f, int lo, int hi) {
  if (hi <= lo) return lo;
  return lo + (int)(fz_u32(f) % (uint32_t)(hi - lo + 1));
}

static inline double fz_raw(fz *f) {
  uint64_t b = fz_u64(f);
  double d;
  memcpy(&d, &b, sizeof d);
  return d;
}

/* A double: mostly on a coarse grid scaled by `scale`, sometimes special. */
static inline double fz_double(fz *f, double scale) {
  uint8_t k = fz_u8(f);
  switch (k >> 5) {
  case 0: return scale * ((int)fz_u8(f) - 128) / 16.0;  /* coarse grid */
  case 1: return scale * ((int)fz_u8(f) - 128) / 4.0;
  case 2: return scale * ((double)fz_u32(f) / 4294967296.0 - 0.5) * 4.0; /* fine */
  case 3: return scale * (k & 1 ? 1.0 : 0.0);
  case 4: { /* huge or tiny magnitudes */
    static const double mags[8] = {1e-300, 1e-12, 1e6, 1e12, 1e150, 1e300, 1.7e308, 4.9e-324};
    return ((k & 8) ? -1.0 : 1.0) * mags[k & 7];
  }
  case 5: { /* non-finite */
    static const double sp[4] = {NAN, INFINITY, -INFINITY, -NAN};
    return (k & 16) ? fz_raw(f) : sp[k & 3];
  }
  default: return scale * ((int)fz_u8(f) - 128) / 64.0;
  }
}

#endif
