/* A dynamic_reconfigure server for the skin_sim nodes, spoken from a table given at
 * run time (no .cfg file): the ~set_parameters service (dynamic_reconfigure/Reconfigure)
 * and the latched ~parameter_descriptions (ConfigDescription) and ~parameter_updates
 * (Config) topics, so that rqt_reconfigure and `rosrun dynamic_reconfigure dynparam`
 * work; every value in force is also written to the parameter server as ~NAME, as
 * dynamic_reconfigure's own server does. The messages are built and read in pure C
 * (src/stream/ss_dynreconf.h); rosc moves their bytes. Requests are served inside
 * rosc_spin_* like every other callback. Header-only (static functions). */
#ifndef SKIN_SIM_NODE_DYNRECONF_H
#define SKIN_SIM_NODE_DYNRECONF_H

#include "node_log.h"
#include "rosc/rosc.h"
#include "ss_dynreconf.h"

#include <stdlib.h>
#include <string.h>

/* Called for a set_parameters request: values (n, in the order of the table) hold the
 * configuration asked for (parameters the request did not name keep the value in
 * force), changed[i] is 1 where it differs. The callback applies what it accepts and
 * leaves in values what is IN FORCE afterwards (a refused value back to its old one):
 * that is what the caller gets back and what ~parameter_updates publishes. */
typedef void (*node_dr_cb)(ss_dr_value *values, const int *changed, size_t n, void *user);

typedef struct node_dr {
  ss_dr_param *params; /* (n) names copied into names; no descriptions kept */
  char **names;
  ss_dr_value *cur, *req; /* (n) in force; a request being served */
  int *changed;           /* (n) */
  size_t n;
  node_dr_cb cb;
  void *user;
  rosc_pub *descr, *update;
  rosc_srv *srv;
  ss_msg_buf msg, resp; /* the last Config published; the last response */
} node_dr;

/* ~parameter_updates and ~NAME on the parameter server: the values in force. */
static inline int node_dr_publish_(node_dr *dr)
{
  int st = ss_dr_encode_config(dr->params, dr->cur, dr->n, &dr->msg);
  if (st != SS_MSG_OK) return ROSC_E_NOMEM;
  st = rosc_publish(dr->update, dr->msg.data, dr->msg.len);
  for (size_t i = 0; i < dr->n; i++) {
    char key[160];
    snprintf(key, sizeof key, "~%s", dr->names[i]);
    const ss_dr_value *v = &dr->cur[i];
    int s = dr->params[i].type == SS_DR_STR    ? rosc_param_set_string(key, v->str)
            : dr->params[i].type == SS_DR_BOOL ? rosc_param_set_bool(key, v->num != 0.0)
            : dr->params[i].type == SS_DR_INT  ? rosc_param_set_int(key, (int)v->num)
                                               : rosc_param_set_double(key, v->num);
    if (st == ROSC_OK) st = s;
  }
  return st;
}

static inline int node_dr_on_set_(const uint8_t *req, size_t len, const uint8_t **resp,
                                  size_t *resp_len, void *user)
{
  node_dr *dr = user;
  char why[160];
  memcpy(dr->req, dr->cur, dr->n * sizeof *dr->req);
  if (ss_dr_decode_request(dr->params, dr->n, req, len, dr->req, why, sizeof why) != SS_MSG_OK) {
    ROSC_WARN("dynamic_reconfigure: %s", why);
    return 1;
  }
  for (size_t i = 0; i < dr->n; i++)
    dr->changed[i] = ss_dr_differ(dr->params[i].type, &dr->req[i], &dr->cur[i]);
  dr->cb(dr->req, dr->changed, dr->n, dr->user);
  for (size_t i = 0; i < dr->n; i++) dr->req[i].str[SS_DR_STR_MAX - 1] = '\0';
  memcpy(dr->cur, dr->req, dr->n * sizeof *dr->cur);
  node_dr_publish_(dr);
  if (ss_dr_encode_config(dr->params, dr->cur, dr->n, &dr->resp) != SS_MSG_OK) return 1;
  *resp = dr->resp.data;
  *resp_len = dr->resp.len;
  return 0;
}

