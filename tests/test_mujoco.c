/* The four-bar in MuJoCo against the exact analytic solution (ideal loop)
 * and the reference dynamics (crank-coupler clearance joint); the
 * slider-crank's tests follow the four-bar's (their own sketch there).
 *
 *            C  connect equality (loop closure, direct solref k = 1/h^2, b = 1/h)
 *           / \
 *  coupler /   \ follower      hinges A, B, D (axis +z) in a kinematic tree:
 *         B     \              world -> crank -> coupler, world -> follower;
 *  crank /       \             the crank a flywheel (armature 1e6 kg m^2)
 *       A ------- D            started at the crank speed; gravity along -y
 *
 * Semi-implicit Euler on a loop closed in one step: the velocity series is
 * first-order accurate pointwise, and a peak value (where d omega/dt = 0) is
 * moved to second order, so halving h divides the peak error by about 4.
 * With a clearance joint at B the coupler is free at the crank pin and the
 * project's contact law acts through mjcb_passive; RK4 then integrates the
 * same equations as the reference (minimal coordinates, rk8pd at 1e-10). */
#include <string.h>
#include <unistd.h>

#include <jansson.h>

#include "casefile.h"
#include "effective_mass.h"
#include "engine.h"
#include "fb_test.h"
#include "invdyn.h"
#include "mujoco_scene.h"
#include "outcome_text.h"
#include "report.h"
#include "run.h"
#include "slider_crank_invdyn.h"

/* the acceptance bound on peak angular velocity at the default step
 * (measured: 1.9e-6) */
#define PEAK_OMEGA_REL_TOL 1e-4
/* alpha peaks from qacc at the same instants (measured: 2.5e-6); the
 * acceptance bound of omega, which they have no reason to exceed */
#define PEAK_ALPHA_REL_TOL 1e-4
/* the flywheel's speed changes by (reaction torque / armature) ~1e-4 rad/s^2:
 * over 3 revolutions (18 ms) ~1e-8 rad; measured 5.4e-8 rad. 1e-6 rad is
 * still 1e-4 of one step's crank rotation at h = 1e-5 s */
#define CRANK_ANGLE_TOL_RAD 1e-6
/* the loop closure's violation stays far below the smallest radial
 * clearance studied (2.5 um): measured 1.1e-7 m */
#define DRIFT_TOL_M 1e-6
/* halving h divides a second-order peak error by 4; the band allows 20 %
 * of higher-order terms and sampling of the peak on the grid */
#define SECOND_ORDER_LO 3.2
#define SECOND_ORDER_HI 4.8
/* the acceptance bound on the peak contact force of
 * mujoco-clearance-impact against the reference (measured: +0.03 %) */
#define FORCE_PEAK_REL_TOL 0.01
/* penetration peak against the reference: the force law's inverse of the
 * force bound (delta ~ F^(2/3)), measured -0.11 % */
#define PEN_PEAK_REL_TOL 0.01
/* the impact law in RK4 at h = 1e-5 s against the reference, omega peaks:
 * measured 1e-5; the ideal model's bound */
#define CLEARANCE_OMEGA_REL_TOL 1e-4
/* the restitution law's damper force c ddot jumps at contact onset, which a
 * fixed step does not locate: measured -4.3 % peak force at h = 1e-5 s
 * (rk4), +2.1 % at 5e-6 (+0.3 % at 1e-5 with the damper on the effective
 * mass, issue 15); 78 impacts, each onset within one step of the
 * reference's. 5 %: the measured error with a margin of a sixth */
#define RESTITUTION_FORCE_REL_TOL 0.05
/* impact episodes: with the restitution law's damper on the mechanism's
 * effective mass (issue 15; 78 impacts before, on the reduced mass) the
 * reference has 29 at h = 1e-5 s and MuJoCo 33: the contact sequence is
 * chaotic after the first impacts, so the count is held to the 15 %
 * of the reference's, widened by the reference's own uncertainty in that
 * count (issue 28: its error_estimate, a second integration at 1e-13; at
 * its tolerance 1e-12 the reference counts 28, at 1e-13 29, so a bound on
 * 28 alone would test noise) */
#define RESTITUTION_IMPACTS_REL_TOL 0.15

/* MuJoCo's effective mass along the contact normal (from its own mass
 * matrix) must lie within the range the engine-free model gives over all
 * directions and a revolution (effective_mass.h, maximal coordinates): the
 * configurations differ by the pin's microns of play and the crank's
 * armature is finite, 1 % covers both */
#define EFFECTIVE_MASS_REL_TOL 0.01

/* runs the paper case with the given models and overrides into *r */
static void run(fb_run *r, const char *models, const char **sets, int n) {
  const char *all[9];
  char ms[256];
  snprintf(ms, sizeof ms, "run.models=%s", models);
  all[0] = ms;
  /* the step these figures were measured at (the paper case's default is
   * h_s = auto); a later --set wins */
  all[1] = "solver.h_s=1e-5";
  for (int i = 0; i < n; i++) all[i + 2] = sets[i];
  fb_case c;
  fb_test_paper_case(&c, all, n + 2);
  fb_diag d;
  if (fb_run_case(r, &c, NULL, NULL, &d) != FB_OK) fail_msg("run failed: %s", d.msg);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].run.stop.kind != FB_STOP_NONE)
      fail_msg("%s: stopped (%s)", r->model[i].run.name, fb_stop_kind_name(r->model[i].run.stop.kind));
}

static double worst(double a, double b, double c, double d) {
  return fmax(fmax(fabs(a), fabs(b)), fmax(fabs(c), fabs(d)));
}

static double omega_peak_rel(const fb_error *e) {
  return worst(e->coupler.omega_max_rel, e->coupler.omega_min_rel, e->follower.omega_max_rel,
               e->follower.omega_min_rel);
}

static double alpha_peak_rel(const fb_error *e) {
  return worst(e->coupler.alpha_max_rel, e->coupler.alpha_min_rel, e->follower.alpha_max_rel,
               e->follower.alpha_min_rel);
}

static void test_ideal_models_match_analytic(void **state) {
  (void)state;
  static fb_run r;
  run(&r, "mujoco-ideal-nominal, mujoco-ideal-stackup", NULL, 0);
  for (int i = 0; i < 2; i++) {
    const fb_model_result *m = &r.model[i];
    assert_string_equal(fb_engine_name(m->run.model->engine), "mujoco");
    /* [solver] builder = auto keeps MuJoCo's ideal models in its own scene */
    assert_string_equal(m->run.builder, "hand");
    assert_true(m->has_error);
    const double wo = omega_peak_rel(&m->error), wa = alpha_peak_rel(&m->error);
    report_residual(m->run.name, 0, 0);
    report_residual("  peak omega rel, h = 1e-5", wo, PEAK_OMEGA_REL_TOL);
    report_residual("  peak alpha rel, h = 1e-5", wa, PEAK_ALPHA_REL_TOL);
    report_residual("  crank angle err [rad]", m->error.crank_angle_err_max, CRANK_ANGLE_TOL_RAD);
    report_residual("  loop drift [m]", m->run.joint_drift_max, DRIFT_TOL_M);
    assert_true(wo < PEAK_OMEGA_REL_TOL);
    assert_true(wa < PEAK_ALPHA_REL_TOL);
    assert_true(m->error.crank_angle_err_max < CRANK_ANGLE_TOL_RAD);
    assert_true(m->run.joint_drift_max > 0.0 && m->run.joint_drift_max < DRIFT_TOL_M);
  }
  fb_run_free(&r);
}

