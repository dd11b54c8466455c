/* libFuzzer harness: the first thing skin_sim_node does with a received
 * kinematic_mesh's bytes (src/stream/ss_wire.h): ss_wire_skin_mesh_check walks
 * its length prefixes before anything is allocated for them. Asserts
 * the documented results: a message passed has every array within its bytes
 * (their total plus the fixed fields is at most its size: the decoder then allocates
 * at most that) and within the limits; a message refused has a reason. The
 * limits come from the input's first bytes (0: none). */
#include <assert.h>
#include <string.h>

#include "fuzz_util.h"
#include "ss_wire.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fz f = {data, size};
  ss_wire_limits lim;
  lim.max_vertices = fz_u8(&f) & 1 ? 0 : fz_u32(&f) & 0xffff;
  lim.max_triangles = fz_u8(&f) & 1 ? 0 : fz_u32(&f) & 0xffff;
  ss_wire_sizes s;
  char why[320];
  memset(why, 'x', sizeof why);
  if (ss_wire_skin_mesh_check(f.p, f.n, &lim, &s, why, sizeof why)) {
    /* seq, sec, nsec, 4 length prefixes and topology_id: 32 bytes */
    assert(32 + s.frame_id + 4 * (s.positions + s.triangles + s.rigid_part) <= f.n);
    assert(!lim.max_vertices || (s.positions + 2) / 3 <= lim.max_vertices);
    assert(!lim.max_vertices || s.rigid_part <= lim.max_vertices);
    assert(!lim.max_triangles || (s.triangles + 2) / 3 <= lim.max_triangles);
  } else {
    assert(why[0] != '\0' && memchr(why, '\0', sizeof why) != NULL);
  }
  return 0;
}
