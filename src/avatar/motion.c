/* Joint motions: the mannequin's scripted motions as functions of time, and
 * motion tables read from and written to a small CSV format (see
 * ssa_avatar.h), sampled by linear interpolation. */
#include <errno.h>
#include <strings.h>

#include "skin_sim/ssa_avatar.h"
#include "ssa_util.h"

#define NBUILTIN 5
#define SWEEP 4
static const char *builtin_names[NBUILTIN] = {"arms", "elbows", "twist", "all", "sweep"};
static const double builtin_period[NBUILTIN] = {4.0, 3.0, 3.0, 12.0, 4.0};

int ssa_motion_builtin_count(void) { return NBUILTIN; }

const char *ssa_motion_builtin_name(int i) {
  return i >= 0 && i < NBUILTIN ? builtin_names[i] : NULL;
}

int ssa_motion_builtin_index(const char *name) {
  if (!name) return -1;
  for (int i = 0; i < NBUILTIN; i++)
    if (strcmp(name, builtin_names[i]) == 0) return i;
  return -1;
}

double ssa_motion_builtin_period(int i) { return i >= 0 && i < NBUILTIN ? builtin_period[i] : 0.0; }

static void put(const ssa_robot *r, double *q, const char *name, double v) {
  int j = ssa_robot_joint_index(r, name);
  if (j >= 0) q[j] = v;
}

/* The joints each built-in motion moves (arms, elbows, twist; all: every one). */
static const char *const builtin_joints[] = {"l_shoulder_abduct", "r_shoulder_abduct", "l_elbow",
                                             "r_elbow", "torso_twist", "neck_twist", "head_nod"};

/* sweep moves every joint a robot has that moves on its own (not fixed, not a mimic). */
static int sweeps(const ssa_robot *r, int j) {
  int t = r->joint_type[j];
  return r->joint_mimic[j] < 0 &&
         (t == SSA_JOINT_REVOLUTE || t == SSA_JOINT_CONTINUOUS || t == SSA_JOINT_PRISMATIC);
}

int ssa_motion_builtin_coverage(int i, const ssa_robot *robot) {
  if (i < 0 || i >= NBUILTIN || !robot) return 0;
  if (i == SWEEP) {
    int n = 0;
    for (int j = 0; j < robot->njoint; j++) n += sweeps(robot, j);
    return n;
  }
  int first = 0, last = 7; /* all */
  if (i == 0) last = 2;
  if (i == 1) last = 4; /* elbows also holds the shoulders */
  if (i == 2) first = 4;
  int n = 0;
  for (int k = first; k < last; k++) n += ssa_robot_joint_index(robot, builtin_joints[k]) >= 0;
  return n;
}

/* Smooth 0 -> 1 -> 0 over one period (raised cosine). */
static double bump(double t, double period) { return 0.5 - 0.5 * cos(2.0 * SSA_PI * t / period); }

int ssa_motion_builtin_eval(int i, double t, const ssa_robot *robot, double *q) {
  if (i < 0 || i >= NBUILTIN || !robot || !q || !isfinite(t)) return SS_E_ARG;
  memset(q, 0, sizeof(double) * (size_t)robot->njoint);
  if (i == SWEEP) {
    /* any robot: each joint swings about zero, 0.6 rad (or 3 cm) each way, in a
     * phase of its own, within its limits; eased in over the first second */
    double ease = t <= 0.0 ? 0.0 : t >= 1.0 ? 1.0 : bump(0.5 * t, 1.0);
    for (int j = 0; j < robot->njoint; j++) {
      if (!sweeps(robot, j)) continue;
      double amp = robot->joint_type[j] == SSA_JOINT_PRISMATIC ? 0.03 : 0.6;
      double v = ease * amp * sin(2.0 * SSA_PI * t / builtin_period[SWEEP] + 0.9 * j);
      if (robot->joint_has_limits[j]) {
        double lo = robot->joint_lower[j], hi = robot->joint_upper[j], m = 0.02 * (hi - lo);
        v = v < lo + m ? lo + m : v > hi - m ? hi - m : v;
      }
      q[j] = v;
    }
    return SS_OK;
  }
  int arms = i == 0 || i == 3, elbows = i == 1 || i == 3, twist = i == 2 || i == 3;
  if (arms) {
    /* from the T pose (0) down past hanging (1.57) into the torso (1.75) and back */
    double a = 1.75 * bump(t, 4.0);
    put(robot, q, "l_shoulder_abduct", a);
    put(robot, q, "r_shoulder_abduct", a);
  } else if (elbows) {
    put(robot, q, "l_shoulder_abduct", 0.35);
    put(robot, q, "r_shoulder_abduct", 0.35);
  }
  if (elbows) {
    /* deep bends, the two arms half a period apart */
    put(robot, q, "l_elbow", 2.5 * bump(t, 3.0));
    put(robot, q, "r_elbow", 2.5 * bump(t + 1.5, 3.0));
  }
  if (twist) {
    double w = 2.0 * SSA_PI * t / 3.0;
    put(robot, q, "torso_twist", 0.8 * sin(w));
    put(robot, q, "neck_twist", -0.9 * sin(w + 0.6));
    put(robot, q, "head_nod", 0.3 * sin(2 * w));
  }
  return SS_OK;
}

