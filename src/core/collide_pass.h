/* Internal: the contact pass's state, shared by its lookup (collide.c)
 * and its moves (collide_move.c). */
#ifndef SKIN_SIM_COLLIDE_PASS_H
#define SKIN_SIM_COLLIDE_PASS_H

#include "bvh.h"
#include "collide.h"
#include "inside.h"

struct ss_collider {
  const ss_topo *topo;
  ss_bvh *bvh;
  ss_wind *wind;
  int nbface;
  long long *face_step;        /* (nbface) step of the cached face_buried (-1: none) */
  unsigned char *face_buried;  /* (nbface) */
  int *test_face;              /* (nbface) the faces to test in a step, each once */
  int *cand_face;              /* (nvert) nearest face of a vertex behind the surface, or -1 */
  int *move_k;                 /* (nvert) the candidates a sweep over the moves goes over */
  double *cand_x;              /* (nvert x 3) where it goes */
  double *cand_n;              /* (nvert x 3) the surface normal it goes along */
  int *hint;                   /* (nvert) the body face the vertex's last descent ended on, or -1:
                                  where the next one starts */
  int *vf_start, *vf_face;     /* (nvert + 1), (3 nface) CSR: the skin's faces around each
                                  vertex, for the squeeze guard */
  ss_bvh_shape shape;          /* the tree (bvh's) */
  int *parent;                 /* (nnode) each node's parent (-1 at the root) */
  int *leaf_of;                /* (nbface) the leaf that holds each face */
  int *look_face;              /* (nvert) the face of the local nearest point of a vertex to look
                                  further at, or -1 */
  double *look_d2;             /* (nvert) its squared distance */
  int nvert;
  int *dof_of;                 /* (nvert) the pass's index of a vertex (-1: not of the pass): what a
                                  patch move may carry */
  unsigned char *carried;      /* (ndof) 1 for a vertex a patch move carried in this pass */
  int *relook_k;               /* (nvert) the carried vertices, looked at again */
  int *tie_face;               /* (nvert) a clean face tied with a candidate's buried nearest one,
                                  or -1 */
  int *joint_of;               /* (nvert) a vertex's place in a joint move, or -1 */
  double *joint_old;           /* (nvert x 3) where the vertices of a joint move were */
};

/* The moves of the nmove candidates of move_k (collide_move.c): the whole
 * moves first, then (if carry) with the vertex's ring or all at once, else
 * halved, over some sweeps; the velocities in vel (if not NULL) lose their
 * part into the body. Candidates made or given up get cand_face -1.
 * Returns how many were made. */
int ss_collide_sweep_moves(ss_collider *c, const ss_collide_in *in, const int *dof_vert, int nmove, int carry,
                           double *x, double *vel);

#endif
