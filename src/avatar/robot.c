/* URDF robots: the urdfdom model (urdf_parse.cpp) turned into flat arrays,
 * mesh URIs resolved (package://, file://, relative), and forward kinematics.
 *
 * FK follows robot_state_publisher: the pose of a child link is
 * parent_pose x joint_origin x motion(q), motion being a rotation about the
 * joint axis (revolute, continuous) or a translation along it (prismatic).
 * Unlike robot_state_publisher, revolute and prismatic values are clamped to
 * their limits, and mimic joints are computed here (mult x leader + offset,
 * then clamped to their own limits). */
#include <dirent.h>
#include <errno.h>
#include <sys/stat.h>

#include "skin_sim/ssa_avatar.h"
#include "safe_import.h"
#include "ssa_util.h"
#include "urdf_parse.h"
#include "ss_free.h"

/* ---------------------------------------------------------------- files */

char *ssa_read_text_file(const char *path, const char *what, char *err, int err_sz) {
  if (ssa_check_input_file(path, what, SSA_MAX_FILE_MB_DEFAULT, err, err_sz) != SS_OK) return NULL;
  FILE *f = fopen(path, "rb");
  if (!f) {
    ss_fail(err, err_sz, SS_E_IO, "%s '%s' cannot be opened: %s", what, path, strerror(errno));
    return NULL;
  }
  size_t cap = 1 << 16, n = 0;
  char *buf = malloc(cap);
  while (buf) {
    size_t r = fread(buf + n, 1, cap - n - 1, f);
    n += r;
    if (n + 1 < cap) break;
    char *nb = realloc(buf, cap * 2);
    if (!nb) {
      free(buf);
      buf = NULL;
      break;
    }
    buf = nb;
    cap *= 2;
  }
  int bad = ferror(f);
  fclose(f);
  if (!buf || bad) {
    free(buf);
    ss_fail(err, err_sz, SS_E_IO, "%s '%s' cannot be read", what, path);
    return NULL;
  }
  buf[n] = '\0';
  return buf;
}

static int is_dir(const char *p) {
  struct stat st;
  return stat(p, &st) == 0 && S_ISDIR(st.st_mode);
}

