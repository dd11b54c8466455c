/* The one table of simulation settings (include/skin_sim/ss_settings.h) and the
 * checks, parsing and formatting every user of a setting goes through.
 *
 * THE DEFAULTS LIVE HERE: ss_sim_default_settings() and
 * ss_mover_default_settings() fill their structs from this table. To change a
 * default, change its `def` below (one line), and the node, skinsim, the launch
 * file check and the manual's generated tables (bash scripts/doc_tables.sh) follow. */
#include "skin_sim/ss_settings.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "ss_err.h"

#define INF INFINITY
#define IMAX ((double)INT_MAX)
#define OFF(field) offsetof(ss_sim_settings, field)

static const char *const solver_choices[] = {"newton", "quasi-newton", NULL};
static const char *const method_choices[] = {"walk", "project", "nring", NULL};

/* name, cli, type, offset, default, min, max, min_open, max_open, unit, apply, in_key,
 * choices, help, scope */
static const ss_setting table[] = {
    {"solver", NULL, SS_SETTING_ENUM, OFF(solver), SS_SOLVER_QUASI_NEWTON, 0, 1, 0, 0, "",
     SS_APPLY_RECREATE, 1, solver_choices,
     "newton (projected Newton, a factorisation per iteration) or quasi-newton (L-BFGS on a "
     "matrix factored once per step)", SS_SCOPE_RUN},
    {"method", NULL, SS_SETTING_ENUM, OFF(mover.method), SS_METHOD_WALK, 0, 2, 0, 0, "",
     SS_APPLY_RECREATE, 1, method_choices,
     "how anchors move over the body: walk (2D ray tracing), project (closest point), nring", SS_SCOPE_RUN},
    {"rings", NULL, SS_SETTING_INT, OFF(mover.nring_rings), 2, 0, IMAX, 0, 0, "",
     SS_APPLY_RECREATE, 1, NULL, "vertex rings searched by the nring method", SS_SCOPE_RUN},
    {"walk_max_steps", "max-steps", SS_SETTING_INT, OFF(mover.walk_max_steps), 512, 0, IMAX, 0,
     0, "", SS_APPLY_RECREATE, 1, NULL, "bound on the edges one anchor walk crosses", SS_SCOPE_RUN},
    {"dt", NULL, SS_SETTING_DOUBLE, OFF(dt), 1.0 / 30.0, 0, INF, 1, 1, "s", SS_APPLY_STEP, 1,
     NULL, "frame time step when the caller gives none (the node and skinsim run use the input's)", SS_SCOPE_RUN},
    {"substeps", NULL, SS_SETTING_INT, OFF(substeps), 4, 1, 1000, 0, 0, "", SS_APPLY_STEP, 1,
     NULL, "implicit Euler steps per frame", SS_SCOPE_RUN},
    {"iterations", NULL, SS_SETTING_INT, OFF(iterations), 2, 0, IMAX, 0, 0, "", SS_APPLY_STEP, 1,
     NULL, "solver iterations per substep (the real-time budget)", SS_SCOPE_RUN},
    {"tol", NULL, SS_SETTING_DOUBLE, OFF(tol), 1e-4, 0, INF, 0, 0, "edge lengths", SS_APPLY_STEP,
     1, NULL, "convergence: largest vertex residual, in mean rest edge lengths", SS_SCOPE_RUN},
    {"safety_residual", "safety-residual", SS_SETTING_DOUBLE, OFF(safety_residual), 0.05, 0, INF,
     0, 1, "edge lengths", SS_APPLY_STEP, 1, NULL,
     "quasi-Newton: a substep still above this residual keeps iterating up to iterations_max; "
     "0 off", SS_SCOPE_RUN},
    {"iterations_max", "iterations-max", SS_SETTING_INT, OFF(iterations_max), 32, 0, IMAX, 0, 0,
     "", SS_APPLY_STEP, 1, NULL, "hard cap on iterations of a hard substep (safety_residual)", SS_SCOPE_RUN},
    {"lbfgs_history", "lbfgs-history", SS_SETTING_INT, OFF(lbfgs_history), 6, 1, 32, 0, 0, "",
     SS_APPLY_RECREATE, 1, NULL, "L-BFGS pairs kept (quasi-Newton)", SS_SCOPE_RUN},
    {"young", NULL, SS_SETTING_DOUBLE, OFF(young), 50.0, 0, INF, 0, 1, "N/m", SS_APPLY_REFACTOR, 1,
     NULL, "membrane Young's modulus times thickness",
     SS_SCOPE_MODEL},
    {"poisson", NULL, SS_SETTING_DOUBLE, OFF(poisson), 0.3, 0, 0.5, 0, 1, "", SS_APPLY_REFACTOR, 1,
     NULL, "membrane Poisson ratio",
     SS_SCOPE_MODEL},
    {"density", NULL, SS_SETTING_DOUBLE, OFF(density), 1.0, 0, INF, 1, 1, "kg/m^2",
     SS_APPLY_REFACTOR, 1, NULL, "skin mass per rest area",
     SS_SCOPE_MODEL},
    {"stiffness", NULL, SS_SETTING_DOUBLE, OFF(anchor_stiffness), 1e3, 0, INF, 0, 1, "N/m per m^2",
     SS_APPLY_REFACTOR, 1, NULL, "zero-length anchor springs, per rest area of skin",
     SS_SCOPE_MODEL},
    {"barycenters", NULL, SS_SETTING_BOOL, OFF(barycenter_anchors), 1, 0, 1, 0, 0, "",
     SS_APPLY_RECREATE, 1, NULL, "an anchor spring at every face barycenter too",
     SS_SCOPE_MODEL},
    {"bending", NULL, SS_SETTING_DOUBLE, OFF(bending), 0.0, 0, INF, 0, 1, "N m", SS_APPLY_REFACTOR,
     1, NULL, "hinge bending stiffness; 0 off (turning it on or off recreates the skin)",
     SS_SCOPE_MODEL},
    {"gravity", NULL, SS_SETTING_VEC3, OFF(gravity), 0.0, -INF, INF, 1, 1, "m/s^2",
     SS_APPLY_STEP, 1, NULL, "gravity vector 'x y z' (skinsim --gravity G: 0 0 -G)", SS_SCOPE_RUN},
    {"damping", NULL, SS_SETTING_DOUBLE, OFF(damping), 0.0, 0, INF, 0, 1, "1/s",
     SS_APPLY_REFACTOR, 1, NULL, "mass-proportional damping", SS_SCOPE_RUN},
    {"slide", NULL, SS_SETTING_DOUBLE, OFF(slide), 30.0 * 0.69314718055994530942, 0, INF, 0, 0,
     "1/s", SS_APPLY_STEP, 1, NULL,
     "how fast anchors follow the skin (time constant 1/slide); 0 glued, inf frictionless", SS_SCOPE_RUN},
    {"tether", NULL, SS_SETTING_DOUBLE, OFF(tether), 3.0, 0, INF, 0, 1, "1/s", SS_APPLY_STEP, 1,
     NULL, "rate at which anchors walk back home (connective tissue); next to home they are put "
     "back on their home face; 0 free sliding", SS_SCOPE_RUN},
    {"orient", NULL, SS_SETTING_DOUBLE, OFF(orient), 200.0, 0, INF, 0, 1, "N/m",
     SS_APPLY_REFACTOR, 1, NULL,
     "skin faces resist turning over against the body and vertices resist going under it "
     "(energy per m^2 of skin, as young); 0 off, the paper's skin",
     SS_SCOPE_MODEL},
    {"compression", NULL, SS_SETTING_DOUBLE, OFF(compression), 0.1, 0, 1, 1, 0, "",
     SS_APPLY_REFACTOR, 1, NULL,
     "membrane stiffness under compression, as a share of that in tension (skin wrinkles "
     "below an edge's scale); 1 the Stable Neo-Hookean membrane",
     SS_SCOPE_MODEL},
    {"collide", NULL, SS_SETTING_BOOL, OFF(collide), 0, 0, 1, 0, 0, "", SS_APPLY_STEP, 1, NULL,
     "skin vertices behind the body's clean surface around their anchor are moved out of it "
     "at the end of each step (not where the body passes through itself); false off",
     SS_SCOPE_RUN},
    {"collide_thickness", "collide-thickness", SS_SETTING_DOUBLE, OFF(collide_thickness), 0.0, 0,
     1, 0, 0, "edge lengths", SS_APPLY_STEP, 1, NULL,
     "distance collide keeps between skin and body, in mean rest edge lengths", SS_SCOPE_RUN},
    {"threads", NULL, SS_SETTING_INT, OFF(threads), 0, 0, 64, 0, 0, "", SS_APPLY_RECREATE, 0,
     NULL, "threads for energies and anchor walks; 0: all cores where they pay (the same bits "
     "for any count)", SS_SCOPE_RUN},
};

