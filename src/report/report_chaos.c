#include "report_chaos.h"

#include "numfmt.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "outcome_text.h"
#include "reference.h"
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
                                  "clearance, member k >= 1 along 2 pi (k - 1) / (members - 1)"));
  json_object_set_new(o, "ecc_fraction", json_real(FB_ENSEMBLE_ECC_FRACTION));
  json_object_set_new(o, "perturbation_m", num(FB_ENSEMBLE_ECC_FRACTION * r->c.radial_clearance));
  json_object_set_new(o, "window_from_s", num(r->t_window));
  json_object_set_new(o, "impacts_min", json_integer(e->impacts_min));
  json_object_set_new(o, "impacts_max", json_integer(e->impacts_max));
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

static const char *agree_word(const fb_model_result *m) {
  if (!m->has_stats_compare) return "-";
  return m->stats_compare.agree < 0 ? "not measured (ensemble = 1)"
                                    : (m->stats_compare.agree ? "yes" : "no");
}

void fb_report_print_chaos(FILE *f, const fb_run *r) {
  step_line(f, r, "\n");
  if (!any_ensemble(r)) return;
  const int members = r->c.ensemble > 1 ? r->c.ensemble : 1;
  fputc('\n', f);
  fb_report_say(f, "impact statistics over the window t >= %.6g s, pooled over %d run%s (the pins' "
                   "start moved by %g x clearance per member), spread: standard deviation over the "
                   "members:",
                r->t_window, members, members > 1 ? "s" : "", FB_ENSEMBLE_ECC_FRACTION);
  fprintf(f, "model\n  %-18s %6s %10s %10s %10s %10s %9s %9s %13s\n", "per impact", "count",
          "mean", "p50", "p90", "max", "sd mean", "sd p90", "rel mean/p90");
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble) stats_rows(f, &r->model[i], NULL, &r->c);
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    if (!m->has_stats_compare) continue;
    fb_report_say(f, "%s against %s's distribution (within %g sd): %s%s", m->run.name, m->ref_name,
            FB_ENSEMBLE_AGREE_SIGMAS, agree_word(m),
            m->has_divergence && m->divergence.diverged ? " (divergent: compare these, not peaks)"
                                                        : "");
  }
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
    else if (m->has_divergence)
      fprintf(f, "- %s: %s; stays with %s's trajectory to the end (%d impacts matched, %s)\n",
              m->run.name, fb_report_model_status(st, sizeof st, m), m->ref_name,
              m->divergence.matched, m->divergence.one_to_one ? "one to one" : "not one to one");
    if (m->peaks_unconverged)
      fprintf(f, "- %s: window peaks not converged (~): force max ~%.3g N, coupler alpha "
                 "~%.3g / ~%.3g rad/s^2\n",
              m->run.name, m->has_spikes ? m->spikes.force_max : NAN, m->peaks.coupler.alpha_max,
              m->peaks.coupler.alpha_min);
  }
  if (!any_ensemble(r)) return;
  fprintf(f, "\nPer-impact statistics over t >= %.6g s, pooled over %d run(s), the pins' start "
             "moved by %g x the radial clearance per member; sd: standard deviation over the "
             "members; rel: against the reference's pooled value.\n\n",
          r->t_window, r->c.ensemble > 1 ? r->c.ensemble : 1, FB_ENSEMBLE_ECC_FRACTION);
  fprintf(f, "| model | per impact | count | mean | p50 | p90 | max | sd mean / p90 | rel mean/p90 |\n");
  fprintf(f, "|---|---|---|---|---|---|---|---|---|\n");
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble) stats_rows(f, &r->model[i], "|", &r->c);
  fputc('\n', f);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_stats_compare)
      fprintf(f, "- %s against %s's distribution (within %g sd): %s\n", r->model[i].run.name,
              r->model[i].ref_name, FB_ENSEMBLE_AGREE_SIGMAS, agree_word(&r->model[i]));
}

/* ---- verdicts: what each rests on (verdict.h) ------------------------------ */

/* A model whose statistics agree with the reference's while one of them is
 * this far off relative (half again, or half below) agrees only because its
 * members spread widely: the ensemble could not tell the two apart, which
 * is weaker than showing them alike (measured: Simbody on a 60 / 200 mm
 * crank-rocker, force max +154 % within 2.3 sd of its spread, docs/chaos.md);
 * the reason says so [-]. */
#define FB_STATS_WIDE_REL 0.5

/* the 12 statistics of fb_impact_stats in the order of ensemble.c */
static double stat_q(const fb_impact_stats *s, int q) {
  const fb_dist *d[3] = {&s->force, &s->alpha_coupler, &s->alpha_follower};
  const double v[4] = {d[q / 4]->mean, d[q / 4]->p50, d[q / 4]->p90, d[q / 4]->max};
  return v[q % 4];
}

/* "force mean", "coupler alpha p90", a slider's "slider a max" */
static const char *stat_label(int q, const fb_case *c) {
  static const char *const which[4] = {"mean", "p50", "p90", "max"};
  static _Thread_local char buf[12][48];
  const fb_mech_desc *mech = fb_case_mech(c);
  if (q < 4) snprintf(buf[q], sizeof buf[q], "force %s", which[q % 4]);
  else
    snprintf(buf[q], sizeof buf[q], "%s %s %s", fb_mech_output_name(mech, q / 4 - 1),
             fb_mech_output_symbol(mech, q / 4 - 1, FB_Q_ACC), which[q % 4]);
  return buf[q];
}

/* the statistic farthest from its yardstick: in standard deviations when
 * measured, else relative; returns its index (-1: none finite) */
