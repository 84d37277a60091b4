/* report.html of a planar case's run (report_html_planar.h): the page's
 * data by the description's body and joint names. */
#include "report_html_planar.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figures.h"
#include "model_table.h"
#include "names.h"
#include "planar_outputs.h"
#include "report_html.h"
#include "report_internal.h"
#include "report_planar_outputs.h"
#include "units.h"

/* sample i of column y: kept when it is a bucket's smallest or largest
 * (FB_REPORT_BUCKETS over the run, as a four-bar's data) */
static void keep_extremes(unsigned char *keep, const double *y, size_t n) {
  const size_t per = n > 2 * FB_REPORT_BUCKETS ? (n + FB_REPORT_BUCKETS - 1) / FB_REPORT_BUCKETS : 1;
  for (size_t from = 0; from < n; from += per) {
    size_t small = from, big = from;
    for (size_t i = from + 1; i < n && i < from + per; i++) {
      small = y[i] < y[small] ? i : small;
      big = y[i] > y[big] ? i : big;
    }
    keep[small] = 1;
    keep[big] = 1;
  }
}

/* the kept samples of y, times scale, null where not finite */
static json_t *kept(const double *y, const unsigned char *keep, size_t n, double scale) {
  json_t *a = json_array();
  for (size_t i = 0; i < n; i++)
    if (keep[i]) json_array_append_new(a, isfinite(y[i] * scale) ? json_real(y[i] * scale) : json_null());
  return a;
}

/* output c's series key in the page's data: the CSV column's word before
 * its unit (ram_guide_slide_v, tool_a_x) */
static const char *output_series(char *buf, size_t size, const fb_planar *m, int c) {
  static const char *const unit[] = {"_m_s2", "_m_s", "_m"};
  fb_report_planar_output_column(buf, size, m, c);
  const size_t n = strlen(buf);
  for (size_t k = 0; k < sizeof unit / sizeof unit[0]; k++) {
    const size_t u = strlen(unit[k]);
    if (n > u && strcmp(buf + n - u, unit[k]) == 0) {
      buf[n - u] = '\0';
      break;
    }
  }
  return buf;
}

/* one translating output of the page: name, its position, velocity and
 * acceleration columns c, c + dv, c + da, and the summary.json object of
 * its slider keys (path) */
static json_t *translating(const fb_planar *m, const char *name, int c, int dv, int da,
                           const char *path) {
  char col[3][FB_REPORT_JOINT_KEY_SIZE + 32], ser[2][FB_REPORT_JOINT_KEY_SIZE + 32];
  fb_report_planar_output_column(col[0], sizeof col[0], m, c);
  fb_report_planar_output_column(col[1], sizeof col[1], m, c + dv);
  fb_report_planar_output_column(col[2], sizeof col[2], m, c + da);
  output_series(ser[0], sizeof ser[0], m, c + dv);
  output_series(ser[1], sizeof ser[1], m, c + da);
  return json_pack("{s:s,s:b,s:[s,s,s],s:[s,s,s],s:[s,s,s],s:[n,s,s],s:[s+,s+,s+,s+,n]}",
                   "name", name, "translates", 1, "symbol", "x", "v", "a", "unit", "m", "m/s",
                   "m/s^2", "column", col[0], col[1], col[2], "series", ser[0], ser[1], "summary",
                   path, ".velocity_max_m_s", path, ".velocity_min_m_s", path,
                   ".acceleration_max_m_s2", path, ".acceleration_min_m_s2");
}

/* the page's outputs: every moving body that turns, its columns, series
 * keys and the summary.json keys of its peaks (models[].bodies.<NAME>);
 * then every output point's x and y and every prismatic joint's slide
 * (models[].points.<point>.x, .y; models[].slides.<joint>) */