#define NSET ((int)(sizeof table / sizeof table[0]))

const ss_setting *ss_settings_table(int *count) {
  if (count) *count = NSET;
  return table;
}

const ss_setting *ss_setting_find(const char *name) {
  if (!name) return NULL;
  for (int i = 0; i < NSET; i++)
    if (strcmp(table[i].name, name) == 0) return &table[i];
  return NULL;
}

const char *ss_setting_cli(const ss_setting *d) { return d->cli ? d->cli : d->name; }

const ss_setting *ss_setting_find_cli(const char *flag) {
  if (!flag) return NULL;
  if (strncmp(flag, "--", 2) == 0) flag += 2;
  for (int i = 0; i < NSET; i++)
    if (ss_setting_cli(&table[i])[0] && strcmp(ss_setting_cli(&table[i]), flag) == 0)
      return &table[i];
  return NULL;
}

/* ---- access ---------------------------------------------------------------- */

static int ncomp(const ss_setting *d) { return d->type == SS_SETTING_VEC3 ? 3 : 1; }

double ss_setting_get(const ss_setting *d, const ss_sim_settings *s, int i) {
  const char *p = (const char *)s + d->offset;
  if (d->type == SS_SETTING_DOUBLE || d->type == SS_SETTING_VEC3) {
    double v;
    memcpy(&v, p + sizeof(double) * (size_t)(d->type == SS_SETTING_VEC3 ? i : 0), sizeof v);
    return v;
  }
  int v;
  memcpy(&v, p, sizeof v);
  return (double)v;
}