static int is_file(const char *p) {
  struct stat st;
  return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

static const char *base_name(const char *p) {
  const char *s = strrchr(p, '/');
  return s ? s + 1 : p;
}

/* 1 if folder dir holds a package.xml whose <name> is pkg (as rospack finds packages). */
static int package_xml_names(const char *dir, const char *pkg) {
  char path[4096];
  snprintf(path, sizeof path, "%s/package.xml", dir);
  if (!is_file(path)) return 0;
  char *xml = ssa_read_text_file(path, "package.xml", NULL, 0);
  if (!xml) return 0;
  int hit = 0;
  const char *open = strstr(xml, "<name>");
  if (open) {
    open += 6;
    while (*open == ' ' || *open == '\t' || *open == '\n' || *open == '\r') open++;
    size_t n = strlen(pkg);
    const char *after = open + n;
    while (*after == ' ' || *after == '\t' || *after == '\n' || *after == '\r') after++;
    hit = strncmp(open, pkg, n) == 0 && strncmp(after, "</name>", 7) == 0;
  }
  free(xml);
  return hit;
}

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Depth-first search under root (itself included) for package pkg: a folder
 * named pkg, or a folder whose package.xml names pkg; at most depth levels
 * down, entries in name order so the result does not depend on readdir. */
static int find_dir(const char *root, const char *pkg, int depth, char *out, int out_sz) {
  char path[4096];
  if (package_xml_names(root, pkg)) {
    snprintf(out, (size_t)out_sz, "%s", root);
    return 1;
  }
  snprintf(path, sizeof path, "%s/%s", root, pkg);
  if (is_dir(path)) {
    snprintf(out, (size_t)out_sz, "%s", path);
    return 1;
  }
  if (depth <= 0) return 0;
  DIR *d = opendir(root);
  if (!d) return 0;
  char **names = NULL;
  int nn = 0, cap = 0, ok = 1;
  struct dirent *e;
  while (ok && (e = readdir(d)) != NULL) {
    if (e->d_name[0] == '.') continue;
    if (nn == cap) {
      int nc = cap ? 2 * cap : 32;
      char **nb = realloc(names, sizeof(char *) * (size_t)nc);
      if (!nb) {
        ok = 0;
        break;
      }
      names = nb;
      cap = nc;
    }
    if (!(names[nn] = ssa_strdup(e->d_name))) ok = 0; else nn++;
  }
  closedir(d);
  if (nn > 1) qsort(names, (size_t)nn, sizeof(char *), cmp_str);
  int found = 0;
  for (int i = 0; ok && i < nn && !found; i++) {
    snprintf(path, sizeof path, "%s/%s", root, names[i]);
    if (is_dir(path)) found = find_dir(path, pkg, depth - 1, out, out_sz);
  }
  ssa_free_strs(names, nn);
  return found;
}

/* Package NAME in one path list (entries NAME=DIR or roots). */
static int find_package_in(const char *list, const char *pkg, char *out, int out_sz) {
  if (!list) return 0;
  const char *p = list;
  char entry[4096];
  /* explicit NAME=DIR entries win over searched roots */
  for (int pass = 0; pass < 2; pass++) {
    p = list;
    while (*p) {
      size_t n = strcspn(p, ":;");
      if (n > 0 && n < sizeof entry) {
        memcpy(entry, p, n);
        entry[n] = '\0';
        char *eq = strchr(entry, '=');
        if (pass == 0 && eq) {
          *eq = '\0';
          if (strcmp(entry, pkg) == 0 && is_dir(eq + 1)) {
            snprintf(out, (size_t)out_sz, "%s", eq + 1);
            return 1;
          }
        } else if (pass == 1 && !eq) {
          if (strcmp(base_name(entry), pkg) == 0 && is_dir(entry)) {
            snprintf(out, (size_t)out_sz, "%s", entry);
            return 1;
          }
          if (is_dir(entry) && find_dir(entry, pkg, 4, out, out_sz)) return 1;
        }
      }
      p += n;
      if (*p) p++;
    }
  }
  return 0;
}

int ssa_resolve_uri(const char *uri, const char *base_dir, const char *package_path, char *out,
                    int out_sz, char *err, int err_sz) {
  if (!uri || !out || out_sz <= 0) return ss_fail(err, err_sz, SS_E_ARG, "no mesh URI given");
  char path[4096];
  if (strncmp(uri, "package://", 10) == 0) {
    const char *rest = uri + 10;
    const char *slash = strchr(rest, '/');
    char pkg[256];
    size_t n = slash ? (size_t)(slash - rest) : strlen(rest);
    if (n == 0 || n >= sizeof pkg)
      return ss_fail(err, err_sz, SS_E_IO, "mesh URI '%s' names no package", uri);
    memcpy(pkg, rest, n);
    pkg[n] = '\0';
    char dir[4096];
    if (!find_package_in(package_path, pkg, dir, sizeof dir) &&
        !find_package_in(getenv("ROS_PACKAGE_PATH"), pkg, dir, sizeof dir))
      return ss_fail(err, err_sz, SS_E_IO,
                     "mesh URI '%s' cannot be resolved: package '%s' is not in the package "
                     "path '%s' nor under ROS_PACKAGE_PATH '%s'",
                     uri, pkg, package_path ? package_path : "",
                     getenv("ROS_PACKAGE_PATH") ? getenv("ROS_PACKAGE_PATH") : "");
    snprintf(path, sizeof path, "%s%s", dir, slash ? slash : "");
  } else if (strncmp(uri, "file://", 7) == 0) {
    snprintf(path, sizeof path, "%s", uri + 7);
  } else if (strstr(uri, "://")) {
    return ss_fail(err, err_sz, SS_E_IO, "mesh URI '%s' has an unsupported scheme", uri);
  } else if (uri[0] == '/' || !base_dir || !base_dir[0]) {
    snprintf(path, sizeof path, "%s", uri);
  } else {
    snprintf(path, sizeof path, "%s/%s", base_dir, uri);
  }
  if (!is_file(path))
    return ss_fail(err, err_sz, SS_E_IO, "mesh URI '%s' resolves to '%s', which is not a file",
                   uri, path);
  if ((int)strlen(path) >= out_sz)
    return ss_fail(err, err_sz, SS_E_ARG, "mesh path '%s' is too long", path);
  snprintf(out, (size_t)out_sz, "%s", path);
  return SS_OK;
}

/* ---------------------------------------------------------------- load */

void ssa_robot_destroy(ssa_robot *r) {
  if (!r) return;
  free(r->name);
  free(r->path);
  ssa_free_strs(r->link_name, r->nlink);
  free(r->link_parent);
  free(r->link_joint);
  free(r->link_order);
  ssa_free_strs(r->joint_name, r->njoint);
  SS_FREE_ALL(r->joint_type, r->joint_parent_link, r->joint_child_link, r->joint_origin,
              r->joint_axis, r->joint_has_limits, r->joint_lower, r->joint_upper, r->joint_mimic,
              r->joint_mimic_mult, r->joint_mimic_off, r->visual_link, r->visual_is_mesh);
  ssa_free_strs(r->visual_uri, r->nvisual);
  ssa_free_strs(r->visual_path, r->nvisual);
  SS_FREE_ALL(r->visual_origin, r->visual_scale, r->visual_kind, r->visual_size, r);
}

int ssa_robot_link_index(const ssa_robot *r, const char *name) {
  if (!r || !name) return -1;
  for (int i = 0; i < r->nlink; i++)
    if (strcmp(r->link_name[i], name) == 0) return i;
  return -1;
}

int ssa_robot_joint_index(const ssa_robot *r, const char *name) {
  if (!r || !name) return -1;
  for (int i = 0; i < r->njoint; i++)
    if (strcmp(r->joint_name[i], name) == 0) return i;
  return -1;
}

#define ALLOC(ptr, n) ((ptr) = calloc((size_t)((n) > 0 ? (n) : 1), sizeof *(ptr)))

static int build(ssa_robot *r, const ssa_urdf_data *d, const char *what, const char *base_dir,
                 const char *package_path, char *err, int err_sz) {
  if (d->nlink > SSA_MAX_LINKS || d->njoint > SSA_MAX_LINKS)
    return ss_fail(err, err_sz, SS_E_ARG, "%s has %d links and %d joints, over the bound of %d",
                   what, d->nlink, d->njoint, SSA_MAX_LINKS);
  r->name = ssa_strdup(d->robot_name);
  r->root_link = d->root_link;
  r->nlink = d->nlink;
  r->njoint = d->njoint;
  r->nvisual = d->nvisual;
  if (!r->name || !ALLOC(r->link_name, r->nlink) || !ALLOC(r->link_parent, r->nlink) ||
      !ALLOC(r->link_joint, r->nlink) || !ALLOC(r->link_order, r->nlink) ||
      !ALLOC(r->joint_name, r->njoint) || !ALLOC(r->joint_type, r->njoint) ||
      !ALLOC(r->joint_parent_link, r->njoint) || !ALLOC(r->joint_child_link, r->njoint) ||
      !ALLOC(r->joint_origin, 16 * r->njoint) || !ALLOC(r->joint_axis, 3 * r->njoint) ||
      !ALLOC(r->joint_has_limits, r->njoint) || !ALLOC(r->joint_lower, r->njoint) ||
      !ALLOC(r->joint_upper, r->njoint) || !ALLOC(r->joint_mimic, r->njoint) ||
      !ALLOC(r->joint_mimic_mult, r->njoint) || !ALLOC(r->joint_mimic_off, r->njoint) ||
      !ALLOC(r->visual_link, r->nvisual) || !ALLOC(r->visual_is_mesh, r->nvisual) ||
      !ALLOC(r->visual_uri, r->nvisual) || !ALLOC(r->visual_path, r->nvisual) ||
      !ALLOC(r->visual_origin, 16 * r->nvisual) || !ALLOC(r->visual_scale, 3 * r->nvisual) ||
      !ALLOC(r->visual_kind, r->nvisual) || !ALLOC(r->visual_size, 3 * r->nvisual))
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading %s", what);
  for (int i = 0; i < r->nlink; i++) {
    if (!(r->link_name[i] = ssa_strdup(d->link_name[i])))
      return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading %s", what);
    r->link_parent[i] = -1;
    r->link_joint[i] = -1;
  }
  for (int j = 0; j < r->njoint; j++) {
    if (!(r->joint_name[j] = ssa_strdup(d->joint_name[j])))
      return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading %s", what);
    r->joint_type[j] = d->joint_type[j];
    r->joint_parent_link[j] = d->joint_parent[j];
    r->joint_child_link[j] = d->joint_child[j];
    if (d->joint_parent[j] < 0 || d->joint_child[j] < 0)
      return ss_fail(err, err_sz, SS_E_IO, "%s: joint '%s' connects an unknown link", what,
                     d->joint_name[j]);
    if (r->link_joint[d->joint_child[j]] >= 0) /* a link is the child of one joint */
      return ss_fail(err, err_sz, SS_E_ARG,
                     "%s: link '%s' is the child of joints '%s' and '%s': the joints form a "
                     "cycle, or give the link two parents", what, d->link_name[d->joint_child[j]],
                     d->joint_name[r->link_joint[d->joint_child[j]]], d->joint_name[j]);
    r->link_parent[d->joint_child[j]] = d->joint_parent[j];
    r->link_joint[d->joint_child[j]] = j;
    m4_from_tqs(d->joint_origin + 7 * j, d->joint_origin + 7 * j + 3, NULL,
                r->joint_origin + 16 * j);
    const double *a = d->joint_axis + 3 * j;
    double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(n > 0) || !isfinite(n)) {
      if (r->joint_type[j] != SSA_JOINT_FIXED && r->joint_type[j] != SSA_JOINT_UNSUPPORTED)
        return ss_fail(err, err_sz, SS_E_IO, "%s: joint '%s' has a zero axis", what,
                       d->joint_name[j]);
      n = 1.0;
    }
    for (int k = 0; k < 3; k++) r->joint_axis[3 * j + k] = a[k] / n;
    r->joint_has_limits[j] = d->joint_has_limits[j] && d->joint_lower[j] <= d->joint_upper[j] &&
                             !(d->joint_lower[j] == 0 && d->joint_upper[j] == 0);
    r->joint_lower[j] = d->joint_lower[j];
    r->joint_upper[j] = d->joint_upper[j];
    r->joint_mimic_mult[j] = d->joint_mimic_mult[j];
    r->joint_mimic_off[j] = d->joint_mimic_off[j];
    r->joint_mimic[j] = -1;
  }
  for (int j = 0; j < r->njoint; j++) {
    if (!d->joint_mimic[j]) continue;
    int m = -1;
    for (int k = 0; k < d->njoint; k++)
      if (strcmp(d->joint_name[k], d->joint_mimic[j]) == 0) m = k;
    if (m < 0)
      return ss_fail(err, err_sz, SS_E_ARG, "%s: joint '%s' mimics unknown joint '%s'", what,
                     d->joint_name[j], d->joint_mimic[j]);
    r->joint_mimic[j] = m;
  }
  /* mimic cycles */
  for (int j = 0; j < r->njoint; j++) {
    int k = j, steps = 0;
    while (r->joint_mimic[k] >= 0 && steps <= r->njoint) {
      k = r->joint_mimic[k];
      steps++;
    }
    if (steps > r->njoint)
      return ss_fail(err, err_sz, SS_E_ARG, "%s: mimic joints form a cycle through '%s'", what,
                     r->joint_name[j]);
  }
  /* link order: breadth-first from the root, each link's children in index
   * order, through per-parent child lists (a robot of thousands of parts) */
  int *child_start = calloc((size_t)r->nlink + 1, sizeof(int));
  int *child = malloc((size_t)r->nlink * sizeof(int));
  if (!child_start || !child) {
    free(child_start);
    free(child);
    return ss_fail(err, err_sz, SS_E_NOMEM, "%s: out of memory for %d links", what, r->nlink);
  }
  for (int c = 0; c < r->nlink; c++)
    if (r->link_parent[c] >= 0) child_start[r->link_parent[c] + 1]++;
  for (int l = 0; l < r->nlink; l++) child_start[l + 1] += child_start[l];
  for (int c = 0; c < r->nlink; c++)
    if (r->link_parent[c] >= 0) child[child_start[r->link_parent[c]]++] = c;
  /* filling moved each start to the next one's: back by one */
  for (int l = r->nlink; l > 0; l--) child_start[l] = child_start[l - 1];
  child_start[0] = 0;
  int n = 0;
  r->link_order[n++] = r->root_link;
  for (int head = 0; head < n; head++) {
    int l = r->link_order[head];
    for (int i = child_start[l]; i < child_start[l + 1] && n < r->nlink; i++)
      r->link_order[n++] = child[i];
  }
  free(child_start);
  free(child);
  if (n != r->nlink)
    return ss_fail(err, err_sz, SS_E_IO, "%s: %d of %d links are not connected to root '%s'",
                   what, r->nlink - n, r->nlink, r->link_name[r->root_link]);
  for (int v = 0; v < r->nvisual; v++) {
    r->visual_link[v] = d->visual_link[v];
    r->visual_is_mesh[v] = d->visual_geom[v] == SSA_GEOM_MESH;
    m4_from_tqs(d->visual_origin + 7 * v, d->visual_origin + 7 * v + 3, NULL,
                r->visual_origin + 16 * v);
    memcpy(r->visual_scale + 3 * v, d->visual_scale + 3 * v, 3 * sizeof(double));
    r->visual_kind[v] = d->visual_geom[v]; /* ssa_urdf_geom and ssa_visual_kind agree */
    memcpy(r->visual_size + 3 * v, d->visual_size + 3 * v, 3 * sizeof(double));
    if (d->visual_uri[v]) {
      if (!(r->visual_uri[v] = ssa_strdup(d->visual_uri[v])))
        return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading %s", what);
      char path[4096];
      if (ssa_resolve_uri(d->visual_uri[v], base_dir, package_path, path, sizeof path, NULL, 0) ==
          SS_OK)
        r->visual_path[v] = ssa_strdup(path);
    }
  }
  return SS_OK;
}

