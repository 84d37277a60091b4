/* fourbar contact-params' output (tables_contact_params.h): the rows in
 * each engine's own syntax, the verification tables, or one JSON object. */
#include "tables_contact_params.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "model_table.h"
#include "resolution.h"

static double rel(double x, double ref) { return ref != 0.0 ? (x - ref) / fabs(ref) : x - ref; }

/* ---- JSON ------------------------------------------------------------------ */

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

static json_t *mujoco_json(const fb_mujoco_params *p, const char *form) {
  json_t *o = json_object();
  json_object_set_new(o, "form", json_string(form));
  json_object_set_new(o, "solref", json_pack("[f,f]", p->solref[0], p->solref[1]));
  json_object_set_new(o, "solimp", json_pack("[f,f,f,f,f]", p->solimp[0], p->solimp[1],
                                             p->solimp[2], p->solimp[3], p->solimp[4]));
  json_object_set_new(o, "stiffness_per_mass_1_s2", json_real(p->kappa));
  json_object_set_new(o, "damping_per_mass_1_s", json_real(p->beta));
  return o;
}

static json_t *params_json(const fb_cp_rows *rw) {
  json_t *p = json_object();
  json_t *ode = json_object();
  json_object_set_new(ode, "matched", json_pack("{s:f,s:f}", "erp", rw->ode.erp, "cfm_m_n_s",
                                                rw->ode.cfm));
  json_object_set_new(ode, "standard", json_pack("{s:f,s:f}", "erp", rw->ode_standard.erp,
                                                 "cfm_m_n_s", rw->ode_standard.cfm));
  json_object_set_new(ode, "contact_max_correcting_vel_m_s", json_real(rw->max_vel));
  json_object_set_new(ode, "contact_surface_layer_m", json_real(0.0));
  json_object_set_new(p, "ode", ode);
  json_object_set_new(p, "gazebo", json_pack("{s:f,s:f,s:f,s:f,s:f}", "kp", rw->gazebo.kp, "kd",
                                             rw->gazebo.kd, "max_vel", rw->max_vel, "min_depth",
                                             0.0, "max_step_size", rw->lc.h));
  json_t *mj = json_object();
  json_object_set_new(mj, "direct", mujoco_json(&rw->mj_direct, "direct"));
  json_object_set_new(mj, "direct_continuous", mujoco_json(&rw->mj_continuous, "direct-continuous"));
  json_object_set_new(mj, "standard",
                      rw->has_standard ? mujoco_json(&rw->mj_standard, "standard") : json_null());
  json_object_set_new(mj, "standard_note",
                      rw->has_standard ? json_null() : json_string(rw->standard_note));
  json_t *at = json_array();
  for (int i = 0; i < rw->n_masses; i++) {
    json_t *x = mujoco_json(&rw->mj_at[i], "direct-at-mass");
    json_object_set_new(x, "mass_kg", json_real(rw->masses[i]));
    json_array_append_new(at, x);
  }
  json_object_set_new(mj, "direct_at_mass", at);
  json_object_set_new(mj, "integrator", json_string("Euler"));
  json_object_set_new(p, "mujoco", mj);
  json_object_set_new(p, "bullet", json_pack("{s:f,s:f,s:f}", "contact_stiffness", rw->gazebo.kp,
                                             "contact_damping", rw->gazebo.kd,
                                             "contact_processing_threshold", 0.0));
  return p;
}