/* ---------------------------------------------------------------- tables */

void ssa_motion_destroy(ssa_motion *m) {
  if (!m) return;
  ssa_free_strs(m->joint_name, m->njoint);
  free(m->time);
  free(m->value);
  free(m);
}

static char *trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
    s[--n] = '\0';
  return s;
}

static int count_fields(const char *s) {
  int n = 1;
  for (; *s; s++) n += *s == ',';
  return n;
}

int ssa_motion_read_csv(ssa_motion **out, const char *path, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  if (!path) return ss_fail(err, err_sz, SS_E_ARG, "no motion file given");
  char *text = ssa_read_text_file(path, "motion file", err, err_sz);
  if (!text) return SS_E_IO;
  ssa_motion *m = calloc(1, sizeof *m);
  int st = SS_OK, line_no = 0, cap = 0;
  if (!m) st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", path);
  char *save = NULL;
  int header = 0;
  for (char *line = text; st == SS_OK && line; line = save) {
    char *nl = strchr(line, '\n');
    save = nl ? nl + 1 : NULL;
    if (nl) *nl = '\0';
    line_no++;
    char *s = trim(line);
    if (!*s || *s == '#') continue;
    int nf = count_fields(s);
    if (!header) {
      if (nf < 2) {
        st = ss_fail(err, err_sz, SS_E_ARG,
                     "motion file '%s', line %d: the header needs a time column and at least one joint",
                     path, line_no);
        break;
      }
      m->njoint = nf - 1;
      m->joint_name = calloc((size_t)m->njoint, sizeof(char *));
      if (!m->joint_name) {
        st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", path);
        break;
      }
      char *p = s;
      for (int k = 0; k < nf; k++) {
        char *c = strchr(p, ',');
        if (c) *c = '\0';
        char *name = trim(p);
        if (k == 0 && strcasecmp(name, "time") != 0) {
          st = ss_fail(err, err_sz, SS_E_ARG,
                       "motion file '%s', line %d: the first column must be 'time' (seconds), "
                       "not '%s'", path, line_no, name);
          break;
        }
        if (k > 0) {
          if (!*name) {
            st = ss_fail(err, err_sz, SS_E_ARG, "motion file '%s', line %d: column %d has no joint name",
                         path, line_no, k + 1);
            break;
          }
          for (int e = 0; e < k - 1; e++)
            if (strcmp(m->joint_name[e], name) == 0) { /* one of the two would silently win */
              st = ss_fail(err, err_sz, SS_E_ARG, "motion file '%s', line %d: columns %d and %d "
                           "both name joint '%s'", path, line_no, e + 2, k + 1, name);
              break;
            }
          if (st != SS_OK) break;
          if (!(m->joint_name[k - 1] = ssa_strdup(name))) {
            st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", path);
            break;
          }
        }
        p = c ? c + 1 : p + strlen(p);
      }
      header = 1;
      continue;
    }
    if (nf != m->njoint + 1) {
      st = ss_fail(err, err_sz, SS_E_ARG,
                   "motion file '%s', line %d: %d columns where the header has %d", path, line_no,
                   nf, m->njoint + 1);
      break;
    }
    if (m->nframe == cap) {
      int nc = cap ? 2 * cap : 64;
      double *nt = realloc(m->time, sizeof(double) * (size_t)nc);
      if (nt) m->time = nt;
      double *nv = realloc(m->value, sizeof(double) * (size_t)nc * (size_t)m->njoint);
      if (nv) m->value = nv;
      if (!nt || !nv) {
        st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", path);
        break;
      }
      cap = nc;
    }
    char *p = s;
    for (int k = 0; k < nf; k++) {
      char *c = strchr(p, ',');
      if (c) *c = '\0';
      char *field = trim(p), *end = NULL;
      errno = 0;
      double v = strtod(field, &end);
      if (!*field || *trim(end) || errno == ERANGE || !isfinite(v)) {
        st = ss_fail(err, err_sz, SS_E_ARG, "motion file '%s', line %d, column %d: '%s' is not a finite number",
                     path, line_no, k + 1, field);
        break;
      }
      if (k == 0)
        m->time[m->nframe] = v;
      else
        m->value[(size_t)m->nframe * (size_t)m->njoint + (size_t)(k - 1)] = v;
      p = c ? c + 1 : p + strlen(p);
    }
    if (st != SS_OK) break;
    if (!(fabs(m->time[m->nframe]) <= SSA_MOTION_MAX_S)) {
      st = ss_fail(err, err_sz, SS_E_ARG,
                   "motion file '%s', line %d, column 1 (time): %g s is past the bound of %g s: "
                   "absolute stamps (seconds since 1970) or milliseconds? times are seconds from "
                   "the motion's start", path, line_no, m->time[m->nframe], SSA_MOTION_MAX_S);
      break;
    }
    if (m->nframe > 0 && !(m->time[m->nframe] > m->time[m->nframe - 1])) {
      st = ss_fail(err, err_sz, SS_E_ARG, "motion file '%s', line %d: time %g does not increase",
                   path, line_no, m->time[m->nframe]);
      break;
    }
    m->nframe++;
  }
  free(text);
  if (st == SS_OK && !header)
    st = ss_fail(err, err_sz, SS_E_ARG, "motion file '%s' has no header row", path);
  if (st == SS_OK && m->nframe == 0)
    st = ss_fail(err, err_sz, SS_E_ARG, "motion file '%s' has no rows of values", path);
  if (st != SS_OK) {
    ssa_motion_destroy(m);
    return st;
  }
  *out = m;
  return SS_OK;
}

