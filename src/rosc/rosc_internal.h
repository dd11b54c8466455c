// Internal to the rosc shim (src/rosc/*.cpp) and to its test helpers (tests/ros/rosc_test.cpp),
// not part of its C API: the exception guard every extern "C" function runs its body in, the
// node's state, and the handles behind rosc_pub and rosc_sub.
//
//   rosc.cpp        node life, spinning, time, rates, logging
//   rosc_param.cpp  parameters
//   rosc_msg.cpp    one publish / subscribe path for serialized messages of any type
//   rosc_srv.cpp    services (bytes, like topics) and diagnostics
#ifndef ROSC_INTERNAL_H
#define ROSC_INTERNAL_H

#include "rosc/rosc.h"

#include <ros/exceptions.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/subscriber.h>

#include <cstdarg>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

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

// "~x" resolved to the node's private name (NodeHandle methods refuse private names);
// other names as given (the NodeHandle resolves them).
std::string resolve_private(const char *name);

// ------------------------------------------------------------------ the node (rosc.cpp)
// ROSC_OK while the node runs (after rosc_init, before rosc_shutdown), else ROSC_E_STATE.
int need_node();
// ros::init has run (names can be resolved).
bool ros_initialized();
// The node's handle; only while need_node() is ROSC_OK.
ros::NodeHandle &node();

// One log line at level with the caller's place: what rosc_log_at and the test
// helpers' rosc_log run.
int vlog(int level, const char *file, int line, const char *func, const char *fmt, va_list ap);

// ------------------------------------------------------------------ parameters (rosc_param.cpp)
// A string parameter of any size, malloc'd (caller frees); ROSC_E_NOTFOUND if not set.
int param_get_string_alloc(const char *name, char **out, size_t *len);

}  // namespace rosc_internal

// The handles behind rosc_pub and rosc_sub (rosc_msg.cpp), read by the test helpers.
struct rosc_pub {
  const void *row;  // the type served (rosc_msg.cpp's table)
  ros::Publisher pub;
};

struct rosc_sub {
  ros::Subscriber sub;
  rosc_msg_cb cb = nullptr;
  void *user = nullptr;
  std::string topic;
};

#endif
