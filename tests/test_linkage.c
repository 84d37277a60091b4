/* Exact four-bar kinematics: closed-form oracles.
 *
 *            C
 *           / \
 *  coupler /   \ follower
 *         B     \
 *  crank /       \
 *       A ------- D
 *          ground
 *
 * The paper's crank-rocker (108, 279.4, 270.5, 254 mm) is the main fixture. */
#include <string.h>

#include "analytic.h"
#include "fb_test.h"
#include "linkage.h"

/* Loop closure holds to roundoff: lengths ~0.3 m, so double precision gives
 * ~1e-16 * 0.3 per term; 1e-12 m is the bound with ample margin. */
#define LOOP_TOL_M 1e-12
/* Central differences in crank angle with step DTH: truncation error of the
 * first difference is DTH^2 / 6 * max|theta'''| (~10 for this linkage, so
 * 2e-8) plus roundoff eps * pi / DTH (~7e-12); 1e-7 per unit crank speed
 * covers both. */
#define DTH 1e-4
#define FD_VEL_TOL 1e-7
/* Second difference: DTH^2 / 12 * max|theta''''| (~100: 1e-7) plus roundoff
 * 4 eps pi / DTH^2 (~3e-7); 2e-6 per unit crank speed squared. */
#define FD_ACC_TOL 2e-6
/* docs/paper.md prints peak |alpha| / omega^2 to 7 digits: half a unit in the last
 * digit is 5e-7 absolute. */
#define PAPER_RATIO_TOL 5e-7
/* Transmission angle: acos near 0.5 rad has no conditioning trouble. */
#define ANGLE_TOL 1e-12

static const fb_linkage paper = {{0.108, 0.2794, 0.2705, 0.254}};

/* A sum of two lengths near 0.4 m: the decimal inputs and the sum each round
 * by half an ulp (5.6e-17 m); 1e-15 m is a few ulps. */
#define GRASHOF_SUM_TOL 1e-15

static double loop_residual(const fb_linkage *lk, const fb_linkage_state *s) {
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER];
  const double c = lk->length[FB_FOLLOWER], g = lk->length[FB_GROUND];
  double rx = a * cos(s->crank_angle) + b * cos(s->coupler_angle) - c * cos(s->follower_angle) - g;
  double ry = a * sin(s->crank_angle) + b * sin(s->coupler_angle) - c * sin(s->follower_angle);
  return hypot(rx, ry);
}

static void test_loop_closure_both_branches(void **state) {
  (void)state;
  double worst = 0.0;
  for (int br = 0; br < 2; br++)
    for (int k = 0; k < 3600; k++) {
      fb_linkage_state s;
      double th = 2.0 * M_PI * k / 3600.0;
      assert_int_equal(fb_linkage_solve(&s, &paper, (fb_branch)br, th, 1.0, 0.0, NULL), FB_OK);
      double r = loop_residual(&paper, &s);
      if (r > worst) worst = r;
      assert_true(r < LOOP_TOL_M);
      /* the joint points agree with the angles */
      assert_near(s.b[0] + paper.length[FB_COUPLER] * cos(s.coupler_angle), s.c[0], LOOP_TOL_M);
      assert_near(s.c[0] - paper.length[FB_FOLLOWER] * cos(s.follower_angle),
                  paper.length[FB_GROUND], LOOP_TOL_M);
    }
  report_residual("loop closure [m]", worst, LOOP_TOL_M);
}

static void test_branches_are_mirror_sides(void **state) {
  (void)state;
  /* open: C left of B->D (cross product > 0); crossed: right */
  for (int k = 0; k < 360; k++) {
    double th = 2.0 * M_PI * k / 360.0;
    fb_linkage_state o, x;
    fb_linkage_solve(&o, &paper, FB_BRANCH_OPEN, th, 1.0, 0.0, NULL);
    fb_linkage_solve(&x, &paper, FB_BRANCH_CROSSED, th, 1.0, 0.0, NULL);
    double bdx = paper.length[FB_GROUND] - o.b[0], bdy = -o.b[1];
    double cross_o = bdx * (o.c[1] - o.b[1]) - bdy * (o.c[0] - o.b[0]);
    double cross_x = bdx * (x.c[1] - x.b[1]) - bdy * (x.c[0] - x.b[0]);
    assert_true(cross_o > 0.0);
    assert_true(cross_x < 0.0);
  }
}

static double wrap(double x) { return remainder(x, 2.0 * M_PI); }

