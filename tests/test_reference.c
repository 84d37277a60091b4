/* The reference dynamics (minimal coordinates, GSL rk8pd): the ideal limit
 * against the exact solution, its own tolerance convergence, and ODE's
 * clearance model converging toward it as h shrinks. */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "joint_law.h"
#include "reference.h"
#include "run.h"

/* the bound; measured 3e-14 (rk8pd at 1e-10 on a smooth 0-DOF loop) */
#define IDEAL_REL_TOL 1e-8
/* the reference at its default tolerance (1e-12) against 1e-13: the force
 * peak agrees to 2.3e-10 (measured); 1e-4 is the bound this test always had
 * (it compared 1e-10 with 1e-12 before issue 28) */
#define SELF_CONVERGENCE_REL_TOL 1e-4

static void test_ideal_limit_matches_analytic(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.revolutions=2"};
  fb_test_paper_case(&c, sets, 1);
  fb_series s;
  size_t steps;
  assert_int_equal(fb_reference_run(&s, &steps, &c, NULL, 1, NULL, NULL), FB_OK);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  const double w = fb_case_omega2(&c);
  double worst = 0;
  for (size_t i = 0; i < s.n; i++) {
    fb_linkage_state x;
    fb_linkage_solve(&x, &lk, c.branch, s.crank_angle[i], w, 0.0, NULL);
    const double e[6] = {remainder(s.coupler_angle[i] - x.coupler_angle, 2 * M_PI),
                         remainder(s.follower_angle[i] - x.follower_angle, 2 * M_PI),
                         (s.coupler_omega[i] - x.coupler_omega) / fabs(w),
                         (s.follower_omega[i] - x.follower_omega) / fabs(w),
                         (s.coupler_alpha[i] - x.coupler_alpha) / (w * w),
                         (s.follower_alpha[i] - x.follower_alpha) / (w * w)};
    for (int k = 0; k < 6; k++) worst = fmax(worst, fabs(e[k]));
  }
  report_residual("reference ideal limit vs analytic", worst, IDEAL_REL_TOL);
  assert_true(worst < IDEAL_REL_TOL);
  fb_series_free(&s);
}

static double force_peak(const fb_series *s, double t0) {
  double f = 0;
  for (size_t i = 0; i < s->n; i++)
    if (s->t[i] >= t0) f = fmax(f, s->contact[FB_JOINT_B][FB_C_FORCE][i]);
  return f;
}

static void test_reference_converged_in_tolerance(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.revolutions=2"};
  fb_test_paper_case(&c, sets, 1);
  fb_contact_law law[4];
  assert_int_equal(fb_joint_laws(law, NULL, &c, NULL), FB_OK);
  fb_series a, b;
  size_t sa, sb;
  assert_int_equal(fb_reference_run(&a, &sa, &c, &law[FB_JOINT_B], 0, NULL, NULL), FB_OK);
  setenv("FOURBAR_REFERENCE_TOL", "1e-13", 1);
  assert_int_equal(fb_reference_run(&b, &sb, &c, &law[FB_JOINT_B], 0, NULL, NULL), FB_OK);
  unsetenv("FOURBAR_REFERENCE_TOL");
  const double t0 = 2 * M_PI / c.crank_speed;
  report_residual("reference force peak, default tol (1e-12) vs 1e-13",
                  fabs(force_peak(&a, t0) - force_peak(&b, t0)) / force_peak(&b, t0), SELF_CONVERGENCE_REL_TOL);
  assert_rel(force_peak(&a, t0), force_peak(&b, t0), SELF_CONVERGENCE_REL_TOL);
  assert_true(sb > sa); /* the tighter tolerance did work harder */
  fb_series_free(&a);
  fb_series_free(&b);
}

/* A spike refined at an output step of 1e-5 s against the same spike at
 * 1e-6 s (peak_refine.h, FB_REFERENCE_REFINE: the two sample intervals
 * re-integrated, every FB_REFERENCE_REFINE_STRIDE-th of 64 points per
 * interval a stop of the integration, the extreme searched by Brent's
 * method between the stops beside the best). Measured on the
 * paper case's window: force peak 7e-6 apart, coupler alpha minimum 4.6e-5
 * (unrefined, a spike sampled at 1e-5 s misses by up to 17.5 %); the bounds
 * are 7x and 4x that. */
#define REFINED_FORCE_REL_TOL 5e-5
#define REFINED_ALPHA_REL_TOL 2e-4

static double alpha_min(const fb_series *s, double t0) {
  double a = 0;
  for (size_t i = 0; i < s->n; i++)
    if (s->t[i] >= t0) a = fmin(a, s->coupler_alpha[i]);
  return a;
}

