/* ss_mesh.h, ss_weld_create: a mesh with duplicated seam vertices becomes one
 * welded skin; a mesh without seams is unchanged; bad meshes are refused. */
#include "skin_sim/ss_mesh.h"
#include "ss_test.h"

#include <string.h>

int main(void)
{
  /* a unit square of two triangles whose diagonal is a seam: vertices 0 and 2
   * are duplicated as 4 and 5 (the second triangle uses the copies) */
  const double pos[18] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0};
  const int faces[6] = {0, 1, 2, 4, 5, 3};
  char err[256] = "";
  ss_weld *w = NULL;
  CHECK(ss_weld_create(&w, 6, pos, 2, faces, -1.0, err, sizeof err) == SS_OK);
  if (w) {
    CHECK(w->nvert == 6 && w->nweld == 4 && w->nface == 2);
    CHECK(w->vert_weld[4] == w->vert_weld[0] && w->vert_weld[5] == w->vert_weld[2]);
    CHECK(w->weld_rep[w->vert_weld[4]] == 0 && w->weld_rep[w->vert_weld[5]] == 2);
    for (int v = 0; v < 6; v++)
      CHECK(memcmp(w->pos + 3 * w->vert_weld[v], pos + 3 * v, 3 * sizeof(double)) == 0);
    for (int i = 0; i < 6; i++) CHECK(w->faces[i] == w->vert_weld[faces[i]]);
    /* the two faces now share an edge of welded ids */
    CHECK(w->faces[0] == w->faces[3] && w->faces[2] == w->faces[4]);
  }
  ss_weld_destroy(w);
  /* a tolerance: 1 mm apart welds at 2 mm, not at 0 */
  double near[18];
  memcpy(near, pos, sizeof near);
  near[12] = 0.001;
  CHECK(ss_weld_create(&w, 6, near, 2, faces, 0.002, err, sizeof err) == SS_OK);
  CHECK(w && w->nweld == 4);
  ss_weld_destroy(w);
  CHECK(ss_weld_create(&w, 6, near, 2, faces, 0.0, err, sizeof err) == SS_OK);
  CHECK(w && w->nweld == 5);
  ss_weld_destroy(w);
  /* no seams: identity */
  const int f2[6] = {0, 1, 2, 0, 2, 3};
  CHECK(ss_weld_create(&w, 4, pos, 2, f2, -1.0, err, sizeof err) == SS_OK);
  CHECK(w && w->nweld == 4);
  for (int v = 0; w && v < 4; v++) CHECK(w->vert_weld[v] == v && w->weld_rep[v] == v);
  ss_weld_destroy(w);
  /* bad meshes: one clear error, no output */
  const int bad[6] = {0, 1, 2, 4, 9, 3};
  w = (ss_weld *)1;
  CHECK(ss_weld_create(&w, 6, pos, 2, bad, -1.0, err, sizeof err) == SS_E_MESH && w == NULL);
  CHECK(strstr(err, "triangle 1") != NULL);
  double nan_pos[18];
  memcpy(nan_pos, pos, sizeof nan_pos);
  nan_pos[7] = NAN;
  CHECK(ss_weld_create(&w, 6, nan_pos, 2, faces, -1.0, err, sizeof err) == SS_E_NONFINITE);
  CHECK(ss_weld_create(NULL, 6, pos, 2, faces, -1.0, err, sizeof err) == SS_E_ARG);
  ss_weld_destroy(NULL);
  return ss_test_finish("test_weld");
}
