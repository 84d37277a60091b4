/* The planar core's inverse dynamics (planar_invdyn.h: joint reactions and
 * drive torque from the Lagrange multipliers) against the closed forms:
 * the four-bar's Newton-Euler solve (invdyn.h) and the slider-crank's
 * body-by-body elimination (slider_crank_invdyn.h); and, on the six-bar,
 * against the power balance (the drive's power equals the rate of change
 * of the kinetic and potential energy: an oracle that needs no reaction).
 *
 *            C                     reactions: on body[1] from body[0];
 *           / \                    the four-bar's D (follower-ground)
 *  coupler /   \ follower          is on the ground from the follower
 *         B     \                  here, on the follower from the
 *  crank /       \                 ground in invdyn.h: opposite signs
 *       A ------- D */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "fb_test_planar.h"
#include "invdyn.h"
#include "planar_case.h"
#include "planar_invdyn.h"
#include "slider_crank_invdyn.h"

/* Reactions and torque: both sides solve linear systems (the core a 9 x 9
 * LU of condition ~1e3, invdyn.h a 9 x 9 LU, slider_crank_invdyn.h none)
 * from the same kinematics (equal to 1e-15, test_planar_kinematics.c):
 * 1e-10 of the largest reaction (tens of N) holds with a factor of 1e3
 * over the rounding. */
#define REACTION_REL_TOL 1e-10
/* The power balance on the six-bar: T omega2 = dE/dt with
 * dE/dt = sum m v.a + I w alpha + m g v_y, all from the core's exact
 * kinematics; relative to the largest |T omega2|: rounding only. */
#define POWER_REL_TOL 1e-10

