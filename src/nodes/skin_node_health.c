/* skin_sim_node's services and health (skin_node.h): ~reset, live tuning through
 * dynamic_reconfigure, and /diagnostics (each window's status, and the status
 * during a long step). */
#include "skin_node.h"

/* ------------------------------------------------------------------ services, health */
int node_on_reset(void *user)
{
  node *nd = user;
  nd->reset_req = 1;
  ROSC_INFO("~reset: the skin is created again on the next kinematic_mesh");
  return 0;
}

/* ------------------------------------------------------------------ live tuning */
/* A set_parameters request (inside rosc_spin_once, between steps): each changed value
 * is checked by the core and refused with a log line naming it, or taken; the skin then
 * gets them from its next step (ss_sim_set_settings refactors what needs it), or is
 * created again on the next mesh when the change needs a new skin. values go back as
 * what is in force. */
static void on_reconfigure(ss_dr_value *v, const int *changed, size_t n, void *user)
{
  node *nd = user;
  int nset = 0;
  const ss_setting *t = ss_settings_table(&nset);
  ss_sim_settings want = nd->p.set;
  char err[ERR_SZ] = "", was[128], now[128];
  int any = 0, refactor = 0;
  for (size_t i = 0; i < n && i < (size_t)nset; i++) {
    if (!changed[i]) continue;
    const ss_setting *d = &t[i];
    ss_sim_settings trial = want;
    int rc;
    if (d->type == SS_SETTING_ENUM || d->type == SS_SETTING_VEC3) {
      rc = ss_setting_parse(d, v[i].str, &trial, err, sizeof err);
    } else {
      ss_setting_set(d, &trial, 0, v[i].num);
      rc = ss_setting_check(d, &trial, err, sizeof err);
    }
    ss_setting_format(d, &want, was, sizeof was);
    if (rc != SS_OK) {
      ROSC_WARN("dynamic_reconfigure: %s refused: %s; it stays %s", d->name, err, was);
      continue;
    }
    ss_setting_format(d, &trial, now, sizeof now);
    ROSC_INFO("dynamic_reconfigure: %s %s -> %s", d->name, was, now);
    want = trial;
    any = 1;
    refactor |= d->apply == SS_APPLY_REFACTOR;
  }
  if (any && nd->sim) {
    int recreate = 0;
    if (ss_sim_set_settings(nd->sim, &want, &recreate, err, sizeof err) != SS_OK) {
      ROSC_WARN("dynamic_reconfigure: refused: %s", err);
      want = nd->p.set;
    } else if (recreate) {
      nd->recreate_req = 1;
      ROSC_WARN("dynamic_reconfigure: %s: the skin is created again on the next "
                "kinematic_mesh, on its pose", err);
    } else {
      ROSC_INFO("dynamic_reconfigure: in force from the next step%s",
                refactor ? " (masses, springs and matrices rebuilt and refactored)" : "");
    }
  }
  if (want.substeps != nd->p.set.substeps || want.iterations != nd->p.set.iterations)
    ss_budget_init(&nd->budget, want.substeps, want.iterations);
  nd->p.set = want;
  for (size_t i = 0; i < n && i < (size_t)nset; i++) dr_value(&t[i], &nd->p.set, &v[i]);
}