static void test_ideal_second_order_peaks(void **state) {
  (void)state;
  static fb_run r1, r2;
  const char *s1[] = {"solver.h_s=4e-5"}, *s2[] = {"solver.h_s=2e-5"};
  run(&r1, "mujoco-ideal-nominal", s1, 1);
  run(&r2, "mujoco-ideal-nominal", s2, 1);
  const double r = fabs(r1.model[0].error.coupler.omega_max_rel) /
                   fabs(r2.model[0].error.coupler.omega_max_rel);
  report_residual("peak omega error ratio h / (h/2)", r, SECOND_ORDER_LO);
  assert_true(r > SECOND_ORDER_LO && r < SECOND_ORDER_HI);
  fb_run_free(&r1);
  fb_run_free(&r2);
}

static void test_clearance_impact_matches_reference(void **state) {
  (void)state;
  static fb_run r;
  run(&r, "mujoco-clearance-impact, reference", NULL, 0);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  assert_true(m->has_spikes);
  assert_string_equal(m->ref_name, "reference");
  const fb_reference_error *re = &m->ref_error;
  report_residual("mujoco impact force peak rel", re->force_max_rel, FORCE_PEAK_REL_TOL);
  report_residual("mujoco impact penetration peak rel", re->penetration_max_rel, PEN_PEAK_REL_TOL);
  const double wo = worst(re->coupler.omega_max_rel, re->coupler.omega_min_rel,
                          re->follower.omega_max_rel, re->follower.omega_min_rel);
  report_residual("mujoco impact omega peak rel vs reference", wo, CLEARANCE_OMEGA_REL_TOL);
  assert_true(fabs(re->force_max_rel) < FORCE_PEAK_REL_TOL);
  assert_true(fabs(re->penetration_max_rel) < PEN_PEAK_REL_TOL);
  assert_true(wo < CLEARANCE_OMEGA_REL_TOL);
  assert_int_equal(re->impacts, re->impacts_reference);
  /* provenance: the effective mass along the normal, from MuJoCo's mass
   * matrix, against the range CONTACT_MASS_* measured independently */
  assert_true(m->run.has_provenance);
  const fb_contact_provenance *p = &m->run.provenance[FB_JOINT_B];
  double lo = INFINITY, hi = 0.0;
  for (int k = 0; k < 720; k++) {
    fb_linkage_state st;
    fb_diag d;
    const fb_linkage *lk = &m->run.lengths;
    assert_int_equal(fb_linkage_solve(&st, lk, r.c.branch, k * M_PI / 360.0, 1.0, 0.0, &d), FB_OK);
    fb_mechanism mech;
    fb_mechanism_from_state(&mech, lk, &st, r.c.link, 1 << FB_JOINT_B);
    double w[4][2][2], a, b;
    assert_int_equal(fb_effective_mass_tensor(w, &mech, &d), FB_OK);
    fb_effective_mass_range(w[FB_JOINT_B], &a, &b);
    lo = fmin(lo, a);
    hi = fmax(hi, b);
  }
  report_residual("mujoco effective mass min [kg]", p->mass_eff_min, lo);
  report_residual("mujoco effective mass max [kg]", p->mass_eff_max, hi);
  report_residual("mujoco impact h omega_c max", p->h_omega_max, 0);
  assert_true(p->contact_steps > 0);
  assert_true(p->mass_eff_min >= lo * (1.0 - EFFECTIVE_MASS_REL_TOL));
  assert_true(p->mass_eff_max <= hi * (1.0 + EFFECTIVE_MASS_REL_TOL));
  assert_true(isnan(p->erp_max));
  /* MuJoCo has no ERP/CFM and maps nothing: its law is an applied force.
   * summary.json keeps the contact keys with null figures and says so in
   * `mapping`; the printed table shows "-", never "nan" */
  json_t *sum = fb_report_summary_json(&r, NULL);
  /* who built it: [solver] builder = auto takes MuJoCo's clearance models
   * through its kit binding (the reference has no builder) */
  json_t *models = json_object_get(sum, "models");
  assert_string_equal(json_string_value(json_object_get(json_array_get(models, 0), "builder")),
                      "kit");
  assert_true(json_is_null(json_object_get(json_array_get(models, 1), "builder")));
  json_t *c0 = json_array_get(json_object_get(json_array_get(json_object_get(sum, "models"), 0),
                                              "contact"), 0);
  assert_non_null(c0);
  assert_true(json_is_null(json_object_get(c0, "erp_max")));
  assert_true(json_is_null(json_object_get(c0, "cfm_min")));
  assert_string_equal(json_string_value(json_object_get(c0, "mapping")), "none (applied force)");
  assert_true(json_is_real(json_object_get(c0, "h_omega_c_max")));
  json_decref(sum);
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  fb_report_print_table(f, &r);
  fclose(f);
  /* the contact table's law row of the model (its model column is as wide
   * as the run's longest model name) */
  const char *contact = strstr(text, "\ncontact (");
  assert_non_null(contact);
  const char *row = strstr(contact, "\nmujoco-clearance-impact ");
  assert_non_null(row);
  assert_non_null(strstr(row, "crank-coupler"));
  const char *eol = strchr(row + 1, '\n');
  char line[256];
  snprintf(line, sizeof line, "%.*s", (int)(eol ? eol - row - 1 : 200), row + 1);
  if (strstr(line, "nan") || strstr(line, "matched") || !strstr(line, "none (applied force)"))
    fail_msg("contact row: %s", line);
  free(text);
  fb_run_free(&r);
}

/* [solver] h_s = adaptive (step_control.h) on the paper case, the model
 * through MuJoCo's kit binding (the default builder): peak force and
 * penetration within 3e-3 and the coupler alpha spike within 1e-2 of the
 * reference, impacts equal, with about 3,700 steps per revolution against
 * 60,000 at the 1e-6 s grid. Measured +2.3e-3, +1.1e-3, -3.9e-3 (7,388
 * steps in 2 revolutions). The peaks' 1e-3 is not resolved by either
 * builder at the step's accuracy: the smallest step, 1e-6 s, leaves
 * h omega_c at 1.22 in the impacts, and the peak force moves by about 1e-3
 * with the schedule (accuracy 0.3 against 0.1: the kit +2.3e-3 and
 * +1.1e-3; the hand-built scene, same steps within 0.2 %, +2.0e-4 and
 * +1.4e-3); at the fixed 1e-6 s grid both are within 2.2e-4. 3e-3 holds
 * the measured 2.3e-3 with a third to spare; a schedule that left the
 * impact's step (the hold) would move the force by percents. */