void ss_setting_set(const ss_setting *d, ss_sim_settings *s, int i, double v) {
  char *p = (char *)s + d->offset;
  if (d->type == SS_SETTING_DOUBLE || d->type == SS_SETTING_VEC3) {
    memcpy(p + sizeof(double) * (size_t)(d->type == SS_SETTING_VEC3 ? i : 0), &v, sizeof v);
  } else {
    int iv = (int)v;
    memcpy(p, &iv, sizeof iv);
  }
}

int ss_setting_equal(const ss_setting *d, const ss_sim_settings *a, const ss_sim_settings *b) {
  size_t n = (d->type == SS_SETTING_DOUBLE || d->type == SS_SETTING_VEC3)
                 ? sizeof(double) * (size_t)ncomp(d)
                 : sizeof(int);
  return memcmp((const char *)a + d->offset, (const char *)b + d->offset, n) == 0;
}

/* ---- text ------------------------------------------------------------------ */

static void fmt_num(double v, char *buf, size_t size) {
  if (isinf(v)) snprintf(buf, size, "%sinf", v < 0 ? "-" : "");
  else if (v == floor(v) && fabs(v) < 1e15) snprintf(buf, size, "%.0f", v); /* 1000, not 1e+03 */
  else snprintf(buf, size, "%.17g", v);
  /* else the shortest text that reads back to the same bits */
  for (int prec = 1; prec < 17 && isfinite(v) && v != floor(v); prec++) {
    char t[64];
    snprintf(t, sizeof t, "%.*g", prec, v);
    if (strtod(t, NULL) == v) {
      snprintf(buf, size, "%s", t);
      break;
    }
  }
}

