// rosc dynamic_reconfigure (include/rosc/rosc.h: "dynamic_reconfigure"): the protocol of
// dynamic_reconfigure's server spoken from a table the caller gives at run time, so
// that a node's settings are described once (its own table) and no .cfg file copies
// them: ~set_parameters (dynamic_reconfigure/Reconfigure), latched
// ~parameter_descriptions (ConfigDescription) and ~parameter_updates (Config), and the
// values in force mirrored on the parameter server as ~NAME, as dynamic_reconfigure's
// C++ server does. One group, "Default" (id 0), holds every parameter. Requests are
// served inside rosc_spin_* (single-threaded), like every other callback of the shim.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using rosc_internal::guard;
using rosc_internal::valid_name;

namespace {

struct param {
  std::string name, description, edit_method;
  int type = ROSC_DR_DOUBLE;
  unsigned level = 0;
  double min = 0, max = 0;
};

const char *type_name(int type)
{
  switch (type) {
  case ROSC_DR_INT: return "int";
  case ROSC_DR_BOOL: return "bool";
  case ROSC_DR_STR: return "str";
  default: return "double";
  }
}

// dynamic_reconfigure's edit_method for an enum of strings: a Python dict literal that
// its client and rqt_reconfigure evaluate.
std::string enum_edit_method(const char *const *choices, const std::string &what)
{
  std::string s = "{'enum': [";
  for (int k = 0; choices[k] != nullptr; k++) {
    std::string c = choices[k];
    if (k) s += ", ";
    s += "{'name': '" + c + "', 'type': 'str', 'value': '" + c + "', 'srcline': 0, " +
         "'srcfile': '', 'description': '" + c + "', 'ctype': 'std::string', " +
         "'cconsttype': 'const char * const'}";
  }
  s += "], 'enum_description': '" + what + "'}";
  return s;
}

int32_t to_int(double v)
{
  if (!(v == v)) return 0;
  if (v >= static_cast<double>(INT_MAX)) return INT_MAX;
  if (v <= static_cast<double>(INT_MIN)) return INT_MIN;
  return static_cast<int32_t>(v);
}

bool same(int type, const rosc_dr_value &a, const rosc_dr_value &b)
{
  if (type == ROSC_DR_STR) return std::strcmp(a.str, b.str) == 0;
  return a.num == b.num || (a.num != a.num && b.num != b.num);
}

}  // namespace

struct rosc_dynreconf {
  std::vector<param> params;
  std::vector<rosc_dr_value> dflt, cur;
  rosc_dr_cb cb = nullptr;
  void *user = nullptr;
  ros::ServiceServer srv;
  ros::Publisher pub_descr, pub_update;

  dynamic_reconfigure::Config to_msg(const std::vector<rosc_dr_value> &v) const
  {
    dynamic_reconfigure::Config c;
    for (size_t i = 0; i < params.size(); i++) {
      const param &p = params[i];
      switch (p.type) {
      case ROSC_DR_INT: {
        dynamic_reconfigure::IntParameter x;
        x.name = p.name;
        x.value = to_int(v[i].num);
        c.ints.push_back(x);
        break;
      }
      case ROSC_DR_BOOL: {
        dynamic_reconfigure::BoolParameter x;
        x.name = p.name;
        x.value = v[i].num != 0.0;
        c.bools.push_back(x);
        break;
      }
      case ROSC_DR_STR: {
        dynamic_reconfigure::StrParameter x;
        x.name = p.name;
        x.value = v[i].str;
        c.strs.push_back(x);
        break;
      }
      default: {
        dynamic_reconfigure::DoubleParameter x;
        x.name = p.name;
        x.value = v[i].num;
        c.doubles.push_back(x);
        break;
      }
      }
    }
    dynamic_reconfigure::GroupState g;
    g.name = "Default";
    g.state = true;
    g.id = 0;
    g.parent = 0;
    c.groups.push_back(g);
    return c;
  }

  // The values named in a request, over a copy of those in force.
  std::vector<rosc_dr_value> merge(const dynamic_reconfigure::Config &c) const
  {
    std::vector<rosc_dr_value> v = cur;
    for (size_t i = 0; i < params.size(); i++) {
      const param &p = params[i];
      for (const auto &x : c.ints)
        if (x.name == p.name) v[i].num = p.type == ROSC_DR_STR ? v[i].num : x.value;
      for (const auto &x : c.doubles)
        if (x.name == p.name) v[i].num = p.type == ROSC_DR_STR ? v[i].num : x.value;
      for (const auto &x : c.bools)
        if (x.name == p.name) v[i].num = p.type == ROSC_DR_STR ? v[i].num : (x.value ? 1.0 : 0.0);
      for (const auto &x : c.strs)
        if (x.name == p.name && p.type == ROSC_DR_STR)
          std::snprintf(v[i].str, sizeof v[i].str, "%s", x.value.c_str());
    }
    return v;
  }

  void to_server() const
  {
    for (size_t i = 0; i < params.size(); i++) {
      const std::string key = ros::names::resolve("~" + params[i].name);
      switch (params[i].type) {
      case ROSC_DR_INT: ros::param::set(key, static_cast<int>(to_int(cur[i].num))); break;
      case ROSC_DR_BOOL: ros::param::set(key, cur[i].num != 0.0); break;
      case ROSC_DR_STR: ros::param::set(key, std::string(cur[i].str)); break;
      default: ros::param::set(key, cur[i].num); break;
      }
    }
  }

