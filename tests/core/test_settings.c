/* The settings table (ss_settings.h) and live changes (ss_sim_set_settings):
 *  - the defaults the table gives are the documented values, bit for bit (the table
 *    replaced ss_sim_default_settings' hand-written ones: they must not drift);
 *  - every bad value is refused with one sentence naming the setting and its range;
 *  - every setting's default prints as text that parses back to the same bits;
 *  - a live change of a setting that needs new masses, springs or matrices (young,
 *    poisson, density, stiffness, damping, bending) or none (slide, tether, gravity,
 *    substeps, iterations) gives, from the next step, the same bits as a simulation
 *    created with it (bending: the same to 1e-12, its weights are rescaled);
 *  - a structural change (barycenters, solver, method, threads, bending on) asks for a
 *    new simulation and changes nothing; a bad value changes nothing. */
#include "sim_fixtures.h"
#include "skin_sim/ss_settings.h"
#include "skin_sim/ss_sim.h"
#include "ss_test.h"

#include <string.h>

static void defaults(void) {
  ss_sim_settings s = ss_sim_default_settings();
  CHECK(s.solver == SS_SOLVER_QUASI_NEWTON && s.mover.method == SS_METHOD_WALK);
  CHECK(s.dt == 1.0 / 30.0 && s.substeps == 4 && s.iterations == 2 && s.tol == 1e-4);
  CHECK(s.safety_residual == 0.05 && s.iterations_max == 32 && s.lbfgs_history == 6);
  CHECK(s.young == 50.0 && s.poisson == 0.3 && s.density == 1.0 && s.anchor_stiffness == 1e3);
  CHECK(s.barycenter_anchors == 1 && s.bending == 0.0 && s.damping == 0.0);
  CHECK(s.tether == 3.0); /* drift-free: the skin comes home after a motion (issue 11) */
  CHECK(s.slide == 30.0 * log(2.0)); /* the former default, bit for bit */
  CHECK(s.gravity[0] == 0.0 && s.gravity[1] == 0.0 && s.gravity[2] == 0.0);
  CHECK(s.mover.walk_max_steps == 512 && s.mover.nring_rings == 2 && s.face_mask == NULL);
  CHECK(s.threads == 0); /* all cores where they pay (sim.c: auto_threads) */
  CHECK(ss_settings_check(&s, NULL, 0) == SS_OK);
  ss_mover_settings m = ss_mover_default_settings();
  CHECK(memcmp(&m, &s.mover, sizeof m) == 0);
}