int ssa_motion_write_csv(const ssa_motion *m, const char *path, char *err, int err_sz) {
  if (!m || !path) return ss_fail(err, err_sz, SS_E_ARG, "no motion or file given");
  FILE *f = fopen(path, "w");
  if (!f)
    return ss_fail(err, err_sz, SS_E_IO, "motion file '%s' cannot be written: %s", path,
                   strerror(errno));
  fprintf(f, "time");
  for (int j = 0; j < m->njoint; j++) fprintf(f, ",%s", m->joint_name[j]);
  fprintf(f, "\n");
  for (int i = 0; i < m->nframe; i++) {
    fprintf(f, "%.17g", m->time[i]);
    for (int j = 0; j < m->njoint; j++)
      fprintf(f, ",%.17g", m->value[(size_t)i * (size_t)m->njoint + (size_t)j]);
    fprintf(f, "\n");
  }
  int bad = ferror(f);
  if (fclose(f) != 0 || bad)
    return ss_fail(err, err_sz, SS_E_IO, "motion file '%s' could not be written completely", path);
  return SS_OK;
}

int ssa_motion_from_builtin(ssa_motion **out, int i, const ssa_robot *robot, double duration,
                            int nframe, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  if (i < 0 || i >= NBUILTIN || !robot || nframe < 2 || !(duration > 0))
    return ss_fail(err, err_sz, SS_E_ARG, "motion: bad built-in motion, robot, duration or frame count");
  ssa_motion *m = calloc(1, sizeof *m);
  int n = 0;
  for (int j = 0; j < robot->njoint; j++)
    n += robot->joint_type[j] != SSA_JOINT_FIXED && robot->joint_type[j] != SSA_JOINT_UNSUPPORTED &&
         robot->joint_mimic[j] < 0;
  double *q = calloc((size_t)(robot->njoint > 0 ? robot->njoint : 1), sizeof(double));
  if (m) {
    m->njoint = n;
    m->nframe = nframe;
    m->joint_name = calloc((size_t)(n > 0 ? n : 1), sizeof(char *));
    m->time = malloc(sizeof(double) * (size_t)nframe);
    m->value = malloc(sizeof(double) * (size_t)nframe * (size_t)(n > 0 ? n : 1));
  }
  if (!m || !q || !m->joint_name || !m->time || !m->value) {
    free(q);
    ssa_motion_destroy(m);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for a motion");
  }
  int k = 0;
  for (int j = 0; j < robot->njoint; j++)
    if (robot->joint_type[j] != SSA_JOINT_FIXED && robot->joint_type[j] != SSA_JOINT_UNSUPPORTED &&
        robot->joint_mimic[j] < 0)
      m->joint_name[k++] = ssa_strdup(robot->joint_name[j]);
  for (int f = 0; f < nframe; f++) {
    double t = duration * f / (nframe - 1);
    m->time[f] = t;
    ssa_motion_builtin_eval(i, t, robot, q);
    k = 0;
    for (int j = 0; j < robot->njoint; j++)
      if (robot->joint_type[j] != SSA_JOINT_FIXED && robot->joint_type[j] != SSA_JOINT_UNSUPPORTED &&
          robot->joint_mimic[j] < 0)
        m->value[(size_t)f * (size_t)n + (size_t)k++] = q[j];
  }
  free(q);
  for (int j = 0; j < n; j++)
    if (!m->joint_name[j]) {
      ssa_motion_destroy(m);
      return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for a motion");
    }
  *out = m;
  return SS_OK;
}

