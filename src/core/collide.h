/* Internal: the skin kept outside the body where the body is clean (collide.c). */
#ifndef SKIN_SIM_COLLIDE_H
#define SKIN_SIM_COLLIDE_H

#include "walk.h" /* ss_frames */

/* What one contact pass reads (flat, the caller's). */
typedef struct ss_collide_in {
  const ss_topo *topo;        /* body topology (welded vertex rings) */
  const ss_frames *fr;        /* body face normals and areas in the current pose */
  const double *body;         /* body positions in the current pose (nbvert x 3) */
  const int *anchor_face;     /* per skin vertex: the body face it is anchored on now */
  const double *anchor_pos;   /* per skin vertex: where that anchor is (x 3), on the body */
  const int *faces;           /* skin faces (nface x 3) as at create, or NULL: no squeeze guard */
  const double *rest_area;    /* (nface) their rest areas; 0 is not judged */
  double thickness;           /* metres kept between skin and body (>= 0) */
  double reach;               /* metres: the scale of the body (its mean edge length) */
} ss_collide_in;

/* Scratch and the body's winding-number hierarchy of one sim: made at
 * create, so that the pass allocates nothing. */
typedef struct ss_collider ss_collider;
/* nface, faces: the skin's faces (nface x 3, the skin's topology: read at
 * create only), for the faces around each vertex. */
int ss_collider_create(ss_collider **out, const ss_topo *btopo, const double *body_rest,
                       int nvert, int nface, const int *faces);
void ss_collider_destroy(ss_collider *c);

/* One pass over the skin vertices dof_vert[0 .. ndof) of x (in place, on
 * nthread threads, the same bits for any count): each behind the body's
 * clean surface around its anchor is put on it, thickness in front, and
 * its velocity in vel (if not NULL) loses its part into the body. `step`
 * counts the caller's steps (the surface test is kept for some steps).
 * Returns how many moved. */
int ss_collider_run(ss_collider *c, const ss_collide_in *in, int ndof, const int *dof_vert,
                    int nthread, long long step, double *x, double *vel);

/* The sim's pass (sim.c, after each substep's solve, settings collide). */
struct ss_sim;
int ss_sim_collide(struct ss_sim *sim);

#endif