static json_t *outputs_json(const fb_planar *m) {
  json_t *a = json_array();
  for (int b = 1; b < m->nbodies; b++) {
    if (!fb_planar_body_turns(m, b)) continue; /* its angle is the ground's throughout */
    const char *n = m->body[b].name;
    json_array_append_new(
        a, json_pack("{s:s,s:b,s:[s,s,s],s:[s,s,s],s:[s+,s+,s+],s:[n,s+,s+],"
                     "s:[s++,s++,s++,s++,n]}",
                     "name", n, "translates", 0, "symbol", "angle", "omega", "alpha", "unit", "rad",
                     "rad/s", "rad/s^2", "column", n, "_angle_rad", n, "_omega_rad_s", n,
                     "_alpha_rad_s2", "series", n, "_omega", n, "_alpha", "summary", "bodies.", n,
                     ".omega_max_rad_s", "bodies.", n, ".omega_min_rad_s", "bodies.", n,
                     ".alpha_max_rad_s2", "bodies.", n, ".alpha_min_rad_s2"));
  }
  char word[FB_REPORT_JOINT_KEY_SIZE], name[FB_REPORT_JOINT_KEY_SIZE + 16],
      path[FB_REPORT_JOINT_KEY_SIZE + 32];
  for (int k = 0; k < m->npoints; k++)
    for (int axis = 0; axis < 2; axis++) {
      const int c = FB_PLANAR_POINT_QUANTITIES * k + axis;
      snprintf(name, sizeof name, "%s %c", m->point[k].name, "xy"[axis]);
      snprintf(path, sizeof path, "points.%s.%c", fb_name_word(word, sizeof word, m->point[k].name),
               "xy"[axis]);
      json_array_append_new(a, translating(m, name, c, 2, 4, path));
    }
  int c = FB_PLANAR_POINT_QUANTITIES * m->npoints;
  for (int j = 0; j < m->njoints; j++) {
    if (m->joint[j].kind != FB_KIND_PRISMATIC) continue;
    snprintf(name, sizeof name, "%s slide", m->joint[j].name);
    snprintf(path, sizeof path, "slides.%s", fb_name_word(word, sizeof word, m->joint[j].name));
    json_array_append_new(a, translating(m, name, c, 1, 2, path));
    c += FB_PLANAR_SLIDE_QUANTITIES;
  }
  return a;
}

/* 1 when output column c is a velocity or an acceleration (the page's
 * series): a point's quantities 2 to 5, a slide's 1 and 2 (a spring's
 * columns are the CSV's and summary.json's, not the page's) */
static int output_rate(const fb_planar *m, int c) {
  const int np = FB_PLANAR_POINT_QUANTITIES * m->npoints;
  if (c >= fb_planar_output_count(m)) return 0; /* a spring's (planar_run.h out) */
  return c < np ? c % FB_PLANAR_POINT_QUANTITIES >= 2 : (c - np) % FB_PLANAR_SLIDE_QUANTITIES >= 1;
}

/* the largest-magnitude value of y over [i0, i1], its sign kept */
static double largest(const double *y, size_t i0, size_t i1) {
  double v = y[i0];
  for (size_t i = i0; i <= i1; i++)
    if (fabs(y[i]) > fabs(v)) v = y[i];
  return v;
}

/* a clearance model's contact episodes (unbroken runs of positive
 * penetration, planar_verdict.h's episodes, every touch listed) into the
 * page's impact list, as the four-bar's (report_html.c): each its onset and
 * end, the drive angle at onset, its largest force and penetration, every
 * moving body's largest |alpha| over it and the few steps after (the
 * rebound spike follows the force peak); their samples and
 * FB_REPORT_IMPACT_PAD either side kept; at its clearance joint ct
 * (fb_planar_model_contact). Returns the episodes counted; *listed those
 * listed (FB_REPORT_MAX_IMPACTS at most) */