static void test_velocity_acceleration_vs_central_differences(void **state) {
  (void)state;
  const double omega2 = -104.71975511965977; /* 1000 rpm clockwise */
  const double alpha2 = 250.0;               /* a non-zero crank acceleration too */
  double worst_v = 0.0, worst_a = 0.0;
  for (int br = 0; br < 2; br++)
    for (int k = 0; k < 360; k++) {
      double th = 2.0 * M_PI * (k + 0.5) / 360.0;
      fb_linkage_state m, z, p;
      fb_linkage_solve(&m, &paper, (fb_branch)br, th - DTH, omega2, alpha2, NULL);
      fb_linkage_solve(&z, &paper, (fb_branch)br, th, omega2, alpha2, NULL);
      fb_linkage_solve(&p, &paper, (fb_branch)br, th + DTH, omega2, alpha2, NULL);
      const double pos_m[2] = {m.coupler_angle, m.follower_angle};
      const double pos_z[2] = {z.coupler_angle, z.follower_angle};
      const double pos_p[2] = {p.coupler_angle, p.follower_angle};
      const double vel[2] = {z.coupler_omega, z.follower_omega};
      const double acc[2] = {z.coupler_alpha, z.follower_alpha};
      for (int i = 0; i < 2; i++) {
        double d1 = wrap(pos_p[i] - pos_m[i]) / (2.0 * DTH);            /* dtheta/dtheta2 */
        double d2 = (wrap(pos_p[i] - pos_z[i]) - wrap(pos_z[i] - pos_m[i])) / (DTH * DTH);
        double ev = fabs(vel[i] - d1 * omega2) / fabs(omega2);
        double ea = fabs(acc[i] - (d1 * alpha2 + d2 * omega2 * omega2)) / (omega2 * omega2);
        if (ev > worst_v) worst_v = ev;
        if (ea > worst_a) worst_a = ea;
        assert_true(ev < FD_VEL_TOL);
        assert_true(ea < FD_ACC_TOL);
      }
    }
  report_residual("velocity vs central difference", worst_v, FD_VEL_TOL);
  report_residual("acceleration vs second difference", worst_a, FD_ACC_TOL);
}

