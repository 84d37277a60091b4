#include "report_verdict.h"

#include "impact.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

json_t *fb_report_members_json(const fb_ensemble *e) {
  json_t *a = json_array();
  for (int i = 0; i < e->members; i++) {
    const fb_member *m = &e->member[i];
    json_t *o = json_object();
    json_object_set_new(o, "member", json_integer(m->k));
    json_object_set_new(o, "impacts", json_integer(m->impacts));
    json_object_set_new(o, "revolutions", num(m->revolutions));
    for (int k = 0; k < FB_STAT_COUNT; k++)
      json_object_set_new(o, fb_stat_key((fb_stat_kind)k), num(fb_member_stat(m, (fb_stat_kind)k)));
    json_object_set_new(o, "parts_s", num(m->t_part));
    json_array_append_new(a, o);
  }
  return a;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y ? 1 : 0;
}

const char *fb_report_parting_text(char *buf, size_t size, const fb_ensemble *e, double t_window) {
  double t[FB_ENSEMBLE_MAX];
  int n = 0;
  for (int k = 1; k < e->members; k++)
    if (isfinite(e->member[k].t_part)) t[n++] = e->member[k].t_part;
  if (e->members < 2) {
    snprintf(buf, size, "1 member (the run itself)");
  } else if (n == 0) {
    snprintf(buf, size, "%d members: none parts from the run itself (a regular sequence: their "
             "statistics are one value)", e->members);
  } else {
    qsort(t, (size_t)n, sizeof t[0], cmp_double);
    snprintf(buf, size, "%d members: %d part from the run itself between %.3g and %.3g ms "
             "(median %.3g ms), the window from %.3g ms", e->members, n, t[0] * 1e3,
             t[n - 1] * 1e3, 0.5 * (t[(n - 1) / 2] + t[n / 2]) * 1e3, t_window * 1e3);
  }
  return buf;
}

const char *fb_report_equiv_word(fb_equiv_decision d) {
  switch (d) {
    case FB_EQUIV_EQUIVALENT: return "equivalent";
    case FB_EQUIV_DIFFERENT: return "different";
    case FB_EQUIV_UNDEFINED: return "undefined";
    case FB_EQUIV_UNDECIDED: break;
  }
  return "undecided";
}

static json_t *first_json(const fb_model_result *m) {
  if (!m->has_first_check) return json_null();
  const fb_first_check *c = &m->first_check;
  json_t *o = json_object();
  json_object_set_new(o, "compared", json_integer(c->compared));
  json_object_set_new(o, "unpaired", c->unpaired ? json_integer(c->unpaired) : json_null());
  json_object_set_new(o, "worst_of_bound", num(c->worst));
  json_object_set_new(o, "worst_impact", c->worst_k ? json_integer(c->worst_k) : json_null());
  json_object_set_new(o, "what", json_string(m->run.model->rigid
                                                 ? "the first impact's onset and rebound ratio"
                                                 : "the first impact's onset, peak force and "
                                                   "penetration"));
  json_object_set_new(o, "bound", json_real(c->bound));
  json_object_set_new(o, "ok", json_boolean(c->ok));
  return o;
}

