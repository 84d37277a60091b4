#include "tolerance.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "closed_form.h"
#include "work.h"
#include "montecarlo.h"

const char *fb_tol_output_name_of(fb_mech_type t, int i) {
  return (i >= 0 && i < FB_TOL_NOUT) ? fb_closed_form_of(t)->tol_names[i] : "?";
}

const char *fb_tol_output_unit_of(fb_mech_type t, int i) {
  static const char *const unit[][2] = {{"_rad_s2", "rad/s^2"}, {"_rad_s", "rad/s"},
                                        {"_rad", "rad"},        {"_m_s2", "m/s^2"},
                                        {"_m_s", "m/s"},        {"_m", "m"}};
  const char *name = fb_tol_output_name_of(t, i);
  const size_t n = strlen(name);
  for (size_t k = 0; k < sizeof unit / sizeof unit[0]; k++) {
    const size_t m = strlen(unit[k][0]);
    if (n > m && strcmp(name + n - m, unit[k][0]) == 0) return unit[k][1];
  }
  return "";
}

fb_status fb_tol_outputs_of(double out[FB_TOL_NOUT], fb_mech_type t, const fb_linkage *lk,
                            fb_branch branch, double omega2, fb_diag *diag) {
  return fb_closed_form_of(t)->tol_outputs(out, lk, branch, omega2, diag);
}

fb_status fb_tol_sensitivities_of(double out[FB_TOL_NOUT][FB_LINK_COUNT], fb_mech_type t,
                                  const fb_linkage *lk, fb_branch branch, double omega2,
                                  fb_diag *diag) {
  return fb_closed_form_of(t)->tol_sensitivities(out, lk, branch, omega2, diag);
}

/* "crank 0.1, coupler 0.28, follower 0.27, ground 0.25": the case's lengths
 * named by its mechanism's description, values len[] [m] */
static void lengths_text(char *buf, size_t size, const fb_case *c, const double *len) {
  const fb_mech_desc *mech = fb_case_mech(c);
  size_t n = 0;
  buf[0] = '\0';
  for (int k = 0; k < mech->nlengths && n < size; k++)
    n += (size_t)snprintf(buf + n, size - n, "%s%s %g", k ? ", " : "", mech->length[k], len[k]);
}

/* one sample of the mechanism's lengths len (its nlengths; a slot it has
 * not at its nominal) evaluated: fb_mc_eval for the case ctx */
static fb_status mc_eval(double *out, const double *len, void *ctx, fb_diag *diag) {
  const fb_case *c = ctx;
  const int nl = fb_case_mech(c)->nlengths;
  fb_linkage lk;
  for (int k = 0; k < FB_LINK_COUNT; k++) lk.length[k] = k < nl ? len[k] : c->nominal.length[k];
  return fb_tol_outputs_of(out, c->mechanism, &lk, c->branch, fb_case_omega2(c), diag);
}

/* the Monte Carlo of the mechanism's lengths, in their order (montecarlo.h) */
static fb_status monte_carlo(fb_stackup_result *out, const fb_case *c, size_t samples,
                             unsigned long seed, fb_distribution dist, int jobs,
                             void (*progress)(double fraction, void *user), void *user,
                             fb_diag *diag) {
  const fb_mc_problem p = {fb_case_mech(c)->nlengths, c->nominal.length, c->plus_minus,
                           FB_TOL_NOUT, mc_eval, (void *)c, 0, 0};
  fb_mc_output o[FB_TOL_NOUT];
  double failed[FB_LINK_COUNT];
  fb_mc_result r = {.out = o, .failed_len = failed};
  fb_diag inner;
  const fb_status st = fb_mc_run(&r, &p, samples, seed, dist, jobs, progress, user, &inner);
  out->mc_wall_s = r.wall_s;
  if (st != FB_OK) {
    char lengths[160];
    lengths_text(lengths, sizeof lengths, c, failed);
    return fb_diag_set(diag, st, "Monte Carlo sample %zu (%s m): %s", r.failed_at, lengths,
                       inner.msg);
  }
  out->ci_level = r.ci_level;
  memcpy(out->q_rank, r.q_rank, sizeof out->q_rank);
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    memcpy(out->q[i], o[i].q, sizeof out->q[i]);
    memcpy(out->q_ci[i], o[i].q_ci, sizeof out->q_ci[i]);
    out->mc_mean[i] = o[i].mean;
    out->mc_std[i] = o[i].std;
  }
  out->samples = r.samples;
  out->jobs = r.jobs;
  return FB_OK;
}

/* the corner m of 2^n over the mechanism's n lengths: length k at its
 * maximum where bit k of m is set, else at its minimum; 0 (nominal) for a
 * slot the mechanism has not */
static void corner_of(int corner[FB_LINK_COUNT], int m, int n) {
  for (int k = 0; k < FB_LINK_COUNT; k++) corner[k] = k >= n ? 0 : (m >> k) & 1 ? +1 : -1;
}