/* Serves every setting of the table; 1 on success. */
int node_serve_settings(node *nd)
{
  int nset = 0;
  const ss_setting *t = ss_settings_table(&nset);
  ss_dr_param *par = calloc((size_t)nset, sizeof *par);
  ss_dr_value *dflt = calloc((size_t)nset, sizeof *dflt);
  ss_dr_value *cur = calloc((size_t)nset, sizeof *cur);
  char (*desc)[256] = calloc((size_t)nset, sizeof *desc);
  int ok = par && dflt && cur && desc;
  const ss_sim_settings def = ss_sim_default_settings();
  for (int i = 0; ok && i < nset; i++) {
    const ss_setting *d = &t[i];
    char range[160];
    ss_setting_format_range(d, range, sizeof range);
    snprintf(desc[i], sizeof desc[i], "%s (%s%s%s; %s)", d->help, d->unit, d->unit[0] ? ", " : "",
             range, d->apply == SS_APPLY_STEP ? "from the next step"
             : d->apply == SS_APPLY_REFACTOR ? "from the next step, refactors"
                                             : "creates the skin again");
    par[i].name = d->name;
    par[i].type = d->type == SS_SETTING_INT ? SS_DR_INT
                  : d->type == SS_SETTING_DOUBLE ? SS_DR_DOUBLE
                  : d->type == SS_SETTING_BOOL ? SS_DR_BOOL : SS_DR_STR;
    par[i].description = desc[i];
    par[i].level = 1u << d->apply;
    par[i].min = d->min;
    par[i].max = d->max;
    par[i].choices = d->type == SS_SETTING_ENUM ? d->choices : NULL;
    dr_value(d, &def, &dflt[i]);
    dr_value(d, &nd->p.set, &cur[i]);
  }
  if (ok)
    ok = node_dr_create(&nd->dr, par, dflt, cur, (size_t)nset, on_reconfigure, nd) ==
         ROSC_OK;
  free(par);
  free(dflt);
  free(cur);
  free(desc);
  return ok;
}

/* The status /diagnostics says during a long step, from the shim's own thread: it
 * reads only busy_period_ms, set before the step. */
void node_busy_status(double busy_s, int last_level, rosc_diag_busy_status *out, void *user)
{
  const node *nd = user;
  out->level = ss_input_busy(busy_s, nd->busy_period_ms, last_level, out->message,
                             (int)sizeof out->message, out->value, (int)sizeof out->value);
  snprintf(out->key, sizeof out->key, "step in progress (s)");
}

/* Publishes the status of the last window on /diagnostics when ~diagnostic_period has
 * passed; the level is the core's judgement of the window's figures (ss_input_health). */
