/* skin_sim stream: dynamic_reconfigure's messages from a table (ss_dynreconf.h). */
#include "ss_dynreconf.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A writer that first only counts (data NULL), then writes into a buffer of that size. */
typedef struct writer {
  uint8_t *data;
  size_t n;
} writer;

static void w_bytes(writer *w, const void *src, size_t n) {
  if (w->data && n) memcpy(w->data + w->n, src, n);
  w->n += n;
}
static void w_u32(writer *w, uint32_t v) { w_bytes(w, &v, 4); }
static void w_i32(writer *w, int32_t v) { w_bytes(w, &v, 4); }
static void w_u8(writer *w, int v) {
  uint8_t b = v != 0;
  w_bytes(w, &b, 1);
}
static void w_str(writer *w, const char *s) {
  size_t n = s ? strlen(s) : 0;
  w_u32(w, (uint32_t)n);
  w_bytes(w, s, n);
}

static int32_t to_int(double v) {
  if (!(v == v)) return 0;
  if (v >= (double)INT_MAX) return INT_MAX;
  if (v <= (double)INT_MIN) return INT_MIN;
  return (int32_t)v;
}

static uint32_t count_type(const ss_dr_param *p, size_t n, int type) {
  uint32_t k = 0;
  for (size_t i = 0; i < n; i++) k += p[i].type == type;
  return k;
}

/* Config: bools, ints, strs, doubles (each {name, value}), then groups. */
static void w_config(writer *w, const ss_dr_param *p, const ss_dr_value *v, size_t n) {
  static const int order[4] = {SS_DR_BOOL, SS_DR_INT, SS_DR_STR, SS_DR_DOUBLE};
  for (int k = 0; k < 4; k++) {
    w_u32(w, count_type(p, n, order[k]));
    for (size_t i = 0; i < n; i++) {
      if (p[i].type != order[k]) continue;
      w_str(w, p[i].name);
      if (order[k] == SS_DR_BOOL) w_u8(w, v[i].num != 0.0);
      else if (order[k] == SS_DR_INT) w_i32(w, to_int(v[i].num));
      else if (order[k] == SS_DR_STR) w_str(w, v[i].str);
      else w_bytes(w, &v[i].num, 8);
    }
  }
  w_u32(w, 1); /* GroupState Default: state, id 0, parent 0 */
  w_str(w, "Default");
  w_u8(w, 1);
  w_i32(w, 0);
  w_i32(w, 0);
}

static const char *type_name(int type) {
  switch (type) {
  case SS_DR_INT: return "int";
  case SS_DR_BOOL: return "bool";
  case SS_DR_STR: return "str";
  default: return "double";
  }
}

/* dynamic_reconfigure's edit_method for an enum of strings: a Python dict literal that
 * its client and rqt_reconfigure evaluate. */
static void w_enum(writer *w, const char *const *choices, const char *what) {
  w_bytes(w, "{'enum': [", 10);
  for (int k = 0; choices[k] != NULL; k++) {
    const char *c = choices[k];
    const char *parts[] = {k ? ", " : "", "{'name': '", c, "', 'type': 'str', 'value': '", c,
                           "', 'srcline': 0, 'srcfile': '', 'description': '", c,
                           "', 'ctype': 'std::string', 'cconsttype': 'const char * const'}"};
    for (size_t j = 0; j < sizeof parts / sizeof parts[0]; j++) w_bytes(w, parts[j], strlen(parts[j]));
  }
  const char *tail[] = {"], 'enum_description': '", what ? what : "", "'}"};
  for (size_t j = 0; j < 3; j++) w_bytes(w, tail[j], strlen(tail[j]));
}

/* The edit_method string field: "" without choices. */
static void w_edit_method(writer *w, const char *const *choices, const char *what) {
  writer count = {NULL, 0};
  if (choices) w_enum(&count, choices, what);
  w_u32(w, (uint32_t)count.n);
  if (choices) w_enum(w, choices, what);
}

static int finish(writer *w, ss_msg_buf *out) {
  if (w->n > UINT32_MAX) return SS_MSG_E_INVALID;
  if (w->n > out->cap) {
    uint8_t *d = realloc(out->data, w->n ? w->n : 1);
    if (d == NULL) return SS_MSG_E_NOMEM;
    out->data = d;
    out->cap = w->n ? w->n : 1;
  }
  out->len = w->n;
  w->data = out->data;
  w->n = 0;
  return SS_MSG_OK;
}

int ss_dr_encode_config(const ss_dr_param *p, const ss_dr_value *values, size_t n,
                        ss_msg_buf *out) {
  if (p == NULL || values == NULL || out == NULL) return SS_MSG_E_INVALID;
  writer w = {NULL, 0};
  w_config(&w, p, values, n);
  int st = finish(&w, out);
  if (st == SS_MSG_OK) w_config(&w, p, values, n);
  return st;
}

static void w_description(writer *w, const ss_dr_param *p, const ss_dr_value *lo,
                          const ss_dr_value *hi, const ss_dr_value *dflt, size_t n) {
  w_u32(w, 1); /* one Group: name, type, parameters, parent, id */
  w_str(w, "Default");
  w_str(w, "");
  w_u32(w, (uint32_t)n);
  for (size_t i = 0; i < n; i++) {
    w_str(w, p[i].name);
    w_str(w, type_name(p[i].type));
    w_u32(w, p[i].level);
    w_str(w, p[i].description);
    w_edit_method(w, p[i].type == SS_DR_STR ? p[i].choices : NULL, p[i].description);
  }
  w_i32(w, 0);
  w_i32(w, 0);
  w_config(w, p, hi, n);
  w_config(w, p, lo, n);
  w_config(w, p, dflt, n);
}