static void test_refined_spike_independent_of_output_step(void **state) {
  (void)state;
  fb_series s[2];
  double t0 = 0.0;
  const char *hs[2] = {"solver.h_s=1e-5", "solver.h_s=1e-6"};
  for (int k = 0; k < 2; k++) {
    fb_case c;
    const char *sets[] = {"run.revolutions=2", hs[k]};
    fb_test_paper_case(&c, sets, 2);
    fb_contact_law law[4];
    assert_int_equal(fb_joint_laws(law, NULL, &c, NULL), FB_OK);
    size_t steps;
    assert_int_equal(fb_reference_run(&s[k], &steps, &c, &law[FB_JOINT_B], 0, NULL, NULL), FB_OK);
    t0 = 2 * M_PI / c.crank_speed;
  }
  report_residual("refined force peak, h 1e-5 vs 1e-6 s",
                  fabs(force_peak(&s[0], t0) / force_peak(&s[1], t0) - 1), REFINED_FORCE_REL_TOL);
  report_residual("refined coupler alpha min, h 1e-5 vs 1e-6 s",
                  fabs(alpha_min(&s[0], t0) / alpha_min(&s[1], t0) - 1), REFINED_ALPHA_REL_TOL);
  assert_rel(force_peak(&s[0], t0), force_peak(&s[1], t0), REFINED_FORCE_REL_TOL);
  assert_rel(alpha_min(&s[0], t0), alpha_min(&s[1], t0), REFINED_ALPHA_REL_TOL);
  fb_series_free(&s[0]);
  fb_series_free(&s[1]);
}

/* The reference's cost is linear in simulated time (issue 54): its accepted
 * steps per revolution at 8 revolutions within 10 % of those at 2 (the
 * issue's bound), at its own tolerance and at its check's (1e-13). Step
 * counts, not time. Before the crank's clock restarted each sample and the
 * eccentricity was formed from deviations (main before issue 54, this
 * test's settings: fourbar run --set run.models=reference --set
 * solver.h_s=5e-6 --set run.revolutions=2 and 8), the growth was 51 % for
 * the reference and 96 % for its check (18.5k to 27.8k, 106k to 209k steps
 * per revolution); now 1.2 % and 1.8 %. */
#define STEPS_PER_REV_GROWTH_MAX 0.10

static void test_steps_per_revolution_constant(void **state) {
  (void)state;
  const char *tols[2] = {NULL, "1e-13"};
  for (int k = 0; k < 2; k++) {
    double per_rev[2];
    const char *revs[2] = {"run.revolutions=2", "run.revolutions=8"};
    const double n_rev[2] = {2.0, 8.0};
    for (int r = 0; r < 2; r++) {
      fb_case c;
      const char *sets[] = {revs[r], "solver.h_s=5e-6"};
      fb_test_paper_case(&c, sets, 2);
      fb_contact_law law[4];
      assert_int_equal(fb_joint_laws(law, NULL, &c, NULL), FB_OK);
      if (tols[k]) setenv("FOURBAR_REFERENCE_TOL", tols[k], 1);
      fb_series s;
      size_t steps;
      const fb_status st = fb_reference_run(&s, &steps, &c, &law[FB_JOINT_B], 0, NULL, NULL);
      unsetenv("FOURBAR_REFERENCE_TOL");
      assert_int_equal(st, FB_OK);
      fb_series_free(&s);
      per_rev[r] = (double)steps / n_rev[r];
    }
    report_residual(k ? "check (1e-13): steps per revolution, 8 against 2 revolutions"
                      : "reference: steps per revolution, 8 against 2 revolutions",
                    fabs(per_rev[1] / per_rev[0] - 1.0), STEPS_PER_REV_GROWTH_MAX);
    assert_true(fabs(per_rev[1] / per_rev[0] - 1.0) <= STEPS_PER_REV_GROWTH_MAX);
  }
}

static void test_ode_converges_to_reference(void **state) {
  (void)state;
  /* ODE's impact model against the reference of the same law: the peak
   * contact force error shrinks as h does (measured -7.4 %, -1.7 %, -1.5 %
   * at h = 1e-5, 5e-6, 2.5e-6 s over 3 revolutions) */
  const char *hs[3] = {"solver.h_s=1e-5", "solver.h_s=5e-6", "solver.h_s=2.5e-6"};
  double err[3];
  for (int k = 0; k < 3; k++) {
    const char *sets[] = {"run.revolutions=2", "run.models=ode-clearance-impact,reference", hs[k]};
    fb_case c;
    fb_test_paper_case(&c, sets, 3);
    static fb_run r;
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    assert_true(r.model[0].has_ref_error);
    err[k] = fabs(r.model[0].ref_error.force_max_rel);
    if (fb_test_verbose()) fprintf(stderr, "  %s: force peak error %.3e, penetration %.3e\n", hs[k], err[k],
                                   r.model[0].ref_error.penetration_max_rel);
    fb_run_free(&r);
  }
  assert_true(err[1] < err[0]);
  assert_true(err[2] < 0.03); /* within 3 % at the finest step */
}

