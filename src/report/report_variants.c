#include "report_variants.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "outcome_text.h"
#include "report_common.h"

#define say fb_report_say

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

/* a body's values in the order of FB_BODY_PEAK_KEYS, as a table of 4 */
static void values4(double v[4], const fb_case_body_values *b) {
  v[0] = b->omega_max, v[1] = b->omega_min, v[2] = b->alpha_max, v[3] = b->alpha_min;
}
static void peaks4(double v[4], const fb_body_peaks *b) {
  v[0] = b->omega_max, v[1] = b->omega_min, v[2] = b->alpha_max, v[3] = b->alpha_min;
}
static const char *const key4[4] = {"omega_max", "omega_min", "alpha_max", "alpha_min"};
static const char *const unit4[4] = {"rad_s", "rad_s", "rad_s2", "rad_s2"};
static const char *const law_key[FB_PUBLISHED_LAWS] = {"impact", "restitution"};

json_t *fb_report_published_json(const fb_case *c) {
  json_t *o = json_object();
  int any = 0;
  for (int l = 0; l < FB_PUBLISHED_LAWS; l++) {
    if (!fb_variants_published_any(&c->published[l])) continue;
    json_t *law = json_object();
    const fb_case_body_values *b[2] = {&c->published[l].coupler, &c->published[l].follower};
    for (int q = 0; q < 2; q++) {
      double v[4];
      values4(v, b[q]);
      json_t *body = json_object();
      for (int k = 0; k < 4; k++) {
        char key[64];
        snprintf(key, sizeof key, "%s_%s", key4[k], unit4[k]);
        if (isfinite(v[k])) json_object_set_new(body, key, json_real(v[k]));
      }
      json_object_set_new(law, q ? "follower" : "coupler", body);
    }
    json_object_set_new(o, law_key[l], law);
    any = 1;
  }
  if (!any) {
    json_decref(o);
    return json_null();
  }
  json_object_set_new(o, "source", c->published_source[0] ? json_string(c->published_source)
                                                          : json_null());
  return o;
}

json_t *fb_report_vs_published_json(const fb_case *c, const fb_model *m, const fb_peaks *p,
                                    int has_peaks) {
  const fb_case_published *pub = fb_variants_published(c, m);
  if (!has_peaks || !fb_variants_published_any(pub)) return json_null();
  json_t *o = json_object();
  const fb_case_body_values *b[2] = {&pub->coupler, &pub->follower};
  const fb_body_peaks *mp[2] = {&p->coupler, &p->follower};
  for (int q = 0; q < 2; q++) {
    double v[4], x[4];
    values4(v, b[q]);
    peaks4(x, mp[q]);
    json_t *body = json_object();
    for (int k = 0; k < 4; k++) {
      char key[64];
      snprintf(key, sizeof key, "%s_rel", key4[k]);
      if (isfinite(v[k])) json_object_set_new(body, key, num((x[k] - v[k]) / fabs(v[k])));
    }
    json_object_set_new(o, q ? "follower" : "coupler", body);
  }
  return o;
}

static json_t *peaks_json(const fb_peaks *p) {
  json_t *o = json_object();
  json_object_set_new(o, "coupler", fb_report_body_peaks_json(&p->coupler));
  json_object_set_new(o, "follower", fb_report_body_peaks_json(&p->follower));
  return o;
}

static const char *variant_model_status(char *buf, size_t size, const fb_variant_model *m) {
  if (m->stop.kind == FB_STOP_NONE) return snprintf(buf, size, "ok"), buf;
  return fb_stop_text(buf, size, &m->stop);
}

