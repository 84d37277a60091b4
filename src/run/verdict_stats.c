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
  out->bound = FB_MATCHED_IMPACT_ERROR_BOUND;
  out->ok = 1;
  const double window = FB_IMPACT_MATCH_REV_FRACTION * period;
  /* the impacts that begin before the model parts, the largest of them for
   * the grazing share (metrics.h, FB_MATCHED_GRAZING_SHARE) */
  double big = 0.0;
  for (int k = 0; k < e->first_impacts; k++)
    if (e->first_impact_t[k] < d->t) {
      out->compared = k + 1;
      big = fmax(big, e->first_impact_force_reference[k]);
    }
  /* impacts either run has before the model parts: each needs a partner */
  const int before = d->impacts_model > d->impacts_reference ? d->impacts_model
                                                             : d->impacts_reference;
  const int want = before < FB_FIRST_IMPACTS ? before : FB_FIRST_IMPACTS;
  if (out->compared < want) {
    out->unpaired = out->compared + 1;
    out->ok = 0;
    return;
  }
  for (int k = 0; k < out->compared; k++) {
    if (!(fabs(e->first_impact_t_error[k]) <= window)) {
      out->unpaired = k + 1;
      out->ok = 0;
      return;
    }
    if (rigid || e->first_impact_force_reference[k] < FB_MATCHED_GRAZING_SHARE * big) continue;
    /* the first impact, a single impact of the law before any chaos, to the
     * faithful-step verification's penetration bound; the next to the
     * matched impacts' bound (in units of the bound: worst <= 1 passes) */
    const double pen = fabs(e->first_impact_penetration_rel[k]) /
                       (k == 0 ? FB_FAITHFUL_PENETRATION_TOL : FB_MATCHED_IMPACT_ERROR_BOUND);
    const double force = fabs(e->first_impact_force_rel[k]) / FB_MATCHED_IMPACT_ERROR_BOUND;
    const double w = fmax(pen, force);
    if (!(w <= out->worst)) out->worst = w, out->worst_k = k + 1;
  }
  if (rigid && out->compared > 0) {
    /* the first impact's rebound: Newton's e_N against the penalty law's,
     * to the matched impacts' bound */
    out->worst = fabs(rebound / rebound_reference - 1.0) / FB_MATCHED_IMPACT_ERROR_BOUND;
    out->worst_k = 1;
  }
  out->ok = out->worst <= 1.0; /* NaN (a rebound not measured) is never ok */
}
