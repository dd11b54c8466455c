// rosc: the C API of include/rosc/rosc.h over roscpp (Debian 12's ROS 1).
//
// The only file of skin_sim that includes ROS headers. Each extern "C" function runs
// its body through guard(), which turns every C++ exception into a negative status
// (and one log line), so nothing unwinds into C. The shim keeps no copies of
// messages: a subscriber callback builds a C view over the received message (plus
// small per-subscriber scratch arrays reused from message to message) and a publisher
// copies a C view into one message object it reuses. roscpp serialises a message
// passed by const reference before publish() returns (also for subscribers in the
// same process), so reusing it is safe.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <ros/callback_queue.h>
#include <ros/console.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <skin_sim/SkinMesh.h>
#include <skin_sim/SkinStats.h>
#include <std_msgs/String.h>
#include <visualization_msgs/Marker.h>

#include <chrono>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <string>
#include <unordered_map>
#include <vector>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::valid_name;

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

int need_node()
{
  if (!g_node.started || g_node.shut_down || g_node.nh == nullptr) return ROSC_E_STATE;
  return ROSC_OK;
}

void atexit_cleanup() { rosc_shutdown(); }

// ------------------------------------------------------------------ logging
std::mutex g_log_mutex;
ros::console::LogLocation g_log_loc[5] = {};

struct Throttle {
  double last = 0.0;
  unsigned long long held = 0;
};
std::unordered_map<std::string, Throttle> g_throttle;  // under g_log_mutex
const size_t kMaxThrottleKeys = 4096;

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

double steady_seconds()
{
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

// Decides whether a throttled message prints now; *held receives how many messages
// of this key were held back since the last one printed.
bool throttle_pass(const char *key, double period_s, unsigned long long *held)
{
  std::lock_guard<std::mutex> lock(g_log_mutex);
  if (g_throttle.size() >= kMaxThrottleKeys) g_throttle.clear();  // bounded memory
  double now = steady_seconds();
  auto it = g_throttle.find(key);
  if (it == g_throttle.end()) {
    Throttle t;
    t.last = now;
    g_throttle.emplace(key, t);
    *held = 0;
    return true;
  }
  if (now - it->second.last < period_s) {
    ++it->second.held;
    return false;
  }
  *held = it->second.held;
  it->second.held = 0;
  it->second.last = now;
  return true;
}

int vlog(int level, const char *file, int line, const char *func, double period_s,
         const char *key, const char *fmt, va_list ap)
{
  if (level < ROSC_LOG_DEBUG || level > ROSC_LOG_FATAL || fmt == nullptr) return ROSC_E_INVALID;
  unsigned long long held = 0;
  if (period_s > 0.0 && !throttle_pass(key != nullptr ? key : fmt, period_s, &held))
    return ROSC_OK;
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
  if (held > 0) text += " (" + std::to_string(held) + " similar messages held back)";
  log_plain(level, file, line, func, text.c_str());
  return ROSC_OK;
}

// ------------------------------------------------------------------ message conversion
int header_to_ros(const rosc_header &c, std_msgs::Header &r)
{
  size_t n = strnlen(c.frame_id, ROSC_FRAME_ID_MAX);
  if (n == ROSC_FRAME_ID_MAX || c.stamp.nsec >= 1000000000u) return ROSC_E_INVALID;
  r.seq = c.seq;
  r.stamp.sec = c.stamp.sec;
  r.stamp.nsec = c.stamp.nsec;
  r.frame_id.assign(c.frame_id, n);
  return ROSC_OK;
}

bool header_from_ros(const std_msgs::Header &r, rosc_header &c)
{
  if (r.frame_id.size() >= ROSC_FRAME_ID_MAX) return false;
  c.seq = r.seq;
  c.stamp.sec = r.stamp.sec;
  c.stamp.nsec = r.stamp.nsec;
  std::memcpy(c.frame_id, r.frame_id.c_str(), r.frame_id.size() + 1);
  return true;
}

template <class T>
bool array_ok(const T *p, size_t n) { return p != nullptr || n == 0; }

template <class T, class V>
void assign_array(V &dst, const T *p, size_t n)
{
  if (n == 0) dst.clear();
  else dst.assign(p, p + n);
}

}  // namespace

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

