/* The writers of a planar case's run, by body name (report_planar.h). */
#include "report_planar.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "episode.h"
#include "fileio.h"
#include "numfmt.h"
#include "outcome_text.h"
#include "report_internal.h"
#include "report_planar_outputs.h"
#include "resolution.h"
#include "run.h"
#include "series.h"
#include "series_write.h"
#include "units.h"

/* finite number or null */
static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

static json_t *pair(const double v[2]) { return json_pack("[o,o]", num(v[0]), num(v[1])); }

/* the description as compiled: bodies (what was derived), joints, drive */
static json_t *description_json(const fb_planar *m) {
  json_t *d = json_object(), *bodies = json_array(), *joints = json_array();
  static const char *const what[] = {"mass", "inertia", "centre"};
  for (int b = 1; b < m->nbodies; b++) {
    const fb_planar_body *p = &m->body[b];
    json_t *derived = json_array();
    for (int k = 0; k < 3; k++)
      if (p->derived & (1 << k)) json_array_append_new(derived, json_string(what[k]));
    json_array_append_new(bodies, json_pack("{s:s,s:o,s:o,s:o,s:o}", "name", p->name, "mass_kg",
                                            num(p->mass), "inertia_kg_m2", num(p->inertia),
                                            "centre_m", pair(p->centre), "derived", derived));
  }
  for (int j = 0; j < m->njoints; j++) {
    const fb_planar_joint *q = &m->joint[j];
    json_array_append_new(
        joints, json_pack("{s:s,s:s,s:[s,s],s:o}", "name", q->name, "kind",
                          q->kind == FB_KIND_PRISMATIC ? "prismatic" : "revolute", "bodies",
                          m->body[q->body[0]].name, m->body[q->body[1]].name, "at_m", pair(q->at)));
  }
  json_object_set_new(d, "bodies", bodies);
  json_object_set_new(d, "joints", joints);
  json_t *springs = json_array(), *loads = json_array();
  for (int k = 0; k < m->nsprings; k++) {
    const fb_planar_spring *q = &m->spring[k];
    double a[2], b[2];
    fb_planar_at_assembly(a, m, q->body[0], q->point[0]);
    fb_planar_at_assembly(b, m, q->body[1], q->point[1]);
    json_array_append_new(
        springs, json_pack("{s:s,s:[s,s],s:o,s:o,s:o,s:o,s:o}", "name", q->name, "bodies",
                           m->body[q->body[0]].name, m->body[q->body[1]].name, "at_a_m", pair(a),
                           "at_b_m", pair(b), "stiffness_n_m", num(q->stiffness), "free_length_m",
                           num(q->free_length), "damping_n_s_m", num(q->damping)));
  }
  static const char *const active[] = {"always", "outstroke", "return"};
  for (int k = 0; k < m->nloads; k++) {
    const fb_planar_load *q = &m->load[k];
    double at[2];
    fb_planar_at_assembly(at, m, q->body, q->point);
    json_array_append_new(
        loads, json_pack("{s:s,s:s,s:o,s:o,s:o,s:s,s:o}", "name", q->name, "body",
                         m->body[q->body].name, "at_m", pair(at), "force_n", pair(q->force),
                         "torque_n_m", num(q->torque), "active", active[q->active], "stroke_joint",
                         q->stroke >= 0 ? json_string(m->joint[q->stroke].name) : json_null()));
  }
  json_object_set_new(d, "springs", springs);
  json_object_set_new(d, "loads", loads);
  json_object_set_new(d, "torque_drive",
                      m->torque_joint >= 0
                          ? json_pack("{s:s,s:o}", "joint", m->joint[m->torque_joint].name,
                                      "torque_n_m", num(m->drive_torque))
                          : json_null());
  json_object_set_new(d, "drive", m->drive >= 0 ? json_string(m->joint[m->drive].name)
                                                 : json_null()); /* undriven */
  return d;
}

/* a reference's verdict (planar_run.h): ok, unconverged, unchecked, or
 * failed */
static const char *verdict_of(const fb_planar_ref_result *q, char *why, size_t size) {
  if (q->failed) {
    snprintf(why, size, "the integration stopped: %s", q->stop);
    return "failed";
  }
  if (!fb_planar_ref_checked(q)) {
    snprintf(why, size, "no check integration: its tolerance %.2g is the floor (%.2g), nothing "
             "tighter to compare with", q->tol, q->check_tol);
    return "unchecked";
  }
  snprintf(why, size, "its window peaks move by %.2g (largest, relative) in its check integration "
           "at tolerance %.2g; the bound is %.2g", q->check_rel, q->check_tol, FB_UNCONVERGED_REL);
  return q->converged ? "ok" : "unconverged";
}

/* a reference's own keys: its clearance joint, law, window, contact peaks,
 * check integration and verdict */
/* a clearance model's joint and law (a reference's, or an engine's
 * through the engine kit, which takes the reference's law) */
static json_t *law_json(const fb_contact_law *law, double force_work) {
  return json_pack("{s:s,s:o,s:o,s:o,s:o}", "kind",
                   law->kind == FB_LAW_IMPACT ? "impact" : "restitution", "stiffness",
                   num(law->stiffness), "exponent", num(law->exponent), "restitution",
                   num(law->restitution), "working_force_n", num(force_work));
}

/* a clearance model's joints and law: clearance_joints (every one), law
 * (the first's), and per_joint: each joint's law, force and penetration
 * peaks (force_max_n and penetration_max_m of the model are their
 * largest) */
static void clearance_json(json_t *e, const fb_planar_run *r, const fb_planar_model *p) {
  const fb_planar_ref_result *q = &p->ref;
  json_t *names = json_array(), *each = json_array();
  for (int k = 0; k < fb_planar_model_contacts(p); k++) {
    const fb_planar_ref_joint a = fb_planar_model_contact(p, k);
    json_array_append_new(names, json_string(r->m->joint[a.joint].name));
    json_array_append_new(each, json_pack("{s:s,s:o,s:o,s:o}", "joint", r->m->joint[a.joint].name,
                                          "law", law_json(&a.law, a.force_work), "force_max_n",
                                          q->failed ? json_null() : num(a.force_max),
                                          "penetration_max_m",
                                          q->failed ? json_null() : num(a.penetration_max)));
  }
  json_object_set_new(e, "clearance_joints", names);
  json_object_set_new(e, "law", law_json(&q->law, q->force_work));
  json_object_set_new(e, "per_joint", each);
  json_object_set_new(e, "window_from_s", num(r->t_window));
}

