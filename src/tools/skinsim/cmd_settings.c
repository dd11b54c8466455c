/* skinsim settings: the table of simulation settings (include/skin_sim/ss_settings.h),
 * printed for people and for the test that checks launch/skin.launch and README.md
 * against it (tests/tool/test_skinsim_settings.sh). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "skin_sim/ss_settings.h"

/* The type as the launch file and README name it. */
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

int cmd_settings(int argc, char **argv) {
  int tsv = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--tsv") == 0) {
      tsv = 1;
    } else {
      cli_error("settings: unknown option '%s' (settings [--tsv])", argv[i]);
      return EXIT_USAGE;
    }
  }
  int n = 0;
  const ss_setting *t = ss_settings_table(&n);
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