int ss_dr_encode_description(const ss_dr_param *p, const ss_dr_value *dflt, size_t n,
                             ss_msg_buf *out) {
  if (p == NULL || dflt == NULL || out == NULL) return SS_MSG_E_INVALID;
  ss_dr_value *lo = calloc(n ? n : 1, sizeof *lo), *hi = calloc(n ? n : 1, sizeof *hi);
  int st = lo && hi ? SS_MSG_OK : SS_MSG_E_NOMEM;
  for (size_t i = 0; st == SS_MSG_OK && i < n; i++) {
    lo[i].num = p[i].type == SS_DR_BOOL ? 0.0 : p[i].min;
    hi[i].num = p[i].type == SS_DR_BOOL ? 1.0 : p[i].max;
  }
  writer w = {NULL, 0};
  if (st == SS_MSG_OK) {
    w_description(&w, p, lo, hi, dflt, n);
    st = finish(&w, out);
  }
  if (st == SS_MSG_OK) w_description(&w, p, lo, hi, dflt, n);
  free(lo);
  free(hi);
  return st;
}

/* ------------------------------------------------------------------ a request */
typedef struct reader {
  const uint8_t *p;
  size_t left;
} reader;

static int r_bytes(reader *r, void *dst, size_t n) {
  if (n > r->left) return 0;
  if (dst && n) memcpy(dst, r->p, n);
  r->p += n;
  r->left -= n;
  return 1;
}

/* A string: its bytes in place (s, len). */
static int r_str(reader *r, const char **s, uint32_t *len) {
  if (!r_bytes(r, len, 4) || *len > r->left) return 0;
  *s = (const char *)r->p;
  return r_bytes(r, NULL, *len);
}

static long find(const ss_dr_param *p, size_t n, const char *s, uint32_t len) {
  for (size_t i = 0; i < n; i++)
    if (strlen(p[i].name) == len && memcmp(p[i].name, s, len) == 0) return (long)i;
  return -1;
}

int ss_dr_decode_request(const ss_dr_param *p, size_t n, const uint8_t *buf, size_t len,
                         ss_dr_value *values, char *why, size_t why_size) {
  static const int order[4] = {SS_DR_BOOL, SS_DR_INT, SS_DR_STR, SS_DR_DOUBLE};
  static const char *const names[5] = {"bools", "ints", "strs", "doubles", "groups"};
  char dummy[1];
  if (why == NULL || why_size == 0) {
    why = dummy;
    why_size = sizeof dummy;
  }
  why[0] = '\0';
  if (p == NULL || values == NULL || (buf == NULL && len)) return SS_MSG_E_INVALID;
  reader r = {buf, len};
  for (int k = 0; k < 5; k++) {
    uint32_t count = 0;
    if (!r_bytes(&r, &count, 4)) goto malformed;
    for (uint32_t e = 0; e < count; e++) {
      const char *s = NULL, *sv = NULL;
      uint32_t sl = 0, svl = 0, u = 0;
      uint8_t b = 0;
      double d = 0.0;
      int32_t iv = 0;
      if (!r_str(&r, &s, &sl)) goto malformed;
      if (k == 4) { /* GroupState: state, id, parent */
        if (!r_bytes(&r, &b, 1) || !r_bytes(&r, &u, 4) || !r_bytes(&r, &u, 4)) goto malformed;
        continue;
      }
      int ok = order[k] == SS_DR_BOOL  ? r_bytes(&r, &b, 1)
               : order[k] == SS_DR_INT ? r_bytes(&r, &iv, 4)
               : order[k] == SS_DR_STR ? r_str(&r, &sv, &svl)
                                       : r_bytes(&r, &d, 8);
      if (!ok) goto malformed;
      long i = find(p, n, s, sl);
      if (i < 0 || (order[k] == SS_DR_STR) != (p[i].type == SS_DR_STR)) continue;
      if (order[k] == SS_DR_STR) {
        size_t m = svl < SS_DR_STR_MAX - 1 ? svl : SS_DR_STR_MAX - 1;
        memcpy(values[i].str, sv, m);
        values[i].str[m] = '\0';
      } else {
        values[i].num = order[k] == SS_DR_BOOL ? (b ? 1.0 : 0.0) : order[k] == SS_DR_INT ? iv : d;
      }
    }
    continue;
  malformed:
    snprintf(why, why_size, "set_parameters: %s: the %zu-byte request ends inside it", names[k], len);
    return SS_MSG_E_MALFORMED;
  }
  if (r.left != 0) {
    snprintf(why, why_size, "set_parameters: %zu bytes after the end of the request", r.left);
    return SS_MSG_E_MALFORMED;
  }
  return SS_MSG_OK;
}

int ss_dr_differ(int type, const ss_dr_value *a, const ss_dr_value *b) {
  if (type == SS_DR_STR) return strcmp(a->str, b->str) != 0;
  return !(a->num == b->num || (a->num != a->num && b->num != b->num));
}