static json_t *check_json(const fb_cp_check *x) {
  json_t *e = json_object();
  json_object_set_new(e, "engine", json_string(x->engine));
  json_object_set_new(e, "engine_version",
                      x->engine_version ? json_string(x->engine_version) : json_null());
  json_object_set_new(e, "form", json_string(x->form));
  json_object_set_new(e, "mass_kg", json_real(x->mass));
  json_object_set_new(e, "recommended", json_boolean(x->recommended));
  json_object_set_new(e, "faithful", json_boolean(x->ran && x->faithful));
  json_object_set_new(e, "status", json_string(x->ran ? "ok" : x->why));
  json_object_set_new(e, "restitution", x->ran ? num(x->restitution) : json_null());
  json_object_set_new(e, "restitution_target", num(x->restitution_target));
  json_object_set_new(e, "restitution_rel", x->ran ? num(x->restitution_rel) : json_null());
  json_object_set_new(e, "restitution_onset_phase", x->ran ? num(x->restitution_phase)
                                                           : json_null());
  json_object_set_new(e, "penetration_max_m", x->ran ? num(x->penetration) : json_null());
  json_object_set_new(e, "penetration_target_m", num(x->penetration_target));
  json_object_set_new(e, "penetration_rel", x->ran ? num(x->penetration_rel) : json_null());
  json_object_set_new(e, "penetration_onset_phase", x->ran ? num(x->penetration_phase)
                                                           : json_null());
  json_object_set_new(e, "force_max_n", x->ran ? num(x->force) : json_null());
  json_object_set_new(e, "force_target_n", num(x->force_target));
  return e;
}

static json_t *checks_json(const fb_cp_step *st) {
  json_t *v = json_array();
  for (int i = 0; i < st->n_checks; i++) json_array_append_new(v, check_json(&st->checks[i]));
  return v;
}

/* an at_step contact: the stiffest faithful contact of the same restitution
 * at its step, k [N/m], c [N s/m] */
static json_t *at_step_json(const fb_cp_step *st, double k, double c) {
  const fb_cp_rows *rw = &st->rows;
  json_t *a = json_object();
  json_object_set_new(a, "h_s", json_real(rw->lc.h));
  json_object_set_new(a, "stiffness_n_m", json_real(k));
  json_object_set_new(a, "damping_n_s_m", json_real(c));
  json_object_set_new(a, "h_omega_c", json_real(rw->h_omega_c));
  json_t *im = json_array();
  for (int i = 0; i < rw->n_masses; i++)
    json_array_append_new(im, json_pack("{s:f,s:o,s:o,s:o}", "mass_kg", rw->masses[i],
                                        "restitution", num(rw->restitution[i]), "penetration_m",
                                        num(rw->penetration[i]), "contact_duration_s",
                                        num(rw->duration[i])));
  json_object_set_new(a, "impacts", im);
  const int d = rw->n_masses > 1 ? 1 : 0;
  json_object_set_new(a, "restitution", num(rw->restitution[d]));
  json_object_set_new(a, "penetration_m", num(rw->penetration[d]));
  json_object_set_new(a, "contact_duration_s", num(rw->duration[d]));
  json_object_set_new(a, "params", params_json(rw));
  json_object_set_new(a, "verify", checks_json(st));
  return a;
}

