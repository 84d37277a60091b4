/* The report floor's shared cells (report_common.h) and helpers
 * (report_internal.h). */
#include "report_common.h"

#include "casefile.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <string.h>

#include "engine.h"
#include "fileio.h"
#include "outcome_text.h"
#include "report_internal.h"
#include "names.h"

/* finite number or null */
static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

json_t *fb_report_body_peaks_json(const fb_body_peaks *p) {
  json_t *o = json_object();
#define FB_JSON_PEAK(field, key) json_object_set_new(o, key, num(p->field));
  FB_BODY_PEAK_KEYS(FB_JSON_PEAK)
#undef FB_JSON_PEAK
  return o;
}

json_t *fb_report_bodies_json(const char *const *name, const fb_body_peaks *p, int n) {
  json_t *o = json_object();
  for (int b = 0; b < n; b++) json_object_set_new(o, name[b], fb_report_body_peaks_json(&p[b]));
  return o;
}

json_t *fb_report_slider_peaks_json(const fb_body_peaks *p) {
  json_t *o = json_object();
  json_object_set_new(o, "position_max_m", num(p->pos_max));
  json_object_set_new(o, "position_min_m", num(p->pos_min));
  json_object_set_new(o, "velocity_max_m_s", num(p->omega_max));
  json_object_set_new(o, "velocity_min_m_s", num(p->omega_min));
  json_object_set_new(o, "acceleration_max_m_s2", num(p->alpha_max));
  json_object_set_new(o, "acceleration_min_m_s2", num(p->alpha_min));
  return o;
}

json_t *fb_report_adaptive_steps_json(const fb_step_stats *s) {
  if (!s) return json_null();
  return json_pack("{s:I,s:o,s:I,s:o,s:I}", "steps_taken", (json_int_t)s->steps, "h_min_s",
                   num(s->h_min), "h_min_count", (json_int_t)s->n_h_min, "h_max_s",
                   num(s->h_max), "h_max_count", (json_int_t)s->n_h_max);
}

/* prose: printf-formatted text wrapped at spaces to FB_TABLE_COLUMNS,
 * continuation lines indented by two spaces */
void fb_report_say(FILE *f, const char *fmt, ...) {
  char text[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  for (char *line = text; line;) {
    char *nl = strchr(line, '\n');
    if (nl) *nl = '\0';
    const char *p = line;
    int indent = 0;
    while (strlen(p) + (size_t)indent > FB_TABLE_COLUMNS) {
      const int room = FB_TABLE_COLUMNS - indent;
      int cut = room;
      while (cut > 0 && p[cut] != ' ') cut--;
      if (cut == 0) break; /* one word longer than a line: printed whole */
      fprintf(f, "%*s%.*s\n", indent, "", cut, p);
      p += cut + 1;
      indent = 2;
    }
    fprintf(f, "%*s%s\n", indent, "", p);
    line = nl ? nl + 1 : NULL;
  }
}

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

fb_status fb_report_write_json(const char *path, const json_t *j, fb_diag *diag) {
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) return st;
  if (json_dumpf(j, out.f, JSON_INDENT(2) | JSON_REAL_PRECISION(12)) != 0) {
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_IO, "%s: JSON write failed", path);
  }
  fputc('\n', out.f);
  return fb_outfile_commit(&out, diag);
}

json_t *fb_report_loads_of(const double *t, size_t n, double t_from, const double *torque,
                           int njoints, const char *const joint[], const double *const fx[],
                           const double *const fy[]) {
  double tmax = -INFINITY, tmin = INFINITY;
  size_t held = 0;
  for (size_t i = 0; i < n; i++) {
    if (t[i] < t_from) continue;
    tmax = fmax(tmax, torque[i]);
    tmin = fmin(tmin, torque[i]);
    held++;
  }
  if (held == 0) return json_null();
  json_t *o = json_object(), *r = json_object();
  json_object_set_new(o, "drive_torque_max_n_m", num(tmax));
  json_object_set_new(o, "drive_torque_min_n_m", num(tmin));
  json_object_set_new(o, "drive_torque_abs_max_n_m", num(fmax(fabs(tmax), fabs(tmin))));
  for (int j = 0; j < njoints; j++) {
    double most = 0.0;
    for (size_t i = 0; i < n; i++)
      if (t[i] >= t_from) most = fmax(most, hypot(fx[j][i], fy[j][i]));
    char key[FB_REPORT_JOINT_KEY_SIZE];
    json_object_set_new(r, fb_report_joint_key(key, sizeof key, joint[j]), num(most));
  }
  json_object_set_new(o, "reaction_max_n", r);
  return o;
}

