/* Contact laws, stiffness models and the ERP/CFM mapping: hand-computed
 * values and exact round trips. */
#include <string.h>

#include "contact.h"
#include "fb_test.h"

/* a formula evaluated two ways in double precision: a few ulp */
#define FORMULA_REL_TOL 1e-12
/* the bound on the mapping round trip */
#define ROUNDTRIP_REL_TOL 1e-12

static void test_moduli_and_stiffness(void **state) {
  (void)state;
  const double e = 207e9, nu = 0.29;
  const double es = fb_contact_modulus(e, nu, e, nu);
  assert_rel(es, e / (2.0 * (1.0 - nu * nu)), FORMULA_REL_TOL); /* 113.0036 GPa */
  assert_rel(es, 113003.6e6, 1e-7);                               /* PAPER.md's E* */
  /* sphere on a flat (r2 -> infinity): K = 4/3 E* sqrt(r1) */
  assert_rel(fb_contact_hertz_sphere(es, 0.01, 1e300), 4.0 / 3.0 * es * sqrt(0.01), FORMULA_REL_TOL);
  /* Goldsmith internal contact equals Hertz with the hole's radius negative */
  const double rp = 0.005, rh = 0.0050145;
  assert_rel(fb_contact_goldsmith(e, nu, e, nu, rp, rh), fb_contact_hertz_sphere(es, rp, -rh),
             FORMULA_REL_TOL);
  assert_true(isnan(fb_contact_goldsmith(e, nu, e, nu, rh, rp)));
  /* line contact half-width, by hand: F = 100 N, L = 13 mm, R* = 1 mm */
  assert_rel(fb_contact_line_halfwidth(100, 0.013, es, 1e-3),
             sqrt(4.0 * 100 * 1e-3 / (M_PI * 0.013 * es)), FORMULA_REL_TOL);
}

static void test_johnson_inverse_round_trip(void **state) {
  (void)state;
  const double es = 113.0036e9, l = 0.013, dr = 14.5e-6;
  for (double f = 1.0; f < 1e5; f *= 3.7) {
    double d = fb_contact_johnson_approach(f, l, es, dr), back;
    assert_int_equal(fb_contact_johnson_force(&back, d, l, es, dr, NULL), FB_OK);
    assert_rel(back, f, 1e-10);
    /* the tangent stiffness is the slope: compare with a central difference */
    double df = 1e-6 * f;
    double slope = 2 * df / (fb_contact_johnson_approach(f + df, l, es, dr) -
                             fb_contact_johnson_approach(f - df, l, es, dr));
    assert_rel(fb_contact_johnson_stiffness(f, l, es, dr), slope, 1e-6);
  }
  fb_diag d;
  double f;
  assert_int_equal(fb_contact_johnson_force(&f, 1.0, l, es, dr, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "monotone"));
}

static void test_laws_by_hand(void **state) {
  (void)state;
  fb_contact_law l = fb_contact_law_default();
  l.stiffness = 2e9;
  l.exponent = 1.5;
  l.restitution = 0.8;
  const double d = 1e-5, v = 0.3, v0 = 0.5;
  const double el = 2e9 * pow(1e-5, 1.5); /* 63.2456 N */
  const struct {
    fb_law_kind k;
    double factor; /* F / el */
  } cases[] = {
      {FB_LAW_HERTZ, 1.0},
      {FB_LAW_LANKARANI_NIKRAVESH, 1.0 + 0.75 * (1 - 0.64) * 0.6},
      {FB_LAW_HUNT_CROSSLEY, 1.0 + 1.5 * 0.2 * 0.6},
      {FB_LAW_FLORES, 1.0 + 8.0 * 0.2 / 4.0 * 0.6},
      {FB_LAW_GONTHIER, 1.0 + 0.36 / 0.8 * 0.6},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    l.kind = cases[i].k;
    assert_rel(fb_contact_force(&l, d, v, v0), el * cases[i].factor, FORMULA_REL_TOL);
    assert_near(fb_contact_force(&l, -1e-9, v, v0), 0.0, 0.0); /* no contact */
    if (cases[i].k != FB_LAW_HERTZ) /* damped laws are clamped: no adhesion */
      assert_near(fb_contact_force(&l, d, -100.0, v0), 0.0, 0.0);
  }
  l.kind = FB_LAW_LINEAR;
  l.stiffness = 1e6;
  l.damping = 200;
  assert_rel(fb_contact_force(&l, d, v, v0), 1e6 * d + 200 * v, FORMULA_REL_TOL);
  l.kind = FB_LAW_IMPACT;
  l.stiffness = 2e9;
  l.damping = 1000;
  l.damping_depth = 4e-5; /* z = 0.25: STEP = 1000 * 0.0625 * 2.5 = 156.25 */
  assert_rel(fb_contact_force(&l, d, v, v0), el + 156.25 * v, FORMULA_REL_TOL);
  l.damping_depth = 5e-6; /* beyond d_max: full damping */
  assert_rel(fb_contact_force(&l, d, v, v0), el + 1000 * v, FORMULA_REL_TOL);
  assert_int_equal(fb_law_parse("hunt-crossley"), FB_LAW_HUNT_CROSSLEY);
  assert_int_equal(fb_law_parse("nope"), FB_LAW_COUNT);
}