#define ADAPTIVE_PEAK_REL_TOL 3e-3
#define ADAPTIVE_SPIKE_REL_TOL 1e-2
static void test_clearance_impact_adaptive(void **state) {
  (void)state;
  static fb_run r;
  const char *sets[] = {"solver.h_s=adaptive", "run.revolutions=2"};
  run(&r, "mujoco-clearance-impact, reference", sets, 2);
  const fb_model_result *m = &r.model[0], *ref = &r.model[1];
  assert_true(m->has_ref_error);
  const fb_reference_error *re = &m->ref_error;
  const double spike = fmax(fabs(m->peaks.coupler.alpha_max), fabs(m->peaks.coupler.alpha_min));
  const double spike_ref = fmax(fabs(ref->peaks.coupler.alpha_max), fabs(ref->peaks.coupler.alpha_min));
  report_residual("mujoco adaptive force peak rel", re->force_max_rel, ADAPTIVE_PEAK_REL_TOL);
  report_residual("mujoco adaptive penetration peak rel", re->penetration_max_rel, ADAPTIVE_PEAK_REL_TOL);
  report_residual("mujoco adaptive coupler spike rel", spike / spike_ref - 1.0, ADAPTIVE_SPIKE_REL_TOL);
  assert_true(fabs(re->force_max_rel) < ADAPTIVE_PEAK_REL_TOL);
  assert_true(fabs(re->penetration_max_rel) < ADAPTIVE_PEAK_REL_TOL);
  assert_true(fabs(spike / spike_ref - 1.0) < ADAPTIVE_SPIKE_REL_TOL);
  assert_int_equal(re->impacts, re->impacts_reference);
  /* the steps: on the grid's multiples, far fewer than the samples */
  assert_true(m->run.has_step_stats);
  assert_true(m->run.step_stats.steps < m->run.series.n / 5);
  assert_true(m->run.step_stats.h_max <= 2e-5 * (1 + 1e-12));
  fb_run_free(&r);
}

/* the adaptive step follows the project's law only: MuJoCo's native
 * contacts are refused before the model runs */
/* refused by the case check before anything runs and, should a case reach
 * it unchecked, by the engine itself */
static void test_adaptive_refuses_native(void **state) {
  (void)state;
  const char *sets[] = {"run.models=mujoco-clearance-native", "solver.h_s=adaptive",
                        "run.revolutions=2"};
  char paper[4096];
  const char *dir = getenv("FOURBAR_CASES_DIR");
  snprintf(paper, sizeof paper, "%s/paper_crank_rocker.ini", dir ? dir : "cases");
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper, sets, 3, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "h_s = adaptive"));
  assert_non_null(strstr(d.msg, "native"));
  /* the scene of a case with the same law, and the native model run in it */
  sets[0] = "run.models=mujoco-clearance-restitution";
  fb_test_paper_case(&c, sets, 3);
  fb_scene *def = malloc(sizeof *def);
  assert_int_equal(fb_scene_from_case(def, &c, &d), FB_OK);
  fb_model_run mr;
  assert_int_not_equal(fb_model_run_one(&mr, def, fb_model_find("mujoco-clearance-native"), NULL,
                                        NULL, &d), FB_OK);
  fb_model_run_free(&mr);
  assert_non_null(strstr(d.msg, "h_s = adaptive"));
  assert_non_null(strstr(d.msg, "native"));
  free(def);
}

static void test_clearance_restitution_matches_reference(void **state) {
  (void)state;
  static fb_run r;
  run(&r, "mujoco-clearance-restitution, reference-restitution", NULL, 0);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  const fb_reference_error *re = &m->ref_error;
  report_residual("mujoco restitution force peak rel", re->force_max_rel,
                  RESTITUTION_FORCE_REL_TOL);
  const fb_model_result *ref = &r.model[1];
  assert_true(ref->has_ref_estimate);
  const double ref_spread =
      fabs((double)(ref->ref_estimate.impacts - ref->ref_estimate.impacts_reference));
  const double impacts_off = fabs((double)(re->impacts - re->impacts_reference));
  const double impacts_bound = RESTITUTION_IMPACTS_REL_TOL * re->impacts_reference + ref_spread;
  report_residual("mujoco restitution impacts off (count)", impacts_off, impacts_bound);
  assert_true(fabs(re->force_max_rel) < RESTITUTION_FORCE_REL_TOL);
  assert_true(re->impacts_reference > 0 && impacts_off <= impacts_bound);
  fb_run_free(&r);
}

/* MuJoCo's own constraint solver on the clearance, bore = tendon (the
 * default): a spatial tendon from the hole's centre to the pin's limited to
 * the radial clearance, its limit row carrying the restitution law's spring
 * and damper in the force form (solref per unit of MuJoCo's diagonal
 * approximation, impedance 1e-4: mujoco_scene.c, native_solref_update). At
 * the automatic step on the paper case it measured peak force +3.0 %,
 * penetration +3.0 %, 27 contact episodes of the reference's 27 (the facets
 * before it: +27 %, +3.5 %, 282). Issue 27's target: peak force within
 * 10 % at the automatic step; the penetration is held to the same 10 % */
#define NATIVE_FORCE_REL_TOL 0.10
#define NATIVE_PEN_REL_TOL 0.10
/* in continuous contact (FB_STATE_CONTINUOUS at both) the penetration
 * carries the load as the law's spring does: measured +0.010 %. The
 * acceleration-level form contact-params prints (impedance 0.9999, per unit
 * of the effective mass) gives the row MuJoCo's reference acceleration
 * whatever else pushes, and measured -94 % here (and 1190 episodes) */
#define NATIVE_PERSISTENT_PEN_REL_TOL 0.05

