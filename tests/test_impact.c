/* Single-impact fidelity: the reference integration against closed forms,
 * the damping laws' achieved restitution against docs/contact.md's table, and ODE
 * with ERP/CFM mapped every step against both, its world built by ODE's kit
 * binding (kit_impact.h) as fourbar impact builds it.
 *
 *      v0 |
 *         v
 *        ( m )      one body, no gravity, meets the ground plane z = 0
 *   ==============  penetration delta = -z, force F(delta, ddot) >= 0 */
#include <string.h>

#include "fb_test.h"
#include "impact.h"
#include "kit_impact.h"
#include "ode_kit.h"

/* rk8pd at relative tolerance 1e-12, peaks by parabola through samples at
 * T/4000: interpolation error (T/4000)^3-ish, far below 1e-7 */
#define REF_VS_CLOSED_REL_TOL 1e-7
/* docs/contact.md prints achieved restitution to 3 decimals from "a quick
 * simulation": half a unit in the last digit, doubled for that simulation */
#define TABLE_TOL 1e-3
/* the acceptance bounds */
#define ODE_PENETRATION_REL_TOL 0.01
#define ODE_DURATION_REL_TOL 0.02
#define ODE_RESTITUTION_REL_TOL 0.02
/* ODE step for the fidelity tests: T / 400 (the issue allows up to T / 200).
 * Measured: ODE's mapped spring loses restitution at about 1.1 h omega_c
 * (omega_c = pi / T), so 1.8 % at T / 200 is too close to the 2 % bound;
 * at T / 400 it is 0.9 %. The 0.97 keeps h off an exact divisor of T: ODE's
 * contact duration is counted in whole steps. */
#define STEPS_PER_CONTACT (400.0 / 0.97)

static fb_impact_def base(fb_law_kind kind, double cr) {
  fb_impact_def d;
  memset(&d, 0, sizeof d);
  d.law = fb_contact_law_default();
  d.law.kind = kind;
  d.law.restitution = cr;
  d.mass = 1.0;
  d.speed = 1.0;
  d.stepper = FB_STEPPER_WORLD;
  d.quick_iterations = 20;
  d.mapping = FB_MAPPING_SECANT;
  d.h = fb_impact_duration_estimate(&d) / STEPS_PER_CONTACT;
  return d;
}

static void test_reference_matches_closed_forms(void **state) {
  (void)state;
  /* undamped Hertz: delta_max = (5 m v0^2 / 4 K)^(2/5), T = 2.943 delta_max / v0 */
  fb_impact_def d = base(FB_LAW_HERTZ, 1.0);
  fb_impact_result r, c;
  assert_int_equal(fb_impact_reference(&r, &d, NULL), FB_OK);
  assert_true(fb_impact_closed_form(&c, &d));
  assert_rel(c.penetration_max, pow(5.0 / (4.0 * 1e10), 0.4), 1e-14);
  assert_rel(c.contact_duration, 2.9432 * c.penetration_max, 1e-4); /* printed 2.943 */
  assert_rel(r.penetration_max, c.penetration_max, REF_VS_CLOSED_REL_TOL);
  assert_rel(r.contact_duration, c.contact_duration, REF_VS_CLOSED_REL_TOL);
  assert_rel(r.force_max, c.force_max, REF_VS_CLOSED_REL_TOL);
  assert_near(r.restitution, 1.0, REF_VS_CLOSED_REL_TOL);
  /* damped linear oscillator and the restitution law (which must hit cr) */
  const fb_law_kind kinds[2] = {FB_LAW_LINEAR, FB_LAW_RESTITUTION};
  for (int i = 0; i < 2; i++) {
    d = base(kinds[i], 0.6);
    d.law.exponent = 1.0;
    d.law.stiffness = 1e7;
    d.law.damping = 800.0;
    assert_int_equal(fb_impact_reference(&r, &d, NULL), FB_OK);
    assert_true(fb_impact_closed_form(&c, &d));
    report_residual("linear restitution ref vs closed", fabs(r.restitution - c.restitution), REF_VS_CLOSED_REL_TOL);
    assert_rel(r.penetration_max, c.penetration_max, REF_VS_CLOSED_REL_TOL);
    assert_rel(r.contact_duration, c.contact_duration, REF_VS_CLOSED_REL_TOL);
    assert_rel(r.force_max, c.force_max, REF_VS_CLOSED_REL_TOL);
    assert_rel(r.restitution, c.restitution, REF_VS_CLOSED_REL_TOL);
    if (kinds[i] == FB_LAW_RESTITUTION) assert_near(c.restitution, 0.6, 1e-12);
  }
}