/* fb_planar_model_resolution with its warning in words (outcome_text.c)
 * into warn (size bytes; empty unless 0 is returned) */
static int resolution(const fb_planar_run *r, const fb_planar_model *p, char *warn, size_t size) {
  if (warn && size) warn[0] = '\0';
  fb_warning w;
  const int ok = fb_planar_model_resolution(r, p, &w);
  if (ok == 0 && warn) fb_warning_text(warn, size, &w);
  return ok;
}

/* summary.json's `contact` of an engine clearance model: each clearance
 * joint's contact as the run met it, under the four-bar's keys
 * (report_summary.c), and the largest fixed step that resolves it */
static json_t *contact_json(const fb_planar_run *r, const fb_planar_model *p) {
  json_t *all = json_array();
  for (int k = 0; k < p->ref.njoints; k++) {
    const fb_planar_ref_joint *a = &p->ref.at[k];
    char warn[512] = "";
    fb_warning w;
    const int ok = fb_planar_model_joint_resolution(r, p, k, &w);
    if (ok == 0) fb_warning_text(warn, sizeof warn, &w);
    const double hw = a->h_omega_max;
    json_t *o = json_object();
    json_object_set_new(o, "joint", json_string(r->m->joint[a->joint].name));
    json_object_set_new(o, "law", json_string(fb_law_name(a->law.kind)));
    json_object_set_new(o, "effective_mass_kg",
                        isfinite(a->m_eff_min) && isfinite(a->m_eff_max)
                            ? json_pack("{s:f,s:f}", "min", a->m_eff_min, "max", a->m_eff_max)
                            : json_null());
    json_object_set_new(o, "h_omega_c_max", ok >= 0 ? num(hw) : json_null());
    json_object_set_new(o, "h_omega_c_bound", num(FB_H_OMEGA_C_BOUND));
    json_object_set_new(o, "contact_steps", json_integer((json_int_t)a->contact_steps));
    json_object_set_new(o, "resolved", ok >= 0 ? json_boolean(ok) : json_null());
    json_object_set_new(o, "resolving_step_s",
                        ok >= 0 ? num(p->h * FB_H_OMEGA_C_BOUND / hw * FB_H_AUTO_MARGIN)
                                : json_null());
    json_object_set_new(o, "warning", ok == 0 ? json_string(warn) : json_null());
    json_array_append_new(all, o);
  }
  return all;
}

/* 1 when the run's step resolves estimate e: h x rate within the bound
 * (to rounding: auto sets h from the bound itself) */
static int estimate_resolved(const fb_planar_run *r, const fb_planar_contact_estimate *e) {
  return !(fb_planar_run_h_rate(r, e) > FB_H_OMEGA_C_BOUND * (1.0 + 1e-12));
}

/* a given step's warning on estimate e (empty when h resolves it), with
 * the largest step that would */
static void estimate_warning(char *warn, size_t size, const fb_planar_run *r,
                             const fb_planar_contact_estimate *e) {
  warn[0] = '\0';
  if (estimate_resolved(r, e)) return;
  const double hr = fb_planar_run_h_rate(r, e);
  snprintf(warn, size, "under-resolved before the run: h x %s = %.3g at the %s joint exceeds "
           "%g; set [solver] h_s = auto, or a fixed step of %.3g s or smaller",
           e->rates.by_damper ? "c/m_eff" : "omega_c", hr,
           r->m->joint[e->joint].name, FB_H_OMEGA_C_BOUND, e->h_resolving);
}

/* one contact estimate of the run (planar_resolution.h) as the step's JSON */
static json_t *estimate_json(const fb_planar_run *r, const fb_planar_contact_estimate *e) {
  char warn[512];
  estimate_warning(warn, sizeof warn, r, e);
  const fb_contact_rates *q = &e->rates;
  json_t *o = json_object();
  json_object_set_new(o, "joint", json_string(r->m->joint[e->joint].name));
  json_object_set_new(o, "law", json_string(fb_law_name(e->law.kind)));
  json_object_set_new(o, "effective_mass_kg", json_pack("{s:o,s:o}", "min", num(e->m_eff_min),
                                                        "max", num(e->m_eff_max)));
  json_object_set_new(o, "force_expected_n", num(e->force_expected));
  json_object_set_new(o, "omega_c_rad_s", num(q->omega_c));
  json_object_set_new(o, "damper_rate_1_s", num(q->damper_rate));
  json_object_set_new(o, "approach_speed_m_s", num(q->approach_speed));
  json_object_set_new(o, "damper_ramp_rate_1_s", num(q->ramp_rate));
  json_object_set_new(o, "rate_1_s", num(q->rate));
  json_object_set_new(o, "rate_from", json_string(q->limit));
  json_object_set_new(o, "h_resolving_s", num(e->h_resolving));
  json_object_set_new(o, "h_rate", num(fb_planar_run_h_rate(r, e)));
  json_object_set_new(o, "h_ramp_rate", num(fb_planar_run_step(&r->c) * q->ramp_rate));
  json_object_set_new(o, "resolved", json_boolean(estimate_resolved(r, e)));
  json_object_set_new(o, "warning", warn[0] ? json_string(warn) : json_null());
  return o;
}

/* the step the estimates choose: their smallest h_resolving [s] (NAN: none) */
static double estimates_step(const fb_planar_run *r) {
  double h = NAN;
  for (int k = 0; k < r->nest; k++)
    h = isfinite(h) ? fmin(h, r->est[k].h_resolving) : r->est[k].h_resolving;
  return h;
}

/* summary.json's `step`: the step the models ran at, how it was chosen,
 * each clearance contact's estimate before the run, and the largest
 * h omega_c any engine's clearance model met (the four-bar's keys,
 * report_chaos.c fb_report_step_json, as far as a planar run measures them) */
