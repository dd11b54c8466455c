// rosc_wire.h: a SkinMesh's length prefixes checked before anything is allocated.
#include "rosc_wire.h"

#include <cstdio>
#include <cstring>

namespace {

struct Reader {
  const uint8_t *p;
  size_t left, total;
  char *why;
  size_t why_size;

  // The next little-endian uint32 (ROS 1's wire format), or false if the message ends.
  bool u32(const char *field, uint32_t &v)
  {
    if (left < 4) {
      std::snprintf(why, why_size, "%s: the %zu-byte message ends inside it", field, total);
      return false;
    }
    v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    p += 4;
    left -= 4;
    return true;
  }

  // An array's (or string's) length prefix and its elements, skipped; false if the
  // prefix claims more bytes than are left (computed in 64 bits: no wrap).
  bool array(const char *field, uint64_t elem, uint64_t &n)
  {
    uint32_t len = 0;
    if (!u32(field, len)) return false;
    uint64_t bytes = (uint64_t)len * elem;
    if (bytes > left) {
      std::snprintf(why, why_size,
                    "%s: length %u (%llu bytes) but only %zu bytes are left in the %zu-byte "
                    "message", field, (unsigned)len, (unsigned long long)bytes, left, total);
      return false;
    }
    p += bytes;
    left -= (size_t)bytes;
    n = len;
    return true;
  }
};

bool over(char *why, size_t why_size, const char *field, uint64_t n, uint64_t per,
          uint64_t limit, const char *what, const char *param)
{
  if (limit == 0 || (n + per - 1) / per <= limit) return false;  // n < 2^32: no wrap
  std::snprintf(why, why_size, "%s: %llu values (%llu %s) exceed %s = %llu", field,
                (unsigned long long)n, (unsigned long long)((n + per - 1) / per), what, param,
                (unsigned long long)limit);
  return true;
}

}  // namespace

extern "C" int rosc_wire_skin_mesh_check(const uint8_t *buf, size_t len,
                                         const rosc_wire_limits *lim, rosc_wire_sizes *sizes,
                                         char *why, size_t why_size)
{
  char dummy[1];
  if (why == nullptr || why_size == 0) {
    why = dummy;
    why_size = sizeof dummy;
  }
  why[0] = '\0';
  if (buf == nullptr && len != 0) {
    std::snprintf(why, why_size, "no message");
    return 0;
  }
  Reader r{buf, len, len, why, why_size};
  uint32_t u = 0;
  rosc_wire_sizes s;
  std::memset(&s, 0, sizeof s);
  uint64_t mv = lim ? lim->max_vertices : 0, mt = lim ? lim->max_triangles : 0;
  if (!r.u32("header.seq", u) || !r.u32("header.stamp.sec", u) || !r.u32("header.stamp.nsec", u) ||
      !r.array("header.frame_id", 1, s.frame_id) || !r.u32("topology_id", u) ||
      !r.array("positions", 4, s.positions) ||
      over(why, why_size, "positions", s.positions, 3, mv, "vertices", "~max_vertices") ||
      !r.array("triangles", 4, s.triangles) ||
      over(why, why_size, "triangles", s.triangles, 3, mt, "triangles", "~max_triangles") ||
      !r.array("rigid_part", 4, s.rigid_part) ||
      over(why, why_size, "rigid_part", s.rigid_part, 1, mv, "vertices", "~max_vertices"))
    return 0;
  if (sizes) *sizes = s;
  return 1;
}
