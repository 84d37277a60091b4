/* fourbar bench --grid scaling (scaling.h) */
#include "scaling.h"

#include "pilot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "run.h"
#include "tolerance.h"

static const double default_revolutions[] = {1, 2, 4, 8, 16};
static const double default_stiffness[] = {1, 10, 100};
static const int default_members[] = {1, 4, 4};
static const int default_jobs[] = {1, 1, 2};
static const double default_samples[] = {1e4, 1e5};

const fb_scaling_plan fb_scaling_default = {
    .revolutions = default_revolutions, .nrevolutions = 5,
    .stiffness = default_stiffness,     .nstiffness = 3,
    .members = default_members,         .jobs = default_jobs,
    .nensemble = 3,
    .samples = default_samples,         .nsamples = 2,
};

static fb_scaling_row *new_row(fb_scaling_row *rows, int *n, const char *vary, double value,
                               int jobs) {
  fb_scaling_row *row = &rows[(*n)++];
  memset(row, 0, sizeof *row);
  snprintf(row->vary, sizeof row->vary, "%s", vary);
  row->value = value;
  row->jobs = jobs;
  row->estimate_s = row->reference_steps_per_rev = row->check_steps_per_rev = NAN;
  return row;
}

/* runs case k as fb_run_case does, timed, into row */
static void run_row(fb_scaling_row *row, const fb_case *k) {
  static fb_run r;
  fb_diag d;
  const double w0 = fb_clock_s(), c0 = fb_clock_cpu_s();
  const fb_status st = fb_run_case(&r, k, NULL, NULL, &d);
  row->wall_s = fb_clock_s() - w0;
  row->cpu_s = fb_clock_cpu_s() - c0;
  row->ran = st == FB_OK;
  snprintf(row->status, sizeof row->status, "%.250s", st == FB_OK ? "ok" : d.msg);
  if (st != FB_OK) return;
  row->estimate_s = r.estimate_s;
  for (int i = 0; i < r.n; i++)
    if (strcmp(r.model[i].run.name, "reference") == 0) {
      row->reference_steps_per_rev = (double)r.model[i].run.steps / k->revolutions;
      if (r.model[i].ref_check_steps)
        row->check_steps_per_rev = (double)r.model[i].ref_check_steps / k->revolutions;
    }
  fb_run_free(&r);
}

static void monte_carlo_row(fb_scaling_row *row, const fb_case *c, size_t samples) {
  static fb_stackup_result out;
  fb_diag d;
  double bytes, each;
  /* the estimate stackup says: this case's cost per sample, measured */
  if (fb_tol_eval_cost(&each, NULL, (double)samples, c, &d) != FB_OK) each = NAN;
  fb_tol_estimate(each, samples, row->jobs, &bytes, &row->estimate_s);
  const double w0 = fb_clock_s(), c0 = fb_clock_cpu_s();
  const fb_status st = fb_tol_analyse_jobs(&out, c, FB_TOL_MONTECARLO, samples, 1,
                                           c->distribution ? FB_DIST_UNIFORM : FB_DIST_NORMAL,
                                           row->jobs, NULL, NULL, &d);
  row->wall_s = fb_clock_s() - w0;
  row->cpu_s = fb_clock_cpu_s() - c0;
  row->ran = st == FB_OK;
  snprintf(row->status, sizeof row->status, "%.250s", st == FB_OK ? "ok" : d.msg);
}

/* row i of plan p's runs (its revolutions, stiffness and ensemble rows, in
 * that order) as its case *k, what it varies and its value and jobs */
static void row_case(fb_case *k, const char **vary, double *value, int *jobs, const fb_case *c,
                     const fb_scaling_plan *p, int i) {
  *k = *c;
  *jobs = 1;
  if (i < p->nrevolutions) {
    k->revolutions = p->revolutions[i];
    k->model_count = 1;
    snprintf(k->models[0], sizeof k->models[0], "reference");
    k->ensemble = 1;
    k->peaks = FB_PEAKS_ALL;
    *vary = "revolutions";
    *value = p->revolutions[i];
    return;
  }
  i -= p->nrevolutions;
  if (i < p->nstiffness) {
    k->clearance.stiffness_scale = c->clearance.stiffness_scale * p->stiffness[i];
    k->ensemble = 1;
    *vary = "stiffness_scale";
    *value = p->stiffness[i];
    return;
  }
  i -= p->nstiffness;
  k->ensemble = p->members[i];
  k->jobs = p->jobs[i];
  *jobs = p->jobs[i];
  *vary = "ensemble";
  *value = p->members[i];
}

fb_status fb_scaling_run(fb_scaling_row *rows, int *n, const fb_case *c, const fb_scaling_plan *p,
                         fb_diag *diag) {
  *n = 0;
  if (p->nrevolutions + p->nstiffness + p->nensemble + p->nsamples > FB_SCALING_MAX_ROWS)
    return fb_diag_set(diag, FB_ERR_ARG, "a scaling plan of more than %d rows",
                       FB_SCALING_MAX_ROWS);
  fb_case *k = malloc(sizeof *k);
  if (!k) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int i = 0; i < p->nrevolutions + p->nstiffness + p->nensemble; i++) {
    const char *vary;
    double value;
    int jobs;
    row_case(k, &vary, &value, &jobs, c, p, i);
    run_row(new_row(rows, n, vary, value, jobs), k);
  }
  for (int i = 0; i < p->nsamples; i++)
    monte_carlo_row(new_row(rows, n, "montecarlo_samples", p->samples[i], 1), c,
                    (size_t)p->samples[i]);
  free(k);
  return FB_OK;
}

fb_status fb_scaling_estimate(double *cpu_s, double *pilot_s, const fb_case *c,
                              const fb_scaling_plan *p, fb_diag *diag) {
  *cpu_s = 0.0;
  if (pilot_s) *pilot_s = 0.0;
  fb_case *k = malloc(sizeof *k);
  if (!k) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  fb_status st = FB_OK;
  for (int i = 0; i < p->nrevolutions + p->nstiffness + p->nensemble && st == FB_OK; i++) {
    const char *vary;
    double value;
    int jobs;
    row_case(k, &vary, &value, &jobs, c, p, i);
    fb_pilot pl;
    st = fb_pilot_case(&pl, k, diag);
    if (st != FB_OK) break; /* (the row would fail alone; the bench says so) */
    *cpu_s += pl.cpu_s;
    if (pilot_s) *pilot_s += pl.pilot_cpu_s;
  }
  free(k);
  double each;
  if (st == FB_OK && p->nsamples > 0 && (st = fb_tol_eval_cost(&each, NULL, 0.0, c, diag)) == FB_OK)
    for (int i = 0; i < p->nsamples; i++) *cpu_s += p->samples[i] * each;
  return st;
}