/* the core's motion of m at drive angle phi (q in: a guess) */
static void motion(double *q, double *qd, double *qdd, fb_planar_kin *k, double phi, double w) {
  fb_diag d;
  if (fb_planar_position(k, q, phi, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_planar_drive dr = {phi, w, 0.0};
  assert_int_equal(fb_planar_motion(k, qd, qdd, q, &dr, NULL, &d), FB_OK);
}

static void test_fourbar(void **state) {
  (void)state;
  const fb_case c = fb_test_paper_once();
  fb_test_planar t = fb_test_planar_paper(&c, &c.nominal);
  fb_planar *m = t.m;
  fb_diag d;
  const double w = fb_case_omega2(&c);
  double q[9], qd[9], qdd[9], worst = 0.0, big = 0.0, kin_worst = 0.0;
  fb_planar_assembly(m, q);
  for (int i = 0; i < 36; i++) {
    const double phi = i * 10.0 * M_PI / 180.0;
    motion(q, qd, qdd, t.k, phi, w);
    fb_planar_reaction r[4];
    double torque;
    assert_int_equal(fb_planar_invdyn(r, &torque, m, q, qd, qdd, c.gravity, &d), FB_OK);
    /* the same multipliers through the LU fb_planar_motion has just left */
    fb_planar_reaction rk[4];
    double torque_k;
    assert_int_equal(fb_planar_invdyn_kin(rk, &torque_k, t.k, q, qd, qdd, c.gravity, &d), FB_OK);
    for (int j = 0; j < 4; j++)
      for (int a = 0; a < 2; a++) kin_worst = fmax(kin_worst, fabs(rk[j].force[a] - r[j].force[a]));
    kin_worst = fmax(kin_worst, fabs(torque_k - torque) / 0.1);
    fb_reactions x;
    assert_int_equal(fb_invdyn_solve(&x, &c.nominal, c.branch, c.link, c.gravity,
                                     c.crank_angle0 + phi, w, &d), FB_OK);
    for (int j = 0; j < 4; j++) {
      const double sign = j == FB_JOINT_D ? -1.0 : 1.0;
      for (int a = 0; a < 2; a++) {
        worst = fmax(worst, fabs(r[j].force[a] - sign * x.force[j][a]));
        big = fmax(big, fabs(x.force[j][a]));
      }
      /* a pin carries no moment */
      assert_true(fabs(r[j].moment) <= 1e-12 * big * 0.3);
    }
    worst = fmax(worst, fabs(torque - x.drive_torque) / 0.1); /* a torque over a 0.1 m arm */
  }
  report_residual("four-bar reactions, core vs invdyn.h (rel)", worst / big, REACTION_REL_TOL);
  assert_true(worst / big <= REACTION_REL_TOL);
  /* two LUs of the same matrix (of Phi_q^T, and Phi_q's reused): rounding */
  report_residual("four-bar reactions, reused LU vs own (rel)", kin_worst / big, REACTION_REL_TOL);
  assert_true(kin_worst / big <= REACTION_REL_TOL);
  fb_test_planar_free(&t);
}

static void test_slider_crank(void **state) {
  (void)state;
  fb_case c = fb_test_paper_once();
  const fb_linkage lk = {{0.06, 0.21, 0.015, 0.0}};
  fb_test_planar t = fb_test_planar_slider(&c, &lk, 0.5, 2e-4, 0.2);
  fb_planar *m = t.m;
  fb_diag d;
  const fb_slider_crank sc = fb_slider_crank_of(&lk);
  const fb_slider_crank_mass sm = fb_slider_crank_mass_of(c.link);
  const double w = -120.0;
  double q[9], qd[9], qdd[9], worst = 0.0, big = 0.0, moment = 0.0;
  fb_planar_assembly(m, q);
  for (int i = 0; i < 36; i++) {
    const double phi = i * 10.0 * M_PI / 180.0;
    motion(q, qd, qdd, t.k, phi, w);
    fb_planar_reaction r[4];
    double torque;
    assert_int_equal(fb_planar_invdyn(r, &torque, m, q, qd, qdd, c.gravity, &d), FB_OK);
    fb_slider_crank_reactions x;
    assert_int_equal(fb_slider_crank_invdyn(&x, &sc, &sm, c.gravity, 0.2 + phi, w, 0.0, &d), FB_OK);
    for (int j = 0; j < 3; j++)
      for (int a = 0; a < 2; a++) {
        worst = fmax(worst, fabs(r[j].force[a] - x.force[j][a]));
        big = fmax(big, fabs(x.force[j][a]));
      }
    /* the guide: on the ground from the slider, the normal force's opposite, no friction */
    worst = fmax(worst, fmax(fabs(r[3].force[1] + x.guide_force), fabs(r[3].force[0])));
    worst = fmax(worst, fabs(torque - x.drive_torque) / 0.1);
    moment = fmax(moment, fabs(r[3].moment));
  }
  report_residual("slider-crank reactions, core vs closed form (rel)", worst / big, REACTION_REL_TOL);
  assert_true(worst / big <= REACTION_REL_TOL);
  /* every force on the slider passes through the pin: the guide's couple is zero */
  assert_true(moment <= REACTION_REL_TOL * big * 0.1);
  fb_test_planar_free(&t);
}

/* the six-bar: the drive's power against the energy's rate */
static void test_sixbar_power(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  fb_test_planar t = fb_test_planar_sixbar(&c);
  const fb_planar *m = t.m;
  const int n = fb_planar_nq(m);
  double q[15], qd[15], qdd[15], worst = 0.0, big = 0.0;
  assert_int_equal(n, 15);
  fb_planar_assembly(m, q);
  const double w = fb_case_omega2(&c);
  for (int i = 0; i < 36; i++) {
    const double phi = i * 10.0 * M_PI / 180.0;
    motion(q, qd, qdd, t.k, phi, w);
    fb_planar_reaction r[7];
    double torque;
    assert_int_equal(fb_planar_invdyn(r, &torque, m, q, qd, qdd, c.gravity, &d), FB_OK);
    double de = 0.0;
    for (int b = 1; b < m->nbodies; b++) {
      const double *v = qd + 3 * (b - 1), *a = qdd + 3 * (b - 1);
      de += m->body[b].mass * (v[0] * a[0] + v[1] * a[1] + c.gravity * v[1]) +
            m->body[b].inertia * v[2] * a[2];
    }
    worst = fmax(worst, fabs(torque * w - de));
    big = fmax(big, fabs(torque * w));
  }
  report_residual("six-bar power balance (rel)", worst / big, POWER_REL_TOL);
  assert_true(big > 0.0 && worst / big <= POWER_REL_TOL);
  fb_test_planar_free(&t);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_fourbar),
      cmocka_unit_test(test_slider_crank),
      cmocka_unit_test(test_sixbar_power),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
