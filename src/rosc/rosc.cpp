// rosc: the C API of include/rosc/rosc.h over roscpp (Debian 12's ROS 1): the node's life,
// spinning, time, rates and logging. Parameters are in rosc_param.cpp, messages (publishers
// and subscribers) in rosc_msg.cpp, services and diagnostics in rosc_srv.cpp; what they share
// is in rosc_internal.h.
//
// The only code of skin_sim that includes ROS headers is src/rosc. Each extern "C" function
// runs its body through guard(), which turns every C++ exception into a negative status
// (and one log line), so nothing unwinds into C.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <ros/callback_queue.h>
#include <ros/console.h>
#include <ros/ros.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <string>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::need_node;
using rosc_internal::valid_name;
using rosc_internal::vlog;

namespace {

// ------------------------------------------------------------------ state
struct NodeState {
  bool ros_initialized = false;  // ros::init ran
  bool started = false;          // the node handle exists (the node runs)
  bool shut_down = false;
  ros::NodeHandle *nh = nullptr;
};
NodeState g_node;

void log_plain(int level, const char *file, int line, const char *func, const char *msg);

void atexit_cleanup() { rosc_shutdown(); }

// ------------------------------------------------------------------ logging
std::mutex g_log_mutex;
ros::console::LogLocation g_log_loc[5] = {};

ros::console::Level to_ros_level(int level)
{
  switch (level) {
  case ROSC_LOG_DEBUG: return ros::console::levels::Debug;
  case ROSC_LOG_INFO: return ros::console::levels::Info;
  case ROSC_LOG_WARN: return ros::console::levels::Warn;
  case ROSC_LOG_ERROR: return ros::console::levels::Error;
  default: return ros::console::levels::Fatal;
  }
}

// Sends one finished line to rosconsole under the logger "ros.skin_sim", the way the
// ROS_LOG macros do but with the C caller's file, line and function.
void log_plain(int level, const char *file, int line, const char *func, const char *msg)
{
  ROSCONSOLE_AUTOINIT;
  ros::console::LogLocation *loc = &g_log_loc[level];
  {
    std::lock_guard<std::mutex> lock(g_log_mutex);
    if (!loc->initialized_)
      ros::console::initializeLogLocation(loc, ROSCONSOLE_DEFAULT_NAME, to_ros_level(level));
  }
  if (!loc->logger_enabled_) return;
  ros::console::print(nullptr, loc->logger_, loc->level_, file != nullptr ? file : "?", line,
                      func != nullptr ? func : "?", "%s", msg);
}

}  // namespace

int rosc_internal::vlog(int level, const char *file, int line, const char *func, const char *fmt,
                        va_list ap)
{
  if (level < ROSC_LOG_DEBUG || level > ROSC_LOG_FATAL || fmt == nullptr) return ROSC_E_INVALID;
  char small[512];
  va_list ap2;
  va_copy(ap2, ap);
  int n = std::vsnprintf(small, sizeof small, fmt, ap2);
  va_end(ap2);
  if (n < 0) return ROSC_E_INVALID;
  std::string text;
  if ((size_t)n < sizeof small) {
    text.assign(small, (size_t)n);
  } else {
    text.resize((size_t)n + 1);
    std::vsnprintf(&text[0], text.size(), fmt, ap);
    text.resize((size_t)n);
  }
  log_plain(level, file, line, func, text.c_str());
  return ROSC_OK;
}

int rosc_internal::need_node()
{
  if (!g_node.started || g_node.shut_down || g_node.nh == nullptr) return ROSC_E_STATE;
  return ROSC_OK;
}

bool rosc_internal::ros_initialized() { return g_node.ros_initialized; }

std::string rosc_internal::resolve_private(const char *name)
{
  return name[0] == '~' ? ros::names::resolve(name) : std::string(name);
}

ros::NodeHandle &rosc_internal::node() { return *g_node.nh; }

void rosc_internal::log_internal(const char *func, const char *what)
{
  std::string text = std::string("rosc: ") + func + ": " + what;
  log_plain(ROSC_LOG_ERROR, __FILE__, __LINE__, func, text.c_str());
}

// ------------------------------------------------------------------ opaque handles
struct rosc_rate {
  explicit rosc_rate(double hz) : rate(hz) {}
  ros::Rate rate;
};

// ================================================================== the C API
// (C linkage comes from the declarations in rosc.h.)

const char *rosc_strerror(int status)
{
  switch (status) {
  case ROSC_OK: return "ok";
  case ROSC_E_INVALID: return "invalid argument";
  case ROSC_E_STATE: return "node not running (not initialised, or shut down)";
  case ROSC_E_ROS: return "roscpp error";
  case ROSC_E_NOMEM: return "out of memory";
  case ROSC_E_TYPE: return "parameter has another type";
  case ROSC_E_TRUNCATED: return "buffer too small";
  case ROSC_E_TIMEOUT: return "the ROS master did not answer in time";
  case ROSC_E_NOTFOUND: return "parameter not set";
  case ROSC_E_SHUTDOWN: return "node shutting down";
  default: return "unknown status";
  }
}