json_t *fb_report_variants_json(const fb_run *r) {
  json_t *a = json_array();
  for (int v = 0; v < r->variant_count; v++) {
    const fb_variant_result *vr = &r->variant[v];
    json_t *o = json_object();
    json_object_set_new(o, "name", json_string(vr->def.name));
    json_object_set_new(o, "set", json_string(vr->def.set));
    json_object_set_new(o, "models_key", vr->def.models[0] ? json_string(vr->def.models)
                                                           : json_null());
    json_object_set_new(o, "description", vr->def.description[0]
                                              ? json_string(vr->def.description)
                                              : json_null());
    json_object_set_new(o, "h_s", num(vr->h));
    json_t *models = json_array();
    for (int i = 0; i < vr->n; i++) {
      const fb_variant_model *m = &vr->model[i];
      json_t *mo = json_object();
      char status[256];
      json_object_set_new(mo, "name", json_string(m->model->name));
      json_object_set_new(mo, "status", json_string(variant_model_status(status, sizeof status, m)));
      json_object_set_new(mo, "peaks_converged", json_boolean(!m->peaks_unconverged));
      json_object_set_new(mo, "peaks", m->has_peaks ? peaks_json(&m->peaks) : json_null());
      json_object_set_new(mo, "vs_published",
                          fb_report_vs_published_json(&r->c, m->model, &m->peaks, m->has_peaks));
      json_array_append_new(models, mo);
    }
    json_object_set_new(o, "models", models);
    json_array_append_new(a, o);
  }
  return a;
}

/* a column's value as printed: fixed decimals (fmt) for the magnitudes a
 * peak has, else 4 significant digits (a published 1e308 is not 309 digits) */
static const char *cell_number(char *buf, size_t size, const char *fmt, double v) {
  snprintf(buf, size, fabs(v) < 1e9 ? fmt : "%.4g", v);
  return buf;
}

/* a model's difference from a published value, in percent; a published 0
 * has no relative difference (never "inf %") */
static const char *difference(char *buf, size_t size, double x, double pub) {
  if (pub == 0.0) return snprintf(buf, size, "n/a: published 0"), buf;
  const double pct = 100.0 * ((x - pub) / fabs(pub)); /* no overflow at 1e308 */
  snprintf(buf, size, fabs(pct) < 1e6 ? "%+.2f %%" : "%+.3g %%", pct);
  return buf;
}

/* one row of the published comparison: the model's value and its
 * difference in each column the publication gives */
static void published_row(FILE *f, int W, const char *label, const fb_peaks *p, int unconverged,
                          const double pub[8], const int col[8], int ncol) {
  double x[8];
  peaks4(x, &p->coupler);
  peaks4(x + 4, &p->follower);
  fprintf(f, "%-*s", W, label);
  for (int k = 0; k < ncol; k++) {
    const int q = col[k];
    char v[32], cell[100], d[32];
    fb_report_figure(v, sizeof v, q % 4 < 2 ? "%.2f" : "%.4g", x[q], unconverged);
    snprintf(cell, sizeof cell, "%s (%s)", v, difference(d, sizeof d, x[q], pub[q]));
    fprintf(f, " %24s", cell);
  }
  fputc('\n', f);
}

static void print_published(FILE *f, const fb_run *r, int W) {
  const fb_case *c = &r->c;
  static const char *const body[2] = {"coupler", "follower"};
  static const char *const head[4] = {"omega max", "omega min", "alpha max", "alpha min"};
  static const char *const unit[4] = {"rad/s", "rad/s", "rad/s^2", "rad/s^2"};
  for (int l = 0; l < FB_PUBLISHED_LAWS; l++) {
    const fb_case_published *pub = &c->published[l];
    if (!fb_variants_published_any(pub)) continue;
    double v[8];
    values4(v, &pub->coupler);
    values4(v + 4, &pub->follower);
    int col[8], ncol = 0;
    for (int q = 0; q < 8; q++)
      if (isfinite(v[q])) col[ncol++] = q;
    fputc('\n', f);
    say(f, "published values of the %s law%s%s%s against this run's models of that law and its "
           "variants' (difference from the published value, %%; peaks over the run's window):",
        law_key[l], c->published_source[0] ? " (" : "", c->published_source,
        c->published_source[0] ? ")" : "");
    fprintf(f, "%-*s", W, "");
    for (int k = 0; k < ncol; k++) {
      char h[48];
      snprintf(h, sizeof h, "%s %s", body[col[k] / 4], head[col[k] % 4]);
      fprintf(f, " %24s", h);
    }
    fprintf(f, "\n%-*s", W, "model");
    for (int k = 0; k < ncol; k++) fprintf(f, " %24s", unit[col[k] % 4]);
    fprintf(f, "\n%-*s", W, "published");
    for (int k = 0; k < ncol; k++) {
      char cell[32];
      fprintf(f, " %24s", cell_number(cell, sizeof cell, col[k] % 4 < 2 ? "%.2f" : "%.4g", v[col[k]]));
    }
    fputc('\n', f);
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      if (m->has_peaks && fb_variants_published(c, m->run.model) == pub)
        published_row(f, W, m->run.name, &m->peaks, m->peaks_unconverged, v, col, ncol);
    }
    for (int vi = 0; vi < r->variant_count; vi++)
      for (int i = 0; i < r->variant[vi].n; i++) {
        const fb_variant_model *m = &r->variant[vi].model[i];
        if (!m->has_peaks || fb_variants_published(c, m->model) != pub) continue;
        char label[2 * FB_NAME_SIZE + 2];
        snprintf(label, sizeof label, "%s: %s", r->variant[vi].def.name, m->model->name);
        published_row(f, W, label, &m->peaks, m->peaks_unconverged, v, col, ncol);
      }
  }
}