json_t *fb_report_test_json(const fb_model_result *m) {
  if (!m->has_test && !m->has_first_check) return json_null();
  json_t *o = json_object();
  json_object_set_new(o, "first_impacts", first_json(m));
  if (!m->has_test) {
    json_object_set_new(o, "statistics", json_null());
    return o;
  }
  const fb_stat_test *t = &m->test;
  json_t *a = json_array();
  for (int q = 0; q < t->n; q++) {
    const fb_equiv *e = &t->eq[q];
    json_t *s = json_object();
    json_object_set_new(s, "name", json_string(fb_stat_name(t->kind[q])));
    json_object_set_new(s, "key", json_string(fb_stat_key(t->kind[q])));
    json_object_set_new(s, "margin", json_real(e->margin));
    json_object_set_new(s, "members", json_integer(e->nx));
    json_object_set_new(s, "members_reference", json_integer(e->ny));
    json_object_set_new(s, "skipped", json_integer(e->skipped_x));
    json_object_set_new(s, "skipped_reference", json_integer(e->skipped_y));
    json_object_set_new(s, "mean", num(e->mean_x));
    json_object_set_new(s, "mean_reference", num(e->mean_y));
    json_object_set_new(s, "sd", num(e->sd_x));
    json_object_set_new(s, "sd_reference", num(e->sd_y));
    json_object_set_new(s, "ratio", num(e->ratio));
    json_object_set_new(s, "interval", json_pack("[o,o]", num(e->lo), num(e->hi)));
    json_object_set_new(s, "df", num(e->df));
    json_object_set_new(s, "p_equivalent", num(e->p_equivalent));
    json_object_set_new(s, "p_different", num(e->p_different));
    json_object_set_new(s, "decision", json_string(fb_report_equiv_word(e->decision)));
    json_object_set_new(s, "outside", json_boolean(t->different[q]));
    json_array_append_new(a, s);
  }
  json_object_set_new(o, "statistics", a);
  json_object_set_new(o, "decision", json_string(fb_report_equiv_word(t->decision)));
  json_object_set_new(o, "alpha", json_real(t->alpha));
  json_object_set_new(o, "look", json_integer(t->look));
  json_object_set_new(o, "looks", json_integer(t->looks));
  json_object_set_new(o, "members", json_integer(t->members));
  json_object_set_new(o, "members_reference", json_integer(t->members_reference));
  json_object_set_new(o, "at_cap", json_boolean(t->at_cap));
  json_object_set_new(o, "wall_cut", json_boolean(t->wall_cut));
  return o;
}

/* "force mean 1.02 [0.91, 1.14]" */
static size_t stat_text(char *buf, size_t size, const fb_equiv *e, fb_stat_kind k) {
  if (!isfinite(e->ratio))
    return (size_t)snprintf(buf, size, "%s %s", fb_stat_name(k),
                            e->decision == FB_EQUIV_EQUIVALENT ? "none on either side"
                            : e->nx < 2 || e->ny < 2
                                ? "not finite in enough members"
                                : "none in the reference's members");
  return (size_t)snprintf(buf, size, "%s %.3g [%.3g, %.3g]", fb_stat_name(k), e->ratio, e->lo,
                          e->hi);
}