static json_t *step_json(const fb_planar_run *r) {
  double hw = NAN, h = fb_planar_run_step(&r->c);
  for (int i = 0; i < r->n; i++)
    if (isfinite(r->model[i].h_omega_max) && r->model[i].engine && r->model[i].force)
      hw = isfinite(hw) ? fmax(hw, r->model[i].h_omega_max) : r->model[i].h_omega_max;
  json_t *o = json_object();
  json_object_set_new(o, "h_s", num(h));
  json_object_set_new(o, "auto", json_boolean(fb_planar_run_step_auto(&r->c)));
  char rule[160];
  snprintf(rule, sizeof rule, "h x rate <= %g at the fastest clearance contact (rate: omega_c "
           "or the damper's c / m_eff), at most one revolution / %g steps", FB_H_OMEGA_C_BOUND,
           FB_H_AUTO_STEPS_PER_REV);
  json_object_set_new(o, "auto_rule", json_string(rule));
  json_object_set_new(o, "auto_estimate_s", num(fb_planar_run_step_auto(&r->c)
                                                     ? r->h_auto_estimate : estimates_step(r)));
  json_object_set_new(o, "rechosen", json_integer(r->h_rechosen));
  json_t *ct = json_array();
  for (int k = 0; k < r->nest; k++) json_array_append_new(ct, estimate_json(r, &r->est[k]));
  json_object_set_new(o, "contact", ct);
  json_object_set_new(o, "h_omega_c_max", isfinite(hw) ? num(hw) : json_null());
  json_object_set_new(o, "h_omega_c_bound", num(FB_H_OMEGA_C_BOUND));
  json_object_set_new(o, "within_bound",
                      isfinite(hw) ? json_boolean(hw <= FB_H_OMEGA_C_BOUND) : json_null());
  return o;
}

/* the header's bodies: the mass properties the run used, each given or
 * derived from the case's bars (summary.json's description.bodies) */
static void bodies_text(FILE *f, const fb_planar *m) {
  static const char *const what[] = {"mass", "inertia", "centre"};
  fprintf(f, "| body | mass [kg] | centre x [m] | centre y [m] | inertia [kg m^2] | derived "
             "from bars |\n|---|---:|---:|---:|---:|---|\n");
  for (int b = 1; b < m->nbodies; b++) {
    const fb_planar_body *p = &m->body[b];
    char derived[64] = "";
    for (int k = 0; k < 3; k++)
      if (p->derived & (1 << k))
        snprintf(derived + strlen(derived), sizeof derived - strlen(derived), "%s%s",
                 derived[0] ? ", " : "", what[k]);
    fprintf(f, "| %s | %.6g | %.6g | %.6g | %.6g | %s |\n", p->name, p->mass, p->centre[0],
            p->centre[1], p->inertia, derived[0] ? derived : "none (given)");
  }
  if (m->nsprings)
    fprintf(f, "| spring | bodies | stiffness [N/m] | free length [m] | damping [N s/m] |\n"
               "|---|---|---:|---:|---:|\n");
  for (int k = 0; k < m->nsprings; k++) {
    const fb_planar_spring *q = &m->spring[k];
    fprintf(f, "| %s | %s, %s | %.6g | %.6g | %.6g |\n", q->name, m->body[q->body[0]].name,
            m->body[q->body[1]].name, q->stiffness, q->free_length, q->damping);
  }
  if (m->torque_joint >= 0)
    fprintf(f, "torque drive: %.6g N m on joint '%s' (+ on %s, - on %s), its speed from the "
               "dynamics\n", m->drive_torque, m->joint[m->torque_joint].name,
            m->body[m->joint[m->torque_joint].body[1]].name,
            m->body[m->joint[m->torque_joint].body[0]].name);
  if (m->nloads)
    fprintf(f, "| load | body | force x [N] | force y [N] | torque [N m] | acts |\n"
               "|---|---|---:|---:|---:|---|\n");
  for (int k = 0; k < m->nloads; k++) {
    const fb_planar_load *q = &m->load[k];
    char acts[2 * FB_PLANAR_NAME_SIZE + 32] = "always";
    if (q->stroke >= 0)
      snprintf(acts, sizeof acts, "%s of %s", q->active == FB_PLANAR_LOAD_OUTSTROKE ? "outstroke"
                                                                                    : "return",
               m->joint[q->stroke].name);
    fprintf(f, "| %s | %s | %.6g | %.6g | %.6g | %s |\n", q->name, m->body[q->body].name,
            q->force[0], q->force[1], q->torque, acts);
  }
}

/* the header's step lines: the step, how it was chosen, each clearance
 * contact's rates and h times its rate */
static void step_text(FILE *f, const fb_planar_run *r) {
  const double h = fb_planar_run_step(&r->c);
  if (r->c.solver.h_mode == FB_STEP_ADAPTIVE)
    fprintf(f, "step h = %.4g s: the output grid of [solver] h_s = adaptive (h_min_s); an "
            "engine's model steps from h_min_s to h_max_s = %.4g s as its contacts ask "
            "(summary.json models[].adaptive_steps)\n", h, r->c.solver.h_max);
  else if (fb_planar_run_step_auto(&r->c) && r->nest && r->h_rechosen)
    fprintf(f, "step h = %.4g s: auto, rechosen %d time%s from the estimate's %.4g s (an engine's "
            "clearance model met h omega_c above %g)\n", h, r->h_rechosen,
            r->h_rechosen > 1 ? "s" : "", r->h_auto_estimate, FB_H_OMEGA_C_BOUND);
  else if (fb_planar_run_step_auto(&r->c) && r->nest)
    fprintf(f, "step h = %.4g s: auto, h x rate <= %g at the fastest clearance contact (at most "
            "one revolution / %g)\n", h, FB_H_OMEGA_C_BOUND, FB_H_AUTO_STEPS_PER_REV);
  else if (r->nest)
    fprintf(f, "step h = %.4g s: [solver] h_s %s; the contacts' estimate resolves at "
            "h <= %.4g s ([solver] h_s = auto)\n", h,
            r->c.solver.h_mode == FB_STEP_DEFAULT ? "not given (the key's default)" : "as given",
            estimates_step(r));
  for (int k = 0; k < r->nest; k++) {
    const fb_planar_contact_estimate *e = &r->est[k];
    const fb_contact_rates *q = &e->rates;
    char warn[512];
    estimate_warning(warn, sizeof warn, r, e);
    fprintf(f, "  contact at '%s', %s law: effective mass %.4g kg, expected force %.4g N, "
            "omega_c %.4g rad/s, damper c/m_eff %.4g 1/s, h x rate %.3g (%s)%s%s",
            r->m->joint[e->joint].name, fb_law_name(e->law.kind), e->m_eff_min,
            e->force_expected, q->omega_c, q->damper_rate, fb_planar_run_h_rate(r, e), q->limit,
            warn[0] ? ": " : "", warn);
    if (q->ramp_rate > 0.0)
      fprintf(f, "; damper ramp v_n/d_max %.4g 1/s at v_n %.3g m/s (h x ramp %.3g, reported)",
              q->ramp_rate, q->approach_speed, h * q->ramp_rate);
    fputc('\n', f);
  }
}