static void test_damping_laws_restitution_table(void **state) {
  (void)state;
  /* docs/contact.md: achieved restitution of each law for a target, n = 1.5 */
  const double target[4] = {0.9, 0.7, 0.5, 0.3};
  const fb_law_kind laws[4] = {FB_LAW_LANKARANI_NIKRAVESH, FB_LAW_HUNT_CROSSLEY, FB_LAW_FLORES,
                               FB_LAW_GONTHIER};
  const double table[4][4] = {{0.913, 0.909, 0.894, 0.876},
                              {0.796, 0.768, 0.683, 0.670},
                              {0.725, 0.663, 0.470, 0.488},
                              {0.684, 0.581, 0.256, 0.304}};
  double worst = 0;
  for (int t = 0; t < 4; t++)
    for (int l = 0; l < 4; l++) {
      fb_impact_def d = base(laws[l], target[t]);
      fb_impact_result r;
      assert_int_equal(fb_impact_reference(&r, &d, NULL), FB_OK);
      worst = fmax(worst, fabs(r.restitution - table[t][l]));
      assert_near(r.restitution, table[t][l], TABLE_TOL);
    }
  report_residual("restitution vs docs/contact.md table", worst, TABLE_TOL);
}

/* the single impact and the static load in ODE, as fourbar impact runs them */
static fb_status ode_impact(fb_impact_result *out, const fb_impact_def *d) {
  return fb_kit_impact(out, &fb_ode_kit, d, NULL, NULL);
}

static fb_status ode_static(double *penetration, const fb_impact_def *d, double load,
                            double duration) {
  return fb_kit_impact_static(penetration, &fb_ode_kit, d, load, duration, NULL, NULL);
}

/* a binding that applies no soft row (no add_contact) or no load is refused
 * by name, not run */
static void test_binding_without_a_row_is_refused(void **state) {
  (void)state;
  fb_impact_def d = base(FB_LAW_HERTZ, 1.0);
  fb_impact_result o;
  const fb_kit_binding none = {.engine = "nothing"};
  fb_diag dg = {0};
  assert_int_equal(fb_kit_impact(&o, &none, &d, NULL, &dg), FB_ERR_ARG);
  assert_non_null(strstr(dg.msg, "nothing"));
  fb_kit_binding no_load = fb_ode_kit;
  no_load.apply_wrench = NULL;
  double pen;
  assert_int_equal(fb_kit_impact_static(&pen, &no_load, &d, 1.0, 1e-3, NULL, &dg), FB_ERR_ARG);
  assert_non_null(strstr(dg.msg, "no load"));
  assert_true(isnan(pen));
}

static double rel(double x, double ref) { return fabs(x - ref) / fabs(ref); }

