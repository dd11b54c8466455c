/* The layout of a mesh's topology (ss_topo, opaque in skin_sim/ss_mesh.h):
 * the core's inside. The core's passes read it directly; so do the lab, the
 * benchmarks and the tests, which are built with the project's internal
 * libraries and may follow its changes. Users outside read it through the
 * accessors of ss_mesh.h (ss_topo_nweld, ss_topo_vert_weld, ...). */
#ifndef SKIN_SIM_TOPO_H
#define SKIN_SIM_TOPO_H

#include "skin_sim/ss_mesh.h"

enum ss_edge_kind {
  SS_EDGE_INTERIOR = 0,    /* exactly two faces */
  SS_EDGE_BOUNDARY = 1,    /* one face */
  SS_EDGE_NONMANIFOLD = 2  /* three or more faces */
};

struct ss_topo {
  int nvert;                 /* caller's vertex count */
  int nface;                 /* triangle count */
  int nweld;                 /* distinct vertices after welding */
  int nedge;                 /* distinct (welded) edges */
  int nboundary_edge;        /* edges with one face */
  int nnonmanifold_edge;     /* edges with three or more faces */
  int ndegenerate_face;      /* faces of (near) zero area at rest */
  int *face_vert;            /* (nface x 3) caller vertex index of each corner (a copy) */
  int *vert_weld;            /* (nvert) welded id of each caller vertex */
  int *weld_rep;             /* (nweld) one caller vertex of each welded id (the smallest index) */
  int *face_adj;             /* (nface x 3) face across edge k, or -1 (boundary or non-manifold) */
  int *face_adj_edge;        /* (nface x 3) index of that same edge in the neighbour face, or -1 */
  unsigned char *edge_kind;  /* (nface x 3) ss_edge_kind of edge k */
  unsigned char *face_degenerate; /* (nface) 1 if the face's rest area is below tolerance */
  int *vf_start;             /* (nweld + 1) CSR: faces around welded vertex w are */
  int *vf_face;              /*   vf_face[vf_start[w] .. vf_start[w+1]-1]; (3 nface) */
  double mean_edge_length;   /* mean rest length over distinct edges */
};

#endif
