// rosc services and diagnostics (include/rosc/rosc.h: "services", "diagnostics"):
// services served as bytes (one row per service type, from the generated C++ service's
// traits), and a diagnostic_updater::Updater behind a C handle. Kept apart from rosc.cpp (which holds the node, topics and logging); it uses
// only the node's public state (rosc_ok) and the exception guard of rosc_internal.h.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/advertise_service_options.h>
#include <ros/service_callback_helper.h>
#include <std_srvs/Empty.h>

#include <boost/make_shared.hpp>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <vector>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::valid_name;

// ------------------------------------------------------------------ services
namespace {

// A service type served as bytes: one row per type a node serves (rosc.h: ROSC_SRV_TYPES).
struct SrvRow {
  std::string datatype, md5, req_datatype, res_datatype;
};

template <class S>
SrvRow srv_row()
{
  return {ros::service_traits::datatype<S>(), ros::service_traits::md5sum<S>(),
          ros::message_traits::datatype<typename S::Request>(),
          ros::message_traits::datatype<typename S::Response>()};
}

const SrvRow *find_srv(const char *datatype)
{
  static const SrvRow rows[] = {srv_row<std_srvs::Empty>(),
                                srv_row<dynamic_reconfigure::Reconfigure>()};
  if (datatype == nullptr) return nullptr;
  for (const SrvRow &r : rows)
    if (r.datatype == datatype) return &r;
  return nullptr;
}

}  // namespace

struct rosc_srv {
  ros::ServiceServer srv;
  rosc_srv_cb cb = nullptr;
  rosc_empty_cb empty_cb = nullptr;  // rosc_srv_empty's: no request or response to pass
  void *user = nullptr;
};

namespace {

// roscpp's service callback helper for every service: the request's bytes go to the
// node, its response's bytes back, framed as roscpp frames them (ok byte, then the
// length on success).
class SrvHelper : public ros::ServiceCallbackHelper {
 public:
  explicit SrvHelper(rosc_srv *s) : s_(s) {}
  bool call(ros::ServiceCallbackHelperCallParams &p) override
  {
    const uint8_t *req = p.request.message_start;
    size_t len = p.request.num_bytes - static_cast<size_t>(req - p.request.buf.get());
    const uint8_t *resp = nullptr;
    size_t n = 0;
    bool ok = s_->empty_cb != nullptr ? s_->empty_cb(s_->user) == 0
                                      : s_->cb(req, len, &resp, &n, s_->user) == 0;
    if (resp == nullptr) n = 0;
    size_t head = ok ? 5 : 1;
    p.response.num_bytes = static_cast<uint32_t>(head + n);
    p.response.buf.reset(new uint8_t[head + n]);
    p.response.buf[0] = ok ? 1 : 0;
    uint32_t n32 = static_cast<uint32_t>(n);
    if (ok) std::memcpy(p.response.buf.get() + 1, &n32, 4);
    if (n) std::memcpy(p.response.buf.get() + head, resp, n);
    return ok;
  }

 private:
  rosc_srv *s_;
};

int srv_advertise(rosc_srv **out, const char *name, const SrvRow *row, std::unique_ptr<rosc_srv> s)
{
  if (!rosc_ok()) return ROSC_E_STATE;
  ros::AdvertiseServiceOptions ops;
  ops.service = ros::names::resolve(name);  // NodeHandle methods refuse private names
  ops.md5sum = row->md5;
  ops.datatype = row->datatype;
  ops.req_datatype = row->req_datatype;
  ops.res_datatype = row->res_datatype;
  ops.helper = boost::make_shared<SrvHelper>(s.get());
  s->srv = rosc_internal::node().advertiseService(ops);
  if (!s->srv) return ROSC_E_ROS;
  *out = s.release();
  return ROSC_OK;
}

}  // namespace

int rosc_srv_create(rosc_srv **out, const char *name, const char *srv_type, rosc_srv_cb cb,
                    void *user)
{
  return guard(__func__, [&]() -> int {
    const SrvRow *row = find_srv(srv_type);
    if (out == nullptr || !valid_name(name) || row == nullptr || cb == nullptr)
      return ROSC_E_INVALID;
    std::unique_ptr<rosc_srv> s(new rosc_srv());
    s->cb = cb;
    s->user = user;
    return srv_advertise(out, name, row, std::move(s));
  });
}

int rosc_srv_empty(rosc_srv **out, const char *name, rosc_empty_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || !valid_name(name) || cb == nullptr) return ROSC_E_INVALID;
    std::unique_ptr<rosc_srv> s(new rosc_srv());
    s->empty_cb = cb;
    s->user = user;
    return srv_advertise(out, name, find_srv("std_srvs/Empty"), std::move(s));
  });
}

int rosc_srv_name(const rosc_srv *srv, char *buf, size_t buf_size)
{
  return guard(__func__, [&]() -> int {
    if (srv == nullptr) return ROSC_E_INVALID;
    return copy_out(srv->srv.getService(), buf, buf_size);
  });
}

int rosc_srv_destroy(rosc_srv *srv)
{
  return guard(__func__, [&]() -> int {
    if (srv == nullptr) return ROSC_OK;
    srv->srv.shutdown();
    delete srv;
    return ROSC_OK;
  });
}