static void test_ode_undamped_hertz_vs_closed_form(void **state) {
  (void)state;
  fb_impact_def d = base(FB_LAW_HERTZ, 1.0);
  fb_impact_result o, c;
  assert_int_equal(ode_impact(&o, &d), FB_OK);
  assert_true(fb_impact_closed_form(&c, &d));
  report_residual("ODE hertz penetration", rel(o.penetration_max, c.penetration_max), ODE_PENETRATION_REL_TOL);
  report_residual("ODE hertz duration", rel(o.contact_duration, c.contact_duration), ODE_DURATION_REL_TOL);
  assert_true(rel(o.penetration_max, c.penetration_max) < ODE_PENETRATION_REL_TOL);
  assert_true(rel(o.contact_duration, c.contact_duration) < ODE_DURATION_REL_TOL);
  /* the tangent mapping meets the same bounds */
  d.mapping = FB_MAPPING_TANGENT;
  assert_int_equal(ode_impact(&o, &d), FB_OK);
  assert_true(rel(o.penetration_max, c.penetration_max) < ODE_PENETRATION_REL_TOL);
  assert_true(rel(o.contact_duration, c.contact_duration) < ODE_DURATION_REL_TOL);
}

static void test_ode_restitution_of_each_law(void **state) {
  (void)state;
  for (int k = 0; k < FB_LAW_COUNT; k++) {
    fb_impact_def d = base((fb_law_kind)k, 0.7);
    if (k == FB_LAW_LINEAR || k == FB_LAW_RESTITUTION) {
      d.law.exponent = 1.0;
      d.law.stiffness = 1e7;
      d.law.damping = 500.0;
    }
    if (k == FB_LAW_IMPACT) d.law.damping = 2e4;
    d.h = fb_impact_duration_estimate(&d) / STEPS_PER_CONTACT;
    fb_impact_result o, r;
    assert_int_equal(fb_impact_reference(&r, &d, NULL), FB_OK);
    assert_int_equal(ode_impact(&o, &d), FB_OK);
    char name[96];
    snprintf(name, sizeof name, "ODE restitution, %s", fb_law_name((fb_law_kind)k));
    report_residual(name, rel(o.restitution, r.restitution), ODE_RESTITUTION_REL_TOL);
    assert_true(rel(o.restitution, r.restitution) < ODE_RESTITUTION_REL_TOL);
  }
}

static void test_ode_error_grows_with_h_omega(void **state) {
  (void)state;
  /* the mapped spring's numerical dissipation is first order in h omega:
   * ten times the step gives about ten times the restitution loss */
  fb_impact_def d = base(FB_LAW_HERTZ, 1.0);
  fb_impact_result a, b;
  const double t = fb_impact_duration_estimate(&d);
  d.h = t / 1000.0;
  assert_int_equal(ode_impact(&a, &d), FB_OK);
  d.h = t / 100.0;
  assert_int_equal(ode_impact(&b, &d), FB_OK);
  double ratio = (1.0 - b.restitution) / (1.0 - a.restitution);
  report_residual("restitution loss ratio, 10x step", ratio, 10.0);
  assert_true(ratio > 8.0 && ratio < 12.0);
}

/* The acceptance bounds for the matched mapping at h omega_c = 0.1
 * (omega_c = pi / reference contact duration, as fourbar impact reports it).
 * Measured: hertz +0.01 % / +0.05 %, restitution -0.04 % / -0.04 % (onset step corrected),
 * lankarani-nikravesh +0.00 % / +0.07 % (restitution / penetration). */
#define MATCHED_REL_TOL 0.01
#define MATCHED_LN_REL_TOL 0.02
#define MATCHED_H_OMEGA 0.1

