/* skin_sim stream: a received skin_sim/SkinMesh in ROS 1's wire format, sized before
 * anything is allocated for it (the node library, src/stream, not installed; no ROS
 * headers: tests/fuzz/fuzz_wire.c drives it as it is).
 *
 * roscpp's own deserialiser trusts each array's length prefix: it resizes the vector
 * to the prefix, then reads prefix x element-size bytes computed in 32 bits, so a
 * 56-byte message whose positions claim 0x40000002 floats allocates 4 GiB (the byte
 * count wraps to 8 and the read succeeds). ss_wire_skin_mesh_check walks the
 * message's length prefixes first, each against the bytes the message has left and
 * against the node's limits; skin_sim_node checks a message's bytes so before it
 * decodes them (ss_msg.h), whose allocations are then bounded by the message's size. */
#ifndef SKIN_SIM_SS_WIRE_H
#define SKIN_SIM_SS_WIRE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The sizes a node accepts (0: no limit beyond the message's own bytes). */
typedef struct ss_wire_limits {
  uint64_t max_vertices;  /* positions / 3, and rigid_part */
  uint64_t max_triangles; /* triangles / 3 */
} ss_wire_limits;

/* The element counts of a message that passed. */
typedef struct ss_wire_sizes {
  uint64_t frame_id, positions, triangles, rigid_part;
} ss_wire_sizes;

/* 1 if buf[0, len) is a SkinMesh whose every length prefix fits the bytes left and
 * the limits (sizes, may be NULL, filled in); else 0 with one sentence in why naming
 * the field and the sizes. lim may be NULL (no limits). */
int ss_wire_skin_mesh_check(const uint8_t *buf, size_t len, const ss_wire_limits *lim,
                            ss_wire_sizes *sizes, char *why, size_t why_size);

#ifdef __cplusplus
}
#endif
#endif
