// rosc for tests (tests/ros/rosc_test.h): the calls only the ROS test helpers make, on the
// shim's inside (src/rosc/rosc_internal.h): each runs in the same exception guard, checks
// the same node state, on the same handles as the nodes' calls in src/rosc.
#include "rosc_test.h"
#include "rosc_internal.h"

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <ros/ros.h>
#include <ros/topic_manager.h>
#include <sensor_msgs/JointState.h>
#include <skin_sim/SkinMesh.h>
#include <skin_sim/SkinStats.h>
#include <std_msgs/String.h>
#include <std_srvs/Empty.h>
#include <visualization_msgs/Marker.h>

#include <cmath>
#include <cstdarg>
#include <cstring>
#include <string>
#include <vector>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::need_node;
using rosc_internal::valid_name;

// ------------------------------------------------------------------ node and time
int rosc_resolve_name(const char *name, char *buf, size_t buf_size)
{
  return guard(__func__, [&]() -> int {
    if (!valid_name(name)) return ROSC_E_INVALID;
    if (!rosc_internal::ros_initialized()) return ROSC_E_STATE;
    return copy_out(ros::names::resolve(name), buf, buf_size);
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

// ------------------------------------------------------------------ parameters
int rosc_param_get_string_alloc(const char *name, char **out, size_t *len)
{
  return rosc_internal::param_get_string_alloc(name, out, len);
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

// ------------------------------------------------------------------ topics
int rosc_pub_topic(const rosc_pub *pub, char *buf, size_t buf_size)
{
  return guard(__func__, [&]() -> int {
    if (pub == nullptr) return ROSC_E_INVALID;
    return copy_out(pub->pub.getTopic(), buf, buf_size);
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

namespace {
template <class M>
int reserialize(const uint8_t *buf, size_t len, int *same)
{
  M m;
  ros::serialization::IStream in(const_cast<uint8_t *>(buf), static_cast<uint32_t>(len));
  ros::serialization::deserialize(in, m);
  std::vector<uint8_t> out(ros::serialization::serializationLength(m));
  ros::serialization::OStream os(out.data(), static_cast<uint32_t>(out.size()));
  ros::serialization::serialize(os, m);
  *same = in.getLength() == 0 && out.size() == len && std::memcmp(out.data(), buf, len) == 0;
  return ROSC_OK;
}
}  // namespace

int rosc_test_reserialize(const char *datatype, const uint8_t *buf, size_t len, int *same)
{
  return guard(__func__, [&]() -> int {
    if (datatype == nullptr || (buf == nullptr && len) || same == nullptr) return ROSC_E_INVALID;
    std::string t = datatype;
    if (t == "skin_sim/SkinMesh") return reserialize<skin_sim::SkinMesh>(buf, len, same);
    if (t == "skin_sim/SkinStats") return reserialize<skin_sim::SkinStats>(buf, len, same);
    if (t == "sensor_msgs/JointState") return reserialize<sensor_msgs::JointState>(buf, len, same);
    if (t == "visualization_msgs/Marker")
      return reserialize<visualization_msgs::Marker>(buf, len, same);
    if (t == "std_msgs/String") return reserialize<std_msgs::String>(buf, len, same);
    if (t == "dynamic_reconfigure/Config")
      return reserialize<dynamic_reconfigure::Config>(buf, len, same);
    if (t == "dynamic_reconfigure/ConfigDescription")
      return reserialize<dynamic_reconfigure::ConfigDescription>(buf, len, same);
    return ROSC_E_INVALID;
  });
}

int rosc_test_wait_rosout(double timeout_s)
{
  return guard(__func__, [&]() -> int {
    int st = need_node();
    if (st != ROSC_OK) return st;
    ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s > 0 ? timeout_s : 0);
    while (ros::TopicManager::instance()->getNumSubscribers("/rosout") == 0) {
      if (ros::WallTime::now() >= deadline) return ROSC_E_TIMEOUT;
      ros::WallDuration(0.02).sleep();
    }
    return ROSC_OK;
  });
}

// ------------------------------------------------------------------ services
int rosc_call_empty(const char *name, double timeout_s)
{
  return guard(__func__, [&]() -> int {
    if (!valid_name(name)) return ROSC_E_INVALID;
    if (!rosc_ok()) return ROSC_E_STATE;
    std::string resolved = ros::names::resolve(name);
    if (!ros::service::waitForService(resolved, ros::Duration(timeout_s > 0 ? timeout_s : 0.001)))
      return ROSC_E_TIMEOUT;
    std_srvs::Empty e;
    return ros::service::call(resolved, e) ? ROSC_OK : ROSC_E_ROS;
  });
}

// ------------------------------------------------------------------ logging
int rosc_log(int level, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int st = guard(__func__, [&]() -> int {
    return rosc_internal::vlog(level, nullptr, 0, "", fmt, ap);
  });
  va_end(ap);
  return st;
}