const char *fb_report_series_format_name(fb_series_format f) {
  return f == FB_SERIES_HDF5 ? "hdf5" : f == FB_SERIES_NONE ? "none" : "csv";
}

const char *fb_report_joint_key(char *buf, size_t size, const char *joint) {
  return fb_name_word(buf, size, joint);
}

json_t *fb_report_loads_json(const fb_series *s, double t_from) {
  if (!s->has_loads) return json_null();
  const fb_mech_desc *mech = s->mech ? s->mech : &fb_mech_fourbar;
  const char *joint[4];
  const double *fx[4], *fy[4];
  for (int j = 0; j < 4; j++) {
    joint[j] = fb_mech_joint_name(mech, j);
    fx[j] = s->reaction[j][0];
    fy[j] = s->reaction[j][1];
  }
  return fb_report_loads_of(s->t, s->n, t_from, s->drive_torque, 4, joint, fx, fy);
}

const fb_contact_law *fb_report_model_law(fb_contact_law *buf, const fb_run *r,
                                          const fb_model_result *m, int j) {
  const fb_model *row = m->run.model;
  if (!row || row->law == FB_MODEL_LAW_NONE || !(m->run.clearance_mask & (1 << j)) ||
      !r->scene.has_law[row->law])
    return NULL;
  /* the model's own view: an engine model's law carries the injected error */
  fb_model_scene sm;
  fb_diag inner;
  *buf = fb_scene_select(&sm, &r->scene, row, &inner) == FB_OK ? sm.law[j]
                                                               : r->scene.law[row->law][j];
  return buf;
}

const char *fb_report_model_mapping(const fb_run *r, const fb_model_result *m) {
  if (!m->run.has_provenance) return NULL;
  const fb_engine *e = fb_engine_get(m->run.model->engine, NULL);
  const char *own = e && e->mapping_text ? e->mapping_text(m->run.collider) : NULL;
  return own ? own : fb_mapping_name(r->scene.mapping);
}

const char *fb_report_body_abbrev(const char *body) {
  static const char *const names[][2] = {{"coupler", "cpl"}, {"follower", "flw"}, {"slider", "sld"}};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    if (strcmp(body, names[i][0]) == 0) return names[i][1];
  static _Thread_local char three[4];
  snprintf(three, sizeof three, "%s", body);
  return three;
}

const char *fb_report_injected_case_text(char *buf, size_t size, const fb_case *c) {
  const fb_clearance *cl = &c->clearance;
  const int given = fb_casefile_given(c, "clearance", "engine_damping_scale");
  buf[0] = '\0';
  if (cl->engine_stiffness_scale == 1.0 && cl->engine_damping_scale == 1.0 && !given) return NULL;
  snprintf(buf, size, "injected error: [clearance] engine_stiffness_scale = %g, "
           "engine_damping_scale = %g%s multiply the contact law of every engine model (the "
           "references keep the case's law)", cl->engine_stiffness_scale,
           cl->engine_damping_scale,
           given ? " (given: the restitution law's damper is that of the case's stiffness, scaled)"
                 : " (the restitution law's damper follows the scaled stiffness)");
  return buf;
}

const char *fb_report_injected_text(char *buf, size_t size, const fb_run *r) {
  if (!fb_report_injected_case_text(buf, size, &r->c)) return NULL;
  size_t n = strlen(buf);
  for (int i = 0; i < r->n && n < size; i++)
    if (r->model[i].run.model->rigid)
      n += (size_t)snprintf(buf + n, size - n, "; %s is rigid: no stiffness or damper to scale",
                            r->model[i].run.name);
  return buf;
}
