/* Divergence of a model from its reference (metrics.h, fb_metrics_divergence),
 * and the eccentricity-direction error in continuous contact,
 * on hand-made series whose answer is known by construction:
 *
 *   reference  pin  . . . . .|impact|. . . . . .|impact|. . . . .
 *   model      pin  . . . . .|impact|. . . . . .|impact|. . / drifts away
 *                   t = 0    1 ms                3 ms        5 ms
 *
 * the model's pin follows the reference's until it drifts linearly from
 * t = 4 ms, crossing the tolerance at a sample computed by hand. */
#include <math.h>
#include <string.h>

#include "metrics.h"
#include "fb_test.h"

/* clearance, coupler and step of the made-up series */
#define C_M 10e-6
#define L_COUPLER_M 0.25
#define H_S 1e-6
#define N_SAMPLES 6000
#define PERIOD_S 0.06

/* fills s: pin at (0.2 c, 0) in free flight, impacts at 1 ms and 3 ms lasting
 * 20 samples with peak force f_peak and penetration pen_peak; from t_drift on
 * the eccentricity grows along y by rate [m/s] */
static void make(fb_series *s, double f_peak, double pen_peak, double t_drift, double rate,
                 double t_shift) {
  assert_int_equal(fb_series_init(s, N_SAMPLES), FB_OK);
  assert_int_equal(fb_series_enable_contact(s, 1 << 1), FB_OK);
  for (int i = 0; i < N_SAMPLES; i++) {
    fb_sample x;
    memset(&x, 0, sizeof x);
    x.t = i * H_S;
    x.crank_angle = 2.0 * M_PI * x.t / PERIOD_S;
    const double starts[2] = {1e-3 + t_shift, 3e-3 + t_shift};
    int in = 0;
    for (int k = 0; k < 2; k++) in |= x.t >= starts[k] - 0.5 * H_S && x.t < starts[k] + 20 * H_S - 0.5 * H_S;
    x.contact[1][FB_C_STATE] = in ? FB_STATE_IMPACT : FB_STATE_FREE;
    x.contact[1][FB_C_FORCE] = in ? f_peak : 0.0;
    x.contact[1][FB_C_PEN] = in ? pen_peak : 0.0;
    x.contact[1][FB_C_EX] = 0.2 * C_M;
    x.contact[1][FB_C_EY] = x.t > t_drift ? rate * (x.t - t_drift) : 0.0;
    assert_int_equal(fb_series_push(s, &x), FB_OK);
  }
}

/* the crossing sample is found exactly: no tolerance on a sample time
 * beyond the rounding of i * h (a few ulp) */
#define T_TOL 1e-15
/* peak ratios of decimal constants: a few ulp */
#define REL_TOL 1e-14

static void test_stays_with_the_reference(void **state) {
  (void)state;
  fb_series s, r;
  make(&r, 1000.0, 2e-6, INFINITY, 0.0, 0.0);
  make(&s, 1010.0, 2e-6, INFINITY, 0.0, 0.0);
  fb_divergence d;
  fb_diag diag;
  assert_int_equal(fb_metrics_divergence(&d, &s, &r, 1, C_M, L_COUPLER_M, PERIOD_S, &diag), FB_OK);
  assert_false(d.diverged);
  assert_true(isinf(d.t));
  assert_int_equal(d.impacts_model, 2);
  assert_int_equal(d.impacts_reference, 2);
  assert_int_equal(d.matched, 2);
  assert_true(d.one_to_one);
  assert_rel(d.force_rel_max, 0.01, REL_TOL); /* 1010 against 1000 */
  assert_near(d.impact[1].t, 3e-3, 1e-12);
  assert_near(d.ecc_tol, 0.5 * C_M, 0.0);
  assert_rel(d.angle_tol, 0.5 * C_M / L_COUPLER_M, REL_TOL);
  fb_series_free(&s);
  fb_series_free(&r);
}

/* drift from t = 4 ms at 1 m/s: |de| = 1 m/s x (t - 4 ms) passes 0.5 c = 5 um
 * after 5 us, at the first sample beyond: t = 4.006 ms (at 4.005 ms it is
 * 5 um, not beyond). The impact at 3 ms is before it: both impacts matched. */
