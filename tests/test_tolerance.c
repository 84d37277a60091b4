/* Tolerance stack-up: exact sensitivities against finite differences of the
 * analytic peaks, RSS inside the worst-case corners, Monte Carlo converging to
 * the linearised distribution, and reproducibility by seed; the
 * slider-crank's sensitivities, names and 8 corners. */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "linkage.h"
#include "tolerance.h"
#include "work.h"

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

/* Quantiles (0.135 %, 50 %, 99.865 %) of the paper case with 500 samples,
 * recorded with the grid + Brent peak search before the series search
 * replaced it (`fourbar stackup --method montecarlo --samples 500 --seed S
 * --set tolerance.distribution=D --json`, 12 digits, commit 1a7a942): the
 * samples of a seed must not move. The bound is 1e-6 relative; the
 * two searches agree to ~1e-12 (measured 1.2e-12 on these). */
#define RECORDED_REL_TOL 1e-6
static const double RECORDED_S1_NORMAL_500[FB_TOL_NOUT][3] = {
    {78.2155783693, 78.7064641582, 79.1753586411}, /* coupler_omega_max_rad_s */
    {-42.3380511431, -42.2004564642, -42.067655953}, /* coupler_omega_min_rad_s */
    {7507.41238364, 7576.12460752, 7640.81094371}, /* coupler_alpha_max_rad_s2 */
    {-12065.6525796, -11972.5854566, -11874.8048473}, /* coupler_alpha_min_rad_s2 */
    {80.0858074096, 80.5663754208, 81.0136703233}, /* follower_omega_max_rad_s */
    {-43.9392263621, -43.8180668761, -43.687359106}, /* follower_omega_min_rad_s */
    {12389.4458928, 12487.0638656, 12578.6302828}, /* follower_alpha_max_rad_s2 */
    {-7577.71614923, -7513.91078312, -7445.93918819}, /* follower_alpha_min_rad_s2 */
    {0.534407859023, 0.536433911431, 0.538650391202}, /* transmission_angle_min_rad */
    {1.43346264844, 1.43690033943, 1.43999133132}, /* transmission_angle_max_rad */
};
static const double RECORDED_S2_UNIFORM_500[FB_TOL_NOUT][3] = {
    {78.1186827358, 78.6779570267, 79.3515169595}, /* coupler_omega_max_rad_s */
    {-42.3963064697, -42.1935904414, -42.0135280729}, /* coupler_omega_min_rad_s */
    {7486.38288071, 7571.79251828, 7661.68341789}, /* coupler_alpha_max_rad_s2 */
    {-12103.8198533, -11966.5033588, -11854.5942696}, /* coupler_alpha_min_rad_s2 */
    {79.8989086744, 80.5420433914, 81.1492205966}, /* follower_omega_max_rad_s */
    {-43.9956645252, -43.8140851931, -43.6201908909}, /* follower_omega_min_rad_s */
    {12347.8193019, 12483.0054013, 12610.2888507}, /* follower_alpha_max_rad_s2 */
    {-7600.97680125, -7510.44803612, -7428.63500205}, /* follower_alpha_min_rad_s2 */
    {0.533135538763, 0.536478007908, 0.539768392233}, /* transmission_angle_min_rad */
    {1.43186269895, 1.43683390036, 1.44248111586}, /* transmission_angle_max_rad */
};

static void check_recorded(const double rec[FB_TOL_NOUT][3], unsigned long seed, fb_distribution dist,
                           int jobs) {
  static fb_stackup_result r;
  assert_int_equal(fb_tol_analyse_jobs(&r, &paper, FB_TOL_MONTECARLO, 500, seed, dist, jobs, NULL, NULL,
                                       NULL), FB_OK);
  double worst = 0.0;
  for (int i = 0; i < FB_TOL_NOUT; i++)
    for (int j = 0; j < 3; j++) {
      assert_rel(r.q[i][j], rec[i][j], RECORDED_REL_TOL);
      worst = fmax(worst, fabs(r.q[i][j] - rec[i][j]) / fabs(rec[i][j]));
    }
  report_residual("quantiles vs recorded (rel)", worst, RECORDED_REL_TOL);
}