int ssa_robot_load_string(ssa_robot **out, const char *urdf_xml, const char *base_dir,
                          const char *package_path, char *err, int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  if (!urdf_xml) return ss_fail(err, err_sz, SS_E_ARG, "no URDF text given");
  ssa_urdf_data *d = NULL;
  char why[768];
  why[0] = '\0';
  int st = ssa_urdf_parse(urdf_xml, &d, why, sizeof why);
  if (st != SS_OK) return ss_fail(err, err_sz, st, "URDF text: %s", why);
  ssa_robot *r = calloc(1, sizeof *r);
  if (!r) {
    ssa_urdf_data_free(d);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading URDF text");
  }
  st = build(r, d, "URDF text", base_dir, package_path, err, err_sz);
  ssa_urdf_data_free(d);
  if (st == SS_OK && !(r->path = ssa_strdup("")))
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading URDF text");
  if (st != SS_OK) {
    ssa_robot_destroy(r);
    return st;
  }
  *out = r;
  return SS_OK;
}

int ssa_robot_load(ssa_robot **out, const char *urdf_path, const char *package_path, char *err,
                   int err_sz) {
  if (!out) return ss_fail(err, err_sz, SS_E_ARG, "no output pointer given");
  *out = NULL;
  if (!urdf_path) return ss_fail(err, err_sz, SS_E_ARG, "no URDF path given");
  char *xml = ssa_read_text_file(urdf_path, "URDF file", err, err_sz);
  if (!xml) return SS_E_IO;
  char base[4096];
  snprintf(base, sizeof base, "%s", urdf_path);
  char *slash = strrchr(base, '/');
  if (slash)
    *slash = '\0';
  else
    snprintf(base, sizeof base, ".");
  ssa_urdf_data *d = NULL;
  char why[768];
  why[0] = '\0';
  int st = ssa_urdf_parse(xml, &d, why, sizeof why);
  free(xml);
  if (st != SS_OK) return ss_fail(err, err_sz, st, "URDF file '%s': %s", urdf_path, why);
  ssa_robot *r = calloc(1, sizeof *r);
  if (!r) {
    ssa_urdf_data_free(d);
    return ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", urdf_path);
  }
  char what[4200];
  snprintf(what, sizeof what, "URDF file '%s'", urdf_path);
  st = build(r, d, what, base, package_path, err, err_sz);
  ssa_urdf_data_free(d);
  if (st == SS_OK && !(r->path = ssa_strdup(urdf_path)))
    st = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory reading '%s'", urdf_path);
  if (st != SS_OK) {
    ssa_robot_destroy(r);
    return st;
  }
  *out = r;
  return SS_OK;
}