static void test_grashof_classes(void **state) {
  (void)state;
  struct {
    fb_linkage lk;
    fb_grashof want;
  } cases[] = {
      {{{0.108, 0.2794, 0.2705, 0.254}}, FB_GRASHOF_CRANK_ROCKER}, /* paper: s = crank */
      {{{4.0, 5.0, 4.5, 2.0}}, FB_GRASHOF_DOUBLE_CRANK},           /* s = ground */
      {{{4.0, 2.0, 4.5, 5.0}}, FB_GRASHOF_DOUBLE_ROCKER},          /* s = coupler */
      {{{4.0, 5.0, 2.0, 4.5}}, FB_GRASHOF_ROCKER_CRANK},           /* s = follower */
      {{{2.0, 4.0, 3.0, 3.0}}, FB_GRASHOF_CHANGE_POINT},           /* 2 + 4 = 3 + 3 */
      {{{5.0, 1.0, 5.5, 10.0}}, FB_GRASHOF_NON_GRASHOF},           /* 1 + 10 > 5 + 5.5 */
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    assert_int_equal(fb_linkage_grashof(&cases[i].lk), cases[i].want);
  assert_string_equal(fb_grashof_name(FB_GRASHOF_CRANK_ROCKER), "crank-rocker");
  assert_string_equal(fb_grashof_name(FB_GRASHOF_NON_GRASHOF), "non-Grashof");
}

/* The sums the class compares, and where a change-point linkage folds flat:
 * at a fold the velocity problem is singular (fb_linkage_solve refuses the
 * toggle), a little way off it solves: an independent check of the angles.
 *
 *   kite 1 / 1 / 2 / 2 (crank, coupler, follower, ground):
 *     theta2 = 0:  A --- B --- D, C on the line beyond (|BD| = 1 = |b - c|)
 *     theta2 = pi: B --- A ----- D, C folded back (|BD| = 3 = b + c) */
static void test_grashof_sums_and_folds(void **state) {
  (void)state;
  double sl, pq, th[2];
  int s, l;
  fb_linkage_grashof_sums(&paper, &sl, &pq, &s, &l);
  assert_near(sl, 0.3874, GRASHOF_SUM_TOL);
  assert_near(pq, 0.5245, GRASHOF_SUM_TOL);
  assert_int_equal(s, FB_CRANK);
  assert_int_equal(l, FB_COUPLER);
  assert_int_equal(fb_linkage_fold_angles(&paper, th), 0);
  char text[512];
  fb_linkage_grashof_text(text, sizeof text, &paper);
  assert_non_null(strstr(text, "Grashof crank-rocker: s + l = 108 + 279.4 = 387.4 mm < p + q = 524.5 mm"));
  assert_non_null(strstr(text, "margin 137.1 mm"));

  const fb_linkage kite = {{1.0, 1.0, 2.0, 2.0}};
  assert_int_equal(fb_linkage_grashof(&kite), FB_GRASHOF_CHANGE_POINT);
  assert_int_equal(fb_linkage_fold_angles(&kite, th), 2);
  assert_near(th[0], 0.0, 0.0);
  assert_near(th[1], M_PI, 0.0);
  const fb_linkage cp = {{2.0, 4.0, 3.0, 3.0}}; /* folds at theta2 = 0 only */
  assert_int_equal(fb_linkage_fold_angles(&cp, th), 1);
  assert_near(th[0], 0.0, 0.0);
  const double off[3] = {0.0, 0.1, M_PI};
  const fb_status want[3] = {FB_ERR_ASSEMBLY, FB_OK, FB_ERR_ASSEMBLY};
  for (int k = 0; k < 3; k++) {
    fb_linkage_state st;
    fb_diag d;
    assert_int_equal(fb_linkage_solve(&st, &kite, FB_BRANCH_OPEN, off[k], 1.0, 0.0, &d), want[k]);
  }
  fb_linkage_grashof_text(text, sizeof text, &kite);
  assert_non_null(strstr(text, "change-point"));
  assert_non_null(strstr(text, "0 deg and 180 deg"));
}

static void test_unassemblable_gives_error_not_nan(void **state) {
  (void)state;
  const fb_linkage bad = {{0.01, 0.01, 0.01, 1.0}}; /* coupler + follower << ground */
  fb_diag d;
  double lo, hi;
  int full;
  assert_int_equal(fb_linkage_crank_range(&bad, &lo, &hi, &full, &d), FB_ERR_ASSEMBLY);
  assert_non_null(strstr(d.msg, "no crank angle closes the loop"));
  fb_linkage_state s;
  memset(&s, 0, sizeof s);
  assert_int_equal(fb_linkage_solve(&s, &bad, FB_BRANCH_OPEN, 0.3, 1.0, 0.0, &d), FB_ERR_ASSEMBLY);
  assert_non_null(strstr(d.msg, "cannot be assembled"));
  assert_true(s.coupler_angle == 0.0); /* untouched: no NaN leaks out */
  const fb_linkage neg = {{-0.1, 0.3, 0.3, 0.3}};
  assert_int_equal(fb_linkage_solve(&s, &neg, FB_BRANCH_OPEN, 0.0, 1.0, 0.0, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "crank length"));
}

static void test_crank_range_closed_form(void **state) {
  (void)state;
  double lo, hi;
  int full;
  assert_int_equal(fb_linkage_crank_range(&paper, &lo, &hi, &full, NULL), FB_OK);
  assert_true(full);
  assert_near(lo, 0.0, 0.0);
  assert_near(hi, M_PI, 0.0);
  /* a non-Grashof linkage driven from its longest-neighbour link: the limit
   * angle satisfies a^2 + g^2 - 2 a g cos(hi) = (b + c)^2 */
  const fb_linkage tri = {{0.3, 0.1, 0.25, 0.35}};
  assert_int_equal(fb_linkage_crank_range(&tri, &lo, &hi, &full, NULL), FB_OK);
  assert_false(full);
  double want_hi = acos((0.09 + 0.1225 - 0.35 * 0.35) / (2 * 0.3 * 0.35));
  double want_lo = acos((0.09 + 0.1225 - 0.15 * 0.15) / (2 * 0.3 * 0.35));
  assert_near(hi, want_hi, ANGLE_TOL);
  assert_near(lo, want_lo, ANGLE_TOL);
  /* inside the range it solves, outside it refuses */
  fb_linkage_state s;
  assert_int_equal(fb_linkage_solve(&s, &tri, FB_BRANCH_OPEN, 0.5 * (lo + hi), 1, 0, NULL), FB_OK);
  assert_int_equal(fb_linkage_solve(&s, &tri, FB_BRANCH_OPEN, 0.5 * lo, 1, 0, NULL), FB_ERR_ASSEMBLY);
}

static void test_transmission_angle_extremes(void **state) {
  (void)state;
  double mu_min, mu_max;
  assert_int_equal(fb_linkage_transmission_range(&paper, &mu_min, &mu_max, NULL), FB_OK);
  /* closed form at theta2 = 0 (|BD| = g - a) and pi (|BD| = g + a) */
  const double b = 0.2794, c = 0.2705, f0 = 0.254 - 0.108, f1 = 0.254 + 0.108;
  assert_near(mu_min, acos((b * b + c * c - f0 * f0) / (2 * b * c)), ANGLE_TOL);
  assert_near(mu_max, acos((b * b + c * c - f1 * f1) / (2 * b * c)), ANGLE_TOL);
  /* and every solved state lies between them */
  for (int k = 0; k < 720; k++) {
    fb_linkage_state s;
    fb_linkage_solve(&s, &paper, FB_BRANCH_OPEN, 2 * M_PI * k / 720.0, 1, 0, NULL);
    assert_true(s.transmission_angle >= mu_min - ANGLE_TOL);
    assert_true(s.transmission_angle <= mu_max + ANGLE_TOL);
  }
}

static void test_paper_peak_ratios(void **state) {
  (void)state;
  /* docs/paper.md: peak |alpha| / omega^2 = 1.091571 (coupler), 1.138543 (follower)
   * for the nominal linkage at constant crank speed: an independent number */
  fb_peaks p;
  const double w = 104.71975511965977;
  assert_int_equal(fb_analytic_peaks(&p, &paper, FB_BRANCH_OPEN, -w, NULL), FB_OK);
  double rc = fmax(fabs(p.coupler.alpha_max), fabs(p.coupler.alpha_min)) / (w * w);
  double rf = fmax(fabs(p.follower.alpha_max), fabs(p.follower.alpha_min)) / (w * w);
  assert_near(rc, 1.091571, PAPER_RATIO_TOL);
  assert_near(rf, 1.138543, PAPER_RATIO_TOL);
  /* direction reverses velocities and leaves accelerations (omega^2) alone */
  fb_peaks q;
  fb_analytic_peaks(&q, &paper, FB_BRANCH_OPEN, +w, NULL);
  assert_near(q.coupler.omega_max, -p.coupler.omega_min, 1e-9 * w);
  assert_near(q.coupler.alpha_max, p.coupler.alpha_max, 1e-9 * w * w);
}

static void test_refined_peaks_beat_dense_grid(void **state) {
  (void)state;
  /* the Brent-refined peak is at least the best of 1e6 samples and exceeds
   * it by no more than that grid's own sampling error (quadratic near a
   * peak: (pi / 1e6)^2 / 2 * |omega''| with |omega''| < 1e4 rad/s here) */
  fb_peaks p;
  const double w = 100.0;
  fb_analytic_peaks(&p, &paper, FB_BRANCH_OPEN, w, NULL);
  double best = -1e300;
  for (int k = 0; k < 1000000; k++) {
    fb_linkage_state s;
    fb_linkage_solve(&s, &paper, FB_BRANCH_OPEN, 2 * M_PI * k / 1e6, w, 0, NULL);
    if (s.coupler_omega > best) best = s.coupler_omega;
  }
  const double grid_err = 0.5 * (M_PI / 1e6) * (M_PI / 1e6) * 1e4;
  assert_true(p.coupler.omega_max >= best - 1e-12);
  assert_true(p.coupler.omega_max - best <= grid_err);
}

static void test_peaks_refuse_non_rotating_crank(void **state) {
  (void)state;
  const fb_linkage tri = {{0.3, 0.1, 0.25, 0.35}};
  fb_peaks p;
  fb_diag d;
  assert_int_equal(fb_analytic_peaks(&p, &tri, FB_BRANCH_OPEN, 1.0, &d), FB_ERR_ASSEMBLY);
  assert_non_null(strstr(d.msg, "cannot turn fully"));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_loop_closure_both_branches),
      cmocka_unit_test(test_branches_are_mirror_sides),
      cmocka_unit_test(test_velocity_acceleration_vs_central_differences),
      cmocka_unit_test(test_grashof_classes),
      cmocka_unit_test(test_grashof_sums_and_folds),
      cmocka_unit_test(test_unassemblable_gives_error_not_nan),
      cmocka_unit_test(test_crank_range_closed_form),
      cmocka_unit_test(test_transmission_angle_extremes),
      cmocka_unit_test(test_paper_peak_ratios),
      cmocka_unit_test(test_refined_peaks_beat_dense_grid),
      cmocka_unit_test(test_peaks_refuse_non_rotating_crank),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
