#include "clock.h"
#include "tolerance.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"

static const char *const out_names[FB_TOL_NOUT] = {
    "coupler_omega_max_rad_s",   "coupler_omega_min_rad_s",    "coupler_alpha_max_rad_s2",
    "coupler_alpha_min_rad_s2",  "follower_omega_max_rad_s",   "follower_omega_min_rad_s",
    "follower_alpha_max_rad_s2", "follower_alpha_min_rad_s2",  "transmission_angle_min_rad",
    "transmission_angle_max_rad"};

const char *fb_tol_output_name(int i) { return (i >= 0 && i < FB_TOL_NOUT) ? out_names[i] : "?"; }

int fb_tol_output_parse(const char *name) {
  size_t n = strlen(name);
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    if (strcmp(name, out_names[i]) == 0) return i;
    /* without the unit suffix: the name is a prefix followed by "_rad" */
    if (strncmp(name, out_names[i], n) == 0 && strncmp(out_names[i] + n, "_rad", 4) == 0) return i;
  }
  return -1;
}

static void peaks_to_outputs(const fb_peaks *p, double out[FB_TOL_NOUT]) {
  out[0] = p->coupler.omega_max;
  out[1] = p->coupler.omega_min;
  out[2] = p->coupler.alpha_max;
  out[3] = p->coupler.alpha_min;
  out[4] = p->follower.omega_max;
  out[5] = p->follower.omega_min;
  out[6] = p->follower.alpha_max;
  out[7] = p->follower.alpha_min;
}

fb_status fb_tol_outputs(double out[FB_TOL_NOUT], const fb_linkage *lk, fb_branch branch,
                         double omega2, fb_diag *diag) {
  fb_peaks p;
  fb_status st = fb_analytic_peaks(&p, lk, branch, omega2, diag);
  if (st != FB_OK) return st;
  peaks_to_outputs(&p, out);
  return fb_linkage_transmission_range(lk, &out[8], &out[9], diag);
}

fb_status fb_tol_sensitivities(double out[FB_TOL_NOUT][FB_LINK_COUNT], const fb_linkage *lk,
                               fb_branch branch, double omega2, fb_diag *diag) {
  fb_peaks p;
  double where[8];
  fb_status st = fb_analytic_peaks_where(&p, where, lk, branch, omega2, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < 8; i++) {
    double s[4][FB_LINK_COUNT];
    st = fb_linkage_sensitivity(s, lk, branch, where[i], omega2, diag);
    if (st != FB_OK) return st;
    /* output i: body i / 4 (coupler, follower), quantity (i % 4) / 2 (omega, alpha) */
    const int row = (i % 4 < 2 ? 0 : 2) + (i < 4 ? 0 : 1);
    for (int k = 0; k < FB_LINK_COUNT; k++) out[i][k] = s[row][k];
  }
  /* transmission angle at theta2 = 0 (f = g - a) and pi (f = g + a) */
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double c = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];
  for (int e = 0; e < 2; e++) {
    const double sgn = e == 0 ? -1.0 : 1.0; /* f = g + sgn a */
    const double f = g + sgn * a;
    const double u = (b * b + c * c - f * f) / (2.0 * b * c);
    const double k = -1.0 / sqrt(1.0 - u * u); /* d acos(u) / du */
    const double du_df = -f / (b * c);
    out[8 + e][FB_CRANK] = k * du_df * sgn;
    out[8 + e][FB_GROUND] = k * du_df;
    out[8 + e][FB_COUPLER] = k * (1.0 / c - u / b);
    out[8 + e][FB_FOLLOWER] = k * (1.0 / b - u / c);
  }
  return FB_OK;
}

static fb_status corner_outputs(double out[FB_TOL_NOUT], const fb_case *c, const int corner[4],
                                fb_diag *diag) {
  fb_linkage lk;
  for (int k = 0; k < FB_LINK_COUNT; k++)
    lk.length[k] = c->nominal.length[k] + corner[k] * c->plus_minus[k];
  fb_diag inner;
  fb_status st = fb_tol_outputs(out, &lk, c->branch, fb_case_omega2(c), &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, st, "corner %c%c%c%c (crank %g, coupler %g, follower %g, ground %g m): %s",
                       "-0+"[corner[0] + 1], "-0+"[corner[1] + 1], "-0+"[corner[2] + 1],
                       "-0+"[corner[3] + 1], lk.length[0], lk.length[1], lk.length[2],
                       lk.length[3], inner.msg);
  return FB_OK;
}

