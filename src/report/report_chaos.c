#include "report_chaos.h"

#include "numfmt.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "impact.h"
#include "outcome_text.h"
#include "reference.h"
#include "report_verdict.h"
#include "resolution.h"

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

static json_t *dist_json(const fb_dist *d, int with_n) {
  json_t *o = json_object();
  if (with_n) json_object_set_new(o, "impacts", json_integer(d->n));
#define FB_DIST_JSON(field, key) json_object_set_new(o, key, num(d->field));
  FB_DIST_KEYS(FB_DIST_JSON)
#undef FB_DIST_JSON
  return o;
}

/* the distributions by their keys, per output body in the names of the
 * case's mechanism (fb_mech_output_key: the slider's acceleration) */
static json_t *stats_json(const fb_impact_stats *s, int with_n, const fb_case *c) {
  json_t *o = json_object();
  char key[64], kb[96];
#define FB_STATS_JSON(field, prefix, unit)                                        \
  snprintf(key, sizeof key, "%s_%s", prefix, unit);                               \
  json_object_set_new(o, fb_mech_output_key(kb, sizeof kb, fb_case_mech(c), key), \
                      dist_json(&s->field, with_n));
  FB_IMPACT_STATS_KEYS(FB_STATS_JSON)
#undef FB_STATS_JSON
  return o;
}

json_t *fb_report_ensemble_json(const fb_model_result *m, const fb_run *r) {
  if (!m->has_ensemble) return json_null();
  const fb_ensemble *e = &m->ensemble;
  json_t *o = json_object();
  json_object_set_new(o, "members", json_integer(e->members));
  json_object_set_new(o, "perturbation",
                      json_string("pin eccentricity at t = 0 moved by ecc_fraction x radial "
                                  "clearance, member k >= 1 along k golden angles (2.39996 rad) "
                                  "from +x"));
  json_object_set_new(o, "ecc_fraction", json_real(FB_ENSEMBLE_ECC_FRACTION));
  json_object_set_new(o, "perturbation_m", num(FB_ENSEMBLE_ECC_FRACTION * r->c.radial_clearance));
  json_object_set_new(o, "window_from_s", num(r->t_window));
  json_object_set_new(o, "impacts_min", json_integer(e->impacts_min));
  json_object_set_new(o, "impacts_max", json_integer(e->impacts_max));
  json_object_set_new(o, "per_member", fb_report_members_json(e));
  json_object_set_new(o, "pooled", stats_json(&e->pooled, 1, &r->c));
  json_object_set_new(o, "spread", e->members > 1 ? stats_json(&e->spread, 1, &r->c) : json_null());
  if (m->has_stats_compare) {
    const fb_stats_compare *c = &m->stats_compare;
    json_t *v = json_object();
    json_object_set_new(v, "reference", json_string(m->ref_name));
    json_object_set_new(v, "rel", stats_json(&c->rel, 0, &r->c));
    json_object_set_new(v, "sigmas", c->agree >= 0 ? stats_json(&c->sigmas, 0, &r->c) : json_null());
    json_object_set_new(v, "agree_sigmas", json_real(FB_ENSEMBLE_AGREE_SIGMAS));
    json_object_set_new(v, "agree", c->agree >= 0 ? json_boolean(c->agree) : json_null());
    json_object_set_new(o, "vs_reference", v);
  } else {
    json_object_set_new(o, "vs_reference", json_null());
  }
  return o;
}

json_t *fb_report_converged_json(const fb_model_result *m) {
  if (!m->peaks_unconverged) return json_true();
  if (m->has_divergence && m->divergence.diverged)
    return json_string("no: divergent from its reference (compare impact_statistics)");
  return json_string("no: the reference's check integration moves its window peaks by more "
                     "than 1e-3 (reference_error_estimate)");
}

