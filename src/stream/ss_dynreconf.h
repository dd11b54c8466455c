/* skin_sim stream: dynamic_reconfigure's protocol spoken from a table given at run
 * time (the node library, src/stream; no ROS headers): the bytes of its messages
 * (dynamic_reconfigure/Config and ConfigDescription, ROS 1's wire format) built from a
 * node's own table of parameters, and a set_parameters request read back into it. The
 * node serves them through rosc's byte topics and byte services
 * (src/nodes/node_dynreconf.h), so no .cfg file copies the table and the shim knows
 * no field of them. One group, "Default" (id 0), holds every parameter. */
#ifndef SKIN_SIM_SS_DYNRECONF_H
#define SKIN_SIM_SS_DYNRECONF_H

#include "ss_msg.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { SS_DR_INT = 0, SS_DR_DOUBLE = 1, SS_DR_BOOL = 2, SS_DR_STR = 3 };
#define SS_DR_STR_MAX 128
typedef struct ss_dr_param {
  const char *name;           /* e.g. "slide" */
  int type;                   /* SS_DR_* */
  const char *description;    /* one line, shown by rqt_reconfigure (NULL: "") */
  unsigned level;             /* ORed over the changed parameters (dynamic_reconfigure's level) */
  double min, max;            /* numbers: the bounds clients are told (may be infinite) */
  const char *const *choices; /* str: NULL-terminated names offered as a menu; NULL: free text */
} ss_dr_param;
typedef struct ss_dr_value {
  double num;              /* int, double, bool (0/1) */
  char str[SS_DR_STR_MAX]; /* str */
} ss_dr_value;

/* Config: values (n, in the table's order) by type, and the one group's state. Ints
 * are clamped to int32. SS_MSG_E_NOMEM if out cannot grow. */
int ss_dr_encode_config(const ss_dr_param *p, const ss_dr_value *values, size_t n,
                        ss_msg_buf *out);
/* ConfigDescription: the group with every parameter (type, level, description, an
 * enum edit_method for choices), and the max, min and default Configs. */
int ss_dr_encode_description(const ss_dr_param *p, const ss_dr_value *dflt, size_t n,
                             ss_msg_buf *out);
/* A Reconfigure request (a Config) over values: each parameter it names by a table name
 * takes its value (numbers from ints, doubles or bools for number parameters, strs for
 * str ones, cut to SS_DR_STR_MAX - 1 bytes); others keep theirs. SS_MSG_E_MALFORMED,
 * with why, if the bytes do not hold a Config. */
int ss_dr_decode_request(const ss_dr_param *p, size_t n, const uint8_t *buf, size_t len,
                         ss_dr_value *values, char *why, size_t why_size);
/* 1 if a and b differ as values of a parameter of type (NaN equals NaN). */
int ss_dr_differ(int type, const ss_dr_value *a, const ss_dr_value *b);

#ifdef __cplusplus
}
#endif
#endif
