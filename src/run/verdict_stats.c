#include "verdict_stats.h"

#include <math.h>
#include <string.h>

#include "impact.h"

const char *fb_stat_name(fb_stat_kind k) {
  static const char *const names[FB_STAT_COUNT] = {"impact rate", "force mean", "force p90",
                                                    "omega deviation"};
  return k >= 0 && k < FB_STAT_COUNT ? names[k] : "?";
}

const char *fb_stat_key(fb_stat_kind k) {
  static const char *const keys[FB_STAT_COUNT] = {"rate_per_rev", "force_mean_n", "force_p90_n",
                                                   "omega_dev_rad_s"};
  return k >= 0 && k < FB_STAT_COUNT ? keys[k] : "?";
}

double fb_stat_margin(fb_stat_kind k) {
  switch (k) {
    case FB_STAT_RATE: return FB_MARGIN_RATE;
    case FB_STAT_OMEGA_DEV: return FB_MARGIN_OMEGA;
    default: return FB_MARGIN_FORCE;
  }
}

double fb_member_stat(const fb_member *m, fb_stat_kind k) {
  switch (k) {
    case FB_STAT_RATE: return m->rate;
    case FB_STAT_FORCE_MEAN: return m->force_mean;
    case FB_STAT_FORCE_P90: return m->force_p90;
    case FB_STAT_OMEGA_DEV: return m->omega_dev;
    default: return NAN;
  }
}

void fb_stat_test_run(fb_stat_test *out, const fb_ensemble *e, const fb_ensemble *ref, int rigid,
                      double alpha) {
  memset(out, 0, sizeof *out);
  static const fb_stat_kind penalty[3] = {FB_STAT_RATE, FB_STAT_FORCE_MEAN, FB_STAT_FORCE_P90};
  static const fb_stat_kind rigid_kinds[2] = {FB_STAT_RATE, FB_STAT_OMEGA_DEV};
  out->n = rigid ? 2 : 3;
  out->alpha = alpha;
  out->members = e->members;
  out->members_reference = ref->members;
  double p[FB_TEST_MAX_STATS];
  int all_in = 1, undefined = 0;
  for (int q = 0; q < out->n; q++) {
    const fb_stat_kind k = rigid ? rigid_kinds[q] : penalty[q];
    out->kind[q] = k;
    double x[FB_ENSEMBLE_MAX], y[FB_ENSEMBLE_MAX];
    for (int i = 0; i < e->members; i++) x[i] = fb_member_stat(&e->member[i], k);
    for (int i = 0; i < ref->members; i++) y[i] = fb_member_stat(&ref->member[i], k);
    fb_equiv_ratio(&out->eq[q], x, e->members, y, ref->members, fb_stat_margin(k), alpha);
    p[q] = out->eq[q].p_different;
    all_in &= out->eq[q].decision == FB_EQUIV_EQUIVALENT;
    undefined |= out->eq[q].decision == FB_EQUIV_UNDEFINED;
  }
  /* error: one statistic shown outside its margin, Holm over the statistics */
  const int outside = fb_holm(p, out->n, alpha, out->different);
  out->decision = outside    ? FB_EQUIV_DIFFERENT
                  : all_in   ? FB_EQUIV_EQUIVALENT
                  : undefined ? FB_EQUIV_UNDEFINED
                              : FB_EQUIV_UNDECIDED;
}

void fb_first_check_of(fb_first_check *out, const fb_reference_error *e, const fb_divergence *d,
                       double period, double rebound, double rebound_reference, int rigid) {
  memset(out, 0, sizeof *out);
  out->bound = rigid ? FB_MATCHED_IMPACT_ERROR_BOUND : FB_FAITHFUL_PENETRATION_TOL;
  out->ok = 1;
  /* the first impacts that begin before the model parts are listed; the
   * first alone is held (verdict_stats.h) */
  for (int k = 0; k < e->first_impacts; k++)
    if (e->first_impact_t[k] < d->t) out->compared = k + 1;
  /* either run's first impact before the model parts needs a partner */
  if (d->impacts_model > 0 || d->impacts_reference > 0) {
    if (out->compared == 0 ||
        !(fabs(e->first_impact_t_error[0]) <= FB_IMPACT_MATCH_REV_FRACTION * period)) {
      out->unpaired = 1;
      out->ok = 0;
      return;
    }
  }
  if (out->compared == 0) return; /* no impact on either side: nothing to hold */
  out->worst_k = 1;
  if (rigid) /* Newton's e_N against the penalty law's rebound */
    out->worst = fabs(rebound / rebound_reference - 1.0) / out->bound;
  else
    out->worst = fmax(fabs(e->first_impact_force_rel[0]), fabs(e->first_impact_penetration_rel[0])) /
                 out->bound;
  out->ok = out->worst <= 1.0; /* NaN (a rebound not measured) is never ok */
}