static void test_quantiles_equal_recorded(void **state) {
  (void)state;
  check_recorded(RECORDED_S1_NORMAL_500, 1, FB_DIST_NORMAL, 1);
  check_recorded(RECORDED_S2_UNIFORM_500, 2, FB_DIST_UNIFORM, 1);
  check_recorded(RECORDED_S1_NORMAL_500, 1, FB_DIST_NORMAL, 3);
}

static void test_jobs_same_numbers(void **state) {
  (void)state;
  /* 1000 samples: four blocks of 256, so three threads share the work */
  static fb_stackup_result a, b;
  assert_int_equal(fb_tol_analyse_jobs(&a, &paper, FB_TOL_MONTECARLO, 1000, 5, FB_DIST_NORMAL, 1, NULL,
                                       NULL, NULL), FB_OK);
  assert_int_equal(fb_tol_analyse_jobs(&b, &paper, FB_TOL_MONTECARLO, 1000, 5, FB_DIST_NORMAL, 3, NULL,
                                       NULL, NULL), FB_OK);
  assert_int_equal(b.jobs, 3);
  assert_memory_equal(a.q, b.q, sizeof a.q);
  assert_memory_equal(a.q_ci, b.q_ci, sizeof a.q_ci);
  assert_memory_equal(a.mc_mean, b.mc_mean, sizeof a.mc_mean);
  assert_memory_equal(a.mc_std, b.mc_std, sizeof a.mc_std);
  /* a failing sample: the same (lowest) one is named whatever the jobs */
  fb_case c;
  const char *sets[] = {"linkage.ground_mm=117.0"}; /* near the change point: samples fail */
  fb_test_paper_case(&c, sets, 1);
  fb_diag d1, d3;
  assert_int_equal(fb_tol_analyse_jobs(&a, &c, FB_TOL_MONTECARLO, 2000, 1, FB_DIST_NORMAL, 1, NULL, NULL,
                                       &d1), FB_ERR_ASSEMBLY);
  assert_int_equal(fb_tol_analyse_jobs(&b, &c, FB_TOL_MONTECARLO, 2000, 1, FB_DIST_NORMAL, 3, NULL, NULL,
                                       &d3), FB_ERR_ASSEMBLY);
  assert_string_equal(d1.msg, d3.msg);
  assert_non_null(strstr(d1.msg, "Monte Carlo sample "));
  assert_int_equal(fb_tol_analyse_jobs(&a, &paper, FB_TOL_MONTECARLO, 10, 1, FB_DIST_NORMAL, 0, NULL, NULL,
                                       &d1), FB_ERR_ARG);
}

/* P(B <= k) for B ~ Binomial(n, p) by summing the probability mass in logs:
 * independent of GSL's incomplete-beta route */
static double binom_cdf(int k, double p, int n) {
  double s = 0.0;
  for (int i = 0; i <= k; i++)
    s += exp(lgamma(n + 1.0) - lgamma(i + 1.0) - lgamma(n - i + 1.0) + i * log(p) + (n - i) * log1p(-p));
  return s;
}

static void test_quantile_confidence_ranks(void **state) {
  (void)state;
  size_t lo, hi;
  /* the textbook case: median of 100 samples, 95 %: X_(40) .. X_(61)
   * (P(B <= 39) = 0.0176, P(B <= 40) = 0.0284 for B ~ Binomial(100, 1/2)) */
  fb_tol_quantile_ranks(100, 0.5, 0.95, &lo, &hi);
  assert_int_equal(lo, 40);
  assert_int_equal(hi, 61);
  /* against direct binomial sums: each side's tail is at most 2.5 %, and one
   * rank further in would exceed it */
  const int ns[] = {30, 200, 1000, 5000};
  const double ps[] = {0.00135, 0.1, 0.5, 0.99865};
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 4; b++) {
      const int n = ns[a];
      const double p = ps[b];
      fb_tol_quantile_ranks((size_t)n, p, 0.95, &lo, &hi);
      if (lo) {
        assert_true(binom_cdf((int)lo - 1, p, n) <= 0.025 + 1e-12);
        if ((int)lo < n) assert_true(binom_cdf((int)lo, p, n) > 0.025 - 1e-12);
      } else {
        assert_true(binom_cdf(0, p, n) > 0.025 - 1e-12); /* even X_(1) cannot bound it */
      }
      if (hi) {
        assert_true(1.0 - binom_cdf((int)hi - 1, p, n) <= 0.025 + 1e-12);
        if (hi > 1) assert_true(1.0 - binom_cdf((int)hi - 2, p, n) > 0.025 - 1e-12);
      } else {
        assert_true(1.0 - binom_cdf(n - 1, p, n) > 0.025 - 1e-12);
      }
    }
  /* 500 samples cannot bound the 0.135 % quantile from below at 95 %, 10000 can */
  fb_tol_quantile_ranks(500, 0.00135, 0.95, &lo, &hi);
  assert_int_equal(lo, 0);
  fb_tol_quantile_ranks(10000, 0.00135, 0.95, &lo, &hi);
  assert_true(lo >= 1 && lo < 14 && hi > 14);
  /* the interval of a result contains its quantile */
  static fb_stackup_result r;
  assert_int_equal(fb_tol_analyse(&r, &paper, FB_TOL_MONTECARLO, 3000, 9, FB_DIST_NORMAL, NULL, NULL, NULL),
                   FB_OK);
  for (int i = 0; i < FB_TOL_NOUT; i++)
    for (int j = 0; j < 3; j++) assert_true(r.q_ci[i][j][0] <= r.q[i][j] && r.q[i][j] <= r.q_ci[i][j][1]);
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

