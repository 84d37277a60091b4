/* The ideal four-bar in ODE against the exact analytic solution.
 *
 *            C
 *           / \          hinges at A, B, C, D (axis +z); crank driven by a
 *  coupler /   \         velocity motor at A; gravity along -y
 *         B     \ follower
 *  crank /       \
 *       A ------- D
 *
 * ODE's dWorldStep is semi-implicit Euler: velocities at t_{n+1} satisfy the
 * constraints of the configuration at t_n, so the velocity series lags the
 * exact one by about one step (a first-order pointwise error, bounded by
 * h * max|alpha|), while a peak value, where d omega / dt = 0, is only moved
 * to second order. The tolerances below come from those two facts. */
#include <math.h>
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "mech_kinematics.h"
#include "run.h"

/* the acceptance bound on peak angular velocity at the default step */
#define PEAK_OMEGA_REL_TOL 1e-4
/* pointwise error <= LAG_FACTOR * h * max|alpha|: one step of lag plus the
 * ERP position correction, which adds a fraction of a step */
#define LAG_FACTOR 1.5
/* halving h divides a first-order error by 2 and a second-order one by 4;
 * the bands allow the ratio to wander by 10 % (higher-order terms) */
#define FIRST_ORDER_LO 1.8
#define FIRST_ORDER_HI 2.2
#define SECOND_ORDER_LO 3.6
#define SECOND_ORDER_HI 4.4
/* hinge anchors may drift apart by much less than the smallest radial
 * clearance the project studies (2.5 um for 10 H7/g6): 1 um at h = 1e-5 s */
#define DRIFT_TOL_M 1e-6

static char paper_path[4096];

static void run_ode(fb_run *r, const char *h, const char *stepper) {
  char hs[64], ss[64];
  snprintf(hs, sizeof hs, "solver.h_s=%s", h);
  snprintf(ss, sizeof ss, "solver.stepper=%s", stepper);
  const char *sets[] = {hs, ss, "run.revolutions=2", "run.models=ode-ideal-nominal"};
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 4, &d), FB_OK);
  fb_status st = fb_run_case(r, &c, NULL, NULL, &d);
  if (st != FB_OK) fail_msg("run failed: %s", d.msg);
  assert_int_equal(r->model[0].run.stop.kind, FB_STOP_NONE);
  assert_true(r->model[0].has_error);
}

static double worst_peak_rel(const fb_error *e) {
  const double v[4] = {e->coupler.omega_max_rel, e->coupler.omega_min_rel,
                       e->follower.omega_max_rel, e->follower.omega_min_rel};
  double w = 0;
  for (int i = 0; i < 4; i++) w = fmax(w, fabs(v[i]));
  return w;
}

static void test_ideal_ode_matches_analytic(void **state) {
  (void)state;
  static fb_run r;
  run_ode(&r, "1e-5", "world");
  const fb_model_result *m = &r.model[0];
  const double h = 1e-5;
  double peak = worst_peak_rel(&m->error);
  report_residual("peak omega rel, h = 1e-5", peak, PEAK_OMEGA_REL_TOL);
  assert_true(peak < PEAK_OMEGA_REL_TOL);
  const fb_peaks *x = &m->exact;
  double amax_c = fmax(fabs(x->coupler.alpha_max), fabs(x->coupler.alpha_min));
  double amax_f = fmax(fabs(x->follower.alpha_max), fabs(x->follower.alpha_min));
  report_residual("coupler omega err max [rad/s]", m->error.coupler.omega_err_max,
                  LAG_FACTOR * h * amax_c);
  assert_true(m->error.coupler.omega_err_max < LAG_FACTOR * h * amax_c);
  assert_true(m->error.follower.omega_err_max < LAG_FACTOR * h * amax_f);
  report_residual("joint drift [m]", m->run.joint_drift_max, DRIFT_TOL_M);
  assert_true(m->run.joint_drift_max < DRIFT_TOL_M);
  fb_run_free(&r);
}

