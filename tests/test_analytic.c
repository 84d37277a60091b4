/* The analytic peak search (Taylor series in crank angle, adaptive nodes)
 * against the dense-grid search (uniform grid + Brent) on many random
 * Grashof linkages that turn their crank fully, on both branches, including
 * linkages close to a change point (folding: transmission angle near 0 or
 * pi) and the nominal linkages of every hard case.
 *
 *            C
 *           / \
 *  coupler /   \ follower        a random linkage: lengths in [0.05, 1] m,
 *         B     \                 the shortest link the crank
 *  crank /       \                (crank-rocker) or the ground (double-crank)
 *       A ------- D
 */
#include <gsl/gsl_rng.h>

#include "analytic.h"
#include "casefile.h"
#include "fb_test.h"

/* crank angles of the reference grid: 2 pi / 50000 = 1.3e-4 rad, below a
 * tenth of the narrowest feature here (the distance to the nearest complex
 * singularity, ~sqrt(2 eps) = 1.4e-3 rad at a change-point gap eps = 1e-6) */
#define DENSE_GRID 50000
/* both searches refine to ~1e-12 rad; the values then differ by rounding
 * alone, which the near-change-point linkages amplify (sin(theta3 - theta4)
 * small in both methods' formulas): measured up to 6e-11 of the output's
 * scale (the larger of |max| and |min|); 1e-9 leaves room for that */
#define PEAK_VS_GRID_REL_TOL 1e-9
/* random linkages of each kind */
#define N_RANDOM 150
#define N_NEAR_CHANGE_POINT 60
/* relative gap to the change point s + l = p + q: 10^-U(1, 6) */
#define GAP_DECADES_MIN 1.0
#define GAP_DECADES_MAX 6.0

static double worst_rel;
static int compared;

/* compares the two searches on one linkage; returns 0 when the crank does
 * not turn fully (not a test case) */
static int compare(const fb_linkage *lk, fb_branch branch, double omega2, const char *what) {
  fb_peaks p, q;
  double wp[8], wq[8];
  if (fb_analytic_peaks_where(&p, wp, lk, branch, omega2, NULL) != FB_OK) return 0;
  fb_diag d;
  if (fb_analytic_peaks_grid(&q, wq, lk, branch, omega2, DENSE_GRID, &d) != FB_OK)
    fail_msg("%s: the grid search fails where the series search does not: %s", what, d.msg);
  /* the eight extremes in where's order: coupler omega max, min, alpha max,
   * min, then the follower's */
  const double a[8] = {p.coupler.omega_max, p.coupler.omega_min, p.coupler.alpha_max,
                       p.coupler.alpha_min, p.follower.omega_max, p.follower.omega_min,
                       p.follower.alpha_max, p.follower.alpha_min};
  const double b[8] = {q.coupler.omega_max, q.coupler.omega_min, q.coupler.alpha_max,
                       q.coupler.alpha_min, q.follower.omega_max, q.follower.omega_min,
                       q.follower.alpha_max, q.follower.alpha_min};
  for (int i = 0; i < 8; i++) {
    /* scale: the larger magnitude of the same quantity's max and min */
    const int j = i - i % 2;
    const double scale = fmax(fabs(b[j]), fabs(b[j + 1]));
    const double e = fabs(a[i] - b[i]) / scale;
    if (e > worst_rel) worst_rel = e;
    if (!(e <= PEAK_VS_GRID_REL_TOL))
      fail_msg("%s (%.12g, %.12g, %.12g, %.12g m, %s): peak %d series %.15g at %.12g rad, "
               "grid %.15g at %.12g rad, |diff| = %.3g of scale",
               what, lk->length[0], lk->length[1], lk->length[2], lk->length[3],
               branch == FB_BRANCH_OPEN ? "open" : "crossed", i, a[i], wp[i], b[i], wq[i], e);
    /* the reported crank angle reproduces the peak through fb_linkage_solve */
    fb_linkage_state s;
    assert_int_equal(fb_linkage_solve(&s, lk, branch, wp[i], omega2, 0.0, NULL), FB_OK);
    const double direct[8] = {s.coupler_omega,  s.coupler_omega,  s.coupler_alpha,  s.coupler_alpha,
                              s.follower_omega, s.follower_omega, s.follower_alpha, s.follower_alpha};
    if (!(fabs(direct[i] - a[i]) <= PEAK_VS_GRID_REL_TOL * scale))
      fail_msg("%s: peak %d %.15g but the solve at its crank angle %.12g gives %.15g", what, i,
               a[i], wp[i], direct[i]);
  }
  compared++;
  return 1;
}

