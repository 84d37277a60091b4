/* A case run whole (run_case.h): its models (run.c, fb_run_models), then
 * its ensemble (ensemble.c) and the verdicts that settle on it
 * (verdict.c). The ensemble runs above the models: it runs its members
 * with fb_run_models, and this file calls both. */
#include "run_case.h"

#include "clock.h"
#include "ensemble.h"
#include "verdict.h"

/* the verdicts; and, where one is unsettled and the case leaves [run]
 * ensemble to the run (c.ensemble_auto), the sequential test
 * (fb_ensemble_sequential), which stops before a look whose estimate would
 * pass [run] max_wall_s */
static fb_status settle(fb_run *r, double t_start, fb_progress_fn progress, void *user,
                        fb_diag *diag) {
  const double t0 = fb_clock_s(), c0 = fb_clock_cpu_s();
  int unsettled = fb_verdict_assess(r);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble) r->models_wall_s += r->model[i].run.wall_s;
  if (!unsettled || r->c.ensemble > 1 || !r->c.ensemble_auto) return FB_OK;
  fb_status st = fb_ensemble_sequential(r, t_start, progress, user, diag);
  if (st != FB_OK) return st;
  r->ensemble_wall_s = fb_clock_s() - t0;
  r->ensemble_cpu_s = fb_clock_cpu_s() - c0;
  r->ensemble_auto_skipped = r->seq_looks == 0 && r->seq_wall_cut;
  fb_verdict_assess(r);
  return FB_OK;
}

fb_status fb_run_case(fb_run *r, const fb_case *c, fb_progress_fn progress, void *user,
                      fb_diag *diag) {
  const double t_start = fb_clock_s();
  fb_status st = fb_run_models(r, c, progress, user, diag);
  if (st != FB_OK || c->member) return st;
  r->t_run_start = t_start;
  const double t0 = fb_clock_s(), c0 = fb_clock_cpu_s();
  st = fb_ensemble_measure(r, progress, user, diag);
  if (r->c.ensemble > 1) {
    r->ensemble_wall_s = fb_clock_s() - t0;
    r->ensemble_cpu_s = fb_clock_cpu_s() - c0;
  }
  if (st == FB_OK) st = settle(r, t_start, progress, user, diag);
  if (st != FB_OK) {
    fb_run_free(r);
    return st;
  }
  return FB_OK;
}