static void test_ode_matched_mapping_at_h_omega_0_1(void **state) {
  (void)state;
  const fb_law_kind kinds[3] = {FB_LAW_HERTZ, FB_LAW_RESTITUTION, FB_LAW_LANKARANI_NIKRAVESH};
  for (int i = 0; i < 3; i++) {
    fb_impact_def d = base(kinds[i], 0.9);
    if (kinds[i] == FB_LAW_RESTITUTION) d.law.exponent = 1.0;
    fb_impact_result r, o, today;
    assert_int_equal(fb_impact_reference(&r, &d, NULL), FB_OK);
    d.h = MATCHED_H_OMEGA * r.contact_duration / M_PI;
    d.mapping = FB_MAPPING_MATCHED;
    assert_int_equal(ode_impact(&o, &d), FB_OK);
    d.mapping = FB_MAPPING_SECANT;
    assert_int_equal(ode_impact(&today, &d), FB_OK);
    const double tol = kinds[i] == FB_LAW_LANKARANI_NIKRAVESH ? MATCHED_LN_REL_TOL : MATCHED_REL_TOL;
    char name[96];
    snprintf(name, sizeof name, "matched restitution, %s", fb_law_name(kinds[i]));
    report_residual(name, rel(o.restitution, r.restitution), tol);
    snprintf(name, sizeof name, "matched penetration, %s", fb_law_name(kinds[i]));
    report_residual(name, rel(o.penetration_max, r.penetration_max), tol);
    assert_true(fabs(rel(o.restitution, r.restitution)) < tol);
    assert_true(fabs(rel(o.penetration_max, r.penetration_max)) < tol);
    /* the standard map loses ~1.1 h omega_c of restitution: ten times more */
    assert_true(fabs(rel(today.restitution, r.restitution)) >
                5.0 * fabs(rel(o.restitution, r.restitution)));
  }
}

/* issue 28 item 1: the matched-static row under a sustained load.
 *
 *         | F (constant from t = 0)
 *        ( m )      rests touching z = 0 at t = 0, linear law k, c = 2 zeta sqrt(k m)
 *   ==============  static depth F / k (the law's), F / a for a matched row
 *
 * The bound on the static penetration: 0.5 % of F / k for zeta up to
 * 2 and h omega up to 1 (measured residual after 80 / omega: below 1e-9,
 * the motion's decay). The matched row's static depth is F / a with its
 * a = m (1 + beta - tr) / (beta h^2), written out here from the poles
 * (beta = exp(-c h / m), tr = 2 exp(-zeta omega h) cos or cosh of the pole
 * spread times h): that closed form holds the harness itself, and shows the
 * matched row 10 % too shallow at zeta 1, h omega 0.1. Both to 1e-6 (the
 * residual motion after 80 / omega, ~1e-9, with margin). */
#define STATIC_PENETRATION_REL_TOL 0.005
#define STATIC_MATCHED_CLOSED_REL_TOL 1e-6
#define STATIC_SETTLE_PERIODS 80.0 /* duration x omega: the slowest mode (zeta 0.25:
                                      exp(-0.25 x 80) = 2e-9) has died out */

static double matched_a(double k, double c, double m, double h) {
  const double w = sqrt(k / m), z = c / (2.0 * sqrt(k * m)), beta = exp(-c * h / m);
  const double tr = z < 1.0 ? 2.0 * exp(-z * w * h) * cos(w * sqrt(1.0 - z * z) * h)
                            : 2.0 * exp(-z * w * h) * cosh(w * sqrt(z * z - 1.0) * h);
  return m * (1.0 + beta - tr) / (beta * h * h);
}

static void test_matched_static_rests_at_the_law_depth(void **state) {
  (void)state;
  const double zetas[4] = {0.25, 0.5, 1.0, 2.0}, hws[3] = {0.1, 0.5, 1.0};
  const double k = 1e9, m = 0.1, load = 100.0, w = sqrt(k / m);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 3; j++) {
      fb_impact_def d = base(FB_LAW_LINEAR, 1.0);
      d.law.stiffness = k;
      d.law.exponent = 1.0;
      d.law.damping = 2.0 * zetas[i] * sqrt(k * m);
      d.mass = m;
      d.h = hws[j] / w;
      double pen, pen_matched;
      d.mapping = FB_MAPPING_MATCHED_STATIC;
      assert_int_equal(ode_static(&pen, &d, load, STATIC_SETTLE_PERIODS / w), FB_OK);
      d.mapping = FB_MAPPING_MATCHED;
      assert_int_equal(ode_static(&pen_matched, &d, load, STATIC_SETTLE_PERIODS / w),
                       FB_OK);
      char name[96];
      snprintf(name, sizeof name, "matched-static depth / (F/k), zeta %.2g, h omega %.2g",
               zetas[i], hws[j]);
      report_residual(name, rel(pen, load / k), STATIC_PENETRATION_REL_TOL);
      assert_true(fabs(rel(pen, load / k)) < STATIC_PENETRATION_REL_TOL);
      const double a = matched_a(k, d.law.damping, m, d.h);
      snprintf(name, sizeof name, "matched depth / (F/a), zeta %.2g, h omega %.2g", zetas[i],
               hws[j]);
      report_residual(name, rel(pen_matched, load / a), STATIC_MATCHED_CLOSED_REL_TOL);
      assert_true(fabs(rel(pen_matched, load / a)) < STATIC_MATCHED_CLOSED_REL_TOL);
      /* and the matched row misses F / k by more than the bound (by 2.4 % at
       * zeta 0.25, h omega 0.1, the mildest of these; 0.904 F/k at zeta 1) */
      assert_true(fabs(rel(pen_matched, load / k)) > STATIC_PENETRATION_REL_TOL);
    }
}