/* random Grashof lengths with the shortest link as crank or ground; gap > 0
 * sets s = p + q - l - gap l (near the change point), gap = 0 draws freely */
static void random_linkage(fb_linkage *lk, gsl_rng *r, double gap) {
  for (;;) {
    double L[4];
    for (int k = 0; k < 4; k++) L[k] = 0.05 + 0.95 * gsl_rng_uniform(r);
    /* L[0] is the shortest: swap the minimum into place */
    int m = 0;
    for (int k = 1; k < 4; k++)
      if (L[k] < L[m]) m = k;
    double t = L[0];
    L[0] = L[m], L[m] = t;
    const double l = fmax(L[1], fmax(L[2], L[3]));
    const double pq = L[1] + L[2] + L[3] - l;
    if (gap > 0.0) L[0] = pq - l - gap * l;
    if (!(L[0] > 0.0 && L[0] + l < pq)) continue;
    /* crank-rocker (shortest = crank) or double-crank (shortest = ground) */
    const int ground_shortest = gsl_rng_uniform(r) < 0.3;
    lk->length[FB_CRANK] = ground_shortest ? L[3] : L[0];
    lk->length[FB_GROUND] = ground_shortest ? L[0] : L[3];
    lk->length[FB_COUPLER] = L[1];
    lk->length[FB_FOLLOWER] = L[2];
    double lo, hi;
    int full;
    if (fb_linkage_crank_range(lk, &lo, &hi, &full, NULL) == FB_OK && full) return;
  }
}

static void test_random_linkages_match_dense_grid(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 20);
  for (int n = 0; n < N_RANDOM + N_NEAR_CHANGE_POINT; n++) {
    fb_linkage lk;
    const double gap = n < N_RANDOM ? 0.0
                                    : pow(10.0, -(GAP_DECADES_MIN + (GAP_DECADES_MAX - GAP_DECADES_MIN) *
                                                                        gsl_rng_uniform(r)));
    random_linkage(&lk, r, gap);
    const fb_branch br = n % 2 ? FB_BRANCH_CROSSED : FB_BRANCH_OPEN;
    const double omega2 = n % 3 ? 104.7 : -57.3; /* both directions */
    assert_true(compare(&lk, br, omega2, n < N_RANDOM ? "random" : "near change point"));
  }
  gsl_rng_free(r);
}

static void compare_case(const char *path, const char *name, void *user) {
  fb_case c;
  fb_diag d;
  if (fb_casefile_load(&c, path, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  *(int *)user += compare(&c.nominal, c.branch, fb_case_omega2(&c), name);
}

static void test_hard_cases_match_dense_grid(void **state) {
  (void)state;
  int turning = 0;
  assert_true(fb_test_each_hard_case(compare_case, &turning) >= 10);
  assert_true(turning >= 10); /* every hard case's crank turns fully */
}

static void test_report(void **state) {
  (void)state;
  /* the figure the closing note quotes; always printed */
  fprintf(stderr, "  largest |series - dense grid| over %d linkages: %.3e of the output's scale\n",
          compared, worst_rel);
  assert_true(compared >= N_RANDOM + N_NEAR_CHANGE_POINT + 10);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_random_linkages_match_dense_grid),
      cmocka_unit_test(test_hard_cases_match_dense_grid),
      cmocka_unit_test(test_report),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