void node_diagnose(node *nd)
{
  double now = 0, period = 1.0;
  rosc_wall_now_s(&now);
  rosc_diag_period(nd->diag, &period);
  if (now - nd->diag_wall < period) return;
  double window_s = now - nd->diag_wall;
  nd->diag_wall = now;
  uint32_t dropped = nd->dropped + (uint32_t)nd->stream.lost;
  ss_input_window w;
  w.arrived = (uint32_t)(nd->frames_in - nd->win.in);
  w.stepped = (uint32_t)(nd->processed - nd->win.processed);
  w.rejected = nd->rejected - nd->win.rejected;
  w.dropped = dropped - nd->win.dropped;
  w.skipped = nd->skipped - nd->win.skipped;
  w.resets = nd->resets - nd->win.resets;
  w.failures = nd->failures - nd->win.failures;
  unsigned long nstep = nd->nstep_ms - nd->win.nstep_ms;
  w.not_stepped = w.stepped - (uint32_t)nstep; /* created again, or no time to step */
  w.step_ms_mean = nstep ? (nd->step_ms_sum - nd->win.step_ms_sum) / (double)nstep : 0.0;
  w.period_ms = 1e-3 * (double)nd->stream.period_us;
  w.lowered = (uint32_t)(nd->budget.lowered_steps - nd->win.lowered);
  char msg[256];
  int level = ss_input_health(&w, msg, sizeof msg);
  char v[16][32];
  snprintf(v[0], sizeof v[0], "%.1f", window_s);
  snprintf(v[1], sizeof v[1], "%.2f", w.step_ms_mean);
  snprintf(v[2], sizeof v[2], "%.2f", nd->step_ms_max);
  snprintf(v[3], sizeof v[3], "%.2f", w.period_ms);
  snprintf(v[4], sizeof v[4], "%.2f", nd->budget_ms);
  snprintf(v[5], sizeof v[5], "%u", (unsigned)w.arrived);
  snprintf(v[6], sizeof v[6], "%u", (unsigned)w.stepped);
  snprintf(v[7], sizeof v[7], "%u", (unsigned)w.rejected);
  snprintf(v[8], sizeof v[8], "%u", (unsigned)w.dropped);
  snprintf(v[9], sizeof v[9], "%u", (unsigned)w.skipped);
  snprintf(v[10], sizeof v[10], "%u", (unsigned)w.resets);
  snprintf(v[11], sizeof v[11], "%u", (unsigned)w.failures);
  snprintf(v[12], sizeof v[12], "%u", (unsigned)nd->resets);
  snprintf(v[13], sizeof v[13], "%d", nd->nweld);
  /* with ~threads 0 the skin measures whether all cores pay (a busy robot
   * computer: mostly one): how many of the window's skin steps ran on more */
  snprintf(v[14], sizeof v[14], "%lu of %lu", nd->steps_multi - nd->win.steps_multi,
           nd->steps - nd->win.steps);
  char wv[6][64];
  snprintf(wv[0], sizeof wv[0], "%d x %d of %d x %d", nd->budget.substeps, nd->budget.iterations,
           nd->p.set.substeps, nd->p.set.iterations);
  snprintf(wv[1], sizeof wv[1], "%u", (unsigned)w.lowered);
  snprintf(wv[2], sizeof wv[2], "%d", nd->nface_sim);
  snprintf(wv[3], sizeof wv[3], "%d", nd->nface_carried);
  snprintf(wv[4], sizeof wv[4], "%d", nd->faces_turned);
  snprintf(wv[5], sizeof wv[5], "%d", nd->vertices_far);
  enum { NKV = 21 };
  rosc_kv kv[NKV + SS_NWARNING] = {{"window (s)", v[0]},         {"step time mean (ms)", v[1]},
                  {"step time max (ms)", v[2]}, {"input period (ms)", v[3]},
                  {"step budget (ms)", v[4]},   {"inputs received", v[5]},
                  {"inputs processed", v[6]},   {"inputs rejected", v[7]},
                  {"inputs dropped", v[8]},     {"inputs skipped", v[9]},
                  {"resets", v[10]},            {"failures", v[11]},
                  {"resets total", v[12]},      {"skin vertices", v[13]},
                  {"skin steps on more than one thread", v[14]},
                  {"substeps x iterations in force", wv[0]},
                  {"steps below the settings' work (budget)", wv[1]},
                  {"triangles simulated", wv[2]}, {"triangles carried rigidly", wv[3]},
                  {"skin faces turned against the body", wv[4]},
                  {"skin vertices over an edge from the body", wv[5]}};
  /* the core's warnings over the skin's life (since it was last created) */
  char wkey[SS_NWARNING][48], wval[SS_NWARNING][24];
  const ss_warning *warn = nd->sim ? ss_sim_warnings(nd->sim) : NULL; /* no skin yet: 0 */
  for (int k = 0; k < SS_NWARNING; k++) {
    snprintf(wkey[k], sizeof wkey[k], "skin steps %s (since created)", ss_warning_name(k));
    snprintf(wval[k], sizeof wval[k], "%lld", warn ? warn[k].number : 0LL);
    kv[NKV + k].key = wkey[k];
    kv[NKV + k].value = wval[k];
  }
  rosc_diag_update(nd->diag, level, msg, kv, sizeof kv / sizeof kv[0]);
  nd->win.in = nd->frames_in;
  nd->win.processed = nd->processed;
  nd->win.nstep_ms = nd->nstep_ms;
  nd->win.step_ms_sum = nd->step_ms_sum;
  nd->win.rejected = nd->rejected;
  nd->win.dropped = dropped;
  nd->win.skipped = nd->skipped;
  nd->win.resets = nd->resets;
  nd->win.failures = nd->failures;
  nd->win.steps = nd->steps;
  nd->win.steps_multi = nd->steps_multi;
  nd->win.lowered = nd->budget.lowered_steps;
  nd->step_ms_max = 0.0;
}