/* A single impact never reaches the persistent row (FB_PERSISTENT_PHASE_RAD):
 * at h omega_c = 0.1 matched-static gives the matched row's figures exactly
 * and keeps the 1 % on restitution against the reference, for the
 * laws of both clearance models (restitution law from cr 0.9 down to 0.14,
 * the heavily damped case) and undamped Hertz. */
#define MATCHED_STATIC_RESTITUTION_REL_TOL 0.01

static void test_matched_static_single_impact(void **state) {
  (void)state;
  const fb_law_kind kinds[4] = {FB_LAW_HERTZ, FB_LAW_RESTITUTION, FB_LAW_RESTITUTION,
                                FB_LAW_IMPACT};
  const double crs[4] = {1.0, 0.9, 0.14, 1.0};
  for (int i = 0; i < 4; i++) {
    fb_impact_def d = base(kinds[i], crs[i]);
    if (kinds[i] == FB_LAW_RESTITUTION) d.law.exponent = 1.0;
    if (kinds[i] == FB_LAW_IMPACT) {
      d.law.damping = 1e3;      /* c_max [N s/m]: zeta ~0.1 at full depth for K = 1e10, m = 1 */
      d.law.damping_depth = 1e-4;
    }
    fb_impact_result r, o, mt;
    assert_int_equal(fb_impact_reference(&r, &d, NULL), FB_OK);
    d.h = MATCHED_H_OMEGA * r.contact_duration / M_PI;
    d.mapping = FB_MAPPING_MATCHED_STATIC;
    assert_int_equal(ode_impact(&o, &d), FB_OK);
    d.mapping = FB_MAPPING_MATCHED;
    assert_int_equal(ode_impact(&mt, &d), FB_OK);
    char name[96];
    snprintf(name, sizeof name, "matched-static restitution, %s cr %g", fb_law_name(kinds[i]),
             crs[i]);
    report_residual(name, rel(o.restitution, r.restitution), MATCHED_STATIC_RESTITUTION_REL_TOL);
    assert_true(fabs(rel(o.restitution, r.restitution)) < MATCHED_STATIC_RESTITUTION_REL_TOL);
    assert_true(o.restitution == mt.restitution);
    assert_true(o.penetration_max == mt.penetration_max);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_reference_matches_closed_forms),
      cmocka_unit_test(test_binding_without_a_row_is_refused),
      cmocka_unit_test(test_damping_laws_restitution_table),
      cmocka_unit_test(test_ode_undamped_hertz_vs_closed_form),
      cmocka_unit_test(test_ode_restitution_of_each_law),
      cmocka_unit_test(test_ode_error_grows_with_h_omega),
      cmocka_unit_test(test_ode_matched_mapping_at_h_omega_0_1),
      cmocka_unit_test(test_matched_static_rests_at_the_law_depth),
      cmocka_unit_test(test_matched_static_single_impact),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
