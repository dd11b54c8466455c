/* skin_sim core: status codes and small shared definitions.
 *
 * Every core function that can fail returns an int status: 0 (SS_OK) on
 * success, a negative SS_E_* code on error. Functions that take user input and
 * can fail also take (char *err, int err_sz): on error they write one sentence
 * naming the problem there (err may be NULL). The core never prints and never
 * exits; callers decide what to do. */
#ifndef SKIN_SIM_SS_COMMON_H
#define SKIN_SIM_SS_COMMON_H

#ifdef __cplusplus
extern "C" {
#endif

enum ss_status {
  SS_OK = 0,
  SS_E_ARG = -1,         /* an argument makes no sense (NULL, negative count, unknown name) */
  SS_E_NOMEM = -2,       /* allocation failed */
  SS_E_MESH = -3,        /* malformed mesh: no triangles, index out of range */
  SS_E_NONFINITE = -4,   /* NaN or Inf in input */
  SS_E_SOLVER = -5,      /* the linear solver failed (CHOLMOD error) */
  SS_E_IO = -6,          /* a file could not be read or written */
  SS_E_UNSUPPORTED = -7  /* a feature not available in this build */
};

/* A short English name of a status code, e.g. "malformed mesh". Never NULL. */
const char *ss_status_string(int status);

/* How an anchor is moved across the body surface (doc/model.md, "Anchor update"). */
enum ss_method {
  SS_METHOD_WALK = 0,    /* the paper: 2D ray tracing face to face */
  SS_METHOD_PROJECT = 1, /* "projection springs": Euclidean closest point on the whole body */
  SS_METHOD_NRING = 2    /* closest point among faces within N rings of the anchor's face */
};

/* Monotonic wall clock in milliseconds (for timings; never asserted in tests). */
double ss_now_ms(void);

/* "walk", "project", "nring"; NULL for an unknown value. */
const char *ss_method_name(int method);
/* Parses a method name; returns the ss_method or -1 if unknown. */
int ss_method_parse(const char *name);

#ifdef __cplusplus
}
#endif
#endif
