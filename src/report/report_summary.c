/* summary.json and timing.json (report_summary.h): a run's every number
 * as JSON, one function per block of a model's object (its collider, its
 * verdict, its windows of peaks, its errors against the analytic solution,
 * its reference and its check integration, its engine's own settings, its
 * spikes and contact), in the order docs/outputs.md gives the keys. */
#include "report_summary.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "engine.h"
#include "casefile.h"
#include "outcome_text.h"
#include "report_chaos.h"
#include "report_verdict.h"
#include "report_internal.h"
#include "report_variants.h"
#include "resolution.h"
#include "series_write.h"
#include "start.h"

/* finite number or null */
static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

/* relative peaks of a rotating body ("omega_max_rel", ...) or a translating
 * one ("velocity_max_m_s_rel", ...) */
static json_t *rel_peaks_json(const fb_body_peaks *p, int translates) {
  json_t *o = json_object();
  json_object_set_new(o, translates ? "velocity_max_m_s_rel" : "omega_max_rel", num(p->omega_max));
  json_object_set_new(o, translates ? "velocity_min_m_s_rel" : "omega_min_rel", num(p->omega_min));
  json_object_set_new(o, translates ? "acceleration_max_m_s2_rel" : "alpha_max_rel",
                      num(p->alpha_max));
  json_object_set_new(o, translates ? "acceleration_min_m_s2_rel" : "alpha_min_rel",
                      num(p->alpha_min));
  return o;
}

static json_t *body_error_json(const fb_body_error *e) {
  json_t *o = json_object();
  json_object_set_new(o, "omega_max_rel", num(e->omega_max_rel));
  json_object_set_new(o, "omega_min_rel", num(e->omega_min_rel));
  json_object_set_new(o, "alpha_max_rel", num(e->alpha_max_rel));
  json_object_set_new(o, "alpha_min_rel", num(e->alpha_min_rel));
  json_object_set_new(o, "omega_err_max_rad_s", num(e->omega_err_max));
  json_object_set_new(o, "omega_err_rms_rad_s", num(e->omega_err_rms));
  json_object_set_new(o, "alpha_err_max_rad_s2", num(e->alpha_err_max));
  json_object_set_new(o, "alpha_err_rms_rad_s2", num(e->alpha_err_rms));
  return o;
}

/* the link lengths by the names of the case's description (the four-bar's
 * crank, coupler, follower, ground; the slider-crank's crank, coupler,
 * offset) [m] */
static json_t *lengths_json(const fb_run *r, const fb_linkage *lk) {
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  json_t *o = json_object();
  for (int i = 0; i < mech->nlengths; i++) json_object_set_new(o, mech->length[i], num(lk->length[i]));
  return o;
}

static json_t *peak_at_json(const fb_peak_at *a) {
  json_t *o = json_object();
  json_object_set_new(o, "time_s", num(a->t));
  json_object_set_new(o, "crank_angle_rad", num(a->crank_angle));
  return o;
}

/* where each peak of output body b was: "omega_max", ... ("velocity_max",
 * ... for a translating body) */
static json_t *body_at_json(const fb_run *r, int b, const fb_body_peak_at *a) {
  const int tr = fb_mech_output_translates(fb_case_mech(&r->c), b);
  json_t *o = json_object();
  json_object_set_new(o, tr ? "velocity_max" : "omega_max", peak_at_json(&a->omega_max));
  json_object_set_new(o, tr ? "velocity_min" : "omega_min", peak_at_json(&a->omega_min));
  json_object_set_new(o, tr ? "acceleration_max" : "alpha_max", peak_at_json(&a->alpha_max));
  json_object_set_new(o, tr ? "acceleration_min" : "alpha_min", peak_at_json(&a->alpha_min));
  return o;
}

