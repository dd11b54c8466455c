/* ss_sim_count_off_body: at rest nothing is turned or far; a vertex lifted
 * more than an edge off the body counts as far; a face folded over counts as
 * turned; a vertex moved along the body stays near it; a skin built with its faces wound
 * the other way round is not turned at rest. */
#include "skin_sim/ss_sim.h"
#include "ss_test.h"
#include "ss_test_mesh.h"

#include <string.h>

int main(void) {
  test_mesh g = test_grid(4, 4, 0.0, 1);
  ss_sim_settings set = ss_sim_default_settings();
  set.threads = 1;
  char err[256] = "";
  ss_sim *sim = NULL;
  CHECK(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &set, err, sizeof err) == SS_OK);
  if (!sim) return ss_test_finish("test_count_off_body");
  int turned = -1, far = -1;
  ss_sim_count_off_body(sim, &turned, &far);
  CHECK(turned == 0 && far == 0);

  double *x = malloc(sizeof(double) * 3 * (size_t)g.nvert);
  memcpy(x, g.pos, sizeof(double) * 3 * (size_t)g.nvert);
  /* the middle vertex (2, 2) lifted 1.5 edges: far; its faces tilt, none turns */
  int mid = 2 * 5 + 2;
  x[3 * mid + 2] = 1.5;
  CHECK(ss_sim_set_state(sim, x, NULL, err, sizeof err) == SS_OK);
  ss_sim_count_off_body(sim, &turned, &far);
  CHECK(far == 1 && turned == 0);
  /* the same vertex pushed across its neighbours in the plane (to x = 3.6):
   * the faces between fold over; it is 1.6 edges from its anchor but on the
   * body, so not far */
  x[3 * mid + 2] = 0.0;
  x[3 * mid + 0] = 3.6;
  CHECK(ss_sim_set_state(sim, x, NULL, err, sizeof err) == SS_OK);
  ss_sim_count_off_body(sim, &turned, &far);
  CHECK_MSG(turned >= 2, "turned %d", turned);
  CHECK(far == 0);
  /* and 1.2 edges above the plane there: far */
  x[3 * mid + 2] = 1.2;
  CHECK(ss_sim_set_state(sim, x, NULL, err, sizeof err) == SS_OK);
  ss_sim_count_off_body(sim, &turned, &far);
  CHECK(far == 1);
  ss_sim_count_off_body(sim, NULL, NULL); /* both optional */
  ss_sim_destroy(sim);

  /* the skin wound the other way round (a separate skin bound by closest
   * point): turned is judged against its own rest, so 0 at rest */
  int *flip = malloc(sizeof(int) * 3 * (size_t)g.nface);
  for (int f = 0; f < g.nface; f++) {
    flip[3 * f] = g.faces[3 * f];
    flip[3 * f + 1] = g.faces[3 * f + 2];
    flip[3 * f + 2] = g.faces[3 * f + 1];
  }
  ss_sim_mesh skin = {g.nvert, g.pos, g.nface, flip};
  sim = NULL;
  CHECK(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, &skin, &set, err, sizeof err) == SS_OK);
  if (sim) {
    ss_sim_count_off_body(sim, &turned, &far);
    CHECK(turned == 0 && far == 0);
  }
  ss_sim_destroy(sim);
  free(flip);
  free(x);
  test_mesh_free(&g);
  return ss_test_finish("test_count_off_body");
}