static fb_status corner_outputs(double out[FB_TOL_NOUT], const fb_case *c, const int corner[4],
                                fb_diag *diag) {
  fb_linkage lk;
  for (int k = 0; k < FB_LINK_COUNT; k++)
    lk.length[k] = c->nominal.length[k] + corner[k] * c->plus_minus[k];
  fb_diag inner;
  fb_status st = fb_tol_outputs_of(out, c->mechanism, &lk, c->branch, fb_case_omega2(c), &inner);
  if (st == FB_OK) return FB_OK;
  const int n = fb_case_mech(c)->nlengths;
  char mark[FB_LINK_COUNT + 1] = "";
  for (int k = 0; k < n; k++) mark[k] = "-0+"[corner[k] + 1];
  mark[n] = '\0';
  char lengths[160];
  lengths_text(lengths, sizeof lengths, c, lk.length);
  return fb_diag_set(diag, st, "corner %s (%s m): %s", mark, lengths, inner.msg);
}

fb_status fb_tol_analyse(fb_stackup_result *out, const fb_case *c, int mask, size_t samples,
                         unsigned long seed, fb_distribution dist,
                         void (*progress)(double fraction, void *user), void *user,
                         fb_diag *diag) {
  return fb_tol_analyse_jobs(out, c, mask, samples, seed, dist, 1, progress, user, diag);
}

fb_status fb_tol_analyse_jobs(fb_stackup_result *out, const fb_case *c, int mask, size_t samples,
                              unsigned long seed, fb_distribution dist, int jobs,
                              void (*progress)(double fraction, void *user), void *user,
                              fb_diag *diag) {
  if (jobs < 1 || jobs > FB_TOL_MAX_JOBS)
    return fb_diag_set(diag, FB_ERR_ARG, "jobs = %d: must be from 1 to %d", jobs, FB_TOL_MAX_JOBS);
  memset(out, 0, sizeof *out);
  const double omega2 = fb_case_omega2(c);
  fb_status st = fb_tol_outputs_of(out->nominal, c->mechanism, &c->nominal, c->branch, omega2, diag);
  if (st == FB_OK)
    st = fb_tol_sensitivities_of(out->sens, c->mechanism, &c->nominal, c->branch, omega2, diag);
  if (st != FB_OK) return st;
  if (mask & FB_TOL_CORNERS) {
    double best_abs[FB_TOL_NOUT];
    const int nl = fb_case_mech(c)->nlengths;
    for (int m = 0; m < 1 << nl; m++) {
      int corner[4];
      corner_of(corner, m, nl);
      double v[FB_TOL_NOUT];
      st = corner_outputs(v, c, corner, diag);
      if (st != FB_OK) return st;
      for (int i = 0; i < FB_TOL_NOUT; i++) {
        if (m == 0 || v[i] < out->corner_min[i]) out->corner_min[i] = v[i];
        if (m == 0 || v[i] > out->corner_max[i]) out->corner_max[i] = v[i];
        if (m == 0 || fabs(v[i]) > best_abs[i]) {
          best_abs[i] = fabs(v[i]);
          memcpy(out->corner_of_max[i], corner, sizeof corner);
        }
      }
    }
  }
  if (mask & FB_TOL_RSS) {
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      double s2 = 0.0;
      for (int k = 0; k < FB_LINK_COUNT; k++) {
        double d = out->sens[i][k] * c->plus_minus[k]; /* a slot the mechanism has not: 0 */
        s2 += d * d;
      }
      out->rss_half[i] = sqrt(s2);
    }
  }
  if ((mask & FB_TOL_MONTECARLO) && samples > 0) st = monte_carlo(out, c, samples, seed, dist, jobs, progress, user, diag);
  return st;
}

fb_status fb_tol_resolve_worst(fb_case *c, fb_diag *diag) {
  if (!c->stackup.worst) return FB_OK;
  const int i = c->stackup.worst_output;
  const int nl = fb_case_mech(c)->nlengths;
  double best = -1.0;
  for (int m = 0; m < 1 << nl; m++) {
    int corner[4];
    corner_of(corner, m, nl);
    double v[FB_TOL_NOUT];
    fb_status st = corner_outputs(v, c, corner, diag);
    if (st != FB_OK) return st;
    if (fabs(v[i]) > best) {
      best = fabs(v[i]);
      memcpy(c->stackup.corner, corner, sizeof corner);
    }
  }
  c->stackup.worst = 0;
  return FB_OK;
}

/* one evaluation of the outputs at the nominal lengths (fb_work_eval) */
static fb_status nominal_eval(void *ctx, fb_diag *diag) {
  const fb_case *c = ctx;
  double out[FB_TOL_NOUT];
  return fb_tol_outputs_of(out, c->mechanism, &c->nominal, c->branch, fb_case_omega2(c), diag);
}

fb_status fb_tol_eval_cost(double *s_per_eval, int *evals, double units, const fb_case *c,
                           fb_diag *diag) {
  return fb_work_probe(s_per_eval, evals, units, nominal_eval, (void *)c, diag);
}

void fb_tol_estimate(double s_per_sample, size_t samples, int jobs, double *bytes, double *seconds) {
  fb_mc_estimate(s_per_sample, FB_TOL_NOUT, FB_LINK_COUNT, samples, jobs, bytes, seconds);
}

fb_status fb_tol_check_cost(double s_per_sample, size_t samples, int jobs, fb_diag *diag) {
  double bytes, seconds;
  fb_tol_estimate(s_per_sample, samples, jobs, &bytes, &seconds);
  return fb_mc_check_cost(samples, bytes, seconds, diag);
}
