/* skinsim: argument parsing, JSON output and the progress bar. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "skin_sim/ss_anchor.h"
#include "skin_sim/ss_settings.h"
#include "ss_track.h"

void cli_error(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("skinsim: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
}

int cli_int(const char *opt, const char *text, long min, long max, int *out) {
  char *end = NULL;
  errno = 0;
  long v = text ? strtol(text, &end, 10) : 0;
  if (!text || !*text || *end || errno || v < min || v > max) {
    cli_error("%s expects a whole number from %ld to %ld, got '%s'", opt, min, max,
              text ? text : "");
    return -1;
  }
  *out = (int)v;
  return 0;
}

int cli_double(const char *opt, const char *text, double min, double max, double *out) {
  char *end = NULL;
  errno = 0;
  double v = text ? strtod(text, &end) : 0.0;
  if (!text || !*text || *end || errno || !isfinite(v) || v < min || v > max) {
    cli_error("%s expects a number from %g to %g, got '%s'", opt, min, max, text ? text : "");
    return -1;
  }
  *out = v;
  return 0;
}

const char *cli_value(int argc, char **argv, int *i) {
  if (*i + 1 >= argc) {
    cli_error("%s needs a value", argv[*i]);
    return NULL;
  }
  return argv[++*i];
}

/* Writes the key (JSON, CSV header) and returns 1 if the value follows. */
static int json_key(json_out *j, const char *key) {
  if (j->mode == JSON_OBJECT) {
    fprintf(j->f, "%s\n  \"%s\": ", j->count++ ? "," : "", key);
    return 1;
  }
  if (j->count++) fputc(',', j->f);
  if (j->mode == CSV_HEADER) fputs(key, j->f);
  return j->mode == CSV_ROW;
}

void json_begin(json_out *j, FILE *f) {
  j->f = f;
  j->count = 0;
  j->mode = JSON_OBJECT;
  fputc('{', f);
}

void csv_begin(json_out *j, FILE *f, int mode) {
  j->f = f;
  j->count = 0;
  j->mode = mode;
}

void json_str(json_out *j, const char *key, const char *value) {
  if (!json_key(j, key)) return;
  fputc('"', j->f);
  for (const char *c = value; c && *c; c++) {
    if (j->mode == CSV_ROW) { /* RFC 4180: quotes doubled */
      if (*c == '"') fputs("\"\"", j->f);
      else if ((unsigned char)*c < 0x20) fputc(' ', j->f);
      else fputc(*c, j->f);
    } else if (*c == '"' || *c == '\\') fprintf(j->f, "\\%c", *c);
    else if ((unsigned char)*c < 0x20) fprintf(j->f, "\\u%04x", (unsigned char)*c);
    else fputc(*c, j->f);
  }
  fputc('"', j->f);
}

void json_int(json_out *j, const char *key, long long value) {
  if (json_key(j, key)) fprintf(j->f, "%lld", value);
}

void json_num(json_out *j, const char *key, double value) {
  if (!json_key(j, key)) return;
  if (isfinite(value)) fprintf(j->f, "%.6g", value);
  else if (j->mode == JSON_OBJECT) fputs("null", j->f);
}

void json_null(json_out *j, const char *key) {
  if (json_key(j, key) && j->mode == JSON_OBJECT) fputs("null", j->f);
}

void json_hex(json_out *j, const char *key, unsigned long long value) {
  if (json_key(j, key)) fprintf(j->f, "\"%016llx\"", value);
}

void json_end(json_out *j) {
  fputs(j->mode == JSON_OBJECT ? "\n}\n" : "\n", j->f);
  fflush(j->f);
}

int cli_check_json(const char *path) {
  if (strcmp(path, "-") == 0) return 0;
  struct stat st;
  if (stat(path, &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      cli_error("--json '%s' is a folder, not a file", path);
      return -1;
    }
    if (access(path, W_OK) != 0) {
      cli_error("--json '%s' cannot be written: %s", path, strerror(errno));
      return -1;
    }
    return 0;
  }
  char dir[4096];
  const char *slash = strrchr(path, '/');
  if (!slash) snprintf(dir, sizeof dir, ".");
  else if (slash == path) snprintf(dir, sizeof dir, "/");
  else snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
  if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
    cli_error("--json '%s': the folder '%s' does not exist (skinsim creates no folder for it)",
              path, dir);
    return -1;
  }
  if (access(dir, W_OK | X_OK) != 0) {
    cli_error("--json '%s': cannot write into the folder '%s': %s", path, dir, strerror(errno));
    return -1;
  }
  return 0;
}