static size_t impacts_json(json_t *impacts, unsigned char *keep, const fb_planar_run *r,
                           const fb_planar_model *p, const fb_planar_ref_joint *ct,
                           size_t *listed) {
  const fb_planar *m = r->m;
  const size_t n = p->n;
  const double *pen = ct->pen, *force = ct->force;
  size_t count = 0;
  *listed = 0;
  for (size_t i = 0; i < n; i++) {
    if (!(pen[i] > 0.0)) continue;
    size_t i1 = i;
    while (i1 + 1 < n && pen[i1 + 1] > 0.0) i1++;
    count++;
    if (*listed < FB_REPORT_MAX_IMPACTS) {
      double fmax_n = 0.0, pmax = 0.0;
      for (size_t k = i; k <= i1; k++) {
        if (isfinite(force[k])) fmax_n = fmax(fmax_n, force[k]);
        pmax = fmax(pmax, pen[k]);
      }
      const size_t a = i > FB_REPORT_IMPACT_PAD ? i - FB_REPORT_IMPACT_PAD : 0;
      const size_t b = i1 + FB_REPORT_IMPACT_PAD < n ? i1 + FB_REPORT_IMPACT_PAD : n - 1;
      for (size_t k = a; k <= b; k++) keep[k] = 1;
      double deg = fmod(p->drive[i] * 180.0 / M_PI, 360.0);
      deg = deg < 0.0 ? deg + 360.0 : deg;
      json_t *im = json_pack("{s:s,s:s,s:f,s:f,s:o,s:f,s:f}", "model", p->name, "joint",
                             m->joint[ct->joint].name, "t_s", p->t[i], "t_end_s", p->t[i1],
                             "crank_angle_deg", m->drive >= 0 ? json_real(deg) : json_null(),
                             "force_n", fmax_n, "penetration_m", pmax);
      const size_t a2 = i1 + 3 < n ? i1 + 3 : n - 1;
      for (int body = 1; body < m->nbodies; body++) {
        char col[96];
        snprintf(col, sizeof col, "%s_alpha_rad_s2", m->body[body].name);
        const double v = largest(p->q + ((size_t)(body - 1) * 3 + 2) * n, i, a2);
        json_object_set_new(im, col, isfinite(v) ? json_real(v) : json_null());
      }
      for (int c = 0; c < p->nout; c++) { /* the points' and slides' accelerations too */
        if (!output_rate(m, c)) continue;
        char col[FB_REPORT_JOINT_KEY_SIZE + 32];
        fb_report_planar_output_column(col, sizeof col, m, c);
        const double v = largest(p->out + (size_t)c * n, i, a2);
        json_object_set_new(im, col, isfinite(v) ? json_real(v) : json_null());
      }
      json_array_append_new(impacts, im);
      (*listed)++;
    }
    i = i1;
  }
  return count;
}

/* a pin's orbit as the four-bar's page draws it (report_page.js): its
 * eccentricity [um] and state at the kept samples (those of the bodies'
 * and the contact's extremes: every impact is among them) (0 free flight,
 * 1 in contact: a planar run does not tell an impact from continuous
 * contact), at its clearance joint ct */
static void orbit_json(json_t *j, const fb_planar_model *p, const fb_planar_ref_joint *ct,
                       const unsigned char *keep) {
  const size_t n = p->n;
  double *state = malloc((n ? n : 1) * sizeof *state);
  if (!state) return; /* the page then draws no orbit */
  for (size_t i = 0; i < n; i++) state[i] = ct->pen[i] > 0.0 ? 1.0 : 0.0;
  json_object_set_new(j, "ecc_x_um", kept(ct->ecc, keep, n, 1.0 / FB_M_PER_UM));
  json_object_set_new(j, "ecc_y_um", kept(ct->ecc + n, keep, n, 1.0 / FB_M_PER_UM));
  json_object_set_new(j, "state", kept(state, keep, n, 1.0));
  free(state);
}

/* one model's data: its kept samples by body, a clearance model's joint
 * columns and impacts (a reference's, an engine's through the kit) */