static void refusals(void) {
  struct {
    const char *name, *text, *says;
  } bad[] = {
      {"poisson", "0.5", "poisson must be in [0, 0.5)"},
      {"poisson", "-0.1", "poisson must be in [0, 0.5)"},
      {"density", "0", "density must be in (0, inf)"},
      {"young", "inf", "young must be in [0, inf)"},
      {"substeps", "0", "substeps must be in [1, 1000]"},
      {"threads", "65", "threads must be in [0, 64]"},
      {"substeps", "2.5", "substeps expects a whole number"},
      {"method", "crawl", "method expects walk, project, nring, got 'crawl'"},
      {"solver", "", "solver expects newton, quasi-newton"},
      {"gravity", "0 0", "gravity expects three numbers"},
      {"gravity", "0 nan 0", "gravity must be finite (component y is nan)"},
      {"barycenters", "maybe", "barycenters expects true or false"},
      {"slide", "nan", "slide must be in [0, inf]"},
      {"tether", "1e999", "tether expects a number"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    ss_sim_settings s = ss_sim_default_settings(), before = s;
    char err[256] = "";
    const ss_setting *d = ss_setting_find(bad[i].name);
    CHECK(d != NULL);
    if (!d) continue;
    int rc = ss_setting_parse(d, bad[i].text, &s, err, sizeof err);
    CHECK_MSG(rc == SS_E_ARG && strstr(err, bad[i].says) && memcmp(&s, &before, sizeof s) == 0,
              "%s '%s': %s", bad[i].name, bad[i].text, err);
  }
  /* and through the core's create: one sentence naming it */
  ss_sim_settings s = ss_sim_default_settings();
  s.poisson = 0.5;
  char err[256] = "";
  CHECK(ss_settings_check(&s, err, sizeof err) == SS_E_ARG && strstr(err, "poisson"));
  /* slide may be +inf (frictionless), and the CLI names map to the table */
  CHECK(ss_setting_parse(ss_setting_find("slide"), "inf", &s, NULL, 0) == SS_OK && isinf(s.slide));
  CHECK(ss_setting_find_cli("--max-steps") == ss_setting_find("walk_max_steps"));
  CHECK(ss_setting_find_cli("stiffness") == ss_setting_find("stiffness"));
  CHECK(ss_setting_find("face_mask") == NULL && ss_setting_find_cli("--frames") == NULL);
}

static void round_trip(void) {
  int n = 0;
  const ss_setting *t = ss_settings_table(&n);
  CHECK(n >= 20);
  const ss_sim_settings def = ss_sim_default_settings();
  for (int i = 0; i < n; i++) {
    char text[128], err[256] = "";
    ss_setting_format(&t[i], &def, text, sizeof text);
    ss_sim_settings s = ss_sim_default_settings();
    ss_setting_set(&t[i], &s, 0, t[i].type == SS_SETTING_VEC3 ? 7.0 : t[i].max); /* disturb */
    int rc = ss_setting_parse(&t[i], text, &s, err, sizeof err);
    CHECK_MSG(rc == SS_OK && ss_setting_equal(&t[i], &s, &def), "%s: '%s' %s", t[i].name, text,
              err);
    char dtext[128];
    ss_setting_format_default(&t[i], dtext, sizeof dtext);
    CHECK_MSG(strcmp(dtext, text) == 0, "%s: default '%s' vs value '%s'", t[i].name, dtext, text);
  }
}

/* Steps sim over the fixture's motion from frame f0 to f1. */
static void run(ss_sim *sim, const fx_mesh *g, double *pose, int f0, int f1) {
  for (int f = f0; f < f1; f++) {
    fx_pose(g, (f + 1) / 30.0, pose);
    CHECK(ss_sim_step(sim, pose, 1.0 / 30.0, NULL, NULL, 0) == SS_OK);
  }
}

typedef void (*change_fn)(ss_sim_settings *s);
static void c_young(ss_sim_settings *s) { s->young = 120.0; }
static void c_poisson(ss_sim_settings *s) { s->poisson = 0.45; }
static void c_density(ss_sim_settings *s) { s->density = 3.0; }
static void c_stiff(ss_sim_settings *s) { s->anchor_stiffness = 300.0; }
static void c_damping(ss_sim_settings *s) { s->damping = 2.0; }
static void c_slide(ss_sim_settings *s) { s->slide = 3.0; s->tether = 1.5; }
static void c_gravity(ss_sim_settings *s) { s->gravity[2] = -9.81; }
static void c_substeps(ss_sim_settings *s) { s->substeps = 3; s->iterations = 4; }
static void c_bending(ss_sim_settings *s) { s->bending = 5e-3; }

static void live(int solver) {
  fx_mesh g = fx_grid(9, 9, 1.0, 1.0, 0.1);
  double *pose = malloc(sizeof(double) * 3 * (size_t)g.nvert);
  struct {
    const char *what;
    change_fn fn;
    double tol;
  } cases[] = {{"young", c_young, 0}, {"poisson", c_poisson, 0}, {"density", c_density, 0},
               {"stiffness", c_stiff, 0}, {"damping", c_damping, 0}, {"slide, tether", c_slide, 0},
               {"gravity", c_gravity, 0}, {"substeps, iterations", c_substeps, 0},
               {"bending", c_bending, 1e-12}};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    ss_sim_settings a = ss_sim_default_settings();
    a.solver = solver;
    if (cases[c].fn == c_bending) a.bending = 1e-3; /* on in both: rescaled in place */
    ss_sim_settings b = a;
    cases[c].fn(&b);
    ss_sim *live_sim = NULL, *fresh = NULL;
    CHECK(ss_sim_create(&live_sim, g.nvert, g.pos, g.nface, g.faces, NULL, &a, NULL, 0) == SS_OK);
    CHECK(ss_sim_create(&fresh, g.nvert, g.pos, g.nface, g.faces, NULL, &b, NULL, 0) == SS_OK);
    if (!live_sim || !fresh) continue;
    int recreate = -1;
    char err[256] = "";
    CHECK(ss_sim_set_settings(live_sim, &b, &recreate, err, sizeof err) == SS_OK && recreate == 0);
    run(live_sim, &g, pose, 0, 12);
    run(fresh, &g, pose, 0, 12);
    const double *x = ss_sim_skin_positions(live_sim), *y = ss_sim_skin_positions(fresh);
    double diff = 0.0;
    for (int i = 0; i < 3 * g.nvert; i++) diff = fmax(diff, fabs(x[i] - y[i]));
    CHECK_MSG(diff <= cases[c].tol, "%s, solver %s: live change differs from a fresh sim by %g",
              cases[c].what, ss_solver_name(solver), diff);
    ss_sim_destroy(live_sim);
    ss_sim_destroy(fresh);
  }
  /* a change mid-run is taken from the next step and moves the skin */
  ss_sim_settings a = ss_sim_default_settings();
  a.solver = solver;
  ss_sim *s1 = NULL, *s2 = NULL;
  CHECK(ss_sim_create(&s1, g.nvert, g.pos, g.nface, g.faces, NULL, &a, NULL, 0) == SS_OK);
  CHECK(ss_sim_create(&s2, g.nvert, g.pos, g.nface, g.faces, NULL, &a, NULL, 0) == SS_OK);
  if (s1 && s2) {
    run(s1, &g, pose, 0, 6);
    run(s2, &g, pose, 0, 6);
    ss_sim_settings b = a;
    b.anchor_stiffness = 50.0;
    CHECK(ss_sim_set_settings(s2, &b, NULL, NULL, 0) == SS_OK);
    CHECK(ss_sim_get_settings(s2)->anchor_stiffness == 50.0);
    run(s1, &g, pose, 6, 12);
    run(s2, &g, pose, 6, 12);
    double diff = 0.0;
    for (int i = 0; i < 3 * g.nvert; i++)
      diff = fmax(diff, fabs(ss_sim_skin_positions(s1)[i] - ss_sim_skin_positions(s2)[i]));
    CHECK_MSG(diff > 1e-6, "a softer skin mid-run must lag more (diff %g)", diff);
  }
  ss_sim_destroy(s1);
  ss_sim_destroy(s2);
  free(pose);
  fx_free(&g);
}

