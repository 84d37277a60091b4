/* The verdict's statistics (equivalence.h): the two one-sided tests of a
 * ratio of means with Welch's degrees of freedom, Fieller's interval, and
 * Holm's step-down. Checked three ways:
 *
 * - against hand-worked values (the Welch-Satterthwaite df of a textbook
 *   pair, the exact spread-free limits, the zero-mean cases);
 * - against an independent derivation of what the tests promise: by Monte
 *   Carlo, normal samples drawn with the true ratio on a margin (GSL's
 *   Mersenne Twister), the share declared equivalent is alpha (the two
 *   one-sided tests' size), the share declared different with the ratio on
 *   a margin at most alpha, and with the ratio at 1 the share equivalent is
 *   the power a normal approximation predicts;
 * - Fieller's interval: the margins at which each one-sided test just
 *   stops rejecting are its ends. */
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>

#include "equivalence.h"
#include "fb_test.h"

/* the level the verdict uses (verdict.h) for the simulation checks */
#define ALPHA 0.05
/* Monte Carlo draws: the binomial standard error of a share near 0.05 over
 * 20000 draws is 0.0015, so a 4.5-sigma band below is 0.007 wide */
#define DRAWS 20000
#define SHARE_TOL 0.007

static void test_welch_df_and_exact_limits(void **state) {
  (void)state;
  /* x: 1, 2, 3, 4 (mean 2.5, sd^2 5/3); y: 2, 4, 6 (mean 4, sd^2 4): at
   * theta = 1 (the ratio's test at theta = 1 is Welch's test of the
   * difference) a = 5/12, b = 4/3, df = (a + b)^2 / (a^2 / 3 + b^2 / 2),
   * worked by hand: 3.0625 / (0.0578704 + 0.888889) = 3.23472 */
  const double x[4] = {1, 2, 3, 4}, y[3] = {2, 4, 6};
  fb_equiv e;
  fb_equiv_ratio(&e, x, 4, y, 3, 1.25, ALPHA);
  assert_int_equal(e.nx, 4);
  assert_int_equal(e.ny, 3);
  assert_near(e.mean_x, 2.5, 1e-15);
  assert_near(e.sd_y, 2.0, 1e-15);
  assert_near(e.ratio, 0.625, 1e-15);
  /* the df at the ratio 0.625: b = 0.625^2 4/3 = 0.520833 */
  const double a = 5.0 / 12.0, b = 0.625 * 0.625 * 4.0 / 3.0;
  assert_near(e.df, (a + b) * (a + b) / (a * a / 3.0 + b * b / 2.0), 1e-12);
  const double bb = 4.0 / 3.0;
  assert_near((a + bb) * (a + bb) / (a * a / 3.0 + bb * bb / 2.0), 3.23472, 1e-5);
  /* no spread on either side: the ratio is exact */
  const double c1[3] = {2, 2, 2}, c2[3] = {2.2, 2.2, 2.2}, c3[3] = {3, 3, 3};
  fb_equiv_ratio(&e, c2, 3, c1, 3, 1.25, ALPHA);
  assert_int_equal(e.decision, FB_EQUIV_EQUIVALENT);
  assert_near(e.p_equivalent, 0.0, 0.0);
  assert_near(e.lo, 1.1, 1e-15);
  fb_equiv_ratio(&e, c3, 3, c1, 3, 1.25, ALPHA);
  assert_int_equal(e.decision, FB_EQUIV_DIFFERENT);
  assert_near(e.p_different, 0.0, 0.0);
  /* no impacts anywhere: equivalent; none against some: different */
  const double z[4] = {0, 0, 0, 0}, some[4] = {3, 5, 4, 6};
  fb_equiv_ratio(&e, z, 4, z, 4, 1.25, ALPHA);
  assert_int_equal(e.decision, FB_EQUIV_EQUIVALENT);
  fb_equiv_ratio(&e, some, 4, z, 4, 1.25, ALPHA);
  assert_int_equal(e.decision, FB_EQUIV_DIFFERENT);
  fb_equiv_ratio(&e, z, 4, some, 4, 1.25, ALPHA);
  assert_int_equal(e.decision, FB_EQUIV_DIFFERENT);
  /* a non-finite member is left out and counted, never silently */
  const double holes[4] = {3, NAN, 4, 5};
  fb_equiv_ratio(&e, holes, 4, some, 4, 1.25, ALPHA);
  assert_int_equal(e.nx, 3);
  assert_int_equal(e.skipped_x, 1);
  /* one finite value: nothing to test */
  const double one[2] = {3, NAN};
  fb_equiv_ratio(&e, one, 2, some, 4, 1.25, ALPHA);
  assert_int_equal(e.decision, FB_EQUIV_UNDEFINED);
}

/* Fieller's interval's ends are the margins at which the two one-sided tests
 * at the (1 - 2 alpha) level just stop rejecting: a margin equal to its
 * upper end (at the interval's df) leaves p_U = alpha */