json_t *fb_report_step_json(const fb_run *r) {
  json_t *o = json_object();
  json_object_set_new(o, "h_s", num(r->c.solver.h));
  json_object_set_new(o, "auto", json_boolean(r->h_auto));
  json_object_set_new(o, "auto_estimate_s", r->h_auto ? num(r->h_auto_estimate) : json_null());
  json_object_set_new(o, "rechosen", json_integer(r->h_rechosen));
  json_object_set_new(o, "h_omega_c_max", r->h_omega_c_max > 0.0 ? num(r->h_omega_c_max) : json_null());
  json_object_set_new(o, "h_omega_c_bound", json_real(FB_H_OMEGA_C_BOUND));
  json_object_set_new(o, "within_bound", r->h_omega_c_max > 0.0
                                             ? json_boolean(r->h_omega_c_max <= FB_H_OMEGA_C_BOUND)
                                             : json_null());
  const fb_step_check *k = &r->step_check;
  json_object_set_new(
      o, "single_impact",
      k->checked ? json_pack("{s:s,s:o,s:o,s:f,s:f,s:b,s:o}", "joint",
                             fb_case_joint_name(&r->c, k->joint), "restitution_rel",
                             num(k->restitution_rel), "penetration_rel", num(k->penetration_rel),
                             "restitution_tol", FB_FAITHFUL_RESTITUTION_TOL, "penetration_tol",
                             FB_FAITHFUL_PENETRATION_TOL, "faithful", k->faithful,
                             "largest_faithful_step_s", num(k->largest_step))
                 : json_null());
  return o;
}

static int any_ensemble(const fb_run *r) {
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble) return 1;
  return 0;
}

static void step_line(FILE *f, const fb_run *r, const char *pre) {
  if (!(r->h_omega_c_max > 0.0) && !r->h_auto) return;
  char line[512];
  size_t n = (size_t)snprintf(line, sizeof line, "step h = %.4g s%s", r->c.solver.h,
                              r->h_auto ? " (h_s = auto" : "");
  if (r->h_auto && r->h_rechosen && n < sizeof line)
    n += (size_t)snprintf(line + n, sizeof line - n, ", re-chosen %d time%s from its estimate %.4g s",
                          r->h_rechosen, r->h_rechosen > 1 ? "s" : "", r->h_auto_estimate);
  if (r->h_auto && n < sizeof line) n += (size_t)snprintf(line + n, sizeof line - n, ")");
  if (r->h_omega_c_max > 0.0 && n < sizeof line)
    snprintf(line + n, sizeof line - n, ": largest h omega_c over the contact steps %.3g, bound %g: %s",
             r->h_omega_c_max, FB_H_OMEGA_C_BOUND,
             r->h_omega_c_max <= FB_H_OMEGA_C_BOUND ? "within" : "beyond");
  fputs(pre, f);
  fb_report_say(f, "%s", line);
  char faithful[600];
  if (fb_report_step_check_text(faithful, sizeof faithful, r)) fb_report_say(f, "  %s", faithful);
}

const char *fb_report_step_check_text(char *buf, size_t size, const fb_run *r) {
  const fb_step_check *k = &r->step_check;
  buf[0] = '\0';
  if (!k->checked) return NULL;
  char largest[64] = "none found";
  if (isfinite(k->largest_step)) snprintf(largest, sizeof largest, "h = %.4g s", k->largest_step);
  snprintf(buf, size, "the restitution law's single impact at this step (fourbar contact-params "
           "--case: ODE's matched row, every effective mass and onset phase): restitution %+.2g %%, "
           "penetration %+.2g %% at the %s joint, against %g %% and %g %%: %s (largest faithful "
           "step %s)", 100.0 * k->restitution_rel, 100.0 * k->penetration_rel,
           fb_case_joint_name(&r->c, k->joint), 100.0 * FB_FAITHFUL_RESTITUTION_TOL,
           100.0 * FB_FAITHFUL_PENETRATION_TOL,
           k->faithful ? "faithful" : "not faithful: this run accepts that rebound error",
           largest);
  return buf;
}

