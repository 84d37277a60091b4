/* fourbar impact below the command: the reference, each engine's single
 * impact through the engine table, the closed form (impact_study.h). */
#include "impact_study.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

double fb_impact_rel(double x, double ref) { return ref != 0.0 ? (x - ref) / fabs(ref) : x - ref; }

/* the impact op of the engine called name, with its single impact of a
 * law; NULL with the reason (the flag --engine named) in diag */
static const fb_engine_impact *law_engine(const char *name, fb_diag *diag) {
  int id = 0;
  while (id < FB_ENGINE_COUNT && strcmp(fb_engine_name((fb_engine_id)id), name) != 0) id++;
  if (id == FB_ENGINE_COUNT) {
    fb_diag_set(diag, FB_ERR_ARG, "--engine '%s': no such engine", name);
    return NULL;
  }
  fb_diag dg;
  const fb_engine *e = fb_engine_get((fb_engine_id)id, &dg);
  if (!e) {
    char display[32]; /* the engine's name capitalised: "Bullet" */
    snprintf(display, sizeof display, "%s", name);
    display[0] = (char)toupper((unsigned char)display[0]);
    fb_diag_set(diag, FB_ERR_ARG, "--engine %s: %s is not in this build: %s", name, display,
                fb_engine_howto((fb_engine_id)id));
    return NULL;
  }
  if (!e->impact || !e->impact->law) {
    fb_diag_set(diag, FB_ERR_ARG, "--engine %s: it has no single impact of a law", name);
    return NULL;
  }
  return e->impact;
}

/* one engine's impact into run */
static void run_engine(fb_impact_run *run, const char *name, const fb_engine_impact *e,
                       const fb_impact_def *d, const fb_impact_opts *o) {
  fb_diag dg;
  memset(run, 0, sizeof *run);
  run->engine = name;
  run->status = e->law(&run->r, d, o, &dg);
  if (run->status != FB_OK) snprintf(run->msg, sizeof run->msg, "%s", dg.msg);
}

fb_status fb_impact_study_run(fb_impact_study *out, const fb_impact_request *q, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  out->bad_input = 1;
  const fb_engine_impact *engine[FB_IMPACT_RUNS_MAX] = {law_engine("ode", diag), NULL};
  if (!engine[0]) return FB_ERR_ARG;
  const char *names[FB_IMPACT_RUNS_MAX] = {"ode", q->engine};
  out->n_runs = 1;
  if (q->engine) {
    if (!(engine[1] = law_engine(q->engine, diag))) return FB_ERR_ARG;
    out->n_runs = 2;
  }
  fb_impact_def d = q->d;
  d.law.mass = d.mass;
  d.h = 1.0; /* checked below once the default is known */
  fb_status st = fb_impact_check(&d, diag);
  if (st != FB_OK) return st;
  const double t_est = fb_impact_duration_estimate(&d);
  if (q->h < 0.0)
    return fb_diag_set(diag, FB_ERR_RANGE, "--h-s %g: the step size must be positive", q->h);
  d.h = q->h > 0.0 ? q->h : t_est / 200.0;
  if ((st = fb_impact_check(&d, diag)) != FB_OK) return st;
  out->d = d;
  out->opts = q->opts;
  out->bad_input = 0;
  if ((st = fb_impact_reference(&out->ref, &d, diag)) != FB_OK) return st;
  run_engine(&out->runs[0], names[0], engine[0], &d, &q->opts);
  out->has_closed_form = fb_impact_closed_form(&out->closed_form, &d);
  for (int i = 1; i < out->n_runs; i++) run_engine(&out->runs[i], names[i], engine[i], &d, &q->opts);
  out->h_omega = d.h * M_PI / out->ref.contact_duration;
  return FB_OK;
}