static void test_convergence_orders(void **state) {
  (void)state;
  static fb_run a, b;
  run_ode(&a, "4e-5", "world");
  run_ode(&b, "2e-5", "world");
  double rms_ratio = a.model[0].error.coupler.omega_err_rms / b.model[0].error.coupler.omega_err_rms;
  double peak_ratio = worst_peak_rel(&a.model[0].error) / worst_peak_rel(&b.model[0].error);
  report_residual("rms omega error ratio h / (h/2)", rms_ratio, FIRST_ORDER_LO);
  report_residual("peak omega error ratio h / (h/2)", peak_ratio, SECOND_ORDER_LO);
  assert_true(rms_ratio > FIRST_ORDER_LO && rms_ratio < FIRST_ORDER_HI);
  assert_true(peak_ratio > SECOND_ORDER_LO && peak_ratio < SECOND_ORDER_HI);
  fb_run_free(&a);
  fb_run_free(&b);
}

static void test_quickstep_runs_and_is_less_accurate(void **state) {
  (void)state;
  /* SOR with 20 iterations on a closed loop: finite, close in velocity, but
   * not converged: its peak error is larger than the direct solver's */
  static fb_run q, w;
  run_ode(&q, "1e-5", "quick");
  run_ode(&w, "1e-5", "world");
  double eq = worst_peak_rel(&q.model[0].error), ew = worst_peak_rel(&w.model[0].error);
  report_residual("quickstep peak omega rel", eq, 1e-2);
  assert_true(eq < 1e-2);
  assert_true(eq > ew);
  fb_run_free(&q);
  fb_run_free(&w);
}

static void test_same_seed_same_numbers(void **state) {
  (void)state;
  static fb_run a, b;
  run_ode(&a, "1e-4", "quick");
  run_ode(&b, "1e-4", "quick");
  const fb_series *sa = &a.model[0].run.series, *sb = &b.model[0].run.series;
  assert_int_equal(sa->n, sb->n);
  assert_memory_equal(sa->coupler_omega, sb->coupler_omega, sa->n * sizeof(double));
  fb_run_free(&a);
  fb_run_free(&b);
}

/* ODE's own fatal check (dxNormalize4's assertion, reached with CFM = 0 on
 * the closed loop's redundant hinge rows; the case file refuses that value,
 * so the case is changed after loading) stops the model with a named reason
 * instead of aborting the process (issue 13 item 2) */
static void test_ode_fatal_error_is_a_status_not_an_abort(void **state) {
  (void)state;
  const char *sets[] = {"run.revolutions=2", "run.models=analytic,ode-ideal-nominal"};
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 2, &d), FB_OK);
  c.solver.world_cfm = 0.0;
  static fb_run r;
  fb_status st = fb_run_case(&r, &c, NULL, NULL, &d);
  if (st != FB_OK) fail_msg("run failed: %s", d.msg);
  assert_int_equal(r.model[0].run.stop.kind, FB_STOP_NONE);
  /* a solver stop, with ODE's own words and the step */
  assert_int_equal(r.model[1].run.stop.kind, FB_STOP_SOLVER);
  assert_true(r.model[1].run.stop.detail[0] != '\0');
  assert_true(r.model[1].run.stop.step > 0);
  fb_run_free(&r);
}

/* [solver] h_s = adaptive on the ideal four-bar (no contact: every step
 * asks for h_max_s, reached by the ramp): samples on the grid of h_min_s,
 * about one ODE step per h_max_s, and the peaks as accurate as the issue's
 * bound for the default step (the samples inside a step are interpolated) */