/* one row: model, quantity, pooled mean / p50 / p90 / max (spread), vs ref */
static void stats_rows(FILE *f, const fb_model_result *m, const char *bar, const fb_case *c) {
  const fb_ensemble *e = &m->ensemble;
  const fb_dist *d[3] = {&e->pooled.force, &e->pooled.alpha_coupler, &e->pooled.alpha_follower};
  const fb_dist *s[3] = {&e->spread.force, &e->spread.alpha_coupler, &e->spread.alpha_follower};
  const fb_dist *rel[3] = {&m->stats_compare.rel.force, &m->stats_compare.rel.alpha_coupler,
                           &m->stats_compare.rel.alpha_follower};
  /* per output body: "cpl alpha rad/s^2", a slider's "sld a m/s^2" */
  const fb_mech_desc *mech = fb_case_mech(c);
  char body[2][32];
  for (int b = 0; b < 2; b++)
    snprintf(body[b], sizeof body[b], "%s %s %s", fb_report_body_abbrev(fb_mech_output_name(mech, b)),
             fb_mech_output_symbol(mech, b, FB_Q_ACC), fb_mech_output_unit(mech, b, FB_Q_ACC));
  const int four = mech == &fb_mech_fourbar; /* its words as they always were */
  const char *what[3] = {"force N", four ? "cpl alpha rad/s^2" : body[0],
                         four ? "fol alpha rad/s^2" : body[1]};
  for (int q = 0; q < 3; q++) {
    char agree[48] = "-";
    if (m->has_stats_compare)
      snprintf(agree, sizeof agree, "%s/%s", FB_NUM_CELL("%+.2f", rel[q]->mean, FB_NUM_NONE_TABLE),
               FB_NUM_CELL("%+.2f", rel[q]->p90, FB_NUM_NONE_TABLE));
    /* no impact in the window: no figure, "-" (numfmt.h), never nan */
#define CELL(fmt, x) FB_NUM_CELL(fmt, x, FB_NUM_NONE_TABLE)
    if (bar)
      fprintf(f, "| %s | %s | %d | %s | %s | %s | %s | %s / %s | %s |\n",
              q ? "" : m->run.name, what[q], d[q]->n, CELL("%.4g", d[q]->mean),
              CELL("%.4g", d[q]->p50), CELL("%.4g", d[q]->p90), CELL("%.4g", d[q]->max),
              CELL("%.3g", s[q]->mean), CELL("%.3g", s[q]->p90), agree);
    else {
      if (q == 0) fprintf(f, "%s\n", m->run.name); /* the model on a line of its own: <= 120 */
      fprintf(f, "  %-18s %6d %10s %10s %10s %10s %9s %9s %13s\n", what[q], d[q]->n,
              CELL("%.4g", d[q]->mean), CELL("%.4g", d[q]->p50), CELL("%.4g", d[q]->p90),
              CELL("%.4g", d[q]->max), CELL("%.3g", s[q]->mean), CELL("%.3g", s[q]->p90), agree);
    }
#undef CELL
  }
}

void fb_report_print_chaos(FILE *f, const fb_run *r) {
  step_line(f, r, "\n");
  if (!any_ensemble(r)) return;
  fputc('\n', f);
  fb_report_say(f, "impact statistics over the window t >= %.6g s, pooled over each model's members "
                   "(the pins' start moved by %g x clearance per member), spread: standard deviation "
                   "over the members; rel: against the reference's pooled value:",
                r->t_window, FB_ENSEMBLE_ECC_FRACTION);
  fprintf(f, "model\n  %-18s %6s %10s %10s %10s %10s %9s %9s %13s\n", "per impact", "count",
          "mean", "p50", "p90", "max", "sd mean", "sd p90", "rel mean/p90");
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble) stats_rows(f, &r->model[i], NULL, &r->c);
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    char parts[256];
    if (m->has_ensemble && m->ensemble.members > 1)
      fb_report_say(f, "%s: %s", m->run.name,
                    fb_report_parting_text(parts, sizeof parts, &m->ensemble, r->t_window));
  }
  fb_report_print_tests(f, r, 0);
  int marked = 0;
  for (int i = 0; i < r->n; i++) marked |= r->model[i].peaks_unconverged;
  if (marked)
    fb_report_say(f, "(~: a peak of a divergent model, or of a reference whose tighter integration "
                     "moves it by > %g, printed to 3 significant figures: not a converged number)",
                  FB_UNCONVERGED_REL);
}

