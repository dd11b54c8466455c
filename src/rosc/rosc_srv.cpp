// rosc services and diagnostics (include/rosc/rosc.h: "services", "diagnostics"):
// std_srvs/Empty servers and calls, and a diagnostic_updater::Updater behind a C
// handle. Kept apart from rosc.cpp (which holds the node, topics and logging); it uses
// only the node's public state (rosc_ok) and the exception guard of rosc_internal.h.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::valid_name;

// ------------------------------------------------------------------ services
struct rosc_srv {
  ros::ServiceServer srv;
  rosc_empty_cb cb = nullptr;
  void *user = nullptr;
  bool on_call(std_srvs::Empty::Request &, std_srvs::Empty::Response &) { return cb(user) == 0; }
};

int rosc_srv_empty(rosc_srv **out, const char *name, rosc_empty_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || !valid_name(name) || cb == nullptr) return ROSC_E_INVALID;
    if (!rosc_ok()) return ROSC_E_STATE;
    std::unique_ptr<rosc_srv> s(new rosc_srv());
    s->cb = cb;
    s->user = user;
    ros::NodeHandle nh;  // "~x" is resolved first: NodeHandle methods refuse private names
    s->srv = nh.advertiseService(ros::names::resolve(name), &rosc_srv::on_call, s.get());
    if (!s->srv) return ROSC_E_ROS;
    *out = s.release();
    return ROSC_OK;
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
struct rosc_diag {
  std::unique_ptr<diagnostic_updater::Updater> up;
  int level = ROSC_DIAG_STALE;
  std::string message = "no status yet";
  std::vector<std::pair<std::string, std::string>> kv;
  void run(diagnostic_updater::DiagnosticStatusWrapper &st)
  {
    st.summary(static_cast<unsigned char>(level), message);
    for (const auto &p : kv) st.add(p.first, p.second);
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
    *out = d.release();
    return ROSC_OK;
  });
}

int rosc_diag_period(rosc_diag *d, double *out)
{
  return guard(__func__, [&]() -> int {
    if (d == nullptr || out == nullptr) return ROSC_E_INVALID;
    *out = d->up->getPeriod();
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
    d->level = level;
    d->message = message;
    d->kv.clear();
    for (size_t i = 0; i < n; i++) d->kv.emplace_back(kv[i].key, kv[i].value);
    d->up->force_update();
    return ROSC_OK;
  });
}

int rosc_diag_destroy(rosc_diag *d)
{
  return guard(__func__, [&]() -> int {
    delete d;
    return ROSC_OK;
  });
}