struct rosc_pub {
  int type;
  ros::Publisher pub;
  skin_sim::SkinMesh mesh;
  skin_sim::SkinStats stats;
  sensor_msgs::JointState joints;
  visualization_msgs::Marker marker;
  std_msgs::String str;
};

struct rosc_sub {
  int type;
  ros::Subscriber sub;
  void *user = nullptr;
  rosc_skin_mesh_cb mesh_cb = nullptr;
  rosc_skin_stats_cb stats_cb = nullptr;
  rosc_joint_state_cb joints_cb = nullptr;
  rosc_marker_cb marker_cb = nullptr;
  rosc_string_cb string_cb = nullptr;
  uint64_t dropped = 0;
  std::string topic;
  // scratch reused across messages (views into them live only during a callback)
  std::vector<const char *> names;
  std::vector<float> points, colors;

  void drop(const char *why)
  {
    ++dropped;
    rosc_log_throttle(ROSC_LOG_ERROR, 5.0, topic.c_str(),
                      "rosc: dropped a message on %s: %s (%llu dropped so far)", topic.c_str(),
                      why, (unsigned long long)dropped);
  }

  void on_mesh(const skin_sim::SkinMesh &m)
  {
    rosc_skin_mesh c;
    if (!header_from_ros(m.header, c.header)) return drop("frame_id too long");
    c.topology_id = m.topology_id;
    c.positions = m.positions.data();
    c.n_positions = m.positions.size();
    c.triangles = m.triangles.data();
    c.n_triangles = m.triangles.size();
    mesh_cb(&c, user);
  }

  void on_stats(const skin_sim::SkinStats &m)
  {
    rosc_skin_stats c;
    if (!header_from_ros(m.header, c.header)) return drop("frame_id too long");
    c.total_ms = m.total_ms;
    c.walk_ms = m.walk_ms;
    c.assemble_ms = m.assemble_ms;
    c.solve_ms = m.solve_ms;
    c.iterations = m.iterations;
    c.residual = m.residual;
    c.substeps = m.substeps;
    c.anchors_at_boundary = m.anchors_at_boundary;
    c.anchors_at_crease = m.anchors_at_crease;
    c.max_slide = m.max_slide;
    c.inputs_rejected = m.inputs_rejected;
    c.inputs_dropped = m.inputs_dropped;
    c.resets = m.resets;
    c.inputs_skipped = m.inputs_skipped;
    c.failures = m.failures;
    c.latency_ms = m.latency_ms;
    stats_cb(&c, user);
  }

  void on_joints(const sensor_msgs::JointState &m)
  {
    rosc_joint_state c;
    if (!header_from_ros(m.header, c.header)) return drop("frame_id too long");
    names.resize(m.name.size());
    for (size_t i = 0; i < m.name.size(); ++i) names[i] = m.name[i].c_str();
    c.name = names.data();
    c.n_name = names.size();
    c.position = m.position.data();
    c.n_position = m.position.size();
    c.velocity = m.velocity.data();
    c.n_velocity = m.velocity.size();
    c.effort = m.effort.data();
    c.n_effort = m.effort.size();
    joints_cb(&c, user);
  }

