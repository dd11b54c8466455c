/* skin_sim_node's parameters: the simulation settings (the core's table,
 * ss_settings.h) and the node's own, described once in a table of their own
 * here (skin_params.c): name, type, default, range, unit and help. The node
 * reads both tables, the manual's rows are printed from them
 * (`skin_sim_node --params-markdown`, scripts/doc_tables.sh), and skin.launch
 * passes only what a user sets: no default is written anywhere else. */
#ifndef SKIN_SIM_SKIN_PARAMS_H
#define SKIN_SIM_SKIN_PARAMS_H

#include <stdio.h>

#include "rosc/rosc.h"
#include "ss_msg.h"
#include "skin_sim/ss_settings.h"

/* ~marker_color: what colours skin_marker */
enum { MARKER_SLIDE = 0, MARKER_STRETCH = 1, MARKER_ONE = 2 };

typedef struct params {
  ss_sim_settings set;
  double weld_tol;    /* m; < 0 relative (ss_topo_create) */
  double max_gap;     /* s */
  double max_step;    /* s */
  int max_split;
  double marker_rate; /* Hz; 0 off; < 0 every frame */
  double slide_scale; /* m: red at this slide */
  char marker_color_text[64];
  int marker_color;   /* MARKER_SLIDE, MARKER_STRETCH or MARKER_ONE (~marker_color) */
  float marker_rgb[3];/* MARKER_ONE: the colour */
  int queue_size;
  int max_vertices, max_triangles; /* a kinematic_mesh beyond them is refused unread */
  char mask_box[256];
  int have_box;
  double box[6];      /* xmin ymin zmin xmax ymax zmax */
  char frame_id[SS_MSG_FRAME_ID_MAX]; /* "" : the input's frame; else the outputs' frame */
  char tf_prefix[128];              /* "" : none; else "PREFIX/" before the outputs' frame */
  double step_budget; /* s: 0 the input's period; < 0 none (the settings' substeps and
                         iterations always) */
  char skin_mesh[1024];      /* "" : the skin is the received body; else a mesh file or URI */
  double skin_max_distance;  /* m: a ~skin_mesh vertex farther from the body is refused */
  char package_path[1024];   /* package:// resolution (ssa_resolve_uri) */
} params;

/* Reads every parameter (~NAME of both tables) into p, checking each: 1 if all
 * are good, else 0 after one error per bad one (the node then exits 2). */
int skin_params_read(params *p);
/* The node's own parameters as rows of the manual's table (doc/ros.md). */
void skin_params_markdown(FILE *out);

#endif