static inline int node_dr_destroy(node_dr *dr) /* NULL is fine */
{
  if (dr == NULL) return ROSC_OK;
  rosc_srv_destroy(dr->srv);
  rosc_pub_destroy(dr->descr);
  rosc_pub_destroy(dr->update);
  for (size_t i = 0; dr->names && i < dr->n; i++) free(dr->names[i]);
  free(dr->names);
  free(dr->params);
  free(dr->cur);
  free(dr->req);
  free(dr->changed);
  ss_msg_buf_free(&dr->msg);
  ss_msg_buf_free(&dr->resp);
  free(dr);
  return ROSC_OK;
}

/* params, dflt, current: n entries each (copied). Publishes the description and the
 * current configuration at once, then serves ~set_parameters. */
static inline int node_dr_create(node_dr **out, const ss_dr_param *params, const ss_dr_value *dflt,
                                 const ss_dr_value *current, size_t n, node_dr_cb cb, void *user)
{
  if (out == NULL || params == NULL || dflt == NULL || current == NULL || n == 0 || cb == NULL)
    return ROSC_E_INVALID;
  node_dr *dr = calloc(1, sizeof *dr);
  if (dr == NULL) return ROSC_E_NOMEM;
  dr->n = n;
  dr->cb = cb;
  dr->user = user;
  dr->params = calloc(n, sizeof *dr->params);
  dr->names = calloc(n, sizeof *dr->names);
  dr->cur = calloc(n, sizeof *dr->cur);
  dr->req = calloc(n, sizeof *dr->req);
  dr->changed = calloc(n, sizeof *dr->changed);
  int st = dr->params && dr->names && dr->cur && dr->req && dr->changed ? ROSC_OK : ROSC_E_NOMEM;
  for (size_t i = 0; st == ROSC_OK && i < n; i++) {
    if (params[i].name == NULL || params[i].name[0] == '\0' || params[i].type < SS_DR_INT ||
        params[i].type > SS_DR_STR)
      st = ROSC_E_INVALID;
    else if ((dr->names[i] = strdup(params[i].name)) == NULL)
      st = ROSC_E_NOMEM;
    dr->params[i] = params[i];
    dr->params[i].name = dr->names[i];
    dr->cur[i] = current[i];
    dr->cur[i].str[SS_DR_STR_MAX - 1] = '\0';
  }
  if (st == ROSC_OK) st = rosc_pub_create(&dr->descr, "dynamic_reconfigure/ConfigDescription",
                                          "~parameter_descriptions", 1, 1);
  if (st == ROSC_OK)
    st = rosc_pub_create(&dr->update, "dynamic_reconfigure/Config", "~parameter_updates", 1, 1);
  if (st == ROSC_OK) st = ss_dr_encode_description(params, dflt, n, &dr->msg) == SS_MSG_OK
                              ? rosc_publish(dr->descr, dr->msg.data, dr->msg.len)
                              : ROSC_E_NOMEM;
  for (size_t i = 0; i < n; i++) dr->params[i].description = NULL; /* not kept */
  if (st == ROSC_OK) st = node_dr_publish_(dr);
  if (st == ROSC_OK)
    st = rosc_srv_create(&dr->srv, "~set_parameters", "dynamic_reconfigure/Reconfigure",
                         node_dr_on_set_, dr);
  if (st != ROSC_OK) {
    node_dr_destroy(dr);
    return st;
  }
  *out = dr;
  return ROSC_OK;
}

/* The values in force changed outside a request: publishes them (n as at create). */
static inline int node_dr_update(node_dr *dr, const ss_dr_value *values, size_t n)
{
  if (dr == NULL || values == NULL || n != dr->n) return ROSC_E_INVALID;
  memcpy(dr->cur, values, n * sizeof *dr->cur);
  for (size_t i = 0; i < n; i++) dr->cur[i].str[SS_DR_STR_MAX - 1] = '\0';
  return node_dr_publish_(dr);
}

#endif