/* a slider-crank (crank 50, coupler 120, offset 8 mm, 3000 rpm ccw) with
 * tolerances on its three lengths, from the paper case's other fields */
static fb_case slider_crank_case(double offset_m) {
  fb_case c = paper;
  c.mechanism = FB_MECH_SLIDER_CRANK;
  const double len[FB_LINK_COUNT] = {0.050, 0.120, offset_m, 0.0};
  const double tol[FB_LINK_COUNT] = {0.1e-3, 0.2e-3, 0.15e-3, 0.0};
  for (int k = 0; k < FB_LINK_COUNT; k++) c.nominal.length[k] = len[k], c.plus_minus[k] = tol[k];
  c.crank_speed = 3000 * 2 * M_PI / 60;
  c.direction = +1;
  return c;
}

/* the slider-crank's sensitivities against central differences of its
 * outputs, relative to the row's largest (some entries are near zero);
 * the same step and bound as the four-bar's */
static void test_slider_crank_sensitivities(void **state) {
  (void)state;
  const fb_case c = slider_crank_case(0.008);
  const double w = fb_case_omega2(&c);
  double s[FB_TOL_NOUT][FB_LINK_COUNT], fd[FB_TOL_NOUT][3];
  assert_int_equal(fb_tol_sensitivities_of(s, c.mechanism, &c.nominal, c.branch, w, NULL), FB_OK);
  for (int k = 0; k < 3; k++) {
    fb_linkage p = c.nominal, m = c.nominal;
    p.length[k] += SENS_FD_STEP_M;
    m.length[k] -= SENS_FD_STEP_M;
    double op[FB_TOL_NOUT], om[FB_TOL_NOUT];
    assert_int_equal(fb_tol_outputs_of(op, c.mechanism, &p, c.branch, w, NULL), FB_OK);
    assert_int_equal(fb_tol_outputs_of(om, c.mechanism, &m, c.branch, w, NULL), FB_OK);
    for (int i = 0; i < FB_TOL_NOUT; i++) fd[i][k] = (op[i] - om[i]) / (2 * SENS_FD_STEP_M);
  }
  double worst = 0.0;
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    const double scale = fmax(fabs(fd[i][0]), fmax(fabs(fd[i][1]), fabs(fd[i][2])));
    assert_true(s[i][FB_GROUND] == 0.0);
    for (int k = 0; k < 3; k++) {
      const double e = fabs(s[i][k] - fd[i][k]) / scale;
      worst = fmax(worst, e);
      if (e > SENS_REL_TOL)
        fail_msg("%s / d %s: exact %.10g, finite difference %.10g",
                 fb_tol_output_name_of(c.mechanism, i), fb_mech_slider_crank.length[k], s[i][k],
                 fd[i][k]);
    }
  }
  report_residual("slider-crank sensitivity vs finite difference (rel to row)", worst,
                  SENS_REL_TOL);
  /* at offset 0 the smallest transmission angle acos((crank + |offset|) /
   * coupler) has a corner: its offset entry is the +offset side's
   * derivative, -1 / (coupler sin mu_min), a one-sided difference's */
  const fb_case z = slider_crank_case(0.0);
  assert_int_equal(fb_tol_sensitivities_of(s, z.mechanism, &z.nominal, z.branch, w, NULL), FB_OK);
  const double mu = acos(0.050 / 0.120);
  assert_near(s[8][FB_LENGTH_OFFSET], -1.0 / (0.120 * sin(mu)), 1e-12 / (0.120 * sin(mu)));
  assert_near(s[9][FB_LENGTH_OFFSET], 0.0, 0.0); /* the stroke is even in the offset */
}

