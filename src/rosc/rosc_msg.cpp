// rosc messages (include/rosc/rosc.h: "messages", "publishers", "subscribers"): the C views
// of the message types the nodes use, converted to and from their ROS messages, and one
// generic path for publishing and subscribing any of them.
//
// Each message type has a traits struct Msg<C> (C the view): its ROS message, its callback
// type, to_ros (view -> message, checking the view) and from_ros (message -> view, or the
// reason it is dropped). rosc_publish() and rosc_subscribe() dispatch on the rosc_msg_type
// once and run the same code for every type. The shim keeps no copies of messages: a subscriber
// callback builds a C view over the received message (plus small per-subscriber scratch
// arrays reused from message to message) and a publisher copies a C view into one message
// object it reuses. roscpp serialises a message passed by const reference before publish()
// returns (also for subscribers in the same process), so reusing it is safe.
// Every subscriber takes its messages as bytes; a subscriber's byte check (a node's:
// skin_sim_node sizes a SkinMesh with src/stream/ss_wire.h) sees them before roscpp's
// deserialiser allocates anything.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <ros/ros.h>
#include <ros/subscribe_options.h>
#include <ros/subscription_callback_helper.h>
#include <sensor_msgs/JointState.h>
#include <skin_sim/SkinMesh.h>
#include <skin_sim/SkinStats.h>
#include <std_msgs/String.h>
#include <visualization_msgs/Marker.h>

#include <boost/make_shared.hpp>

#include <cstring>
#include <memory>
#include <new>
#include <string>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::need_node;
using rosc_internal::valid_name;

