/* A planar run's output points and slides in its writers
 * (report_planar_outputs.h). */
#include "report_planar_outputs.h"

#include <math.h>
#include <stdio.h>

#include "names.h"
#include "numfmt.h"
#include "planar_loads.h"
#include "planar_outputs.h"
#include "report_common.h"
#include "report_internal.h"

const char *fb_report_planar_output_column(char *buf, size_t size, const fb_planar *m, int c) {
  static const char *const point_suffix[FB_PLANAR_POINT_QUANTITIES] = {
      "x_m", "y_m", "v_x_m_s", "v_y_m_s", "a_x_m_s2", "a_y_m_s2"};
  static const char *const slide_suffix[FB_PLANAR_SLIDE_QUANTITIES] = {
      "slide_m", "slide_v_m_s", "slide_a_m_s2"};
  static const char *const spring_suffix[FB_PLANAR_SPRING_QUANTITIES] = {
      "length_m", "length_v_m_s", "tension_n"};
  char word[FB_REPORT_JOINT_KEY_SIZE];
  const int np = FB_PLANAR_POINT_QUANTITIES * m->npoints;
  const int ns = fb_planar_output_count(m); /* then the springs' (planar_run.h out) */
  if (c >= ns && c < ns + FB_PLANAR_SPRING_QUANTITIES * m->nsprings) {
    fb_name_word(word, sizeof word, m->spring[(c - ns) / FB_PLANAR_SPRING_QUANTITIES].name);
    snprintf(buf, size, "%s_%s", word, spring_suffix[(c - ns) % FB_PLANAR_SPRING_QUANTITIES]);
    return buf;
  }
  if (c < np) {
    fb_name_word(word, sizeof word, m->point[c / FB_PLANAR_POINT_QUANTITIES].name);
    snprintf(buf, size, "%s_%s", word, point_suffix[c % FB_PLANAR_POINT_QUANTITIES]);
    return buf;
  }
  int s = (c - np) / FB_PLANAR_SLIDE_QUANTITIES;
  for (int j = 0; j < m->njoints; j++) {
    if (m->joint[j].kind != FB_KIND_PRISMATIC) continue;
    if (s-- > 0) continue;
    fb_name_word(word, sizeof word, m->joint[j].name);
    snprintf(buf, size, "%s_%s", word, slide_suffix[(c - np) % FB_PLANAR_SLIDE_QUANTITIES]);
    return buf;
  }
  snprintf(buf, size, "output_%d", c);
  return buf;
}

static json_t *num_or_null(double x) { return isfinite(x) ? json_real(x) : json_null(); }

/* the extremes of output columns c (position), c + dv (its rate) and
 * c + da (its acceleration) over the window's samples, as a slider's */
static fb_body_peaks extremes(const fb_planar_run *r, const fb_planar_model *p, int c, int dv,
                              int da) {
  fb_body_peaks k = {.pos_max = NAN, .pos_min = NAN, .omega_max = NAN, .omega_min = NAN,
                     .alpha_max = NAN, .alpha_min = NAN};
  const double *x = p->out + (size_t)c * p->n, *v = x + (size_t)dv * p->n, *a = x + (size_t)da * p->n;
  for (size_t i = 0; i < p->n; i++) {
    if (p->t[i] < r->t_window) continue;
    k.pos_max = fmax(k.pos_max, x[i]), k.pos_min = fmin(k.pos_min, x[i]); /* NaN-free */
    k.omega_max = fmax(k.omega_max, v[i]), k.omega_min = fmin(k.omega_min, v[i]);
    k.alpha_max = fmax(k.alpha_max, a[i]), k.alpha_min = fmin(k.alpha_min, a[i]);
  }
  return k;
}

/* point k's largest speed (m = 0) or acceleration's magnitude (m = 1) over
 * the window's samples */
static double magnitude_max(const fb_planar_run *r, const fb_planar_model *p, int k, int m) {
  const int c = FB_PLANAR_POINT_QUANTITIES * k + 2 + 2 * m;
  const double *x = p->out + (size_t)c * p->n, *y = x + p->n;
  double most = NAN;
  for (size_t i = 0; i < p->n; i++)
    if (p->t[i] >= r->t_window) most = fmax(most, hypot(x[i], y[i]));
  return most;
}

