/* skin_sim stream: a SkinMesh's length prefixes checked before anything is allocated
 * (ss_wire.h). */
#include "ss_wire.h"

#include <stdio.h>
#include <string.h>

typedef struct reader {
  const uint8_t *p;
  size_t left, total;
  char *why;
  size_t why_size;
} reader;

/* The next little-endian uint32 (ROS 1's wire format), or 0 if the message ends. */
static int read_u32(reader *r, const char *field, uint32_t *v) {
  if (r->left < 4) {
    snprintf(r->why, r->why_size, "%s: the %zu-byte message ends inside it", field, r->total);
    return 0;
  }
  const uint8_t *p = r->p;
  *v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
  r->p += 4;
  r->left -= 4;
  return 1;
}

/* An array's (or string's) length prefix and its elements, skipped; 0 if the prefix
 * claims more bytes than are left (computed in 64 bits: no wrap). */
static int read_array(reader *r, const char *field, uint64_t elem, uint64_t *n) {
  uint32_t len = 0;
  if (!read_u32(r, field, &len)) return 0;
  uint64_t bytes = (uint64_t)len * elem;
  if (bytes > r->left) {
    snprintf(r->why, r->why_size,
             "%s: length %u (%llu bytes) but only %zu bytes are left in the %zu-byte message",
             field, (unsigned)len, (unsigned long long)bytes, r->left, r->total);
    return 0;
  }
  r->p += bytes;
  r->left -= (size_t)bytes;
  *n = len;
  return 1;
}

/* 1 (with why) if n values, per to an element, are more elements than limit. */
static int over(reader *r, const char *field, uint64_t n, uint64_t per, uint64_t limit,
                const char *what, const char *param) {
  if (limit == 0 || (n + per - 1) / per <= limit) return 0; /* n < 2^32: no wrap */
  snprintf(r->why, r->why_size, "%s: %llu values (%llu %s) exceed %s = %llu", field,
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
  if (buf == NULL && len != 0) {
    snprintf(why, why_size, "no message");
    return 0;
  }
  reader r = {buf, len, len, why, why_size};
  uint32_t u = 0;
  ss_wire_sizes s;
  memset(&s, 0, sizeof s);
  uint64_t mv = lim ? lim->max_vertices : 0, mt = lim ? lim->max_triangles : 0;
  if (!read_u32(&r, "header.seq", &u) || !read_u32(&r, "header.stamp.sec", &u) ||
      !read_u32(&r, "header.stamp.nsec", &u) || !read_array(&r, "header.frame_id", 1, &s.frame_id) ||
      !read_u32(&r, "topology_id", &u) || !read_array(&r, "positions", 4, &s.positions) ||
      over(&r, "positions", s.positions, 3, mv, "vertices", "~max_vertices") ||
      !read_array(&r, "triangles", 4, &s.triangles) ||
      over(&r, "triangles", s.triangles, 3, mt, "triangles", "~max_triangles") ||
      !read_array(&r, "rigid_part", 4, &s.rigid_part) ||
      over(&r, "rigid_part", s.rigid_part, 1, mv, "vertices", "~max_vertices"))
    return 0;
  if (sizes) *sizes = s;
  return 1;
}