namespace {

// ------------------------------------------------------------------ conversions
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

// A view's (pointer, count) pair over a received message's array.
template <class V, class T>
void view_array(const V &src, const T *&p, size_t &n)
{
  p = src.data();
  n = src.size();
}

const char *const kLongFrameId = "frame_id too long";

template <class C> struct Msg;

template <> struct Msg<rosc_skin_mesh> {
  using Ros = skin_sim::SkinMesh;
  static int to_ros(const rosc_skin_mesh &c, Ros &m)
  {
    if (!array_ok(c.positions, c.n_positions) || !array_ok(c.triangles, c.n_triangles) ||
        !array_ok(c.rigid_part, c.n_rigid_part))
      return ROSC_E_INVALID;
    int st = header_to_ros(c.header, m.header);
    if (st != ROSC_OK) return st;
    m.topology_id = c.topology_id;
    assign_array(m.positions, c.positions, c.n_positions);
    assign_array(m.triangles, c.triangles, c.n_triangles);
    assign_array(m.rigid_part, c.rigid_part, c.n_rigid_part);
    return ROSC_OK;
  }
  static const char *from_ros(const Ros &m, rosc_skin_mesh &c, rosc_sub &)
  {
    if (!header_from_ros(m.header, c.header)) return kLongFrameId;
    c.topology_id = m.topology_id;
    view_array(m.positions, c.positions, c.n_positions);
    view_array(m.triangles, c.triangles, c.n_triangles);
    view_array(m.rigid_part, c.rigid_part, c.n_rigid_part);
    return nullptr;
  }
};

// SkinStats: the same fields on both sides.
template <class A, class B>
void copy_stats(const A &a, B &b)
{
#define ROSC_COPY_(type, name) b.name = a.name;
  ROSC_SKIN_STATS_FIELDS(ROSC_COPY_)
#undef ROSC_COPY_
}

template <> struct Msg<rosc_skin_stats> {
  using Ros = skin_sim::SkinStats;
  static int to_ros(const rosc_skin_stats &c, Ros &m)
  {
    int st = header_to_ros(c.header, m.header);
    if (st != ROSC_OK) return st;
    copy_stats(c, m);
    return ROSC_OK;
  }
  static const char *from_ros(const Ros &m, rosc_skin_stats &c, rosc_sub &)
  {
    if (!header_from_ros(m.header, c.header)) return kLongFrameId;
    copy_stats(m, c);
    return nullptr;
  }
};

template <> struct Msg<rosc_joint_state> {
  using Ros = sensor_msgs::JointState;
  static int to_ros(const rosc_joint_state &c, Ros &m)
  {
    if (!array_ok(c.name, c.n_name) || !array_ok(c.position, c.n_position) ||
        !array_ok(c.velocity, c.n_velocity) || !array_ok(c.effort, c.n_effort))
      return ROSC_E_INVALID;
    for (size_t i = 0; i < c.n_name; ++i)
      if (c.name[i] == nullptr) return ROSC_E_INVALID;
    int st = header_to_ros(c.header, m.header);
    if (st != ROSC_OK) return st;
    m.name.resize(c.n_name);
    for (size_t i = 0; i < c.n_name; ++i) m.name[i].assign(c.name[i]);
    assign_array(m.position, c.position, c.n_position);
    assign_array(m.velocity, c.velocity, c.n_velocity);
    assign_array(m.effort, c.effort, c.n_effort);
    return ROSC_OK;
  }
  static const char *from_ros(const Ros &m, rosc_joint_state &c, rosc_sub &s)
  {
    if (!header_from_ros(m.header, c.header)) return kLongFrameId;
    s.names.resize(m.name.size());
    for (size_t i = 0; i < m.name.size(); ++i) s.names[i] = m.name[i].c_str();
    view_array(s.names, c.name, c.n_name);
    view_array(m.position, c.position, c.n_position);
    view_array(m.velocity, c.velocity, c.n_velocity);
    view_array(m.effort, c.effort, c.n_effort);
    return nullptr;
  }
};

template <> struct Msg<rosc_marker> {
  using Ros = visualization_msgs::Marker;
  static int to_ros(const rosc_marker &c, Ros &m)
  {
    if (!array_ok(c.points, c.n_points) || !array_ok(c.colors, c.n_colors))
      return ROSC_E_INVALID;
    size_t ns_len = strnlen(c.ns, ROSC_MARKER_NS_MAX);
    if (ns_len == ROSC_MARKER_NS_MAX) return ROSC_E_INVALID;
    int st = header_to_ros(c.header, m.header);
    if (st != ROSC_OK) return st;
    m.ns.assign(c.ns, ns_len);
    m.id = c.id;
    m.type = c.type;
    m.action = c.action;
    m.pose.position.x = c.position[0];
    m.pose.position.y = c.position[1];
    m.pose.position.z = c.position[2];
    m.pose.orientation.x = c.orientation[0];
    m.pose.orientation.y = c.orientation[1];
    m.pose.orientation.z = c.orientation[2];
    m.pose.orientation.w = c.orientation[3];
    m.scale.x = c.scale[0];
    m.scale.y = c.scale[1];
    m.scale.z = c.scale[2];
    m.color.r = c.color[0];
    m.color.g = c.color[1];
    m.color.b = c.color[2];
    m.color.a = c.color[3];
    m.lifetime.sec = c.lifetime.sec;
    m.lifetime.nsec = c.lifetime.nsec;
    m.frame_locked = c.frame_locked != 0;
    m.points.resize(c.n_points);
    for (size_t i = 0; i < c.n_points; ++i) {
      m.points[i].x = c.points[3 * i + 0];
      m.points[i].y = c.points[3 * i + 1];
      m.points[i].z = c.points[3 * i + 2];
    }
    m.colors.resize(c.n_colors);
    for (size_t i = 0; i < c.n_colors; ++i) {
      m.colors[i].r = c.colors[4 * i + 0];
      m.colors[i].g = c.colors[4 * i + 1];
      m.colors[i].b = c.colors[4 * i + 2];
      m.colors[i].a = c.colors[4 * i + 3];
    }
    m.text.assign(c.text != nullptr ? c.text : "");
    m.mesh_resource.assign(c.mesh_resource != nullptr ? c.mesh_resource : "");
    m.mesh_use_embedded_materials = c.mesh_use_embedded_materials != 0;
    return ROSC_OK;
  }
  static const char *from_ros(const Ros &m, rosc_marker &c, rosc_sub &s)
  {
    if (!header_from_ros(m.header, c.header)) return kLongFrameId;
    if (m.ns.size() >= ROSC_MARKER_NS_MAX) return "ns too long";
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
    s.points.resize(3 * m.points.size());
    for (size_t i = 0; i < m.points.size(); ++i) {
      s.points[3 * i + 0] = (float)m.points[i].x;
      s.points[3 * i + 1] = (float)m.points[i].y;
      s.points[3 * i + 2] = (float)m.points[i].z;
    }
    s.colors.resize(4 * m.colors.size());
    for (size_t i = 0; i < m.colors.size(); ++i) {
      s.colors[4 * i + 0] = m.colors[i].r;
      s.colors[4 * i + 1] = m.colors[i].g;
      s.colors[4 * i + 2] = m.colors[i].b;
      s.colors[4 * i + 3] = m.colors[i].a;
    }
    c.points = s.points.data();
    c.n_points = m.points.size();
    c.colors = s.colors.data();
    c.n_colors = m.colors.size();
    c.text = m.text.c_str();
    c.mesh_resource = m.mesh_resource.c_str();
    c.mesh_use_embedded_materials = m.mesh_use_embedded_materials ? 1 : 0;
    return nullptr;
  }
};

template <> struct Msg<rosc_string> {
  using Ros = std_msgs::String;
  static int to_ros(const rosc_string &c, Ros &m)
  {
    if (c.data == nullptr) return ROSC_E_INVALID;
    m.data.assign(c.data, c.len);
    return ROSC_OK;
  }
  static const char *from_ros(const Ros &m, rosc_string &c, rosc_sub &)
  {
    c.data = m.data.c_str();
    c.len = m.data.size();
    return nullptr;
  }
};

// Calls f(Msg<C>()) for the view type C of message type `type`.
template <class F>
int dispatch(int type, F &&f)
{
  switch (type) {
  case ROSC_MSG_SKIN_MESH: return f(Msg<rosc_skin_mesh>());
  case ROSC_MSG_SKIN_STATS: return f(Msg<rosc_skin_stats>());
  case ROSC_MSG_JOINT_STATE: return f(Msg<rosc_joint_state>());
  case ROSC_MSG_MARKER: return f(Msg<rosc_marker>());
  case ROSC_MSG_STRING: return f(Msg<rosc_string>());
  default: return ROSC_E_INVALID;
  }
}

// The view type of a traits struct: Msg<C> -> C.
template <class T> struct ViewOf;
template <class C> struct ViewOf<Msg<C>> { using type = C; };

// One received message, deserialised unless the subscriber's byte check refused it.
template <class M>
struct Received {
  M msg;
  bool refused = false;
};

// roscpp's subscription callback helper for every subscriber, of traits T: it gets the
// message's bytes (roscpp deserialises lazily, in the spinning thread, just before the
// callback; a message dropped from the queue is never deserialised), runs the
// subscriber's byte check on them, and deserialises only what it passes; call() converts
// the message to its C view. Its type is not T::Ros, so a publisher in the same process
// serialises for it too: every message takes this one path.
template <class T>
class Helper : public ros::SubscriptionCallbackHelper {
 public:
  using M = typename T::Ros;
  explicit Helper(rosc_sub *s) : s_(s) {}
  ros::VoidConstPtr deserialize(const ros::SubscriptionCallbackHelperDeserializeParams &p) override
  {
    boost::shared_ptr<Received<M>> r = boost::make_shared<Received<M>>();
    if (s_->check != nullptr && !s_->check(p.buffer, p.length, s_->user)) {
      r->refused = true;
      return r;
    }
    ros::serialization::IStream stream(p.buffer, p.length);
    ros::serialization::deserialize(stream, r->msg);
    return r;
  }
  void call(ros::SubscriptionCallbackHelperCallParams &p) override
  {
    const Received<M> *r = static_cast<const Received<M> *>(p.event.getConstMessage().get());
    if (r == nullptr || r->refused) return;
    typename ViewOf<T>::type c;
    const char *why = T::from_ros(r->msg, c, *s_);
    if (why != nullptr) return s_->drop(why);
    s_->cb(&c, s_->user);
  }
  const std::type_info &getTypeInfo() override { return typeid(Received<M>); }
  bool isConst() override { return true; }
  bool hasHeader() override { return false; }