static void test_adaptive_ideal_lands_on_the_grid(void **state) {
  (void)state;
  const char *sets[] = {"run.revolutions=2", "run.models=ode-ideal-nominal", "solver.h_s=adaptive",
                        "solver.h_min_s=1e-6", "solver.h_max_s=2e-5"};
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 5, &d), FB_OK);
  static fb_run r;
  if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("run failed: %s", d.msg);
  const fb_model_run *m = &r.model[0].run;
  assert_int_equal(m->stop.kind, FB_STOP_NONE);
  const double dur = fb_case_duration(&c);
  assert_int_equal(m->series.n, (size_t)llround(dur / 1e-6) + 1);
  for (size_t i = 0; i < m->series.n; i += 997) assert_near(m->series.t[i], 1e-6 * (double)i, 1e-15);
  assert_true(m->has_step_stats);
  /* the ramp from one grid step (the start) to 20 takes 11 steps before
   * the first at 20 (2, 3, 4, 5, 6, 7, 8, 10, 12, 15, 18): the rest are
   * 2e-5 s, the last one perhaps past the run's end */
  assert_near(m->step_stats.h_max, 2e-5, 1e-18);
  assert_near(m->step_stats.h_min, 2e-6, 1e-18);
  assert_int_equal(m->step_stats.steps - m->step_stats.n_h_max, 11);
  assert_true(m->step_stats.steps <= (size_t)(dur / 2e-5) + 11);
  const double w = worst_peak_rel(&r.model[0].error);
  report_residual("adaptive ideal, worst omega peak", w, PEAK_OMEGA_REL_TOL);
  assert_true(w < PEAK_OMEGA_REL_TOL);
  fb_run_free(&r);
}

/* the adaptive step follows the exact collider's contact only: a faceted
 * model is refused, naming the collider, by the case check (before anything
 * runs) and, should a case reach it unchecked, by the scene itself */
static void test_adaptive_refuses_other_colliders(void **state) {
  (void)state;
  const char *sets[] = {"run.revolutions=2", "run.models=ode-clearance-faceted", "solver.h_s=adaptive"};
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 3, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "h_s = adaptive"));
  assert_non_null(strstr(d.msg, "faceted"));
  /* the scene of a case with the same law, and the faceted model run in it */
  sets[1] = "run.models=ode-clearance-impact";
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 3, &d), FB_OK);
  fb_scene *def = malloc(sizeof *def);
  assert_int_equal(fb_scene_from_case(def, &c, &d), FB_OK);
  fb_model_run mr;
  assert_int_not_equal(fb_model_run_one(&mr, def, fb_model_find("ode-clearance-faceted"), NULL, NULL, &d),
                       FB_OK);
  fb_model_run_free(&mr);
  assert_non_null(strstr(d.msg, "h_s = adaptive"));
  assert_non_null(strstr(d.msg, "faceted"));
  free(def);
}

/* [clearance] engine_stiffness_scale and engine_damping_scale (an injected
 * error, issue 55): every engine model's law is scaled, the references'
 * is the case's, and a rigid model's is not touched. The restitution law's
 * damper c = 2 zeta sqrt(p m) follows the scaled p unless the damping scale
 * is given; given, it is that scale times the damper of the case's p. */