  void on_marker(const visualization_msgs::Marker &m)
  {
    rosc_marker c;
    if (!header_from_ros(m.header, c.header)) return drop("frame_id too long");
    if (m.ns.size() >= ROSC_MARKER_NS_MAX) return drop("ns too long");
    std::memcpy(c.ns, m.ns.c_str(), m.ns.size() + 1);
    c.id = m.id;
    c.type = m.type;
    c.action = m.action;
    c.position[0] = m.pose.position.x;
    c.position[1] = m.pose.position.y;
    c.position[2] = m.pose.position.z;
    c.orientation[0] = m.pose.orientation.x;
    c.orientation[1] = m.pose.orientation.y;
    c.orientation[2] = m.pose.orientation.z;
    c.orientation[3] = m.pose.orientation.w;
    c.scale[0] = m.scale.x;
    c.scale[1] = m.scale.y;
    c.scale[2] = m.scale.z;
    c.color[0] = m.color.r;
    c.color[1] = m.color.g;
    c.color[2] = m.color.b;
    c.color[3] = m.color.a;
    c.lifetime.sec = m.lifetime.sec;
    c.lifetime.nsec = m.lifetime.nsec;
    c.frame_locked = m.frame_locked ? 1 : 0;
    points.resize(3 * m.points.size());
    for (size_t i = 0; i < m.points.size(); ++i) {
      points[3 * i + 0] = (float)m.points[i].x;
      points[3 * i + 1] = (float)m.points[i].y;
      points[3 * i + 2] = (float)m.points[i].z;
    }
    colors.resize(4 * m.colors.size());
    for (size_t i = 0; i < m.colors.size(); ++i) {
      colors[4 * i + 0] = m.colors[i].r;
      colors[4 * i + 1] = m.colors[i].g;
      colors[4 * i + 2] = m.colors[i].b;
      colors[4 * i + 3] = m.colors[i].a;
    }
    c.points = points.data();
    c.n_points = m.points.size();
    c.colors = colors.data();
    c.n_colors = m.colors.size();
    c.text = m.text.c_str();
    c.mesh_resource = m.mesh_resource.c_str();
    c.mesh_use_embedded_materials = m.mesh_use_embedded_materials ? 1 : 0;
    marker_cb(&c, user);
  }

  void on_string(const std_msgs::String &m)
  {
    rosc_string c;
    c.data = m.data.c_str();
    c.len = m.data.size();
    string_cb(&c, user);
  }
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

int rosc_resolve_name(const char *name, char *buf, size_t buf_size)
{
  return guard(__func__, [&]() -> int {
    if (!valid_name(name)) return ROSC_E_INVALID;
    if (!g_node.ros_initialized) return ROSC_E_STATE;
    return copy_out(ros::names::resolve(name), buf, buf_size);
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

int rosc_now_s(double *out)
{
  rosc_time t;
  if (out == nullptr) return ROSC_E_INVALID;
  int st = rosc_now(&t);
  if (st == ROSC_OK) *out = rosc_time_to_s(t);
  return st;
}

int rosc_wall_now(rosc_time *out)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    ros::WallTime t = ros::WallTime::now();
    out->sec = t.sec;
    out->nsec = t.nsec;
    return ROSC_OK;
  });
}

int rosc_wall_now_s(double *out)
{
  rosc_time t;
  if (out == nullptr) return ROSC_E_INVALID;
  int st = rosc_wall_now(&t);
  if (st == ROSC_OK) *out = rosc_time_to_s(t);
  return st;
}

int rosc_sleep(double seconds)
{
  return guard(__func__, [&]() -> int {
    int st = need_node();
    if (st != ROSC_OK) return st;
    if (!(seconds >= 0.0)) return ROSC_E_INVALID;
    return ros::Duration(seconds).sleep() ? ROSC_OK : ROSC_E_SHUTDOWN;
  });
}

int rosc_wall_sleep(double seconds)
{
  return guard(__func__, [&]() -> int {
    if (!(seconds >= 0.0)) return ROSC_E_INVALID;
    ros::WallDuration(seconds).sleep();
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

// ------------------------------------------------------------------ parameters
// Each getter asks the master once (an XmlRpcValue) and checks the type itself, so
// "not set" and "set with another type" are told apart.
namespace {
int param_fetch(const char *name, XmlRpc::XmlRpcValue &v, bool *found)
{
  if (!valid_name(name)) return ROSC_E_INVALID;
  int st = need_node();
  if (st != ROSC_OK) return st;
  *found = ros::param::get(name, v) && v.valid();
  return ROSC_OK;
}
}  // namespace

int rosc_param_get_string(const char *name, char *buf, size_t buf_size, const char *def,
                          int *was_set)
{
  return guard(__func__, [&]() -> int {
    if (buf == nullptr || buf_size == 0) return ROSC_E_INVALID;
    if (was_set != nullptr) *was_set = 0;
    int dst = copy_out(def != nullptr ? def : "", buf, buf_size);
    XmlRpc::XmlRpcValue v;
    bool found = false;
    int st = param_fetch(name, v, &found);
    if (st != ROSC_OK) return st;
    if (!found) return dst;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return ROSC_E_TYPE;
    if (was_set != nullptr) *was_set = 1;
    return copy_out(static_cast<std::string &>(v), buf, buf_size);
  });
}

int rosc_param_get_double(const char *name, double *out, double def, int *was_set)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    *out = def;
    if (was_set != nullptr) *was_set = 0;
    XmlRpc::XmlRpcValue v;
    bool found = false;
    int st = param_fetch(name, v, &found);
    if (st != ROSC_OK || !found) return st;
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) *out = static_cast<double>(v);
    else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) *out = static_cast<int>(v);
    else return ROSC_E_TYPE;
    if (was_set != nullptr) *was_set = 1;
    return ROSC_OK;
  });
}

