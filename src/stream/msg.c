/* skin_sim stream: ROS 1 messages as C views, encoded and decoded by one walk over
 * each message's field table (ss_msg.h). */
#include "ss_msg.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "ROS 1's wire format is little-endian; this encoder copies host words"
#endif

/* What a field is on the wire and in its view. */
enum {
  K_U32,       /* lanes x 4 bytes (uint32, int32, float) */
  K_STAMP,     /* a time: 2 x uint32, nsec < 1e9 */
  K_F64,       /* lanes x 8 bytes */
  K_BOOL,      /* one byte; an int in the view */
  K_STR_FIXED, /* string; a char[cap] in the view */
  K_STR,       /* string; a const char * in the view (NULL: "") */
  K_ARR32,     /* array of count elements of lanes x 4 bytes; (const T *, size_t) */
  K_ARR64,     /* array of count float64; (const double *, size_t) */
  K_ARR_PTS,   /* array of count geometry_msgs/Point (3 float64); (const float *, size_t) */
  K_ARR_STR    /* array of count strings; (const char *const *, size_t) */
};

typedef struct field {
  const char *name;
  int kind, lanes, slot; /* slot: the scratch array of a decoded variable-size field */
  size_t off, count_off, cap;
} field;

#define F_(T, kind, lanes, name, member) {name, kind, lanes, 0, offsetof(T, member), 0, 0}
#define F_STR_FIXED(T, name, member) \
  {name, K_STR_FIXED, 1, 0, offsetof(T, member), 0, sizeof(((T *)0)->member)}