void fb_report_print_variants(FILE *f, const fb_run *r, int W) {
  /* the label column holds "variant: model" too */
  for (int v = 0; v < r->variant_count; v++)
    for (int i = 0; i < r->variant[v].n; i++) {
      const int w = (int)(strlen(r->variant[v].def.name) + 2 + strlen(r->variant[v].model[i].model->name));
      if (w > W) W = w;
    }
  if (r->variant_count > 0) {
    fputc('\n', f);
    say(f, "variants (the case with more overrides, run beside it; peaks over the same window):");
    for (int v = 0; v < r->variant_count; v++) {
      const fb_variant_result *vr = &r->variant[v];
      say(f, "  %s: %s%s%s (h = %g s)", vr->def.name, vr->def.set,
          vr->def.models[0] ? "; models " : "", vr->def.models, vr->h);
      if (vr->def.description[0]) say(f, "    %s", vr->def.description);
    }
    fprintf(f, "%-*s %9s %9s %10s %10s %9s %9s %10s %10s\n", W, "variant: model", "cpl w max",
            "min", "alpha max", "min", "fol w max", "min", "alpha max", "min");
    fprintf(f, "%-*s %9s %9s %10s %10s %9s %9s %10s %10s\n", W, "", "rad/s", "rad/s", "rad/s^2",
            "rad/s^2", "rad/s", "rad/s", "rad/s^2", "rad/s^2");
    for (int v = 0; v < r->variant_count; v++)
      for (int i = 0; i < r->variant[v].n; i++) {
        const fb_variant_model *m = &r->variant[v].model[i];
        char label[2 * FB_NAME_SIZE + 2], stop[256];
        snprintf(label, sizeof label, "%s: %s", r->variant[v].def.name, m->model->name);
        fprintf(f, "%-*s", W, label);
        if (!m->has_peaks) {
          fprintf(f, " (no peaks: %.60s)\n", fb_stop_text(stop, sizeof stop, &m->stop));
          continue;
        }
        const fb_body_peaks *p[2] = {&m->peaks.coupler, &m->peaks.follower};
        const int u = m->peaks_unconverged;
        for (int b = 0; b < 2; b++) {
          char c0[24], c1[24], c2[24], c3[24];
          fprintf(f, " %9s %9s %10s %10s", fb_report_figure(c0, sizeof c0, "%.4f", p[b]->omega_max, u),
                  fb_report_figure(c1, sizeof c1, "%.4f", p[b]->omega_min, u),
                  fb_report_figure(c2, sizeof c2, "%.4g", p[b]->alpha_max, u),
                  fb_report_figure(c3, sizeof c3, "%.4g", p[b]->alpha_min, u));
        }
        fputc('\n', f);
      }
  }
  print_published(f, r, W);
}
