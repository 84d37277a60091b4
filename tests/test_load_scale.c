/* The ideal joint load's time scale (load_scale.h): the table's tau against
 * an independent finite difference of the inverse dynamics, its scaling
 * with the crank speed, the lookahead window and the crank at rest.
 *
 *   tau = |F| / |dF/dt|: the time in which the load at a joint changes by
 *   its own size, in magnitude or direction */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "fb_test_planar.h"
#include "invdyn.h"
#include "load_scale.h"

/* the table's central difference spans 2 x 2 pi / 7200 rad, the oracle's
 * 2e-6 rad: their truncation errors differ by ~(1.7e-3 rad)^2 / 6 of the
 * load's third derivative over its slope, measured 1.2e-5 of tau on the
 * paper case; a table read one sample off measured 2.7e-2, so 1e-3 fails
 * it */
#define TAU_REL_TOL 1e-3
/* the planar core's table of a description against the closed form's
 * reactions: the same inverse dynamics (tests/test_planar_invdyn.c: 1.2e-15),
 * measured 3.7e-14 of the load; the core's position followed over 7200
 * angles adds its Newton tolerance */
#define PLANAR_LOAD_REL_TOL 1e-10
/* the assembly's drive angle is the table's angle0, entry k at angle0 +
 * 2 pi k / n: the planar table read as if entry 0 were at crank angle 0,
 * 1 rad off, measured tau 61 times off and the load 23 times: an offset
 * forgotten fails */
#define PLANAR_ASSEMBLY_RAD 1.0

/* without gravity every reaction is an inertial force, omega2^2 times a
 * function of the crank angle, so omega2 tau is independent of omega2:
 * rounding only */
#define SCALING_REL_TOL 1e-9

static fb_case paper;

static double tau_oracle(const fb_case *c, int j, double th, double w) {
  const double e = 1e-6;
  fb_reactions a, b, r;
  assert_int_equal(fb_invdyn_solve(&a, &c->nominal, c->branch, c->link, c->gravity, th - e, w, 0), FB_OK);
  assert_int_equal(fb_invdyn_solve(&b, &c->nominal, c->branch, c->link, c->gravity, th + e, w, 0), FB_OK);
  assert_int_equal(fb_invdyn_solve(&r, &c->nominal, c->branch, c->link, c->gravity, th, w, 0), FB_OK);
  const double rate = hypot(b.force[j][0] - a.force[j][0], b.force[j][1] - a.force[j][1]) /
                      (2.0 * e) * fabs(w);
  return hypot(r.force[j][0], r.force[j][1]) / rate;
}

/* no lookahead: the table holds tau itself at every sampled crank angle, at
 * every joint asked for, and nothing for the others */
static void test_tau_matches_finite_difference(void **state) {
  (void)state;
  const double w = 2.0 * M_PI * 1000.0 / 60.0;
  fb_load_scale ls;
  assert_int_equal(fb_load_scale_build(&ls, &paper.nominal, paper.branch, paper.link,
                                       paper.gravity, w, 0x6, 0.0, NULL),
                   FB_OK);
  double worst = 0.0, shortest = INFINITY, longest = 0.0;
  for (int k = 0; k < ls.n; k += 37) {
    const double th = 2.0 * M_PI * (k + 0.25) / ls.n; /* inside sample k */
    for (int j = 1; j <= 2; j++) {
      double tau, force;
      fb_load_scale_at(&ls, j, th, &tau, &force);
      const double want = tau_oracle(&paper, j, 2.0 * M_PI * k / ls.n, w);
      worst = fmax(worst, fabs(tau / want - 1.0));
      shortest = fmin(shortest, tau);
      longest = fmax(longest, tau);
      assert_true(force > 0.0);
    }
  }
  report_residual("load time scale against a finite difference", worst, TAU_REL_TOL);
  assert_true(worst < TAU_REL_TOL);
  /* the paper's load at B is slow most of the revolution and fast once:
   * the table must not be flat */
  assert_true(longest > 10.0 * shortest);
  double tau, force;
  fb_load_scale_at(&ls, 0, 1.0, &tau, &force); /* A: not asked */
  assert_true(isinf(tau) && force == 0.0);
  fb_load_scale_free(&ls);
}

/* without gravity, omega2 tau is the same at 500 and 2000 rpm */
static void test_tau_scales_with_speed(void **state) {
  (void)state;
  fb_load_scale a, b;
  const double w1 = 2.0 * M_PI * 500.0 / 60.0, w2 = 4.0 * w1;
  assert_int_equal(fb_load_scale_build(&a, &paper.nominal, paper.branch, paper.link, 0.0, w1,
                                       0x2, 0.0, NULL), FB_OK);
  assert_int_equal(fb_load_scale_build(&b, &paper.nominal, paper.branch, paper.link, 0.0, w2,
                                       0x2, 0.0, NULL), FB_OK);
  double worst = 0.0;
  for (int k = 0; k < a.n; k += 11) {
    const double rel = (a.ahead[1][k] * w1) / (b.ahead[1][k] * w2) - 1.0;
    worst = fmax(worst, fabs(rel));
    /* the loads themselves scale with omega2^2 */
    worst = fmax(worst, fabs(b.force[1][k] / (16.0 * a.force[1][k]) - 1.0));
  }
  report_residual("omega2 tau across crank speeds", worst, SCALING_REL_TOL);
  assert_true(worst < SCALING_REL_TOL);
  fb_load_scale_free(&a);
  fb_load_scale_free(&b);
}

/* the lookahead: each entry is the smallest tau (largest load) over the
 * crank angles the crank sweeps next, forward in its own sense of rotation */