/* names: the four-bar's per-body names mapped by the description
 * (fb_mech_output_key, summary.json's), then the transmission angle and the
 * stroke; units from the names */
static void test_slider_crank_names(void **state) {
  (void)state;
  for (int i = 0; i < 8; i++) {
    char key[64];
    fb_mech_output_key(key, sizeof key, &fb_mech_slider_crank, fb_tol_output_name(i));
    assert_string_equal(fb_tol_output_name_of(FB_MECH_SLIDER_CRANK, i), key);
    assert_string_equal(fb_tol_output_name_of(FB_MECH_FOURBAR, i), fb_tol_output_name(i));
  }
  assert_string_equal(fb_tol_output_name_of(FB_MECH_SLIDER_CRANK, 8), "transmission_angle_min_rad");
  assert_string_equal(fb_tol_output_name_of(FB_MECH_SLIDER_CRANK, 9), "stroke_m");
  assert_string_equal(fb_tol_output_name_of(FB_MECH_SLIDER_CRANK, 10), "?");
  static const char *const unit[FB_TOL_NOUT] = {"rad/s", "rad/s", "rad/s^2", "rad/s^2", "m/s",
                                                "m/s", "m/s^2", "m/s^2", "rad", "m"};
  for (int i = 0; i < FB_TOL_NOUT; i++)
    assert_string_equal(fb_tol_output_unit_of(FB_MECH_SLIDER_CRANK, i), unit[i]);
}

/* corners: the 8 over crank, coupler and offset, each evaluated here, give
 * the analysis's range and the corner of the largest magnitude (its fourth
 * slot 0); RSS inside them at this size of tolerance */
static void test_slider_crank_corners(void **state) {
  (void)state;
  const fb_case c = slider_crank_case(-0.006);
  static fb_stackup_result r;
  assert_int_equal(fb_tol_analyse(&r, &c, FB_TOL_CORNERS | FB_TOL_RSS, 0, 1, FB_DIST_NORMAL, NULL,
                                  NULL, NULL), FB_OK);
  double lo[FB_TOL_NOUT], hi[FB_TOL_NOUT], best[FB_TOL_NOUT];
  int arg[FB_TOL_NOUT] = {0};
  for (int m = 0; m < 8; m++) {
    fb_linkage lk = c.nominal;
    for (int k = 0; k < 3; k++) lk.length[k] += ((m >> k) & 1 ? 1 : -1) * c.plus_minus[k];
    double v[FB_TOL_NOUT];
    assert_int_equal(fb_tol_outputs_of(v, c.mechanism, &lk, c.branch, fb_case_omega2(&c), NULL),
                     FB_OK);
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      if (m == 0 || v[i] < lo[i]) lo[i] = v[i];
      if (m == 0 || v[i] > hi[i]) hi[i] = v[i];
      if (m == 0 || fabs(v[i]) > best[i]) best[i] = fabs(v[i]), arg[i] = m;
    }
  }
  for (int i = 0; i < FB_TOL_NOUT; i++) {
    assert_near(r.corner_min[i], lo[i], 0.0);
    assert_near(r.corner_max[i], hi[i], 0.0);
    for (int k = 0; k < 3; k++)
      assert_int_equal(r.corner_of_max[i][k], (arg[i] >> k) & 1 ? 1 : -1);
    assert_int_equal(r.corner_of_max[i][FB_GROUND], 0);
    assert_true(r.nominal[i] - r.rss_half[i] >= lo[i] - 1e-12 * fabs(lo[i]));
    assert_true(r.nominal[i] + r.rss_half[i] <= hi[i] + 1e-12 * fabs(hi[i]));
  }
}

