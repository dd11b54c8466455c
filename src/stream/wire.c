/* skin_sim stream: a SkinMesh's length prefixes checked before anything is allocated
 * (ss_wire.h), by the decoder's sizing walk (ss_msg.h), then against the limits. */
#include "ss_wire.h"

#include "ss_msg.h"

#include <stdio.h>
#include <string.h>

/* 1 (with why) if n values, per to an element, are more elements than limit. */
static int over(char *why, size_t why_size, const char *field, uint64_t n, uint64_t per,
                uint64_t limit, const char *what, const char *param) {
  if (limit == 0 || (n + per - 1) / per <= limit) return 0; /* n < 2^32: no wrap */
  snprintf(why, why_size, "%s: %llu values (%llu %s) exceed %s = %llu", field,
           (unsigned long long)n, (unsigned long long)((n + per - 1) / per), what, param,
           (unsigned long long)limit);
  return 1;
}

int ss_wire_skin_mesh_check(const uint8_t *buf, size_t len, const ss_wire_limits *lim,
                            ss_wire_sizes *sizes, char *why, size_t why_size) {
  char dummy[1];
  if (why == NULL || why_size == 0) {
    why = dummy;
    why_size = sizeof dummy;
  }
  why[0] = '\0';
  ss_msg_skin_mesh m;
  if (buf == NULL && len != 0) {
    snprintf(why, why_size, "no message");
    return 0;
  }
  if (ss_msg_decode(SS_MSG_SKIN_MESH, buf, len, &m, NULL, why, why_size) != SS_MSG_OK) return 0;
  uint64_t mv = lim ? lim->max_vertices : 0, mt = lim ? lim->max_triangles : 0;
  if (over(why, why_size, "positions", m.n_positions, 3, mv, "vertices", "~max_vertices") ||
      over(why, why_size, "triangles", m.n_triangles, 3, mt, "triangles", "~max_triangles") ||
      over(why, why_size, "rigid_part", m.n_rigid_part, 1, mv, "vertices", "~max_vertices"))
    return 0;
  if (sizes) {
    sizes->frame_id = strlen(m.header.frame_id);
    sizes->positions = m.n_positions;
    sizes->triangles = m.n_triangles;
    sizes->rigid_part = m.n_rigid_part;
  }
  return 1;
}