fb_status fb_tol_analyse(fb_stackup_result *out, const fb_case *c, int mask, size_t samples,
                         unsigned long seed, fb_distribution dist,
                         void (*progress)(double fraction, void *user), void *user,
                         fb_diag *diag) {
  memset(out, 0, sizeof *out);
  const double omega2 = fb_case_omega2(c);
  fb_status st = fb_tol_outputs(out->nominal, &c->nominal, c->branch, omega2, diag);
  if (st == FB_OK) st = fb_tol_sensitivities(out->sens, &c->nominal, c->branch, omega2, diag);
  if (st != FB_OK) return st;
  if (mask & FB_TOL_CORNERS) {
    double best_abs[FB_TOL_NOUT];
    for (int m = 0; m < 16; m++) {
      int corner[4];
      for (int k = 0; k < 4; k++) corner[k] = (m >> k) & 1 ? +1 : -1;
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
        double d = out->sens[i][k] * c->plus_minus[k];
        s2 += d * d;
      }
      out->rss_half[i] = sqrt(s2);
    }
  }
  if ((mask & FB_TOL_MONTECARLO) && samples > 0) {
    double t0 = fb_clock_s();
    double *v = malloc(samples * FB_TOL_NOUT * sizeof(double));
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!v || !rng) {
      free(v);
      if (rng) gsl_rng_free(rng);
      return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", samples);
    }
    gsl_rng_set(rng, seed);
    for (size_t n = 0; n < samples && st == FB_OK; n++) {
      fb_linkage lk;
      for (int k = 0; k < FB_LINK_COUNT; k++) {
        double x = dist == FB_DIST_UNIFORM ? gsl_ran_flat(rng, -1.0, 1.0)
                                           : gsl_ran_gaussian(rng, 1.0 / 3.0);
        lk.length[k] = c->nominal.length[k] + x * c->plus_minus[k];
      }
      double o[FB_TOL_NOUT];
      fb_diag inner;
      st = fb_tol_outputs(o, &lk, c->branch, omega2, &inner);
      if (st != FB_OK) {
        fb_diag_set(diag, st, "Monte Carlo sample %zu (crank %g, coupler %g, follower %g, ground %g m): %s",
                    n, lk.length[0], lk.length[1], lk.length[2], lk.length[3], inner.msg);
        break;
      }
      for (int i = 0; i < FB_TOL_NOUT; i++) v[i * samples + n] = o[i];
      if (progress && (n + 1) % 100 == 0) progress((double)(n + 1) / (double)samples, user);
    }
    if (st == FB_OK) {
      for (int i = 0; i < FB_TOL_NOUT; i++) {
        double *col = v + i * samples;
        out->mc_mean[i] = gsl_stats_mean(col, 1, samples);
        out->mc_std[i] = samples > 1 ? gsl_stats_sd(col, 1, samples) : 0.0;
        gsl_sort(col, 1, samples);
        out->q[i][0] = gsl_stats_quantile_from_sorted_data(col, 1, samples, 0.00135);
        out->q[i][1] = gsl_stats_quantile_from_sorted_data(col, 1, samples, 0.5);
        out->q[i][2] = gsl_stats_quantile_from_sorted_data(col, 1, samples, 0.99865);
      }
      out->samples = samples;
    }
    gsl_rng_free(rng);
    free(v);
    out->mc_wall_s = fb_clock_s() - t0;
    if (progress) progress(1.0, user);
  }
  return st;
}

fb_status fb_tol_resolve_worst(fb_case *c, fb_diag *diag) {
  if (!c->stackup.worst) return FB_OK;
  const int i = c->stackup.worst_output;
  double best = -1.0;
  for (int m = 0; m < 16; m++) {
    int corner[4];
    for (int k = 0; k < 4; k++) corner[k] = (m >> k) & 1 ? +1 : -1;
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