/* The Monte Carlo's up-front estimate: the samples times this case's own
 * cost per evaluation, measured by a probe (work.h) that evaluates the
 * outputs at least once and until it has spent FB_WORK_PROBE_S of CPU,
 * over the jobs; its memory against a measurement (issue 54: `/usr/bin/time
 * fourbar stackup --method montecarlo --samples 1000000` on the paper
 * case, 143,880 kB peak resident): conservative, within 2x. Nothing here
 * compares a time with a time (the probe's figure is the machine's):
 * counts and the arithmetic only; the estimate's size against measured
 * CPU is in docs/performance.md. */
#define MC_1E6_MEASURED_BYTES (143880.0 * 1024.0)
#define MC_ESTIMATE_OVER_MEASURED_MAX 2.0

static void test_monte_carlo_estimate(void **state) {
  (void)state;
  double each, bytes, seconds;
  int evals = 0;
  fb_diag d;
  if (fb_tol_eval_cost(&each, &evals, 0.0, &paper, &d) != FB_OK) fail_msg("%s", d.msg);
  assert_true(evals >= FB_WORK_PROBE_MIN && evals <= FB_WORK_PROBE_MAX);
  assert_true(isfinite(each) && each > 0.0);
  fb_tol_estimate(each, 1000000, 1, &bytes, &seconds);
  assert_true(seconds == 1e6 * each);
  double b4, s4;
  fb_tol_estimate(each, 1000000, 4, &b4, &s4);
  assert_true(s4 == seconds / 4.0 && b4 == bytes);
  if (fb_test_verbose())
    fprintf(stderr, "  %d evaluations probed, %.3g s each: 1e6 samples estimated at %.3g s, "
            "%.3g MiB; measured %.3g MiB\n", evals, each, seconds, bytes / 1048576.0,
            MC_1E6_MEASURED_BYTES / 1048576.0);
  assert_true(bytes >= MC_1E6_MEASURED_BYTES &&
              bytes <= MC_ESTIMATE_OVER_MEASURED_MAX * MC_1E6_MEASURED_BYTES);
}

/* The probe for long work (work.h): work estimated above FB_WORK_NOTE_S
 * is probed in further windows up to FB_WORK_PROBE_SHARE of its estimate
 * and FB_WORK_PROBE_LONG_S, and the fastest window kept, never above the
 * first window's mean. Counts only: a million samples of the paper case
 * (about 15 s) probe more evaluations than work of unknown size, and no
 * more than FB_WORK_PROBE_MAX. */
static void test_probe_for_long_work(void **state) {
  (void)state;
  double short_each, long_each;
  int short_evals = 0, long_evals = 0;
  fb_diag d;
  if (fb_tol_eval_cost(&short_each, &short_evals, 0.0, &paper, &d) != FB_OK) fail_msg("%s", d.msg);
  if (fb_tol_eval_cost(&long_each, &long_evals, 1e6, &paper, &d) != FB_OK) fail_msg("%s", d.msg);
  if (fb_test_verbose())
    fprintf(stderr, "  unknown work: %d evaluations, %.3g s each; 1e6 samples: %d, %.3g s each\n",
            short_evals, short_each, long_evals, long_each);
  assert_true(1e6 * short_each > FB_WORK_NOTE_S); /* precondition: long work */
  assert_true(long_evals > short_evals);
  assert_true(long_evals <= FB_WORK_PROBE_MAX);
  assert_true(isfinite(long_each) && long_each > 0.0);
}

int main(void) {
  fb_test_paper_case(&paper, NULL, 0);
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_sensitivities_vs_finite_differences),
      cmocka_unit_test(test_monte_carlo_estimate),
      cmocka_unit_test(test_probe_for_long_work),
      cmocka_unit_test(test_rss_inside_corners_and_mc_converges),
      cmocka_unit_test(test_same_seed_same_numbers),
      cmocka_unit_test(test_quantiles_equal_recorded),
      cmocka_unit_test(test_jobs_same_numbers),
      cmocka_unit_test(test_quantile_confidence_ranks),
      cmocka_unit_test(test_worst_corner),
      cmocka_unit_test(test_slider_crank_sensitivities),
      cmocka_unit_test(test_slider_crank_names),
      cmocka_unit_test(test_slider_crank_corners),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