/* ---------------------------------------------------------------- joints and FK */

int ssa_robot_set_joints(const ssa_robot *r, double *q, int n, const char *const *names,
                         const double *values, char *err, int err_sz) {
  if (!r || !q || n < 0 || (n > 0 && (!names || !values)))
    return ss_fail(err, err_sz, SS_E_ARG, "joint values: missing arrays");
  for (int i = 0; i < n; i++) {
    int j = ssa_robot_joint_index(r, names[i]);
    if (j < 0)
      return ss_fail(err, err_sz, SS_E_ARG, "robot '%s' has no joint named '%s'", r->name,
                     names[i] ? names[i] : "(null)");
    if (!isfinite(values[i]))
      return ss_fail(err, err_sz, SS_E_NONFINITE, "joint '%s' of robot '%s' got a non-finite value",
                     names[i], r->name);
    q[j] = values[i];
  }
  return SS_OK;
}

double ssa_robot_joint_value(const ssa_robot *r, const double *q, int j) {
  if (!r || j < 0 || j >= r->njoint) return 0.0;
  int t = r->joint_type[j];
  if (t == SSA_JOINT_FIXED || t == SSA_JOINT_UNSUPPORTED) return 0.0;
  double v;
  if (r->joint_mimic[j] >= 0)
    v = r->joint_mimic_mult[j] * ssa_robot_joint_value(r, q, r->joint_mimic[j]) +
        r->joint_mimic_off[j];
  else
    v = q ? q[j] : 0.0;
  if (!isfinite(v)) v = 0.0;
  if (r->joint_has_limits[j]) {
    if (v < r->joint_lower[j]) v = r->joint_lower[j];
    if (v > r->joint_upper[j]) v = r->joint_upper[j];
  }
  return v;
}

