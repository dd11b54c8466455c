/* skin_sim core: the one table of simulation settings.
 *
 * Every field of ss_sim_settings (but face_mask) is described once here, in
 * src/core/settings.c: its name, type, default, range, unit and help. From that
 * table come ss_sim_default_settings(), the core's range checks (ss_sim_create,
 * ss_sim_set_settings), the reference cache key, skinsim's flags and help, the
 * node's `~` parameters and its dynamic_reconfigure server; the manual's tables
 * (doc/ros.md, doc/cli.md) are generated from it (`skinsim settings --markdown`,
 * `bash scripts/doc_tables.sh`) and the launch files are checked against it by tests.
 *
 * The name is the node's parameter (`~young`) and the dynamic_reconfigure name;
 * `cli` is skinsim's flag (`--young`) where it differs, NULL where there is none.
 * Ranges are inclusive unless min_open / max_open say the bound is excluded: an
 * excluded infinite bound means "finite" (young in [0, inf): any finite value
 * >= 0), an included one allows infinity (slide in [0, inf]: +inf frictionless).
 * Ints and enums are stored as int, bools as int (0/1), vec3 as double[3]
 * (each component in the range). */
#ifndef SKIN_SIM_SS_SETTINGS_H
#define SKIN_SIM_SS_SETTINGS_H

#include <stddef.h>

#include "ss_sim.h"

#ifdef __cplusplus
extern "C" {
#endif

enum ss_setting_type {
  SS_SETTING_INT = 0,
  SS_SETTING_DOUBLE = 1,
  SS_SETTING_BOOL = 2,
  SS_SETTING_ENUM = 3,   /* an int index into choices; named by its choice */
  SS_SETTING_VEC3 = 4    /* double[3], written "x y z" */
};

/* How a change reaches a running simulation (ss_sim_set_settings). */
enum ss_setting_apply {
  SS_APPLY_STEP = 0,     /* from the next step, nothing rebuilt (dt, tol, slide, gravity...) */
  SS_APPLY_REFACTOR = 1, /* from the next step; masses, springs or the system matrix are
                            rebuilt and refactored (young, density, stiffness, damping...) */
  SS_APPLY_RECREATE = 2  /* changes the skin's structure: the simulation must be created again
                            (solver, method, barycenters, threads...) */
};

/* Whose a setting is: a model's (its material: every sim on one model has the
 * model's, ss_sim_create_from_model) or each run's own. */
enum ss_setting_scope {
  SS_SCOPE_RUN = 0,
  SS_SCOPE_MODEL = 1
};

typedef struct ss_setting {
  const char *name;      /* node parameter and dynamic_reconfigure name, e.g. "young" */
  const char *cli;       /* skinsim flag without "--" where it differs ("max-steps"); NULL:
                            the same as name; "" : no flag of that name */
  int type;              /* ss_setting_type */
  size_t offset;         /* into ss_sim_settings */
  double def;            /* default (int, bool, enum: the integer value) */
  double min, max;       /* range (enum: 0 .. number of choices - 1) */
  int min_open, max_open;/* 1: that bound is excluded */
  const char *unit;      /* "N/m", "1/s", "" for none */
  int apply;             /* ss_setting_apply */
  int in_key;            /* 1: part of the reference cache key (0: threads, bit-identical) */
  const char *const *choices; /* enum: the names, NULL-terminated */
  const char *help;      /* one line */
  int scope;             /* ss_setting_scope */
} ss_setting;

/* The table and its length. */
const ss_setting *ss_settings_table(int *count);
/* The entry of that name (or of that CLI flag name, with or without "--"); NULL if none. */
const ss_setting *ss_setting_find(const char *name);
const ss_setting *ss_setting_find_cli(const char *flag);
/* The skinsim flag of a setting, without "--" ("" if none). */
const char *ss_setting_cli(const ss_setting *d);

/* Checks one setting's value in s against its range; SS_E_ARG with one sentence
 * naming the setting, the value and the range ("poisson must be in [0, 0.5), got 0.7"). */
int ss_setting_check(const ss_setting *d, const ss_sim_settings *s, char *err, int err_sz);
/* Checks every setting (in table order); the first failure is reported. */
int ss_settings_check(const ss_sim_settings *s, char *err, int err_sz);

/* Parses text into the setting (int: whole number; double: number, "inf"; bool:
 * true/false/1/0; enum: a choice name; vec3: "x y z") and checks its range. On
 * error s is untouched and err names the setting and the text. */
int ss_setting_parse(const ss_setting *d, const char *text, ss_sim_settings *s, char *err,
                     int err_sz);
/* Writes the setting's value in s as text the parser reads back ("%.17g" numbers). */
void ss_setting_format(const ss_setting *d, const ss_sim_settings *s, char *buf, size_t size);
/* The default / the range as text ("0.3"; "[0, 0.5)"). */
void ss_setting_format_default(const ss_setting *d, char *buf, size_t size);
void ss_setting_format_range(const ss_setting *d, char *buf, size_t size);

/* A number against a range from min to max, a bound excluded where its *_open
 * is 1; NaN is in no range. The same rule and text as the settings' for tables
 * of other parameters (the nodes' own). */
int ss_range_contains(double v, double min, int min_open, double max, int max_open);
/* The range as text: "[0, 0.5)", "(0, inf)"; "finite" for (-inf, inf). */
void ss_range_format(double min, int min_open, double max, int max_open, char *buf, size_t size);

/* Numeric access (int, bool, enum: the integer as a double; vec3: component i). */
double ss_setting_get(const ss_setting *d, const ss_sim_settings *s, int i);
void ss_setting_set(const ss_setting *d, ss_sim_settings *s, int i, double v);
/* 1 if the setting has the same value in a and b (bit for bit). */
int ss_setting_equal(const ss_setting *d, const ss_sim_settings *a, const ss_sim_settings *b);

#ifdef __cplusplus
}
#endif
#endif