static void structural(void) {
  fx_mesh g = fx_grid(6, 6, 1.0, 1.0, 0.0);
  ss_sim_settings a = ss_sim_default_settings();
  ss_sim *sim = NULL;
  CHECK(ss_sim_create(&sim, g.nvert, g.pos, g.nface, g.faces, NULL, &a, NULL, 0) == SS_OK);
  if (!sim) return;
  struct {
    const char *name;
    ss_sim_settings s;
  } cases[5];
  for (int i = 0; i < 5; i++) cases[i].s = a;
  cases[0].name = "barycenters", cases[0].s.barycenter_anchors = 0;
  cases[1].name = "solver", cases[1].s.solver = SS_SOLVER_NEWTON;
  cases[2].name = "method", cases[2].s.mover.method = SS_METHOD_PROJECT;
  cases[3].name = "lbfgs_history", cases[3].s.lbfgs_history = 3;
  cases[4].name = "bending", cases[4].s.bending = 1e-3; /* turned on: hinges to build */
  for (int i = 0; i < 5; i++) {
    cases[i].s.young = 99.0; /* with a change that could apply: nothing applies */
    int recreate = 0;
    char err[256] = "";
    CHECK(ss_sim_set_settings(sim, &cases[i].s, &recreate, err, sizeof err) == SS_OK);
    CHECK_MSG(recreate == 1 && strstr(err, cases[i].name) && strstr(err, "created again"),
              "%s: recreate %d, '%s'", cases[i].name, recreate, err);
    CHECK(ss_sim_get_settings(sim)->young == 50.0);
  }
  ss_sim_settings bad = a;
  bad.young = 80.0;
  bad.poisson = 0.7;
  char err[256] = "";
  CHECK(ss_sim_set_settings(sim, &bad, NULL, err, sizeof err) == SS_E_ARG && strstr(err, "poisson"));
  CHECK(ss_sim_get_settings(sim)->young == 50.0 && ss_sim_get_settings(sim)->poisson == 0.3);
  ss_sim_destroy(sim);
  fx_free(&g);
}

/* The range rule and text the nodes' own parameter tables share with the settings. */
static void ranges(void) {
  CHECK(ss_range_contains(0.0, 0.0, 0, 0.5, 1) && !ss_range_contains(0.5, 0.0, 0, 0.5, 1));
  CHECK(!ss_range_contains(0.0, 0.0, 1, INFINITY, 0) && ss_range_contains(INFINITY, 0.0, 1, INFINITY, 0));
  CHECK(!ss_range_contains(NAN, -INFINITY, 0, INFINITY, 0));
  CHECK(!ss_range_contains(INFINITY, -INFINITY, 1, INFINITY, 1));
  char buf[64];
  ss_range_format(0.0, 0, 0.5, 1, buf, sizeof buf);
  CHECK(strcmp(buf, "[0, 0.5)") == 0);
  ss_range_format(0.0, 1, INFINITY, 0, buf, sizeof buf);
  CHECK(strcmp(buf, "(0, inf]") == 0);
  ss_range_format(-INFINITY, 1, INFINITY, 1, buf, sizeof buf);
  CHECK(strcmp(buf, "finite") == 0);
}

int main(void) {
  defaults();
  ranges();
  refusals();
  round_trip();
  live(SS_SOLVER_QUASI_NEWTON);
  live(SS_SOLVER_NEWTON);
  structural();
  return ss_test_finish("test_settings");
}
