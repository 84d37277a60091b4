#include "report.h"

#include <jansson.h>
#include "resolution.h"

#include <math.h>
#include <stdarg.h>
#include <string.h>

#include "casefile.h"
#include "fileio.h"
#include "outcome_text.h"
#include "report_chaos.h"
#include "report_variants.h"
#include "start.h"
#include "clock.h"
#include "series_write.h"
#include "textsafe.h"
#include <stdlib.h>
#include <sys/stat.h>
#include <time.h>

/* finite number or null */
static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

json_t *fb_report_body_peaks_json(const fb_body_peaks *p) {
  json_t *o = json_object();
#define FB_JSON_PEAK(field, key) json_object_set_new(o, key, num(p->field));
  FB_BODY_PEAK_KEYS(FB_JSON_PEAK)
#undef FB_JSON_PEAK
  return o;
}

static json_t *rel_peaks_json(const fb_body_peaks *p) {
  json_t *o = json_object();
  json_object_set_new(o, "omega_max_rel", num(p->omega_max));
  json_object_set_new(o, "omega_min_rel", num(p->omega_min));
  json_object_set_new(o, "alpha_max_rel", num(p->alpha_max));
  json_object_set_new(o, "alpha_min_rel", num(p->alpha_min));
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

static json_t *lengths_json(const fb_linkage *lk) {
  json_t *o = json_object();
  for (int i = 0; i < FB_LINK_COUNT; i++)
    json_object_set_new(o, fb_link_name(i), num(lk->length[i]));
  return o;
}

static json_t *peak_at_json(const fb_peak_at *a) {
  json_t *o = json_object();
  json_object_set_new(o, "time_s", num(a->t));
  json_object_set_new(o, "crank_angle_rad", num(a->crank_angle));
  return o;
}

static json_t *body_at_json(const fb_body_peak_at *a) {
  json_t *o = json_object();
  json_object_set_new(o, "omega_max", peak_at_json(&a->omega_max));
  json_object_set_new(o, "omega_min", peak_at_json(&a->omega_min));
  json_object_set_new(o, "alpha_max", peak_at_json(&a->alpha_max));
  json_object_set_new(o, "alpha_min", peak_at_json(&a->alpha_min));
  return o;
}

/* {"from_s", "to_s", "coupler": PEAKS, "follower": PEAKS, "at": {"coupler": {"omega_max":
 * {"time_s", "crank_angle_rad"}, ...}, "follower": ...}} */
static json_t *window_json(const fb_peaks *p, const fb_peaks_at *at, double from, double to) {
  json_t *o = json_object();
  json_object_set_new(o, "from_s", num(from));
  json_object_set_new(o, "to_s", num(to));
  json_object_set_new(o, "coupler", fb_report_body_peaks_json(&p->coupler));
  json_object_set_new(o, "follower", fb_report_body_peaks_json(&p->follower));
  json_t *a = json_object();
  json_object_set_new(a, "coupler", body_at_json(&at->coupler));
  json_object_set_new(a, "follower", body_at_json(&at->follower));
  json_object_set_new(o, "at", a);
  return o;
}

/* peaks of the load columns over t >= t_from: {"drive_torque_max_n_m",
 * "drive_torque_min_n_m", "drive_torque_abs_max_n_m", "reaction_max_n":
 * {joint: largest |force|}}, or null when the model reports no loads */
static json_t *loads_json(const fb_series *s, double t_from) {
  if (!s->has_loads) return json_null();
  double tmax = -INFINITY, tmin = INFINITY, rmax[4] = {0, 0, 0, 0};
  size_t n = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->t[i] < t_from) continue;
    tmax = fmax(tmax, s->drive_torque[i]);
    tmin = fmin(tmin, s->drive_torque[i]);
    for (int j = 0; j < 4; j++) rmax[j] = fmax(rmax[j], hypot(s->reaction[j][0][i], s->reaction[j][1][i]));
    n++;
  }
  if (n == 0) return json_null();
  json_t *o = json_object(), *r = json_object();
  json_object_set_new(o, "drive_torque_max_n_m", num(tmax));
  json_object_set_new(o, "drive_torque_min_n_m", num(tmin));
  json_object_set_new(o, "drive_torque_abs_max_n_m", num(fmax(fabs(tmax), fabs(tmin))));
  for (int j = 0; j < 4; j++) {
    char key[32];
    snprintf(key, sizeof key, "%s", fb_joint_name(j));
    for (char *p = key; *p; p++)
      if (*p == '-') *p = '_';
    json_object_set_new(r, key, num(rmax[j]));
  }
  json_object_set_new(o, "reaction_max_n", r);
  return o;
}

/* the law of a clearance model's joint j as its run used it, NULL if none */
static const fb_contact_law *model_law(const fb_run *r, const fb_model_result *m, int j) {
  const fb_model *row = m->run.model;
  if (!row || row->law == FB_MODEL_LAW_NONE || !(m->run.clearance_mask & (1 << j)) ||
      !r->scene.has_law[row->law])
    return NULL;
  return &r->scene.law[row->law][j];
}

/* how model m's contact reaches its engine: ODE's mapping of the law into
 * ERP/CFM (fb_mapping_name); MuJoCo's law is a generalised force through
 * the passive-force hook and its native model MuJoCo's own solref contact,
 * neither mapped; NULL where the engine keeps no provenance (reference) */
static const char *model_mapping(const fb_run *r, const fb_model_result *m) {
  if (!m->run.has_provenance) return NULL;
  if (m->run.model->engine == FB_ENGINE_MUJOCO)
    return m->run.collider == FB_COLLIDER_NATIVE ? "none (MuJoCo contact)" : "none (applied force)";
  if (m->run.model->engine == FB_ENGINE_SIMBODY) return "none (applied force)";
  return fb_mapping_name(r->scene.mapping);
}

/* a figure of the printed tables: "-" where the engine has none (NaN) */
static const char *figure_text(char *buf, size_t size, const char *fmt, double x) {
  if (isfinite(x)) snprintf(buf, size, fmt, x);
  else snprintf(buf, size, "-");
  return buf;
}

