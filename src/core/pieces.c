/* skin_sim core: the pieces of a mesh that move rigidly (ss_mesh.h).
 *
 * Pieces are the connected components of the faces through shared (welded)
 * vertices, found with a union-find over vertices (path halving, union by
 * index), O(faces) amortised. A piece is rigid when every vertex of it moves
 * with the same body part k > 0: then no face of it can stretch, bend or
 * slide relative to the body, and simulating it would only cost time. */
#include <stdlib.h>

#include "skin_sim/ss_mesh.h"
#include "union_find.h"

int ss_mesh_rigid_pieces(int nvert, int nface, const int *faces, const int *vert_weld,
                         const uint32_t *rigid_part, unsigned char *mask, ss_rigid_count *out) {
  if (out) out->npiece = out->npiece_carried = out->nface_carried = 0;
  if (nvert < 0 || nface < 0 || (nface > 0 && (!faces || !mask)) || (nvert > 0 && !rigid_part))
    return SS_E_ARG;
  for (size_t i = 0; i < 3 * (size_t)nface; i++)
    if (faces[i] < 0 || faces[i] >= nvert) return SS_E_ARG;
  if (nface == 0) return SS_OK;
  int *parent = malloc((size_t)nvert * sizeof(int));
  int *first = malloc((size_t)nvert * sizeof(int)); /* welded id -> its first copy */
  uint32_t *part = malloc((size_t)nvert * sizeof(uint32_t)); /* per root, see below */
  if (!parent || !first || !part) {
    free(parent);
    free(first);
    free(part);
    return SS_E_NOMEM;
  }
  for (int v = 0; v < nvert; v++) parent[v] = v, first[v] = -1;
  /* seam copies are one vertex */
  if (vert_weld)
    for (int v = 0; v < nvert; v++) {
      int w = vert_weld[v];
      if (w < 0 || w >= nvert) continue;
      if (first[w] < 0) first[w] = v;
      else uf_union(parent, v, first[w]);
    }
  for (int f = 0; f < nface; f++) {
    const int *c = faces + 3 * (size_t)f;
    uf_union(parent, c[0], c[1]);
    uf_union(parent, c[0], c[2]);
  }
  /* the part all vertices of a root's piece move with: UINT32_MAX none seen
   * yet, 0 once one deforms or two differ */
  for (int v = 0; v < nvert; v++) part[v] = UINT32_MAX;
  for (int v = 0; v < nvert; v++) {
    int r = uf_find(parent, v);
    uint32_t k = rigid_part[v];
    if (part[r] == UINT32_MAX) part[r] = k;
    else if (part[r] != k) part[r] = 0;
  }
  /* pieces are the roots of faces' vertices, each counted once (first[] now
   * marks roots seen) */
  int npiece = 0, ncarried = 0, nface_carried = 0;
  for (int v = 0; v < nvert; v++) first[v] = 0;
  for (int f = 0; f < nface; f++) {
    int r = uf_find(parent, faces[3 * (size_t)f]);
    int rigid = part[r] != 0 && part[r] != UINT32_MAX;
    if (!first[r]) {
      first[r] = 1;
      npiece++;
      ncarried += rigid;
    }
    if (rigid) {
      mask[f] = 0;
      nface_carried++;
    }
  }
  free(parent);
  free(first);
  free(part);
  if (out) {
    out->npiece = npiece;
    out->npiece_carried = ncarried;
    out->nface_carried = nface_carried;
  }
  return SS_OK;
}