int rosc_param_get_int(const char *name, int *out, int def, int *was_set)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    *out = def;
    if (was_set != nullptr) *was_set = 0;
    XmlRpc::XmlRpcValue v;
    bool found = false;
    int st = param_fetch(name, v, &found);
    if (st != ROSC_OK || !found) return st;
    if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) {
      *out = static_cast<int>(v);
    } else if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
      double d = static_cast<double>(v);
      if (!(d == std::floor(d)) || d < (double)INT_MIN || d > (double)INT_MAX) return ROSC_E_TYPE;
      *out = (int)d;
    } else {
      return ROSC_E_TYPE;
    }
    if (was_set != nullptr) *was_set = 1;
    return ROSC_OK;
  });
}

int rosc_param_get_bool(const char *name, int *out, int def, int *was_set)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    *out = def ? 1 : 0;
    if (was_set != nullptr) *was_set = 0;
    XmlRpc::XmlRpcValue v;
    bool found = false;
    int st = param_fetch(name, v, &found);
    if (st != ROSC_OK || !found) return st;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) return ROSC_E_TYPE;
    *out = static_cast<bool>(v) ? 1 : 0;
    if (was_set != nullptr) *was_set = 1;
    return ROSC_OK;
  });
}

int rosc_param_get_string_alloc(const char *name, char **out, size_t *len)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    XmlRpc::XmlRpcValue v;
    bool found = false;
    int st = param_fetch(name, v, &found);
    if (st != ROSC_OK) return st;
    if (!found) return ROSC_E_NOTFOUND;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return ROSC_E_TYPE;
    const std::string &s = static_cast<std::string &>(v);
    char *p = static_cast<char *>(std::malloc(s.size() + 1));
    if (p == nullptr) return ROSC_E_NOMEM;
    std::memcpy(p, s.c_str(), s.size() + 1);
    *out = p;
    if (len != nullptr) *len = s.size();
    return ROSC_OK;
  });
}

int rosc_param_has(const char *name, int *out)
{
  return guard(__func__, [&]() -> int {
    if (!valid_name(name) || out == nullptr) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    *out = ros::param::has(name) ? 1 : 0;
    return ROSC_OK;
  });
}

int rosc_param_explain(int status, const char *name, const char *expected, char *err,
                       size_t err_size)
{
  if (err == nullptr || err_size == 0) return status;
  err[0] = '\0';
  if (status == ROSC_OK) return status;
  const char *nm = name != nullptr ? name : "(null)";
  if (status != ROSC_E_TYPE) {
    std::snprintf(err, err_size, "parameter %s: %s", nm, rosc_strerror(status));
    return status;
  }
  std::string held = "a value of another type";
  guard(__func__, [&]() -> int {
    XmlRpc::XmlRpcValue v;
    bool found = false;
    if (param_fetch(nm, v, &found) != ROSC_OK || !found) return ROSC_OK;
    char buf[160];
    switch (v.getType()) {
      case XmlRpc::XmlRpcValue::TypeString: {
        std::string t = static_cast<std::string &>(v);
        if (t.size() > 60) t = t.substr(0, 60) + "...";
        held = "the string '" + t + "'";
        char *end = nullptr;
        const std::string &full = static_cast<std::string &>(v);
        std::strtod(full.c_str(), &end);
        if (!full.empty() && end != nullptr && *end == '\0' && expected != nullptr &&
            std::strstr(expected, "double") != nullptr)
          held += " (in a launch file, a number without a '.' such as 1e-4 stays a string: "
                  "write type=\"double\")";
        break;
      }
      case XmlRpc::XmlRpcValue::TypeDouble:
        std::snprintf(buf, sizeof buf, "the double %g", static_cast<double>(v));
        held = buf;
        break;
      case XmlRpc::XmlRpcValue::TypeInt:
        std::snprintf(buf, sizeof buf, "the int %d", static_cast<int>(v));
        held = buf;
        break;
      case XmlRpc::XmlRpcValue::TypeBoolean:
        held = static_cast<bool>(v) ? "the bool true" : "the bool false";
        break;
      case XmlRpc::XmlRpcValue::TypeArray: held = "a list"; break;
      case XmlRpc::XmlRpcValue::TypeStruct: held = "a dictionary"; break;
      default: break;
    }
    return ROSC_OK;
  });
  std::snprintf(err, err_size, "%s must be %s, but is %s", nm,
                expected != nullptr ? expected : "of another type", held.c_str());
  return status;
}

