// rosc parameters (include/rosc/rosc.h: "parameters"): typed getters that tell "not set"
// from "set with another type", setters, the type a parameter holds, and the URDF
// under robot_description. Each getter asks the master once (an XmlRpcValue) and checks
// the type itself.
#include "rosc/rosc.h"
#include "rosc_internal.h"

#include <ros/param.h>
#include <ros/ros.h>

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using rosc_internal::copy_out;
using rosc_internal::guard;
using rosc_internal::need_node;
using rosc_internal::valid_name;

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

namespace {
// One getter for every scalar type: *out = def, then the server's value if it is set;
// convert(v, out) takes a value of an accepted type, else returns ROSC_E_TYPE.
template <class T, class Convert>
int get_scalar(const char *func, const char *name, T *out, T def, int *was_set, Convert convert)
{
  return guard(func, [&]() -> int {
    if (out == nullptr) return ROSC_E_INVALID;
    *out = def;
    if (was_set != nullptr) *was_set = 0;
    XmlRpc::XmlRpcValue v;
    bool found = false;
    int st = param_fetch(name, v, &found);
    if (st != ROSC_OK || !found) return st;
    st = convert(v, out);
    if (st != ROSC_OK) return st;
    if (was_set != nullptr) *was_set = 1;
    return ROSC_OK;
  });
}
}  // namespace

int rosc_param_get_double(const char *name, double *out, double def, int *was_set)
{
  return get_scalar(__func__, name, out, def, was_set, [](XmlRpc::XmlRpcValue &v, double *o) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) *o = static_cast<double>(v);
    else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) *o = static_cast<int>(v);
    else return ROSC_E_TYPE;
    return ROSC_OK;
  });
}

int rosc_param_get_int(const char *name, int *out, int def, int *was_set)
{
  return get_scalar(__func__, name, out, def, was_set, [](XmlRpc::XmlRpcValue &v, int *o) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) {
      *o = static_cast<int>(v);
    } else if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
      double d = static_cast<double>(v);
      if (!(d == std::floor(d)) || d < (double)INT_MIN || d > (double)INT_MAX) return ROSC_E_TYPE;
      *o = (int)d;
    } else {
      return ROSC_E_TYPE;
    }
    return ROSC_OK;
  });
}

int rosc_param_get_bool(const char *name, int *out, int def, int *was_set)
{
  return get_scalar(__func__, name, out, def ? 1 : 0, was_set, [](XmlRpc::XmlRpcValue &v, int *o) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) return ROSC_E_TYPE;
    *o = static_cast<bool>(v) ? 1 : 0;
    return ROSC_OK;
  });
}

int rosc_internal::param_get_string_alloc(const char *name, char **out, size_t *len)
{
  return guard("rosc_param_get_string_alloc", [&]() -> int {
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


int rosc_param_type(const char *name, int *type)
{
  return guard(__func__, [&]() -> int {
    if (type == nullptr) return ROSC_E_INVALID;
    XmlRpc::XmlRpcValue v;
    bool found = false;
    int st = param_fetch(name, v, &found);
    if (st != ROSC_OK) return st;
    if (!found) return ROSC_E_NOTFOUND;
    switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeString: *type = ROSC_PARAM_STRING; break;
    case XmlRpc::XmlRpcValue::TypeInt: *type = ROSC_PARAM_INT; break;
    case XmlRpc::XmlRpcValue::TypeDouble: *type = ROSC_PARAM_DOUBLE; break;
    case XmlRpc::XmlRpcValue::TypeBoolean: *type = ROSC_PARAM_BOOL; break;
    case XmlRpc::XmlRpcValue::TypeArray: *type = ROSC_PARAM_LIST; break;
    case XmlRpc::XmlRpcValue::TypeStruct: *type = ROSC_PARAM_DICT; break;
    default: *type = ROSC_PARAM_OTHER; break;
    }
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
    return rosc_internal::param_get_string_alloc(key.c_str(), out, len);
  });
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