static size_t append(char *buf, size_t size, size_t n, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static size_t append(char *buf, size_t size, size_t n, const char *fmt, ...) {
  if (n >= size) return n;
  va_list ap;
  va_start(ap, fmt);
  n += (size_t)vsnprintf(buf + n, size - n, fmt, ap);
  va_end(ap);
  return n;
}

static size_t first_reason(char *buf, size_t size, size_t n, const fb_model_result *m) {
  const fb_first_check *c = &m->first_check;
  if (!m->has_first_check || !c->worst_k) return n;
  if (c->unpaired)
    return append(buf, size, n, "; its first impact before it parts from %s has no partner within "
                  "%g of a revolution: wrong whatever its statistics say", m->ref_name,
                  FB_IMPACT_MATCH_REV_FRACTION);
  if (m->run.model->rigid)
    return append(buf, size, n, "; its first impact's rebound ratio %.4g against the law's cr "
                  "(the limit of %s's as its penalty stiffens): at %.0f %% of its bound %g%s",
                  m->first_impact.rebound, m->ref_name, 100.0 * c->worst, c->bound,
                  c->ok ? "" : ": beyond it, wrong whatever its statistics say");
  return append(buf, size, n, "; its first impact, before it parts, against %s's: force and "
                "penetration at %.0f %% of the single impact's bound %g%s", m->ref_name,
                100.0 * c->worst, c->bound,
                c->ok ? "" : ": beyond it, wrong whatever its statistics say");
}

void fb_report_test_reason(char *buf, size_t size, const fb_model_result *m) {
  size_t n = strlen(buf);
  n = first_reason(buf, size, n, m);
  if (!m->has_test || (m->has_first_check && !m->first_check.ok)) return;
  const fb_stat_test *t = &m->test;
  const char *word = t->decision == FB_EQUIV_EQUIVALENT ? "equivalent"
                     : t->decision == FB_EQUIV_DIFFERENT ? "different"
                                                         : "undecided";
  n = append(buf, size, n, "; %s on its members' statistics over %d members (%s %d, look %d of %d, "
             "level %.3g)%s:", word, t->members, m->ref_name, t->members_reference, t->look,
             t->looks, t->alpha,
             t->wall_cut ? " (stopped: the next look would pass [run] max_wall_s)"
             : t->at_cap && t->looks > 1 ? " (at the cap)"
                                          : "");
  for (int q = 0; q < t->n; q++) {
    /* the different ones when it is different, else every one */
    if (t->decision == FB_EQUIV_DIFFERENT && !t->different[q]) continue;
    char s[160];
    stat_text(s, sizeof s, &t->eq[q], t->kind[q]);
    n = append(buf, size, n, " %s%s", s, q + 1 < t->n ? "," : "");
  }
  if (t->decision == FB_EQUIV_DIFFERENT)
    n = append(buf, size, n, " outside the margin (Holm over %d statistics)", t->n);
  else
    n = append(buf, size, n, " against the margins [1/theta, theta], theta %g (rate %g)",
               t->n > 2 ? FB_MARGIN_FORCE : FB_MARGIN_OMEGA, FB_MARGIN_RATE);
}

void fb_report_print_tests(FILE *f, const fb_run *r, int markdown) {
  int any = 0;
  for (int i = 0; i < r->n; i++) any |= r->model[i].has_test;
  if (!any) return;
  if (markdown) {
    fprintf(f, "\n| model | statistic | members | mean | sd | reference members | mean | sd | "
               "ratio | interval | margin | p equivalent | p different | decision |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  } else {
    fputc('\n', f);
    fb_report_say(f, "verdict tests (docs/verdicts.md): each statistic per member, the model's "
                     "members' mean over its reference's, with Fieller's interval at the look's "
                     "level; equivalent when both one-sided tests put the ratio inside "
                     "[1/theta, theta]:");
    fprintf(f, "%-26s %-15s %3s %10s %9s %3s %10s %9s %7s %17s %6s %8s %8s %s\n", "model",
            "statistic", "n", "mean", "sd", "n", "ref mean", "sd", "ratio", "interval", "theta",
            "p equiv", "p diff", "decision");
  }
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    if (!m->has_test) continue;
    const fb_stat_test *t = &m->test;
    for (int q = 0; q < t->n; q++) {
      const fb_equiv *e = &t->eq[q];
      char iv[48];
      snprintf(iv, sizeof iv, "[%.3g, %.3g]", e->lo, e->hi);
      if (markdown)
        fprintf(f, "| %s | %s | %d | %.4g | %.3g | %d | %.4g | %.3g | %.3g | %s | %g | %.3g | %.3g "
                   "| %s |\n", q ? "" : m->run.name, fb_stat_name(t->kind[q]), e->nx, e->mean_x,
                e->sd_x, e->ny, e->mean_y, e->sd_y, e->ratio, iv, e->margin, e->p_equivalent,
                e->p_different, fb_report_equiv_word(e->decision));
      else
        fprintf(f, "%-26s %-15s %3d %10.4g %9.3g %3d %10.4g %9.3g %7.3g %17s %6g %8.2g %8.2g %s\n",
                q ? "" : m->run.name, fb_stat_name(t->kind[q]), e->nx, e->mean_x, e->sd_x, e->ny,
                e->mean_y, e->sd_y, e->ratio, iv, e->margin, e->p_equivalent, e->p_different,
                fb_report_equiv_word(e->decision));
    }
  }
}

void fb_report_test_title(char *buf, size_t size, const fb_model_result *m) {
  const fb_stat_test *t = &m->test;
  size_t n = (size_t)snprintf(buf, size, "%s: %s on statistics, %d members (%s %d), look %d of %d "
                              "at level %.3g:", m->run.name, fb_verdict_name(m->verdict), t->members,
                              m->ref_name, t->members_reference, t->look, t->looks, t->alpha);
  double p = 0.0;
  for (int q = 0; q < t->n && n < size; q++) {
    const fb_equiv *e = &t->eq[q];
    n += (size_t)snprintf(buf + n, size - n, " %s %.3g [%.3g, %.3g] in [%.3g, %.3g]%s",
                          fb_stat_name(t->kind[q]), e->ratio, e->lo, e->hi, 1.0 / e->margin,
                          e->margin, q + 1 < t->n ? "," : "");
    p = fmax(p, e->p_equivalent);
  }
  if (n < size)
    snprintf(buf + n, size - n, "; p (equivalent) %.2g: %s", p, fb_report_equiv_word(t->decision));
}

static json_t *forces_json(const fb_model_result *m) {
  json_t *a = json_array();
  for (int k = 0; k < m->ensemble.members; k++) {
    json_t *f = json_array();
    const fb_impact_values *v = &m->member_impacts[k];
    for (size_t i = 0; i < v->n; i++) json_array_append_new(f, num(v->force[i]));
    json_array_append_new(a, f);
  }
  return a;
}

static json_t *rates_json(const fb_ensemble *e) {
  json_t *a = json_array();
  for (int k = 0; k < e->members; k++) json_array_append_new(a, num(e->member[k].rate));
  return a;
}

json_t *fb_report_verdicts_json(const fb_run *r, const char *(*color)(const fb_run *, const char *)) {
  json_t *list = json_array();
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i], *ref = NULL;
    if (m->basis != FB_BASIS_STATISTICS || !m->has_test) continue;
    for (int k = 0; k < r->n; k++)
      if (strcmp(r->model[k].run.name, m->ref_name) == 0) ref = &r->model[k];
    if (!ref || !ref->has_ensemble) continue;
    char title[1400];
    fb_report_test_title(title, sizeof title, m);
    json_t *o = json_object();
    json_object_set_new(o, "model", json_string(m->run.name));
    json_object_set_new(o, "reference", json_string(ref->run.name));
    json_object_set_new(o, "color", json_string(color(r, m->run.name)));
    json_object_set_new(o, "verdict", json_string(fb_verdict_name(m->verdict)));
    json_object_set_new(o, "title", json_string(title));
    json_object_set_new(o, "model_forces", forces_json(m));
    json_object_set_new(o, "reference_forces", forces_json(ref));
    json_object_set_new(o, "model_rates", rates_json(&m->ensemble));
    json_object_set_new(o, "reference_rates", rates_json(&ref->ensemble));
    for (int q = 0; q < m->test.n; q++) {
      const fb_equiv *e = &m->test.eq[q];
      if (m->test.kind[q] != FB_STAT_RATE) continue;
      json_object_set_new(o, "rate", json_pack("{s:o,s:o,s:o,s:f,s:o,s:o}", "ratio", num(e->ratio),
                                              "lo", num(e->lo), "hi", num(e->hi), "margin",
                                              e->margin, "mean", num(e->mean_x), "mean_reference",
                                              num(e->mean_y)));
    }
    const fb_first_check *c = &m->first_check;
    const int rigid = m->run.model->rigid;
    json_t *first = json_array(), *bounds = json_array();
    for (int k = 0; k < c->compared; k++) {
      json_array_append_new(
          first, json_pack("{s:o,s:o}", "force_rel",
                           rigid ? json_null() : num(m->ref_error.first_impact_force_rel[k]),
                           "penetration_rel",
                           rigid ? json_null() : num(m->ref_error.first_impact_penetration_rel[k])));
      json_array_append_new(bounds, k == 0 ? json_real(c->bound) : json_null()); /* not held */
    }
    json_object_set_new(o, "first", first);
    json_object_set_new(o, "first_bounds", bounds);
    json_object_set_new(o, "rigid", json_boolean(rigid));
    json_object_set_new(o, "rebound_rel", rigid ? num(m->first_impact.rebound /
                                                      r->c.clearance.restitution - 1.0)
                                                : json_null());
    json_object_set_new(o, "first_ok", json_boolean(c->ok));
    json_object_set_new(o, "first_worst", num(c->worst));
    json_array_append_new(list, o);
  }
  return list;
}
