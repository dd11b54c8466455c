// rosc messages (include/rosc/rosc.h: "messages", "publishers", "subscribers"): one path
// for every message type, moving serialized bytes. A type is one row of a table (its
// name, md5sum and definition, from the generated C++ message's traits); the shim has no
// code per field. A publisher is advertised with the row, so that the connection header
// says what a roscpp node's would (rosbag records it, rostopic and rviz read it); it
// publishes a Bytes, a message type whose serialisation is the bytes the node encoded.
// A subscriber asks roscpp for the row's type and takes each message through its own
// subscription callback helper, which keeps the bytes instead of deserialising them.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
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
#include <vector>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::need_node;
using rosc_internal::valid_name;

namespace {

// ------------------------------------------------------------------ the types served
struct Row {
  std::string datatype, md5, definition;
  bool has_header;  // roscpp then numbers header.seq per publisher, as for its own types
};

template <class M>
Row row()
{
  namespace mt = ros::message_traits;
  return {mt::datatype<M>(), mt::md5sum<M>(), mt::definition<M>(), mt::hasHeader<M>()};
}

// One row per message type a node uses (rosc.h: ROSC_MSG_TYPES).
const Row *find_row(const char *datatype)
{
  static const Row rows[] = {row<skin_sim::SkinMesh>(), row<skin_sim::SkinStats>(),
                             row<sensor_msgs::JointState>(), row<visualization_msgs::Marker>(),
                             row<std_msgs::String>(), row<dynamic_reconfigure::Config>(),
                             row<dynamic_reconfigure::ConfigDescription>()};
  if (datatype == nullptr) return nullptr;
  for (const Row &r : rows)
    if (r.datatype == datatype) return &r;
  return nullptr;
}

// A message given as its serialized bytes, under its row's type.
struct Bytes {
  const uint8_t *data;
  uint32_t len;
  const Row *row;
};

// A received message's bytes, copied out of roscpp's buffer (which it frees after
// deserialize()).
struct Received {
  std::vector<uint8_t> bytes;
};

}  // namespace

namespace ros {
namespace message_traits {
template <> struct IsMessage<Bytes> : TrueType {};
template <> struct MD5Sum<Bytes> {
  static const char *value(const Bytes &m) { return m.row->md5.c_str(); }
};
template <> struct DataType<Bytes> {
  static const char *value(const Bytes &m) { return m.row->datatype.c_str(); }
};
template <> struct Definition<Bytes> {
  static const char *value(const Bytes &m) { return m.row->definition.c_str(); }
};
}  // namespace message_traits
namespace serialization {
template <> struct Serializer<Bytes> {
  template <class Stream>
  static void write(Stream &stream, const Bytes &m)
  {
    if (m.len) std::memcpy(stream.advance(m.len), m.data, m.len);
  }
  static uint32_t serializedLength(const Bytes &m) { return m.len; }
};
}  // namespace serialization
}  // namespace ros

namespace {

// roscpp's subscription callback helper for every subscriber: deserialize() (in the
// spinning thread, just before call(); a message dropped from the queue never gets
// here) copies the bytes, call() hands them to the node. Its type is not the row's
// message type, so a publisher in the same process serialises for it too: every
// message takes this one path.
class Helper : public ros::SubscriptionCallbackHelper {
 public:
  explicit Helper(rosc_sub *s) : s_(s) {}
  ros::VoidConstPtr deserialize(const ros::SubscriptionCallbackHelperDeserializeParams &p) override
  {
    boost::shared_ptr<Received> r = boost::make_shared<Received>();
    r->bytes.assign(p.buffer, p.buffer + p.length);
    return r;
  }
  void call(ros::SubscriptionCallbackHelperCallParams &p) override
  {
    const Received *r = static_cast<const Received *>(p.event.getConstMessage().get());
    if (r != nullptr) s_->cb(r->bytes.data(), r->bytes.size(), s_->user);
  }
  const std::type_info &getTypeInfo() override { return typeid(Received); }
  bool isConst() override { return true; }
  bool hasHeader() override { return false; }

 private:
  rosc_sub *s_;
};

}  // namespace

// ================================================================== the C API
// ------------------------------------------------------------------ publishers
int rosc_pub_create(rosc_pub **out, const char *datatype, const char *topic, unsigned queue_size,
                    int latch)
{
  return guard(__func__, [&]() -> int {
    const Row *r = find_row(datatype);
    if (out == nullptr || r == nullptr || !valid_name(topic) || queue_size == 0)
      return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    std::unique_ptr<rosc_pub> p(new rosc_pub());
    p->row = r;
    ros::AdvertiseOptions ops(rosc_internal::resolve_private(topic), queue_size, r->md5,
                              r->datatype, r->definition);
    ops.latch = latch != 0;
    ops.has_header = r->has_header;
    p->pub = rosc_internal::node().advertise(ops);
    if (!p->pub) return ROSC_E_ROS;
    *out = p.release();
    return ROSC_OK;
  });
}

int rosc_publish(rosc_pub *pub, const uint8_t *bytes, size_t len)
{
  return guard(__func__, [&]() -> int {
    if (pub == nullptr || (bytes == nullptr && len != 0) || len >= 0xffffffffu)
      return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    // serialised before publish() returns (also for subscribers in this process)
    pub->pub.publish(Bytes{bytes, static_cast<uint32_t>(len), static_cast<const Row *>(pub->row)});
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
int rosc_subscribe(rosc_sub **out, const char *datatype, const char *topic, unsigned queue_size,
                   rosc_msg_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    const Row *r = find_row(datatype);
    if (out == nullptr || r == nullptr || cb == nullptr || !valid_name(topic) || queue_size == 0)
      return ROSC_E_INVALID;
    int st = need_node();
    if (st != ROSC_OK) return st;
    std::unique_ptr<rosc_sub> s(new rosc_sub());
    s->cb = cb;
    s->user = user;
    ros::SubscribeOptions ops(rosc_internal::resolve_private(topic), queue_size, r->md5,
                              r->datatype);
    ops.helper = boost::make_shared<Helper>(s.get());
    ops.transport_hints = ros::TransportHints().tcpNoDelay();
    s->sub = rosc_internal::node().subscribe(ops);
    if (!s->sub) return ROSC_E_ROS;
    s->topic = s->sub.getTopic();
    *out = s.release();
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