static void test_engine_scales_leave_references_alone(void **state) {
  (void)state;
  /* the ratios are exact products of doubles and one sqrt: a few ulps */
  const double TOL_REL = 1e-12;
  fb_case c;
  fb_diag d;
  const char *sets[3] = {"run.models=ode-clearance-impact,ode-clearance-restitution,reference,"
                         "reference-restitution",
                         "clearance.engine_stiffness_scale=4", "run.ensemble=1"};
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 3, &d), FB_OK);
  fb_scene *def = malloc(sizeof *def);
  assert_int_equal(fb_scene_from_case(def, &c, &d), FB_OK);
  const int j = FB_JOINT_B;
  fb_model_scene ode, ref, odr, rfr;
  assert_int_equal(fb_scene_select(&ode, def, fb_model_find("ode-clearance-impact"), &d), FB_OK);
  assert_int_equal(fb_scene_select(&ref, def, fb_model_find("reference"), &d), FB_OK);
  assert_int_equal(fb_scene_select(&odr, def, fb_model_find("ode-clearance-restitution"), &d), FB_OK);
  assert_int_equal(fb_scene_select(&rfr, def, fb_model_find("reference-restitution"), &d), FB_OK);
  assert_near(ode.law[j].stiffness / ref.law[j].stiffness, 4.0, 4.0 * TOL_REL);
  assert_near(ode.law[j].damping, ref.law[j].damping, 0.0); /* c_max: damping scale 1 */
  assert_near(odr.law[j].stiffness / rfr.law[j].stiffness, 4.0, 4.0 * TOL_REL);
  /* the damper follows p: the same zeta, so twice the damper (sqrt 4) */
  assert_near(fb_contact_law_zeta(&odr.law[j]), fb_contact_law_zeta(&rfr.law[j]), 1e-15);
  /* given: the case's damper times the scale, zeta times s_d / sqrt(s_k) */
  const char *sets2[4] = {sets[0], sets[1], sets[2], "clearance.engine_damping_scale=10"};
  assert_int_equal(fb_casefile_load(&c, paper_path, sets2, 4, &d), FB_OK);
  assert_int_equal(fb_scene_from_case(def, &c, &d), FB_OK);
  assert_int_equal(fb_scene_select(&ode, def, fb_model_find("ode-clearance-impact"), &d), FB_OK);
  assert_int_equal(fb_scene_select(&odr, def, fb_model_find("ode-clearance-restitution"), &d), FB_OK);
  assert_int_equal(fb_scene_select(&rfr, def, fb_model_find("reference-restitution"), &d), FB_OK);
  assert_near(ode.law[j].damping / def->law[FB_MODEL_LAW_IMPACT][j].damping, 10.0, 10.0 * TOL_REL);
  const double m = 0.3; /* any effective mass: both dampers go as sqrt(m) */
  const double c_engine = 2.0 * fb_contact_law_zeta(&odr.law[j]) * sqrt(odr.law[j].stiffness * m);
  const double c_case = 2.0 * fb_contact_law_zeta(&rfr.law[j]) * sqrt(rfr.law[j].stiffness * m);
  assert_near(c_engine / c_case, 10.0, 10.0 * TOL_REL);
  free(def);
}

/* The scene of a case computes its joints' largest ideal reactions once:
 * the automatic step, the contact estimates, the joint laws and the scene
 * ask for the same lengths' peaks (fb_mech_reaction_peaks keeps them). A
 * gravity of its own keeps the kept results of other tests out. */
static void test_reaction_peaks_once(void **state) {
  (void)state;
  const char *sets[] = {"environment.gravity_m_s2=9.80123"};
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_casefile_load(&c, paper_path, sets, 1, &d), FB_OK);
  fb_scene *def = malloc(sizeof *def);
  const long before = fb_mech_reaction_peaks_computed();
  assert_int_equal(fb_scene_from_case(def, &c, &d), FB_OK);
  assert_int_equal(fb_scene_from_case(def, &c, &d), FB_OK);
  assert_int_equal(fb_mech_reaction_peaks_computed() - before, 1);
  free(def);
}

int main(void) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  snprintf(paper_path, sizeof paper_path, "%s/paper_crank_rocker.ini", d ? d : "cases");
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_ideal_ode_matches_analytic),
      cmocka_unit_test(test_convergence_orders),
      cmocka_unit_test(test_quickstep_runs_and_is_less_accurate),
      cmocka_unit_test(test_same_seed_same_numbers),
      cmocka_unit_test(test_ode_fatal_error_is_a_status_not_an_abort),
      cmocka_unit_test(test_adaptive_ideal_lands_on_the_grid),
      cmocka_unit_test(test_adaptive_refuses_other_colliders),
      cmocka_unit_test(test_engine_scales_leave_references_alone),
      cmocka_unit_test(test_reaction_peaks_once),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