// ------------------------------------------------------------------ node life
int rosc_init(int *argc, char **argv, const char *node_name, unsigned options,
              double master_timeout_s)
{
  return guard(__func__, [&]() -> int {
    if (argc == nullptr || *argc < 0 || (*argc > 0 && argv == nullptr) || !valid_name(node_name))
      return ROSC_E_INVALID;
    if (g_node.started || g_node.shut_down) return ROSC_E_STATE;
    if (!g_node.ros_initialized) {
      uint32_t o = 0;
      if (options & ROSC_INIT_ANONYMOUS) o |= ros::init_options::AnonymousName;
      if (options & ROSC_INIT_NO_SIGINT) o |= ros::init_options::NoSigintHandler;
      if (options & ROSC_INIT_NO_ROSOUT) o |= ros::init_options::NoRosout;
      ros::init(*argc, argv, node_name, o);
      g_node.ros_initialized = true;
    }
    if (master_timeout_s >= 0.0) {
      ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(master_timeout_s);
      while (!ros::master::check()) {
        if (ros::WallTime::now() >= deadline) return ROSC_E_TIMEOUT;
        ros::WallDuration(0.05).sleep();
      }
    }
    g_node.nh = new ros::NodeHandle();  // starts the node: XML-RPC server, /rosout, clock
    g_node.started = true;
    // Registered once the node runs, so it runs at exit before roscpp's own atexit
    // handler and before the destructors of roscpp's singletons (all created by now):
    // stopping the node later throws boost::lock_error from a destroyed mutex.
    std::atexit(atexit_cleanup);
    return ROSC_OK;
  });
}

int rosc_ok(void)
{
  return guard(__func__, []() -> int {
    return (need_node() == ROSC_OK && ros::ok()) ? 1 : 0;
  });
}

int rosc_shutdown(void)
{
  return guard(__func__, []() -> int {
    if (!g_node.ros_initialized) return ROSC_E_STATE;
    if (g_node.shut_down) return ROSC_OK;
    g_node.shut_down = true;
    delete g_node.nh;
    g_node.nh = nullptr;
    ros::shutdown();
    return ROSC_OK;
  });
}

int rosc_node_name(char *buf, size_t buf_size)
{
  return guard(__func__, [&]() -> int {
    if (!g_node.ros_initialized) return ROSC_E_STATE;
    return copy_out(ros::this_node::getName(), buf, buf_size);
  });
}

// ------------------------------------------------------------------ spinning
int rosc_spin_once(double timeout_s)
{
  return guard(__func__, [&]() -> int {
    int st = need_node();
    if (st != ROSC_OK) return st;
    if (!ros::ok()) return ROSC_E_SHUTDOWN;
    if (!(timeout_s >= 0.0)) timeout_s = 0.0;
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(timeout_s));
    return ROSC_OK;
  });
}

int rosc_spin_for(double duration_s)
{
  return guard(__func__, [&]() -> int {
    int st = need_node();
    if (st != ROSC_OK) return st;
    bool forever = !(duration_s >= 0.0);
    ros::WallTime deadline = ros::WallTime::now();
    if (!forever) deadline += ros::WallDuration(duration_s);
    while (ros::ok()) {
      double left = 0.1;
      if (!forever) {
        left = (deadline - ros::WallTime::now()).toSec();
        if (left <= 0.0) return ROSC_OK;
        if (left > 0.1) left = 0.1;
      }
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(left));
    }
    return ROSC_E_SHUTDOWN;
  });
}

// ------------------------------------------------------------------ time
int rosc_now(rosc_time *out)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    ros::Time t = ros::Time::now();
    out->sec = t.sec;
    out->nsec = t.nsec;
    return ROSC_OK;
  });
}

namespace {
void wall_now(rosc_time *out)
{
  ros::WallTime t = ros::WallTime::now();
  out->sec = t.sec;
  out->nsec = t.nsec;
}
}  // namespace

int rosc_wall_now_s(double *out)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    rosc_time t;
    wall_now(&t);
    *out = rosc_time_to_s(t);
    return ROSC_OK;
  });
}

int rosc_rate_create(rosc_rate **out, double hz)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || !(hz > 0.0) || !std::isfinite(hz)) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    *out = new rosc_rate(hz);
    return ROSC_OK;
  });
}

int rosc_rate_sleep(rosc_rate *rate, int *met)
{
  return guard(__func__, [&]() -> int {
    if (rate == nullptr) return ROSC_E_INVALID;
    bool on_time = rate->rate.sleep();
    if (met != nullptr) *met = on_time ? 1 : 0;
    return ros::ok() ? ROSC_OK : ROSC_E_SHUTDOWN;
  });
}

int rosc_rate_reset(rosc_rate *rate)
{
  return guard(__func__, [&]() -> int {
    if (rate == nullptr) return ROSC_E_INVALID;
    rate->rate.reset();
    return ROSC_OK;
  });
}

int rosc_rate_destroy(rosc_rate *rate)
{
  return guard(__func__, [&]() -> int {
    delete rate;
    return ROSC_OK;
  });
}

// ------------------------------------------------------------------ logging
int rosc_log_at(int level, const char *file, int line, const char *func, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int st = guard(__func__, [&]() -> int { return vlog(level, file, line, func, fmt, ap); });
  va_end(ap);
  return st;
}