namespace {
template <class T>
int param_set(const char *func, const char *name, const T &value)
{
  return guard(func, [&]() -> int {
    if (!valid_name(name)) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    ros::param::set(name, value);
    return ROSC_OK;
  });
}
}  // namespace

int rosc_param_set_string(const char *name, const char *value)
{
  if (value == nullptr) return ROSC_E_INVALID;
  return guard(__func__, [&]() -> int { return param_set(__func__, name, std::string(value)); });
}
int rosc_param_set_double(const char *name, double value) { return param_set(__func__, name, value); }
int rosc_param_set_int(const char *name, int value) { return param_set(__func__, name, value); }
int rosc_param_set_bool(const char *name, int value) { return param_set(__func__, name, value != 0); }

int rosc_param_delete(const char *name)
{
  return guard(__func__, [&]() -> int {
    if (!valid_name(name)) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    ros::param::del(name);
    return ROSC_OK;
  });
}

int rosc_robot_description(char **out, size_t *len)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    std::string key;
    if (!ros::param::search("robot_description", key)) return ROSC_E_NOTFOUND;
    return rosc_param_get_string_alloc(key.c_str(), out, len);
  });
}

// ------------------------------------------------------------------ messages
int rosc_marker_init_triangle_list(rosc_marker *m)
{
  if (m == nullptr) return ROSC_E_INVALID;
  std::memset(m, 0, sizeof *m);
  m->type = ROSC_MARKER_TRIANGLE_LIST;
  m->action = ROSC_MARKER_ADD;
  m->orientation[3] = 1.0;
  m->scale[0] = m->scale[1] = m->scale[2] = 1.0;
  m->color[0] = m->color[1] = m->color[2] = m->color[3] = 1.0f;
  return ROSC_OK;
}

// ------------------------------------------------------------------ publishers
int rosc_pub_create(rosc_pub **out, int type, const char *topic, unsigned queue_size, int latch)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || !valid_name(topic) || queue_size == 0) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    std::unique_ptr<rosc_pub> p(new rosc_pub());
    p->type = type;
    ros::NodeHandle &nh = *g_node.nh;
    bool l = latch != 0;
    switch (type) {
    case ROSC_MSG_SKIN_MESH: p->pub = nh.advertise<skin_sim::SkinMesh>(topic, queue_size, l); break;
    case ROSC_MSG_SKIN_STATS: p->pub = nh.advertise<skin_sim::SkinStats>(topic, queue_size, l); break;
    case ROSC_MSG_JOINT_STATE:
      p->pub = nh.advertise<sensor_msgs::JointState>(topic, queue_size, l);
      break;
    case ROSC_MSG_MARKER:
      p->pub = nh.advertise<visualization_msgs::Marker>(topic, queue_size, l);
      break;
    case ROSC_MSG_STRING: p->pub = nh.advertise<std_msgs::String>(topic, queue_size, l); break;
    default: return ROSC_E_INVALID;
    }
    if (!p->pub) return ROSC_E_ROS;
    *out = p.release();
    return ROSC_OK;
  });
}

namespace {
int check_pub(rosc_pub *pub, const void *msg, int type)
{
  if (pub == nullptr || msg == nullptr || pub->type != type) return ROSC_E_INVALID;
  return need_node();
}
}  // namespace