/* summary.json's `contact`: one object per clearance joint (report.h) */
static json_t *contact_json(const fb_run *r, const fb_model_result *m) {
  json_t *arr = json_array();
  for (int j = 0; j < 4; j++) {
    const fb_contact_law *law = model_law(r, m, j);
    if (!law) continue;
    json_t *o = fb_report_contact_law_json(j, law, r->scene.mapping);
    const fb_contact_provenance *p = &m->run.provenance[j];
    const int have = m->run.has_provenance && p->contact_steps > 0;
    const char *mapping = model_mapping(r, m);
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

/* the printed contact table: what each clearance model's rows received */
/* prose, defined with the printed table below */
#define say fb_report_say

static void print_contact(FILE *f, const fb_run *r, int W) {
  int any = 0;
  for (int i = 0; i < r->n; i++)
    for (int j = 0; j < 4; j++) any |= model_law(r, &r->model[i], j) != NULL;
  if (!any) return;
  fputc('\n', f);
  say(f, "contact (per clearance joint; stiffness in N/m^n; m_eff, ERP, CFM and h omega_c = "
         "h sqrt(k / m_eff) over the run's contact steps; resolved: h omega_c <= %g):",
      FB_H_OMEGA_C_BOUND);
  for (int part = 0; part < 2; part++) {
  if (part == 0)
    fprintf(f, "%-*s %-16s %-11s %-20s %11s %4s\n", W, "model", "joint", "law", "mapping",
            "stiffness", "n");
  else
    fprintf(f, "%-*s %-16s %17s %9s %9s %9s %s\n", W, "model", "joint", "m_eff kg", "ERP max",
            "CFM min", "h omega_c", "resolved");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    for (int j = 0; j < 4; j++) {
      const fb_contact_law *law = model_law(r, m, j);
      if (!law) continue;
      const fb_contact_provenance *p = &m->run.provenance[j];
      const int have = m->run.has_provenance && p->contact_steps > 0;
      char mass[48] = "-", erp[24] = "-", cfm[24] = "-", hw[24] = "-";
      if (have) {
        if (isfinite(p->mass_eff_min) && isfinite(p->mass_eff_max))
          snprintf(mass, sizeof mass, "%.4g .. %.4g", p->mass_eff_min, p->mass_eff_max);
        figure_text(erp, sizeof erp, "%.4g", p->erp_max);
        figure_text(cfm, sizeof cfm, "%.3e", p->cfm_min);
        figure_text(hw, sizeof hw, "%.3g", p->h_omega_max);
      }
      const char *mapping = model_mapping(r, m);
      if (part == 0)
        fprintf(f, "%-*s %-16s %-11s %-20s %11.5g %4.3g\n", W, m->run.name, fb_joint_name(j),
                fb_law_name(law->kind), mapping ? mapping : "-", law->stiffness, law->exponent);
      else
        fprintf(f, "%-*s %-16s %17s %9s %9s %9s %s\n", W, m->run.name, fb_joint_name(j), mass, erp,
                cfm, hw, !have || !isfinite(p->h_omega_max) ? "-" : (p->h_omega_max <= FB_H_OMEGA_C_BOUND ? "yes" : "no: under-resolved"));
    }
  }
  }
}

static const char *model_verdict(const fb_model_result *m, const fb_run *r, char *why,
                                 size_t why_size);

static json_t *model_json(const fb_model_result *m, const fb_run *r) {
  json_t *o = json_object();
  const fb_model_run *run = &m->run;
  json_object_set_new(o, "name", json_string(run->name));
  json_object_set_new(o, "kind", json_string(fb_engine_name(run->model->engine)));
  /* how its clearance contact was found (docs/colliders.md); null without clearance joints */
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
  char stop[256];
  json_object_set_new(o, "status", json_string(fb_report_model_status(stop, sizeof stop, m)));
  char why[1024];
  json_object_set_new(o, "verdict", json_string(model_verdict(m, r, why, sizeof why)));
  const char *basis = fb_verdict_basis_name(m->basis);
  json_object_set_new(o, "verdict_basis", basis ? json_string(basis) : json_null());
  json_object_set_new(o, "verdict_reason", json_string(why));
  json_object_set_new(o, "peaks_converged", fb_report_converged_json(m));
  json_object_set_new(o, "vs_published",
                      fb_report_vs_published_json(&r->c, run->model, &m->peaks, m->has_peaks));
  json_object_set_new(o, "impact_statistics", fb_report_ensemble_json(m, r));
  json_object_set_new(o, "h_s", num(run->h));
  json_object_set_new(o, "steps", json_integer((json_int_t)run->steps));
  /* [solver] h_s = adaptive: the engine's own steps (steps above counts the
   * output grid's samples) */
  if (run->has_step_stats)
    json_object_set_new(
        o, "adaptive_steps",
        json_pack("{s:I,s:o,s:I,s:o,s:I}", "steps_taken", (json_int_t)run->step_stats.steps,
                  "h_min_s", num(run->step_stats.h_min), "h_min_count",
                  (json_int_t)run->step_stats.n_h_min, "h_max_s", num(run->step_stats.h_max),
                  "h_max_count", (json_int_t)run->step_stats.n_h_max));
  else
    json_object_set_new(o, "adaptive_steps", json_null());
  json_object_set_new(o, "lengths_m", lengths_json(&run->lengths));
  if (m->has_peaks) {
    json_object_set_new(o, "coupler", fb_report_body_peaks_json(&m->peaks.coupler));
    json_object_set_new(o, "follower", fb_report_body_peaks_json(&m->peaks.follower));
  } else {
    json_object_set_new(o, "coupler", json_null());
    json_object_set_new(o, "follower", json_null());
  }
  const fb_series *ser = &run->series;
  const double t_end = ser->n ? ser->t[ser->n - 1] : 0.0;
  if (m->has_peaks) {
    json_t *w = window_json(&m->peaks, &m->peaks_at, r->t_window, t_end);
    json_object_set_new(w, "window", json_string(r->c.peaks == FB_PEAKS_ALL ? "all" : "steady"));
    json_object_set_new(o, "peaks", w);
  } else {
    json_object_set_new(o, "peaks", json_null());
  }
  if (m->has_startup) {
    json_t *w = window_json(&m->startup, &m->startup_at, 0.0, fmin(t_end, r->t_startup_end));
    if (run->clearance_mask) {
      json_object_set_new(w, "force_max_n", num(m->startup_force_max));
      json_object_set_new(w, "penetration_max_m", num(m->startup_penetration_max));
      const fb_first_impact *fi = &m->first_impact;
      if (m->first_impact_joint >= 0 && fi->found) {
        json_t *f = json_object();
        json_object_set_new(f, "joint", json_string(fb_joint_name(m->first_impact_joint)));
        json_object_set_new(f, "time_s", num(fi->t));
        json_object_set_new(f, "speed_m_s", num(fi->speed));
        json_object_set_new(f, "crank_angle_rad", num(fi->crank_angle));
        json_object_set_new(w, "first_impact", f);
      } else {
        json_object_set_new(w, "first_impact", json_null());
      }
    }
    json_object_set_new(o, "startup", w);
  } else {
    json_object_set_new(o, "startup", json_null());
  }
  json_object_set_new(o, "penetration_max_m", run->clearance_mask ? num(m->penetration_max_run)
                                                                  : json_null());
  json_t *warnings = json_array();
  char wt[512];
  for (int k = 0; k < m->warning_count; k++)
    json_array_append_new(warnings, json_string(fb_warning_text(wt, sizeof wt, &m->warnings[k])));
  json_object_set_new(o, "warnings", warnings);
  if (m->has_error) {
    json_t *e = json_object();
    json_object_set_new(e, "reference",
                        json_string(run->model->engine != FB_ENGINE_ANALYTIC
                                        ? "analytic solution of the same link lengths"
                                        : "exact (refined) peaks of the same solution: the "
                                          "sampling floor of the time grid"));
    json_object_set_new(e, "coupler", body_error_json(&m->error.coupler));
    json_object_set_new(e, "follower", body_error_json(&m->error.follower));
    json_object_set_new(e, "crank_angle_err_max_rad", num(m->error.crank_angle_err_max));
    json_object_set_new(o, "error_vs_analytic", e);
  } else {
    json_object_set_new(o, "error_vs_analytic", json_null());
  }
  if (m->has_peaks) {
    json_t *d = json_object();
    json_object_set_new(d, "coupler", rel_peaks_json(&m->delta_vs_nominal.coupler));
    json_object_set_new(d, "follower", rel_peaks_json(&m->delta_vs_nominal.follower));
    json_object_set_new(o, "delta_vs_analytic_nominal", d);
  } else {
    json_object_set_new(o, "delta_vs_analytic_nominal", json_null());
  }
  if (fb_engine_steps_world(run->model->engine)) json_object_set_new(o, "joint_drift_max_m", num(run->joint_drift_max));
  json_object_set_new(o, "loads", loads_json(&run->series, r->t_window));
  if (run->model->engine == FB_ENGINE_MUJOCO) {
    /* MuJoCo's own choices as the model used them (0 in the case: 1/h^2, 1/h) */
    const fb_mujoco_opts *mj = &r->c.mujoco;
    const int integ = fb_mujoco_integrator_resolve(mj, run->clearance_mask);
    json_object_set_new(
        o, "mujoco",
        json_pack("{s:s,s:o,s:o,s:o,s:o}", "integrator", fb_mujoco_integrator_name(integ),
                  "loop_stiffness_1_s2",
                  num(mj->loop_stiffness > 0.0 ? mj->loop_stiffness : 1.0 / (run->h * run->h)),
                  "loop_damping_1_s", num(mj->loop_damping > 0.0 ? mj->loop_damping : 1.0 / run->h),
                  "loop_impedance", num(mj->loop_impedance), "drive_armature_kg_m2",
                  num(mj->drive_armature)));
    if (run->collider == FB_COLLIDER_NATIVE)
      json_object_set_new(json_object_get(o, "mujoco"), "native_bore",
                          json_string(fb_mujoco_bore_name(mj->native_bore)));
  }
  if (run->model->engine == FB_ENGINE_BULLET) {
    /* Bullet's own choices as the model used them */
    const fb_bullet_opts *bt = &r->c.bullet;
    json_object_set_new(o, "bullet",
                        json_pack("{s:s,s:i,s:s}", "solver", fb_bullet_solver_name(bt->solver),
                                  "iterations", bt->iterations, "world", "btDiscreteDynamicsWorld"));
  }
  if (run->model->engine == FB_ENGINE_SIMBODY)
    json_object_set_new(o, "simbody",
                        json_pack("{s:s,s:o}", "integrator",
                                  fb_simbody_integrator_name(r->c.simbody.integrator), "accuracy",
                                  num(r->c.simbody.accuracy)));
  if (m->has_ref_error) {
    const fb_reference_error *e = &m->ref_error;
    json_t *o2 = json_object(), *a = json_array(), *b = json_array();
    json_object_set_new(o2, "reference", json_string(m->ref_name));
    json_object_set_new(o2, "coupler", body_error_json(&e->coupler));
    json_object_set_new(o2, "follower", body_error_json(&e->follower));
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
    json_object_set_new(o, "error_vs_reference", o2);
  }
  if (m->has_divergence) {
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
    json_object_set_new(o, "divergence", dv);
  }
  if (m->has_ref_estimate) {
    /* the reference against its own integration at a tighter tolerance */
    const fb_reference_error *e = &m->ref_estimate;
    json_t *o3 = json_object();
    json_object_set_new(o3, "tolerance", num(m->ref_tol));
    json_object_set_new(o3, "check_tolerance", num(m->ref_check_tol));
    json_object_set_new(o3, "check_steps", json_integer((json_int_t)m->ref_check_steps));
    json_object_set_new(o3, "coupler", body_error_json(&e->coupler));
    json_object_set_new(o3, "follower", body_error_json(&e->follower));
    json_object_set_new(o3, "force_max_rel", num(e->force_max_rel));
    json_object_set_new(o3, "force_err_rms_n", num(e->force_err_rms));
    json_object_set_new(o3, "penetration_max_rel", num(e->penetration_max_rel));
    json_object_set_new(o3, "impacts", json_integer(e->impacts));
    json_object_set_new(o3, "impacts_check", json_integer(e->impacts_reference));
    fb_report_check_json(o3, m);
    json_object_set_new(o, "error_estimate", o3);
  }
  if (m->has_spikes) {
    const fb_spikes *k = &m->spikes;
    json_t *sp = json_object();
    /* counts as JSON integers, the rest as numbers (null when not finite) */
#define FB_JSON_SPIKE(field, key)                                                         \
  json_object_set_new(sp, key, _Generic((k->field), int: json_integer((json_int_t)(k->field)), \
                                        default: num((double)(k->field))));
    FB_SPIKE_KEYS(FB_JSON_SPIKE)
#undef FB_JSON_SPIKE
    json_object_set_new(sp, "alpha_reference", json_string(m->spikes_reference));
    json_object_set_new(o, "spikes", sp);
    json_t *joints = json_array();
    for (int j = 0; j < 4; j++)
      if (run->clearance_mask & (1 << j)) json_array_append_new(joints, json_string(fb_joint_name(j)));
    json_object_set_new(o, "clearance_joints", joints);
  } else {
    json_object_set_new(o, "spikes", json_null());
  }
  /* what the contact rows received, also for a run that stopped early */
  if (run->clearance_mask) json_object_set_new(o, "contact", contact_json(r, m));
  return o;
}


static json_t *stackup_json(const fb_case *c) {
  json_t *o = json_object();
  char corner[FB_LINK_COUNT + 1];
  for (int k = 0; k < FB_LINK_COUNT; k++) corner[k] = "-0+"[c->stackup.corner[k] + 1];
  corner[FB_LINK_COUNT] = '\0';
  json_object_set_new(o, "corner", json_string(corner));
  json_t *links = json_array();
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  for (int k = 0; k < FB_LINK_COUNT; k++) {
    json_t *l = json_object();
    json_object_set_new(l, "link", json_string(fb_link_name(k)));
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
    snprintf(kw, sizeof kw, "%s_width_mm", fb_link_name(i));
    snprintf(kt, sizeof kt, "%s_thickness_mm", fb_link_name(i));
    json_t *l = json_object();
    json_object_set_new(l, "link", json_string(fb_link_name(i)));
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

static const char *series_format_name(fb_series_format f) {
  return f == FB_SERIES_HDF5 ? "hdf5" : f == FB_SERIES_NONE ? "none" : "csv";
}

json_t *fb_report_summary_json(const fb_run *r, const char *case_path) {
  const fb_case *c = &r->c;
  json_t *o = json_object();
  json_object_set_new(o, "case", json_string(c->name));
  json_object_set_new(o, "case_file", case_path ? json_string(case_path) : json_null());
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
  json_object_set_new(o, "stackup", stackup_json(c));
  json_object_set_new(o, "masses", masses_json(c));
  json_object_set_new(o, "series",
                      json_pack("{s:s,s:i,s:s}", "format", series_format_name(c->series), "every",
                                c->series_every, "rule", FB_SERIES_KEEP_RULE));
  json_object_set_new(o, "step", fb_report_step_json(r));
  json_object_set_new(o, "ensemble", fb_report_ensemble_run_json(r));
  json_t *an = json_object();
  json_object_set_new(an, "coupler", fb_report_body_peaks_json(&r->analytic_nominal.coupler));
  json_object_set_new(an, "follower", fb_report_body_peaks_json(&r->analytic_nominal.follower));
  json_object_set_new(o, "analytic_nominal", an);
  json_t *models = json_array();
  for (int i = 0; i < r->n; i++) json_array_append_new(models, model_json(&r->model[i], r));
  json_object_set_new(o, "models", models);
  json_object_set_new(o, "published", fb_report_published_json(c));
  json_object_set_new(o, "variants", fb_report_variants_json(r));
  return o;
}

json_t *fb_report_timing_json(const fb_run *r) {
  json_t *models = json_array();
  for (int i = 0; i < r->n; i++) {
    const fb_model_run *run = &r->model[i].run;
    json_array_append_new(models, json_pack("{s:s,s:I,s:o,s:o,s:o,s:o}", "name", run->name, "steps",
                                            (json_int_t)run->steps, "wall_s", num(run->wall_s),
                                            "setup_s", num(run->setup_s), "time_per_step_us",
                                            run->steps ? num(1e6 * run->wall_s / (double)run->steps)
                                                       : json_null(),
                                            "stepping_s", num(run->stepping_s)));
  }
  /* the ensemble's members beyond the first (docs/chaos.md): its cost */
  json_t *ens = json_pack("{s:i,s:s,s:o,s:o,s:o}", "members", r->c.ensemble > 1 ? r->c.ensemble : 1,
                          "source", r->ensemble_auto > 1 ? "run" : r->c.ensemble > 1 ? "case" : "none",
                          "wall_s", num(r->ensemble_wall_s), "models_wall_s", num(r->models_wall_s),
                          "estimate_s", r->ensemble_auto > 1 || r->ensemble_auto_skipped
                                            ? num(r->ensemble_estimate_s)
                                            : json_null());
  return json_pack("{s:s,s:o,s:o}", "case", r->c.name, "models", models, "ensemble", ens);
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

/* bytes of the file at path (0 when it cannot be read) */
static double file_bytes(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0 ? (double)sb.st_size : 0.0;
}

/* the time series in the case's format ([run] series, series_every); the
 * wall time and bytes written go to *write_s and *bytes */
/* CPU time of this process [s] (the writer's cost without the waits of a
 * busy machine or of the disk) */
static double cpu_s(void) {
  struct timespec ts;
  return clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) == 0 ? (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec
                                                           : 0.0;
}

static fb_status write_series(const char *dir, const fb_run *r, const char *case_path,
                              double *write_s, double *cpu, double *bytes, fb_diag *diag) {
  char path[4096];
  const fb_case *c = &r->c;
  *write_s = 0.0;
  *cpu = 0.0;
  *bytes = 0.0;
  if (c->series == FB_SERIES_NONE) return FB_OK;
  const double t0 = fb_clock_s(), c0 = cpu_s();
  unsigned char *keep[FB_MAX_MODELS] = {0};
  fb_status st = FB_OK;
  if (c->series_every > 1)
    for (int i = 0; i < r->n && st == FB_OK; i++) {
      const fb_series *s = &r->model[i].run.series;
      keep[i] = malloc(s->n ? s->n : 1);
      if (!keep[i]) st = fb_diag_set(diag, FB_ERR_NOMEM, "series selection: out of memory");
      else fb_series_keep(s, c->series_every, keep[i]);
    }
  if (st == FB_OK && c->series == FB_SERIES_HDF5) {
    snprintf(path, sizeof path, "%s/series.h5", dir);
    json_t *j = fb_report_summary_json(r, case_path);
    char *text = json_dumps(j, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    json_decref(j);
    st = fb_series_write_hdf5(path, r, keep, text, diag);
    free(text);
    *bytes = file_bytes(path);
  }
  if (c->series == FB_SERIES_CSV)
    for (int i = 0; i < r->n && st == FB_OK; i++) {
      snprintf(path, sizeof path, "%s/%s.csv", dir, r->model[i].run.name);
      st = fb_series_write_csv(path, &r->model[i].run.series, keep[i], diag);
      *bytes += file_bytes(path);
    }
  for (int i = 0; i < r->n; i++) free(keep[i]);
  *write_s = fb_clock_s() - t0;
  *cpu = cpu_s() - c0;
  return st;
}

fb_status fb_report_write_run(const char *dir, const fb_run *r, const char *case_path,
                              fb_diag *diag) {
  char path[4096];
  double write_s, write_cpu_s, bytes;
  fb_status st = write_series(dir, r, case_path, &write_s, &write_cpu_s, &bytes, diag);
  if (st != FB_OK) return st;
  snprintf(path, sizeof path, "%s/summary.json", dir);
  json_t *j = fb_report_summary_json(r, case_path);
  st = fb_report_write_json(path, j, diag);
  json_decref(j);
  if (st != FB_OK) return st;
  snprintf(path, sizeof path, "%s/timing.json", dir);
  j = fb_report_timing_json(r);
  json_object_set_new(j, "series_write_s", json_real(write_s));
  json_object_set_new(j, "series_write_cpu_s", json_real(write_cpu_s));
  json_object_set_new(j, "series_bytes", json_integer((json_int_t)bytes));
  st = fb_report_write_json(path, j, diag);
  json_decref(j);
  return st;
}

static double worst_rel(const fb_body_error *a, const fb_body_error *b, int alpha) {
  double v[4] = {alpha ? a->alpha_max_rel : a->omega_max_rel,
                 alpha ? a->alpha_min_rel : a->omega_min_rel,
                 alpha ? b->alpha_max_rel : b->omega_max_rel,
                 alpha ? b->alpha_min_rel : b->omega_min_rel};
  double w = 0.0;
  for (int i = 0; i < 4; i++)
    if (fabs(v[i]) > w) w = fabs(v[i]);
  return w;
}

/* Every printed line is at most this wide (a terminal of 120 columns shows
 * the table without wrapping; issue 30). Prose is wrapped to it; tables
 * size their model column to the longest model name of the run. */
#define FB_TABLE_COLUMNS 120

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

/* width of the model column: the longest model name of the run */
static int model_width(const fb_run *r) {
  int w = 5; /* "model" */
  for (int i = 0; i < r->n; i++) {
    const int n = (int)strlen(r->model[i].run.name);
    if (n > w) w = n;
  }
  return w;
}

/* each clearance model against its reference: where it leaves it and the
 * impacts matched one to one before */
static void print_divergence(FILE *f, const fb_run *r, int W) {
  int any = 0;
  for (int i = 0; i < r->n; i++) any |= r->model[i].has_divergence;
  if (!any) return;
  fputc('\n', f);
  say(f, "divergence from the reference (pin eccentricity beyond %g x clearance or coupler "
         "angle beyond %g x clearance / coupler length):",
      FB_DIVERGE_ECC_FRACTION, FB_DIVERGE_ANGLE_FRACTION);
  fprintf(f, "%-*s %12s %9s %15s %9s %9s\n", W, "model", "leaves at", "crank", "impacts before",
          "force", "penetr.");
  fprintf(f, "%-*s %12s %9s %15s %9s %9s\n", W, "", "ms", "deg", "model/ref/match", "err max",
          "err max");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    if (!m->has_divergence) continue;
    const fb_divergence *d = &m->divergence;
    char at[32], ang[32], counts[48];
    if (d->diverged) {
      snprintf(at, sizeof at, "%.4f", d->t * 1e3);
      snprintf(ang, sizeof ang, "%.1f", d->crank_angle * 180.0 / M_PI);
    } else {
      snprintf(at, sizeof at, "beyond run");
      snprintf(ang, sizeof ang, "-");
    }
    snprintf(counts, sizeof counts, "%d/%d/%d%s", d->impacts_model, d->impacts_reference,
             d->matched, d->one_to_one ? "" : "*");
    fprintf(f, "%-*s %12s %9s %15s %9.2e %9.2e\n", W, m->run.name, at, ang, counts,
            d->force_rel_max, d->penetration_rel_max);
  }
  say(f, "(* not one to one: an impact before the divergence has no partner; err max: "
         "largest |relative error| of the matched impacts' peak force and penetration, "
         "bound %g)", FB_MATCHED_IMPACT_ERROR_BOUND);
}

/* the start-up of the clearance models (first impact's time, speed and
 * crank angle; revolution 1's largest coupler |alpha|, when, peak force and
 * penetration) */
static void print_startup(FILE *f, const fb_run *r, int W) {
  int any = 0;
  for (int i = 0; i < r->n; i++) any |= r->model[i].has_startup && r->model[i].run.clearance_mask;
  if (!any) return;
  fputc('\n', f);
  say(f, "start-up (revolution 1, t < %.6g s; start = %s, pin %s):", r->t_startup_end,
      fb_start_name(r->c.start), fb_pin_start_name(r->c.pin_start));
  fprintf(f, "%-*s %12s %10s %10s %14s %10s %12s %10s\n", W, "model", "1st impact", "speed",
          "crank", "cpl alpha pk", "at t", "force max", "penetr.");
  fprintf(f, "%-*s %12s %10s %10s %14s %10s %12s %10s\n", W, "", "us", "m/s", "deg", "rad/s^2",
          "ms", "N", "um");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    if (!m->has_startup || !m->run.clearance_mask) continue;
    const fb_body_peaks *c = &m->startup.coupler;
    const fb_body_peak_at *a = &m->startup_at.coupler;
    const int hi = fabs(c->alpha_max) >= fabs(c->alpha_min);
    fprintf(f, "%-*s ", W, m->run.name);
    if (m->first_impact.found)
      fprintf(f, "%12.4f %10.4f %10.3f ", m->first_impact.t * 1e6, m->first_impact.speed,
              m->first_impact.crank_angle * 180.0 / M_PI);
    else
      fprintf(f, "%12s %10s %10s ", "none", "-", "-");
    fprintf(f, "%14.4g %10.4f %12.4g %10.4g\n", hi ? c->alpha_max : c->alpha_min,
            (hi ? a->alpha_max.t : a->alpha_min.t) * 1e3, m->startup_force_max,
            m->startup_penetration_max * 1e6);
  }
}

static void print_warnings(FILE *f, const fb_run *r) {
  int warned = 0;
  for (int i = 0; i < r->n; i++) warned |= r->model[i].warning_count > 0;
  if (!warned) return;
  char wt[512];
  fprintf(f, "\nwarnings:\n");
  for (int i = 0; i < r->n; i++)
    for (int k = 0; k < r->model[i].warning_count; k++)
      say(f, "  %s: %s", r->model[i].run.name, fb_warning_text(wt, sizeof wt, &r->model[i].warnings[k]));
}

/* one line per model, first: ok or warn, its error against its yardstick,
 * and its impacts */
/* the printed verdict of a model and what it rests on (verdict.h); why
 * gets the reason printed beside it (report_chaos.h) */
static const char *model_verdict(const fb_model_result *m, const fb_run *r, char *why,
                                 size_t why_size) {
  fb_report_verdict_why(why, why_size, m, r);
  return fb_verdict_name(m->verdict);
}

static void print_verdict(FILE *f, const fb_run *r, int W) {
  say(f, "verdict (ok: ran to its end with no warning and an error within its bound; warn: a "
         "warning, a stop, or a yardstick that does not settle it (the reason beside it, warnings "
         "below); error: a clearance model that keeps its reference's trajectory but misses its "
         "matched impacts' bound; unchecked: nothing in the run to measure it against. basis: "
         "pointwise (it stays with its yardstick, peaks compared), statistics (its trajectory "
         "parted, or its yardstick's peaks did not converge: an ensemble's impact statistics "
         "decide), unsettled (the same, with no ensemble). error column: largest relative peak "
         "error of an ideal model against the exact analytic peaks of its own lengths (bound %g), "
         "of a clearance model against its reference of the same law (omega, alpha and force "
         "peaks; on statistics, of its pooled impact statistics), of a reference against its "
         "check integration):",
      FB_IDEAL_PEAK_ERROR_BOUND);
  fprintf(f, "%-*s %-9s %-10s %9s  %-28s %11s\n", W, "model", "verdict", "basis", "error",
          "against", "impacts");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    char err[32] = "-", against[64] = "-", impacts[32] = "-", why[1024] = "";
    if (fb_report_verdict_error(err, sizeof err, against, sizeof against, m)) {
    } else if (!m->run.clearance_mask && m->has_error) {
      const double e = fmax(worst_rel(&m->error.coupler, &m->error.follower, 0),
                            worst_rel(&m->error.coupler, &m->error.follower, 1));
      snprintf(err, sizeof err, "%.2e", e);
      snprintf(against, sizeof against, "%s",
               m->run.model->engine == FB_ENGINE_ANALYTIC ? "exact peaks (sampling floor)"
                                                          : "exact analytic peaks");
    } else if (m->run.clearance_mask) {
      snprintf(against, sizeof against, "no reference in this run");
    }
    if (m->has_spikes) {
      if (m->has_ref_error)
        snprintf(impacts, sizeof impacts, "%d (ref %d)", m->spikes.impacts, m->ref_error.impacts_reference);
      else
        snprintf(impacts, sizeof impacts, "%d", m->spikes.impacts);
    }
    const char *verdict = model_verdict(m, r, why, sizeof why);
    const char *basis = fb_verdict_basis_name(m->basis);
    char line[1400];
    const int n = snprintf(line, sizeof line, "%-*s %-9s %-10s %9s  %-28s %11s", W, m->run.name,
                           verdict, basis ? basis : "-", err, against, impacts);
    /* the reason beside the row when it fits, else on lines of its own under it */
    if (why[0] && (size_t)n + 2 + strlen(why) <= FB_TABLE_COLUMNS)
      fprintf(f, "%s  %s\n", line, why);
    else if (why[0])
      fprintf(f, "%s\n", line), say(f, "  %s", why);
    else
      fprintf(f, "%s\n", line);
  }
  fb_report_print_ensemble_auto(f, r);
}

/* the run's peaks (the paper's table): coupler and follower omega and alpha
 * extremes, one row per model */
static void print_peaks(FILE *f, const fb_run *r, int W) {
  const int all = r->c.peaks == FB_PEAKS_ALL;
  fputc('\n', f);
  say(f, "peaks (the paper's table) over %s:",
      all ? "the whole run from t = 0 (start-up included; [run] peaks = all)"
          : "the revolutions after the first ([run] peaks = steady)");
  fprintf(f, "%-*s %-40s %s\n", W, "", "coupler omega / alpha", "follower omega / alpha");
  fprintf(f, "%-*s %9s %9s %10s %10s %9s %9s %10s %10s\n", W, "model", "max", "min", "max", "min",
          "max", "min", "max", "min");
  fprintf(f, "%-*s %9s %9s %10s %10s %9s %9s %10s %10s\n", W, "", "rad/s", "rad/s", "rad/s^2",
          "rad/s^2", "rad/s", "rad/s", "rad/s^2", "rad/s^2");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    char stop[256];
    fprintf(f, "%-*s", W, m->run.name);
    if (m->has_peaks) {
      const fb_body_peaks *p[2] = {&m->peaks.coupler, &m->peaks.follower};
      const int u = m->peaks_unconverged; /* marked "~", 3 figures (report_chaos.h) */
      char c0[24], c1[24], c2[24], c3[24];
      for (int b = 0; b < 2; b++)
        fprintf(f, " %9s %9s %10s %10s", fb_report_figure(c0, sizeof c0, "%.4f", p[b]->omega_max, u),
                fb_report_figure(c1, sizeof c1, "%.4f", p[b]->omega_min, u),
                fb_report_figure(c2, sizeof c2, "%.2f", p[b]->alpha_max, u),
                fb_report_figure(c3, sizeof c3, "%.2f", p[b]->alpha_min, u));
      fputc('\n', f);
    } else {
      fprintf(f, " (no peaks: %.60s)\n", fb_stop_text(stop, sizeof stop, &m->run.stop));
    }
  }
}

/* per model: its peaks against the exact analytic peaks of its own lengths
 * (an error for ideal models, the clearance effect for clearance models),
 * and its cost */
static void print_cost(FILE *f, const fb_run *r, int W) {
  fputc('\n', f);
  say(f, "against the exact analytic peaks of the same lengths (largest |relative difference| of "
         "the four omega, or alpha, peaks): an error for an ideal model (for analytic ones the "
         "sampling floor of the time grid), the clearance effect for a clearance model; and cost:");
  fprintf(f, "%-*s %9s %9s  %-16s %9s %9s %8s\n", W, "model", "omega", "alpha", "meaning", "steps",
          "wall", "per step");
  fprintf(f, "%-*s %9s %9s  %-16s %9s %9s %8s\n", W, "", "rel", "rel", "", "", "s", "us");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    fprintf(f, "%-*s ", W, m->run.name);
    if (m->has_error)
      fprintf(f, "%9.2e %9.2e  %-16s ", worst_rel(&m->error.coupler, &m->error.follower, 0),
              worst_rel(&m->error.coupler, &m->error.follower, 1),
              m->run.clearance_mask ? "clearance effect" : "error");
    else
      fprintf(f, "%9s %9s  %-16s ", "-", "-", "-");
    fprintf(f, "%9zu %9.3f %8.2f\n", m->run.steps, m->run.wall_s,
            m->run.steps ? 1e6 * m->run.wall_s / (double)m->run.steps : 0.0);
  }
}

