/* skinsim settings: the table of simulation settings (include/skin_sim/ss_settings.h),
 * printed for people, as TSV for scripts (the test that checks launch/skin.launch
 * against it, tests/tool/test_skinsim_settings.sh) and as Markdown for the manual
 * (doc/ros.md, doc/cli.md: `bash scripts/doc_tables.sh` writes it there). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "skin_sim/ss_settings.h"

/* The type as the launch file and doc/ros.md name it. */
static const char *ros_type(const ss_setting *d) {
  switch (d->type) {
  case SS_SETTING_INT: return "int";
  case SS_SETTING_DOUBLE: return "double";
  case SS_SETTING_BOOL: return "bool";
  default: return "string"; /* enum: a name; vec3: "x y z" */
  }
}

static const char *apply_name(int apply) {
  return apply == SS_APPLY_STEP ? "step" : apply == SS_APPLY_REFACTOR ? "refactor" : "recreate";
}

/* A live change (dynamic_reconfigure, ss_sim_set_settings) in words. */
static const char *apply_words(int apply) {
  return apply == SS_APPLY_STEP       ? "next step"
         : apply == SS_APPLY_REFACTOR ? "next step, refactors"
                                      : "new skin";
}

/* One Markdown table: the node's parameter, skinsim's flag, type and default with unit,
 * range, how a live change applies, meaning. '|' in a text would end a cell: none has one. */
static void print_markdown(const ss_setting *t, int n) {
  printf("| parameter | `skinsim` flag | type, default | range | live change | meaning |\n");
  printf("|---|---|---|---|---|---|\n");
  for (int k = 0; k < n; k++) {
    const ss_setting *d = &t[k];
    char def[96], range[160], flag[64] = "";
    ss_setting_format_default(d, def, sizeof def);
    ss_setting_format_range(d, range, sizeof range);
    if (ss_setting_cli(d)[0]) snprintf(flag, sizeof flag, "`--%s`", ss_setting_cli(d));
    if (d->type == SS_SETTING_ENUM) { /* the choices are the range */
      size_t len = 0;
      range[0] = '\0';
      for (int c = 0; d->choices[c]; c++)
        len += (size_t)snprintf(range + len, sizeof range - len, "%s`%s`", c ? ", " : "",
                                d->choices[c]);
    }
    printf("| `~%s` | %s | %s, %s%s%s | %s | %s | %s |\n", d->name, flag[0] ? flag : "-",
           ros_type(d), def, d->unit[0] ? " " : "", d->unit, range, apply_words(d->apply),
           d->help);
  }
}

int cmd_settings(int argc, char **argv) {
  int tsv = 0, markdown = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--tsv") == 0) {
      tsv = 1;
    } else if (strcmp(argv[i], "--markdown") == 0) {
      markdown = 1;
    } else {
      cli_error("settings: unknown option '%s' (settings [--tsv | --markdown])", argv[i]);
      return EXIT_USAGE;
    }
  }
  int n = 0;
  const ss_setting *t = ss_settings_table(&n);
  if (markdown) {
    print_markdown(t, n);
    return 0;
  }
  if (!tsv)
    printf("%-16s %-18s %-7s %-20s %-22s %-13s %-8s %s\n", "setting (~param)", "skinsim flag",
           "type", "default", "range", "unit", "live", "help");
  if (tsv)
    printf("name\tflag\ttype\tdefault\trange\tunit\tlive\thelp\n");
  for (int k = 0; k < n; k++) {
    const ss_setting *d = &t[k];
    char def[96], range[160], flag[64] = "";
    ss_setting_format_default(d, def, sizeof def);
    ss_setting_format_range(d, range, sizeof range);
    if (ss_setting_cli(d)[0]) snprintf(flag, sizeof flag, "--%s", ss_setting_cli(d));
    if (tsv)
      printf("%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", d->name, flag, ros_type(d), def, range, d->unit,
             apply_name(d->apply), d->help);
    else
      printf("%-16s %-18s %-7s %-20s %-22s %-13s %-8s %s\n", d->name, flag, ros_type(d),
             def, range, d->unit[0] ? d->unit : "-", apply_name(d->apply), d->help);
  }
  return 0;
}