static void test_clearance_native_tendon_matches_reference(void **state) {
  (void)state;
  static fb_run r;
  const char *sets[] = {"solver.h_s=auto"};
  run(&r, "mujoco-clearance-native, reference-restitution", sets, 1);
  const fb_model_result *m = &r.model[0], *ref = &r.model[1];
  assert_true(m->has_ref_error);
  const fb_reference_error *re = &m->ref_error;
  report_residual("mujoco native (tendon) force peak rel, auto", re->force_max_rel,
                  NATIVE_FORCE_REL_TOL);
  report_residual("mujoco native (tendon) penetration peak rel, auto", re->penetration_max_rel,
                  NATIVE_PEN_REL_TOL);
  report_residual("mujoco native (tendon) persistent penetration rel",
                  re->persistent_penetration_rel, NATIVE_PERSISTENT_PEN_REL_TOL);
  /* episodes: the bound of the passive-force model's test (the sequence is
   * chaotic past the first impacts; the reference's own spread added) */
  assert_true(ref->has_ref_estimate);
  const double ref_spread =
      fabs((double)(ref->ref_estimate.impacts - ref->ref_estimate.impacts_reference));
  const double impacts_off = fabs((double)(re->impacts - re->impacts_reference));
  const double impacts_bound = RESTITUTION_IMPACTS_REL_TOL * re->impacts_reference + ref_spread;
  report_residual("mujoco native (tendon) impacts off (count)", impacts_off, impacts_bound);
  assert_true(fabs(re->force_max_rel) < NATIVE_FORCE_REL_TOL);
  assert_true(fabs(re->penetration_max_rel) < NATIVE_PEN_REL_TOL);
  assert_true(re->persistent_samples > 0);
  assert_true(fabs(re->persistent_penetration_rel) < NATIVE_PERSISTENT_PEN_REL_TOL);
  assert_true(re->impacts_reference > 0 && impacts_off <= impacts_bound);
  /* summary.json names the bore */
  json_t *sum = fb_report_summary_json(&r, NULL);
  json_t *mj = json_object_get(json_array_get(json_object_get(sum, "models"), 0), "mujoco");
  assert_string_equal(json_string_value(json_object_get(mj, "native_bore")), "tendon");
  json_decref(sum);
  fb_run_free(&r);
}

/* bore = facets (the pin a sphere in a ring of 64 boxes, the law as direct
 * solref per unit of the mechanism's effective mass along the eccentricity
 * at impedance 0.9999, updated every step: docs/contact-params.md), kept
 * selectable so that the facet study stays reproducible: a
 * characterisation, not a faithful model. Before the per-step effective
 * mass (the law's 0.085 kg for every contact) it measured at h = 1e-5 s
 * peak force +113 %, penetration -44 %; with it +26 %, -11 %, and still
 * 472 contact episodes against the reference's 28 (several boxes touch the
 * conformal pin at once, and the contacts carry no steady load: continuous
 * contact penetration -85 %). Through MuJoCo's kit binding (the default
 * builder; its tree closes no loop, so the facets carry the steady load)
 * it measures +21 %, +22 % and 43 episodes against 29. The bands guard the
 * measured differences: the old mass moves the force above the band and
 * the penetration below it, a faithful collider would move the force below
 * it */
#define FACETS_FORCE_REL_LO 0.1
#define FACETS_FORCE_REL_HI 0.5
#define FACETS_PEN_REL_LO (-0.25)
#define FACETS_PEN_REL_HI 0.35

static void test_clearance_native_facets_characterised(void **state) {
  (void)state;
  static fb_run r;
  const char *sets[] = {"mujoco.native_bore=facets"};
  run(&r, "mujoco-clearance-native, reference-restitution", sets, 1);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  const fb_reference_error *re = &m->ref_error;
  report_residual("mujoco native (facets) force peak rel", re->force_max_rel, FACETS_FORCE_REL_HI);
  report_residual("mujoco native (facets) penetration peak rel", re->penetration_max_rel,
                  FACETS_PEN_REL_LO);
  report_residual("mujoco native (facets) impacts", re->impacts, re->impacts_reference);
  assert_true(re->force_max_rel > FACETS_FORCE_REL_LO && re->force_max_rel < FACETS_FORCE_REL_HI);
  assert_true(re->penetration_max_rel > FACETS_PEN_REL_LO &&
              re->penetration_max_rel < FACETS_PEN_REL_HI);
  assert_true(re->impacts > re->impacts_reference); /* chatter on the facets */
  json_t *sum = fb_report_summary_json(&r, NULL);
  json_t *mj = json_object_get(json_array_get(json_object_get(sum, "models"), 0), "mujoco");
  assert_string_equal(json_string_value(json_object_get(mj, "native_bore")), "facets");
  json_decref(sum);
  fb_run_free(&r);
}

/* MuJoCo's reactions (Newton-Euler after its constraint stage, the connect
 * equality's force, the flywheel's torque) at the sample's state against the
 * inverse dynamics of the exact motion at the same crank angle. Pointwise,
 * semi-implicit Euler is first order (the velocities lag by about a step),
 * and so are the forces: measured, as a share of the largest reaction
 * (reactions / drive torque), 6.8e-4 / 9.9e-4 at h = 4e-5 s, 3.3e-4 / 5.1e-4
 * at 2e-5, 1.6e-4 / 2.6e-4 at 1e-5, 8.0e-5 / 1.3e-4 at 5e-6. 5e-4 at the
 * default 1e-5 s leaves a factor 2 */
#define REACTION_REL_TOL 5e-4

static void test_reactions_match_inverse_dynamics(void **state) {
  (void)state;
  static fb_run r;
  run(&r, "mujoco-ideal-nominal", NULL, 0);
  const fb_series *s = &r.model[0].run.series;
  assert_true(s->has_loads);
  const double w = fb_case_omega2(&r.c);
  double err = 0, fbig = 0, terr = 0, tmax = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->t[i] < r.t_window) continue;
    fb_reactions q;
    fb_diag d;
    assert_int_equal(fb_invdyn_solve(&q, &r.c.nominal, r.c.branch, r.c.link, r.c.gravity,
                                     s->crank_angle[i], w, &d),
                     FB_OK);
    for (int j = 0; j < 4; j++) {
      err = fmax(err, hypot(s->reaction[j][0][i] - q.force[j][0], s->reaction[j][1][i] - q.force[j][1]));
      fbig = fmax(fbig, hypot(q.force[j][0], q.force[j][1]));
    }
    terr = fmax(terr, fabs(s->drive_torque[i] - q.drive_torque));
    tmax = fmax(tmax, fabs(q.drive_torque));
  }
  report_residual("joint reactions, MuJoCo vs inverse dynamics", err / fbig, REACTION_REL_TOL);
  report_residual("drive torque, MuJoCo vs inverse dynamics", terr / tmax, REACTION_REL_TOL);
  assert_true(err / fbig < REACTION_REL_TOL);
  assert_true(terr / tmax < REACTION_REL_TOL);
  fb_run_free(&r);
}

/* the scene stage's view of the paper case for one model */
static void view(fb_scene *def, fb_model_scene *sm, const char *model, const char **sets,
                 int n) {
  fb_case c;
  /* the step the MJCF figures were written for (the paper case's default is
   * h_s = auto); a later --set wins */
  const char *all[9] = {"solver.h_s=1e-5"};
  for (int i = 0; i < n && i < 8; i++) all[i + 1] = sets[i];
  fb_test_paper_case(&c, all, n + 1);
  c.model_count = 1;
  snprintf(c.models[0], sizeof c.models[0], "%s", model);
  fb_diag d;
  if (fb_scene_from_case(def, &c, &d) != FB_OK) fail_msg("%s", d.msg);
  if (fb_scene_select(sm, def, fb_model_find(model), &d) != FB_OK) fail_msg("%s", d.msg);
}