int rosc_publish_skin_mesh(rosc_pub *pub, const rosc_skin_mesh *msg)
{
  return guard(__func__, [&]() -> int {
    int st = check_pub(pub, msg, ROSC_MSG_SKIN_MESH);
    if (st != ROSC_OK) return st;
    if (!array_ok(msg->positions, msg->n_positions) || !array_ok(msg->triangles, msg->n_triangles))
      return ROSC_E_INVALID;
    skin_sim::SkinMesh &m = pub->mesh;
    st = header_to_ros(msg->header, m.header);
    if (st != ROSC_OK) return st;
    m.topology_id = msg->topology_id;
    assign_array(m.positions, msg->positions, msg->n_positions);
    assign_array(m.triangles, msg->triangles, msg->n_triangles);
    pub->pub.publish(m);
    return ROSC_OK;
  });
}

int rosc_publish_skin_stats(rosc_pub *pub, const rosc_skin_stats *msg)
{
  return guard(__func__, [&]() -> int {
    int st = check_pub(pub, msg, ROSC_MSG_SKIN_STATS);
    if (st != ROSC_OK) return st;
    skin_sim::SkinStats &m = pub->stats;
    st = header_to_ros(msg->header, m.header);
    if (st != ROSC_OK) return st;
    m.total_ms = msg->total_ms;
    m.walk_ms = msg->walk_ms;
    m.assemble_ms = msg->assemble_ms;
    m.solve_ms = msg->solve_ms;
    m.iterations = msg->iterations;
    m.residual = msg->residual;
    m.substeps = msg->substeps;
    m.anchors_at_boundary = msg->anchors_at_boundary;
    m.anchors_at_crease = msg->anchors_at_crease;
    m.max_slide = msg->max_slide;
    m.inputs_rejected = msg->inputs_rejected;
    m.inputs_dropped = msg->inputs_dropped;
    m.resets = msg->resets;
    m.inputs_skipped = msg->inputs_skipped;
    m.failures = msg->failures;
    m.latency_ms = msg->latency_ms;
    pub->pub.publish(m);
    return ROSC_OK;
  });
}

int rosc_publish_joint_state(rosc_pub *pub, const rosc_joint_state *msg)
{
  return guard(__func__, [&]() -> int {
    int st = check_pub(pub, msg, ROSC_MSG_JOINT_STATE);
    if (st != ROSC_OK) return st;
    if (!array_ok(msg->name, msg->n_name) || !array_ok(msg->position, msg->n_position) ||
        !array_ok(msg->velocity, msg->n_velocity) || !array_ok(msg->effort, msg->n_effort))
      return ROSC_E_INVALID;
    for (size_t i = 0; i < msg->n_name; ++i)
      if (msg->name[i] == nullptr) return ROSC_E_INVALID;
    sensor_msgs::JointState &m = pub->joints;
    st = header_to_ros(msg->header, m.header);
    if (st != ROSC_OK) return st;
    m.name.resize(msg->n_name);
    for (size_t i = 0; i < msg->n_name; ++i) m.name[i].assign(msg->name[i]);
    assign_array(m.position, msg->position, msg->n_position);
    assign_array(m.velocity, msg->velocity, msg->n_velocity);
    assign_array(m.effort, msg->effort, msg->n_effort);
    pub->pub.publish(m);
    return ROSC_OK;
  });
}