static void reference_json(json_t *e, const fb_planar_run *r, const fb_planar_model *p) {
  const fb_planar_ref_result *q = &p->ref;
  char why[FB_DIAG_SIZE + 256];
  json_object_set_new(e, "verdict", json_string(verdict_of(&p->ref, why, sizeof why)));
  json_object_set_new(e, "verdict_reason", json_string(why));
  if (q->joint >= 0) {
    clearance_json(e, r, p);
  } else { /* the ideal mechanism's (planar_run.h): no joint, no law */
    json_object_set_new(e, "clearance_joints", json_array());
    json_object_set_new(e, "law", json_null());
    json_object_set_new(e, "window_from_s", num(r->t_window));
  }
  json_object_set_new(e, "force_max_n", q->failed ? json_null() : num(q->force_max));
  json_object_set_new(e, "penetration_max_m", q->failed ? json_null() : num(q->penetration_max));
  json_object_set_new(e, "error_estimate",
                      json_pack("{s:o,s:o,s:I,s:I,s:o}", "tolerance", num(q->tol),
                                "check_tolerance", num(q->check_tol), "steps",
                                (json_int_t)q->steps, "check_steps", (json_int_t)q->check_steps,
                                "peaks_change_max_rel", q->failed ? json_null() : num(q->check_rel)));
}

/* an engine model's verdict (planar_verdict.h): its word, basis, reason
 * and, for a clearance model, its impacts against its reference's */
static void engine_verdict_json(json_t *e, const fb_planar_model *p) {
  const fb_planar_verdict *v = &p->verdict;
  if (!v->judged) return;
  const char *basis = fb_verdict_basis_name(v->basis);
  json_object_set_new(e, "verdict", json_string(fb_verdict_name(v->word)));
  json_object_set_new(e, "verdict_basis", basis ? json_string(basis) : json_null());
  json_object_set_new(e, "verdict_reason", json_string(v->reason));
  if (!p->force) {
    json_object_set_new(e, "peak_error_max_rel", num(v->peak_rel_max));
    return;
  }
  json_object_set_new(
      e, "impacts_vs_reference",
      json_pack("{s:i,s:i,s:i,s:o,s:o,s:o,s:o,s:o,s:o,s:s,s:o}", "impacts", v->impacts,
                "impacts_reference", v->impacts_reference, "matched", v->matched, "parts_s",
                num(v->parts_s), "first_t_error_s", num(v->first_t_error_s), "first_force_rel",
                num(v->first_force_rel), "first_penetration_rel", num(v->first_penetration_rel),
                "matched_force_rel_max", v->matched ? num(v->matched_force_rel_max) : json_null(),
                "matched_penetration_rel_max",
                v->matched ? num(v->matched_penetration_rel_max) : json_null(), "compared_at",
                v->sampled ? "the same sample instants" : "continuous extremes",
                "step_resolution",
                v->sampled ? json_pack("{s:o,s:o}", "first_force_rel",
                                       num(v->first_resolution_force_rel),
                                       "first_penetration_rel",
                                       num(v->first_resolution_penetration_rel))
                           : json_null()));
  if (v->rigid) {
    /* a rigid model's force is an impulse over a step: what it computes
     * instead (planar_verdict.c rigid) */
    json_t *o = json_object_get(e, "impacts_vs_reference");
    json_object_set_new(o, "rigid", json_true());
    json_object_set_new(o, "first_rebound_ratio", num(v->first_rebound_ratio));
    json_object_set_new(o, "first_impulse_n_s", num(v->first_impulse_n_s));
    json_object_set_new(o, "restitution", num(v->restitution));
    json_object_set_new(o, "compared_at", json_string("rebound ratio against the law's cr"));
    json_object_set_new(o, "step_resolution", json_null());
  }
}

/* an analytic model's load peaks over the window, under the four-bar's
 * keys (report_internal.h) */
static json_t *loads_json(const fb_planar_run *r, const fb_planar_model *p) {
  const fb_planar *m = r->m;
  const char *joint[FB_PLANAR_SPEC_MAX_JOINTS];
  const double *fx[FB_PLANAR_SPEC_MAX_JOINTS], *fy[FB_PLANAR_SPEC_MAX_JOINTS];
  for (int j = 0; j < m->njoints; j++) {
    joint[j] = m->joint[j].name;
    fx[j] = p->reaction + (size_t)j * 3 * p->n;
    fy[j] = fx[j] + p->n;
  }
  return fb_report_loads_of(p->t, p->n, r->t_window, p->torque, m->njoints, joint, fx, fy);
}

/* every moving body's peaks (peaks: per body of m, the ground's first) as
 * a table */
static void bodies_table(FILE *f, const fb_planar *m, const fb_body_peaks *peaks) {
  fprintf(f, "| body | omega max [rad/s] | omega min [rad/s] | alpha max [rad/s^2] | "
             "alpha min [rad/s^2] |\n|---|---:|---:|---:|---:|\n");
  for (int b = 1; b < m->nbodies; b++) {
    const fb_body_peaks *k = &peaks[b];
    fprintf(f, "| %s | %s | %s | %s | %s |\n", m->body[b].name,
            FB_NUM_CELL("%.6g", k->omega_max, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", k->omega_min, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", k->alpha_max, FB_NUM_NONE_TABLE),
            FB_NUM_CELL("%.6g", k->alpha_min, FB_NUM_NONE_TABLE));
  }
}

/* a variant's model's verdict and why (size bytes): an engine's against
 * its yardstick, a reference's check; NULL for the analytic model */
static const char *variant_verdict(const fb_planar_variant_model *q, char *why, size_t size) {
  if (q->reference) return verdict_of(&q->ref, why, size);
  if (q->engine && q->verdict.judged) {
    snprintf(why, size, "%s", q->verdict.reason);
    return fb_verdict_name(q->verdict.word);
  }
  if (q->engine && q->ref.failed) {
    snprintf(why, size, "it stopped: %s", q->ref.stop);
    return "failed";
  }
  return NULL;
}

