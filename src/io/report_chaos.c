#include "report_chaos.h"

#include <math.h>
#include <string.h>

#include "outcome_text.h"
#include "resolution.h"

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

const char *fb_report_model_status(char *buf, size_t size, const fb_model_result *m) {
  if (m->run.stop.kind != FB_STOP_NONE || !m->matched_error) return fb_stop_text(buf, size, &m->run.stop);
  const fb_divergence *d = &m->divergence;
  if (m->matched_error == FB_MATCHED_ERROR_THEN_DIVERGENT) {
    snprintf(buf, size,
             "divergent: matched-impact peak error %.3g beyond the bound %g against %s before "
             "its trajectory leaves %s's at t = %.6g s (%d impacts matched); compare the impact "
             "statistics, not peaks",
             fmax(d->force_rel_max, d->penetration_rel_max), FB_MATCHED_IMPACT_ERROR_BOUND,
             m->ref_name, m->ref_name, d->t, d->matched);
    return buf;
  }
  snprintf(buf, size,
           "error: matched-impact peak error %.3g beyond the bound %g against %s, whose "
           "trajectory it keeps (%d impacts matched)",
           fmax(d->force_rel_max, d->penetration_rel_max), FB_MATCHED_IMPACT_ERROR_BOUND,
           m->ref_name, d->matched);
  return buf;
}

const char *fb_report_figure(char *buf, size_t size, const char *fmt, double x, int unconverged) {
  if (unconverged) snprintf(buf, size, "~%.3g", x);
  else snprintf(buf, size, fmt, x);
  return buf;
}

static json_t *dist_json(const fb_dist *d, int with_n) {
  json_t *o = json_object();
  if (with_n) json_object_set_new(o, "impacts", json_integer(d->n));
#define FB_DIST_JSON(field, key) json_object_set_new(o, key, num(d->field));
  FB_DIST_KEYS(FB_DIST_JSON)
#undef FB_DIST_JSON
  return o;
}

static json_t *stats_json(const fb_impact_stats *s, int with_n) {
  json_t *o = json_object();
  char key[64];
#define FB_STATS_JSON(field, prefix, unit)              \
  snprintf(key, sizeof key, "%s_%s", prefix, unit);     \
  json_object_set_new(o, key, dist_json(&s->field, with_n));
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
  json_object_set_new(o, "pooled", stats_json(&e->pooled, 1));
  json_object_set_new(o, "spread", e->members > 1 ? stats_json(&e->spread, 1) : json_null());
  if (m->has_stats_compare) {
    const fb_stats_compare *c = &m->stats_compare;
    json_t *v = json_object();
    json_object_set_new(v, "reference", json_string(m->ref_name));
    json_object_set_new(v, "rel", stats_json(&c->rel, 0));
    json_object_set_new(v, "sigmas", c->agree >= 0 ? stats_json(&c->sigmas, 0) : json_null());
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
static void stats_rows(FILE *f, const fb_model_result *m, const char *bar) {
  const fb_ensemble *e = &m->ensemble;
  const fb_dist *d[3] = {&e->pooled.force, &e->pooled.alpha_coupler, &e->pooled.alpha_follower};
  const fb_dist *s[3] = {&e->spread.force, &e->spread.alpha_coupler, &e->spread.alpha_follower};
  const fb_dist *rel[3] = {&m->stats_compare.rel.force, &m->stats_compare.rel.alpha_coupler,
                           &m->stats_compare.rel.alpha_follower};
  const char *what[3] = {"force N", "cpl alpha rad/s^2", "fol alpha rad/s^2"};
  for (int q = 0; q < 3; q++) {
    char agree[48] = "-";
    if (m->has_stats_compare)
      snprintf(agree, sizeof agree, "%+.2f/%+.2f", rel[q]->mean, rel[q]->p90);
    if (bar)
      fprintf(f, "| %s | %s | %d | %.4g | %.4g | %.4g | %.4g | %.3g / %.3g | %s |\n",
              q ? "" : m->run.name, what[q], d[q]->n, d[q]->mean, d[q]->p50, d[q]->p90,
              d[q]->max, s[q]->mean, s[q]->p90, agree);
    else {
      if (q == 0) fprintf(f, "%s\n", m->run.name); /* the model on a line of its own: <= 120 */
      fprintf(f, "  %-18s %6d %10.4g %10.4g %10.4g %10.4g %9.3g %9.3g %13s\n", what[q], d[q]->n,
              d[q]->mean, d[q]->p50, d[q]->p90, d[q]->max, s[q]->mean, s[q]->p90, agree);
    }
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
    if (r->model[i].has_ensemble) stats_rows(f, &r->model[i], NULL);
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
    if (r->model[i].has_ensemble) stats_rows(f, &r->model[i], "|");
  fputc('\n', f);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_stats_compare)
      fprintf(f, "- %s against %s's distribution (within %g sd): %s\n", r->model[i].run.name,
              r->model[i].ref_name, FB_ENSEMBLE_AGREE_SIGMAS, agree_word(&r->model[i]));
}