void fb_report_markdown_chaos(FILE *f, const fb_run *r) {
  if (!any_ensemble(r) && !r->h_auto) return;
  fprintf(f, "\n## Step, divergence and impact statistics\n\n");
  step_line(f, r, "");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    char st[512];
    if (m->has_divergence && m->divergence.diverged)
      fprintf(f, "- %s: %s; divergent: leaves %s's trajectory at t = %.6g s (crank angle %.1f "
                 "deg, %d impacts matched before it)\n",
              m->run.name, fb_report_model_status(st, sizeof st, m), m->ref_name,
              m->divergence.t, m->divergence.crank_angle * 180.0 / M_PI, m->divergence.matched);
    /* a model that stays with its reference: its verdict's row says so */
    if (m->peaks_unconverged)
      fprintf(f, "- %s: window peaks not converged (~): force max ~%.3g N, coupler alpha "
                 "~%.3g / ~%.3g rad/s^2\n",
              m->run.name, m->has_spikes ? m->spikes.force_max : NAN, m->peaks.coupler.alpha_max,
              m->peaks.coupler.alpha_min);
  }
  if (!any_ensemble(r)) return;
  fprintf(f, "\nPer-impact statistics over t >= %.6g s, pooled over each model's members, the "
             "pins' start moved by %g x the radial clearance per member; sd: standard deviation "
             "over the members; rel: against the reference's pooled value.\n\n",
          r->t_window, FB_ENSEMBLE_ECC_FRACTION);
  fprintf(f, "| model | per impact | count | mean | p50 | p90 | max | sd mean / p90 | rel mean/p90 |\n");
  fprintf(f, "|---|---|---|---|---|---|---|---|---|\n");
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble) stats_rows(f, &r->model[i], "|", &r->c);
  fputc('\n', f);
  for (int i = 0; i < r->n; i++) {
    char parts[256];
    if (r->model[i].has_ensemble && r->model[i].ensemble.members > 1)
      fprintf(f, "- %s: %s\n", r->model[i].run.name,
              fb_report_parting_text(parts, sizeof parts, &r->model[i].ensemble, r->t_window));
  }
  fb_report_print_tests(f, r, 1);
}

/* ---- verdicts: what each rests on (verdict.h) ------------------------------ */

static double peak_alpha_rel(const fb_reference_error *e) {
  const double v[4] = {e->coupler.alpha_max_rel, e->coupler.alpha_min_rel,
                       e->follower.alpha_max_rel, e->follower.alpha_min_rel};
  double w = 0.0;
  for (int q = 0; q < 4; q++) w = isfinite(v[q]) ? fmax(w, fabs(v[q])) : INFINITY;
  return w;
}

/* omega, alpha and force peaks against the reference (or the check) */
static double peak_worst(const fb_reference_error *e) {
  const double w = fb_metrics_peak_rel_worst(&e->coupler, &e->follower);
  return isfinite(e->force_max_rel) ? fmax(w, fabs(e->force_max_rel)) : w;
}

int fb_report_verdict_error(char *err, size_t err_size, char *against, size_t against_size,
                            const fb_model_result *m) {
  if (m->run.clearance_mask && m->has_ref_error && m->run.model->engine != FB_ENGINE_REFERENCE) {
    double w;
    if (m->basis == FB_BASIS_STATISTICS && m->has_test) {
      /* the tested statistic farthest from its reference's: |ratio - 1| */
      w = 0.0;
      for (int q = 0; q < m->test.n; q++)
        if (isfinite(m->test.eq[q].ratio)) w = fmax(w, fabs(m->test.eq[q].ratio - 1.0));
      snprintf(err, err_size, "%.2e", w);
      snprintf(against, against_size, "%s", m->ref_name);
    } else {
      snprintf(err, err_size, "%.2e", peak_worst(&m->ref_error));
      snprintf(against, against_size, "%s", m->ref_name);
    }
    return 1;
  }
  if (m->has_ref_estimate) {
    snprintf(err, err_size, "%.2e", peak_worst(&m->ref_estimate));
    snprintf(against, against_size, "check integration");
    return 1;
  }
  return 0;
}