/* the case's variants, each model's verdict, contact peaks and bodies */
static void variants_table(FILE *f, const fb_planar_run *r) {
  for (int v = 0; v < r->variant_count; v++) {
    const fb_planar_variant *x = &r->variant[v];
    fprintf(f, "\nvariant %s (%s%s%s; h = %.3g s)\n", x->def.name, x->def.set,
            x->def.models[0] ? "; models " : "", x->def.models, x->h);
    if (x->def.description[0]) fprintf(f, "%s\n", x->def.description);
    for (int i = 0; i < x->n; i++) {
      const fb_planar_variant_model *q = &x->model[i];
      char why[FB_DIAG_SIZE + 256];
      const char *word = variant_verdict(q, why, sizeof why);
      fprintf(f, "\nvariant %s, model %s", x->def.name, q->name);
      if (q->contact)
        fprintf(f, ": contact force max %s N, penetration max %s um",
                FB_NUM_CELL("%.6g", q->ref.failed ? NAN : q->ref.force_max, FB_NUM_NONE_TABLE),
                FB_NUM_CELL("%.4g", q->ref.failed ? NAN : q->ref.penetration_max / FB_M_PER_UM,
                            FB_NUM_NONE_TABLE));
      fprintf(f, "\n");
      if (word) fprintf(f, "verdict: %s (%s)\n", word, why);
      bodies_table(f, r->m, q->peaks);
    }
  }
}

/* summary.json's variants: each variant's name, set, models key,
 * description, step and models (name, kind, status, bodies, a contact's
 * force_max_n and penetration_max_m, verdict and verdict_reason) */
static json_t *variants_json(const fb_planar_run *r) {
  json_t *a = json_array();
  const char *name[FB_PLANAR_SPEC_MAX_BODIES];
  for (int b = 1; b < r->m->nbodies; b++) name[b - 1] = r->m->body[b].name;
  for (int v = 0; v < r->variant_count; v++) {
    const fb_planar_variant *x = &r->variant[v];
    json_t *o = json_object(), *models = json_array();
    json_object_set_new(o, "name", json_string(x->def.name));
    json_object_set_new(o, "set", json_string(x->def.set));
    json_object_set_new(o, "models_key", x->def.models[0] ? json_string(x->def.models) : json_null());
    json_object_set_new(o, "description", x->def.description[0] ? json_string(x->def.description)
                                                                : json_null());
    json_object_set_new(o, "h_s", num(x->h));
    for (int i = 0; i < x->n; i++) {
      const fb_planar_variant_model *q = &x->model[i];
      char why[FB_DIAG_SIZE + 256];
      const char *word = variant_verdict(q, why, sizeof why);
      json_t *e = json_pack("{s:s,s:s,s:s}", "name", q->name, "kind",
                            q->reference ? "reference" : q->engine ? "engine" : "analytic",
                            "status", q->ref.failed ? "failed" : "ok");
      json_object_set_new(e, "bodies", fb_report_bodies_json(name, q->peaks + 1, r->m->nbodies - 1));
      if (q->contact) {
        json_object_set_new(e, "force_max_n", q->ref.failed ? json_null() : num(q->ref.force_max));
        json_object_set_new(e, "penetration_max_m",
                            q->ref.failed ? json_null() : num(q->ref.penetration_max));
      }
      json_object_set_new(e, "verdict", word ? json_string(word) : json_null());
      json_object_set_new(e, "verdict_reason", word ? json_string(why) : json_null());
      json_array_append_new(models, e);
    }
    json_object_set_new(o, "models", models);
    json_array_append_new(a, o);
  }
  return a;
}

/* the rule of the samples a planar run writes, in words (summary.json's
 * "series", series.h5) */
#define PLANAR_SERIES_RULE                                                                 \
  "every N-th sample (i mod N = 0), the last sample, and every sample of an impact episode " \
  "(at any clearance joint of the model: from the onset of positive penetration through "    \
  "its compression and restitution, the rate taken from successive penetrations) with one " \
  "sample either side; free flight and continuous contact are kept every N-th sample"

json_t *fb_report_planar_summary_json(const fb_planar_run *r, const char *case_path) {
  const fb_planar *m = r->m;
  json_t *o = json_object(), *models = json_array();
  json_object_set_new(o, "case", json_string(r->c.name));
  json_object_set_new(o, "case_file", json_string(case_path));
  json_object_set_new(o, "mechanism", json_string("planar"));
  json_object_set_new(o, "description", description_json(m));
  json_object_set_new(o, "drive_omega_rad_s", num(r->omega));
  json_object_set_new(o, "revolutions", num(r->c.revolutions));
  json_object_set_new(o, "step", step_json(r));
  json_object_set_new(o, "series",
                      json_pack("{s:s,s:i,s:s}", "format",
                                fb_report_series_format_name(r->c.series), "every",
                                r->c.series_every, "rule", PLANAR_SERIES_RULE));
  char injected[1024];
  json_object_set_new(o, "injected_error",
                      fb_report_injected_case_text(injected, sizeof injected, &r->c)
                          ? json_string(injected)
                          : json_null());
  const char *name[FB_PLANAR_SPEC_MAX_BODIES];
  for (int b = 1; b < m->nbodies; b++) name[b - 1] = m->body[b].name;
  for (int i = 0; i < r->n; i++) {
    const fb_planar_model *p = &r->model[i];
    json_t *e = json_pack("{s:s,s:s,s:s,s:o,s:I}", "name", p->name, "kind",
                          p->reference ? "reference" : p->engine ? "engine" : "analytic", "status",
                          p->ref.failed ? "failed" : "ok", "h_s", num(p->h), "steps",
                          (json_int_t)p->n);
    /* an engine's model of a planar case is its kit binding's (planar_run.h) */
    json_object_set_new(e, "builder", p->engine ? json_string("kit") : json_null());
    json_object_set_new(e, "bodies", fb_report_bodies_json(name, p->peaks + 1, m->nbodies - 1));
    if (p->reference) reference_json(e, r, p);
    if (p->engine && p->force) { /* an engine's clearance model (planar_run.h) */
      clearance_json(e, r, p);
      json_object_set_new(e, "force_max_n", num(p->ref.force_max));
      json_object_set_new(e, "penetration_max_m", num(p->ref.penetration_max));
      json_object_set_new(e, "contact_steps", json_integer((json_int_t)p->ref.steps));
      json_object_set_new(e, "contact", contact_json(r, p));
    }
    if (p->engine)
      json_object_set_new(e, "adaptive_steps",
                          fb_report_adaptive_steps_json(p->has_step_stats ? &p->step_stats : NULL));
    if (p->engine && p->ref.failed) json_object_set_new(e, "stop", json_string(p->ref.stop));
    if (p->torque) json_object_set_new(e, "loads", loads_json(r, p));
    fb_report_planar_outputs_json(e, r, p);
    engine_verdict_json(e, p);
    json_array_append_new(models, e);
  }
  json_object_set_new(o, "models", models);
  json_object_set_new(o, "variants", variants_json(r));
  return o;
}

