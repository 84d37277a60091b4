/* The contact-adaptive step (step_control.h): each rule against a hand
 * computation or a closed form, and the ramp.
 *
 *   pin ( ) approaching the wall |  gap -delta, speed ddot
 *   free flight: h from the undamped Hertz impact's depth at that speed
 *   impact:      h omega_c <= accuracy at that depth (or deeper)
 *   persistent:  penetration change per step and h omega_c bounded (MuJoCo),
 *                or the ideal load's schedule (ODE) */
#include <math.h>

#include "fb_test.h"
#include "step_control.h"

/* formulas evaluated in double on the same inputs: rounding only [-] */
#define STEP_REL_TOL 1e-12

static fb_contact_law hertz(void) {
  fb_contact_law l = fb_contact_law_default(); /* K = 1e10 N/m^1.5, n = 1.5 */
  return l;
}

/* before an impact at 0.2 m/s on 0.1 kg: the undamped Hertz impact's
 * maximum depth is (5 m v^2 / (4 K))^(2/5) (docs: CONTACT, Goldsmith), the
 * tangent stiffness there 1.5 K d^0.5, and h = accuracy / sqrt(k_t / m) */
static void test_free_flight_is_the_impact_step(void **state) {
  (void)state;
  const fb_contact_law law = hertz();
  const double m = 0.1, v = 0.2, acc = 0.3;
  const double d = pow(5.0 * m * v * v / (4.0 * 1e10), 0.4);
  const double want = acc / sqrt(1.5e10 * sqrt(d) / m);
  fb_step_joint j = {.delta = -1e-6, .ddot = v, .m_eff = m, .persistence = 0.0, .dddot = 0.0};
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), want, STEP_REL_TOL);
  /* receding (ddot < 0) at the same speed: the same estimate */
  j.ddot = -v;
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), want, STEP_REL_TOL);
  /* a slow approach uses the speed floor, so the step stays bounded */
  j.ddot = 1e-6;
  const double df = pow(5.0 * m * FB_STEP_V_FLOOR_M_S * FB_STEP_V_FLOOR_M_S / 4e10, 0.4);
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), acc / sqrt(1.5e10 * sqrt(df) / m),
             STEP_REL_TOL);
  /* clamped to [h_min, h_max] */
  assert_true(fb_step_adaptive(&law, &j, acc, 1e-9, 1e-7) == 1e-7);
  assert_true(fb_step_adaptive(&law, &j, acc, 1e-3, 1.0) == 1e-3);
}

/* in an impact deeper than the speed's estimate, the current depth rules */
static void test_impact_uses_the_deeper_depth(void **state) {
  (void)state;
  const fb_contact_law law = hertz();
  const double m = 0.5, d = 2e-5, acc = 0.2; /* the floor speed reaches 6.1e-6 m */
  fb_step_joint j = {.delta = d, .ddot = 1e-4, .m_eff = m, .persistence = 0.5, .dddot = 0.0};
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), acc / sqrt(1.5e10 * sqrt(d) / m),
             STEP_REL_TOL);
}

/* persistent contact: at rest the h omega_c bound; moving, the positive root
 * of (|ddot| + |dddot| h) h = r delta, r = FB_STEP_DEPTH_CHANGE accuracy */
static void test_persistent_contact(void **state) {
  (void)state;
  const fb_contact_law law = hertz();
  const double m = 0.2, d = 5e-7, acc = 0.3;
  const double w = sqrt(1.5e10 * sqrt(d) / m);
  fb_step_joint j = {.delta = d, .ddot = 0.0, .m_eff = m, .persistence = 1.0, .dddot = 0.0};
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), FB_STEP_PERSISTENT_H_OMEGA / w,
             STEP_REL_TOL);
  /* rate only: h = r delta / |ddot| */
  const double r = FB_STEP_DEPTH_CHANGE * acc;
  j.ddot = -2e-3;
  const double h1 = r * d / 2e-3;
  assert_true(h1 < FB_STEP_PERSISTENT_H_OMEGA / w); /* the rate rule binds */
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), h1, STEP_REL_TOL);
  /* with the rate changing at 20 m/s^2: solve 20 h^2 + 2e-3 h = r d by hand */
  j.dddot = 20.0;
  const double h2 = (-2e-3 + sqrt(4e-6 + 4.0 * 20.0 * r * d)) / (2.0 * 20.0);
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), h2, 1e-9); /* the two root forms
                                                                         differ by cancellation */
  assert_true(h2 < h1);
}

/* persistent contact on ODE's schedule: h omega_c <= FB_STEP_PERSISTENT_H_OMEGA
 * with omega_c at the static depth of the load ahead, (F / K)^(1 / n), and
 * h <= FB_STEP_LOAD_SHARE tau_load; the contact's own penetration and rate
 * do not enter (a step that follows them pumps the row's ringing) */