FILE *cli_open_json(const char *path) {
  if (strcmp(path, "-") == 0) return stdout;
  FILE *f = fopen(path, "w");
  if (!f) cli_error("cannot write JSON to '%s': %s", path, strerror(errno));
  return f;
}

void cli_close_json(FILE *f) {
  if (f && f != stdout) fclose(f);
}

void progress_begin(progress *p, const char *label) {
  p->enabled = isatty(STDERR_FILENO);
  p->label = label;
  p->start_ms = ss_now_ms();
}

int progress_update(void *user, int done, int total) {
  progress *p = user;
  if (!p->enabled || total <= 0) return 0;
  const int width = 30;
  int filled = (int)((long long)width * done / total);
  double elapsed = (ss_now_ms() - p->start_ms) / 1000.0;
  double eta = done > 0 ? elapsed * (total - done) / done : 0.0;
  fprintf(stderr, "\r%-12s [", p->label);
  for (int i = 0; i < width; i++) fputc(i < filled ? '#' : '.', stderr);
  fprintf(stderr, "] %d/%d  %.1fs, %.1fs left ", done, total, elapsed, eta);
  fflush(stderr);
  return 0;
}

void progress_end(progress *p) {
  if (p->enabled) fputs("\r\033[K", stderr);
}

int cli_setting_option(int argc, char **argv, int *i, struct ss_sim_settings *sim) {
  const char *a = argv[*i];
  if (strcmp(a, "--no-barycenters") == 0) {
    sim->barycenter_anchors = 0;
    return 1;
  }
  if (strncmp(a, "--", 2) != 0) return 0;
  const ss_setting *d = ss_setting_find_cli(a);
  if (!d) return 0;
  const char *v = cli_value(argc, argv, i);
  if (!v) return -1;
  char err[512] = "", one[128];
  double g = 0.0;
  char *end = NULL;
  if (d->type == SS_SETTING_VEC3 && *v && (g = strtod(v, &end), end && *end == '\0')) {
    /* --gravity G: down the z axis, as before the table (G = 0 gives 0 0 -0) */
    if (!isfinite(g)) {
      cli_error("%s expects a finite number G (for 0 0 -G) or 'x y z', got '%s'", a, v);
      return -1;
    }
    snprintf(one, sizeof one, "0 0 %.17g", -g);
    v = one;
  }
  if (ss_setting_parse(d, v, sim, err, sizeof err)) {
    cli_error("%s: %s", a, err);
    return -1;
  }
  return 1;
}

void cli_settings_help(FILE *f) {
  int n = 0;
  const ss_setting *t = ss_settings_table(&n);
  for (int k = 0; k < n; k++) {
    const ss_setting *d = &t[k];
    if (!ss_setting_cli(d)[0]) continue;
    char def[96], range[160], flag[64];
    ss_setting_format_default(d, def, sizeof def);
    ss_setting_format_range(d, range, sizeof range);
    snprintf(flag, sizeof flag, "--%s %s", ss_setting_cli(d),
             d->type == SS_SETTING_INT ? "N" : d->type == SS_SETTING_BOOL ? "BOOL"
             : d->type == SS_SETTING_ENUM ? "NAME" : d->type == SS_SETTING_VEC3 ? "'X Y Z'" : "X");
    fprintf(f, "        %-26s %s; default %s%s%s, range %s\n", flag, d->help, def,
            d->unit[0] ? " " : "", d->unit, range);
  }
}

int cli_mover_option(int argc, char **argv, int *i, struct ss_mover_settings *mover) {
  const char *a = argv[*i];
  if (strcmp(a, "--method") != 0 && strcmp(a, "--rings") != 0 && strcmp(a, "--max-steps") != 0)
    return 0;
  /* the same names, ranges and messages as the simulation settings (ss_settings.h) */
  ss_sim_settings s = ss_sim_default_settings();
  s.mover = *mover;
  int r = cli_setting_option(argc, argv, i, &s);
  if (r > 0) *mover = s.mover;
  return r;
}
