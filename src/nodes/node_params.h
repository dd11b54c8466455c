/* Private parameters of the skin_sim nodes, read the same way in every node:
 * a parameter of the wrong type (`_substeps:=abc`) or out of range stops the
 * node at start with one error naming it, never a silent default or clamp.
 * Header-only (static functions), included by the nodes' .c files. */
#ifndef SKIN_SIM_NODE_PARAMS_H
#define SKIN_SIM_NODE_PARAMS_H

#include "rosc/rosc.h"
#include "ss_dynreconf.h"
#include "skin_sim/ss_settings.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stddef.h>

/* What the server holds under name, in words: "the string 'abc'" (cut after 60
 * characters), "the double 2.5", "the int 3", "the bool true", "a list", "a
 * dictionary". */
static inline void param_describe(const char *name, char *held, size_t size)
{
  int type = 0, i = 0;
  double d = 0.0;
  char text[64];
  snprintf(held, size, "a value of another type");
  if (rosc_param_type(name, &type) != ROSC_OK) return;
  switch (type) {
  case ROSC_PARAM_STRING:
    rosc_param_get_string(name, text, sizeof text, "", NULL); /* a prefix if longer */
    snprintf(held, size, "the string '%.60s%s'", text, strlen(text) > 60 ? "..." : "");
    break;
  case ROSC_PARAM_INT:
    rosc_param_get_int(name, &i, 0, NULL);
    snprintf(held, size, "the int %d", i);
    break;
  case ROSC_PARAM_DOUBLE:
    rosc_param_get_double(name, &d, 0.0, NULL);
    snprintf(held, size, "the double %g", d);
    break;
  case ROSC_PARAM_BOOL:
    rosc_param_get_bool(name, &i, 0, NULL);
    snprintf(held, size, "the bool %s", i ? "true" : "false");
    break;
  case ROSC_PARAM_LIST: snprintf(held, size, "a list"); break;
  case ROSC_PARAM_DICT: snprintf(held, size, "a dictionary"); break;
  default: break;
  }
}

/* 1 if a getter read its parameter (or its default); else logs why (a wrong type
 * names the parameter, the type wanted and the value given: "~substeps must be an
 * int, but is the string 'abc'") and returns 0. */
static inline int param_ok(int status, const char *name, const char *expected)
{
  if (status == ROSC_OK) return 1;
  if (status != ROSC_E_TYPE) {
    ROSC_ERROR("parameter %s: %s", name, rosc_strerror(status));
    return 0;
  }
  char held[128], text[128];
  param_describe(name, held, sizeof held);
  /* roslaunch reads a number without a '.' (1e-4) as a string */
  const char *hint = "";
  char *end = NULL;
  if (strstr(expected, "double") && rosc_param_get_string(name, text, sizeof text, "", NULL) == ROSC_OK &&
      text[0] != '\0' && (strtod(text, &end), *end == '\0'))
    hint = " (in a launch file, a number without a '.' such as 1e-4 stays a string: write type=\"double\")";
  ROSC_ERROR("%s must be %s, but is %s%s", name, expected, held, hint);
  return 0;
}

static inline int get_int(const char *name, int *v, int def)
{
  return param_ok(rosc_param_get_int(name, v, def, NULL), name, "an int");
}
static inline int get_double(const char *name, double *v, double def)
{
  return param_ok(rosc_param_get_double(name, v, def, NULL), name, "a double (or an int)");
}
static inline int get_bool(const char *name, int *v, int def)
{
  return param_ok(rosc_param_get_bool(name, v, def, NULL), name, "a bool");
}
static inline int get_string(const char *name, char *buf, size_t size, const char *def)
{
  return param_ok(rosc_param_get_string(name, buf, size, def, NULL), name, "a string");
}

/* 1 if an int parameter is within [lo, hi]; else logs it and returns 0 (never clamped). */
static inline int param_range(const char *name, int v, int lo, int hi)
{
  if (v >= lo && v <= hi) return 1;
  ROSC_ERROR("%s = %d is out of range [%d, %d]", name, v, lo, hi);
  return 0;
}

/* ---- the simulation settings (the table of ss_settings.h) ---- */

/* ~NAME of one setting of the table into *set: read as its type (a wrong type is
 * named), then range-checked by the core. 1 if good; else one error, 0. */
static inline int get_setting(const ss_setting *d, ss_sim_settings *set)
{
  char name[80], buf[256], err[512] = "";
  snprintf(name, sizeof name, "~%s", d->name);
  int ok = 1;
  if (d->type == SS_SETTING_INT || d->type == SS_SETTING_BOOL) {
    int v = (int)ss_setting_get(d, set, 0);
    ok = d->type == SS_SETTING_INT ? get_int(name, &v, v) : get_bool(name, &v, v);
    if (ok) ss_setting_set(d, set, 0, v);
  } else if (d->type == SS_SETTING_DOUBLE) {
    double v = ss_setting_get(d, set, 0);
    ok = get_double(name, &v, v);
    if (ok) ss_setting_set(d, set, 0, v);
  } else { /* enum: its name; vec3: "x y z" */
    char def[128];
    ss_setting_format(d, set, def, sizeof def);
    ok = get_string(name, buf, sizeof buf, def);
    if (ok && ss_setting_parse(d, buf, set, err, sizeof err) != SS_OK) {
      ROSC_ERROR("%s: %s", name, err);
      return 0;
    }
  }
  if (ok && ss_setting_check(d, set, err, sizeof err) != SS_OK) {
    ROSC_ERROR("bad skin parameters: %s", err);
    return 0;
  }
  return ok;
}

/* Every setting of the table on dynamic_reconfigure (rqt_reconfigure, dynparam): ints,
 * doubles and bools as such, enums and vectors as text. */
static inline void dr_value(const ss_setting *d, const ss_sim_settings *s, ss_dr_value *v)
{
  memset(v, 0, sizeof *v);
  if (d->type == SS_SETTING_ENUM || d->type == SS_SETTING_VEC3)
    ss_setting_format(d, s, v->str, sizeof v->str);
  else
    v->num = ss_setting_get(d, s, 0);
}

#endif