/* what an unsettled basis waits for */
static size_t settle_hint(char *buf, size_t size, const fb_run *r, const char *what) {
  if (r->c.ensemble > 1)
    return (size_t)snprintf(buf, size, "; its %d-run ensemble has no impact statistics to %s "
                            "(no impacts in the window)", r->c.ensemble, what);
  if (r->ensemble_auto_skipped)
    return (size_t)snprintf(buf, size, "; no members ran (the first look of %d, estimated at "
                            "%.3g s, passes [run] max_wall_s = %g s): raise max_wall_s, or set "
                            "[run] ensemble, to %s", FB_SEQ_FIRST, r->ensemble_estimate_s,
                            r->c.max_wall_s, what);
  return (size_t)snprintf(buf, size, "; no ensemble ran: leave [run] ensemble unset (fourbar run "
                          "tests its members, %d to %d) or set it to %s", FB_SEQ_FIRST, FB_SEQ_CAP,
                          what);
}

static const char *reference_why(char *buf, size_t size, const fb_model_result *m,
                                 const fb_run *r) {
  if (!m->has_ref_estimate) {
    if (m->run.stop.kind != FB_STOP_NONE) return fb_stop_text(buf, size, &m->run.stop);
    snprintf(buf, size, "no check integration (its tolerance is at the floor %g, or the check "
             "stopped): nothing to measure its peaks against", FB_REFERENCE_TOL_MIN);
    return buf;
  }
  const fb_reference_error *e = &m->ref_estimate;
  const double force = fabs(e->force_max_rel), alpha = peak_alpha_rel(e);
  if (m->basis == FB_BASIS_POINTWISE) {
    if (m->warning_count)
      snprintf(buf, size, "%d warning%s (below)", m->warning_count, m->warning_count > 1 ? "s" : "");
    else
      snprintf(buf, size, "force and alpha peaks within %g of its check integration (%.1e)",
               FB_UNCONVERGED_REL, fmax(force, alpha));
    return buf;
  }
  size_t n = 0;
  if (force <= FB_UNCONVERGED_REL)
    n = (size_t)snprintf(buf, size, "alpha peaks not converged against its check integration "
                         "(%.2g; force peak converged, %.1e)", alpha, force);
  else if (alpha <= FB_UNCONVERGED_REL)
    n = (size_t)snprintf(buf, size, "force peak not converged against its check integration "
                         "(%.2g; alpha peaks converged, %.1e)", force, alpha);
  else
    n = (size_t)snprintf(buf, size, "peaks not converged against its check integration (force "
                         "%.2g, alpha %.2g)", force, alpha);
  const fb_divergence *d = &m->check_divergence;
  if (n < size && m->has_check_divergence) {
    if (d->diverged)
      n += (size_t)snprintf(buf + n, size - n, "; it leaves its check at %.4g ms, %d impacts "
                            "matched before (error %.2g)", d->t * 1e3, d->matched,
                            fmax(d->force_rel_max, d->penetration_rel_max));
    else
      n += (size_t)snprintf(buf + n, size - n, "; its trajectory stays with its check");
  }
  if (n >= size) return buf;
  if (m->basis == FB_BASIS_STATISTICS) {
    if (m->check_compare.agree == 1)
      snprintf(buf + n, size - n, "; its check integration's impact rate and forces lie within its "
               "%d members' prediction interval (%.2g sd)", m->ensemble.members,
               m->check_compare.agree_sigmas);
    else
      snprintf(buf + n, size - n, "; its check integration's impact rate or forces lie outside its "
               "%d members' prediction interval (%.2g sd): one run against a heavy-tailed spread, "
               "shown, not judged (docs/verdicts.md)", m->ensemble.members,
               m->check_compare.agree_sigmas);
  } else {
    settle_hint(buf + n, size - n, r, "test its impact statistics");
  }
  return buf;
}