 private:
  rosc_sub *s_;
};

}  // namespace

void rosc_sub::drop(const char *why)
{
  ++dropped;
  rosc_log_at(ROSC_LOG_ERROR, nullptr, 0, "", 5.0, topic.c_str(),
              "rosc: dropped a message on %s: %s (%llu dropped so far)", topic.c_str(), why,
              (unsigned long long)dropped);
}

// ================================================================== the C API
// ------------------------------------------------------------------ publishers
int rosc_pub_create(rosc_pub **out, int type, const char *topic, unsigned queue_size, int latch)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || !valid_name(topic) || queue_size == 0) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    std::unique_ptr<rosc_pub> p(new rosc_pub());
    p->type = type;
    st = dispatch(type, [&](auto traits) -> int {
      using M = typename decltype(traits)::Ros;
      p->msg = std::make_shared<M>();
      p->pub = rosc_internal::node().advertise<M>(topic, queue_size, latch != 0);
      return ROSC_OK;
    });
    if (st != ROSC_OK) return st;
    if (!p->pub) return ROSC_E_ROS;
    *out = p.release();
    return ROSC_OK;
  });
}

int rosc_publish(rosc_pub *pub, int type, const void *msg)
{
  return guard(__func__, [&]() -> int {
    if (pub == nullptr || msg == nullptr || pub->type != type) return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    return dispatch(type, [&](auto traits) -> int {
      using T = decltype(traits);
      auto &m = *static_cast<typename T::Ros *>(pub->msg.get());
      int s = T::to_ros(*static_cast<const typename ViewOf<T>::type *>(msg), m);
      if (s != ROSC_OK) return s;
      pub->pub.publish(m);
      return ROSC_OK;
    });
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
int rosc_subscribe(rosc_sub **out, int type, const char *topic, unsigned queue_size,
                   rosc_msg_cb cb, rosc_bytes_cb check, void *user)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || cb == nullptr || !valid_name(topic) || queue_size == 0)
      return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    return dispatch(type, [&](auto traits) -> int {
      using T = decltype(traits);
      using M = typename T::Ros;
      std::unique_ptr<rosc_sub> s(new rosc_sub());
      s->type = type;
      s->cb = cb;
      s->check = check;
      s->user = user;
      ros::SubscribeOptions ops(topic, queue_size, ros::message_traits::md5sum<M>(),
                                ros::message_traits::datatype<M>());
      ops.helper = boost::make_shared<Helper<T>>(s.get());
      ops.transport_hints = ros::TransportHints().tcpNoDelay();
      s->sub = rosc_internal::node().subscribe(ops);
      if (!s->sub) return ROSC_E_ROS;
      s->topic = s->sub.getTopic();
      *out = s.release();
      return ROSC_OK;
    });
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
