/* fourbar contact-params: flags in, fb_cp_run (src/studies/contact_params.h),
 * the result printed as text or JSON. No physics here. */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case.h"
#include "casefile.h"
#include "cli.h"
#include "contact_params.h"
#include "fb_config.h"
#include "model_table.h"
#include "resolution.h"

static const char params_help[] =
    "usage: fourbar contact-params [--law LAW] [--stiffness K] [--exponent n]\n"
    "         [--damping-n-s-m c | --restitution cr] [--mass-kg m | --mass-kg A:B]\n"
    "         [--h-s h] [--speed-m-s v] [--load-n F] [--no-verify] [--json]\n"
    "       fourbar contact-params --case CASE [--joint NAME]\n"
    "         [--law restitution|hertz] [--h-s h] [--speed-m-s v] [--no-verify]\n"
    "         [--json]\n"
    "\n"
    "The engine parameters that make a soft contact behave like a given physical\n"
    "contact at step h: ODE (per-contact ERP/CFM), Gazebo (SDF kp, kd, max_vel,\n"
    "min_depth), MuJoCo 2.2 (solref/solimp) and Bullet (contact stiffness and\n"
    "damping), each in the engine's own units and syntax. A row is recommended\n"
    "only when it is faithful at h: h omega_c within a run's bound (0.5, at the\n"
    "smallest mass) and every single impact of it, in the engine itself, at every\n"
    "mass and wherever inside a step the contact begins, within 1 % of the\n"
    "continuous contact's restitution and 2 % of its peak penetration. Also\n"
    "printed: the largest faithful step of the contact, and at h the stiffest\n"
    "faithful contact with the same restitution (docs/contact-params.md).\n"
    "\n"
    "  --law          restitution (default: a linear spring with the damper of\n"
    "                 coefficient of restitution cr), linear (spring and damper),\n"
    "                 hertz (K delta^n; with --restitution, a damper of that cr),\n"
    "                 lankarani-nikravesh, hunt-crossley, flores, gonthier (damped\n"
    "                 Hertz laws: translated to the linear spring-damper with the\n"
    "                 law's own restitution and peak penetration at --speed-m-s and\n"
    "                 the design mass)\n"
    "  --stiffness    k [N/m] (Hertz laws: K [N/m^n]); default 1e7\n"
    "  --exponent     n of the Hertz laws (default 1.5)\n"
    "  --restitution  cr: restitution law (0.135, 1], default 0.9; damped Hertz\n"
    "                 laws (0, 1], default 0.9; hertz: optional\n"
    "  --damping-n-s-m  c of the linear law [N s/m] (default 0)\n"
    "  --mass-kg      effective mass along the contact normal [kg], or a range A:B\n"
    "                 (rows designed at the geometric mean, verified at A, it, B);\n"
    "                 default 0.1\n"
    "  --h-s          step size [s]; default: h omega_c = 0.1 at the smallest mass,\n"
    "                 or the largest faithful step when that is smaller; without\n"
    "                 --h-s the stiffest faithful contact is also given at\n"
    "                 MuJoCo's default step (2 ms) and Gazebo's (1 ms)\n"
    "  --speed-m-s    impact speed of the verification and of the Hertz laws'\n"
    "                 operating point [m/s] (default 1)\n"
    "  --load-n       hertz only: linearise at the static penetration of this load\n"
    "                 (tangent stiffness) instead of the impact at --speed-m-s\n"
    "  --case         take the contact from a case file (a path, or a shipped\n"
    "                 case's name): the law of its clearance-restitution models\n"
    "                 (--law restitution: k, cr) or of its clearance-impact models\n"
    "                 (--law hertz: K, n, linearised at the joint's expected force;\n"
    "                 its damper is not carried), the joint's effective-mass range\n"
    "                 over a revolution and every direction, and the run's step\n"
    "                 (unless --h-s)\n"
    "  --joint        the case's clearance joint (crank-coupler, ...); needed when\n"
    "                 the case has several\n"
    "  --verify       verify (the default; kept for scripts)\n"
    "  --no-verify    skip the single impacts: no largest step, no at_step, rows\n"
    "                 held to the h omega_c rule only and marked unverified\n"
    "  --json         one JSON object (docs/contact-params.md lists the keys)\n"
    "Exit status: 0 ok, 1 a recommended row failed its verification (or could\n"
    "not run), 2 bad input.\n";