const char *fb_report_verdict_why(char *buf, size_t size, const fb_model_result *m,
                                  const fb_run *r) {
  buf[0] = '\0';
  if (m->run.model->engine == FB_ENGINE_REFERENCE) return reference_why(buf, size, m, r);
  const int stopped = m->run.stop.kind != FB_STOP_NONE;
  char stop[256];
  const int first_missed = m->has_first_check && !m->first_check.ok;
  if (m->verdict == FB_VERDICT_ERROR && !first_missed && m->basis != FB_BASIS_STATISTICS)
    return fb_report_model_status(buf, size, m);
  if (m->run.clearance_mask && m->basis == FB_BASIS_NONE && !stopped) {
    const fb_model *want = fb_model_reference_of(m->run.model);
    if (want && r->c.clearance.friction > 0.0)
      snprintf(buf, size, "no reference: %s is frictionless ([clearance] friction = %g)",
               want->name, r->c.clearance.friction);
    else if (want)
      snprintf(buf, size, "no reference in this run: add %s to [run] models to check it",
               want->name);
    else
      snprintf(buf, size, "no reference model exists for it: compare it with another engine's "
               "model of the same law");
    if (m->warning_count && strlen(buf) < size)
      snprintf(buf + strlen(buf), size - strlen(buf), "; %d warning%s (below)", m->warning_count,
               m->warning_count > 1 ? "s" : "");
    return buf;
  }
  if (first_missed) {
    snprintf(buf, size, "leaves %s at %.4g ms", m->ref_name, m->divergence.t * 1e3);
    fb_report_test_reason(buf, size, m);
    return buf;
  }
  if (!m->run.clearance_mask || m->basis == FB_BASIS_NONE || m->basis == FB_BASIS_POINTWISE) {
    if (stopped)
      snprintf(buf, size, "%.150s", fb_stop_text(stop, sizeof stop, &m->run.stop));
    else if (m->warning_count)
      snprintf(buf, size, "%d warning%s (below)", m->warning_count, m->warning_count > 1 ? "s" : "");
    else if (m->verdict == FB_VERDICT_WARN)
      snprintf(buf, size, "error above %g", FB_IDEAL_PEAK_ERROR_BOUND);
    else if (m->has_divergence)
      snprintf(buf, size, "stays with %s: %d impacts matched, error %.2g <= %g", m->ref_name,
               m->divergence.matched,
               fmax(m->divergence.force_rel_max, m->divergence.penetration_rel_max),
               FB_MATCHED_IMPACT_ERROR_BOUND);
    return buf;
  }
  /* statistics or unsettled: why the peaks cannot decide */
  size_t n;
  if (m->divergence.diverged)
    n = (size_t)snprintf(buf, size, "leaves %s at %.4g ms", m->ref_name, m->divergence.t * 1e3);
  else
    n = (size_t)snprintf(buf, size, "stays with %s, whose own peaks did not converge",
                         m->ref_name);
  if (n >= size) return buf;
  if (m->basis == FB_BASIS_UNSETTLED) {
    settle_hint(buf + n, size - n, r, "compare its impact statistics");
    return buf;
  }
  fb_report_test_reason(buf, size, m);
  n = strlen(buf);
  if (n >= size) return buf;
  if (n < size && stopped)
    snprintf(buf + n, size - n, "; %.150s", fb_stop_text(stop, sizeof stop, &m->run.stop));
  else if (n < size) {
    int open = 0;
    for (int k = 0; k < m->warning_count; k++)
      open += m->warnings[k].kind != FB_WARN_DIVERGENT && m->warnings[k].kind != FB_WARN_ERROR_BOUND;
    if (open)
      snprintf(buf + n, size - n, "; %d other warning%s (below)", open, open > 1 ? "s" : "");
  }
  return buf;
}

const char *fb_report_verdict(char *why, size_t why_size, const fb_model_result *m,
                              const fb_run *r) {
  fb_report_verdict_why(why, why_size, m, r);
  return fb_verdict_name(m->verdict);
}