int ssa_motion_bind(const ssa_motion *m, const ssa_robot *robot, int *map, char *err, int err_sz) {
  if (!m || !robot || !map) return ss_fail(err, err_sz, SS_E_ARG, "motion: missing arguments");
  for (int k = 0; k < m->njoint; k++) {
    map[k] = ssa_robot_joint_index(robot, m->joint_name[k]);
    if (map[k] < 0)
      return ss_fail(err, err_sz, SS_E_ARG, "motion column '%s' names no joint of robot '%s'",
                     m->joint_name[k], robot->name);
  }
  return SS_OK;
}

void ssa_motion_sample(const ssa_motion *m, const int *map, double t, double *q) {
  if (!m || !map || !q || m->nframe <= 0) return;
  int a = 0, b = 0;
  double u = 0.0;
  if (!(t > m->time[0])) {
    a = b = 0;
  } else if (t >= m->time[m->nframe - 1]) {
    a = b = m->nframe - 1;
  } else {
    int lo = 0, hi = m->nframe - 1; /* time[lo] <= t < time[hi] */
    while (hi - lo > 1) {
      int mid = (lo + hi) / 2;
      if (m->time[mid] <= t)
        lo = mid;
      else
        hi = mid;
    }
    a = lo;
    b = hi;
    u = (t - m->time[a]) / (m->time[b] - m->time[a]);
  }
  for (int k = 0; k < m->njoint; k++) {
    double va = m->value[(size_t)a * (size_t)m->njoint + (size_t)k];
    double vb = m->value[(size_t)b * (size_t)m->njoint + (size_t)k];
    if (map[k] >= 0) q[map[k]] = a == b ? va : (1 - u) * va + u * vb;
  }
}

int ssa_motion_check_limits(const ssa_motion *m, const int *map, const ssa_robot *robot,
                            char *msg, int msg_sz) {
  if (!m || !map || !robot) return 0;
  int count = 0, joints = 0, worst_k = -1, worst_f = 0;
  double worst_excess = 0.0;
  for (int k = 0; k < m->njoint; k++) {
    int j = map[k];
    if (j < 0 || !robot->joint_has_limits[j] || robot->joint_mimic[j] >= 0) continue;
    int here = 0;
    for (int f = 0; f < m->nframe; f++) {
      double v = m->value[(size_t)f * (size_t)m->njoint + (size_t)k];
      double lo = robot->joint_lower[j], hi = robot->joint_upper[j];
      double excess = v < lo ? lo - v : v > hi ? v - hi : 0.0;
      if (!(excess > 1e-9)) continue;
      here++;
      if (excess > worst_excess) {
        worst_excess = excess;
        worst_k = k;
        worst_f = f;
      }
    }
    count += here;
    joints += here > 0;
  }
  if (worst_k >= 0 && msg && msg_sz > 0) {
    char one[512];
    ssa_limit_sentence(robot, map[worst_k], m->value[(size_t)worst_f * (size_t)m->njoint + (size_t)worst_k],
                       one, sizeof one);
    snprintf(msg, (size_t)msg_sz, "%d value%s (of %d joint%s) %s outside the URDF limits; worst: %s at t = %g s",
             count, count == 1 ? "" : "s", joints, joints == 1 ? "" : "s", count == 1 ? "is" : "are", one,
             m->time[worst_f]);
  }
  return count;
}

void ssa_joints_toward(const ssa_robot *robot, const double *q, const double *q_rest, double w,
                       double *out) {
  for (int j = 0; j < robot->njoint; j++) {
    double d = q_rest[j] - q[j];
    if (robot->joint_type[j] == SSA_JOINT_CONTINUOUS) d = remainder(d, 2.0 * SSA_PI);
    out[j] = q[j] + w * d;
  }
}