/* "case", or "derived" / "default" with the bar when a field was not given */
static const char *mass_sources(char *buf, size_t size, const fb_link_mass_source *s) {
  const int v[4] = {s->mass, s->inertia, s->inertia_long, s->inertia_transverse};
  const int same = v[0] == v[1] && v[1] == v[2] && v[2] == v[3];
  if (same)
    snprintf(buf, size, "%s", fb_value_source_name(v[0]));
  else
    snprintf(buf, size, "m %s, I %s, I_long %s, I_tr %s", fb_value_source_name(v[0]),
             fb_value_source_name(v[1]), fb_value_source_name(v[2]), fb_value_source_name(v[3]));
  return buf;
}

/* the run header's masses: one line per link, every mass and hinge-axis
 * inertia, with sources */
static void print_masses(FILE *f, const fb_case *c) {
  int derived = 0;
  for (int i = 0; i < 3; i++) {
    const fb_link_mass *m = &c->link[i];
    const fb_link_mass_source *s = &c->link_source[i];
    char src[128];
    derived |= s->mass == FB_SOURCE_DERIVED || s->inertia == FB_SOURCE_DERIVED ||
               s->inertia_long == FB_SOURCE_DERIVED || s->inertia_transverse == FB_SOURCE_DERIVED;
    say(f, "%s%s %.5g kg, I %.5g kg mm^2, centre of mass at %.3g (%s%s)",
        i ? "             " : "link masses: ", fb_link_name(i), m->mass, m->inertia * 1e6,
        m->com_fraction, mass_sources(src, sizeof src, s),
        s->com_fraction == FB_SOURCE_CASE ? "" : ", centre default");
  }
  if (derived)
    say(f, "derived from bars (width x thickness, mm) crank %.4g x %.4g, coupler %.4g x "
           "%.4g, follower %.4g x %.4g, density %.6g kg/m^3 (docs/keys.md)",
        c->link_width[0] * 1e3, c->link_thickness[0] * 1e3, c->link_width[1] * 1e3,
        c->link_thickness[1] * 1e3, c->link_width[2] * 1e3, c->link_thickness[2] * 1e3,
        c->density);
}

