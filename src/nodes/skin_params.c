/* skin_sim_node's parameter table (skin_params.h) and the reading of both tables. */
#include "skin_params.h"

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "node_params.h"

enum { NP_INT = 0, NP_DOUBLE = 1, NP_STRING = 2 };

typedef struct node_param {
  const char *name;     /* ~NAME */
  int type;             /* NP_* */
  size_t offset, size;  /* into params; size: a string's buffer */
  double def;           /* int, double */
  const char *def_text; /* string */
  double min, max;      /* int, double: the range ... */
  int min_open, max_open; /* ... 1: that bound excluded (an excluded infinite one: finite) */
  const char *unit;     /* "" for none */
  const char *help;     /* one line of the manual */
} node_param;

#define INF INFINITY
#define NUM(name, type, def, lo, hi, lo_open, hi_open, unit, help) \
  {#name, type, offsetof(params, name), 0, def, NULL, lo, hi, lo_open, hi_open, unit, help}
#define STR(name, field, def, unit, help) \
  {#name, NP_STRING, offsetof(params, field), sizeof(((params *)0)->field), 0, def, 0, 0, 0, 0, unit, help}

static const node_param table[] = {
    NUM(step_budget, NP_DOUBLE, 0.0, -INF, INF, 1, 1, "s",
        "the wall time a step may take; 0: the input's period; negative: none (the settings' "
        "substeps and iterations always)"),
    STR(skin_mesh, skin_mesh, "", "",
        "a skin mesh of its own (file or `package://` URI, in the body's frame at its first "
        "pose); \"\": the skin is the received body"),
    NUM(skin_max_distance, NP_DOUBLE, 0.05, 0, INF, 0, 1, "m",
        "a `~skin_mesh` vertex farther than this from the body refuses the skin"),
    STR(package_path, package_path, "", "",
        "`NAME=DIR` entries or search roots for `~skin_mesh`'s `package://` URI (then "
        "`ROS_PACKAGE_PATH`)"),
    STR(mask_box, mask_box, "", "",
        "`xmin ymin zmin xmax ymax zmax` (m): simulate only faces whose centroid (first frame) is "
        "inside; the rest follows the body"),
    NUM(weld_tol, NP_DOUBLE, -1.0, -INF, INF, 1, 1, "m",
        "vertices of the first `kinematic_mesh` closer than this are one skin vertex; negative: "
        "1e-9 x the bounding-box diagonal (bit-identical copies, as `skinsim run`); 0: only "
        "identical positions"),
    NUM(max_gap, NP_DOUBLE, 0.5, 0, INF, 1, 0, "s",
        "a larger jump of the input's stamps between consecutively published messages resets the "
        "skin (never a gap the node made by skipping)"),
    NUM(max_step, NP_DOUBLE, 0.05, 0, INF, 1, 0, "s",
        "an input period longer than this is split into equal substeps ..."),
    NUM(max_split, NP_INT, 8, 1, 1000, 0, 0, "",
        "... at most this many (from the input period, never more because the node is late)"),
    NUM(marker_rate, NP_DOUBLE, 10.0, -INF, INF, 0, 0, "Hz",
        "`skin_marker` rate (0: off; negative: every frame); built only while someone subscribes"),
    STR(marker_color, marker_color_text, "slide", "",
        "`skin_marker`'s colour, shaded: `slide` (blue, green, red at `~slide_scale`), `stretch` "
        "(area against rest: blue at half, grey, red at twice) or one colour `\"R G B\"` (each "
        "0..1)"),
    NUM(slide_scale, NP_DOUBLE, 0.05, 0, INF, 1, 1, "m", "slide drawn fully red"),
    NUM(queue_size, NP_INT, 1, 1, 1000, 0, 0, "",
        "meshes waiting to be stepped (replay.launch: 30); when full the oldest is skipped"),
    NUM(max_vertices, NP_INT, 2000000, 3, INT_MAX, 0, 0, "",
        "a `kinematic_mesh` with more vertices (`positions` / 3, or `rigid_part`) is refused "
        "before it is read"),
    NUM(max_triangles, NP_INT, 4000000, 1, INT_MAX, 0, 0, "",
        "a `kinematic_mesh` with more triangles is refused before it is read"),
    STR(frame_id, frame_id, "", "",
        "frame of `skin_mesh` and `skin_marker`; \"\": the input's `header.frame_id`"),
    STR(tf_prefix, tf_prefix, "", "",
        "`PREFIX/` put before that frame, so two skins in two namespaces are told apart (launch "
        "files: `frame_prefix:=`)"),
};
#define NPARAM ((int)(sizeof table / sizeof table[0]))

static const char *type_name(int type) {
  return type == NP_INT ? "int" : type == NP_DOUBLE ? "double" : "string";
}

/* "[1, 1000]", "(0, inf]", "finite" (any finite number), "" (a string) */
static void format_range(const node_param *d, char *buf, size_t size) {
  buf[0] = 0;
  if (d->type != NP_STRING) ss_range_format(d->min, d->min_open, d->max, d->max_open, buf, size);
}

static int read_one(const node_param *d, params *p) {
  char name[80];
  snprintf(name, sizeof name, "~%s", d->name);
  char *field = (char *)p + d->offset;
  double v = 0.0;
  if (d->type == NP_STRING) return get_string(name, field, d->size, d->def_text);
  if (d->type == NP_INT) {
    int *iv = (int *)(void *)field;
    if (!get_int(name, iv, (int)d->def)) return 0;
    v = *iv;
  } else {
    double *dv = (double *)(void *)field;
    if (!get_double(name, dv, d->def)) return 0;
    v = *dv;
  }
  if (ss_range_contains(v, d->min, d->min_open, d->max, d->max_open)) return 1;
  char range[80];
  format_range(d, range, sizeof range);
  ROSC_ERROR("%s = %g%s%s is out of range %s", name, v, d->unit[0] ? " " : "", d->unit, range);
  return 0;
}

int skin_params_read(params *p) {
  int ok = 1;
  /* every simulation setting: ~NAME, from the core's table (ss_settings.h) */
  p->set = ss_sim_default_settings();
  int nset = 0;
  const ss_setting *settings = ss_settings_table(&nset);
  for (int i = 0; i < nset; i++) ok &= get_setting(&settings[i], &p->set);
  for (int i = 0; i < NPARAM; i++) ok &= read_one(&table[i], p);
  /* the strings that say more than one thing */
  p->have_box = 0;
  if (p->mask_box[0]) {
    double *b = p->box;
    if (sscanf(p->mask_box, "%lf %lf %lf %lf %lf %lf", b, b + 1, b + 2, b + 3, b + 4, b + 5) != 6) {
      ROSC_ERROR("~mask_box: '%s' is not six numbers 'xmin ymin zmin xmax ymax zmax' (m)", p->mask_box);
      ok = 0;
    } else {
      p->have_box = 1;
    }
  }
  const char *mc = p->marker_color_text;
  p->marker_color = MARKER_SLIDE;
  if (strcmp(mc, "stretch") == 0) {
    p->marker_color = MARKER_STRETCH;
  } else if (strcmp(mc, "slide") != 0) {
    float *c = p->marker_rgb;
    char tail = 0;
    if (sscanf(mc, "%f %f %f %c", c, c + 1, c + 2, &tail) != 3 || !(c[0] >= 0.0f && c[0] <= 1.0f) ||
        !(c[1] >= 0.0f && c[1] <= 1.0f) || !(c[2] >= 0.0f && c[2] <= 1.0f)) {
      ROSC_ERROR("~marker_color: '%s' is not slide, stretch or a colour 'R G B' (each in [0, 1])", mc);
      ok = 0;
    }
    p->marker_color = MARKER_ONE;
  }
  return ok;
}

void skin_params_markdown(FILE *out) {
  fprintf(out, "| parameter | type, default | range | meaning |\n|---|---|---|---|\n");
  for (int i = 0; i < NPARAM; i++) {
    const node_param *d = &table[i];
    char def[64], range[80];
    if (d->type == NP_STRING)
      snprintf(def, sizeof def, "\"%s\"", d->def_text);
    else
      snprintf(def, sizeof def, "%.15g", d->def);
    format_range(d, range, sizeof range);
    fprintf(out, "| `~%s` | %s, %s%s%s | %s | %s |\n", d->name, type_name(d->type), def,
            d->unit[0] ? " " : "", d->unit, range, d->help);
  }
}