static json_t *model_json(const fb_planar_run *r, const fb_planar_model *p) {
  const fb_planar *m = r->m;
  const size_t n = p->n;
  unsigned char *keep = calloc(n ? n : 1, 1);
  if (!keep) return NULL;
  for (int b = 1; b < m->nbodies; b++)
    for (int k = 1; k <= 2; k++) keep_extremes(keep, p->q + ((size_t)(b - 1) * 3 + (size_t)k) * n, n);
  for (int c = 0; c < p->nout; c++)
    if (output_rate(m, c)) keep_extremes(keep, p->out + (size_t)c * n, n);
  json_t *impacts = json_array();
  const int ncl = fb_planar_model_contacts(p);
  size_t ne[FB_PLANAR_REF_MAX_JOINTS] = {0}, listed[FB_PLANAR_REF_MAX_JOINTS] = {0};
  for (int k = 0; k < ncl; k++) { /* each clearance joint's impacts, in turn */
    const fb_planar_ref_joint ct = fb_planar_model_contact(p, k);
    keep_extremes(keep, ct.force, n);
    keep_extremes(keep, ct.pen, n);
    ne[k] = impacts_json(impacts, keep, r, p, &ct, &listed[k]);
  }
  if (n) keep[0] = keep[n - 1] = 1;
  size_t nk = 0;
  for (size_t i = 0; i < n; i++) nk += keep[i];
  /* an engine's clearance model is zoomed beside the reference of its law */
  const fb_model *row = p->engine ? fb_model_find(p->name) : NULL;
  const fb_model *ref = row ? fb_model_reference_of(row) : NULL;
  json_t *o = json_pack("{s:s,s:s,s:b,s:s?,s:n,s:s,s:i,s:I,s:I}", "name", p->name, "engine",
                        p->reference ? "reference" : p->engine ? "engine" : "analytic",
                        "clearance", p->force != NULL, "reference",
                        p->force && ref ? ref->name : NULL, "ideal", "color",
                        fb_figure_model_color(NULL, p->name), "dash",
                        fb_figure_model_dash(NULL, p->name), "samples", (json_int_t)n,
                        "kept", (json_int_t)nk);
  json_object_set_new(o, "t", kept(p->t, keep, n, 1.0));
  for (int b = 1; b < m->nbodies; b++) {
    static const char *const key[3] = {NULL, "omega", "alpha"};
    for (int k = 1; k <= 2; k++) {
      char name[96];
      snprintf(name, sizeof name, "%s_%s", m->body[b].name, key[k]);
      json_object_set_new(o, name, kept(p->q + ((size_t)(b - 1) * 3 + (size_t)k) * n, keep, n, 1.0));
    }
  }
  for (int c = 0; c < p->nout; c++) {
    if (!output_rate(m, c)) continue;
    char key[FB_REPORT_JOINT_KEY_SIZE + 32];
    json_object_set_new(o, output_series(key, sizeof key, m, c), kept(p->out + (size_t)c * n, keep, n, 1.0));
  }
  json_t *joints = json_array();
  for (int k = 0; k < ncl; k++) {
    const fb_planar_ref_joint ct = fb_planar_model_contact(p, k);
    json_t *j = json_pack("{s:s,s:i,s:i,s:o,s:o}", "joint", m->joint[ct.joint].name,
                          "impacts", (int)ne[k], "listed", (int)listed[k], "force_n",
                          kept(ct.force, keep, n, 1.0), "penetration_um",
                          kept(ct.pen, keep, n, 1.0 / FB_M_PER_UM));
    if (p->rigid) json_object_set_new(j, "force_is_impulse_over_h", json_true());
    if (ct.ecc) orbit_json(j, p, &ct, keep);
    json_array_append_new(joints, j);
  }
  json_object_set_new(o, "joints", joints);
  json_object_set_new(o, "impacts", impacts);
  free(keep);
  return o;
}

fb_status fb_report_html_write_planar(const char *dir, const fb_planar_run *r,
                                      const json_t *summary, int *charts, fb_diag *diag) {
  const fb_case *c = &r->c;
  int pins = 0; /* revolute clearance joints: the radial clearance is theirs */
  for (int j = 0; j < r->m->njoints; j++)
    pins += ((unsigned)c->clearance.mask & (1u << j)) && r->m->joint[j].kind == FB_KIND_REVOLUTE;
  json_t *d = json_pack("{s:i,s:s,s:f,s:i,s:f,s:o,s:f,s:f}", "format", 1, "case", c->name,
                        "speed_rpm", c->crank_speed / FB_RAD_S_PER_RPM, "direction", c->direction,
                        "crank_angle0_deg", 0.0, "radial_clearance_um",
                        pins ? json_real(c->radial_clearance / FB_M_PER_UM) : json_null(),
                        "t_window_s", r->t_window, "h_s", r->n ? r->model[0].h : c->solver.h);
  json_t *models = json_array();
  json_object_set_new(d, "outputs", outputs_json(r->m));
  /* the angle the page's x axis and impact list give: the drive's; an
   * undriven case (a free start, a torque drive) has no constant speed */
  json_object_set_new(d, "driven", json_boolean(r->m->drive >= 0));
  json_object_set_new(d, "angle_name", json_string("drive"));
  /* a planar pin's orbit tells free flight from contact only (orbit_json) */
  json_object_set_new(d, "orbit_states", json_pack("[s,s]", "free flight", "in contact"));
  for (int i = 0; i < r->n; i++) {
    json_t *m = model_json(r, &r->model[i]);
    if (!m) {
      json_decref(d), json_decref(models);
      return fb_diag_set(diag, FB_ERR_NOMEM, "report.html: out of memory");
    }
    json_array_append_new(models, m);
  }
  json_object_set_new(d, "models", models);
  json_object_set_new(d, "verdicts", json_array());
  return fb_report_html_write_data(dir, d, summary, charts, diag);
}