static double rel(double x, double ref) { return ref != 0.0 ? (x - ref) / fabs(ref) : x - ref; }

static int parse_mass(const char *s, fb_cp_request *q) {
  char *end;
  q->mass_min = strtod(s, &end);
  q->mass_max = q->mass_min;
  if (*end == ':') q->mass_max = strtod(end + 1, &end);
  if (*end != '\0' || end == s) return 0;
  return 1;
}

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

static void print_json(const fb_cp_result *o, const char *case_path, int joint) {
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
                      : json_pack("{s:o,s:o,s:o,s:f,s:o}", "restitution", num(o->law_restitution),
                                  "penetration_max_m", num(o->law_penetration), "force_max_n",
                                  num(o->law_force), "mass_kg", o->m0, "linear_force_max_n",
                                  num(o->lin_force)));
  json_object_set_new(j, "contact", c);
  json_object_set_new(j, "case", joint < 0 ? json_null()
                                 : json_pack("{s:s,s:s,s:s}", "file", case_path, "joint",
                                             fb_joint_name(joint), "model",
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
  json_dumpf(j, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
  fputc('\n', stdout);
  json_decref(j);
}

/* ---- text ------------------------------------------------------------------ */

static void print_rows(const fb_cp_rows *rw) {
  const double h = rw->lc.h;
  printf("  ODE (per contact, every step):\n"
         "    contact.surface.mode = dContactSoftERP | dContactSoftCFM;\n"
         "    contact.surface.soft_erp = %.10g;  contact.surface.soft_cfm = %.10g;\n"
         "    dWorldSetContactMaxCorrectingVel(world, %.4g);  dWorldSetContactSurfaceLayer(world, 0);\n",
         rw->ode.erp, rw->ode.cfm, rw->max_vel);
  printf("  Gazebo classic (SDFormat, ODE physics, <max_step_size>%.6g</max_step_size>):\n"
         "    <surface><contact><ode><kp>%.10g</kp><kd>%.10g</kd><max_vel>%.4g</max_vel>"
         "<min_depth>0</min_depth></ode></contact></surface>\n"
         "    (Gazebo puts two surfaces in series for kp and adds their kd: give this kp and kd\n"
         "    to one collision and kp 1e300, kd 0 to the other, or 2 kp and kd / 2 to each)\n",
         h, rw->gazebo.kp, rw->gazebo.kd, rw->max_vel);
  if (rw->gazebo.kd < 0.0)
    printf("    kd < 0: the matched row's ERP exceeds 1 (it takes back the damper h kp that\n"
           "    Gazebo's kp/kd -> ERP/CFM formula adds); Gazebo uses it as given\n");
  printf("  MuJoCo 2.2 (<option timestep=\"%.6g\" integrator=\"Euler\"/>):\n", h);
  if (rw->n_masses == 1) {
    printf("    <geom ... condim=\"1\" solref=\"%.10g %.10g\" solimp=\"%g %g %g %g %g\"/>   (direct)\n",
           rw->mj_direct.solref[0], rw->mj_direct.solref[1], rw->mj_direct.solimp[0],
           rw->mj_direct.solimp[1], rw->mj_direct.solimp[2], rw->mj_direct.solimp[3],
           rw->mj_direct.solimp[4]);
    if (rw->has_standard)
      printf("    <geom ... condim=\"1\" solref=\"%.10g %.10g\" solimp=\"%g %g %g %g %g\"/>   (standard)\n",
             rw->mj_standard.solref[0], rw->mj_standard.solref[1], rw->mj_standard.solimp[0],
             rw->mj_standard.solimp[1], rw->mj_standard.solimp[2], rw->mj_standard.solimp[3],
             rw->mj_standard.solimp[4]);
  } else {
    printf("    solref is per unit of effective mass: set it per contact from the contact's own\n"
           "    mass (direct form; solimp \"%g %g %g %g %g\"):\n", rw->mj_direct.solimp[0],
           rw->mj_direct.solimp[1], rw->mj_direct.solimp[2], rw->mj_direct.solimp[3],
           rw->mj_direct.solimp[4]);
    for (int i = 0; i < rw->n_masses; i++)
      printf("      %.4g kg: solref=\"%.10g %.10g\"\n", rw->masses[i], rw->mj_at[i].solref[0],
             rw->mj_at[i].solref[1]);
  }
  printf("  Bullet 3.24 (fixed step h = %.6g s):\n"
         "    body.setContactStiffnessAndDamping(%.10g, %.10g);\n"
         "    body.setContactProcessingThreshold(0);  other.setContactStiffnessAndDamping(BT_LARGE_FLOAT, 0);\n"
         "    solverInfo.m_splitImpulse = 0; m_linearSlop = 0; m_sor = 1\n",
         h, rw->gazebo.kp, rw->gazebo.kd);
}

static void print_check(const fb_cp_check *x) {
  if (!x->ran) {
    printf("%-8s %-18s %9.4g %-5s %-4s  failed: %s\n", x->engine, x->form, x->mass,
           x->recommended ? "yes" : "no", "no", x->why);
    return;
  }
  printf("%-8s %-18s %9.4g %-5s %-4s %11.6f %+10.2e %5.3g %13.6e %+10.2e %5.3g %11.5g\n",
         x->engine, x->form, x->mass, x->recommended ? "yes" : "no", x->faithful ? "yes" : "NO",
         x->restitution, x->restitution_rel, x->restitution_phase, x->penetration,
         x->penetration_rel, x->penetration_phase, x->force);
}

static void print_checks(const fb_cp_step *st) {
  printf("%-8s %-18s %9s %-5s %-4s %11s %10s %5s %13s %10s %5s %11s\n", "engine", "form",
         "mass_kg", "recom", "ok", "restitution", "rel", "phase", "penetration_m", "rel", "phase",
         "force_max_n");
  for (int i = 0; i < st->n_checks; i++) print_check(&st->checks[i]);
}

/* an at_step contact's heading: its step, k [N/m], c [N s/m], and what it
 * implies at the design mass and speed v [m/s] */
static void print_at_step(const char *which, const fb_cp_step *st, double k, double c, double v) {
  const fb_cp_rows *rw = &st->rows;
  const int d = rw->n_masses > 1 ? 1 : 0;
  printf("\n== at %sh = %.4g s, the stiffest faithful contact with the same restitution:\n"
         "   k = %.6g N/m, c = %.6g N s/m (h omega_c %.3g); at %.4g kg and %g m/s: restitution "
         "%.4g, peak penetration %.4g m, contact duration %.4g s\n",
         which, rw->lc.h, k, c, rw->h_omega_c, rw->masses[d], v, rw->restitution[d],
         rw->penetration[d], rw->duration[d]);
}

static void print_text(const fb_cp_result *o, const char *case_path, int joint) {
  const fb_cp_request *q = &o->q;
  if (joint >= 0)
    printf("case %s, joint %s: the law of its clearance-%s models%s; effective mass over a "
           "revolution and every direction\n",
           case_path, fb_joint_name(joint), q->law == FB_LAW_HERTZ ? "impact" : "restitution",
           q->law == FB_LAW_HERTZ ? " (its damper not carried), linearised at the joint's "
                                    "expected force" : "");
  printf("contact: %s law, ", fb_law_name(q->law));
  if (q->law == FB_LAW_RESTITUTION)
    printf("k = %g N/m, cr = %g: damper c = %.6g N s/m at the design mass\n", q->stiffness,
           q->restitution, o->c);
  else if (q->law == FB_LAW_LINEAR)
    printf("k = %g N/m, c = %g N s/m\n", q->stiffness, q->damping);
  else if (q->law == FB_LAW_HERTZ)
    printf("K = %g N/m^%g%s; linear spring k = %.6g N/m at %s (penetration %.4g m), damper "
           "c = %.6g N s/m\n", q->stiffness, q->exponent,
           isnan(q->restitution) ? ", undamped" : "", o->k,
           !isnan(q->load) ? "the tangent of the static penetration of the load"
                           : "equal peak penetration of the impact", o->op_penetration, o->c);
  else
    printf("K = %g N/m^%g, cr = %g. Its impact of %.4g kg at %g m/s leaves with restitution "
           "%.6g and reaches %.6g m (peak force %.5g N). As the engines' linear spring-damper "
           "with that restitution and peak penetration at that speed and mass: k = %.6g N/m, "
           "c = %.6g N s/m (its peak force %.5g N, %+.1f %%)\n",
           q->stiffness, q->exponent, q->restitution, o->m0, q->speed, o->law_restitution,
           o->law_penetration, o->law_force, o->k, o->c, o->lin_force,
           100.0 * rel(o->lin_force, o->law_force));
  if (o->damper_floored)
    printf("  (undamped: an ODE row needs a finite CFM, so every row carries the damper of "
           "restitution %g, c = %.4g N s/m)\n", FB_CP_RESTITUTION_MAX, o->c);
  printf("effective mass %g to %g kg, rows designed at %.4g kg; impact speed %g m/s\n",
         q->mass_min, q->mass_max, o->m0, q->speed);
  printf("step h = %.4g s: h omega_c = %.3g at %.4g kg (a run holds h omega_c <= %g)\n", q->h,
         o->given.rows.h_omega_c, q->mass_min, FB_H_OMEGA_C_BOUND);
  if (q->verify) {
    if (isfinite(o->largest_step))
      printf("largest faithful step of this contact: %.4g s (h omega_c %.3g, limited by %s)\n",
             o->largest_step, o->largest_h_omega,
             strcmp(o->largest_limited_by, "rule") == 0
                 ? "the run's bound h omega_c <= 0.5"
                 : "the verification: restitution within 1 %, penetration within 2 %, every "
                   "mass and onset phase");
    else
      printf("largest faithful step of this contact: none down to h omega_c = %g\n",
             FB_CP_H_OMEGA_MIN);
  }
  printf("\n");
  if (o->given.recommended) {
    printf("== your contact at h = %.4g s: recommended%s\n", q->h,
           q->verify ? " (verified below)" : " (not verified: --no-verify)");
    print_rows(&o->given.rows);
  } else {
    printf("== your contact at h = %.4g s: not recommended: %s\n", q->h, o->given.why_not);
  }
  if (o->has_at_step) {
    print_at_step("", &o->at_step, o->at_k, o->at_c, q->speed);
    if (o->at_k > o->k)
      printf("   (stiffer than your contact, which is faithful at this step already)\n");
    print_rows(&o->at_step.rows);
  }
  for (int i = 0; i < o->n_engine_steps; i++) {
    print_at_step(strcmp(o->engine_step[i].engine, "mujoco") == 0 ? "MuJoCo's default step, "
                                                                   : "Gazebo's default step, ",
                  &o->engine_step[i].step, o->engine_step[i].k, o->engine_step[i].c, q->speed);
    print_rows(&o->engine_step[i].step.rows);
  }
  if (o->per_step.present) {
    const fb_cp_per_step *ps = &o->per_step;
    printf("\n== per-step mapping (ODE or Bullet rows set every step from the contact's state):\n"
           "   kp = n K delta^(n-1) (tangent), kd = the law's coefficient of delta', the depth handed\n"
           "   to the row K delta^n / kp; on the contact's effective mass m:\n"
           "   b = m (exp(kd h / m) - 1) / h, a = m (1 - e^{s1 h})(1 - e^{s2 h}) / (exp(-kd h / m) h^2),\n"
           "   soft_erp = h a / b, soft_cfm = 1 / b (s1, s2 the roots of m s^2 + kd s + kp;\n"
           "   fb_contact_row_step). h omega_t at the law's peak: %.3g: %s\n", ps->h_omega_t,
           ps->recommended ? "recommended" : "not recommended at this step (beyond the largest "
                                             "faithful h omega_c of the linear rows)");
  }
  if (!q->verify) return;
  printf("\nverification: single impacts at %g m/s, every onset phase (", q->speed);
  for (int i = 0; i < FB_CP_ONSET_PHASES; i++)
    printf("%s%g", i ? ", " : "", fb_cp_onset_phases[i]);
  printf(" of a step); the worst against the continuous contact (rel = engine / contact - 1); "
         "ok: within %g %% and %g %%\n", 100 * FB_CP_RESTITUTION_TOL, 100 * FB_CP_PENETRATION_TOL);
  if (o->given.n_checks) {
    printf("\nyour contact at h = %.4g s:\n", q->h);
    print_checks(&o->given);
  }
  if (o->has_at_step) {
    printf("\nat_step contact at h = %.4g s:\n", q->h);
    print_checks(&o->at_step);
  }
  for (int i = 0; i < o->n_engine_steps; i++) {
    printf("\nat_step contact at %s's default step h = %.4g s:\n",
           strcmp(o->engine_step[i].engine, "mujoco") == 0 ? "MuJoCo" : "Gazebo",
           o->engine_step[i].h);
    print_checks(&o->engine_step[i].step);
  }
  if (o->per_step.present && o->per_step.h_omega_t <= FB_H_OMEGA_C_BOUND) {
    printf("\nper-step mapping, against the law's own impact at onset phase 0:\n");
    print_check(&o->per_step.check);
  }
  if (!FB_HAVE_MUJOCO) printf("(mujoco not verified: %s)\n", fb_engine_howto(FB_ENGINE_MUJOCO));
  if (!FB_HAVE_BULLET) printf("(bullet not verified: %s)\n", fb_engine_howto(FB_ENGINE_BULLET));
  if (o->failed)
    printf("\n%d recommended row(s) FAILED their verification\n", o->failed);
}

/* ---- flags ------------------------------------------------------------------ */

int fb_cmd_contact_params(int argc, char **argv) {
  static const struct option opts[] = {
      {"law", required_argument, 0, 'L'},       {"stiffness", required_argument, 0, 'k'},
      {"exponent", required_argument, 0, 'n'},  {"restitution", required_argument, 0, 'e'},
      {"damping-n-s-m", required_argument, 0, 'c'}, {"mass-kg", required_argument, 0, 'm'},
      {"h-s", required_argument, 0, 'H'},       {"speed-m-s", required_argument, 0, 'v'},
      {"load-n", required_argument, 0, 'F'},    {"verify", no_argument, 0, 'V'},
      {"no-verify", no_argument, 0, 'N'},       {"json", no_argument, 0, 'j'},
      {"help", no_argument, 0, 'h'},            {"case", required_argument, 0, 'C'},
      {"joint", required_argument, 0, 'J'},     {0, 0, 0, 0}};
  fb_cp_request q;
  fb_cp_request_default(&q);
  int ch, json = 0, m_given = 0, k_given = 0, h_given = 0;
  const char *case_arg = NULL, *joint_arg = NULL;
  const char *P = "contact-params";
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    switch (ch) {
      case 'L':
        q.law = fb_law_parse(optarg);
        if (!(q.law == FB_LAW_LINEAR || q.law == FB_LAW_RESTITUTION || q.law == FB_LAW_HERTZ ||
              q.law == FB_LAW_LANKARANI_NIKRAVESH || q.law == FB_LAW_HUNT_CROSSLEY ||
              q.law == FB_LAW_FLORES || q.law == FB_LAW_GONTHIER))
          return fb_cli_fail(P, 2, "--law '%s': must be restitution, linear, hertz, "
                             "lankarani-nikravesh, hunt-crossley, flores or gonthier", optarg);
        break;
      case 'k': if (!fb_cli_double(P, "--stiffness", optarg, &q.stiffness)) return 2; k_given = 1; break;
      case 'n': if (!fb_cli_double(P, "--exponent", optarg, &q.exponent)) return 2; break;
      case 'e': if (!fb_cli_double(P, "--restitution", optarg, &q.restitution)) return 2; break;
      case 'c': if (!fb_cli_double(P, "--damping-n-s-m", optarg, &q.damping)) return 2; break;
      case 'm':
        if (!parse_mass(optarg, &q))
          return fb_cli_fail(P, 2, "--mass-kg '%s': a mass in kg or a range A:B", optarg);
        m_given = 1;
        break;
      case 'C': case_arg = optarg; break;
      case 'J': joint_arg = optarg; break;
      case 'H': if (!fb_cli_double(P, "--h-s", optarg, &q.h)) return 2; h_given = 1; break;
      case 'v': if (!fb_cli_double(P, "--speed-m-s", optarg, &q.speed)) return 2; break;
      case 'F': if (!fb_cli_double(P, "--load-n", optarg, &q.load)) return 2; break;
      case 'V': q.verify = 1; break;
      case 'N': q.verify = 0; break;
      case 'j': json = 1; break;
      case 'h': fputs(params_help, stdout); return 0;
      default: return fb_cli_fail(P, 2, "unknown option '%s'; see fourbar contact-params --help",
                                  argv[optind - 1]);
    }
  }
  if (optind < argc) return fb_cli_fail(P, 2, "unexpected argument '%s'", argv[optind]);
  char case_path[4096] = "";
  int joint = -1;
  if (joint_arg && !case_arg)
    return fb_cli_fail(P, 2, "--joint %s: names a joint of a case; give --case too", joint_arg);
  if (case_arg) {
    if (k_given || !isnan(q.restitution) || !isnan(q.damping) || !isnan(q.exponent) || m_given ||
        !isnan(q.load))
      return fb_cli_fail(P, 2, "--case takes the stiffness, exponent, damping or restitution, "
                         "effective mass and operating point from the case: drop %s",
                         k_given ? "--stiffness" : !isnan(q.restitution) ? "--restitution"
                         : !isnan(q.damping) ? "--damping-n-s-m" : !isnan(q.exponent) ? "--exponent"
                         : m_given ? "--mass-kg" : "--load-n");
    if (q.law != FB_LAW_RESTITUTION && q.law != FB_LAW_HERTZ)
      return fb_cli_fail(P, 2, "--law %s with --case: a case's clearance models use the "
                         "restitution law (--law restitution, the default) and the impact law "
                         "(--law hertz)", fb_law_name(q.law));
    fb_cli_case_path(case_path, sizeof case_path, case_arg);
    fb_case cs;
    fb_diag cd;
    if (fb_casefile_load(&cs, case_path, NULL, 0, &cd) != FB_OK)
      return fb_cli_fail(P, 2, "%s", cd.msg);
    if (joint_arg) {
      for (int j = 0; j < 4; j++)
        if (strcmp(joint_arg, fb_joint_name(j)) == 0) joint = j;
      if (joint < 0)
        return fb_cli_fail(P, 2, "--joint '%s': must be ground-crank, crank-coupler, "
                           "coupler-follower or follower-ground", joint_arg);
    } else {
      int n = 0;
      for (int j = 0; j < 4; j++)
        if (cs.clearance.mask & (1 << j)) joint = j, n++;
      if (n > 1)
        return fb_cli_fail(P, 2, "--case %s has %d clearance joints: name one with --joint",
                           case_path, n);
    }
    if (fb_cp_request_from_case(&q, &cs, joint, &cd) != FB_OK)
      return fb_cli_fail(P, 2, "--case %s: %s", case_path, cd.msg);
  }
  /* no step given: also the answers at MuJoCo's and Gazebo's default steps */
  q.engine_steps = !h_given;
  static fb_cp_result o;
  fb_diag diag;
  fb_status st = fb_cp_run(&o, &q, &diag);
  if (st != FB_OK) return fb_cli_fail(P, st == FB_ERR_NUMERIC ? 1 : 2, "%s", diag.msg);
  if (json) print_json(&o, case_path, joint);
  else print_text(&o, case_path, joint);
  return o.failed ? 1 : 0;
}