static json_t *timing_json(const fb_planar_run *r) {
  json_t *o = json_object(), *models = json_array();
  json_object_set_new(o, "case", json_string(r->c.name));
  for (int i = 0; i < r->n; i++) {
    const fb_planar_model *p = &r->model[i];
    json_array_append_new(models, json_pack("{s:s,s:I,s:o,s:o}", "name", p->name, "steps",
                                            (json_int_t)p->n, "wall_s", num(p->wall_s),
                                            "time_per_step_us",
                                            num(p->n ? 1e6 * p->wall_s / (double)p->n : NAN)));
  }
  json_object_set_new(o, "models", models);
  return o;
}

/* one CSV cell: %.12g (numfmt.h), empty when not finite */
static void cell(FILE *f, double x, int first) {
  char buf[FB_NUMFMT_G12_SIZE];
  if (!first) fputc(',', f);
  if (isfinite(x)) fwrite(buf, 1, fb_numfmt_g12(buf, x), f);
}

/* ---- a model's columns, as its CSV and the run's HDF5 file name them ---- */

/* what column k of a model reads */
typedef enum { COL_TIME, COL_DRIVE, COL_BODY, COL_FORCE, COL_PEN, COL_TORQUE, COL_REACTION,
               COL_OUTPUT } col_kind;
typedef struct {
  col_kind kind;
  int a, b; /* COL_BODY: body, quantity (angle, omega, alpha); COL_REACTION: joint, component
               (x, y, magnitude, a prismatic joint's moment); COL_FORCE, COL_PEN: the
               contact (fb_planar_model_contact); COL_OUTPUT: output column */
  const double *v; /* COL_FORCE, COL_PEN: the contact's column, found once (not per cell) */
} col_def;

/* a model of a run with its columns (fb_series_table's self) */
typedef struct {
  const fb_planar_run *r;
  const fb_planar_model *p;
  col_def *col;
} model_cols;

/* model p's columns into col (room for max_columns(r)): time, the drive's
 * angle, every moving body's angle, omega and alpha, a clearance model's
 * force and penetration at each clearance joint, the analytic model's loads (the
 * four-bar's names, series.h, then a prismatic joint's couple), the
 * description's outputs; returns their number */
static size_t columns(col_def *col, const fb_planar_run *r, const fb_planar_model *p) {
  const fb_planar *m = r->m;
  size_t n = 0;
  col[n++] = (col_def){COL_TIME, 0, 0, NULL};
  col[n++] = (col_def){COL_DRIVE, 0, 0, NULL};
  for (int b = 1; b < m->nbodies; b++)
    for (int k = 0; k < 3; k++) col[n++] = (col_def){COL_BODY, b, k, NULL};
  for (int k = 0; k < fb_planar_model_contacts(p); k++) {
    const fb_planar_ref_joint ct = fb_planar_model_contact(p, k);
    col[n++] = (col_def){COL_FORCE, k, 0, ct.force};
    col[n++] = (col_def){COL_PEN, k, 0, ct.pen};
  }
  if (p->torque) {
    col[n++] = (col_def){COL_TORQUE, 0, 0, NULL};
    for (int j = 0; j < m->njoints; j++)
      for (int k = 0; k < (m->joint[j].kind == FB_KIND_PRISMATIC ? 4 : 3); k++)
        col[n++] = (col_def){COL_REACTION, j, k, NULL};
  }
  for (int c = 0; c < p->nout; c++) col[n++] = (col_def){COL_OUTPUT, c, 0, NULL};
  return n;
}

static size_t max_columns(const fb_planar_run *r, const fb_planar_model *p) {
  return 4 + 3 * (size_t)r->m->nbodies + 2 * (size_t)fb_planar_model_contacts(p) + 1 +
         4 * (size_t)r->m->njoints + (size_t)p->nout;
}

static void column_name(const fb_series_table *t, size_t k, char *buf, size_t size) {
  static const char *const body[3] = {"angle_rad", "omega_rad_s", "alpha_rad_s2"};
  static const char *const reaction[4] = {"reaction_x_n", "reaction_y_n", "reaction_n",
                                          "reaction_moment_n_m"};
  const model_cols *mc = t->self;
  const fb_planar *m = mc->r->m;
  const col_def c = mc->col[k];
  char w[FB_REPORT_JOINT_KEY_SIZE];
  switch (c.kind) {
    case COL_TIME: snprintf(buf, size, "time_s"); break;
    case COL_DRIVE: snprintf(buf, size, "drive_angle_rad"); break;
    case COL_BODY: snprintf(buf, size, "%s_%s", m->body[c.a].name, body[c.b]); break;
    case COL_FORCE:
      snprintf(buf, size, "%s_force_n", m->joint[fb_planar_model_contact(mc->p, c.a).joint].name);
      break;
    case COL_PEN:
      snprintf(buf, size, "%s_penetration_m",
               m->joint[fb_planar_model_contact(mc->p, c.a).joint].name);
      break;
    case COL_TORQUE: snprintf(buf, size, "drive_torque_n_m"); break;
    case COL_REACTION:
      fb_report_joint_key(w, sizeof w, m->joint[c.a].name);
      snprintf(buf, size, "%s_%s", w, reaction[c.b]);
      break;
    case COL_OUTPUT: fb_report_planar_output_column(buf, size, m, c.a); break;
  }
}

static double column_value(const fb_series_table *t, size_t k, size_t i) {
  const model_cols *mc = t->self;
  const fb_planar_model *p = mc->p;
  const col_def c = mc->col[k];
  switch (c.kind) {
    case COL_TIME: return p->t[i];
    case COL_DRIVE: return p->drive[i];
    case COL_BODY: return fb_planar_model_value(mc->r, p, c.a, c.b, i);
    case COL_FORCE:
    case COL_PEN: return c.v[i];
    case COL_TORQUE: return p->torque[i];
    case COL_REACTION: return fb_planar_model_reaction(p, c.a, c.b, i);
    case COL_OUTPUT: return p->out[(size_t)c.a * p->n + i];
  }
  return NAN;
}