static void test_lookahead_follows_the_crank(void **state) {
  (void)state;
  const double look = 2e-4;
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    const double w = sgn * 2.0 * M_PI * 1000.0 / 60.0;
    fb_load_scale now, ahead;
    assert_int_equal(fb_load_scale_build(&now, &paper.nominal, paper.branch, paper.link,
                                         paper.gravity, w, 0x2, 0.0, NULL), FB_OK);
    assert_int_equal(fb_load_scale_build(&ahead, &paper.nominal, paper.branch, paper.link,
                                         paper.gravity, w, 0x2, look, NULL), FB_OK);
    const int n = now.n;
    const int span = (int)ceil(fabs(w) * look / (2.0 * M_PI / n));
    assert_true(span >= 2);
    for (int k = 0; k < n; k++) {
      double t = INFINITY, f = 0.0;
      for (int q = 0; q <= span; q++) {
        const int i = ((k + sgn * q) % n + n) % n;
        t = fmin(t, now.ahead[1][i]);
        f = fmax(f, now.force[1][i]);
      }
      if (ahead.ahead[1][k] != t || ahead.force[1][k] != f)
        fail_msg("omega2 %+g: entry %d: %g s / %g N, want %g s / %g N", w, k,
                 ahead.ahead[1][k], ahead.force[1][k], t, f);
    }
    fb_load_scale_free(&now);
    fb_load_scale_free(&ahead);
  }
}

/* a crank at rest carries gravity alone, which does not change: tau is
 * infinite and the load is the weight's share; an empty mask builds no
 * table */
static void test_crank_at_rest(void **state) {
  (void)state;
  fb_load_scale ls;
  assert_int_equal(fb_load_scale_build(&ls, &paper.nominal, paper.branch, paper.link,
                                       paper.gravity, 0.0, 0x2, 1e-3, NULL), FB_OK);
  fb_reactions r;
  assert_int_equal(fb_invdyn_solve(&r, &paper.nominal, paper.branch, paper.link, paper.gravity,
                                   0.0, 0.0, NULL), FB_OK);
  double tau, force;
  fb_load_scale_at(&ls, FB_JOINT_B, -2.0 * M_PI, &tau, &force); /* angle 0, from below */
  assert_true(isinf(tau));
  assert_rel(force, hypot(r.force[1][0], r.force[1][1]), SCALING_REL_TOL);
  fb_load_scale_free(&ls);
  assert_int_equal(fb_load_scale_build(&ls, &paper.nominal, paper.branch, paper.link,
                                       paper.gravity, 1.0, 0, 1e-3, NULL), FB_OK);
  assert_null(ls.ahead[1]);
  fb_load_scale_free(&ls);
}

/* the table of the paper's four-bar as a planar description assembled at
 * 1 rad, both senses of rotation: each entry's tau against the closed
 * form's finite difference at the entry's crank angle (the table's own
 * angle0 + 2 pi k / n) and its load against the closed form's reaction
 * there; a joint outside the mask has no table; an undriven description is
 * refused */
static void test_planar_table_matches_closed_form(void **state) {
  (void)state;
  fb_case c = paper;
  c.crank_angle0 = PLANAR_ASSEMBLY_RAD;
  fb_test_planar t = fb_test_planar_paper(&c, &c.nominal);
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    const double w = sgn * 2.0 * M_PI * 1000.0 / 60.0;
    fb_load_scale ls;
    fb_diag d;
    if (fb_load_scale_build_planar(&ls, t.m, c.gravity, w, 0x6u, 0.0, &d) != FB_OK)
      fail_msg("%s", d.msg);
    assert_rel(ls.angle0, PLANAR_ASSEMBLY_RAD, 1e-15);
    double worst_tau = 0.0, worst_load = 0.0;
    for (int k = 0; k < ls.n; k += 37) {
      const double th = ls.angle0 + 2.0 * M_PI * k / ls.n;
      for (int j = 1; j <= 2; j++) {
        double tau, force;
        fb_load_scale_at(&ls, j, th + 0.25 * 2.0 * M_PI / ls.n, &tau, &force);
        worst_tau = fmax(worst_tau, fabs(tau / tau_oracle(&c, j, th, w) - 1.0));
        fb_reactions r;
        assert_int_equal(fb_invdyn_solve(&r, &c.nominal, c.branch, c.link, c.gravity, th, w, 0),
                         FB_OK);
        worst_load = fmax(worst_load, fabs(force / hypot(r.force[j][0], r.force[j][1]) - 1.0));
      }
    }
    report_residual("planar table's tau against the closed form's", worst_tau, TAU_REL_TOL);
    report_residual("planar table's load against the closed form's", worst_load,
                    PLANAR_LOAD_REL_TOL);
    assert_true(worst_tau < TAU_REL_TOL);
    assert_true(worst_load < PLANAR_LOAD_REL_TOL);
    assert_null(ls.ahead[0]);
    assert_null(ls.ahead[3]);
    fb_load_scale_free(&ls);
  }
  /* a torque drive has no constant speed to schedule by */
  fb_load_scale ls;
  fb_diag d;
  const int drive = t.m->drive;
  t.m->drive = -1;
  assert_int_equal(fb_load_scale_build_planar(&ls, t.m, c.gravity, 1.0, 0x2u, 0.0, &d), FB_ERR_ARG);
  t.m->drive = drive;
  assert_int_equal(fb_load_scale_build_planar(&ls, t.m, c.gravity, 1.0, 0x20u, 0.0, &d), FB_ERR_ARG);
  fb_test_planar_free(&t);
}

int main(void) {
  fb_test_paper_case(&paper, NULL, 0);
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_tau_matches_finite_difference),
      cmocka_unit_test(test_tau_scales_with_speed),
      cmocka_unit_test(test_lookahead_follows_the_crank),
      cmocka_unit_test(test_crank_at_rest),
      cmocka_unit_test(test_planar_table_matches_closed_form),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