static void fmt_value(const ss_setting *d, double v, char *buf, size_t size) {
  switch (d->type) {
  case SS_SETTING_ENUM: {
    int k = (int)v;
    snprintf(buf, size, "%s", (k >= 0 && k <= (int)d->max) ? d->choices[k] : "?");
    break;
  }
  case SS_SETTING_BOOL: snprintf(buf, size, "%s", v != 0.0 ? "true" : "false"); break;
  case SS_SETTING_INT: snprintf(buf, size, "%d", (int)v); break;
  default: fmt_num(v, buf, size); break;
  }
}

void ss_setting_format(const ss_setting *d, const ss_sim_settings *s, char *buf, size_t size) {
  if (!size) return;
  if (d->type != SS_SETTING_VEC3) {
    fmt_value(d, ss_setting_get(d, s, 0), buf, size);
    return;
  }
  char c[3][40];
  for (int i = 0; i < 3; i++) fmt_num(ss_setting_get(d, s, i), c[i], sizeof c[i]);
  snprintf(buf, size, "%s %s %s", c[0], c[1], c[2]);
}

void ss_setting_format_default(const ss_setting *d, char *buf, size_t size) {
  if (!size) return;
  if (d->type != SS_SETTING_VEC3) {
    fmt_value(d, d->def, buf, size);
    return;
  }
  char c[40];
  fmt_num(d->def, c, sizeof c);
  snprintf(buf, size, "%s %s %s", c, c, c);
}

void ss_setting_format_range(const ss_setting *d, char *buf, size_t size) {
  if (!size) return;
  if (d->type == SS_SETTING_ENUM) {
    size_t n = 0;
    buf[0] = '\0';
    for (int k = 0; d->choices[k] && n < size; k++)
      n += (size_t)snprintf(buf + n, size - n, "%s%s", k ? ", " : "", d->choices[k]);
    return;
  }
  if (d->type == SS_SETTING_BOOL) {
    snprintf(buf, size, "true, false");
    return;
  }
  ss_range_format(d->min, d->min_open, d->max, d->max_open, buf, size);
}

void ss_range_format(double min, int min_open, double max, int max_open, char *buf, size_t size) {
  if (!size) return;
  if (min == -INFINITY && max == INFINITY && min_open && max_open) {
    snprintf(buf, size, "finite");
    return;
  }
  char lo[40], hi[40];
  fmt_num(min, lo, sizeof lo);
  fmt_num(max, hi, sizeof hi);
  snprintf(buf, size, "%c%s, %s%c", min_open ? '(' : '[', lo, hi, max_open ? ')' : ']');
}

/* ---- checks ---------------------------------------------------------------- */

int ss_range_contains(double v, double min, int min_open, double max, int max_open) {
  if (isnan(v)) return 0;
  if (min_open ? !(v > min) : !(v >= min)) return 0;
  if (max_open ? !(v < max) : !(v <= max)) return 0;
  return 1;
}

int ss_setting_check(const ss_setting *d, const ss_sim_settings *s, char *err, int err_sz) {
  for (int i = 0; i < ncomp(d); i++) {
    double v = ss_setting_get(d, s, i);
    if (ss_range_contains(v, d->min, d->min_open, d->max, d->max_open)) continue;
    char range[160], got[40];
    ss_setting_format_range(d, range, sizeof range);
    fmt_num(v, got, sizeof got);
    if (d->type == SS_SETTING_ENUM)
      return ss_fail(err, err_sz, SS_E_ARG, "unknown %s %s (expected %s)", d->name, got, range);
    if (d->type == SS_SETTING_VEC3)
      return ss_fail(err, err_sz, SS_E_ARG, "%s must be finite (component %c is %s)", d->name,
                     "xyz"[i], got);
    return ss_fail(err, err_sz, SS_E_ARG, "%s must be in %s%s%s (got %s)", d->name, range,
                   d->unit[0] ? " " : "", d->unit, got);
  }
  return SS_OK;
}

