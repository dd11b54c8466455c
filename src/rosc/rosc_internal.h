// Internal to the rosc shim (rosc.cpp, rosc_srv.cpp), not part of its C API: the
// exception guard every extern "C" function runs its body in, and small helpers
// both files use.
#ifndef ROSC_INTERNAL_H
#define ROSC_INTERNAL_H

#include "rosc/rosc.h"

#include <ros/exceptions.h>

#include <cstring>
#include <new>
#include <string>

namespace rosc_internal {

// Logs "rosc: FUNC: WHAT" at ERROR (rosc.cpp; never throws out of a guard).
void log_internal(const char *func, const char *what);

// Runs body() and maps every exception to a status code (with one log line).
template <class F>
int guard(const char *func, F &&body) noexcept
{
  try {
    return body();
  } catch (const std::bad_alloc &) {
    return ROSC_E_NOMEM;
  } catch (const ros::InvalidNameException &e) {
    try { log_internal(func, e.what()); } catch (...) {}
    return ROSC_E_INVALID;
  } catch (const std::exception &e) {
    try { log_internal(func, e.what()); } catch (...) {}
    return ROSC_E_ROS;
  } catch (...) {
    try { log_internal(func, "unknown exception"); } catch (...) {}
    return ROSC_E_ROS;
  }
}

// Copies s into buf (NUL-terminated); ROSC_E_TRUNCATED if it had to be cut.
inline int copy_out(const std::string &s, char *buf, size_t buf_size)
{
  if (buf == nullptr || buf_size == 0) return ROSC_E_INVALID;
  if (s.size() + 1 > buf_size) {
    std::memcpy(buf, s.data(), buf_size - 1);
    buf[buf_size - 1] = '\0';
    return ROSC_E_TRUNCATED;
  }
  std::memcpy(buf, s.c_str(), s.size() + 1);
  return ROSC_OK;
}

inline bool valid_name(const char *name) { return name != nullptr && name[0] != '\0'; }

}  // namespace rosc_internal

#endif