#define F_VAR(T, kind, lanes, slot, name, member) \
  {name, kind, lanes, slot, offsetof(T, member), offsetof(T, n_##member), 0}
#define F_STR(T, slot, name, member) {name, K_STR, 1, slot, offsetof(T, member), 0, 0}
#define F_HEADER(T) \
  F_(T, K_U32, 1, "header.seq", header.seq), F_(T, K_STAMP, 2, "header.stamp", header.stamp), \
      F_STR_FIXED(T, "frame_id", header.frame_id)

static const field skin_mesh_fields[] = {
  F_HEADER(ss_msg_skin_mesh),
  F_(ss_msg_skin_mesh, K_U32, 1, "topology_id", topology_id),
  F_VAR(ss_msg_skin_mesh, K_ARR32, 1, 0, "positions", positions),
  F_VAR(ss_msg_skin_mesh, K_ARR32, 1, 1, "triangles", triangles),
  F_VAR(ss_msg_skin_mesh, K_ARR32, 1, 2, "rigid_part", rigid_part),
};

#define F_STATS_(type, name) F_(ss_msg_skin_stats, K_U32, 1, #name, name),
static const field skin_stats_fields[] = {
  F_HEADER(ss_msg_skin_stats),
  SS_MSG_SKIN_STATS_FIELDS(F_STATS_)
};

static const field joint_state_fields[] = {
  F_HEADER(ss_msg_joint_state),
  F_VAR(ss_msg_joint_state, K_ARR_STR, 1, 0, "name", name),
  F_VAR(ss_msg_joint_state, K_ARR64, 1, 1, "position", position),
  F_VAR(ss_msg_joint_state, K_ARR64, 1, 2, "velocity", velocity),
  F_VAR(ss_msg_joint_state, K_ARR64, 1, 3, "effort", effort),
};

static const field marker_fields[] = {
  F_HEADER(ss_msg_marker),
  F_STR_FIXED(ss_msg_marker, "ns", ns),
  F_(ss_msg_marker, K_U32, 1, "id", id),
  F_(ss_msg_marker, K_U32, 1, "type", type),
  F_(ss_msg_marker, K_U32, 1, "action", action),
  F_(ss_msg_marker, K_F64, 3, "pose.position", position),
  F_(ss_msg_marker, K_F64, 4, "pose.orientation", orientation),
  F_(ss_msg_marker, K_F64, 3, "scale", scale),
  F_(ss_msg_marker, K_U32, 4, "color", color),
  F_(ss_msg_marker, K_U32, 2, "lifetime", lifetime),
  F_(ss_msg_marker, K_BOOL, 1, "frame_locked", frame_locked),
  F_VAR(ss_msg_marker, K_ARR_PTS, 3, 0, "points", points),
  F_VAR(ss_msg_marker, K_ARR32, 4, 1, "colors", colors),
  F_STR(ss_msg_marker, 2, "text", text),
  F_STR(ss_msg_marker, 3, "mesh_resource", mesh_resource),
  F_(ss_msg_marker, K_BOOL, 1, "mesh_use_embedded_materials", mesh_use_embedded_materials),
};

static const field string_fields[] = {F_STR(ss_msg_string, 0, "data", data)};

typedef struct msg_type {
  const char *datatype;
  const field *fields;
  size_t nfields, view_size;
} msg_type;

#define T_(name, fields, view) {name, fields, sizeof fields / sizeof fields[0], sizeof(view)}
static const msg_type types[SS_MSG_TYPES] = {
  T_("skin_sim/SkinMesh", skin_mesh_fields, ss_msg_skin_mesh),
  T_("skin_sim/SkinStats", skin_stats_fields, ss_msg_skin_stats),
  T_("sensor_msgs/JointState", joint_state_fields, ss_msg_joint_state),
  T_("visualization_msgs/Marker", marker_fields, ss_msg_marker),
  T_("std_msgs/String", string_fields, ss_msg_string),
};

const char *ss_msg_datatype(int type) {
  return type >= 0 && type < SS_MSG_TYPES ? types[type].datatype : NULL;
}

void ss_msg_buf_free(ss_msg_buf *b) {
  if (b == NULL) return;
  free(b->data);
  memset(b, 0, sizeof *b);
}

void ss_msg_scratch_free(ss_msg_scratch *s) {
  if (s == NULL) return;
  for (int i = 0; i < SS_MSG_MAX_ARRAYS; i++) free(s->data[i]);
  memset(s, 0, sizeof *s);
}

/* A field's place in its view. */
#define AT(view, f, T) ((T *)(void *)((char *)(view) + (f)->off))
#define COUNT(view, f) (*(size_t *)(void *)((char *)(view) + (f)->count_off))

static size_t elem_bytes(const field *f) {
  switch (f->kind) {
  case K_ARR32: return 4 * (size_t)f->lanes;
  case K_ARR64: return 8;
  case K_ARR_PTS: return 24;
  default: return 0;
  }
}

/* ------------------------------------------------------------------ encoding */
/* The wire size of one field of view, or SIZE_MAX if the view is not valid. */
static size_t field_size(const field *f, const void *view) {
  switch (f->kind) {
  case K_U32: return 4 * (size_t)f->lanes;
  case K_STAMP: return AT(view, f, const uint32_t)[1] < 1000000000u ? 8 : SIZE_MAX;
  case K_F64: return 8 * (size_t)f->lanes;
  case K_BOOL: return 1;
  case K_STR_FIXED: {
    size_t n = strnlen(AT(view, f, const char), f->cap);
    return n < f->cap ? 4 + n : SIZE_MAX;
  }
  case K_STR: {
    const char *s = *AT(view, f, const char *const);
    return 4 + (s ? strlen(s) : 0);
  }
  case K_ARR_STR: {
    const char *const *s = *AT(view, f, const char *const *const);
    size_t n = COUNT(view, f), bytes = 4;
    if (n > UINT32_MAX || (s == NULL && n)) return SIZE_MAX;
    for (size_t i = 0; i < n; i++) {
      if (s[i] == NULL) return SIZE_MAX;
      bytes += 4 + strlen(s[i]);
    }
    return bytes;
  }
  default: { /* arrays of numbers */
    const void *p = *AT(view, f, const void *const);
    size_t n = COUNT(view, f);
    if (n > UINT32_MAX || (p == NULL && n)) return SIZE_MAX;
    return 4 + n * elem_bytes(f);
  }
  }
}

static uint8_t *put(uint8_t *w, const void *src, size_t n) {
  if (n) memcpy(w, src, n);
  return w + n;
}

static uint8_t *put_u32(uint8_t *w, size_t v) {
  uint32_t u = (uint32_t)v;
  return put(w, &u, 4);
}

static uint8_t *put_field(uint8_t *w, const field *f, const void *view) {
  switch (f->kind) {
  case K_U32: case K_STAMP: return put(w, AT(view, f, const void), 4 * (size_t)f->lanes);
  case K_F64: return put(w, AT(view, f, const void), 8 * (size_t)f->lanes);
  case K_BOOL: *w = *AT(view, f, const int) != 0; return w + 1;
  case K_STR_FIXED: case K_STR: {
    const char *s = f->kind == K_STR ? *AT(view, f, const char *const) : AT(view, f, const char);
    size_t n = s ? strlen(s) : 0;
    return put(put_u32(w, n), s, n);
  }
  case K_ARR_STR: {
    const char *const *s = *AT(view, f, const char *const *const);
    size_t n = COUNT(view, f);
    w = put_u32(w, n);
    for (size_t i = 0; i < n; i++) {
      size_t k = strlen(s[i]);
      w = put(put_u32(w, k), s[i], k);
    }
    return w;
  }
  case K_ARR_PTS: {
    const float *p = *AT(view, f, const float *const);
    size_t n = COUNT(view, f);
    w = put_u32(w, n);
    for (size_t i = 0; i < 3 * n; i++) {
      double d = p[i];
      w = put(w, &d, 8);
    }
    return w;
  }
  default: {
    const void *p = *AT(view, f, const void *const);
    size_t n = COUNT(view, f);
    return put(put_u32(w, n), p, n * elem_bytes(f));
  }
  }
}

int ss_msg_encode(int type, const void *view, ss_msg_buf *out) {
  if (type < 0 || type >= SS_MSG_TYPES || view == NULL || out == NULL) return SS_MSG_E_INVALID;
  const msg_type *t = &types[type];
  size_t len = 0;
  for (size_t i = 0; i < t->nfields; i++) {
    size_t n = field_size(&t->fields[i], view);
    if (n == SIZE_MAX || n > UINT32_MAX - len) return SS_MSG_E_INVALID;
    len += n;
  }
  if (len > out->cap) {
    uint8_t *d = realloc(out->data, len);
    if (d == NULL) return SS_MSG_E_NOMEM;
    out->data = d;
    out->cap = len;
  }
  uint8_t *w = out->data;
  for (size_t i = 0; i < t->nfields; i++) w = put_field(w, &t->fields[i], view);
  out->len = len;
  return SS_MSG_OK;
}

/* ------------------------------------------------------------------ decoding */
typedef struct reader {
  const uint8_t *p;
  size_t left, total;
  char *why;
  size_t why_size;
} reader;

static int take(reader *r, const field *f, void *dst, size_t n) {
  if (n > r->left) {
    snprintf(r->why, r->why_size, "%s: the %zu-byte message ends inside it", f->name, r->total);
    return 0;
  }
  if (n) memcpy(dst, r->p, n);
  r->p += n;
  r->left -= n;
  return 1;
}

/* A length prefix whose n elements of elem bytes each fit the bytes left (in 64 bits:
 * no wrap). */
static int take_count(reader *r, const field *f, uint64_t elem, uint32_t *n) {
  if (!take(r, f, n, 4)) return 0;
  if ((uint64_t)*n * elem > r->left) {
    snprintf(r->why, r->why_size,
             "%s: length %u (%llu bytes) but only %zu bytes are left in the %zu-byte message",
             f->name, (unsigned)*n, (unsigned long long)((uint64_t)*n * elem), r->left, r->total);
    return 0;
  }
  return 1;
}

/* n bytes already checked to be there, passed over (a decode that only sizes). */
static int skip(reader *r, size_t n) {
  r->p += n;
  r->left -= n;
  return 0;
}

static void *grow(ss_msg_scratch *s, int slot, size_t bytes) {
  if (bytes == 0) bytes = 1;
  if (bytes > s->cap[slot]) {
    void *d = realloc(s->data[slot], bytes);
    if (d == NULL) return NULL;
    s->data[slot] = d;
    s->cap[slot] = bytes;
  }
  return s->data[slot];
}

static int nomem(reader *r, const field *f) {
  snprintf(r->why, r->why_size, "%s: out of memory", f->name);
  return SS_MSG_E_NOMEM;
}

static int take_field(reader *r, const field *f, void *view, ss_msg_scratch *s) {
  uint32_t n = 0;
  switch (f->kind) {
  case K_U32: return take(r, f, AT(view, f, void), 4 * (size_t)f->lanes) ? 0 : SS_MSG_E_MALFORMED;
  case K_STAMP: {
    uint32_t *t = AT(view, f, uint32_t);
    if (!take(r, f, t, 8)) return SS_MSG_E_MALFORMED;
    if (t[1] < 1000000000u) return 0;
    snprintf(r->why, r->why_size, "%s: nsec %u is not below 1e9", f->name, (unsigned)t[1]);
    return SS_MSG_E_MALFORMED;
  }
  case K_F64: return take(r, f, AT(view, f, void), 8 * (size_t)f->lanes) ? 0 : SS_MSG_E_MALFORMED;
  case K_BOOL: {
    uint8_t b = 0;
    if (!take(r, f, &b, 1)) return SS_MSG_E_MALFORMED;
    *AT(view, f, int) = b != 0;
    return 0;
  }
  case K_STR_FIXED: {
    if (!take_count(r, f, 1, &n)) return SS_MSG_E_MALFORMED;
    if (n >= f->cap) {
      snprintf(r->why, r->why_size, "%s too long (%u bytes, at most %zu)", f->name, (unsigned)n,
               f->cap - 1);
      return SS_MSG_E_MALFORMED;
    }
    char *d = AT(view, f, char);
    take(r, f, d, n);
    d[n] = '\0';
    return 0;
  }
  case K_STR: {
    if (!take_count(r, f, 1, &n)) return SS_MSG_E_MALFORMED;
    if (s == NULL) return skip(r, n);
    char *d = grow(s, f->slot, (size_t)n + 1);
    if (d == NULL) return nomem(r, f);
    take(r, f, d, n);
    d[n] = '\0';
    *AT(view, f, const char *) = d;
    return 0;
  }
  case K_ARR_STR: {
    if (!take_count(r, f, 4, &n)) return SS_MSG_E_MALFORMED;
    reader look = *r; /* sized first: the pointers, then every string with its NUL */
    size_t bytes = (size_t)n * sizeof(char *);
    for (uint32_t i = 0; i < n; i++) {
      uint32_t k = 0;
      if (!take_count(&look, f, 1, &k)) return SS_MSG_E_MALFORMED;
      look.p += k;
      look.left -= k;
      bytes += (size_t)k + 1;
    }
    COUNT(view, f) = n;
    if (s == NULL) return skip(r, (size_t)(look.p - r->p));
    char **ptr = grow(s, f->slot, bytes);
    if (ptr == NULL) return nomem(r, f);
    char *chars = (char *)(ptr + n);
    for (uint32_t i = 0; i < n; i++) {
      uint32_t k = 0;
      take(r, f, &k, 4);
      take(r, f, chars, k);
      chars[k] = '\0';
      ptr[i] = chars;
      chars += (size_t)k + 1;
    }
    *AT(view, f, const char *const *) = (const char *const *)ptr;
    return 0;
  }
  case K_ARR_PTS: {
    if (!take_count(r, f, 24, &n)) return SS_MSG_E_MALFORMED;
    COUNT(view, f) = n;
    if (s == NULL) return skip(r, (size_t)n * 24);
    float *d = grow(s, f->slot, (size_t)n * 3 * sizeof(float));
    if (d == NULL) return nomem(r, f);
    for (size_t i = 0; i < 3 * (size_t)n; i++) {
      double v = 0.0;
      take(r, f, &v, 8);
      d[i] = (float)v;
    }
    *AT(view, f, const float *) = d;
    return 0;
  }
  default: {
    size_t e = elem_bytes(f);
    if (!take_count(r, f, e, &n)) return SS_MSG_E_MALFORMED;
    COUNT(view, f) = n;
    if (s == NULL) return skip(r, (size_t)n * e);
    void *d = grow(s, f->slot, (size_t)n * e);
    if (d == NULL) return nomem(r, f);
    take(r, f, d, (size_t)n * e);
    *AT(view, f, const void *) = d;
    return 0;
  }
  }
}

int ss_msg_decode(int type, const uint8_t *buf, size_t len, void *view, ss_msg_scratch *scratch,
                  char *why, size_t why_size) {
  char dummy[1];
  if (why == NULL || why_size == 0) {
    why = dummy;
    why_size = sizeof dummy;
  }
  why[0] = '\0';
  if (type < 0 || type >= SS_MSG_TYPES || view == NULL ||
      (buf == NULL && len != 0)) {
    snprintf(why, why_size, "invalid argument");
    return SS_MSG_E_INVALID;
  }
  const msg_type *t = &types[type];
  memset(view, 0, t->view_size);
  reader r = {buf, len, len, why, why_size};
  for (size_t i = 0; i < t->nfields; i++) {
    int st = take_field(&r, &t->fields[i], view, scratch);
    if (st != 0) return st;
  }
  if (r.left != 0) {
    snprintf(why, why_size, "%zu bytes after the end of a %zu-byte %s", r.left, len, t->datatype);
    return SS_MSG_E_MALFORMED;
  }
  return SS_MSG_OK;
}