/* An integration whose step collapses ran without end: the step budget
 * stops it with its named reason (issue 13 item 7). Issue 13 lost it with a
 * start at crank angle 1e9 deg (set after loading; the case file refuses
 * it), whose rounding of theta0 + omega2 t the contact law amplified; since
 * the crank turns on a clock restarted each sample (issue 54) that start
 * integrates like any other. Here the contact's damper is made 1e6 times
 * harder (c = 1e10 N s/m on an effective mass ~0.1 kg: a decay rate ~1e11
 * 1/s, which an explicit rk8pd follows with steps ~1e-11 s, far more than
 * the budget's 200 steps per 1e-4 s sample). A stiffer spring instead
 * (x1e4 and up) blows up to NaN (FB_STOP_NONFINITE): relative error control
 * accepts a state that grows with its own tolerance. */
#define LOST_DAMPING_FACTOR 1e6
static void test_step_budget_stops_a_lost_integration(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.revolutions=2", "solver.h_s=1e-4"};
  fb_test_paper_case(&c, sets, 2);
  fb_contact_law law[4];
  assert_int_equal(fb_joint_laws(law, NULL, &c, NULL), FB_OK);
  law[FB_JOINT_B].damping *= LOST_DAMPING_FACTOR;
  fb_series s;
  size_t steps = 0;
  fb_diag d;
  fb_stop stop;
  const fb_status st = fb_reference_run(&s, &steps, &c, &law[FB_JOINT_B], 0, &stop, &d);
  const size_t n = (size_t)llround(fb_case_duration(&c) / c.solver.h);
  if (st == FB_OK) fail_msg("a lost integration finished in %zu steps", steps);
  assert_int_equal(st, FB_ERR_NUMERIC);
  assert_int_equal(stop.kind, FB_STOP_STEP_BUDGET);
  if (!strstr(d.msg, "step budget")) fail_msg("'%s' does not name the step budget", d.msg);
  /* + 1: GSL's driver counts the step that reached its limit */
  if (steps > (n + 1) * FB_REFERENCE_STEPS_PER_SAMPLE + 1)
    fail_msg("%zu steps over the budget %zu: %s", steps, (n + 1) * FB_REFERENCE_STEPS_PER_SAMPLE, d.msg);
  fb_series_free(&s);
}

/* issue 28 item 4, the done-when: at the default tolerance the reference's
 * revolution 2 of the paper's restitution case has the same impact count at
 * output steps 5e-6, 2e-6 and 1e-6 s (measured: 14 at each; at the former
 * 1e-10: 12, 14, 14), and its own error estimate (a second integration at
 * 1e-13) agrees on that count. Counts are integers: equal or not. Not at
 * 1e-5 s any more: an impact is a contact (metrics.h, issue 55), and at
 * 64.33 ms the pin leaves the wall for a few microseconds between two of
 * them, which the 1e-5 s grid samples 1.3 nm in (13; its check 14). */
static void test_revolution_2_impacts_converged(void **state) {
  (void)state;
  const char *hs[3] = {"solver.h_s=5e-6", "solver.h_s=2e-6", "solver.h_s=1e-6"};
  int first = -1;
  for (int i = 0; i < 3; i++) {
    const char *sets[] = {"run.revolutions=2", "run.models=reference-restitution", hs[i]};
    fb_case c;
    fb_test_paper_case(&c, sets, 3);
    static fb_run r;
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const fb_model_result *m = &r.model[0];
    assert_true(m->has_peaks && m->has_spikes);
    const int n = m->spikes.impacts;
    if (fb_test_verbose()) fprintf(stderr, "  revolution 2 impacts at %s: %d\n", hs[i], n);
    if (first < 0) first = n;
    assert_int_equal(n, first);
    assert_true(n > 0);
    /* the estimate: present, at the floor tolerance, same count */
    assert_true(m->has_ref_estimate);
    assert_near(m->ref_tol, FB_REFERENCE_TOL, 0.0);
    assert_near(m->ref_check_tol, FB_REFERENCE_TOL_MIN, 0.0);
    assert_int_equal(m->ref_estimate.impacts, n);
    assert_int_equal(m->ref_estimate.impacts_reference, n);
    assert_true(m->ref_check_steps > m->run.steps);
    fb_run_free(&r);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_ideal_limit_matches_analytic),
      cmocka_unit_test(test_reference_converged_in_tolerance),
      cmocka_unit_test(test_refined_spike_independent_of_output_step),
      cmocka_unit_test(test_steps_per_revolution_constant),
      cmocka_unit_test(test_ode_converges_to_reference),
      cmocka_unit_test(test_step_budget_stops_a_lost_integration),
      cmocka_unit_test(test_revolution_2_impacts_converged),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