static void test_fieller_ends_are_the_tests_boundaries(void **state) {
  (void)state;
  const double x[6] = {10.2, 11.9, 9.1, 12.5, 10.8, 11.1}, y[5] = {10.0, 9.5, 11.2, 10.4, 9.9};
  fb_equiv e;
  fb_equiv_ratio(&e, x, 6, y, 5, 1.25, ALPHA);
  assert_true(e.lo < e.ratio && e.ratio < e.hi);
  /* at theta = hi the upper test's statistic is -t_{1-alpha, df(hi)}; the
   * interval used df at the ratio: the two agree to the df's change */
  const double a = e.sd_x * e.sd_x / e.nx;
  const double b = e.hi * e.hi * e.sd_y * e.sd_y / e.ny;
  const double t = (e.mean_x - e.hi * e.mean_y) / sqrt(a + b);
  assert_near(t, -gsl_cdf_tdist_Pinv(1.0 - ALPHA, e.df), 1e-9);
}

/* the share of draws decided `want` when x ~ N(ratio mu, sd), y ~ N(mu, sd) */
static double share(gsl_rng *g, double ratio, int n, double sd, fb_equiv_decision want) {
  const double mu = 100.0;
  int hits = 0;
  double x[64], y[64];
  for (int d = 0; d < DRAWS; d++) {
    for (int i = 0; i < n; i++) {
      x[i] = ratio * mu + gsl_ran_gaussian(g, sd);
      y[i] = mu + gsl_ran_gaussian(g, sd);
    }
    fb_equiv e;
    fb_equiv_ratio(&e, x, n, y, n, 1.25, ALPHA);
    hits += e.decision == want;
  }
  return (double)hits / DRAWS;
}

static void test_levels_by_simulation(void **state) {
  (void)state;
  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(g, 55);
  /* the ratio on the upper margin: equivalent in alpha of the draws (the
   * one-sided test at its boundary; the other side is 8 standard errors
   * away at n = 16, sd = 10); never much more */
  const double at_margin = share(g, 1.25, 16, 10.0, FB_EQUIV_EQUIVALENT);
  if (fb_test_verbose()) print_message("equivalent at the margin: %.4f\n", at_margin);
  assert_true(fabs(at_margin - ALPHA) < SHARE_TOL);
  const double below = share(g, 0.8, 16, 10.0, FB_EQUIV_EQUIVALENT);
  assert_true(fabs(below - ALPHA) < SHARE_TOL);
  /* on the margin, different in at most alpha / 2 (each side at alpha / 2) */
  const double diff = share(g, 1.25, 16, 10.0, FB_EQUIV_DIFFERENT);
  if (fb_test_verbose()) print_message("different at the margin: %.4f\n", diff);
  assert_true(diff < ALPHA / 2.0 + SHARE_TOL);
  /* equal means: power by the normal approximation. The standard error of
   * xbar - theta ybar at theta = 1.25 is 10 sqrt((1 + 1.5625) / 16) = 4.0;
   * D = 100 - 125 = -25, 6.25 standard errors below 0; the critical t on
   * ~29 df is 1.70: both one-sided tests reject with probability ~1, and
   * at n = 4 (se 8.0, D / se = 3.1, t_{0.95, ~5} = 2.0) about
   * P(T' > 2.0 - 3.1) per side: >= 0.8 overall */
  assert_true(share(g, 1.0, 16, 10.0, FB_EQUIV_EQUIVALENT) > 0.99);
  const double power4 = share(g, 1.0, 4, 10.0, FB_EQUIV_EQUIVALENT);
  if (fb_test_verbose()) print_message("power at n = 4: %.4f\n", power4);
  assert_true(power4 > 0.6 && power4 < 0.95);
  gsl_rng_free(g);
}

static void test_holm(void **state) {
  (void)state;
  /* m = 3 at 0.05: 0.01 <= 0.05 / 3, then 0.02 <= 0.05 / 2, then 0.06 > 0.05 */
  const double p[3] = {0.02, 0.06, 0.01};
  int rej[3];
  assert_int_equal(fb_holm(p, 3, 0.05, rej), 2);
  assert_int_equal(rej[0], 1);
  assert_int_equal(rej[1], 0);
  assert_int_equal(rej[2], 1);
  /* a first p above alpha / m stops it: nothing rejected */
  const double q[3] = {0.02, 0.03, 0.04};
  assert_int_equal(fb_holm(q, 3, 0.05, rej), 0);
  /* NaN: never rejected, but counted in m */
  const double w[2] = {NAN, 0.02};
  assert_int_equal(fb_holm(w, 2, 0.05, rej), 1);
  assert_int_equal(rej[0], 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_welch_df_and_exact_limits),
      cmocka_unit_test(test_fieller_ends_are_the_tests_boundaries),
      cmocka_unit_test(test_levels_by_simulation),
      cmocka_unit_test(test_holm),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