static void test_persistent_load_schedule(void **state) {
  (void)state;
  const fb_contact_law law = hertz();
  const double m = 0.2, f = 800.0, acc = 0.3;
  const double d = pow(f / 1e10, 1.0 / 1.5);
  const double w = sqrt(1.5e10 * sqrt(d) / m);
  fb_step_joint j = {.delta = 5e-7, .ddot = 0.0, .m_eff = m, .persistence = 1.0,
                     .rule = FB_PERSIST_LOAD_SCHEDULE, .tau_load = INFINITY, .load_force = f};
  const double cap = FB_STEP_PERSISTENT_H_OMEGA / w;
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), cap, STEP_REL_TOL);
  /* another depth and a fast rate: the same step */
  j.delta = 2e-6;
  j.ddot = -5e-2;
  j.dddot = 300.0;
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), cap, STEP_REL_TOL);
  /* a load turning fast binds */
  j.tau_load = 0.1 * cap / FB_STEP_LOAD_SHARE;
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), 0.1 * cap, STEP_REL_TOL);
  /* no load known: omega_c at the current depth */
  j.tau_load = INFINITY;
  j.load_force = 0.0;
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0),
             FB_STEP_PERSISTENT_H_OMEGA / sqrt(1.5e10 * sqrt(2e-6) / m), STEP_REL_TOL);
  /* before persistence the impact rule holds, whatever the schedule: here
   * the depth an impact at |ddot| = 5e-2 m/s reaches, deeper than 2e-6 m */
  j.persistence = 0.5;
  j.load_force = f;
  const double di = pow(5.0 * m * 5e-2 * 5e-2 / 4e10, 0.4);
  assert_true(di > j.delta);
  assert_rel(fb_step_adaptive(&law, &j, acc, 1e-9, 1.0), acc / sqrt(1.5e10 * sqrt(di) / m),
             STEP_REL_TOL);
}

/* the rocking bound ([solver] rocking_h_omega): the pin rides the wall as a
 * pendulum of length |e| under the load F on the mass m_t along the wall,
 * omega_t = sqrt(F / (m_t |e|)); in contact h omega_t <= the bound, in
 * impacts and persistent contact alike, and nothing in free flight */
static void test_rocking_bound(void **state) {
  (void)state;
  const fb_contact_law law = hertz();
  const double m = 0.2, f = 500.0, ecc = 15e-6, mt = 0.1, r = 0.1;
  fb_step_joint j = {.delta = 5e-7, .ddot = 0.0, .m_eff = m, .persistence = 1.0,
                     .rule = FB_PERSIST_LOAD_SCHEDULE, .tau_load = INFINITY, .load_force = f,
                     .rocking_h_omega = r, .m_t = mt, .ecc = ecc};
  const double h_t = r / sqrt(f / (mt * ecc)); /* 0.1 / 1.83e4 rad/s = 5.5 us */
  assert_rel(fb_step_adaptive(&law, &j, 0.3, 1e-9, 1.0), h_t, STEP_REL_TOL);
  /* in an impact the shorter of the two binds: the rocking bound at the
   * accuracy 0.3 (h_i 16 us), the impact's own step at 0.01 (0.5 us) */
  j.persistence = 0.5;
  j.ddot = 0.3;
  const double di = pow(5.0 * m * 0.3 * 0.3 / 4e10, 0.4);
  const double w_i = sqrt(1.5e10 * sqrt(di) / m);
  assert_true(0.3 / w_i > h_t && 0.01 / w_i < h_t);
  assert_rel(fb_step_adaptive(&law, &j, 0.3, 1e-9, 1.0), h_t, STEP_REL_TOL);
  assert_rel(fb_step_adaptive(&law, &j, 0.01, 1e-9, 1.0), 0.01 / w_i, STEP_REL_TOL);
  /* free flight: no rocking */
  j.delta = -1e-6;
  j.ddot = 0.0;
  j.persistence = 0.0;
  const double d0 = pow(5.0 * m * FB_STEP_V_FLOOR_M_S * FB_STEP_V_FLOOR_M_S / 4e10, 0.4);
  assert_rel(fb_step_adaptive(&law, &j, 0.3, 1e-9, 1.0), 0.3 / sqrt(1.5e10 * sqrt(d0) / m),
             STEP_REL_TOL);
  /* off (0) or no load known: the schedule alone */
  j.delta = 5e-7;
  j.persistence = 1.0;
  j.rocking_h_omega = 0.0;
  const double d = pow(f / 1e10, 1.0 / 1.5);
  const double cap = FB_STEP_PERSISTENT_H_OMEGA / sqrt(1.5e10 * sqrt(d) / m);
  assert_rel(fb_step_adaptive(&law, &j, 0.3, 1e-9, 1.0), cap, STEP_REL_TOL);
}

static void test_ramp(void **state) {
  (void)state;
  assert_int_equal(fb_step_ramp(20, 1, 20), 2);  /* up by one grid step from 1 */
  assert_int_equal(fb_step_ramp(20, 8, 20), 10); /* up by a quarter */
  assert_int_equal(fb_step_ramp(1, 8, 20), 6);   /* down by a quarter */
  assert_int_equal(fb_step_ramp(5, 3, 4), 4);    /* the cap */
  assert_int_equal(fb_step_ramp(7, 7, 20), 7);   /* steady */
  assert_int_equal(fb_step_ramp(0, 1, 20), 1);   /* never below one grid step */
}

/* inside an impact the step may shrink but not grow */
static void test_hold_in_impact(void **state) {
  (void)state;
  assert_int_equal(fb_step_hold_in_impact(7, 3, 1), 3); /* held */
  assert_int_equal(fb_step_hold_in_impact(2, 3, 1), 2); /* shortened */
  assert_int_equal(fb_step_hold_in_impact(7, 3, 0), 7); /* free flight, persistent contact */
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_free_flight_is_the_impact_step),
      cmocka_unit_test(test_impact_uses_the_deeper_depth),
      cmocka_unit_test(test_persistent_contact),
      cmocka_unit_test(test_persistent_load_schedule),
      cmocka_unit_test(test_rocking_bound),
      cmocka_unit_test(test_ramp),
      cmocka_unit_test(test_hold_in_impact),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