int ssa_robot_check_limits(const ssa_robot *r, const double *q, char *msg, int msg_sz) {
  if (!r || !q) return 0;
  int count = 0, worst = -1;
  double worst_excess = 0.0;
  for (int j = 0; j < r->njoint; j++) {
    if (!r->joint_has_limits[j] || r->joint_mimic[j] >= 0 || !isfinite(q[j])) continue;
    double lo = r->joint_lower[j], hi = r->joint_upper[j];
    double excess = q[j] < lo ? lo - q[j] : q[j] > hi ? q[j] - hi : 0.0;
    if (!(excess > 1e-9)) continue;
    count++;
    if (excess > worst_excess) {
      worst_excess = excess;
      worst = j;
    }
  }
  if (worst >= 0) ssa_limit_sentence(r, worst, q[worst], msg, msg_sz);
  return count;
}

void ssa_limit_sentence(const ssa_robot *r, int j, double v, char *msg, int msg_sz) {
  if (!msg || msg_sz <= 0) return;
  const int rev = r->joint_type[j] == SSA_JOINT_REVOLUTE;
  const char *unit = rev ? "rad" : "m";
  /* a revolute value beyond a full turn, or one whose radian reading is past the
   * limits while its degree reading fits them, was most likely given in degrees */
  const double deg = v * SSA_PI / 180.0;
  const int degrees = rev && (fabs(v) > 2 * SSA_PI + 1e-9 ||
                              (deg >= r->joint_lower[j] && deg <= r->joint_upper[j] && fabs(v) > SSA_PI));
  snprintf(msg, (size_t)msg_sz, "joint '%s' of robot '%s' is %g %s, outside its limits [%g, %g] %s%s",
           r->joint_name[j], r->name, v, unit, r->joint_lower[j], r->joint_upper[j], unit,
           degrees ? " (degrees? joint values are radians)" : "");
}

void ssa_robot_fk(const ssa_robot *r, const double *q, double *link_world) {
  if (!r || !link_world) return;
  for (int oi = 0; oi < r->nlink; oi++) {
    int l = r->link_order[oi];
    double *w = link_world + 16 * l;
    int j = r->link_joint[l];
    if (j < 0) {
      m4_identity(w);
      continue;
    }
    double local[16], motion[16];
    memcpy(local, r->joint_origin + 16 * j, sizeof local);
    double v = ssa_robot_joint_value(r, q, j);
    const double *ax = r->joint_axis + 3 * j;
    switch (r->joint_type[j]) {
      case SSA_JOINT_REVOLUTE:
      case SSA_JOINT_CONTINUOUS:
        m4_axis_angle(ax, v, motion);
        m4_mul_inplace_right(local, motion);
        break;
      case SSA_JOINT_PRISMATIC:
        m4_identity(motion);
        motion[3] = ax[0] * v;
        motion[7] = ax[1] * v;
        motion[11] = ax[2] * v;
        m4_mul_inplace_right(local, motion);
        break;
      default: break;
    }
    m4_mul(link_world + 16 * r->link_parent[l], local, w);
  }
}
