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

/* A mesh's topology (welded ids, face neighbours, edge kinds, the faces
 * around each vertex), built once from rest positions. Opaque: its layout is
 * the core's (src/core/topo.h) and may change; what users need of it is read
 * through the functions below. */
typedef struct ss_topo ss_topo;

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

/* What a caller reads of a topology (all owned by topo, valid until it is
 * destroyed): the counts, the welded id of each caller vertex (nvert), one
 * caller vertex of each welded id (nweld, the smallest index), 1 for each
 * face of (near) zero area at rest (nface), and the mean rest edge length. */
int ss_topo_nvert(const ss_topo *topo);
int ss_topo_nface(const ss_topo *topo);
int ss_topo_nweld(const ss_topo *topo);
const int *ss_topo_vert_weld(const ss_topo *topo);
const int *ss_topo_weld_rep(const ss_topo *topo);
const unsigned char *ss_topo_face_degenerate(const ss_topo *topo);
double ss_topo_rest_edge_length(const ss_topo *topo);

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