/* model p of run r as a table over col (columns' room) */
static fb_series_table model_table(model_cols *mc, col_def *col, const fb_planar_run *r,
                                   const fb_planar_model *p) {
  *mc = (model_cols){r, p, col};
  const fb_model *fm = fb_model_find(p->name);
  return (fb_series_table){p->name, fm ? fb_engine_name(fm->engine) : p->name,
                           fm ? fm->summary : "", p->h, p->n, columns(col, r, p), mc,
                           column_name, column_value, NULL};
}

/* the run's series step: every series_every-th sample, as in the CSV */
static size_t series_every(const fb_planar_run *r) {
  return r->c.series_every > 0 ? (size_t)r->c.series_every : 1;
}

/* the samples model p writes (its CSV's rows, its series.h5 group's) into
 * keep (p->n bytes, 1 kept), by PLANAR_SERIES_RULE: every impact whole,
 * classified by the engines' episode rule (episode.h) from the penetration
 * column (any onset an impact: vmin 0) */
static void planar_keep(const fb_planar_run *r, const fb_planar_model *p, unsigned char *keep) {
  const size_t n = p->n, every = series_every(r);
  for (size_t i = 0; i < n; i++) keep[i] = (unsigned char)(i % every == 0);
  if (n) keep[n - 1] = 1;
  for (int k = 0; k < fb_planar_model_contacts(p) && every > 1; k++) {
    const double *pen = fb_planar_model_contact(p, k).pen;
    fb_episode ep;
    memset(&ep, 0, sizeof ep);
    for (size_t i = 0; i < n; i++) {
      const int on = pen[i] > 0.0;
      const double rate = i && on ? (pen[i] - (pen[i - 1] > 0.0 ? pen[i - 1] : 0.0)) / p->h : 0.0;
      fb_episode_update(&ep, on, rate, 0.0);
      if (ep.state != FB_STATE_IMPACT) continue;
      keep[i] = 1;
      if (i > 0) keep[i - 1] = 1;
      if (i + 1 < n) keep[i + 1] = 1;
    }
  }
}

static fb_status write_csv(const char *dir, const fb_planar_run *r, const fb_planar_model *p,
                           fb_diag *diag) {
  char path[4200];
  snprintf(path, sizeof path, "%s/%s.csv", dir, p->name);
  col_def *col = malloc(max_columns(r, p) * sizeof *col);
  unsigned char *keep = malloc(p->n ? p->n : 1);
  if (!col || !keep) {
    free(col);
    free(keep);
    return fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
  }
  planar_keep(r, p, keep);
  model_cols mc;
  const fb_series_table t = model_table(&mc, col, r, p);
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) {
    free(col);
    free(keep);
    return st;
  }
  for (size_t k = 0; k < t.ncols; k++) {
    char name[FB_REPORT_JOINT_KEY_SIZE + 64];
    column_name(&t, k, name, sizeof name);
    fprintf(out.f, "%s%s", k ? "," : "", name);
  }
  fputc('\n', out.f);
  for (size_t i = 0; i < p->n; i++) {
    if (!keep[i]) continue;
    for (size_t k = 0; k < t.ncols; k++) cell(out.f, column_value(&t, k, i), k == 0);
    fputc('\n', out.f);
  }
  free(col);
  free(keep);
  if (ferror(out.f)) {
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_IO, "%s: write failed", path);
  }
  return fb_outfile_commit(&out, diag);
}

/* every model into DIR/series.h5 (series_write.h), the samples its CSV
 * would hold, summary.json's text in the root's attributes */
static fb_status write_hdf5(const char *dir, const fb_planar_run *r, const char *summary_json,
                            fb_diag *diag) {
  char path[4200];
  snprintf(path, sizeof path, "%s/series.h5", dir);
  const int n = r->n;
  fb_series_table *t = calloc((size_t)(n > 0 ? n : 1), sizeof *t);
  model_cols *mc = calloc((size_t)(n > 0 ? n : 1), sizeof *mc);
  col_def **col = calloc((size_t)(n > 0 ? n : 1), sizeof *col);
  unsigned char **keep = calloc((size_t)(n > 0 ? n : 1), sizeof *keep);
  fb_status st = t && mc && col && keep ? FB_OK : FB_ERR_NOMEM;
  for (int i = 0; i < n && st == FB_OK; i++) {
    const fb_planar_model *p = &r->model[i];
    col[i] = malloc(max_columns(r, p) * sizeof **col);
    keep[i] = malloc(p->n ? p->n : 1);
    if (!col[i] || !keep[i]) {
      st = FB_ERR_NOMEM;
      break;
    }
    planar_keep(r, p, keep[i]);
    t[i] = model_table(&mc[i], col[i], r, p);
  }
  if (st == FB_OK)
    st = fb_series_write_hdf5_tables(path, r->c.name, (int)series_every(r), PLANAR_SERIES_RULE,
                                     t, n, keep, summary_json, diag);
  else
    fb_diag_set(diag, st, "%s: out of memory", path);
  for (int i = 0; col && keep && i < n; i++) {
    free(col[i]);
    free(keep[i]);
  }
  free(t);
  free(mc);
  free(col);
  free(keep);
  return st;
}

/* an analytic model's load peaks (loads_json) as the table's lines: the
 * drive torque's extremes and one row per joint */
static void loads_table(FILE *f, const fb_planar_run *r, const fb_planar_model *p) {
  json_t *l = loads_json(r, p);
  if (json_is_object(l)) {
    json_t *rm = json_object_get(l, "reaction_max_n");
    fprintf(f, "loads (peaks over t >= %.4g s; a reaction is the force on the joint's second "
               "body from its first):\ndrive torque max %.6g N m, min %.6g N m\n"
               "| joint | reaction max [N] |\n|---|---:|\n", r->t_window,
            json_real_value(json_object_get(l, "drive_torque_max_n_m")),
            json_real_value(json_object_get(l, "drive_torque_min_n_m")));
    for (int j = 0; j < r->m->njoints; j++) {
      char key[FB_REPORT_JOINT_KEY_SIZE];
      fb_report_joint_key(key, sizeof key, r->m->joint[j].name);
      fprintf(f, "| %s | %.6g |\n", r->m->joint[j].name,
              json_real_value(json_object_get(rm, key)));
    }
  }
  json_decref(l);
}

