/* skin_sim core: triangle mesh validation and topology.
 *
 * A mesh is given as flat arrays owned by the caller: positions (nvert x 3
 * doubles, xyz interleaved) and faces (nface x 3 ints, counter-clockwise seen
 * from outside). Topology is built once per mesh from its rest positions.
 *
 * Edge k of face f runs from its corner k to corner (k+1)%3. In the face's
 * canonical 2D space (corner 0 at (0,0), corner 1 at (1,0), corner 2 at (0,1))
 * edge 0 lies on y = 0, edge 1 on x + y = 1, edge 2 on x = 0.
 *
 * Coincident vertices (UV or normal seams) are welded for topology only: two
 * caller vertices closer than weld_tol at rest share a welded id, so faces on
 * either side of a seam are neighbours; positions and outputs keep the caller's
 * vertex order. An edge shared by more than two faces is non-manifold: walking
 * treats it as a boundary. */
#ifndef SKIN_SIM_SS_MESH_H
#define SKIN_SIM_SS_MESH_H

#include "ss_common.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum ss_edge_kind {
  SS_EDGE_INTERIOR = 0,    /* exactly two faces */
  SS_EDGE_BOUNDARY = 1,    /* one face */
  SS_EDGE_NONMANIFOLD = 2  /* three or more faces */
};

typedef struct ss_topo {
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
} ss_topo;

/* Checks a mesh given by the caller: nvert > 0, nface > 0, every index in
 * [0, nvert), every position finite. Returns SS_OK or SS_E_MESH /
 * SS_E_NONFINITE with a message naming the first offending face or vertex.
 * pos may be NULL to check indices only. */
int ss_mesh_check(int nvert, const double *pos, int nface, const int *faces,
                  char *err, int err_sz);

/* Builds topology from rest positions; the mesh is checked first. weld_tol is
 * an absolute distance (0 welds only bit-identical positions; negative picks
 * 1e-9 times the bounding box diagonal). Faces repeating a vertex are kept and
 * flagged degenerate. On success *out owns its memory. */
int ss_topo_create(ss_topo **out, int nvert, const double *rest_pos, int nface,
                   const int *faces, double weld_tol, char *err, int err_sz);
void ss_topo_destroy(ss_topo *topo);

/* Mean length of the distinct edges of the mesh posed at pos. */
double ss_topo_mean_edge_length(const ss_topo *topo, const double *pos);

/* A mesh with its coincident vertices welded into one: the skin of a body
 * whose seams (normals, UVs, one mesh per part) duplicate vertices, so that
 * no seam can open. Welded as ss_topo_create welds (same weld_tol meaning);
 * welded vertex w sits at its representative, the smallest caller vertex of
 * w; faces keep their order and corners, renumbered to welded ids. */
typedef struct ss_weld {
  int nvert;       /* caller's vertex count */
  int nweld;       /* welded vertices */
  int nface;       /* triangles (as the caller's) */
  double *pos;     /* (nweld x 3) welded positions */
  int *faces;      /* (nface x 3) welded vertex ids */
  int *vert_weld;  /* (nvert) welded id of each caller vertex */
  int *weld_rep;   /* (nweld) representative caller vertex of each welded id */
} ss_weld;

/* Welds a mesh (checked first; errors as ss_topo_create). On success *out
 * owns its memory; free it with ss_weld_destroy. */
int ss_weld_create(ss_weld **out, int nvert, const double *pos, int nface, const int *faces,
                   double weld_tol, char *err, int err_sz);
void ss_weld_destroy(ss_weld *weld);

/* ---- rigid pieces ----------------------------------------------------------
 * A robot's body is mostly rigid: each link's visual meshes move with that
 * link alone, and a skin piece over such a mesh has nothing to simulate. A
 * PIECE is a set of faces connected through shared vertices (seam copies
 * joined through vert_weld, when not NULL: (nvert) welded id of each vertex,
 * as ss_weld's). rigid_part (nvert) says what each vertex moves with: k > 0,
 * rigidly with body part k (a link or bone it is skinned to alone); 0, a
 * blend of several (it deforms). A piece all of whose vertices move with one
 * part k > 0 moves rigidly: its faces get mask 0 (mask: nface, in and out;
 * faces already 0 stay 0), so that a skin built with that face mask carries
 * it with the body exactly and simulates the rest. Counts go to out (may be
 * NULL). Returns SS_OK, SS_E_ARG (NULL arrays, negative counts) or
 * SS_E_NOMEM. Allocates and frees its own scratch. */
typedef struct ss_rigid_count {
  int npiece;          /* pieces of the mesh */
  int npiece_carried;  /* of which rigid */
  int nface_carried;   /* their faces, all given mask 0 */
} ss_rigid_count;
int ss_mesh_rigid_pieces(int nvert, int nface, const int *faces, const int *vert_weld,
                         const uint32_t *rigid_part, unsigned char *mask, ss_rigid_count *out);

#ifdef __cplusplus
}
#endif
#endif