static void test_mjcf_from_the_definition(void **state) {
  (void)state;
  static fb_scene def;
  fb_model_scene sm;
  view(&def, &sm, "mujoco-ideal-nominal", NULL, 0);
  static char buf[16384];
  fb_diag d;
  assert_int_equal(fb_mujoco_mjcf(buf, sizeof buf, &sm, &d), FB_OK);
  /* the lengths round-trip: printed with 17 significant digits */
  assert_non_null(strstr(buf, "<body name=\"coupler\" pos=\"0.108 0 0\""));
  assert_non_null(strstr(buf, "<connect name=\"loop\""));
  assert_non_null(strstr(buf, "solref=\"-9999999999.99"));  /* -1/h^2, the direct form */
  assert_non_null(strstr(buf, "integrator=\"Euler\""));
  /* a clearance joint at C: no loop equality, the contact closes the loop */
  const char *at_c[] = {"clearance.joints=coupler-follower"};
  view(&def, &sm, "mujoco-clearance-impact", at_c, 1);
  assert_int_equal(fb_mujoco_mjcf(buf, sizeof buf, &sm, &d), FB_OK);
  assert_null(strstr(buf, "<connect"));
  assert_non_null(strstr(buf, "integrator=\"RK4\""));
  /* the native model's bore: a tendon from the hole's centre to the pin's,
   * limited to the radial clearance (14.5 um), and no contact geoms; or the
   * ring of boxes (64) and a sphere pin */
  static char big[65536];
  view(&def, &sm, "mujoco-clearance-native", NULL, 0);
  assert_int_equal(fb_mujoco_mjcf(big, sizeof big, &sm, &d), FB_OK);
  assert_non_null(strstr(big, "<spatial name=\"B_bore\" limited=\"true\" range=\"0 1.45"));
  assert_non_null(strstr(big, "<site site=\"B_hole\"/>"));
  assert_null(strstr(big, "type=\"box\""));
  assert_null(strstr(big, "B_pin_geom"));
  const char *facets[] = {"mujoco.native_bore=facets"};
  view(&def, &sm, "mujoco-clearance-native", facets, 1);
  assert_int_equal(fb_mujoco_mjcf(big, sizeof big, &sm, &d), FB_OK);
  assert_null(strstr(big, "<tendon>"));
  assert_non_null(strstr(big, "B_pin_geom"));
  size_t boxes = 0;
  for (const char *q = big; (q = strstr(q, "type=\"box\"")) != NULL; q++) boxes++;
  assert_int_equal(boxes, 64);
  view(&def, &sm, "mujoco-clearance-impact", at_c, 1);
  /* too small a buffer is an error, not a truncated model */
  assert_int_equal(fb_mujoco_mjcf(buf, 100, &sm, &d), FB_ERR_RANGE);
  /* the definition is checked first */
  def.mujoco.loop_impedance = 1.0;
  fb_mujoco_scene *s = NULL;
  assert_int_equal(fb_mujoco_scene_create(&s, &sm, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "loop_impedance"));
  assert_null(s);
}

/* ---- the slider-crank (issue 45) ----
 *
 *                  B
 *                 / \            world -> crank (hinge A, the flywheel)
 *          crank /   \ coupler            -> coupler, the rod (hinge B);
 *               /     \          world -> slider (slide along +x at
 *              A       [ C ]              y = offset); the piston pin C
 *                 - - - - - - -> x  closed by the connect equality (ideal)
 *                                   or by the law through mjcb_passive
 *
 * Two cases: the shipped cases/slider_crank_flores.ini (crank 50 mm, rod
 * 120 mm, no offset, 5000 rpm, radial clearance 500 um, h_s = auto = 2e-6 s)
 * and this milder one of the test's own (offset 6 mm, stack-up tolerances,
 * 2000 rpm, 100 um, the crank started at 20 deg; h_s = auto = 2.82e-6 s). */
static const char *const SC_CASE_TEXT =
    "[case]\n"
    "name = sc_mujoco\n"
    "[linkage]\n"
    "type = slider-crank\n"
    "crank_mm = 50\n"
    "coupler_mm = 120\n"
    "offset_mm = 6\n"
    "crank_angle0_deg = 20\n"
    "[tolerance]\n"
    "crank_plus_minus_mm = 0.1\n"
    "coupler_plus_minus_mm = 0.1\n"
    "[mass]\n"
    "slider_kg = 0.14\n"
    "[drive]\n"
    "speed_rpm = 2000\n"
    "[pin]\n"
    "radial_clearance_um = 100\n"
    "[clearance]\n"
    "joints = coupler-slider\n"
    "[run]\n"
    "models = analytic\n"
    "revolutions = 2\n"
    "ensemble = 1\n";

/* the acceptance bound of issue 45 on the ideal models' peaks (rod omega and
 * alpha, slider v and a) at the automatic step; measured 7.9e-7 on the
 * shipped case, 2.4e-7 on the test's own */
#define SC_IDEAL_PEAK_REL_TOL 1e-4
/* the bound on peak force and penetration against the reference
 * (matched impacts) at a step that resolves the impact law's damper (below) */
#define SC_CLEARANCE_PEAK_REL_TOL 0.01
/* The impact law's damper with the four-bar's c_max = 1e4 N s/m reaches
 * its full value within d_max = 1 um of penetration, 0.23 us at a 4.3 m/s
 * impact, a ninth of a 2e-6 s step; an explicit fixed step meets that onset
 * at an arbitrary phase of a step (RK4: the force enters at its last
 * stage), which leaves the first sample's impulse first-order wrong.
 * Measured on flores with that damper (before the case set its own for its
 * restitution, 480 N s/m): matched impacts' largest error 3.2 % (force) and
 * 1.5 % (penetration) at 2e-6 s; 4.1 % / 1.4 % at 1e-6 s; 0.69 % / 0.11 % at
 * 5e-7 s; 0.88 % / 0.02 % at 2.5e-7 s. The test's own case keeps that damper
 * and is held to 1 % at the step that resolves the onset [s]: */
#define SC_FINE_H_S "2.5e-7"
/* each law's first impacts one by one on flores at its automatic step
 * (before the rattling's chaos parts the sequences; the restitution model
 * leaves its reference at 11.8 ms after 18 matched impacts, the impact
 * model at 8.4 ms): measured within 0.24 % (restitution) and 0.27 %
 * (impact law) */