void fb_report_planar_table(FILE *f, const fb_planar_run *r) {
  const fb_planar *m = r->m;
  fprintf(f, "case %s: planar, %d moving bodies, %d joints, ", r->c.name, m->nbodies - 1,
          m->njoints);
  if (m->drive < 0 && m->torque_joint >= 0)
    fprintf(f, "driven by a torque at '%s'\n", m->joint[m->torque_joint].name);
  else if (m->drive < 0) fprintf(f, "undriven (a free start)\n");
  else fprintf(f, "drive '%s' at %.6g rad/s\n", m->joint[m->drive].name, r->omega);
  bodies_text(f, m);
  step_text(f, r);
  char injected[1024];
  if (fb_report_injected_case_text(injected, sizeof injected, &r->c)) fprintf(f, "%s\n", injected);
  for (int i = 0; i < r->n; i++) {
    const fb_planar_model *p = &r->model[i];
    fprintf(f, "\nmodel %s (%zu samples every %.3g s)\n", p->name, p->n, p->h);
    if (p->reference) {
      char why[FB_DIAG_SIZE + 256];
      const char *v = verdict_of(&p->ref, why, sizeof why);
      if (p->ref.joint < 0) { /* the ideal mechanism (planar_run.h) */
        fprintf(f, "ideal mechanism (no clearance joint): its forward dynamics under the "
                "case's loads, rk8pd at tolerance %.2g; peaks over t >= %.4g s\nverdict: %s (%s)\n",
                p->ref.tol, r->t_window, v, why);
      } else {
        for (int k = 0; k < p->ref.njoints; k++) { /* a line per clearance joint */
          const fb_planar_ref_joint *a = &p->ref.at[k];
          char work[96]; /* an explicit law has no working force (planar_free.h) */
          if (a->force_work > 0.0)
            snprintf(work, sizeof work, "working force %.4g N", a->force_work);
          else
            snprintf(work, sizeof work, "no working force: its stiffness given, penalty = explicit");
          fprintf(f, "clearance at '%s' (%s law, %s): peaks over t >= %.4g s; "
                  "contact force max %s N, penetration max %s um\n",
                  r->m->joint[a->joint].name,
                  a->law.kind == FB_LAW_IMPACT ? "impact" : "restitution", work, r->t_window,
                  FB_NUM_CELL("%.6g", p->ref.failed ? NAN : a->force_max, FB_NUM_NONE_TABLE),
                  FB_NUM_CELL("%.4g", p->ref.failed ? NAN : a->penetration_max / FB_M_PER_UM,
                              FB_NUM_NONE_TABLE));
        }
        fprintf(f, "verdict: %s (%s)\n", v, why);
      }
    }
    if (p->verdict.judged) {
      const char *basis = fb_verdict_basis_name(p->verdict.basis);
      fprintf(f, "verdict: %s%s%s (%s)\n", fb_verdict_name(p->verdict.word), basis ? ", " : "",
              basis ? basis : "", p->verdict.reason);
    }
    char warn[512];
    const int res = p->engine && p->force ? resolution(r, p, warn, sizeof warn) : -1;
    if (res >= 0) {
      char at[512] = "";
      size_t u = 0;
      for (int k = 0; k < p->ref.njoints && u < sizeof at; k++)
        u += (size_t)snprintf(at + u, sizeof at - u, "%s'%s'", k ? ", " : "",
                              r->m->joint[p->ref.at[k].joint].name);
      fprintf(f, "contact%s at %s: largest h omega_c over %zu contact steps %.3g, bound %g: %s\n",
              p->ref.njoints > 1 ? "s" : "", at, p->ref.steps, p->h_omega_max,
              FB_H_OMEGA_C_BOUND, res ? "resolved" : warn);
    }
    for (int k = 0; p->engine && p->force && p->ref.njoints > 1 && k < p->ref.njoints; k++)
      fprintf(f, "clearance at '%s': contact force max %s N, penetration max %s um\n",
              r->m->joint[p->ref.at[k].joint].name,
              FB_NUM_CELL("%.6g", p->ref.failed ? NAN : p->ref.at[k].force_max, FB_NUM_NONE_TABLE),
              FB_NUM_CELL("%.4g", p->ref.failed ? NAN : p->ref.at[k].penetration_max / FB_M_PER_UM,
                          FB_NUM_NONE_TABLE));
    bodies_table(f, m, p->peaks);
    fb_report_planar_outputs_table(f, r, p);
    if (p->torque) loads_table(f, r, p);
  }
  variants_table(f, r);
}

static fb_status write_markdown(const char *dir, const fb_planar_run *r, const char *case_path,
                                const char *command, char figures[][128], int nfig,
                                fb_diag *diag) {
  char path[4200];
  snprintf(path, sizeof path, "%s/report.md", dir);
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) return st;
  char kit[2048];
  fprintf(out.f, "# %s\n\nCase file `%s`, run by `%s`. A planar case (docs/planar.md): its "
                 "models run on the planar core, and the engines' models (%s) through the "
                 "engine kit.\n\n",
          r->c.name, case_path, command, fb_planar_kit_models(kit, sizeof kit));
  fb_report_planar_table(out.f, r);
  fprintf(out.f, "\n## Figures\n\n");
  if (nfig == 0) fprintf(out.f, "No figures were drawn.\n");
  for (int i = 0; i < nfig; i++) fprintf(out.f, "![%s](%s)\n\n", figures[i], figures[i]);
  if (ferror(out.f)) {
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_IO, "%s: write failed", path);
  }
  return fb_outfile_commit(&out, diag);
}

fb_status fb_report_planar_write(const char *dir, const fb_planar_run *r, const char *case_path,
                                 const char *command, char figures[][128], int nfig,
                                 fb_diag *diag) {
  char path[4200];
  fb_status st = FB_OK;
  for (int i = 0; i < r->n && st == FB_OK && r->c.series == FB_SERIES_CSV; i++)
    st = write_csv(dir, r, &r->model[i], diag);
  if (st != FB_OK) return st;
  snprintf(path, sizeof path, "%s/summary.json", dir);
  json_t *j = fb_report_planar_summary_json(r, case_path);
  st = fb_report_write_json(path, j, diag);
  if (st == FB_OK && r->c.series == FB_SERIES_HDF5) {
    char *text = json_dumps(j, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    st = text ? write_hdf5(dir, r, text, diag)
              : fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
    free(text);
  }
  json_decref(j);
  if (st != FB_OK) return st;
  snprintf(path, sizeof path, "%s/timing.json", dir);
  j = timing_json(r);
  st = fb_report_write_json(path, j, diag);
  json_decref(j);
  if (st != FB_OK) return st;
  return write_markdown(dir, r, case_path, command, figures, nfig, diag);
}