static void test_parts_from_the_reference(void **state) {
  (void)state;
  fb_series s, r;
  make(&r, 1000.0, 2e-6, INFINITY, 0.0, 0.0);
  make(&s, 1000.0, 2e-6, 4e-3, 1.0, 0.0);
  fb_divergence d;
  fb_diag diag;
  assert_int_equal(fb_metrics_divergence(&d, &s, &r, 1, C_M, L_COUPLER_M, PERIOD_S, &diag), FB_OK);
  assert_true(d.diverged);
  assert_near(d.t, 4.006e-3, 1e-12);
  assert_near(d.crank_angle, 2.0 * M_PI * 4.006e-3 / PERIOD_S, 1e-9);
  assert_int_equal(d.matched, 2);
  assert_true(d.one_to_one);
  fb_series_free(&s);
  /* an impact 200 us late (beyond 1e-3 of the 60 ms revolution, 60 us):
   * not matched, so nothing is matched one to one */
  make(&s, 1000.0, 2e-6, INFINITY, 0.0, 200e-6);
  assert_int_equal(fb_metrics_divergence(&d, &s, &r, 1, C_M, L_COUPLER_M, PERIOD_S, &diag), FB_OK);
  assert_int_equal(d.matched, 0);
  assert_false(d.one_to_one);
  fb_series_free(&s);
  fb_series_free(&r);
}

/* the eccentricity-direction error in continuous contact
 * (fb_reference_error.ecc_direction_rms): the reference's pin rides the wall
 * at angle phi_r (near pi, so the model's angle crosses the +-pi cut), the
 * model's at phi_r + (-1)^i EPS on the samples where both are in continuous
 * contact, so the RMS is EPS exactly; where only the model is in continuous
 * contact (its first CONT_0 samples, the reference still in impact) the
 * model's pin is 1 rad away, and those samples must not count. */
#define EPS_RAD 0.01
#define CONT_0 1000
#define CONT_1 5000
static void make_wall(fb_series *s, int model) {
  assert_int_equal(fb_series_init(s, N_SAMPLES), FB_OK);
  assert_int_equal(fb_series_enable_contact(s, 1 << 1), FB_OK);
  for (int i = 0; i < N_SAMPLES; i++) {
    fb_sample x;
    memset(&x, 0, sizeof x);
    x.t = i * H_S;
    x.crank_angle = 2.0 * M_PI * x.t / PERIOD_S;
    const int both = i >= CONT_0 && i < CONT_1;
    double phi = M_PI - 0.004 + 0.002 * sin(2.0 * M_PI * i / 700.0);
    if (model) phi += both ? (i % 2 ? EPS_RAD : -EPS_RAD) : 1.0;
    x.contact[1][FB_C_STATE] = both || (model && i < CONT_1) ? FB_STATE_CONTINUOUS
                               : i < CONT_1                  ? FB_STATE_IMPACT
                                                             : FB_STATE_FREE;
    x.contact[1][FB_C_FORCE] = i < CONT_1 ? 500.0 : 0.0;
    x.contact[1][FB_C_PEN] = i < CONT_1 ? 1e-6 : 0.0;
    x.contact[1][FB_C_EX] = (C_M + 1e-6) * cos(phi);
    x.contact[1][FB_C_EY] = (C_M + 1e-6) * sin(phi);
    assert_int_equal(fb_series_push(s, &x), FB_OK);
  }
}

/* sums of squares of EPS over 4,000 samples: a few ulp of the sum */
#define RMS_REL_TOL 1e-9

static void test_ecc_direction_rms(void **state) {
  (void)state;
  fb_series s, r;
  make_wall(&r, 0);
  make_wall(&s, 1);
  fb_reference_error e;
  fb_diag diag;
  assert_int_equal(fb_metrics_vs_reference(&e, &s, &r, 0.0, 1, &diag), FB_OK);
  assert_int_equal((int)e.persistent_samples, CONT_1 - CONT_0);
  assert_rel(e.ecc_direction_rms, EPS_RAD, RMS_REL_TOL);
  /* a window after the continuous contact holds no such sample: NaN */
  assert_int_equal(fb_metrics_vs_reference(&e, &s, &r, (CONT_1 + 10) * H_S, 1, &diag), FB_OK);
  assert_true(isnan(e.ecc_direction_rms));
  fb_series_free(&s);
  fb_series_free(&r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_stays_with_the_reference),
      cmocka_unit_test(test_parts_from_the_reference),
      cmocka_unit_test(test_ecc_direction_rms),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