void fb_report_planar_outputs_json(json_t *e, const fb_planar_run *r, const fb_planar_model *p) {
  const fb_planar *m = r->m;
  if (!p->out) return;
  json_t *points = json_object(), *slides = json_object();
  char word[FB_REPORT_JOINT_KEY_SIZE];
  for (int k = 0; k < m->npoints; k++) {
    const int c = FB_PLANAR_POINT_QUANTITIES * k;
    const fb_body_peaks x = extremes(r, p, c, 2, 4), y = extremes(r, p, c + 1, 2, 4);
    const double v = magnitude_max(r, p, k, 0), a = magnitude_max(r, p, k, 1);
    json_object_set_new(points, fb_name_word(word, sizeof word, m->point[k].name),
                        json_pack("{s:o,s:o,s:o,s:o}", "x", fb_report_slider_peaks_json(&x), "y",
                                  fb_report_slider_peaks_json(&y), "speed_max_m_s",
                                  isfinite(v) ? json_real(v) : json_null(),
                                  "acceleration_max_m_s2",
                                  isfinite(a) ? json_real(a) : json_null()));
  }
  int c = FB_PLANAR_POINT_QUANTITIES * m->npoints;
  for (int j = 0; j < m->njoints; j++) {
    if (m->joint[j].kind != FB_KIND_PRISMATIC) continue;
    const fb_body_peaks s = extremes(r, p, c, 1, 2);
    json_object_set_new(slides, fb_name_word(word, sizeof word, m->joint[j].name),
                        fb_report_slider_peaks_json(&s));
    c += FB_PLANAR_SLIDE_QUANTITIES;
  }
  json_object_set_new(e, "points", points);
  json_object_set_new(e, "slides", slides);
  if (m->nsprings == 0) return;
  json_t *springs = json_object();
  for (int k = 0; k < m->nsprings; k++, c += FB_PLANAR_SPRING_QUANTITIES) {
    const fb_body_peaks s = extremes(r, p, c, 1, 2); /* length, its rate, the tension */
    json_object_set_new(springs, fb_name_word(word, sizeof word, m->spring[k].name),
                        json_pack("{s:o,s:o,s:o,s:o}", "length_min_m", num_or_null(s.pos_min),
                                  "length_max_m", num_or_null(s.pos_max), "tension_min_n",
                                  num_or_null(s.alpha_min), "tension_max_n",
                                  num_or_null(s.alpha_max)));
  }
  json_object_set_new(e, "springs", springs);
}

void fb_report_planar_outputs_table(FILE *f, const fb_planar_run *r, const fb_planar_model *p) {
  const fb_planar *m = r->m;
  if (!p->out) return;
  if (m->npoints > 0)
    fprintf(f, "| point | x min [m] | x max [m] | y min [m] | y max [m] | speed max [m/s] | "
               "acceleration max [m/s^2] |\n|---|---:|---:|---:|---:|---:|---:|\n");
  for (int k = 0; k < m->npoints; k++) {
    const int c = FB_PLANAR_POINT_QUANTITIES * k;
    const fb_body_peaks x = extremes(r, p, c, 2, 4), y = extremes(r, p, c + 1, 2, 4);
    fprintf(f, "| %s | %s | %s | %s | %s | %s | %s |\n", m->point[k].name,
            FB_NUM_CELL("%.6g", x.pos_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", x.pos_max, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", y.pos_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", y.pos_max, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", magnitude_max(r, p, k, 0), FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", magnitude_max(r, p, k, 1), FB_NUM_NONE_TABLE));
  }
  const int ns = fb_planar_slide_count(m);
  if (ns > 0)
    fprintf(f, "| slide | position min [m] | position max [m] | velocity min [m/s] | "
               "velocity max [m/s] | acceleration min [m/s^2] | acceleration max [m/s^2] |\n"
               "|---|---:|---:|---:|---:|---:|---:|\n");
  int c = FB_PLANAR_POINT_QUANTITIES * m->npoints;
  for (int j = 0; j < m->njoints; j++) {
    if (m->joint[j].kind != FB_KIND_PRISMATIC) continue;
    const fb_body_peaks s = extremes(r, p, c, 1, 2);
    fprintf(f, "| %s | %s | %s | %s | %s | %s | %s |\n", m->joint[j].name,
            FB_NUM_CELL("%.6g", s.pos_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.pos_max, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.omega_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.omega_max, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.alpha_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.alpha_max, FB_NUM_NONE_TABLE));
    c += FB_PLANAR_SLIDE_QUANTITIES;
  }
  if (m->nsprings > 0)
    fprintf(f, "| spring | length min [m] | length max [m] | tension min [N] | "
               "tension max [N] |\n|---|---:|---:|---:|---:|\n");
  for (int k = 0; k < m->nsprings; k++, c += FB_PLANAR_SPRING_QUANTITIES) {
    const fb_body_peaks s = extremes(r, p, c, 1, 2);
    fprintf(f, "| %s | %s | %s | %s | %s |\n", m->spring[k].name,
            FB_NUM_CELL("%.6g", s.pos_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.pos_max, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.alpha_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", s.alpha_max, FB_NUM_NONE_TABLE));
  }
}