#define SC_FIRST_IMPACT_REL_TOL 0.01
/* MuJoCo's effective mass along the normal (its mass matrix with the slide
 * and the flywheel's finite armature) against the closed form's range over a
 * revolution (effective_mass.h, the rod about the held B and the slider
 * along x): the pin's 500 um of play moves the configuration; 1 %, as the
 * four-bar's EFFECTIVE_MASS_REL_TOL */
#define SC_EFFECTIVE_MASS_REL_TOL 0.01
/* reactions against the slider-crank's inverse dynamics at the sample's
 * crank angle, as a share of the largest: first order in h like the
 * four-bar's (REACTION_REL_TOL, 1.6e-4 at 1e-5 s); measured 2.1e-5 /
 * 4.5e-5 (reactions / drive torque) at the test case's 2.82e-6 s */
#define SC_REACTION_REL_TOL 2e-4
/* the loop closure's drift and the flywheel's crank-angle error: the
 * four-bar's bounds (DRIFT_TOL_M, CRANK_ANGLE_TOL_RAD) */

/* loads the test's own case (file = NULL) or a shipped one with overrides */
static void sc_load(fb_case *c, const char *file, const char **sets, int n) {
  fb_diag d;
  const fb_status st = file ? fb_test_shipped_case(c, file, sets, n, &d)
                            : fb_test_case_text(c, SC_CASE_TEXT, sets, n, &d);
  if (st != FB_OK) fail_msg("%s: %s", file ? file : "the test's case", d.msg);
}

/* runs a slider-crank case with the given models and overrides (no added
 * ensemble: the verdicts are not what is tested) */
static void sc_run(fb_run *r, const char *file, const char *models, const char **sets, int n) {
  const char *all[8];
  char ms[256];
  snprintf(ms, sizeof ms, "run.models=%s", models);
  all[0] = ms;
  all[1] = "run.ensemble=1";
  for (int i = 0; i < n && i < 6; i++) all[i + 2] = sets[i];
  static fb_case c;
  sc_load(&c, file, all, n + 2);
  fb_diag d;
  if (fb_run_case(r, &c, NULL, NULL, &d) != FB_OK) fail_msg("run failed: %s", d.msg);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].run.stop.kind != FB_STOP_NONE)
      fail_msg("%s: stopped (%s)", r->model[i].run.name, fb_stop_kind_name(r->model[i].run.stop.kind));
}

static void test_sc_mjcf(void **state) {
  (void)state;
  static fb_scene def;
  fb_model_scene sm;
  fb_case c;
  const char *sets[] = {"run.models=mujoco-ideal-nominal"};
  sc_load(&c, NULL, sets, 1);
  fb_diag d;
  assert_int_equal(fb_scene_from_case(&def, &c, &d), FB_OK);
  assert_int_equal(fb_scene_select(&sm, &def, fb_model_find("mujoco-ideal-nominal"), &d), FB_OK);
  static char buf[16384];
  assert_int_equal(fb_mujoco_mjcf(buf, sizeof buf, &sm, &d), FB_OK);
  /* the slider on its guide y = offset, no follower, the loop closed at the
   * piston pin on the slider */
  assert_non_null(strstr(buf, "<body name=\"slider\" pos=\""));
  assert_non_null(strstr(buf, " 0.0060000000000000001 0\">"));
  assert_non_null(strstr(buf, "<joint name=\"D\" type=\"slide\" axis=\"1 0 0\"/>"));
  assert_null(strstr(buf, "follower"));
  assert_non_null(strstr(buf, "body1=\"coupler\" body2=\"slider\""));
  /* the export: the slider-crank's names, and the keyframe's three speeds */
  assert_int_equal(fb_mujoco_export(buf, sizeof buf, &sm, &d), FB_OK);
  assert_non_null(strstr(buf, "<joint name=\"slider-ground\" type=\"slide\""));
  assert_non_null(strstr(buf, "<site name=\"coupler-slider_pin\""));
  assert_non_null(strstr(buf, "<site name=\"coupler-slider_hole\""));
  const char *key = strstr(buf, "qvel=\"");
  assert_non_null(key);
  int spaces = 0;
  for (const char *q = key + 6; *q && *q != '"'; q++) spaces += *q == ' ';
  assert_int_equal(spaces, 2);
  /* clearance at the piston pin: no equality; the native bore between the
   * rod's pin and the slider's hole */
  const char *cl[] = {"run.models=mujoco-clearance-impact,mujoco-clearance-native"};
  sc_load(&c, NULL, cl, 1);
  assert_int_equal(fb_scene_from_case(&def, &c, &d), FB_OK);
  assert_int_equal(fb_scene_select(&sm, &def, fb_model_find("mujoco-clearance-impact"), &d), FB_OK);
  assert_int_equal(fb_mujoco_mjcf(buf, sizeof buf, &sm, &d), FB_OK);
  assert_null(strstr(buf, "<connect"));
  assert_non_null(strstr(buf, "<site name=\"C_hole\" pos=\"0 0 0\"/>"));
  assert_non_null(strstr(buf, "integrator=\"RK4\""));
  assert_int_equal(fb_scene_select(&sm, &def, fb_model_find("mujoco-clearance-native"), &d), FB_OK);
  assert_int_equal(fb_mujoco_export(buf, sizeof buf, &sm, &d), FB_OK);
  assert_non_null(strstr(buf, "<spatial name=\"coupler-slider_bore\""));
  /* clearance anywhere else is refused by name (the case check refuses it
   * first; a scene edited in code reaches the engine) */
  assert_int_equal(fb_scene_select(&sm, &def, fb_model_find("mujoco-clearance-impact"), &d), FB_OK);
  sm.clearance_mask |= 1 << FB_JOINT_B;
  assert_int_equal(fb_mujoco_mjcf(buf, sizeof buf, &sm, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "piston pin"));
}