int rosc_publish_marker(rosc_pub *pub, const rosc_marker *msg)
{
  return guard(__func__, [&]() -> int {
    int st = check_pub(pub, msg, ROSC_MSG_MARKER);
    if (st != ROSC_OK) return st;
    if (!array_ok(msg->points, msg->n_points) || !array_ok(msg->colors, msg->n_colors))
      return ROSC_E_INVALID;
    size_t ns_len = strnlen(msg->ns, ROSC_MARKER_NS_MAX);
    if (ns_len == ROSC_MARKER_NS_MAX) return ROSC_E_INVALID;
    visualization_msgs::Marker &m = pub->marker;
    st = header_to_ros(msg->header, m.header);
    if (st != ROSC_OK) return st;
    m.ns.assign(msg->ns, ns_len);
    m.id = msg->id;
    m.type = msg->type;
    m.action = msg->action;
    m.pose.position.x = msg->position[0];
    m.pose.position.y = msg->position[1];
    m.pose.position.z = msg->position[2];
    m.pose.orientation.x = msg->orientation[0];
    m.pose.orientation.y = msg->orientation[1];
    m.pose.orientation.z = msg->orientation[2];
    m.pose.orientation.w = msg->orientation[3];
    m.scale.x = msg->scale[0];
    m.scale.y = msg->scale[1];
    m.scale.z = msg->scale[2];
    m.color.r = msg->color[0];
    m.color.g = msg->color[1];
    m.color.b = msg->color[2];
    m.color.a = msg->color[3];
    m.lifetime.sec = msg->lifetime.sec;
    m.lifetime.nsec = msg->lifetime.nsec;
    m.frame_locked = msg->frame_locked != 0;
    m.points.resize(msg->n_points);
    for (size_t i = 0; i < msg->n_points; ++i) {
      m.points[i].x = msg->points[3 * i + 0];
      m.points[i].y = msg->points[3 * i + 1];
      m.points[i].z = msg->points[3 * i + 2];
    }
    m.colors.resize(msg->n_colors);
    for (size_t i = 0; i < msg->n_colors; ++i) {
      m.colors[i].r = msg->colors[4 * i + 0];
      m.colors[i].g = msg->colors[4 * i + 1];
      m.colors[i].b = msg->colors[4 * i + 2];
      m.colors[i].a = msg->colors[4 * i + 3];
    }
    m.text.assign(msg->text != nullptr ? msg->text : "");
    m.mesh_resource.assign(msg->mesh_resource != nullptr ? msg->mesh_resource : "");
    m.mesh_use_embedded_materials = msg->mesh_use_embedded_materials != 0;
    pub->pub.publish(m);
    return ROSC_OK;
  });
}

int rosc_publish_string(rosc_pub *pub, const char *text)
{
  return guard(__func__, [&]() -> int {
    int st = check_pub(pub, text, ROSC_MSG_STRING);
    if (st != ROSC_OK) return st;
    pub->str.data.assign(text);
    pub->pub.publish(pub->str);
    return ROSC_OK;
  });
}

int rosc_pub_num_subscribers(const rosc_pub *pub, unsigned *out)
{
  return guard(__func__, [&]() -> int {
    if (pub == nullptr || out == nullptr) return ROSC_E_INVALID;
    *out = pub->pub.getNumSubscribers();
    return ROSC_OK;
  });
}

int rosc_pub_topic(const rosc_pub *pub, char *buf, size_t buf_size)
{
  return guard(__func__, [&]() -> int {
    if (pub == nullptr) return ROSC_E_INVALID;
    return copy_out(pub->pub.getTopic(), buf, buf_size);
  });
}

int rosc_pub_destroy(rosc_pub *pub)
{
  return guard(__func__, [&]() -> int {
    if (pub == nullptr) return ROSC_OK;
    pub->pub.shutdown();
    delete pub;
    return ROSC_OK;
  });
}

// ------------------------------------------------------------------ subscribers
namespace {
template <class M>
int subscribe(rosc_sub **out, rosc_msg_type type, const char *topic, unsigned queue_size,
              void *user, void (rosc_sub::*handler)(const M &), std::unique_ptr<rosc_sub> s)
{
  if (out == nullptr || !valid_name(topic) || queue_size == 0) return ROSC_E_INVALID;
  int st = need_node();
  if (st != ROSC_OK) return st;
  s->type = type;
  s->user = user;
  rosc_sub *raw = s.get();
  boost::function<void(const boost::shared_ptr<M const> &)> cb =
      [raw, handler](const boost::shared_ptr<M const> &m) { (raw->*handler)(*m); };
  s->sub = g_node.nh->subscribe<M>(topic, queue_size, cb, ros::VoidConstPtr(),
                                   ros::TransportHints().tcpNoDelay());
  if (!s->sub) return ROSC_E_ROS;
  s->topic = s->sub.getTopic();
  *out = s.release();
  return ROSC_OK;
}
}  // namespace

int rosc_sub_skin_mesh(rosc_sub **out, const char *topic, unsigned queue_size,
                       rosc_skin_mesh_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    if (cb == nullptr) return ROSC_E_INVALID;
    std::unique_ptr<rosc_sub> s(new rosc_sub());
    s->mesh_cb = cb;
    return subscribe<skin_sim::SkinMesh>(out, ROSC_MSG_SKIN_MESH, topic, queue_size, user,
                                         &rosc_sub::on_mesh, std::move(s));
  });
}

