/* skin_sim_node's inside, shared by its files (glue only):
 *   skin_sim_node.c   main, the input (inbox, message checks), the skin's creation
 *                     and each step (process)
 *   skin_node_output.c  skin_mesh, skin_stats and skin_marker
 *   skin_node_health.c  ~reset, dynamic_reconfigure, /diagnostics
 *   skin_params.c     the parameter tables */
#ifndef SKIN_SIM_SKIN_NODE_H
#define SKIN_SIM_SKIN_NODE_H

#include "node_dynreconf.h"
#include "node_log.h"
#include "node_msg.h"
#include "node_params.h"
#include "skin_params.h"
#include "rosc/rosc.h"
#include "ss_budget.h"
#include "ss_input.h"
#include "ss_wire.h"
#include "skin_sim/ss_mesh.h"
#include "skin_sim/ss_sim.h"
#include "skin_sim/ssa_avatar.h"

#include <limits.h>
#ifdef __GLIBC__
#include <malloc.h> /* malloc_trim */
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ERR_SZ 512

/* ~skin_mesh as loaded at start: the file's vertices and triangles, welded */
typedef struct skin_file {
  ss_weld *weld;        /* NULL: no ~skin_mesh */
  int *faces;           /* (weld->nface x 3) the file's triangles, as published */
  uint32_t topology_id; /* of its layout, published with it */
} skin_file;


typedef struct mailbox {
  ss_msg_header header;
  int disc;             /* SS_TIME_GAP / SS_TIME_BACKWARDS: the input jumped before it; else 0 */
  uint32_t topology_id;
  float *pos;
  size_t npos, cap_pos;
  uint32_t *tri;
  size_t ntri, cap_tri;
  uint32_t *rigid;      /* rigid_part: what each vertex moves with (nrigid 0: unknown) */
  size_t nrigid, cap_rigid;
} mailbox;

/* Received meshes waiting to be stepped: a ring of ~queue_size slots; when it is
 * full the oldest is skipped (counted). Slots keep their buffers, so a steady
 * stream does not allocate. */
typedef struct inbox {
  mailbox *slot;
  int cap, head, count;
} inbox;

/* The kinds of a rejected kinematic_mesh, each logged on its own throttle. */
enum { REJECT_SIZE, REJECT_CREATE, REJECT_NONFINITE, REJECT_MALFORMED, REJECT_TOPOLOGY,
       REJECT_RIGID_PART, REJECT_STEP, REJECT_KINDS };

typedef struct node {
  params p;
  skin_file skin;         /* ~skin_mesh, or none */
  inbox in;
  msg_pub *pub_mesh, *pub_stats, *pub_marker;
  /* simulation and its topology; the body is the received mesh, the skin its copy or
   * ~skin_mesh, published in its own vertex layout (the body's, or the file's) */
  ss_sim *sim;
  uint32_t topology_id;   /* the input's */
  int nbvert, nbface;     /* the body's: the input's vertices and triangles */
  int *bfaces;            /* (nbface x 3) as received */
  int nvert, nface;       /* the published skin's vertices and triangles */
  int nweld;              /* skin vertices: the body's welded */
  int *vert_weld;         /* (nvert) skin (welded) vertex of each published vertex */
  int *faces;             /* (nface x 3) published triangles */
  uint32_t *tri_out;      /* (nface x 3) */
  unsigned char *mask;    /* (nface) 1: simulated face (~mask_box, rigid pieces carried) */
  unsigned char *carried; /* (nvert) 1: in a rigid piece, published as received */
  int nface_sim, nface_carried; /* skin triangles simulated and carried rigidly */
  ss_budget budget;       /* ~step_budget: the substeps and iterations in force */
  double budget_ms;       /* the budget of the last step (0: none) */
  int faces_turned, vertices_far; /* ss_sim_count_off_body after the last step */
  int nanchor;
  int *face0;             /* (nanchor) anchors as bound at create */
  double *uv0;            /* (nanchor x 2) */
  double *slide;          /* (nanchor) */
  double *body, *body_prev, *body_sub; /* (nbvert x 3) */
  float *pos_out;         /* (nvert x 3) */
  float *mk_pts, *mk_col; /* (nface x 3 x 3), (nface x 3 x 4) */
  float *mk_vcol;         /* (nweld x 4) colour of each skin vertex; NULL until a marker */
  double *mk_work;        /* (nweld x 3) normals, area sums */
  ss_input_stream stream; /* every arrival: seq gaps, the input's period, real jumps */
  int64_t skin_ns;        /* the skin's clock (whole input periods from its creation) */
  int prev_periods;       /* input periods of the last step (0: none since creation) */
  int carry_disc;         /* a jump seen on a message that was rejected: reset on the next */
  /* counters */
  uint32_t rejected, dropped, skipped, resets, failures;
  ss_throttle reject_log[REJECT_KINDS]; /* one warning per kind of problem per second */
  unsigned long frames_in, frames_out, steps; /* steps: ss_sim_step calls */
  double last_marker_wall;
  /* ~reset (std_srvs/Empty): the next mesh creates the skin again on its pose */
  int reset_req;
  /* dynamic_reconfigure changed a setting the skin cannot change in place: the same */
  int recreate_req;
  node_dr *dr;
  /* /diagnostics: figures since the last status (a window of ~diagnostic_period) */
  rosc_diag *diag;
  double diag_wall;       /* wall time of the last status */
  double busy_period_ms;  /* the input period while a step runs (read by busy_status) */
  unsigned long processed; /* meshes processed (skin created, stepped or republished) */
  unsigned long nstep_ms;  /* of which stepped (timed) */
  double step_ms_sum, step_ms_max;
  unsigned long steps_multi; /* of the ss_sim_step calls, those on more than one thread */
  struct { unsigned long in, processed, nstep_ms; double step_ms_sum;
           uint32_t rejected, dropped, skipped, resets, failures;
           unsigned long steps, steps_multi; long long lowered; } win; /* at the window start */
} node;

/* ---- skin_node_output.c ---- */
/* Publishes skin_mesh and skin_stats for the input header in_hdr (stats: the
 * step's sums acc, its wall time and substeps), and skin_marker at ~marker_rate. */
void node_publish(node *nd, const ss_msg_header *in_hdr, const ss_sim_stats *acc, double total_ms,
                  int substeps);

/* ---- skin_node_health.c ---- */
/* ~reset (std_srvs/Empty): the next mesh creates the skin again on its pose. */
int node_on_reset(void *user);
/* Serves every setting of the table through dynamic_reconfigure; 1 on success. */
int node_serve_settings(node *nd);
/* The status /diagnostics says during a long step (rosc_diag_busy's callback). */
void node_busy_status(double busy_s, int last_level, rosc_diag_busy_status *out, void *user);
/* The status of the last window on /diagnostics when ~diagnostic_period has passed. */
void node_diagnose(node *nd);

#endif