void fb_report_print_table(FILE *f, const fb_run *r) {
  const fb_case *c = &r->c;
  const int W = model_width(r);
  say(f, "case %s: %.6g rpm %s, %s branch, %g revolution%s, h = %g s (%s); "
         "peaks over t >= %.6g s (%s); start %s, pin %s",
      c->name, c->crank_speed * 60.0 / (2.0 * M_PI), c->direction > 0 ? "ccw" : "cw",
      c->branch == FB_BRANCH_OPEN ? "open" : "crossed", c->revolutions,
      c->revolutions == 1 ? "" : "s", c->solver.h,
      c->solver.stepper == FB_STEPPER_WORLD ? "dWorldStep" : "dWorldQuickStep", r->t_window,
      c->peaks == FB_PEAKS_ALL ? "the whole run" : "after the first revolution",
      fb_start_name(c->start), fb_pin_start_name(c->pin_start));
  char grashof[1024];
  fb_case_grashof_text(c, grashof, sizeof grashof);
  say(f, "linkage: %s", grashof);
  fputc('\n', f);
  /* one screen first: the verdict per model */
  print_verdict(f, r, W);
  fputc('\n', f);
  int mj_ideal = 0, mj_clear = 0, mj_native = 0;
  for (int i = 0; i < r->n; i++)
    if (r->model[i].run.model->engine == FB_ENGINE_MUJOCO) {
      if (r->model[i].run.clearance_mask) mj_clear = 1;
      else mj_ideal = 1;
      if (r->model[i].run.collider == FB_COLLIDER_NATIVE) mj_native = 1;
    }
  if (mj_ideal || mj_clear)
    say(f, "MuJoCo models: integrator %s%s%s%s%s; loop closure solref (-k, -b) with k = %g "
           "1/s^2, b = %g 1/s, solimp %g",
        mj_ideal ? fb_mujoco_integrator_name(fb_mujoco_integrator_resolve(&c->mujoco, 0)) : "",
        mj_ideal ? " (ideal models)" : "", mj_ideal && mj_clear ? ", " : "",
        mj_clear ? fb_mujoco_integrator_name(fb_mujoco_integrator_resolve(&c->mujoco, 1)) : "",
        mj_clear ? " (clearance models)" : "",
        c->mujoco.loop_stiffness > 0 ? c->mujoco.loop_stiffness : 1.0 / (c->solver.h * c->solver.h),
        c->mujoco.loop_damping > 0 ? c->mujoco.loop_damping : 1.0 / c->solver.h,
        c->mujoco.loop_impedance);
  if (mj_native)
    say(f, "mujoco-clearance-native: bore %s ([mujoco] native_bore; %s)",
        fb_mujoco_bore_name(c->mujoco.native_bore),
        c->mujoco.native_bore == FB_MUJOCO_BORE_FACETS
            ? "a sphere pin in a ring of boxes, MuJoCo's contacts"
            : "a tendon limited to the radial clearance, MuJoCo's limit row along the "
              "eccentricity");
  int bt_models = 0;
  for (int i = 0; i < r->n; i++) bt_models |= r->model[i].run.model->engine == FB_ENGINE_BULLET;
  if (bt_models)
    say(f, "Bullet models: %s, %d iterations (sequential impulse; the MLCP's fallback)",
        fb_bullet_solver_name(c->bullet.solver), c->bullet.iterations);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].run.model->engine == FB_ENGINE_SIMBODY) {
      say(f, "Simbody models: integrator %s, accuracy %g (error-controlled internal steps, "
             "sampled every h)",
          fb_simbody_integrator_name(c->simbody.integrator), c->simbody.accuracy);
      break;
    }
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  char corner[24];
  snprintf(corner, sizeof corner, "stack-up corner %c%c%c%c:", "-0+"[c->stackup.corner[0] + 1],
           "-0+"[c->stackup.corner[1] + 1], "-0+"[c->stackup.corner[2] + 1],
           "-0+"[c->stackup.corner[3] + 1]);
  for (int k = 0; k < FB_LINK_COUNT; k++)
    say(f, "%-20s %s %.4g +- %.3g -> %.4g mm (%s)", k ? "" : corner, fb_link_name(k),
        c->nominal.length[k] * 1e3, c->plus_minus[k] * 1e3, su.length[k] * 1e3,
        c->tolerance_source[k]);
  say(f, "clearance joints: pin %.4g mm, radial clearance %.4g um (%s)", c->pin_diameter * 1e3,
      c->radial_clearance * 1e6, c->clearance_source);
  print_masses(f, c);
  print_peaks(f, r, W);
  fb_report_print_variants(f, r, W);
  print_cost(f, r, W);
  int any = 0;
  for (int i = 0; i < r->n; i++) any |= r->model[i].has_spikes;
  if (any) {
    fputc('\n', f);
    say(f, "spikes (clearance models; ratios of peak |alpha| to the ideal stack-up model):");
    fprintf(f, "%-*s %9s %9s %10s %9s %9s %7s %8s %9s %9s\n", W, "model", "alpha/id", "alpha/id",
            "omega dev", "force", "penetr.", "impacts", "free", "spike at", "spike at");
    fprintf(f, "%-*s %9s %9s %10s %9s %9s %7s %8s %9s %9s\n", W, "", "coupler", "follower",
            "rad/s", "N", "um", "", "fraction", "cpl deg", "flw deg");
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      if (!m->has_spikes) continue;
      const fb_spikes *k = &m->spikes;
      const int u = m->peaks_unconverged; /* marked "~", 3 figures (report_chaos.h) */
      char c0[24], c1[24], c2[24], c3[24];
      fprintf(f, "%-*s %9s %9s %10.4f %9s %9s %7d %8.4f %9.1f %9.1f\n", W, m->run.name,
              fb_report_figure(c0, sizeof c0, "%.3f", k->alpha_peak_ratio_coupler, u),
              fb_report_figure(c1, sizeof c1, "%.3f", k->alpha_peak_ratio_follower, u),
              k->omega_dev_max, fb_report_figure(c2, sizeof c2, "%.1f", k->force_max, u),
              fb_report_figure(c3, sizeof c3, "%.4f", k->penetration_max * 1e6, u), k->impacts,
              k->free_flight_fraction,
              k->alpha_peak_crank_angle_coupler * 180.0 / M_PI,
              k->alpha_peak_crank_angle_follower * 180.0 / M_PI);
    }
  }
  int anyload = 0;
  for (int i = 0; i < r->n; i++) anyload |= r->model[i].run.series.has_loads;
  if (anyload) {
    fputc('\n', f);
    say(f, "loads (peaks over %s; reaction: force on the second-named body):",
        c->peaks == FB_PEAKS_ALL ? "the whole run" : "the revolutions after the first");
    fprintf(f, "%-*s %10s %10s %12s %12s %12s %12s\n%-*s %10s %10s %12s %12s %12s %12s\n", W,
            "model", "torque max", "torque min", "|R| ground-", "|R| crank-", "|R| coupler-",
            "|R| follower-", W, "", "N m", "N m", "crank N", "coupler N", "follower N", "ground N");
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      json_t *l = loads_json(&m->run.series, r->t_window);
      if (json_is_object(l)) {
        json_t *rm = json_object_get(l, "reaction_max_n");
        fprintf(f, "%-*s %10.3f %10.3f %12.2f %12.2f %12.2f %12.2f\n", W, m->run.name,
                json_real_value(json_object_get(l, "drive_torque_max_n_m")),
                json_real_value(json_object_get(l, "drive_torque_min_n_m")),
                json_real_value(json_object_get(rm, "ground_crank")),
                json_real_value(json_object_get(rm, "crank_coupler")),
                json_real_value(json_object_get(rm, "coupler_follower")),
                json_real_value(json_object_get(rm, "follower_ground")));
      }
      json_decref(l);
    }
  }
  int anyref = 0;
  for (int i = 0; i < r->n; i++) anyref |= r->model[i].has_ref_error;
  if (anyref) {
    fputc('\n', f);
    say(f, "against the reference (same law, same instants; the reference of each model is named "
           "in the verdict):");
    fprintf(f, "%-*s %9s %9s %9s %9s %9s %9s %9s\n", W, "model", "omega pk", "omega rms",
            "alpha pk", "alpha rms", "force pk", "penetr.", "impacts");
    fprintf(f, "%-*s %9s %9s %9s %9s %9s %9s %9s\n", W, "", "rel", "rad/s", "rel", "rad/s^2", "rel",
            "rel", "model/ref");
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      if (!m->has_ref_error) continue;
      const fb_reference_error *e = &m->ref_error;
      char counts[32];
      snprintf(counts, sizeof counts, "%d/%d", e->impacts, e->impacts_reference);
      /* a divergent model's peaks compare two histories: marked (report_chaos.h) */
      const int u = m->peaks_unconverged;
      char c0[24], c1[24], c2[24], c3[24];
      fprintf(f, "%-*s %9s %9.3g %9s %9.4g %9s %9s %9s\n", W, m->run.name,
              fb_report_figure(c0, sizeof c0, "%.2e", worst_rel(&e->coupler, &e->follower, 0), u),
              fmax(e->coupler.omega_err_rms, e->follower.omega_err_rms),
              fb_report_figure(c1, sizeof c1, "%.2e", worst_rel(&e->coupler, &e->follower, 1), u),
              fmax(e->coupler.alpha_err_rms, e->follower.alpha_err_rms),
              fb_report_figure(c2, sizeof c2, "%+.2e", e->force_max_rel, u),
              fb_report_figure(c3, sizeof c3, "%+.2e", e->penetration_max_rel, u), counts);
    }
  }
  print_contact(f, r, W);
  print_startup(f, r, W);
  print_divergence(f, r, W);
  fb_report_print_chaos(f, r);
  print_warnings(f, r);
}