/* the names of the case's output bodies (mechanism.h) into name; their number */
static int output_names(const fb_run *r, const char *name[FB_MECH_MAX_OUTPUTS]) {
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  int out[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(mech, out);
  for (int b = 0; b < n; b++) name[b] = mech->body[out[b]].name;
  return n;
}

/* 1 when output body b of the case's mechanism translates (a slider): its
 * keys are position_*_m, velocity_*_m_s, acceleration_*_m_s2 */
static int translating(const fb_run *r, int b) {
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  int out[FB_MECH_MAX_OUTPUTS];
  const int n = fb_mech_outputs(mech, out);
  return b < n && mech->body[out[b]].motion == FB_MOTION_TRANSLATING;
}

/* a body's peaks: a translating body's as docs/outputs.md's models[].slider */
static json_t *body_peaks_json(const fb_run *r, int b, const fb_body_peaks *p) {
  return translating(r, b) ? fb_report_slider_peaks_json(p) : fb_report_body_peaks_json(p);
}

/* a translating body's error against the analytic solution (the peaks' keys
 * with _rel, and the per-sample errors) */
static json_t *slider_error_json(const fb_body_error *e, int with_position) {
  json_t *o = json_object();
  if (with_position) {
    json_object_set_new(o, "position_max_m_rel", num(e->pos_max_rel));
    json_object_set_new(o, "position_min_m_rel", num(e->pos_min_rel));
  }
  json_object_set_new(o, "velocity_max_m_s_rel", num(e->omega_max_rel));
  json_object_set_new(o, "velocity_min_m_s_rel", num(e->omega_min_rel));
  json_object_set_new(o, "acceleration_max_m_s2_rel", num(e->alpha_max_rel));
  json_object_set_new(o, "acceleration_min_m_s2_rel", num(e->alpha_min_rel));
  json_object_set_new(o, "velocity_err_max_m_s", num(e->omega_err_max));
  json_object_set_new(o, "velocity_err_rms_m_s", num(e->omega_err_rms));
  json_object_set_new(o, "acceleration_err_max_m_s2", num(e->alpha_err_max));
  json_object_set_new(o, "acceleration_err_rms_m_s2", num(e->alpha_err_rms));
  return o;
}

static json_t *body_error_of(const fb_run *r, int b, const fb_body_error *e) {
  return translating(r, b) ? slider_error_json(e, 1) : body_error_json(e);
}

/* the same against the reference or the check integration, which compare
 * velocity and acceleration peaks alone */
static json_t *body_rate_error_of(const fb_run *r, int b, const fb_body_error *e) {
  return translating(r, b) ? slider_error_json(e, 0) : body_error_json(e);
}

/* {"from_s", "to_s", "<body>": PEAKS per output body, "at": {"<body>": {"omega_max":
 * {"time_s", "crank_angle_rad"}, ...}, ...}} (the four-bar: coupler, then follower) */
static json_t *window_json(const fb_run *r, const fb_peaks *p, const fb_peaks_at *at, double from,
                           double to) {
  const char *name[FB_MECH_MAX_OUTPUTS];
  const int nb = output_names(r, name);
  json_t *o = json_object();
  json_object_set_new(o, "from_s", num(from));
  json_object_set_new(o, "to_s", num(to));
  for (int b = 0; b < nb; b++) json_object_set_new(o, name[b], body_peaks_json(r, b, &p->body[b]));
  json_t *a = json_object();
  for (int b = 0; b < nb; b++) json_object_set_new(a, name[b], body_at_json(r, b, &at->body[b]));
  json_object_set_new(o, "at", a);
  return o;
}

/* summary.json's `contact`: one object per clearance joint (report_summary.h) */
static json_t *contact_json(const fb_run *r, const fb_model_result *m) {
  json_t *arr = json_array();
  for (int j = 0; j < 4; j++) {
    fb_contact_law lb;
      const fb_contact_law *law = fb_report_model_law(&lb, r, m, j);
    if (!law) continue;
    json_t *o = fb_report_contact_law_json(fb_case_joint_name(&r->c, j), law, r->scene.mapping);
    /* the force an impact must exceed, the same for every model (episode.h) */
    json_object_set_new(o, "impact_floor_n", num(r->scene.impact_floor[j]));
    const fb_contact_provenance *p = &m->run.provenance[j];
    const int have = m->run.has_provenance && p->contact_steps > 0;
    const char *mapping = fb_report_model_mapping(r, m);
    json_object_set_new(o, "mapping", mapping ? json_string(mapping) : json_null());
    if (have && law->kind == FB_LAW_RESTITUTION) {
      const double z = fb_contact_law_zeta(law);
      json_object_set_new(o, "damping_n_s_m",
                          json_pack("{s:f,s:f}", "min", 2.0 * z * sqrt(law->stiffness * p->mass_eff_min),
                                    "max", 2.0 * z * sqrt(law->stiffness * p->mass_eff_max)));
    }
    json_object_set_new(o, "effective_mass_kg",
                        have && isfinite(p->mass_eff_min) && isfinite(p->mass_eff_max)
                            ? json_pack("{s:f,s:f}", "min", p->mass_eff_min, "max", p->mass_eff_max)
                            : json_null());
    json_object_set_new(o, "erp_max", have ? num(p->erp_max) : json_null());
    json_object_set_new(o, "cfm_min", have ? num(p->cfm_min) : json_null());
    json_object_set_new(o, "h_omega_c_max", have ? num(p->h_omega_max) : json_null());
    json_object_set_new(o, "h_omega_c_bound", num(FB_H_OMEGA_C_BOUND));
    json_object_set_new(o, "contact_steps", json_integer((json_int_t)(have ? p->contact_steps : 0)));
    /* an engine without a step-size figure (Simbody's error control) has no verdict */
    json_object_set_new(o, "resolved", have && isfinite(p->h_omega_max)
                                           ? json_boolean(p->h_omega_max <= FB_H_OMEGA_C_BOUND)
                                           : json_null());
    json_array_append_new(arr, o);
  }
  return arr;
}

/* "collider", "collider_segments", "bore", "bore_ovality_m": how its
 * clearance contact was found (docs/colliders.md); null without clearance
 * joints */
static void collider_json(json_t *o, const fb_model_run *run) {
  if (run->clearance_mask) {
    json_object_set_new(o, "collider", json_string(fb_collider_name(run->collider)));
    json_object_set_new(o, "collider_segments",
                        run->segments > 0 ? json_integer(run->segments) : json_null());
    json_object_set_new(o, "bore", json_string(run->bore_ovality > 0.0 ? "ellipse" : "circle"));
    json_object_set_new(o, "bore_ovality_m", num(run->bore_ovality));
  } else {
    json_object_set_new(o, "collider", json_null());
    json_object_set_new(o, "collider_segments", json_null());
    json_object_set_new(o, "bore", json_null());
    json_object_set_new(o, "bore_ovality_m", json_null());
  }
}

/* "status", "verdict", "verdict_basis", "verdict_reason" (verdict.h) */
static void verdict_json(json_t *o, const fb_model_result *m, const fb_run *r) {
  char stop[256];
  json_object_set_new(o, "status", json_string(fb_report_model_status(stop, sizeof stop, m)));
  char why[1024];
  json_object_set_new(o, "verdict", json_string(fb_report_verdict(why, sizeof why, m, r)));
  const char *basis = fb_verdict_basis_name(m->basis);
  json_object_set_new(o, "verdict_basis", basis ? json_string(basis) : json_null());
  json_object_set_new(o, "verdict_reason", json_string(why));
}

/* "peaks": the window's peaks and when they happened (null before the window) */
static json_t *peaks_window_json(const fb_model_result *m, const fb_run *r, double t_end) {
  if (!m->has_peaks) return json_null();
  json_t *w = window_json(r, &m->peaks, &m->peaks_at, r->t_window, t_end);
  json_object_set_new(w, "window", json_string(r->c.peaks == FB_PEAKS_ALL ? "all" : "steady"));
  return w;
}

/* "startup": revolution 1's peaks; a clearance model's also its largest
 * force and penetration and its first impact */
static json_t *startup_window_json(const fb_model_result *m, const fb_run *r, double t_end) {
  if (!m->has_startup) return json_null();
  const fb_model_run *run = &m->run;
  json_t *w = window_json(r, &m->startup, &m->startup_at, 0.0, fmin(t_end, r->t_startup_end));
  if (run->clearance_mask) {
    json_object_set_new(w, "force_max_n", num(m->startup_force_max));
    json_object_set_new(w, "penetration_max_m", num(m->startup_penetration_max));
    const fb_first_impact *fi = &m->first_impact;
    if (m->first_impact_joint >= 0 && fi->found) {
      json_t *f = json_object();
      json_object_set_new(f, "joint", json_string(fb_case_joint_name(&r->c, m->first_impact_joint)));
      json_object_set_new(f, "time_s", num(fi->t));
      json_object_set_new(f, "speed_m_s", num(fi->speed));
      json_object_set_new(f, "crank_angle_rad", num(fi->crank_angle));
      json_object_set_new(f, "rebound_ratio", num(fi->rebound));
      json_object_set_new(f, "contact_duration_s", num(fi->duration));
      json_object_set_new(w, "first_impact", f);
    } else {
      json_object_set_new(w, "first_impact", json_null());
    }
  }
  return w;
}

/* "warnings": each in words (outcome_text.h) */
static json_t *warnings_json(const fb_model_result *m) {
  json_t *warnings = json_array();
  char wt[512];
  for (int k = 0; k < m->warning_count; k++)
    json_array_append_new(warnings, json_string(fb_warning_text(wt, sizeof wt, &m->warnings[k])));
  return warnings;
}

/* "error_vs_analytic": against the analytic solution of the same link
 * lengths (null when not measured) */
static json_t *error_vs_analytic_json(const fb_model_result *m, const fb_run *r) {
  if (!m->has_error) return json_null();
  const char *name[FB_MECH_MAX_OUTPUTS];
  const int nb = output_names(r, name);
  const fb_model_run *run = &m->run;
  json_t *e = json_object();
  json_object_set_new(e, "reference",
                      json_string(run->model->engine != FB_ENGINE_ANALYTIC
                                      ? "analytic solution of the same link lengths"
                                      : "exact (refined) peaks of the same solution: the "
                                        "sampling floor of the time grid"));
  for (int b = 0; b < nb; b++) json_object_set_new(e, name[b], body_error_of(r, b, &m->error.body[b]));
  json_object_set_new(e, "crank_angle_err_max_rad", num(m->error.crank_angle_err_max));
  return e;
}

/* "delta_vs_analytic_nominal": the peaks against the nominal linkage's exact
 * peaks (null before the window) */
static json_t *delta_json(const fb_model_result *m, const fb_run *r) {
  if (!m->has_peaks) return json_null();
  const char *name[FB_MECH_MAX_OUTPUTS];
  const int nb = output_names(r, name);
  json_t *d = json_object();
  for (int b = 0; b < nb; b++)
    json_object_set_new(d, name[b], rel_peaks_json(&m->delta_vs_nominal.body[b], translating(r, b)));
  return d;
}

/* "<engine name>": the engine's own choices as the model used them (its
 * table's settings; nothing for an engine without) */
static void engine_settings_json(json_t *o, const fb_model_run *run, const fb_run *r) {
  const fb_engine *e = fb_engine_get(run->model->engine, NULL);
  fb_engine_setting set[FB_ENGINE_SETTINGS_MAX];
  const int n = e && e->settings ? e->settings(set, &r->c, run->clearance_mask, run->collider, run->h)
                                 : 0;
  if (n <= 0) return;
  json_t *s = json_object();
  for (int k = 0; k < n && k < FB_ENGINE_SETTINGS_MAX; k++)
    json_object_set_new(s, set[k].key,
                        set[k].kind == FB_SETTING_TEXT      ? json_string(set[k].text)
                        : set[k].kind == FB_SETTING_INTEGER ? json_integer(set[k].integer)
                                                            : num(set[k].number));
  json_object_set_new(o, e->name, s);
}

/* "error_vs_reference": a clearance model against the reference of its law */
static json_t *error_vs_reference_json(const fb_model_result *m, const fb_run *r) {
  const fb_reference_error *e = &m->ref_error;
  const char *name[FB_MECH_MAX_OUTPUTS];
  const int nb = output_names(r, name);
  json_t *o2 = json_object(), *a = json_array(), *b = json_array();
  json_object_set_new(o2, "reference", json_string(m->ref_name));
  for (int k = 0; k < nb; k++) json_object_set_new(o2, name[k], body_rate_error_of(r, k, &e->body[k]));
  json_object_set_new(o2, "force_max_rel", num(e->force_max_rel));
  json_object_set_new(o2, "force_err_rms_n", num(e->force_err_rms));
  json_object_set_new(o2, "penetration_max_rel", num(e->penetration_max_rel));
  json_object_set_new(o2, "persistent_penetration_rel", num(e->persistent_penetration_rel));
  json_object_set_new(o2, "persistent_samples", json_integer((json_int_t)e->persistent_samples));
  json_object_set_new(o2, "ecc_direction_rms_rad", num(e->ecc_direction_rms));
  json_object_set_new(o2, "impacts", json_integer(e->impacts));
  json_object_set_new(o2, "impacts_reference", json_integer(e->impacts_reference));
  for (int k = 0; k < 8; k++) {
    if (e->impact_angles[k] >= 0) json_array_append_new(a, num(e->impact_angles[k]));
    if (e->impact_angles_reference[k] >= 0) json_array_append_new(b, num(e->impact_angles_reference[k]));
  }
  json_object_set_new(o2, "impact_crank_angles_rad", a);
  json_object_set_new(o2, "impact_crank_angles_reference_rad", b);
  json_t *fi = json_array();
  for (int k = 0; k < e->first_impacts; k++)
    json_array_append_new(fi, json_pack("{s:o,s:o}", "force_max_rel", num(e->first_impact_force_rel[k]),
                                        "penetration_max_rel",
                                        num(e->first_impact_penetration_rel[k])));
  json_object_set_new(o2, "first_impacts", fi);
  return o2;
}

/* "divergence": where it leaves its reference, the impacts matched before */
static json_t *divergence_json(const fb_model_result *m) {
  const fb_divergence *d = &m->divergence;
  json_t *dv = json_object();
  json_object_set_new(dv, "reference", json_string(m->ref_name));
  json_object_set_new(dv, "diverged", json_boolean(d->diverged));
  json_object_set_new(dv, "time_s", num(d->t)); /* null: stays with it to the end */
  json_object_set_new(dv, "crank_angle_rad", num(d->crank_angle));
  json_object_set_new(dv, "compared_to_s", num(d->t_end));
  json_object_set_new(dv, "eccentricity_tolerance_m", num(d->ecc_tol));
  json_object_set_new(dv, "coupler_angle_tolerance_rad", num(d->angle_tol));
  json_object_set_new(dv, "impacts", json_integer(d->impacts_model));
  json_object_set_new(dv, "impacts_reference", json_integer(d->impacts_reference));
  json_object_set_new(dv, "impacts_matched", json_integer(d->matched));
  json_object_set_new(dv, "one_to_one", json_boolean(d->one_to_one));
  json_object_set_new(dv, "force_rel_max", num(d->force_rel_max));
  json_object_set_new(dv, "penetration_rel_max", num(d->penetration_rel_max));
  json_t *list = json_array();
  for (int k = 0; k < d->matched && k < FB_DIVERGE_MAX_IMPACTS; k++) {
    const fb_matched_impact *q = &d->impact[k];
    json_t *e = json_object();
    json_object_set_new(e, "time_s", num(q->t));
    json_object_set_new(e, "time_error_s", num(q->t_error));
    json_object_set_new(e, "force_n", num(q->force));
    json_object_set_new(e, "force_rel", num(q->force_rel));
    json_object_set_new(e, "penetration_m", num(q->penetration));
    json_object_set_new(e, "penetration_rel", num(q->penetration_rel));
    json_array_append_new(list, e);
  }
  json_object_set_new(dv, "matched_impacts", list);
  return dv;
}

/* "error_estimate": the reference against its own integration at a
 * tighter tolerance, and what else that check measured (report_chaos.h) */
static json_t *error_estimate_json(const fb_model_result *m, const fb_run *r) {
  const fb_reference_error *e = &m->ref_estimate;
  const char *name[FB_MECH_MAX_OUTPUTS];
  const int nb = output_names(r, name);
  json_t *o3 = json_object();
  json_object_set_new(o3, "tolerance", num(m->ref_tol));
  json_object_set_new(o3, "check_tolerance", num(m->ref_check_tol));
  json_object_set_new(o3, "check_steps", json_integer((json_int_t)m->ref_check_steps));
  for (int b = 0; b < nb; b++) json_object_set_new(o3, name[b], body_rate_error_of(r, b, &e->body[b]));
  json_object_set_new(o3, "force_max_rel", num(e->force_max_rel));
  json_object_set_new(o3, "force_err_rms_n", num(e->force_err_rms));
  json_object_set_new(o3, "penetration_max_rel", num(e->penetration_max_rel));
  json_object_set_new(o3, "impacts", json_integer(e->impacts));
  json_object_set_new(o3, "impacts_check", json_integer(e->impacts_reference));
  fb_report_check_json(o3, m, r);
  return o3;
}

/* "spikes" (null before the window) and, with them, "clearance_joints" */
static void spikes_json(json_t *o, const fb_model_result *m, const fb_run *r) {
  if (!m->has_spikes) {
    json_object_set_new(o, "spikes", json_null());
    return;
  }
  const fb_spikes *k = &m->spikes;
  json_t *sp = json_object();
  /* counts as JSON integers, the rest as numbers (null when not finite) */
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  char kb[96];
#define FB_JSON_SPIKE(field, key)                                                         \
  json_object_set_new(sp, fb_mech_output_key(kb, sizeof kb, mech, key),                   \
                      _Generic((k->field), int: json_integer((json_int_t)(k->field)),     \
                               default: num((double)(k->field))));
  FB_SPIKE_KEYS(FB_JSON_SPIKE)
#undef FB_JSON_SPIKE
  json_object_set_new(sp, "alpha_reference", json_string(m->spikes_reference));
  json_object_set_new(o, "spikes", sp);
  json_t *joints = json_array();
  for (int j = 0; j < 4; j++)
    if (m->run.clearance_mask & (1 << j))
      json_array_append_new(joints, json_string(fb_case_joint_name(&r->c, j)));
  json_object_set_new(o, "clearance_joints", joints);
}

/* "bodies": every moving body's omega and alpha extremes by its name
 * (docs/outputs.md): an output body's window peaks, the driven body's
 * prescribed speed (alpha 0), a translating body's zeros (it does not
 * turn); null before the window */
static json_t *bodies_json(const fb_model_result *m, const fb_run *r) {
  if (!m->has_peaks) return json_null();
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  const char *name[FB_MECH_MAX_BODIES];
  fb_body_peaks p[FB_MECH_MAX_BODIES];
  int n = 0, k = 0;
  for (int b = 0; b < mech->nbodies; b++) {
    const fb_mech_body *body = &mech->body[b];
    if (body->motion == FB_MOTION_FIXED) continue;
    memset(&p[n], 0, sizeof p[n]);
    if (b == mech->input) p[n].omega_max = p[n].omega_min = fb_case_omega2(&r->c);
    else if (body->output && body->motion != FB_MOTION_TRANSLATING) p[n] = m->peaks.body[k];
    k += body->output;
    name[n++] = body->name;
  }
  return fb_report_bodies_json(name, p, n);
}

/* one model's object of summary.json's "models" (docs/outputs.md) */
static json_t *model_json(const fb_model_result *m, const fb_run *r) {
  json_t *o = json_object();
  const fb_model_run *run = &m->run;
  json_object_set_new(o, "name", json_string(run->name));
  json_object_set_new(o, "kind", json_string(fb_engine_name(run->model->engine)));
  json_object_set_new(o, "builder", run->builder ? json_string(run->builder) : json_null());
  collider_json(o, run);
  verdict_json(o, m, r);
  json_object_set_new(o, "peaks_converged", fb_report_converged_json(m));
  json_object_set_new(o, "vs_published",
                      fb_report_vs_published_json(&r->c, run->model, &m->peaks, m->has_peaks));
  json_object_set_new(o, "impact_statistics", fb_report_ensemble_json(m, r));
  json_object_set_new(o, "verdict_test", fb_report_test_json(m));
  json_object_set_new(o, "h_s", num(run->h));
  json_object_set_new(o, "steps", json_integer((json_int_t)run->steps));
  json_object_set_new(o, "adaptive_steps",
                      fb_report_adaptive_steps_json(run->has_step_stats ? &run->step_stats : NULL));
  json_object_set_new(o, "lengths_m", lengths_json(r, &run->lengths));
  const char *name[FB_MECH_MAX_OUTPUTS];
  const int nb = output_names(r, name);
  for (int b = 0; b < nb; b++)
    json_object_set_new(o, name[b],
                        m->has_peaks ? body_peaks_json(r, b, &m->peaks.body[b]) : json_null());
  json_object_set_new(o, "bodies", bodies_json(m, r));
  const fb_series *ser = &run->series;
  const double t_end = ser->n ? ser->t[ser->n - 1] : 0.0;
  json_object_set_new(o, "peaks", peaks_window_json(m, r, t_end));
  json_object_set_new(o, "startup", startup_window_json(m, r, t_end));
  json_object_set_new(o, "penetration_max_m", run->clearance_mask ? num(m->penetration_max_run)
                                                                  : json_null());
  json_object_set_new(o, "warnings", warnings_json(m));
  json_object_set_new(o, "error_vs_analytic", error_vs_analytic_json(m, r));
  json_object_set_new(o, "delta_vs_analytic_nominal", delta_json(m, r));
  if (fb_engine_steps_world(run->model->engine)) json_object_set_new(o, "joint_drift_max_m", num(run->joint_drift_max));
  json_object_set_new(o, "loads", fb_report_loads_json(&run->series, r->t_window));
  engine_settings_json(o, run, r);
  if (m->has_ref_error) json_object_set_new(o, "error_vs_reference", error_vs_reference_json(m, r));
  if (m->has_divergence) json_object_set_new(o, "divergence", divergence_json(m));
  if (m->has_ref_estimate) json_object_set_new(o, "error_estimate", error_estimate_json(m, r));
  spikes_json(o, m, r);
  /* what the contact rows received, also for a run that stopped early */
  if (run->clearance_mask) json_object_set_new(o, "contact", contact_json(r, m));
  return o;
}

static json_t *stackup_json(const fb_case *c) {
  json_t *o = json_object();
  const fb_mech_desc *mech = fb_case_mech(c); /* its lengths by their names */
  char corner[FB_LINK_COUNT + 1];
  for (int k = 0; k < mech->nlengths; k++) corner[k] = "-0+"[c->stackup.corner[k] + 1];
  corner[mech->nlengths] = '\0';
  json_object_set_new(o, "corner", json_string(corner));
  json_t *links = json_array();
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  for (int k = 0; k < mech->nlengths; k++) {
    json_t *l = json_object();
    json_object_set_new(l, "link", json_string(mech->length[k]));
    json_object_set_new(l, "nominal_m", num(c->nominal.length[k]));
    json_object_set_new(l, "plus_minus_m", num(c->plus_minus[k]));
    json_object_set_new(l, "stackup_m", num(su.length[k]));
    json_object_set_new(l, "source", json_string(c->tolerance_source[k]));
    json_array_append_new(links, l);
  }
  json_object_set_new(o, "links", links);
  json_object_set_new(o, "pin_diameter_m", num(c->pin_diameter));
  json_object_set_new(o, "radial_clearance_m", num(c->radial_clearance));
  json_object_set_new(o, "clearance_source", json_string(c->clearance_source));
  return o;
}

/* every mass and inertia the run used, with its source (case, derived, default) */
static json_t *masses_json(const fb_case *c) {
  json_t *o = json_object();
  json_object_set_new(o, "density_kg_m3", num(c->density));
  json_object_set_new(o, "density_source",
                      json_string(fb_value_source_name(fb_casefile_given(c, "material",
                                                                        "density_kg_m3")
                                                           ? FB_SOURCE_CASE
                                                           : FB_SOURCE_DEFAULT)));
  json_t *links = json_array();
  for (int i = 0; i < 3; i++) {
    const fb_link_mass *m = &c->link[i];
    const fb_link_mass_source *s = &c->link_source[i];
    char kw[64], kt[64];
    const char *body = fb_case_mech(c)->body[i].name;
    snprintf(kw, sizeof kw, "%s_width_mm", body);
    snprintf(kt, sizeof kt, "%s_thickness_mm", body);
    json_t *l = json_object();
    json_object_set_new(l, "link", json_string(body));
    json_object_set_new(l, "mass_kg", num(m->mass));
    json_object_set_new(l, "mass_source", json_string(fb_value_source_name(s->mass)));
    json_object_set_new(l, "inertia_kg_m2", num(m->inertia));
    json_object_set_new(l, "inertia_source", json_string(fb_value_source_name(s->inertia)));
    json_object_set_new(l, "inertia_long_kg_m2", num(m->inertia_long));
    json_object_set_new(l, "inertia_long_source",
                        json_string(fb_value_source_name(s->inertia_long)));
    json_object_set_new(l, "inertia_transverse_kg_m2", num(m->inertia_transverse));
    json_object_set_new(l, "inertia_transverse_source",
                        json_string(fb_value_source_name(s->inertia_transverse)));
    json_object_set_new(l, "com_fraction", num(m->com_fraction));
    json_object_set_new(l, "com_fraction_source",
                        json_string(fb_value_source_name(s->com_fraction)));
    json_object_set_new(l, "bar_width_m", num(c->link_width[i]));
    json_object_set_new(l, "bar_width_source",
                        json_string(fb_value_source_name(fb_casefile_given(c, "mass", kw)
                                                             ? FB_SOURCE_CASE
                                                             : FB_SOURCE_DEFAULT)));
    json_object_set_new(l, "bar_thickness_m", num(c->link_thickness[i]));
    json_object_set_new(l, "bar_thickness_source",
                        json_string(fb_value_source_name(fb_casefile_given(c, "mass", kt)
                                                             ? FB_SOURCE_CASE
                                                             : FB_SOURCE_DEFAULT)));
    json_array_append_new(links, l);
  }
  json_object_set_new(o, "links", links);
  return o;
}

json_t *fb_report_summary_json(const fb_run *r, const char *case_path) {
  const fb_case *c = &r->c;
  json_t *o = json_object();
  json_object_set_new(o, "case", json_string(c->name));
  json_object_set_new(o, "case_file", case_path ? json_string(case_path) : json_null());
  /* the case's [linkage] type: "four-bar" or "slider-crank" */
  json_object_set_new(o, "mechanism", json_string(fb_case_mech(c)->type));
  json_object_set_new(o, "speed_rpm", num(c->crank_speed * 60.0 / (2.0 * M_PI)));
  json_object_set_new(o, "crank_omega_rad_s", num(fb_case_omega2(c)));
  json_object_set_new(o, "direction", json_string(c->direction > 0 ? "ccw" : "cw"));
  json_object_set_new(o, "branch", json_string(c->branch == FB_BRANCH_OPEN ? "open" : "crossed"));
  json_object_set_new(o, "revolutions", num(c->revolutions));
  json_object_set_new(o, "peak_window_from_s", num(r->t_window));
  json_object_set_new(o, "peak_window", json_string(c->peaks == FB_PEAKS_ALL ? "all" : "steady"));
  json_object_set_new(o, "startup_window_to_s", num(r->t_startup_end));
  json_object_set_new(o, "start", json_string(fb_start_name(c->start)));
  json_object_set_new(o, "pin_start", json_string(fb_pin_start_name(c->pin_start)));
  json_object_set_new(o, "pin_start_angle_rad",
                      c->pin_start == FB_PIN_ANGLE ? num(c->pin_start_angle) : json_null());
  json_object_set_new(o, "penetration_limit_m",
                      num(fb_case_penetration_limit(c))); /* null: none */
  json_object_set_new(o, "stepper", json_string(c->solver.stepper == FB_STEPPER_WORLD
                                                    ? "dWorldStep"
                                                    : "dWorldQuickStep"));
  char injected[1024];
  json_object_set_new(o, "engine_stiffness_scale", num(c->clearance.engine_stiffness_scale));
  json_object_set_new(o, "engine_damping_scale", num(c->clearance.engine_damping_scale));
  json_object_set_new(o, "injected_error", fb_report_injected_text(injected, sizeof injected, r)
                                               ? json_string(injected)
                                               : json_null());
  json_object_set_new(o, "stackup", stackup_json(c));
  json_object_set_new(o, "masses", masses_json(c));
  json_object_set_new(o, "series",
                      json_pack("{s:s,s:i,s:s}", "format", fb_report_series_format_name(c->series), "every",
                                c->series_every, "rule", FB_SERIES_KEEP_RULE));
  json_object_set_new(o, "step", fb_report_step_json(r));
  json_object_set_new(o, "ensemble", fb_report_ensemble_run_json(r));
  json_t *an = json_object();
  const char *name[FB_MECH_MAX_OUTPUTS];
  const int nb = output_names(r, name);
  for (int b = 0; b < nb; b++)
    json_object_set_new(an, name[b], body_peaks_json(r, b, &r->analytic_nominal.body[b]));
  json_object_set_new(o, "analytic_nominal", an);
  json_t *models = json_array();
  for (int i = 0; i < r->n; i++) json_array_append_new(models, model_json(&r->model[i], r));
  json_object_set_new(o, "models", models);
  json_object_set_new(o, "published", fb_report_published_json(c));
  json_object_set_new(o, "variants", fb_report_variants_json(r));
  return o;
}

json_t *fb_report_contact_law_json(const char *joint, const fb_contact_law *law,
                                   fb_mapping mapping) {
  json_t *o = json_object();
  json_object_set_new(o, "joint", json_string(joint));
  json_object_set_new(o, "law", json_string(fb_law_name(law->kind)));
  json_object_set_new(o, "mapping", json_string(fb_mapping_name(mapping)));
  json_object_set_new(o, "stiffness", json_real(law->stiffness));
  json_object_set_new(o, "exponent", json_real(law->exponent));
  switch (law->kind) {
    case FB_LAW_IMPACT:
      json_object_set_new(o, "damping_n_s_m", json_real(law->damping));
      json_object_set_new(o, "damping_depth_m", json_real(law->damping_depth));
      break;
    case FB_LAW_RESTITUTION:
      json_object_set_new(o, "restitution", json_real(law->restitution));
      json_object_set_new(o, "damping_ratio",
                          json_real(fb_contact_law_zeta(law)));
      break;
    case FB_LAW_LINEAR: json_object_set_new(o, "damping_n_s_m", json_real(law->damping)); break;
    case FB_LAW_HERTZ: break;
    default: json_object_set_new(o, "restitution", json_real(law->restitution)); break;
  }
  return o;
}