void fb_report_cp_json(FILE *f, const fb_cp_result *o, const char *case_path, const char *joint) {
  const fb_cp_request *q = &o->q;
  json_t *j = json_object();
  json_t *c = json_object();
  json_object_set_new(c, "law", json_string(fb_law_name(q->law)));
  json_object_set_new(c, "stiffness", json_real(q->stiffness));
  json_object_set_new(c, "stiffness_unit", json_string(q->law == FB_LAW_LINEAR ||
                                                        q->law == FB_LAW_RESTITUTION
                                                            ? "N/m" : "N/m^n"));
  json_object_set_new(c, "exponent", json_real(q->exponent));
  json_object_set_new(c, "restitution", num(q->restitution));
  json_object_set_new(c, "linear_stiffness_n_m", json_real(o->k));
  json_object_set_new(c, "linear_damping_n_s_m", json_real(o->c));
  json_object_set_new(c, "damper_floored", json_boolean(o->damper_floored));
  json_object_set_new(c, "operating_point",
                      q->law != FB_LAW_HERTZ ? json_null()
                      : json_pack("{s:s,s:o}", "rule",
                                  !isnan(q->load) ? "tangent at the static penetration of the load"
                                                  : "equal peak penetration of the impact",
                                  "penetration_m", num(o->op_penetration)));
  json_object_set_new(c, "law_impact",
                      isnan(o->law_penetration) ? json_null()
                      : json_pack("{s:o,s:o,s:o,s:f,s:o,s:o}", "restitution", num(o->law_restitution),
                                  "penetration_max_m", num(o->law_penetration), "force_max_n",
                                  num(o->law_force), "mass_kg", o->m0, "linear_force_max_n",
                                  num(o->lin_force), "restitution_floor", num(o->law_floor)));
  json_object_set_new(j, "contact", c);
  json_object_set_new(j, "case", !joint ? json_null()
                                 : json_pack("{s:s,s:s,s:s}", "file", case_path, "joint",
                                             joint, "model",
                                             q->law == FB_LAW_HERTZ ? "clearance-impact"
                                                                    : "clearance-restitution"));
  json_object_set_new(j, "mass_kg", json_pack("{s:f,s:f,s:f}", "min", q->mass_min, "max",
                                              q->mass_max, "design", o->m0));
  json_object_set_new(j, "h_s", json_real(q->h));
  json_object_set_new(j, "h_omega_c_max", json_real(o->given.rows.h_omega_c));
  json_object_set_new(j, "h_omega_c_bound", json_real(FB_H_OMEGA_C_BOUND));
  json_object_set_new(j, "speed_m_s", json_real(q->speed));
  json_object_set_new(j, "verified", json_boolean(q->verify));
  json_t *ph = json_array();
  for (int i = 0; i < FB_CP_ONSET_PHASES; i++) json_array_append_new(ph, json_real(fb_cp_onset_phases[i]));
  json_object_set_new(j, "onset_phases", ph);
  json_object_set_new(j, "tolerances", json_pack("{s:f,s:f}", "restitution_rel",
                                                 FB_CP_RESTITUTION_TOL, "penetration_rel",
                                                 FB_CP_PENETRATION_TOL));
  json_object_set_new(j, "recommended", json_boolean(o->given.recommended));
  json_object_set_new(j, "params", o->given.recommended ? params_json(&o->given.rows) : json_null());
  json_object_set_new(j, "params_note", o->given.recommended ? json_null()
                                                             : json_string(o->given.why_not));
  json_object_set_new(j, "verify", q->verify ? checks_json(&o->given) : json_null());
  json_object_set_new(j, "largest_step_s", num(o->largest_step));
  json_object_set_new(j, "largest_step_h_omega_c", num(o->largest_h_omega));
  json_object_set_new(j, "largest_step_limited_by",
                      isfinite(o->largest_step) ? json_string(o->largest_limited_by) : json_null());
  json_object_set_new(j, "at_step", o->has_at_step ? at_step_json(&o->at_step, o->at_k, o->at_c)
                                                   : json_null());
  json_t *es = json_array();
  for (int i = 0; i < o->n_engine_steps; i++) {
    json_t *a = at_step_json(&o->engine_step[i].step, o->engine_step[i].k, o->engine_step[i].c);
    json_object_set_new(a, "engine", json_string(o->engine_step[i].engine));
    json_array_append_new(es, a);
  }
  json_object_set_new(j, "at_default_steps", es);
  if (o->per_step.present) {
    const fb_cp_per_step *ps = &o->per_step;
    json_t *p = json_pack("{s:s,s:b,s:f}", "mapping",
                          "matched tangent row of the law every step (fb_contact_row_step)",
                          "recommended", ps->recommended, "h_omega_t", ps->h_omega_t);
    json_object_set_new(p, "verify", q->verify && ps->h_omega_t <= FB_H_OMEGA_C_BOUND
                                         ? check_json(&ps->check) : json_null());
    json_object_set_new(j, "per_step", p);
  } else {
    json_object_set_new(j, "per_step", json_null());
  }
  json_object_set_new(j, "failed_recommended_rows", json_integer(o->failed));
  json_dumpf(j, f, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
  fputc('\n', f);
  json_decref(j);
}

/* ---- text ------------------------------------------------------------------ */

static void print_rows(FILE *f, const fb_cp_rows *rw) {
  const double h = rw->lc.h;
  fprintf(f, "  ODE (per contact, every step):\n"
            "    contact.surface.mode = dContactSoftERP | dContactSoftCFM;\n"
            "    contact.surface.soft_erp = %.10g;  contact.surface.soft_cfm = %.10g;\n"
            "    dWorldSetContactMaxCorrectingVel(world, %.4g);  dWorldSetContactSurfaceLayer(world, 0);\n",
            rw->ode.erp, rw->ode.cfm, rw->max_vel);
  fprintf(f, "  Gazebo classic (SDFormat, ODE physics, <max_step_size>%.6g</max_step_size>):\n"
            "    <surface><contact><ode><kp>%.10g</kp><kd>%.10g</kd><max_vel>%.4g</max_vel>"
            "<min_depth>0</min_depth></ode></contact></surface>\n"
            "    (Gazebo puts two surfaces in series for kp and adds their kd: give this kp and kd\n"
            "    to one collision and kp 1e300, kd 0 to the other, or 2 kp and kd / 2 to each)\n",
            h, rw->gazebo.kp, rw->gazebo.kd, rw->max_vel);
  if (rw->gazebo.kd < 0.0)
    fprintf(f, "    kd < 0: the matched row's ERP exceeds 1 (it takes back the damper h kp that\n"
              "    Gazebo's kp/kd -> ERP/CFM formula adds); Gazebo uses it as given\n");
  fprintf(f, "  MuJoCo 2.2 and 3.x (<option timestep=\"%.6g\" integrator=\"Euler\"/>):\n", h);
  if (rw->n_masses == 1) {
    fprintf(f, "    <geom ... condim=\"1\" solref=\"%.10g %.10g\" solimp=\"%g %g %g %g %g\"/>   (direct)\n",
              rw->mj_direct.solref[0], rw->mj_direct.solref[1], rw->mj_direct.solimp[0],
              rw->mj_direct.solimp[1], rw->mj_direct.solimp[2], rw->mj_direct.solimp[3],
              rw->mj_direct.solimp[4]);
    if (rw->has_standard)
      fprintf(f, "    <geom ... condim=\"1\" solref=\"%.10g %.10g\" solimp=\"%g %g %g %g %g\"/>   (standard)\n",
                rw->mj_standard.solref[0], rw->mj_standard.solref[1], rw->mj_standard.solimp[0],
                rw->mj_standard.solimp[1], rw->mj_standard.solimp[2], rw->mj_standard.solimp[3],
                rw->mj_standard.solimp[4]);
  } else {
    fprintf(f, "    solref is per unit of effective mass: set it per contact from the contact's own\n"
              "    mass (direct form; solimp \"%g %g %g %g %g\"):\n", rw->mj_direct.solimp[0],
              rw->mj_direct.solimp[1], rw->mj_direct.solimp[2], rw->mj_direct.solimp[3],
              rw->mj_direct.solimp[4]);
    for (int i = 0; i < rw->n_masses; i++)
      fprintf(f, "      %.4g kg: solref=\"%.10g %.10g\"\n", rw->masses[i], rw->mj_at[i].solref[0],
                rw->mj_at[i].solref[1]);
  }
  fprintf(f, "  Bullet 3.24 (fixed step h = %.6g s):\n"
            "    body.setContactStiffnessAndDamping(%.10g, %.10g);\n"
            "    body.setContactProcessingThreshold(0);  other.setContactStiffnessAndDamping(BT_LARGE_FLOAT, 0);\n"
            "    solverInfo.m_splitImpulse = 0; m_linearSlop = 0; m_sor = 1\n",
            h, rw->gazebo.kp, rw->gazebo.kd);
}

static void print_check(FILE *f, const fb_cp_check *x) {
  if (!x->ran) {
    fprintf(f, "%-8s %-18s %9.4g %-5s %-4s  failed: %s\n", x->engine, x->form, x->mass,
              x->recommended ? "yes" : "no", "no", x->why);
    return;
  }
  fprintf(f, "%-8s %-18s %9.4g %-5s %-4s %11.6f %+10.2e %5.3g %13.6e %+10.2e %5.3g %11.5g\n",
            x->engine, x->form, x->mass, x->recommended ? "yes" : "no", x->faithful ? "yes" : "NO",
            x->restitution, x->restitution_rel, x->restitution_phase, x->penetration,
            x->penetration_rel, x->penetration_phase, x->force);
}

static void print_checks(FILE *f, const fb_cp_step *st) {
  fprintf(f, "%-8s %-18s %9s %-5s %-4s %11s %10s %5s %13s %10s %5s %11s\n", "engine", "form",
            "mass_kg", "recom", "ok", "restitution", "rel", "phase", "penetration_m", "rel", "phase",
            "force_max_n");
  for (int i = 0; i < st->n_checks; i++) print_check(f, &st->checks[i]);
}

/* the versions of the libraries that verified the rows, where an engine
 * reports one (MuJoCo: the users' 3.x may differ from this build's;
 * docs/contact-params.md gives both) */
static void print_versions(FILE *f, const fb_cp_result *o) {
  const fb_cp_step *steps[2] = {&o->given, &o->at_step};
  for (int s = 0; s < 2; s++)
    for (int i = 0; i < steps[s]->n_checks; i++) {
      const fb_cp_check *x = &steps[s]->checks[i];
      if (x->engine_version && strcmp(x->engine, "mujoco") == 0) {
        fprintf(f, "MuJoCo's rows are verified in MuJoCo %s, this build's (MuJoCo 3.x: "
                  "docs/contact-params.md)\n", x->engine_version);
        return;
      }
    }
}

/* an at_step contact's heading: its step, k [N/m], c [N s/m], and what it
 * implies at the design mass and speed v [m/s] */
static void print_at_step(FILE *f, const char *which, const fb_cp_step *st, double k, double c, double v) {
  const fb_cp_rows *rw = &st->rows;
  const int d = rw->n_masses > 1 ? 1 : 0;
  fprintf(f, "\n== at %sh = %.4g s, the stiffest faithful contact with the same restitution:\n"
            "   k = %.6g N/m, c = %.6g N s/m (h omega_c %.3g); at %.4g kg and %g m/s: restitution "
            "%.4g, peak penetration %.4g m, contact duration %.4g s\n",
            which, rw->lc.h, k, c, rw->h_omega_c, rw->masses[d], v, rw->restitution[d],
            rw->penetration[d], rw->duration[d]);
}

void fb_report_cp_text(FILE *f, const fb_cp_result *o, const char *case_path, const char *joint) {
  const fb_cp_request *q = &o->q;
  if (joint)
    fprintf(f, "case %s, joint %s: the law of its clearance-%s models%s; effective mass over a "
              "revolution and every direction\n",
              case_path, joint, q->law == FB_LAW_HERTZ ? "impact" : "restitution",
              q->law == FB_LAW_HERTZ ? " (its damper not carried), linearised at the joint's "
                                       "expected force" : "");
  fprintf(f, "contact: %s law, ", fb_law_name(q->law));
  if (q->law == FB_LAW_RESTITUTION)
    fprintf(f, "k = %g N/m, cr = %g: damper c = %.6g N s/m at the design mass\n", q->stiffness,
              q->restitution, o->c);
  else if (q->law == FB_LAW_LINEAR)
    fprintf(f, "k = %g N/m, c = %g N s/m\n", q->stiffness, q->damping);
  else if (q->law == FB_LAW_HERTZ)
    fprintf(f, "K = %g N/m^%g%s; linear spring k = %.6g N/m at %s (penetration %.4g m), damper "
              "c = %.6g N s/m\n", q->stiffness, q->exponent,
              isnan(q->restitution) ? ", undamped" : "", o->k,
              !isnan(q->load) ? "the tangent of the static penetration of the load"
                              : "equal peak penetration of the impact", o->op_penetration, o->c);
  else
    fprintf(f, "K = %g N/m^%g, cr = %g. Its impact of %.4g kg at %g m/s leaves with restitution "
              "%.6g and reaches %.6g m (peak force %.5g N). As the engines' linear spring-damper "
              "with that restitution and peak penetration at that speed and mass: k = %.6g N/m, "
              "c = %.6g N s/m (its peak force %.5g N, %+.1f %%)\n",
              q->stiffness, q->exponent, q->restitution, o->m0, q->speed, o->law_restitution,
              o->law_penetration, o->law_force, o->k, o->c, o->lin_force,
              100.0 * rel(o->lin_force, o->law_force));
  if (q->law != FB_LAW_HERTZ && isfinite(o->law_penetration) &&
      fabs(o->law_restitution - q->restitution) > FB_CP_LAW_NOTE_REL * q->restitution) {
    /* the law's own restitution, not cr, is what the rows reproduce: said */
    fprintf(f, "  (the %s law does not leave at the cr asked, %g, but at %.4g: its damper sets "
              "the restitution only approximately, and the rows below reproduce %.4g",
              fb_law_name(q->law), q->restitution, o->law_restitution, o->law_restitution);
    if (isfinite(o->law_floor))
      fprintf(f, "; its damping factor stays finite as cr -> 0, so no cr takes its restitution "
                "below %.4g at exponent %g: for less, --law flores or gonthier", o->law_floor,
                q->exponent);
    fprintf(f, ")\n");
  }
  if (o->damper_floored)
    fprintf(f, "  (undamped: an ODE row needs a finite CFM, so every row carries the damper of "
              "restitution %g, c = %.4g N s/m)\n", FB_CP_RESTITUTION_MAX, o->c);
  fprintf(f, "effective mass %g to %g kg, rows designed at %.4g kg; impact speed %g m/s\n",
            q->mass_min, q->mass_max, o->m0, q->speed);
  fprintf(f, "step h = %.4g s: h omega_c = %.3g at %.4g kg (a run holds h omega_c <= %g)\n", q->h,
            o->given.rows.h_omega_c, q->mass_min, FB_H_OMEGA_C_BOUND);
  if (q->verify) {
    if (isfinite(o->largest_step))
      fprintf(f, "largest faithful step of this contact: %.4g s (h omega_c %.3g, limited by %s)\n",
                o->largest_step, o->largest_h_omega,
                strcmp(o->largest_limited_by, "rule") == 0
                    ? "the run's bound h omega_c <= 0.5"
                    : "the verification: restitution within 1 %, penetration within 2 %, every "
                      "mass and onset phase");
    else
      fprintf(f, "largest faithful step of this contact: none down to h omega_c = %g\n",
                FB_CP_H_OMEGA_MIN);
  }
  fprintf(f, "\n");
  if (o->given.recommended) {
    fprintf(f, "== your contact at h = %.4g s: recommended%s\n", q->h,
              q->verify ? " (verified below)" : " (not verified: --no-verify)");
    print_rows(f, &o->given.rows);
  } else {
    fprintf(f, "== your contact at h = %.4g s: not recommended: %s\n", q->h, o->given.why_not);
  }
  if (q->h_from_case && !o->given.recommended && o->given.n_checks) {
    /* the run's step: what its step line says it accepts (report_chaos.h) */
    double er = 0.0, ep = 0.0;
    for (int k = 0; k < o->given.n_checks; k++) {
      const fb_cp_check *x = &o->given.checks[k];
      if (strcmp(x->engine, "ode") != 0 || strcmp(x->form, "matched") != 0 || !x->ran) continue;
      if (fabs(x->restitution_rel) > fabs(er)) er = x->restitution_rel;
      if (fabs(x->penetration_rel) > fabs(ep)) ep = x->penetration_rel;
    }
    fprintf(f, "   (the case's own step, which fourbar run takes: within its accuracy bound h omega_c "
               "<= %g, and its step line says it accepts this single impact's error, ODE's matched "
               "row: restitution %+.2g %%, penetration %+.2g %%; set [solver] h_s to the largest "
               "faithful step for a faithful run)\n", FB_H_OMEGA_C_BOUND, 100.0 * er, 100.0 * ep);
  }
  if (o->has_at_step) {
    print_at_step(f, "", &o->at_step, o->at_k, o->at_c, q->speed);
    if (o->at_k > o->k)
      fprintf(f, "   (stiffer than your contact, which is faithful at this step already)\n");
    print_rows(f, &o->at_step.rows);
  }
  for (int i = 0; i < o->n_engine_steps; i++) {
    print_at_step(f, strcmp(o->engine_step[i].engine, "mujoco") == 0 ? "MuJoCo's default step, "
                                                                   : "Gazebo's default step, ",
                  &o->engine_step[i].step, o->engine_step[i].k, o->engine_step[i].c, q->speed);
    print_rows(f, &o->engine_step[i].step.rows);
  }
  if (o->per_step.present) {
    const fb_cp_per_step *ps = &o->per_step;
    fprintf(f, "\n== per-step mapping (ODE or Bullet rows set every step from the contact's state):\n"
              "   kp = n K delta^(n-1) (tangent), kd = the law's coefficient of delta', the depth handed\n"
              "   to the row K delta^n / kp; on the contact's effective mass m:\n"
              "   b = m (exp(kd h / m) - 1) / h, a = m (1 - e^{s1 h})(1 - e^{s2 h}) / (exp(-kd h / m) h^2),\n"
              "   soft_erp = h a / b, soft_cfm = 1 / b (s1, s2 the roots of m s^2 + kd s + kp;\n"
              "   fb_contact_row_step). h omega_t at the law's peak: %.3g: %s\n", ps->h_omega_t,
              ps->recommended ? "recommended" : "not recommended at this step (beyond the largest "
                                                "faithful h omega_c of the linear rows)");
  }
  if (!q->verify) return;
  fprintf(f, "\nverification: single impacts at %g m/s, every onset phase (", q->speed);
  for (int i = 0; i < FB_CP_ONSET_PHASES; i++)
    fprintf(f, "%s%g", i ? ", " : "", fb_cp_onset_phases[i]);
  fprintf(f, " of a step); the worst against the continuous contact (rel = engine / contact - 1); "
            "ok: within %g %% and %g %%\n", 100 * FB_CP_RESTITUTION_TOL, 100 * FB_CP_PENETRATION_TOL);
  print_versions(f, o);
  if (o->given.n_checks) {
    fprintf(f, "\nyour contact at h = %.4g s:\n", q->h);
    print_checks(f, &o->given);
  }
  if (o->has_at_step) {
    fprintf(f, "\nat_step contact at h = %.4g s:\n", q->h);
    print_checks(f, &o->at_step);
  }
  for (int i = 0; i < o->n_engine_steps; i++) {
    fprintf(f, "\nat_step contact at %s's default step h = %.4g s:\n",
              strcmp(o->engine_step[i].engine, "mujoco") == 0 ? "MuJoCo" : "Gazebo",
              o->engine_step[i].h);
    print_checks(f, &o->engine_step[i].step);
  }
  if (o->per_step.present && o->per_step.h_omega_t <= FB_H_OMEGA_C_BOUND) {
    fprintf(f, "\nper-step mapping, against the law's own impact at onset phase 0:\n");
    print_check(f, &o->per_step.check);
  }
  for (int i = 0; i < o->n_unverified; i++)
    fprintf(f, "(%s not verified: %s)\n", o->unverified[i].engine, o->unverified[i].howto);
  if (o->failed)
    fprintf(f, "\n%d recommended row(s) FAILED their verification\n", o->failed);
}

