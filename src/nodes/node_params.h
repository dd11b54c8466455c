/* Private parameters of the skin_sim nodes, read the same way in every node:
 * a parameter of the wrong type (`_substeps:=abc`) or out of range stops the
 * node at start with one error naming it, never a silent default or clamp.
 * Header-only (static functions), included by each node's single .c file. */
#ifndef SKIN_SIM_NODE_PARAMS_H
#define SKIN_SIM_NODE_PARAMS_H

#include "rosc/rosc.h"

#include <stddef.h>

/* 1 if a getter read its parameter (or its default); else logs why (a wrong type
 * names the parameter, the type wanted and the value given) and returns 0. */
static inline int param_ok(int status, const char *name, const char *expected)
{
  if (status == ROSC_OK) return 1;
  char why[512];
  rosc_param_explain(status, name, expected, why, sizeof why);
  ROSC_ERROR("%s", why);
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

#endif