/* 1 when a mass or an inertia of some link was derived from its bar */
static int any_derived(const fb_case *c) {
  for (int i = 0; i < 3; i++) {
    const fb_link_mass_source *s = &c->link_source[i];
    if (s->mass == FB_SOURCE_DERIVED || s->inertia == FB_SOURCE_DERIVED ||
        s->inertia_long == FB_SOURCE_DERIVED || s->inertia_transverse == FB_SOURCE_DERIVED)
      return 1;
  }
  return 0;
}

/* "case" when the case set any of the keys of section (a NULL-terminated
 * list), else "default" */
static const char *given_src(const fb_case *c, const char *section, ...) {
  va_list ap;
  va_start(ap, section);
  int given = 0;
  for (const char *k = va_arg(ap, const char *); k; k = va_arg(ap, const char *))
    given |= fb_casefile_given(c, section, k);
  va_end(ap);
  return fb_value_source_name(given ? FB_SOURCE_CASE : FB_SOURCE_DEFAULT);
}

fb_status fb_report_write_markdown(const char *dir, const fb_run *r, const char *case_path,
                                   const char *command, char figures[][128], int n,
                                   const char *figure_note, fb_diag *diag) {
  char path[4096];
  snprintf(path, sizeof path, "%s/report.md", dir);
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) return st;
  /* a text report: every control character of data escaped (textsafe.h) */
  FILE *f = fb_text_safe_stream(out.f, 0);
  if (!f) {
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
  }
  const fb_case *c = &r->c;
  fprintf(f, "# fourbar run: %s\n\n", c->name);
  fprintf(f, "Command: `%s`  \nCase file: `%s`\n\n", command, case_path ? case_path : "-");
  fprintf(f, "## Summary\n\n```\n");
  fb_report_print_table(f, r);
  fprintf(f, "```\n\nPer-model series: %s; every number: `summary.json`.\n\n",
          r->c.series == FB_SERIES_HDF5   ? "`series.h5`, a group per model (docs/series.md)"
          : r->c.series == FB_SERIES_NONE ? "none written (`[run] series = none`)"
                                          : "`<model>.csv`");
  fprintf(f, "## Parameters\n\n| quantity | value | source |\n|---|---|---|\n");
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  for (int k = 0; k < FB_LINK_COUNT; k++)
    fprintf(f, "| %s length | %.4f mm nominal, +- %.3f mm, stack-up %.4f mm | %s |\n",
            fb_link_name(k), c->nominal.length[k] * 1e3, c->plus_minus[k] * 1e3,
            su.length[k] * 1e3, c->tolerance_source[k]);
  fprintf(f, "| pin | diameter %.4g mm, length %.4g mm | %s |\n", c->pin_diameter * 1e3,
          c->pin_length * 1e3,
          c->fit[0] ? c->fit : given_src(c, "pin", "diameter_mm", "length_mm", NULL));
  fprintf(f, "| radial clearance | %.4g um | %s |\n", c->radial_clearance * 1e6, c->clearance_source);
  for (int i = 0; i < 3; i++) {
    const fb_link_mass *m = &c->link[i];
    const fb_link_mass_source *s = &c->link_source[i];
    fprintf(f, "| %s mass | %.6g kg | %s |\n", fb_link_name(i), m->mass,
            fb_value_source_name(s->mass));
    fprintf(f, "| %s inertia (hinge axis, long axis, across) | %.6g, %.6g, %.6g kg mm^2 | %s, "
               "%s, %s |\n",
            fb_link_name(i), m->inertia * 1e6, m->inertia_long * 1e6, m->inertia_transverse * 1e6,
            fb_value_source_name(s->inertia), fb_value_source_name(s->inertia_long),
            fb_value_source_name(s->inertia_transverse));
    fprintf(f, "| %s centre of mass | %.4g of the length from its first joint | %s |\n",
            fb_link_name(i), m->com_fraction, fb_value_source_name(s->com_fraction));
  }
  fprintf(f, "| link bars (width x thickness) | crank %.4g x %.4g mm, coupler %.4g x %.4g mm, "
             "follower %.4g x %.4g mm | %s |\n",
          c->link_width[0] * 1e3, c->link_thickness[0] * 1e3, c->link_width[1] * 1e3,
          c->link_thickness[1] * 1e3, c->link_width[2] * 1e3, c->link_thickness[2] * 1e3,
          any_derived(c) ? given_src(c, "mass", "crank_width_mm", "crank_thickness_mm",
                                     "coupler_width_mm", "coupler_thickness_mm",
                                     "follower_width_mm", "follower_thickness_mm", NULL)
                         : "not used (the case gives every mass and inertia)");
  fprintf(f, "| density | %.6g kg/m^3 | %s |\n", c->density,
          given_src(c, "material", "density_kg_m3", NULL));
  fprintf(f, "| crank speed | %.6g rpm %s | %s |\n", c->crank_speed * 60.0 / (2.0 * M_PI),
          c->direction > 0 ? "ccw" : "cw", given_src(c, "drive", "speed_rpm", "direction", NULL));
  const int h_auto = c->solver.h_mode == FB_STEP_AUTO ||
                     (c->solver.h_mode == FB_STEP_DEFAULT && c->clearance.mask);
  fprintf(f, "| step size h | %.6g s (%s) | %s |\n", c->solver.h,
          c->solver.stepper == FB_STEPPER_WORLD ? "dWorldStep" : "dWorldQuickStep",
          h_auto ? "auto: h omega_c <= 0.5 at the stiffest contact (fourbar penalty CASE)"
                 : given_src(c, "solver", "h_s", NULL));
  if (c->clearance.mask) {
    fprintf(f, "| clearance joints |");
    for (int j = 0; j < 4; j++)
      if (c->clearance.mask & (1 << j)) fprintf(f, " %s", fb_joint_name(j));
    const char *src[4] = {"physical (Johnson line contact at the inverse-dynamics reaction)",
                          "paper (Kc and P read in N-mm units)", "explicit",
                          "goldsmith (paper Eq. 3-5, internal contact of pin and hole)"};
    fprintf(f, " | %s |\n| penalty source | %s, stiffness scale %g | %s |\n",
            given_src(c, "clearance", "joints", NULL), src[c->clearance.penalty],
            c->clearance.stiffness_scale,
            given_src(c, "clearance", "penalty", "stiffness_scale", NULL));
    fprintf(f, "| restitution law | cr = %g | %s |\n", c->clearance.restitution,
            given_src(c, "clearance", "restitution", NULL));
    fprintf(f, "| impact law | n = %g, c_max = %g N s/m, d_max = %g um | %s |\n",
            c->clearance.exponent, c->clearance.damping, c->clearance.damping_depth * 1e6,
            given_src(c, "clearance", "exponent", "damping_n_s_m", "damping_depth_um", NULL));
    fprintf(f, "| mapping | %s | %s |\n", fb_mapping_name((fb_mapping)c->clearance.mapping),
            given_src(c, "clearance", "mapping", NULL));
  }
  fb_report_markdown_chaos(f, r);
  fprintf(f, "\n## Figures\n\n");
  if (n == 0) fprintf(f, "%s\n", figure_note ? figure_note : "No figures were drawn.");
  for (int i = 0; i < n; i++) fprintf(f, "![%s](%s)\n\n", figures[i], figures[i]);
  fclose(f); /* into out.f, whose write errors the commit reports */
  return fb_outfile_commit(&out, diag);
}

json_t *fb_report_contact_law_json(int joint, const fb_contact_law *law, fb_mapping mapping) {
  json_t *o = json_object();
  json_object_set_new(o, "joint", json_string(fb_joint_name(joint)));
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

void fb_report_print_contact_law(FILE *f, int joint, const fb_contact_law *law,
                                 fb_mapping mapping) {
  fprintf(f, "  %-17s %-12s %-8s stiffness %.6g N/m^%.6g", fb_joint_name(joint),
          fb_law_name(law->kind), fb_mapping_name(mapping), law->stiffness, law->exponent);
  switch (law->kind) {
    case FB_LAW_IMPACT:
      fprintf(f, ", c_max %.6g N s/m over d_max %.6g m\n", law->damping, law->damping_depth);
      break;
    case FB_LAW_RESTITUTION:
      fprintf(f, ", cr %.6g: damping ratio %.6g, c = 2 zeta sqrt(p m_eff) at each step\n",
              law->restitution, fb_contact_law_zeta(law));
      break;
    case FB_LAW_LINEAR: fprintf(f, ", c %.6g N s/m\n", law->damping); break;
    case FB_LAW_HERTZ: fputc('\n', f); break;
    default: fprintf(f, ", cr %.6g\n", law->restitution); break;
  }
}
