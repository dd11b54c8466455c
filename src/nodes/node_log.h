/* Throttled logging for the skin_sim nodes: at most one line per period per call
 * site (or per ss_throttle the caller keeps, e.g. one per kind of problem), and the
 * line that goes out says how many were held back. The count is the node library's
 * (src/stream/ss_throttle.h); rosc only hands the finished line to rosconsole.
 * Header-only (static functions), included by the nodes' .c files. */
#ifndef SKIN_SIM_NODE_LOG_H
#define SKIN_SIM_NODE_LOG_H

#include "rosc/rosc.h"
#include "ss_throttle.h"

#include <stdarg.h>
#include <stdio.h>

/* Logs fmt at level through th (period_s apart at most), with the caller's place.
 * ROSC_OK also when the line was held back. */
static inline int node_log_throttled(ss_throttle *th, int level, const char *file, int line,
                                     const char *func, double period_s, const char *fmt, ...)
    ROSC_PRINTF(7, 8);
static inline int node_log_throttled(ss_throttle *th, int level, const char *file, int line,
                                     const char *func, double period_s, const char *fmt, ...)
{
  uint64_t held = 0;
  if (fmt == NULL) return ROSC_E_INVALID;
  if (!ss_throttle_pass(th, ss_throttle_now_s(), period_s, &held)) return ROSC_OK;
  char text[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  if (held == 0) return rosc_log_at(level, file, line, func, "%s", text);
  return rosc_log_at(level, file, line, func, "%s (%llu similar messages held back)", text,
                     (unsigned long long)held);
}

/* Throttled per call site (a static throttle each; a statement). */
#define NODE_LOG_THROTTLE(level, period_s, ...) \
  do { \
    static ss_throttle node_th_ = SS_THROTTLE_INIT; \
    node_log_throttled(&node_th_, (level), __FILE__, __LINE__, __func__, (period_s), __VA_ARGS__); \
  } while (0)
#define NODE_WARN_THROTTLE(period_s, ...) NODE_LOG_THROTTLE(ROSC_LOG_WARN, period_s, __VA_ARGS__)
#define NODE_ERROR_THROTTLE(period_s, ...) NODE_LOG_THROTTLE(ROSC_LOG_ERROR, period_s, __VA_ARGS__)
/* Throttled through a throttle the caller keeps. */
#define NODE_LOG_EVERY(th, level, period_s, ...) \
  node_log_throttled((th), (level), __FILE__, __LINE__, __func__, (period_s), __VA_ARGS__)

#endif