static void test_restitution_zeta(void **state) {
  (void)state;
  assert_near(fb_contact_restitution_zeta(1.0), 0.0, 0.0);
  double prev = 0.0;
  for (double cr = 0.95; cr > 0.14; cr -= 0.1) {
    double z = fb_contact_restitution_zeta(cr);
    assert_true(z > prev); /* more damping for less restitution */
    prev = z;
  }
  /* without the no-adhesion clamp the classic relation would give
   * cr = exp(-zeta pi / sqrt(1 - zeta^2)); with it the body leaves earlier
   * and faster, so the clamped law needs more damping than the classic one */
  const double cr = 0.5, zc = -log(cr) / sqrt(M_PI * M_PI + log(cr) * log(cr));
  assert_true(fb_contact_restitution_zeta(cr) > zc);
  /* below e^-2 (critical damping of the clamped oscillator) there is none */
  assert_true(isnan(fb_contact_restitution_zeta(0.13)));
  fb_contact_law l = fb_contact_law_default();
  l.kind = FB_LAW_RESTITUTION;
  l.restitution = 0.1;
  fb_diag d;
  assert_int_equal(fb_contact_law_check(&l, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "critical damping"));
}

static void test_erp_cfm_round_trip(void **state) {
  (void)state;
  const double hs[] = {1e-6, 1e-4, 1e-2};
  const double ks[] = {1e3, 1e8, 1e12};
  const double cs[] = {0.0, 1.0, 1e4};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++) {
        double erp, cfm, kp, kd;
        assert_int_equal(fb_contact_erp_cfm(hs[i], ks[j], cs[k], &erp, &cfm, NULL), FB_OK);
        assert_true(erp >= 0.0 && erp <= 1.0);
        assert_int_equal(fb_contact_kp_kd(hs[i], erp, cfm, &kp, &kd, NULL), FB_OK);
        assert_rel(kp, ks[j], ROUNDTRIP_REL_TOL);
        /* kd is recovered to 1e-12 of the whole h kp + kd it shares the CFM with */
        assert_near(kd, cs[k], ROUNDTRIP_REL_TOL * (hs[i] * ks[j] + cs[k]));
      }
  double erp, cfm;
  fb_diag d;
  assert_int_equal(fb_contact_erp_cfm(1e-3, 0.0, 0.0, &erp, &cfm, &d), FB_ERR_RANGE);
}

static void test_linearize_reproduces_the_law(void **state) {
  (void)state;
  fb_contact_law l = fb_contact_law_default();
  for (int kind = 0; kind < FB_LAW_COUNT; kind++) {
    l.kind = (fb_law_kind)kind;
    l.exponent = (kind == FB_LAW_LINEAR || kind == FB_LAW_RESTITUTION) ? 1.0 : 1.5;
    l.damping = 300.0;
    for (int m = 0; m < 2; m++) {
      double kp, kd, depth;
      const double d = 3e-6, v = 0.2, v0 = 0.7;
      fb_contact_linearize(&l, (fb_mapping)m, d, v, v0, &kp, &kd, &depth);
      assert_rel(kp * depth + kd * v, fb_contact_force(&l, d, v, v0), FORMULA_REL_TOL);
      if (m == FB_MAPPING_TANGENT) /* slope of the elastic part */
        assert_rel(kp, l.exponent * l.stiffness * pow(d, l.exponent - 1.0), FORMULA_REL_TOL);
    }
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_moduli_and_stiffness),
      cmocka_unit_test(test_johnson_inverse_round_trip),
      cmocka_unit_test(test_laws_by_hand),
      cmocka_unit_test(test_restitution_zeta),
      cmocka_unit_test(test_erp_cfm_round_trip),
      cmocka_unit_test(test_linearize_reproduces_the_law),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
