/* libFuzzer harness: the stream planner as skin_sim_node drives it
 * (src/stream/ss_input.h): a sequence of arrivals (header.seq, stamp) goes
 * through ss_input_stream_arrive, and each one the node would step goes through
 * ss_input_plan_step with the skin's clock and the last step's periods carried
 * over, as the node carries them; sometimes the carried values are wild (the
 * node's state after any history). Asserts the documented results: a step has
 * periods >= 1, 1 <= substeps <= max_split, a finite dt > 0 and moves the skin's
 * clock forward; a first message, a gap or a jump back resets the clock to the
 * stamp; nothing else moves it. Found here: the last step's periods nudged by
 * one at INT_MAX overflowed int. */
#include <assert.h>
#include <limits.h>

#include "fuzz_util.h"
#include "ss_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fz f = {data, size};
  ss_input_stream s;
  memset(&s, 0, sizeof s);
  double max_gap = (fz_u8(&f) & 1) ? 0.5 : fz_double(&f, 1.0);
  double max_step = (fz_u8(&f) & 1) ? 0.05 : fz_double(&f, 0.05);
  int max_split = fz_int(&f, -2, 64);
  int have_skin = 0, prev_periods = 0;
  int64_t skin_ns = 0, stamp = (int64_t)fz_u64(&f);
  uint32_t seq = fz_u32(&f);
  for (int i = 0; i < 64 && f.n > 0; i++) {
    uint8_t op = fz_u8(&f);
    /* the next message: mostly a steady stream, sometimes lost, late, wild */
    switch (op & 7) {
    case 0: stamp = (int64_t)fz_u64(&f); break; /* any stamp */
    case 1: stamp = (int64_t)((uint64_t)stamp - fz_u32(&f)); break;
    case 2: seq += fz_u8(&f); /* fall through: messages lost */
    default: stamp = (int64_t)((uint64_t)stamp + 33333333u * (1u + (op >> 6))); break;
    }
    seq += 1u + ((op & 0x20) ? fz_u32(&f) : 0u);
    int kind = ss_input_stream_arrive(&s, seq, stamp, max_gap);
    assert(kind >= SS_TIME_FIRST && kind <= SS_TIME_GAP);
    assert(s.period_us >= 0);
    if (op & 0x08) continue; /* skipped by the node (a full inbox) */
    if (fz_u8(&f) == 0xff) { /* the node's state after any history */
      prev_periods = fz_int(&f, INT_MAX - 4, INT_MAX);
      skin_ns = (int64_t)fz_u64(&f);
    }
    int disc = (kind == SS_TIME_GAP || kind == SS_TIME_BACKWARDS) ? kind : 0;
    ss_input_plan p;
    int k = ss_input_plan_step(&s, have_skin, skin_ns, stamp, disc, prev_periods, max_step,
                               max_split, &p);
    assert(k == p.kind);
    switch (k) {
    case SS_TIME_STEP:
      assert(p.periods >= 1);
      assert(p.substeps >= 1 && p.substeps <= (max_split < 1 ? 1 : max_split));
      assert(isfinite(p.dt) && p.dt > 0.0);
      assert(p.skin_ns > skin_ns || skin_ns > ((int64_t)1 << 62));
      skin_ns = p.skin_ns;
      prev_periods = p.periods;
      break;
    case SS_TIME_SAME:
      assert(p.periods == 0 && p.dt == 0.0);
      break;
    default: /* first, gap, backwards: the skin is created on this message */
      assert(p.periods == 0 && p.dt == 0.0);
      have_skin = 1;
      skin_ns = p.skin_ns;
      prev_periods = 0;
      break;
    }
  }
  return 0;
}
