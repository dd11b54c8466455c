/* Typed topics for the skin_sim nodes: a publisher of C views (ss_msg.h) encodes each
 * into a buffer it keeps and hands the bytes to rosc; a subscriber decodes the bytes
 * rosc hands it into a view over a scratch it keeps, and drops (with a throttled
 * error, and counted) a message it cannot read. The shim sees bytes only.
 * Header-only (static functions), included by the nodes' .c files. */
#ifndef SKIN_SIM_NODE_MSG_H
#define SKIN_SIM_NODE_MSG_H

#include "node_log.h"
#include "rosc/rosc.h"
#include "ss_msg.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ROS time (rosc_now) as a message's stamp; zero if the node is not running. */
static inline ss_msg_time msg_now(void)
{
  rosc_time t = {0, 0};
  rosc_now(&t);
  ss_msg_time m = {t.sec, t.nsec};
  return m;
}

typedef struct msg_pub {
  rosc_pub *pub;
  int type;       /* SS_MSG_* */
  ss_msg_buf buf; /* the last message's bytes, reused */
} msg_pub;

/* Advertises topic for views of type (SS_MSG_*), as rosc_pub_create. */
static inline int msg_pub_create(msg_pub **out, int type, const char *topic, unsigned queue_size,
                                 int latch)
{
  msg_pub *p = out != NULL && ss_msg_datatype(type) != NULL ? calloc(1, sizeof *p) : NULL;
  int st = out == NULL || ss_msg_datatype(type) == NULL ? ROSC_E_INVALID
           : p == NULL ? ROSC_E_NOMEM
                       : rosc_pub_create(&p->pub, ss_msg_datatype(type), topic, queue_size, latch);
  if (st == ROSC_OK) {
    p->type = type;
    *out = p;
  } else {
    free(p);
  }
  return st;
}

/* Publishes view, the struct of type (ss_msg_skin_mesh for SS_MSG_SKIN_MESH, ...):
 * ROSC_E_INVALID if the publisher has another type or the encoder refuses the view
 * (ss_msg_encode), ROSC_E_NOMEM when the buffer cannot grow. */
static inline int msg_publish(msg_pub *p, int type, const void *view)
{
  if (p == NULL || view == NULL || p->type != type) return ROSC_E_INVALID;
  int st = ss_msg_encode(p->type, view, &p->buf);
  if (st != SS_MSG_OK) return st == SS_MSG_E_NOMEM ? ROSC_E_NOMEM : ROSC_E_INVALID;
  return rosc_publish(p->pub, p->buf.data, p->buf.len);
}

static inline int msg_pub_destroy(msg_pub *p) /* NULL is fine */
{
  int st = p != NULL ? rosc_pub_destroy(p->pub) : ROSC_OK;
  if (p != NULL) ss_msg_buf_free(&p->buf);
  free(p);
  return st;
}

/* A received message: view is the struct of the subscriber's type, valid during the
 * call only. */
typedef void (*msg_view_cb)(const void *view, void *user);
/* A received message's bytes before anything is sized from them: 1 reads it, 0
 * drops it unread (the check says why itself). */
typedef int (*msg_bytes_cb)(const uint8_t *buf, size_t len, void *user);

typedef struct msg_sub {
  rosc_sub *sub;
  int type;
  msg_view_cb cb;
  msg_bytes_cb check; /* may be NULL */
  void *user;
  uint64_t dropped;   /* messages that could not be read */
  size_t keep_bytes;  /* scratch arrays larger than this are given back after a message */
  ss_throttle drop_log;
  ss_msg_scratch scratch;
} msg_sub;

static inline void msg_sub_bytes_(const uint8_t *buf, size_t len, void *user)
{
  msg_sub *s = user;
  ss_msg_any view;
  char why[256], topic[256] = "?";
  if (s->check != NULL && !s->check(buf, len, s->user)) return;
  if (ss_msg_decode(s->type, buf, len, &view, &s->scratch, why, sizeof why) == SS_MSG_OK) {
    s->cb(&view, s->user);
    /* one large message does not keep its memory for the node's life */
    for (int i = 0; i < SS_MSG_MAX_ARRAYS; i++)
      if (s->scratch.cap[i] > s->keep_bytes) {
        free(s->scratch.data[i]);
        s->scratch.data[i] = NULL;
        s->scratch.cap[i] = 0;
      }
    return;
  }
  s->dropped++;
  rosc_sub_topic(s->sub, topic, sizeof topic);
  NODE_LOG_EVERY(&s->drop_log, ROSC_LOG_ERROR, 5.0, "dropped a message on %s: %s (%llu dropped so far)",
                 topic, why, (unsigned long long)s->dropped);
}

/* Subscribes topic for views of type (SS_MSG_*), as rosc_subscribe: check(bytes) (may
 * be NULL) and then cb(view) run inside rosc_spin_*. */
static inline int msg_subscribe(msg_sub **out, int type, const char *topic, unsigned queue_size,
                                msg_view_cb cb, msg_bytes_cb check, void *user)
{
  if (out == NULL || cb == NULL || ss_msg_datatype(type) == NULL) return ROSC_E_INVALID;
  msg_sub *s = calloc(1, sizeof *s);
  if (s == NULL) return ROSC_E_NOMEM;
  *s = (msg_sub){.type = type, .cb = cb, .check = check, .user = user,
                 .keep_bytes = (size_t)8 << 20};
  int st = rosc_subscribe(&s->sub, ss_msg_datatype(type), topic, queue_size, msg_sub_bytes_, s);
  if (st == ROSC_OK) *out = s;
  else free(s);
  return st;
}

static inline int msg_sub_destroy(msg_sub *s) /* NULL is fine */
{
  if (s == NULL) return ROSC_OK;
  int st = rosc_sub_destroy(s->sub);
  ss_msg_scratch_free(&s->scratch);
  free(s);
  return st;
}

#endif