int ss_settings_check(const ss_sim_settings *s, char *err, int err_sz) {
  if (!s) return ss_fail(err, err_sz, SS_E_ARG, "settings are NULL");
  for (int i = 0; i < NSET; i++) {
    int status = ss_setting_check(&table[i], s, err, err_sz);
    if (status) return status;
  }
  return SS_OK;
}

static int parse_double(const char *text, double *out) {
  char *end = NULL;
  errno = 0;
  double v = strtod(text, &end);
  if (end == text || errno == ERANGE) return -1;
  while (*end == ' ' || *end == '\t') end++;
  if (*end) return -1;
  *out = v;
  return 0;
}

int ss_setting_parse(const ss_setting *d, const char *text, ss_sim_settings *s, char *err,
                     int err_sz) {
  if (!d || !s) return ss_fail(err, err_sz, SS_E_ARG, "setting or settings are NULL");
  if (!text) text = "";
  ss_sim_settings t = *s;
  switch (d->type) {
  case SS_SETTING_ENUM: {
    int k = 0;
    while (d->choices[k] && strcmp(d->choices[k], text) != 0) k++;
    if (!d->choices[k]) {
      char range[160];
      ss_setting_format_range(d, range, sizeof range);
      return ss_fail(err, err_sz, SS_E_ARG, "%s expects %s, got '%s'", d->name, range, text);
    }
    ss_setting_set(d, &t, 0, k);
    break;
  }
  case SS_SETTING_BOOL: {
    int b = -1;
    if (!strcasecmp(text, "true") || !strcmp(text, "1")) b = 1;
    if (!strcasecmp(text, "false") || !strcmp(text, "0")) b = 0;
    if (b < 0)
      return ss_fail(err, err_sz, SS_E_ARG, "%s expects true or false, got '%s'", d->name, text);
    ss_setting_set(d, &t, 0, b);
    break;
  }
  case SS_SETTING_INT: {
    char *end = NULL;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (!*text || *end || errno || v < INT_MIN || v > INT_MAX) {
      char range[80];
      ss_setting_format_range(d, range, sizeof range);
      return ss_fail(err, err_sz, SS_E_ARG, "%s expects a whole number in %s, got '%s'", d->name,
                     range, text);
    }
    ss_setting_set(d, &t, 0, (double)v);
    break;
  }
  case SS_SETTING_DOUBLE: {
    double v;
    if (parse_double(text, &v)) {
      char range[80];
      ss_setting_format_range(d, range, sizeof range);
      return ss_fail(err, err_sz, SS_E_ARG, "%s expects a number in %s, got '%s'", d->name, range,
                     text);
    }
    ss_setting_set(d, &t, 0, v);
    break;
  }
  case SS_SETTING_VEC3: {
    double v[3];
    int used = 0;
    char tail = 0;
    if (sscanf(text, "%lf %lf %lf %n%c", &v[0], &v[1], &v[2], &used, &tail) != 3)
      return ss_fail(err, err_sz, SS_E_ARG, "%s expects three numbers 'x y z' (%s), got '%s'",
                     d->name, d->unit, text);
    for (int i = 0; i < 3; i++) ss_setting_set(d, &t, i, v[i]);
    break;
  }
  default: return ss_fail(err, err_sz, SS_E_ARG, "%s: unknown setting type", d->name);
  }
  int status = ss_setting_check(d, &t, err, err_sz);
  if (status) return status;
  *s = t;
  return SS_OK;
}

/* ---- defaults ---------------------------------------------------------------- */

ss_sim_settings ss_sim_default_settings(void) {
  ss_sim_settings s;
  memset(&s, 0, sizeof s);
  for (int i = 0; i < NSET; i++)
    for (int c = 0; c < ncomp(&table[i]); c++) ss_setting_set(&table[i], &s, c, table[i].def);
  s.face_mask = NULL;
  return s;
}

ss_mover_settings ss_mover_default_settings(void) { return ss_sim_default_settings().mover; }