  void publish_update()
  {
    pub_update.publish(to_msg(cur));
    to_server();
  }

  bool on_set(dynamic_reconfigure::Reconfigure::Request &req,
              dynamic_reconfigure::Reconfigure::Response &rsp)
  {
    std::vector<rosc_dr_value> v = merge(req.config);
    std::vector<int> changed(params.size(), 0);
    for (size_t i = 0; i < params.size(); i++) changed[i] = !same(params[i].type, v[i], cur[i]);
    cb(v.data(), changed.data(), v.size(), user);
    cur = v;
    publish_update();
    rsp.config = to_msg(cur);
    return true;
  }
};

int rosc_dynreconf_create(rosc_dynreconf **out, const rosc_dr_param *params,
                          const rosc_dr_value *dflt, const rosc_dr_value *current, size_t n,
                          rosc_dr_cb cb, void *user)
{
  return guard(__func__, [&]() -> int {
    if (out == nullptr || params == nullptr || dflt == nullptr || current == nullptr || n == 0 ||
        cb == nullptr)
      return ROSC_E_INVALID;
    for (size_t i = 0; i < n; i++)
      if (!valid_name(params[i].name) || params[i].type < ROSC_DR_INT ||
          params[i].type > ROSC_DR_STR)
        return ROSC_E_INVALID;
    if (!rosc_ok()) return ROSC_E_STATE;
    std::unique_ptr<rosc_dynreconf> d(new rosc_dynreconf());
    d->cb = cb;
    d->user = user;
    d->dflt.assign(dflt, dflt + n);
    d->cur.assign(current, current + n);
    for (size_t i = 0; i < n; i++) {
      rosc_dr_value *vals[2] = {&d->dflt[i], &d->cur[i]};
      for (rosc_dr_value *v : vals) v->str[sizeof v->str - 1] = '\0';
      param p;
      p.name = params[i].name;
      p.description = params[i].description ? params[i].description : "";
      p.type = params[i].type;
      p.level = params[i].level;
      p.min = params[i].min;
      p.max = params[i].max;
      if (p.type == ROSC_DR_STR && params[i].choices != nullptr)
        p.edit_method = enum_edit_method(params[i].choices, p.description);
      d->params.push_back(p);
    }
    ros::NodeHandle nh;  // "~x" is resolved first: NodeHandle methods refuse private names
    d->pub_descr = nh.advertise<dynamic_reconfigure::ConfigDescription>(
        ros::names::resolve("~parameter_descriptions"), 1, true);
    d->pub_update = nh.advertise<dynamic_reconfigure::Config>(
        ros::names::resolve("~parameter_updates"), 1, true);
    if (!d->pub_descr || !d->pub_update) return ROSC_E_ROS;
    // the description: one group of every parameter, with min, max and defaults
    dynamic_reconfigure::ConfigDescription desc;
    dynamic_reconfigure::Group g;
    g.name = "Default";
    g.type = "";
    g.id = 0;
    g.parent = 0;
    std::vector<rosc_dr_value> lo(d->cur), hi(d->cur);
    for (size_t i = 0; i < n; i++) {
      const param &p = d->params[i];
      dynamic_reconfigure::ParamDescription pd;
      pd.name = p.name;
      pd.type = type_name(p.type);
      pd.level = p.level;
      pd.description = p.description;
      pd.edit_method = p.edit_method;
      g.parameters.push_back(pd);
      lo[i].num = p.type == ROSC_DR_BOOL ? 0.0 : p.min;
      hi[i].num = p.type == ROSC_DR_BOOL ? 1.0 : p.max;
      lo[i].str[0] = hi[i].str[0] = '\0';
    }
    desc.groups.push_back(g);
    desc.min = d->to_msg(lo);
    desc.max = d->to_msg(hi);
    desc.dflt = d->to_msg(d->dflt);
    d->pub_descr.publish(desc);
    d->publish_update();
    d->srv = nh.advertiseService(ros::names::resolve("~set_parameters"), &rosc_dynreconf::on_set,
                                 d.get());
    if (!d->srv) return ROSC_E_ROS;
    *out = d.release();
    return ROSC_OK;
  });
}

int rosc_dynreconf_update(rosc_dynreconf *dr, const rosc_dr_value *values, size_t n)
{
  return guard(__func__, [&]() -> int {
    if (dr == nullptr || values == nullptr || n != dr->params.size()) return ROSC_E_INVALID;
    if (!rosc_ok()) return ROSC_E_STATE;
    dr->cur.assign(values, values + n);
    for (auto &v : dr->cur) v.str[sizeof v.str - 1] = '\0';
    dr->publish_update();
    return ROSC_OK;
  });
}

int rosc_dynreconf_destroy(rosc_dynreconf *dr)
{
  return guard(__func__, [&]() -> int {
    if (dr == nullptr) return ROSC_OK;
    dr->srv.shutdown();
    dr->pub_descr.shutdown();
    dr->pub_update.shutdown();
    delete dr;
    return ROSC_OK;
  });
}
