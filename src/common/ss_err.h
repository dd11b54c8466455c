/* Internal: writing the one-sentence error message of a failing core call. */
#ifndef SKIN_SIM_SS_ERR_H
#define SKIN_SIM_SS_ERR_H

#include <stdarg.h>
#include <stdio.h>

/* Formats into err (if non-NULL and err_sz > 0) and returns status, so that
 * failures read `return ss_fail(err, err_sz, SS_E_MESH, "face %d ...", f);`. */
static inline int ss_fail(char *err, int err_sz, int status, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static inline int ss_fail(char *err, int err_sz, int status, const char *fmt, ...) {
  if (err && err_sz > 0) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, (size_t)err_sz, fmt, ap);
    va_end(ap);
  }
  return status;
}

#endif
