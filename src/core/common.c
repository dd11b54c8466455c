/* Status strings, method names and the clock shared by the core. */
#include "skin_sim/ss_common.h"

#include <string.h>
#include <time.h>

const char *ss_status_string(int status) {
  switch (status) {
    case SS_OK: return "ok";
    case SS_E_ARG: return "invalid argument";
    case SS_E_NOMEM: return "out of memory";
    case SS_E_MESH: return "malformed mesh";
    case SS_E_NONFINITE: return "non-finite value (NaN or Inf)";
    case SS_E_SOLVER: return "linear solver failure";
    case SS_E_IO: return "file input/output error";
    case SS_E_UNSUPPORTED: return "not supported by this build";
    default: return "unknown status";
  }
}

static const char *const method_names[] = {"walk", "project", "nring"};

const char *ss_method_name(int method) {
  if (method < 0 || method > SS_METHOD_NRING) return NULL;
  return method_names[method];
}

int ss_method_parse(const char *name) {
  if (!name) return -1;
  for (int i = 0; i <= SS_METHOD_NRING; i++)
    if (strcmp(name, method_names[i]) == 0) return i;
  return -1;
}

double ss_now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}