static int worst_stat(const fb_stats_compare *c, int sigmas, double *value) {
  int at = -1;
  *value = 0.0;
  for (int q = 0; q < 12; q++) {
    const double v = fabs(stat_q(sigmas ? &c->sigmas : &c->rel, q));
    if (isfinite(v) && (at < 0 || v > *value)) at = q, *value = v;
  }
  return at;
}

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
    if (m->basis == FB_BASIS_STATISTICS && worst_stat(&m->stats_compare, 0, &w) >= 0) {
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
    return (size_t)snprintf(buf, size, "; no ensemble ran (%d runs estimated at %.3g s, beyond "
                            "[run] max_wall_s = %g s): set [run] ensemble = %d to %s",
                            FB_ENSEMBLE_AUTO_MEMBERS, r->ensemble_estimate_s, r->c.max_wall_s,
                            FB_ENSEMBLE_AUTO_MEMBERS, what);
  return (size_t)snprintf(buf, size, "; no ensemble ran: set [run] ensemble = %d to %s",
                          FB_ENSEMBLE_AUTO_MEMBERS, what);
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
    double w;
    const int q = worst_stat(&m->check_compare, 1, &w);
    if (m->check_compare.agree == 1)
      snprintf(buf + n, size - n, "; converged: its impact statistics (the check within %.2g sd "
               "of its %d runs' mean)", m->check_compare.agree_sigmas, m->ensemble.members);
    else
      snprintf(buf + n, size - n, "; its impact statistics did not converge either (the check's "
               "%s %+.0f %%, %.2g sd from its %d runs' mean, bound %.2g)",
               q >= 0 ? stat_label(q, &r->c) : "-",
               q >= 0 ? 100.0 * stat_q(&m->check_compare.rel, q) : NAN, w, m->ensemble.members,
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
  if (m->verdict == FB_VERDICT_ERROR) return fb_report_model_status(buf, size, m);
  if (m->run.clearance_mask && m->basis == FB_BASIS_NONE && !stopped) {
    const fb_model *want = fb_model_reference_of(m->run.model);
    const int cj = fb_case_mech(&r->c)->reference_joint;
    if (want && r->c.clearance.mask != (1 << cj))
      snprintf(buf, size, "no reference: %s covers a clearance at the %s joint alone",
               want->name, fb_case_joint_name(&r->c, cj));
    else if (want && r->c.clearance.friction > 0.0)
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
  const fb_model_result *ref = NULL;
  for (int k = 0; k < r->n; k++)
    if (strcmp(r->model[k].run.name, m->ref_name) == 0) ref = &r->model[k];
  double w;
  const int q = worst_stat(&m->stats_compare, 1, &w);
  if (m->stats_compare.agree != 1)
    n += (size_t)snprintf(buf + n, size - n, "; its impact statistics over %d runs disagree with "
                          "%s's (%s %+.0f %%, %.2g sd apart)", m->ensemble.members, m->ref_name,
                          q >= 0 ? stat_label(q, &r->c) : "-",
                          q >= 0 ? 100.0 * stat_q(&m->stats_compare.rel, q) : NAN, w);
  else
    n += (size_t)snprintf(buf + n, size - n, "; its impact statistics over %d runs agree with "
                          "%s's (within %g sd)", m->ensemble.members, m->ref_name,
                          FB_ENSEMBLE_AGREE_SIGMAS);
  /* agreement inside a wide spread: said, so that ok is not read as alike */
  double rel;
  const int qr = worst_stat(&m->stats_compare, 0, &rel);
  if (n < size && m->stats_compare.agree == 1 && qr >= 0 && rel > FB_STATS_WIDE_REL)
    n += (size_t)snprintf(buf + n, size - n, ", but only inside a wide spread (%s %+.0f %%): "
                          "more runs ([run] ensemble) sharpen it", stat_label(qr, &r->c),
                          100.0 * stat_q(&m->stats_compare.rel, qr));
  if (n >= size) return buf;
  if (ref && ref->basis != FB_BASIS_POINTWISE && !(ref->has_check_compare &&
                                                   ref->check_compare.agree == 1))
    n += (size_t)snprintf(buf + n, size - n, ", but %s's own statistics are not shown converged "
                          "(its row)", m->ref_name);
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
    fb_report_say(f, "ensemble: a model's verdict was unsettled, so the run added %d runs by "
                     "itself (the case leaves [run] ensemble unset; set it to choose, 1: none): "
                     "%.3g s of wall time for the %d runs beyond the first, against %.3g s for "
                     "those models once",
                  r->ensemble_auto, r->ensemble_wall_s, r->ensemble_auto - 1, r->models_wall_s);
  else if (r->ensemble_auto_skipped)
    fb_report_say(f, "ensemble: a model's verdict is unsettled, but %d runs, estimated at %.3g s, "
                     "would pass [run] max_wall_s = %g s: none ran",
                  FB_ENSEMBLE_AUTO_MEMBERS, r->ensemble_estimate_s, r->c.max_wall_s);
}

json_t *fb_report_ensemble_run_json(const fb_run *r) {
  const int members = r->c.ensemble > 1 ? r->c.ensemble : 1;
  const char *source = r->ensemble_auto > 1 ? "run" : members > 1 ? "case" : "none";
  json_t *o = json_object();
  json_object_set_new(o, "members", json_integer(members));
  json_object_set_new(o, "source", json_string(source));
  json_object_set_new(
      o, "reason",
      r->ensemble_auto > 1
          ? json_string("a model's verdict was unsettled (it left its reference, or a reference "
                        "parted from its check integration) and the case leaves [run] ensemble "
                        "unset")
      : r->ensemble_auto_skipped
          ? json_string("a model's verdict is unsettled, but the ensemble's estimated wall time "
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
