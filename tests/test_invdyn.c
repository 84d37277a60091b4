/* Inverse dynamics of the ideal four-bar: statics as a closed-form oracle,
 * ODE's joint feedback as an independent cross-check.
 *
 *            C
 *           / \        F_A: ground on crank      F_B: crank on coupler
 *  coupler /   \       F_C: coupler on follower  F_D: ground on follower
 *         B     \ follower       T: drive torque on the crank
 *  crank /       \
 *       A ------- D */
#include <string.h>

#include "casefile.h"
#include "engine.h"
#include "fb_test.h"
#include "invdyn.h"

/* a 9x9 LU solve of well-scaled equations: roundoff ~1e-13 of the forces */
#define STATICS_TOL_N 1e-9
/* ODE's reactions belong to a semi-implicit Euler step: their error is
 * second order in h. Measured against these inverse-dynamics reactions:
 * 3.4e-3 (h = 1e-4), 3.5e-5 (h = 1e-5), 3.9e-7 (h = 1e-6) of the largest
 * reaction; at h = 1e-5 a bound of 1e-4 leaves a factor 3. */
#define FEEDBACK_REL_TOL 1e-4

static fb_case paper;

static void test_statics_balance_gravity(void **state) {
  (void)state;
  /* a crank turning infinitely slowly: the ground carries the weight, and
   * the drive torque balances the crank's own weight moment plus what the
   * coupler passes on; check the total vertical balance and moments */
  const double w = 1e-9;
  double weight = 0;
  for (int i = 0; i < 3; i++) weight += paper.link[i].mass * paper.gravity;
  for (int k = 0; k < 36; k++) {
    fb_reactions r;
    double th = 2 * M_PI * k / 36.0;
    assert_int_equal(fb_invdyn_solve(&r, &paper.nominal, paper.branch, paper.link, paper.gravity,
                                     th, w, 0), FB_OK);
    assert_near(r.force[0][1] + r.force[3][1], weight, STATICS_TOL_N);
    assert_near(r.force[0][0] + r.force[3][0], 0.0, STATICS_TOL_N);
    /* moment about A of all external loads on the mechanism is zero:
     * T + D x F_D + sum r_G x (m g) = 0, centres of mass at link middles */
    fb_linkage_state s;
    fb_linkage_solve(&s, &paper.nominal, paper.branch, th, w, 0, NULL);
    const double g = paper.gravity, dx = paper.nominal.length[FB_GROUND];
    const double gx[3] = {0.5 * s.b[0], 0.5 * (s.b[0] + s.c[0]), 0.5 * (dx + s.c[0])};
    double m = r.drive_torque + dx * r.force[3][1];
    for (int i = 0; i < 3; i++) m += gx[i] * (-paper.link[i].mass * g);
    assert_near(m, 0.0, STATICS_TOL_N);
  }
}

/* crank angle 0 at t = 0, speed w, step h */
static void set_start(fb_scene *def, void *user) {
  const double *hw = user;
  def->solver.h = hw[0];
  assert_int_equal(fb_scene_set_start(def, 0.0, hw[1], NULL), FB_OK);
}

static void test_reactions_match_ode_feedback(void **state) {
  (void)state;
  const double h = 1e-5, w = fb_case_omega2(&paper);
  fb_scene def;
  fb_model_scene sm;
  const fb_engine *e;
  double start[2] = {h, w};
  void *s = fb_test_engine(&e, &sm, &def, &paper, "ode-ideal-nominal", set_start, start);
  const double period = 2 * M_PI / fabs(w);
  const size_t n = (size_t)llround(2 * period / h);
  double err = 0, fbig = 0, terr = 0, tmax = 0;
  for (size_t k = 1; k <= n; k++) {
    e->step(s, NULL);
    const double t0 = (double)(k - 1) * h; /* the step's forces belong to its start */
    if (t0 < period) continue;              /* after a run-in revolution */
    double f[4][2], torque;
    e->reactions(s, f, &torque);
    fb_reactions r;
    fb_invdyn_solve(&r, &paper.nominal, paper.branch, paper.link, paper.gravity, w * t0, w, NULL);
    for (int j = 0; j < 4; j++) {
      err = fmax(err, hypot(f[j][0] - r.force[j][0], f[j][1] - r.force[j][1]));
      fbig = fmax(fbig, hypot(r.force[j][0], r.force[j][1]));
    }
    terr = fmax(terr, fabs(torque - r.drive_torque));
    tmax = fmax(tmax, fabs(r.drive_torque));
  }
  e->destroy(s);
  report_residual("joint reactions, ODE vs inverse dynamics", err / fbig, FEEDBACK_REL_TOL);
  report_residual("drive torque, ODE vs inverse dynamics", terr / tmax, FEEDBACK_REL_TOL);
  assert_true(err / fbig < FEEDBACK_REL_TOL);
  assert_true(terr / tmax < FEEDBACK_REL_TOL);
}

int main(void) {
  fb_test_paper_case(&paper, NULL, 0);
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_statics_balance_gravity),
      cmocka_unit_test(test_reactions_match_ode_feedback),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
