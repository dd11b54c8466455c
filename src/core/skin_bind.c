/* skin_sim core: where a separate skin binds to its body, asked before the
 * skin is created (ss_sim.h, ss_sim_skin_binding): the same closest points
 * as ss_sim_bind, so that a caller can refuse a skin too far from its body
 * and carry the pieces that ride one rigid link. */
#include <math.h>
#include <stdlib.h>

#include "bvh.h"
#include "skin_sim/ss_sim.h"
#include "ss_err.h"

int ss_sim_skin_binding(int body_nvert, const double *body_rest, int body_nface,
                        const int *body_faces, const ss_sim_mesh *skin, const uint32_t *body_part,
                        uint32_t *skin_part, double *dist, char *err, int err_sz) {
  if (!skin || !skin->pos || skin->nvert <= 0)
    return ss_fail(err, err_sz, SS_E_MESH, "the skin mesh has no vertices");
  for (int i = 0; i < 3 * skin->nvert; i++)
    if (!isfinite(skin->pos[i]))
      return ss_fail(err, err_sz, SS_E_NONFINITE, "skin vertex %d has a non-finite coordinate", i / 3);
  ss_topo *topo = NULL;
  ss_bvh *bvh = NULL;
  int status = ss_topo_create(&topo, body_nvert, body_rest, body_nface, body_faces, -1.0, err, err_sz);
  if (status == SS_OK && ss_bvh_create(&bvh, topo) != SS_OK)
    status = ss_fail(err, err_sz, SS_E_NOMEM, "out of memory for the body's BVH");
  if (status == SS_OK) {
    ss_bvh_refit(bvh, body_rest);
    for (int v = 0; v < skin->nvert; v++) {
      int f = -1;
      double uv[2];
      double d2 = ss_bvh_closest(bvh, body_rest, skin->pos + 3 * v, &f, uv);
      if (dist) dist[v] = sqrt(d2);
      if (skin_part && body_part) {
        uint32_t k = 0;
        if (f >= 0) {
          const int *c = body_faces + 3 * f;
          k = body_part[c[0]];
          if (body_part[c[1]] != k || body_part[c[2]] != k) k = 0;
        }
        skin_part[v] = k;
      }
    }
  }
  ss_bvh_destroy(bvh);
  ss_topo_destroy(topo);
  return status;
}
