/* Tolerance stack-up: exact sensitivities against finite differences of the
 * analytic peaks, RSS inside the worst-case corners, Monte Carlo converging to
 * the linearised distribution, and reproducibility by seed. */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "tolerance.h"

/* central difference of a Brent-refined peak with step 1e-6 m: the peak's
 * own refinement noise (~1e-12 relative of ~1e4) over 2e-6 m gives ~1e-2
 * absolute on sensitivities of 1e3..1e5, plus truncation ~1e-12 * S'''; a
 * relative bound of 1e-5 on each sensitivity covers it */
#define SENS_FD_STEP_M 1e-6
#define SENS_REL_TOL 1e-5
/* Monte Carlo with N samples, normal with sigma = t/3: the sample mean has
 * standard error sigma_out / sqrt(N), the sample standard deviation
 * sigma_out / sqrt(2N). At N = 4000: 1.6 % and 1.1 % of sigma_out. Bounds of
 * 5 standard errors plus the outputs' curvature (second-order terms
 * (S'' t^2 ~ 1e-3 of the band here): */
#define MC_SAMPLES 4000
#define MC_MEAN_TOL_SIGMA 0.08
#define MC_STD_REL_TOL 0.06

static fb_case paper;

static void test_sensitivities_vs_finite_differences(void **state) {
  (void)state;
  const double w = fb_case_omega2(&paper);
  double s[FB_TOL_NOUT][FB_LINK_COUNT];
  assert_int_equal(fb_tol_sensitivities(s, &paper.nominal, paper.branch, w, NULL), FB_OK);
  double worst = 0.0;
  for (int k = 0; k < FB_LINK_COUNT; k++) {
    fb_linkage p = paper.nominal, m = paper.nominal;
    p.length[k] += SENS_FD_STEP_M;
    m.length[k] -= SENS_FD_STEP_M;
    double op[FB_TOL_NOUT], om[FB_TOL_NOUT];
    assert_int_equal(fb_tol_outputs(op, &p, paper.branch, w, NULL), FB_OK);
    assert_int_equal(fb_tol_outputs(om, &m, paper.branch, w, NULL), FB_OK);
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      double fd = (op[i] - om[i]) / (2 * SENS_FD_STEP_M);
      double e = fabs(s[i][k] - fd) / fabs(fd);
      worst = fmax(worst, e);
      if (e > SENS_REL_TOL)
        fail_msg("%s / d %s: exact %.10g, finite difference %.10g", fb_tol_output_name(i),
                 fb_link_name(k), s[i][k], fd);
    }
  }
  report_residual("sensitivity vs finite difference (rel)", worst, SENS_REL_TOL);
}

static void test_rss_inside_corners_and_mc_converges(void **state) {
  (void)state;
  static fb_stackup_result r;
  assert_int_equal(fb_tol_analyse(&r, &paper, FB_TOL_CORNERS | FB_TOL_RSS | FB_TOL_MONTECARLO,
                                  MC_SAMPLES, 7, FB_DIST_NORMAL, NULL, NULL, NULL), FB_OK);
  assert_int_equal(r.samples, MC_SAMPLES);
  double worst_mean = 0, worst_std = 0;
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    /* RSS band lies inside the worst-case range, and both contain nominal */
    assert_true(r.corner_min[i] <= r.nominal[i] - r.rss_half[i]);
    assert_true(r.nominal[i] + r.rss_half[i] <= r.corner_max[i]);
    /* Monte Carlo quantiles stay inside the corners */
    assert_true(r.q[i][0] >= r.corner_min[i] && r.q[i][2] <= r.corner_max[i]);
    /* ... and match the linearised normal distribution: sigma = rss / 3 */
    const double sigma = r.rss_half[i] / 3.0;
    const double em = fabs(r.mc_mean[i] - r.nominal[i]) / sigma;
    const double es = fabs(r.mc_std[i] - sigma) / sigma;
    worst_mean = fmax(worst_mean, em);
    worst_std = fmax(worst_std, es);
    assert_true(em < MC_MEAN_TOL_SIGMA);
    assert_true(es < MC_STD_REL_TOL);
  }
  report_residual("MC mean - nominal [sigma]", worst_mean, MC_MEAN_TOL_SIGMA);
  report_residual("MC std vs RSS/3 (rel)", worst_std, MC_STD_REL_TOL);
  /* a uniform distribution reaches further toward the corners than a
   * normal one with 3 sigma at the limit */
  static fb_stackup_result u;
  assert_int_equal(fb_tol_analyse(&u, &paper, FB_TOL_MONTECARLO, MC_SAMPLES, 7, FB_DIST_UNIFORM,
                                  NULL, NULL, NULL), FB_OK);
  assert_true(u.q[0][2] - u.q[0][0] > r.q[0][2] - r.q[0][0]);
  assert_true(u.q[0][2] <= r.corner_max[0]);
}

static void test_same_seed_same_numbers(void **state) {
  (void)state;
  static fb_stackup_result a, b, c;
  fb_tol_analyse(&a, &paper, FB_TOL_MONTECARLO, 300, 42, FB_DIST_NORMAL, NULL, NULL, NULL);
  fb_tol_analyse(&b, &paper, FB_TOL_MONTECARLO, 300, 42, FB_DIST_NORMAL, NULL, NULL, NULL);
  fb_tol_analyse(&c, &paper, FB_TOL_MONTECARLO, 300, 43, FB_DIST_NORMAL, NULL, NULL, NULL);
  assert_memory_equal(a.q, b.q, sizeof a.q);
  assert_true(memcmp(a.q, c.q, sizeof a.q) != 0);
}

static void test_worst_corner(void **state) {
  (void)state;
  static fb_stackup_result r;
  fb_tol_analyse(&r, &paper, FB_TOL_CORNERS, 0, 1, FB_DIST_NORMAL, NULL, NULL, NULL);
  for (int out = 0; out < FB_TOL_NOUT; out++) {
    fb_case c = paper;
    c.stackup.worst = 1;
    c.stackup.worst_output = out;
    assert_int_equal(fb_tol_resolve_worst(&c, NULL), FB_OK);
    assert_false(c.stackup.worst);
    assert_memory_equal(c.stackup.corner, r.corner_of_max[out], sizeof c.stackup.corner);
    /* the chosen corner attains the largest magnitude over the corners */
    fb_linkage lk;
    fb_case_stackup_lengths(&c, &lk);
    double v[FB_TOL_NOUT];
    fb_tol_outputs(v, &lk, c.branch, fb_case_omega2(&c), NULL);
    assert_near(fabs(v[out]), fmax(fabs(r.corner_min[out]), fabs(r.corner_max[out])), 0.0);
  }
  assert_int_equal(fb_tol_output_parse("coupler_omega_max"), 0);
  assert_int_equal(fb_tol_output_parse("transmission_angle_max_rad"), 9);
  assert_int_equal(fb_tol_output_parse("nope"), -1);
}

int main(void) {
  fb_test_paper_case(&paper, NULL, 0);
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_sensitivities_vs_finite_differences),
      cmocka_unit_test(test_rss_inside_corners_and_mc_converges),
      cmocka_unit_test(test_same_seed_same_numbers),
      cmocka_unit_test(test_worst_corner),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