/* the ideal models at the automatic step on both cases */
static void test_sc_ideal_models_match_analytic(void **state) {
  (void)state;
  static const char *const files[2] = {"slider_crank_flores.ini", NULL};
  for (int f = 0; f < 2; f++) {
    static fb_run r;
    sc_run(&r, files[f], "mujoco-ideal-nominal, mujoco-ideal-stackup", NULL, 0);
    assert_true(r.h_auto);
    for (int i = 0; i < 2; i++) {
      const fb_model_result *m = &r.model[i];
      assert_true(m->has_error);
      const fb_body_error *rod = &m->error.body[0], *sl = &m->error.body[1];
      const double rod_w = worst(rod->omega_max_rel, rod->omega_min_rel, 0, 0);
      const double rod_a = worst(rod->alpha_max_rel, rod->alpha_min_rel, 0, 0);
      const double sl_v = worst(sl->omega_max_rel, sl->omega_min_rel, 0, 0);
      const double sl_a = worst(sl->alpha_max_rel, sl->alpha_min_rel, 0, 0);
      const double sl_x = worst(sl->pos_max_rel, sl->pos_min_rel, 0, 0);
      report_residual(m->run.name, 0, 0);
      report_residual(files[f] ? "  (shipped case)" : "  (test case)", r.c.solver.h, 0);
      report_residual("  rod omega peak rel", rod_w, SC_IDEAL_PEAK_REL_TOL);
      report_residual("  rod alpha peak rel", rod_a, SC_IDEAL_PEAK_REL_TOL);
      report_residual("  slider v peak rel", sl_v, SC_IDEAL_PEAK_REL_TOL);
      report_residual("  slider a peak rel", sl_a, SC_IDEAL_PEAK_REL_TOL);
      report_residual("  slider x peak rel", sl_x, SC_IDEAL_PEAK_REL_TOL);
      report_residual("  crank angle err [rad]", m->error.crank_angle_err_max, CRANK_ANGLE_TOL_RAD);
      report_residual("  loop drift [m]", m->run.joint_drift_max, DRIFT_TOL_M);
      assert_true(rod_w < SC_IDEAL_PEAK_REL_TOL && rod_a < SC_IDEAL_PEAK_REL_TOL);
      assert_true(sl_v < SC_IDEAL_PEAK_REL_TOL && sl_a < SC_IDEAL_PEAK_REL_TOL);
      assert_true(sl_x < SC_IDEAL_PEAK_REL_TOL);
      assert_true(m->error.crank_angle_err_max < CRANK_ANGLE_TOL_RAD);
      assert_true(m->run.joint_drift_max < DRIFT_TOL_M);
    }
    fb_run_free(&r);
  }
}

/* the reactions of the ideal slider-crank against its inverse dynamics
 * (slider_crank_invdyn.h) at the sample's crank angle; the guide's as the
 * force on the ground from the slider, (0, -N) */
static void test_sc_reactions_match_inverse_dynamics(void **state) {
  (void)state;
  static fb_run r;
  sc_run(&r, NULL, "mujoco-ideal-nominal", NULL, 0);
  const fb_series *s = &r.model[0].run.series;
  assert_true(s->has_loads);
  const fb_linkage *lk = &r.c.nominal;
  const fb_slider_crank sc = {lk->length[FB_CRANK], lk->length[FB_COUPLER],
                              lk->length[FB_LENGTH_OFFSET]};
  const fb_link_mass *l = r.c.link;
  const fb_slider_crank_mass mass = {l[0].mass, l[0].inertia, l[0].com_fraction,
                                     l[1].mass, l[1].inertia, l[1].com_fraction, l[2].mass};
  const double w = fb_case_omega2(&r.c);
  double err = 0, fbig = 0, terr = 0, tmax = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->t[i] < r.t_window) continue;
    fb_slider_crank_reactions q;
    fb_diag d;
    assert_int_equal(fb_slider_crank_invdyn(&q, &sc, &mass, r.c.gravity, s->crank_angle[i], w, 0.0, &d),
                     FB_OK);
    double f[4][2];
    for (int j = 0; j < FB_SC_PIN_COUNT; j++) f[j][0] = q.force[j][0], f[j][1] = q.force[j][1];
    f[FB_SC_JOINT_SLIDER_GROUND][0] = 0.0;
    f[FB_SC_JOINT_SLIDER_GROUND][1] = -q.guide_force;
    for (int j = 0; j < 4; j++) {
      err = fmax(err, hypot(s->reaction[j][0][i] - f[j][0], s->reaction[j][1][i] - f[j][1]));
      fbig = fmax(fbig, hypot(f[j][0], f[j][1]));
    }
    terr = fmax(terr, fabs(s->drive_torque[i] - q.drive_torque));
    tmax = fmax(tmax, fabs(q.drive_torque));
  }
  report_residual("slider-crank reactions vs inverse dynamics", err / fbig, SC_REACTION_REL_TOL);
  report_residual("slider-crank drive torque vs inverse dynamics", terr / tmax, SC_REACTION_REL_TOL);
  assert_true(err / fbig < SC_REACTION_REL_TOL);
  assert_true(terr / tmax < SC_REACTION_REL_TOL);
  fb_run_free(&r);
}

/* matched impacts whose peak force is below this share of the largest
 * matched peak are grazing touches, left out of the one-by-one errors: the
 * test case at 2.5e-7 s has three, of 0.2 N / 7 nm (twice) and 26.5 N /
 * 0.64 um (the largest is 1e4 N / 5.1 um), whose relative errors (force
 * -33 % and +9 %, penetration -58 % and -2.6 %) are those of a few samples
 * at the law's foot, where rounding and the onset's phase in the step move
 * a peak of nanometres; the other 12 matched impacts, 712 N and up, are
 * within 0.69 % (force) and 0.46 % (penetration) there */
#define SC_GRAZING_SHARE 0.01

/* the largest |relative error| of force and penetration over the matched
 * impacts that are not grazing touches (SC_GRAZING_SHARE) */
static void sc_matched_errors(const fb_divergence *dv, double *ef, double *ep) {
  const int n = dv->matched < FB_DIVERGE_MAX_IMPACTS ? dv->matched : FB_DIVERGE_MAX_IMPACTS;
  double fmax_n = 0.0;
  for (int k = 0; k < n; k++) fmax_n = fmax(fmax_n, dv->impact[k].force);
  *ef = *ep = 0.0;
  for (int k = 0; k < n; k++) {
    if (dv->impact[k].force < SC_GRAZING_SHARE * fmax_n) continue;
    *ef = fmax(*ef, fabs(dv->impact[k].force_rel));
    *ep = fmax(*ep, fabs(dv->impact[k].penetration_rel));
  }
}

/* peak force and penetration of the clearance-impact model against the
 * reference, and its matched impacts' largest errors */
static void sc_report_impact(const char *what, const fb_model_result *m, double tol) {
  const fb_reference_error *re = &m->ref_error;
  const fb_divergence *dv = &m->divergence;
  double ef, ep;
  sc_matched_errors(dv, &ef, &ep);
  char name[160];
  snprintf(name, sizeof name, "%s force peak rel", what);
  report_residual(name, re->force_max_rel, tol);
  snprintf(name, sizeof name, "%s penetration peak rel", what);
  report_residual(name, re->penetration_max_rel, tol);
  snprintf(name, sizeof name, "%s matched impacts force err max", what);
  report_residual(name, ef, tol);
  snprintf(name, sizeof name, "%s matched impacts penetration err max", what);
  report_residual(name, ep, tol);
  assert_true(m->has_ref_error && m->has_divergence);
  assert_false(dv->diverged);
  assert_int_equal(re->impacts, re->impacts_reference);
  assert_true(dv->matched > 0);
  assert_true(fabs(re->force_max_rel) < tol);
  assert_true(fabs(re->penetration_max_rel) < tol);
  assert_true(ef < tol && ep < tol);
}