int rosc_sub_skin_stats(rosc_sub **out, const char *topic, unsigned queue_size,
                        rosc_skin_stats_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    if (cb == nullptr) return ROSC_E_INVALID;
    std::unique_ptr<rosc_sub> s(new rosc_sub());
    s->stats_cb = cb;
    return subscribe<skin_sim::SkinStats>(out, ROSC_MSG_SKIN_STATS, topic, queue_size, user,
                                          &rosc_sub::on_stats, std::move(s));
  });
}

int rosc_sub_joint_state(rosc_sub **out, const char *topic, unsigned queue_size,
                         rosc_joint_state_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    if (cb == nullptr) return ROSC_E_INVALID;
    std::unique_ptr<rosc_sub> s(new rosc_sub());
    s->joints_cb = cb;
    return subscribe<sensor_msgs::JointState>(out, ROSC_MSG_JOINT_STATE, topic, queue_size, user,
                                              &rosc_sub::on_joints, std::move(s));
  });
}

int rosc_sub_marker(rosc_sub **out, const char *topic, unsigned queue_size, rosc_marker_cb cb,
                    void *user)
{
  return guard(__func__, [&]() -> int {
    if (cb == nullptr) return ROSC_E_INVALID;
    std::unique_ptr<rosc_sub> s(new rosc_sub());
    s->marker_cb = cb;
    return subscribe<visualization_msgs::Marker>(out, ROSC_MSG_MARKER, topic, queue_size, user,
                                                 &rosc_sub::on_marker, std::move(s));
  });
}

int rosc_sub_string(rosc_sub **out, const char *topic, unsigned queue_size, rosc_string_cb cb,
                    void *user)
{
  return guard(__func__, [&]() -> int {
    if (cb == nullptr) return ROSC_E_INVALID;
    std::unique_ptr<rosc_sub> s(new rosc_sub());
    s->string_cb = cb;
    return subscribe<std_msgs::String>(out, ROSC_MSG_STRING, topic, queue_size, user,
                                       &rosc_sub::on_string, std::move(s));
  });
}

int rosc_sub_num_publishers(const rosc_sub *sub, unsigned *out)
{
  return guard(__func__, [&]() -> int {
    if (sub == nullptr || out == nullptr) return ROSC_E_INVALID;
    *out = sub->sub.getNumPublishers();
    return ROSC_OK;
  });
}

int rosc_sub_num_dropped(const rosc_sub *sub, uint64_t *out)
{
  return guard(__func__, [&]() -> int {
    if (sub == nullptr || out == nullptr) return ROSC_E_INVALID;
    *out = sub->dropped;
    return ROSC_OK;
  });
}

int rosc_sub_topic(const rosc_sub *sub, char *buf, size_t buf_size)
{
  return guard(__func__, [&]() -> int {
    if (sub == nullptr) return ROSC_E_INVALID;
    return copy_out(sub->topic, buf, buf_size);
  });
}

int rosc_sub_destroy(rosc_sub *sub)
{
  return guard(__func__, [&]() -> int {
    if (sub == nullptr) return ROSC_OK;
    sub->sub.shutdown();  // also removes its callbacks still waiting in the queue
    delete sub;
    return ROSC_OK;
  });
}

// ------------------------------------------------------------------ logging
int rosc_log(int level, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int st = guard(__func__, [&]() -> int { return vlog(level, nullptr, 0, "", 0.0, nullptr, fmt, ap); });
  va_end(ap);
  return st;
}

int rosc_log_throttle(int level, double period_s, const char *key, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int st = guard(__func__, [&]() -> int {
    if (!(period_s >= 0.0)) return ROSC_E_INVALID;
    return vlog(level, nullptr, 0, "", period_s, key, fmt, ap);
  });
  va_end(ap);
  return st;
}

int rosc_log_at(int level, const char *file, int line, const char *func, double period_s,
                const char *key, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int st = guard(__func__, [&]() -> int { return vlog(level, file, line, func, period_s, key, fmt, ap); });
  va_end(ap);
  return st;
}