// ------------------------------------------------------------------ diagnostics
// The status is published by the spinning thread (rosc_diag_update) and, while that
// thread is busy with one long piece of work (rosc_diag_busy), by a thread of the
// handle's own: every diagnostic period without an update it publishes the last
// status's key/value pairs with the level and message the node's callback gives.
// The mutex guards the status, the busy state and the Updater (not thread-safe).
struct rosc_diag {
  std::unique_ptr<diagnostic_updater::Updater> up;
  int level = ROSC_DIAG_STALE;
  std::string message = "no status yet";
  std::vector<std::pair<std::string, std::string>> kv;
  // the watchdog thread's view
  std::mutex mu;
  std::condition_variable wake;
  std::thread watch;
  bool stop = false;
  double period_s = 1.0;          // the last period read by the spinning thread
  double last_pub_s = 0.0;        // wall time of the last status published
  rosc_diag_busy_cb busy_cb = nullptr;  // NULL: not busy
  void *busy_user = nullptr;
  double busy_since_s = 0.0;
  // what run() publishes (the last status, or the busy one)
  int pub_level = ROSC_DIAG_STALE;
  std::string pub_message = "no status yet";
  std::string pub_extra_key, pub_extra_value;

  void run(diagnostic_updater::DiagnosticStatusWrapper &st)
  {
    st.summary(static_cast<unsigned char>(pub_level), pub_message);
    for (const auto &p : kv) st.add(p.first, p.second);
    if (!pub_extra_key.empty()) st.add(pub_extra_key, pub_extra_value);
  }

  static double now_s() { return ros::WallTime::now().toSec(); }

  // The watchdog: wakes a few times a period; publishes the busy status when the
  // spinning thread has been busy and silent for a period.
  void watch_loop()
  {
    std::unique_lock<std::mutex> lock(mu);
    while (!stop) {
      double period = period_s > 0.0 ? period_s : 1.0;
      wake.wait_for(lock, std::chrono::duration<double>(period / 4.0));
      if (stop) break;
      if (busy_cb == nullptr) continue;
      double now = now_s();
      if (now - busy_since_s < period || now - last_pub_s < period) continue;
      rosc_diag_busy_status b;
      std::memset(&b, 0, sizeof b);
      b.level = ROSC_DIAG_WARN;
      busy_cb(now - busy_since_s, level, &b, busy_user);
      b.message[sizeof b.message - 1] = b.key[sizeof b.key - 1] = b.value[sizeof b.value - 1] = '\0';
      pub_level = b.level;
      pub_message = b.message;
      pub_extra_key = b.key;
      pub_extra_value = b.value;
      try {
        if (ros::ok()) up->force_update();
      } catch (...) {
      }
      last_pub_s = now;
    }
  }
};

int rosc_diag_create(rosc_diag **out, const char *hardware_id, const char *task)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || hardware_id == nullptr || !valid_name(task)) return ROSC_E_INVALID;
    if (!rosc_ok()) return ROSC_E_STATE;
    std::unique_ptr<rosc_diag> d(new rosc_diag());
    d->up.reset(new diagnostic_updater::Updater());
    d->up->setHardwareID(hardware_id[0] ? hardware_id : "none");
    d->up->add(task, d.get(), &rosc_diag::run);
    d->period_s = d->up->getPeriod();
    d->last_pub_s = rosc_diag::now_s();
    rosc_diag *raw = d.get();
    d->watch = std::thread([raw] { raw->watch_loop(); });
    *out = d.release();
    return ROSC_OK;
  });
}

int rosc_diag_period(rosc_diag *d, double *out)
{
  return guard(__func__, [&]() -> int {
    if (d == nullptr || out == nullptr) return ROSC_E_INVALID;
    std::lock_guard<std::mutex> lock(d->mu);
    *out = d->period_s = d->up->getPeriod();
    return ROSC_OK;
  });
}

int rosc_diag_update(rosc_diag *d, int level, const char *message, const rosc_kv *kv, size_t n)
{
  return guard(__func__, [&]() -> int {
    if (d == nullptr || message == nullptr || (kv == nullptr && n != 0)) return ROSC_E_INVALID;
    if (level < ROSC_DIAG_OK || level > ROSC_DIAG_STALE) return ROSC_E_INVALID;
    for (size_t i = 0; i < n; i++)
      if (kv[i].key == nullptr || kv[i].value == nullptr) return ROSC_E_INVALID;
    if (!rosc_ok()) return ROSC_E_STATE;
    std::lock_guard<std::mutex> lock(d->mu);
    d->level = d->pub_level = level;
    d->message = d->pub_message = message;
    d->pub_extra_key.clear();
    d->kv.clear();
    for (size_t i = 0; i < n; i++) d->kv.emplace_back(kv[i].key, kv[i].value);
    d->up->force_update();
    d->last_pub_s = rosc_diag::now_s();
    return ROSC_OK;
  });
}

int rosc_diag_busy(rosc_diag *d, rosc_diag_busy_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    if (d == nullptr) return ROSC_E_INVALID;
    std::lock_guard<std::mutex> lock(d->mu);
    d->busy_cb = cb;
    d->busy_user = user;
    d->busy_since_s = rosc_diag::now_s();
    return ROSC_OK;
  });
}

int rosc_diag_destroy(rosc_diag *d)
{
  return guard(__func__, [&]() -> int {
    if (d == nullptr) return ROSC_OK;
    {
      std::lock_guard<std::mutex> lock(d->mu);
      d->stop = true;
    }
    d->wake.notify_all();
    if (d->watch.joinable()) d->watch.join();
    delete d;
    return ROSC_OK;
  });
}