void fb_report_print_ensemble_auto(FILE *f, const fb_run *r) {
  if (r->ensemble_auto > 1)
    fb_report_say(f, "ensemble: a model's verdict was unsettled, so the run tested members by "
                     "itself (the case leaves [run] ensemble unset; set it to choose, 1: none): "
                     "%d look%s, %d members at most (cap %d)%s: %.3g s of wall time for the members "
                     "beyond the first, against %.3g s for those models once",
                  r->seq_looks, r->seq_looks == 1 ? "" : "s", r->ensemble_auto, FB_SEQ_CAP,
                  r->seq_wall_cut ? ", stopped before a look whose estimate passed [run] max_wall_s"
                                  : "",
                  r->ensemble_wall_s, r->models_wall_s);
  else if (r->ensemble_auto_skipped)
    fb_report_say(f, "ensemble: a model's verdict is unsettled, but the first look of %d members, "
                     "estimated at %.3g s, would pass [run] max_wall_s = %g s: none ran",
                  FB_SEQ_FIRST, r->ensemble_estimate_s, r->c.max_wall_s);
}

json_t *fb_report_ensemble_run_json(const fb_run *r) {
  const int members = r->ensemble_auto > 1 ? r->ensemble_auto : r->c.ensemble > 1 ? r->c.ensemble : 1;
  const char *source = r->ensemble_auto > 1 ? "run" : members > 1 ? "case" : "none";
  json_t *o = json_object();
  json_object_set_new(o, "members", json_integer(members));
  json_object_set_new(o, "source", json_string(source));
  json_object_set_new(o, "looks", json_integer(r->ensemble_auto > 1 ? r->seq_looks : 1));
  json_object_set_new(o, "cap", r->ensemble_auto > 1 ? json_integer(FB_SEQ_CAP) : json_null());
  json_object_set_new(o, "wall_cut", json_boolean(r->seq_wall_cut));
  json_object_set_new(
      o, "reason",
      r->ensemble_auto > 1
          ? json_string("a model's verdict was unsettled (it left its reference, or a reference "
                        "parted from its check integration) and the case leaves [run] ensemble "
                        "unset: the run's sequential test added members until each model was "
                        "decided, or the cap")
      : r->ensemble_auto_skipped
          ? json_string("a model's verdict is unsettled, but the first look's estimated wall time "
                        "passes [run] max_wall_s: none ran")
          : json_null());
  return o;
}

void fb_report_check_json(json_t *o, const fb_model_result *m, const fb_run *r) {
  if (m->has_check_divergence) {
    const fb_divergence *d = &m->check_divergence;
    json_t *dv = json_object();
    json_object_set_new(dv, "diverged", json_boolean(d->diverged));
    json_object_set_new(dv, "time_s", num(d->t)); /* null: stays with it to the end */
    json_object_set_new(dv, "crank_angle_rad", num(d->crank_angle));
    json_object_set_new(dv, "impacts", json_integer(d->impacts_model));
    json_object_set_new(dv, "impacts_check", json_integer(d->impacts_reference));
    json_object_set_new(dv, "impacts_matched", json_integer(d->matched));
    json_object_set_new(dv, "force_rel_max", num(d->force_rel_max));
    json_object_set_new(dv, "penetration_rel_max", num(d->penetration_rel_max));
    json_object_set_new(o, "divergence", dv);
  } else {
    json_object_set_new(o, "divergence", json_null());
  }
  json_object_set_new(o, "impact_statistics",
                      m->has_check_stats ? stats_json(&m->check_stats, 1, &r->c) : json_null());
  if (m->has_check_compare) {
    const fb_stats_compare *c = &m->check_compare;
    json_t *v = json_object();
    json_object_set_new(v, "members", json_integer(m->ensemble.members));
    json_object_set_new(v, "rel", stats_json(&c->rel, 0, &r->c));
    json_object_set_new(v, "sigmas", c->agree >= 0 ? stats_json(&c->sigmas, 0, &r->c) : json_null());
    json_object_set_new(v, "agree_sigmas", num(c->agree_sigmas));
    json_object_set_new(v, "agree", c->agree >= 0 ? json_boolean(c->agree) : json_null());
    json_object_set_new(o, "vs_ensemble", v);
  } else {
    json_object_set_new(o, "vs_ensemble", json_null());
  }
}
