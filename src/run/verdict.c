#include "verdict.h"

#include <math.h>
#include <stddef.h>

#include "model_table.h"
#include "run.h"

const char *fb_verdict_name(fb_verdict_word w) {
  switch (w) {
    case FB_VERDICT_OK: return "ok";
    case FB_VERDICT_WARN: return "warn";
    case FB_VERDICT_ERROR: return "error";
    case FB_VERDICT_UNCHECKED: return "unchecked";
  }
  return "warn";
}

const char *fb_verdict_basis_name(fb_verdict_basis b) {
  switch (b) {
    case FB_BASIS_POINTWISE: return "pointwise";
    case FB_BASIS_STATISTICS: return "statistics";
    case FB_BASIS_UNSETTLED: return "unsettled";
    case FB_BASIS_NONE: break;
  }
  return NULL;
}

/* warnings the basis does not answer: on statistics, the divergence and
 * the matched-impact error before it are what the statistics decide */
static int open_warnings(const fb_model_result *m, int statistics) {
  int n = 0;
  for (int k = 0; k < m->warning_count; k++) {
    const fb_warning_kind w = m->warnings[k].kind;
    if (statistics && m->run.clearance_mask &&
        (w == FB_WARN_DIVERGENT || w == FB_WARN_ERROR_BOUND))
      continue;
    n++;
  }
  return n;
}

/* a reference's peaks converged against its check integration */
static int ref_pointwise(const fb_model_result *ref) {
  return ref->has_ref_estimate && !ref->peaks_unconverged;
}

static void assess_reference(fb_model_result *m) {
  if (!m->has_ref_estimate) { /* stopped, or no tighter tolerance to check with */
    m->basis = FB_BASIS_NONE;
    m->verdict = m->run.stop.kind != FB_STOP_NONE || m->warning_count ? FB_VERDICT_WARN
                                                                       : FB_VERDICT_UNCHECKED;
    return;
  }
  if (!m->peaks_unconverged) {
    m->basis = FB_BASIS_POINTWISE;
    m->verdict = m->warning_count ? FB_VERDICT_WARN : FB_VERDICT_OK;
    return;
  }
  /* its peaks moved: never ok, whatever else converged */
  m->verdict = FB_VERDICT_WARN;
  m->basis = m->has_check_compare && m->check_compare.agree >= 0 ? FB_BASIS_STATISTICS
                                                                 : FB_BASIS_UNSETTLED;
}

static const fb_model_result *reference_of(const fb_run *r, const fb_model_result *m) {
  const fb_model *want = fb_model_reference_of(m->run.model);
  for (int k = 0; want && k < r->n; k++)
    if (r->model[k].run.model == want) return &r->model[k];
  return NULL;
}

/* 1: the reference's own members (ensemble.h, started FB_ENSEMBLE_ECC_FRACTION
 * of the clearance apart) never part from its run: a regular sequence;
 * 0: one does, a chaotic one; -1: fewer than two members */
static int reference_regular(const fb_model_result *ref) {
  if (!ref->has_ensemble || ref->ensemble.members < 2) return -1;
  for (int k = 1; k < ref->ensemble.members; k++)
    if (isfinite(ref->ensemble.member[k].t_part)) return 0;
  return 1;
}

/* the run's own sequential test may still run members (run_case.c) */
static int members_may_come(const fb_run *r) {
  return r->c.ensemble_auto && r->c.ensemble <= 1 && r->seq_looks == 0 && !r->seq_wall_cut;
}

static void assess_clearance(fb_model_result *m, const fb_run *r) {
  const fb_model_result *ref = reference_of(r, m);
  const int stopped = m->run.stop.kind != FB_STOP_NONE;
  if (!m->has_divergence || !ref) { /* nothing to compare with */
    m->basis = FB_BASIS_NONE;
    m->verdict = stopped || m->warning_count ? FB_VERDICT_WARN : FB_VERDICT_UNCHECKED;
    return;
  }
  /* the same history, wrong impacts: wrong, when the reference's sequence
   * is regular; when its own members part (a chaotic sequence whose later
   * impacts no run reproduces), its first impacts and statistics decide */
  const int regular = m->matched_error == FB_MATCHED_ERROR_KEPT ? reference_regular(ref) : 1;
  if (m->matched_error == FB_MATCHED_ERROR_KEPT && regular != 0) {
    const int wait = regular < 0 && members_may_come(r);
    m->basis = wait ? FB_BASIS_UNSETTLED : FB_BASIS_POINTWISE;
    m->verdict = wait ? FB_VERDICT_WARN : FB_VERDICT_ERROR;
    return;
  }
  if (regular && !m->divergence.diverged && ref_pointwise(ref)) {
    m->basis = FB_BASIS_POINTWISE;
    m->verdict = stopped || m->warning_count ? FB_VERDICT_WARN : FB_VERDICT_OK;
    return;
  }
  /* pointwise first: the impacts before it parts, one to one */
  m->has_first_check = m->has_ref_error;
  if (m->has_first_check)
    fb_first_check_of(&m->first_check, &m->ref_error, &m->divergence,
                      2.0 * M_PI / r->c.crank_speed, m->first_impact.rebound,
                      /* a rigid model's rebound: against the law's cr, the limit the
                       * reference's approaches as its penalty stiffens (verdict_stats.h) */
                      m->run.model->rigid ? r->c.clearance.restitution : ref->first_impact.rebound,
                      m->run.model->rigid);
  if (m->has_first_check && !m->first_check.ok) {
    m->basis = FB_BASIS_POINTWISE;
    m->verdict = FB_VERDICT_ERROR;
    return;
  }
  if (!m->has_test) {
    m->basis = FB_BASIS_UNSETTLED;
    m->verdict = FB_VERDICT_WARN;
    return;
  }
  /* then its members' statistics against the reference's members
   * (verdict_stats.h): the yardstick is the reference's distribution, which
   * its members sample; its check integration, one more run, is printed
   * beside it but cannot show that distribution unconverged at these sizes
   * (docs/verdicts.md, "The reference's own check") */
  m->basis = FB_BASIS_STATISTICS;
  if (m->test.decision == FB_EQUIV_EQUIVALENT && !stopped && !open_warnings(m, 1))
    m->verdict = FB_VERDICT_OK;
  else if (m->test.decision == FB_EQUIV_DIFFERENT)
    m->verdict = FB_VERDICT_ERROR;
  else
    m->verdict = FB_VERDICT_WARN;
}

int fb_verdict_assess(fb_run *r) {
  int unsettled = 0;
  for (int i = 0; i < r->n; i++) {
    fb_model_result *m = &r->model[i];
    if (m->run.model->engine == FB_ENGINE_REFERENCE) assess_reference(m);
  }
  for (int i = 0; i < r->n; i++) {
    fb_model_result *m = &r->model[i];
    if (m->run.model->engine == FB_ENGINE_REFERENCE) {
      /* assessed above */
    } else if (m->run.clearance_mask) {
      assess_clearance(m, r);
    } else { /* ideal and analytic models: against the analytic solution */
      const int beyond = m->has_error && fb_metrics_peak_rel_worst(&m->error.body[0],
                                                                   &m->error.body[1]) >
                                             FB_IDEAL_PEAK_ERROR_BOUND;
      m->basis = m->has_error ? FB_BASIS_POINTWISE : FB_BASIS_NONE;
      m->verdict = m->run.stop.kind != FB_STOP_NONE || m->warning_count || beyond
                       ? FB_VERDICT_WARN
                       : FB_VERDICT_OK;
    }
    unsettled += m->basis == FB_BASIS_UNSETTLED;
  }
  return unsettled;
}