static void test_sc_clearance_impact_matches_reference(void **state) {
  (void)state;
  static fb_run r;
  /* the shipped case at its automatic step (its impact damper set for its
   * restitution 0.9: the pin rattles, and the sequence parts from the
   * reference's after about 25 impacts, a statistical verdict): its first
   * impacts, before it parts, within 1 % */
  sc_run(&r, "slider_crank_flores.ini", "mujoco-clearance-impact, reference", NULL, 0);
  assert_true(r.h_auto);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  assert_int_equal(m->ref_error.first_impacts, FB_FIRST_IMPACTS);
  for (int k = 0; k < FB_FIRST_IMPACTS; k++) {
    report_residual("sc impact, auto, impact k force rel", m->ref_error.first_impact_force_rel[k],
                    SC_FIRST_IMPACT_REL_TOL);
    report_residual("sc impact, auto, impact k penetration rel",
                    m->ref_error.first_impact_penetration_rel[k], SC_FIRST_IMPACT_REL_TOL);
    assert_true(fabs(m->ref_error.first_impact_force_rel[k]) < SC_FIRST_IMPACT_REL_TOL);
    assert_true(fabs(m->ref_error.first_impact_penetration_rel[k]) < SC_FIRST_IMPACT_REL_TOL);
  }
  /* the effective mass along the normal, from MuJoCo's mass matrix, within
   * the closed form's range over a revolution */
  assert_true(m->run.has_provenance);
  const fb_contact_provenance *p = &m->run.provenance[FB_JOINT_C];
  const fb_linkage *lk = &m->run.lengths;
  const fb_slider_crank sc = {lk->length[FB_CRANK], lk->length[FB_COUPLER],
                              lk->length[FB_LENGTH_OFFSET]};
  double lo = INFINITY, hi = 0.0;
  for (int k = 0; k < 720; k++) {
    fb_slider_crank_state st;
    fb_diag d;
    assert_int_equal(fb_slider_crank_solve(&st, &sc, k * M_PI / 360.0, 1.0, 0.0, &d), FB_OK);
    fb_mechanism mech;
    fb_mechanism_from_slider_crank(&mech, &st, r.c.link, 1 << FB_JOINT_C);
    double w[4][2][2], a, b;
    assert_int_equal(fb_effective_mass_tensor(w, &mech, &d), FB_OK);
    fb_effective_mass_range(w[FB_JOINT_C], &a, &b);
    lo = fmin(lo, a);
    hi = fmax(hi, b);
  }
  report_residual("sc effective mass min [kg]", p->mass_eff_min, lo);
  report_residual("sc effective mass max [kg]", p->mass_eff_max, hi);
  assert_true(p->contact_steps > 0);
  assert_true(p->mass_eff_min >= lo * (1.0 - SC_EFFECTIVE_MASS_REL_TOL));
  assert_true(p->mass_eff_max <= hi * (1.0 + SC_EFFECTIVE_MASS_REL_TOL));
  fb_run_free(&r);
  /* the test's own case (the four-bar's damper, 1e4 N s/m) at a step that
   * resolves the damper's onset: within 1 % (measured -0.02 %,
   * -0.01 %; at its automatic step 2.82e-6 s it leaves the reference in
   * revolution 2 after 4 matched impacts, the first within 2.3 %) */
  const char *fine[] = {"solver.h_s=" SC_FINE_H_S};
  sc_run(&r, NULL, "mujoco-clearance-impact, reference", fine, 1);
  sc_report_impact("sc impact (test case), h = " SC_FINE_H_S, &r.model[0], SC_CLEARANCE_PEAK_REL_TOL);
  fb_run_free(&r);
}

/* the restitution law on the shipped case at its automatic step: the first
 * impacts one by one; the rattling that follows (45 impacts in two
 * revolutions) is chaotic, its peaks compared by the run's statistics */
/* the count over the window is chaotic past the first impacts: over 16
 * members the reference's own runs count 17 to 45 impacts, so one run's
 * count says nothing (the kit's first member 25 against the reference's
 * 45, the hand-built scene's 43). What is held is the verdict's test on
 * the members' statistics (verdict_stats.h: impact rate, force mean and
 * force p90 within the equivalence margins): measured equivalent, rate 1.00
 * [0.83, 1.22], force mean 1.05, p90 1.15 */
#define SC_RESTITUTION_MEMBERS "run.ensemble=16"

static void test_sc_clearance_restitution_first_impacts(void **state) {
  (void)state;
  static fb_run r;
  const char *sets[] = {SC_RESTITUTION_MEMBERS};
  sc_run(&r, "slider_crank_flores.ini", "mujoco-clearance-restitution, reference-restitution", sets,
         1);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  const fb_reference_error *re = &m->ref_error;
  assert_int_equal(re->first_impacts, FB_FIRST_IMPACTS);
  for (int k = 0; k < re->first_impacts; k++) {
    report_residual("sc restitution impact k force rel", re->first_impact_force_rel[k],
                    SC_FIRST_IMPACT_REL_TOL);
    report_residual("sc restitution impact k penetration rel", re->first_impact_penetration_rel[k],
                    SC_FIRST_IMPACT_REL_TOL);
    assert_true(fabs(re->first_impact_force_rel[k]) < SC_FIRST_IMPACT_REL_TOL);
    assert_true(fabs(re->first_impact_penetration_rel[k]) < SC_FIRST_IMPACT_REL_TOL);
  }
  assert_true(m->has_test);
  assert_int_equal(m->test.members, 16);
  assert_int_equal(m->test.decision, FB_EQUIV_EQUIVALENT);
  assert_int_equal(m->verdict, FB_VERDICT_OK);
  assert_int_equal(m->basis, FB_BASIS_STATISTICS);
  fb_run_free(&r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_mjcf_from_the_definition),
      cmocka_unit_test(test_ideal_models_match_analytic),
      cmocka_unit_test(test_ideal_second_order_peaks),
      cmocka_unit_test(test_clearance_impact_matches_reference),
      cmocka_unit_test(test_clearance_restitution_matches_reference),
      cmocka_unit_test(test_clearance_impact_adaptive),
      cmocka_unit_test(test_adaptive_refuses_native),
      cmocka_unit_test(test_clearance_native_tendon_matches_reference),
      cmocka_unit_test(test_clearance_native_facets_characterised),
      cmocka_unit_test(test_reactions_match_inverse_dynamics),
      cmocka_unit_test(test_sc_mjcf),
      cmocka_unit_test(test_sc_ideal_models_match_analytic),
      cmocka_unit_test(test_sc_reactions_match_inverse_dynamics),
      cmocka_unit_test(test_sc_clearance_impact_matches_reference),
      cmocka_unit_test(test_sc_clearance_restitution_first_impacts),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
