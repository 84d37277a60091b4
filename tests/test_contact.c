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
  assert_rel(es, 113003.6e6, 1e-7);                               /* docs/paper.md's E* */
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

/* The discrete pole sum and product of a matched row are evaluated from ERP
 * and CFM through 1 + det - h^2 a det / m: O(1) numbers formed from terms
 * of size 1, so agreement to ~100 ulp is what double precision allows. */
#define POLE_ABS_TOL 1e-13
/* pole sum and product of the row's update, back to (k, c): acos/acosh of a
 * number within (omega h)^2 of 1 loses eps / (omega h)^2, ~1e-12 at the
 * grid's smallest omega h = 0.01 */
#define MATCHED_ROUNDTRIP_REL_TOL 1e-9

/* pole sum and product of ODE's contact row on one mass m (contact.h):
 * m (u' - u) = -h (a d + b u'), d' = d + h u' */
static void row_update(double h, double m, double erp, double cfm, double *tr, double *det) {
  const double b = 1.0 / cfm, a = erp * b / h;
  *det = m / (m + h * b);
  *tr = 1.0 + *det - h * h * a * *det / m;
}

static void test_matched_poles_are_exact(void **state) {
  (void)state;
  const double m = 0.3, k = 2e8, wn = sqrt(k / m);
  /* under-, critically and over-damped, undamped; h omega from 0.01 to 3 */
  const double zetas[] = {0.0, 0.03, 0.5, 1.0, 2.5};
  const double hws[] = {0.01, 0.1, 0.5, 1.0, 1.5, 3.0};
  for (int i = 0; i < 5; i++)
    for (int j = 0; j < 6; j++) {
      const double z = zetas[i], h = hws[j] / wn, c = 2.0 * z * sqrt(k * m);
      double erp, cfm, tr, det;
      assert_int_equal(fb_contact_matched(h, k, c, m, &erp, &cfm, NULL), FB_OK);
      row_update(h, m, erp, cfm, &tr, &det);
      /* continuous poles s = -zeta wn +- wn sqrt(zeta^2 - 1) */
      double tr_c, det_c = exp(-2.0 * z * wn * h);
      if (z < 1.0)
        tr_c = 2.0 * exp(-z * wn * h) * cos(wn * sqrt(1.0 - z * z) * h);
      else if (z == 1.0)
        tr_c = 2.0 * exp(-wn * h);
      else
        tr_c = 2.0 * exp(-z * wn * h) * cosh(wn * sqrt(z * z - 1.0) * h);
      /* undamped: b's floor scales det by 1 - eps, eps = its size, and so shifts
       * the sum 1 + det (1 - h^2 a / m) by at most 5 eps (h^2 a / m <= 4) */
      const double tol = z > 0.0 ? POLE_ABS_TOL : POLE_ABS_TOL + 5.0 * FB_MATCHED_B_MIN_REL;
      report_residual("matched pole sum", fabs(tr - tr_c), tol);
      assert_near(tr, tr_c, tol);
      if (z > 0.0) assert_near(det, det_c, POLE_ABS_TOL);
      else assert_near(det, 1.0, FB_MATCHED_B_MIN_REL * 2.0); /* the floor of b */
      /* the undamped row is the explicit spring a = (4 m / h^2) sin^2(wn h / 2) */
      if (z == 0.0) {
        const double a = erp / (h * cfm), s = sin(0.5 * wn * h);
        assert_rel(a, 4.0 * m / (h * h) * s * s, 1e-10);
      }
    }
  /* k = c = 0 (zero depth of the impact law): no row */
  double erp, cfm;
  fb_diag d;
  assert_int_equal(fb_contact_matched(1e-5, 0.0, 0.0, m, &erp, &cfm, &d), FB_ERR_RANGE);
  /* a pure damper (k = 0): pole 1 and beta, so a = 0 */
  assert_int_equal(fb_contact_matched(1e-5, 0.0, 100.0, m, &erp, &cfm, NULL), FB_OK);
  assert_near(erp, 0.0, 1e-15);
  /* a huge c h / m: a rigid, fully inelastic row, finite ERP, CFM -> 0 */
  assert_int_equal(fb_contact_matched(1.0, 1e9, 1e9, m, &erp, &cfm, NULL), FB_OK);
  assert_true(isfinite(erp) && erp > 0.0 && cfm >= 0.0 && cfm < 1e-300);
}

/* issue 28 item 1: the matched-static row (fb_contact_row_static). Its a is
 * the law's k, so a sustained load rests at F / k; its b makes the slowest
 * pole of the row's update as slow as the law's: modulus
 * exp(-zeta wn h) (zeta <= 1) or exp(-wn (zeta - sqrt(zeta^2 - 1)) h),
 * written out here, or 1 / (1 + h wn), the fastest decay a row with a = k
 * has (its double root), when the law decays faster than that. Rounding
 * only: 1e-12 absolute on a modulus <= 1. */
#define STATIC_POLE_ABS_TOL 1e-12

static void test_matched_static_row(void **state) {
  (void)state;
  const double m = 0.3, k = 2e8, wn = sqrt(k / m);
  const double zetas[] = {0.03, 0.5, 0.99, 1.0, 1.01, 2.0};
  const double hws[] = {0.1, 0.5, 1.0};
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 3; j++) {
      const double z = zetas[i], h = hws[j] / wn, c = 2.0 * z * sqrt(k * m);
      fb_contact_row row = {.kp = k, .kd = c, .depth = 1e-6, .step_share = 1.0};
      assert_int_equal(fb_contact_matched(h, k, c, m, &row.erp, &row.cfm, NULL), FB_OK);
      const fb_contact_row matched = row;
      fb_contact_row_static(&row, h, m, 1.0);
      assert_rel(row.erp / (h * row.cfm), k, 1e-13); /* a = k */
      double tr, det;
      row_update(h, m, row.erp, row.cfm, &tr, &det);
      const double disc = tr * tr - 4.0 * det;
      const double slowest = disc < 0.0 ? sqrt(det) : 0.5 * (tr + sqrt(disc));
      const double law = z <= 1.0 ? exp(-z * wn * h) : exp(-wn * (z - sqrt(z * z - 1.0)) * h);
      const double want = fmax(law, 1.0 / (1.0 + hws[j]));
      char name[96];
      snprintf(name, sizeof name, "static row slowest pole, zeta %g, h omega %g", z, hws[j]);
      report_residual(name, fabs(slowest - want), STATIC_POLE_ABS_TOL);
      assert_near(slowest, want, STATIC_POLE_ABS_TOL);
      /* stable: both poles inside the unit circle */
      assert_true(det < 1.0 && fabs(tr) < 1.0 + det);
      /* half weight: a and b halfway between the matched and the static row */
      fb_contact_row half = matched;
      fb_contact_row_static(&half, h, m, 0.5);
      const double am = matched.erp / (h * matched.cfm), bm = 1.0 / matched.cfm;
      assert_rel(half.erp / (h * half.cfm), 0.5 * (am + k), 1e-12);
      assert_rel(1.0 / half.cfm, 0.5 * (bm + 1.0 / row.cfm), 1e-12);
      /* weight 0 leaves the matched row alone */
      fb_contact_row none = matched;
      fb_contact_row_static(&none, h, m, 0.0);
      assert_true(none.erp == matched.erp && none.cfm == matched.cfm);
    }
  /* the persistence weight: 0 up to one period of phase, 1 from two */
  assert_near(fb_contact_persistence(0.0), 0.0, 0.0);
  assert_near(fb_contact_persistence(FB_PERSISTENT_PHASE_RAD), 0.0, 0.0);
  assert_near(fb_contact_persistence(FB_PERSISTENT_PHASE_RAD + 0.5 * FB_PERSISTENT_RAMP_RAD), 0.5,
              1e-15);
  assert_near(fb_contact_persistence(FB_PERSISTENT_PHASE_RAD + FB_PERSISTENT_RAMP_RAD), 1.0, 0.0);
  assert_int_equal(fb_mapping_parse("matched-static"), FB_MAPPING_MATCHED_STATIC);
  assert_string_equal(fb_mapping_name(FB_MAPPING_MATCHED_STATIC), "matched-static");
}

static void test_matched_round_trip(void **state) {
  (void)state;
  const double m = 0.09;
  const double ks[] = {1e6, 3e9};
  const double zetas[] = {0.05, 0.7, 1.8};
  const double hws[] = {0.01, 0.3, 1.2};
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 3; j++)
      for (int q = 0; q < 3; q++) {
        const double wn = sqrt(ks[i] / m), h = hws[q] / wn;
        const double c = 2.0 * zetas[j] * sqrt(ks[i] * m);
        double erp, cfm, k2, c2;
        assert_int_equal(fb_contact_matched(h, ks[i], c, m, &erp, &cfm, NULL), FB_OK);
        assert_int_equal(fb_contact_matched_inverse(h, m, erp, cfm, &k2, &c2, NULL), FB_OK);
        report_residual("matched round trip k", fabs(k2 / ks[i] - 1.0), MATCHED_ROUNDTRIP_REL_TOL);
        assert_rel(k2, ks[i], MATCHED_ROUNDTRIP_REL_TOL);
        assert_rel(c2, c, MATCHED_ROUNDTRIP_REL_TOL);
      }
  /* the map is the standard one as h -> 0: ERP -> h k / (h k + c); they
   * differ by the damper h k the standard map adds, h k / c = 2e-7 here */
  double e1, c1, e2, c2;
  fb_contact_matched(1e-11, 1e6, 50.0, 1.0, &e1, &c1, NULL);
  fb_contact_erp_cfm(1e-11, 1e6, 50.0, &e2, &c2, NULL);
  assert_rel(e1, e2, 1e-6);
  assert_rel(c1, c2, 1e-6);
  assert_int_equal(fb_mapping_parse("matched"), FB_MAPPING_MATCHED);
  assert_string_equal(fb_mapping_name(FB_MAPPING_MATCHED), "matched");
  assert_int_equal(fb_mapping_parse("exact"), FB_MAPPING_COUNT);
}

/* the mean-force correction (contact.h, fb_contact_row_mean_force): a
 * matched row of a Hertz law on a mass m under a constant load F, stepped
 * as ODE steps one row (m (u1 - u0) = h (F - lambda), lambda = a d_n + b u1,
 * d_{n+1} = d_n + h u1), the row rebuilt every step at the current depth,
 * the mean force low-passed from 0: it comes to rest at the law's static
 * depth (F / K)^(1/n); without the correction at a depth off by the matched
 * row's a / k - 1 (the check that the correction is what moves it) */
#define REST_STEPS 200000
/* the rest depth after REST_STEPS (zeta 0.3: settled to roundoff) [-] */
#define REST_DEPTH_REL_TOL 1e-9
static double rest_depth(int corrected) {
  fb_contact_law law = fb_contact_law_default(); /* Hertz, K 1e10, n 1.5 */
  law.kind = FB_LAW_HERTZ;
  const double m = 0.2, f = 500.0, h = 2e-6;
  const double d_static = pow(f / law.stiffness, 1.0 / law.exponent);
  const double k_t = law.exponent * law.stiffness * sqrt(d_static);
  const double c = 2.0 * 0.3 * sqrt(k_t * m); /* a damper on the row, zeta 0.3 at rest */
  double d = 0.5 * d_static, u = 0.0, f_mean = 0.0;
  for (int i = 0; i < REST_STEPS; i++) {
    fb_contact_row row;
    fb_contact_linearize(&law, FB_MAPPING_TANGENT, d, u, 0.0, &row.kp, &row.kd, &row.depth);
    row.kd = c;
    assert_int_equal(fb_contact_matched(h, row.kp, row.kd, m, &row.erp, &row.cfm, NULL), FB_OK);
    if (corrected) fb_contact_row_mean_force(&row, h, f_mean);
    const double a = row.erp / (h * row.cfm), b = 1.0 / row.cfm;
    /* m (u1 - u) = h (f - a depth - b u1) */
    const double u1 = (m * u + h * (f - a * row.depth)) / (m + h * b);
    const double lambda = a * row.depth + b * u1;
    u = u1;
    d += h * u1;
    f_mean = fb_contact_mean_force_step(f_mean, lambda, h, sqrt(row.kp / m));
  }
  return d / d_static - 1.0;
}

static void test_mean_force_row(void **state) {
  (void)state;
  const double with = rest_depth(1), without = rest_depth(0);
  report_residual("rest depth, corrected", with, REST_DEPTH_REL_TOL);
  report_residual("rest depth, matched row alone", without, REST_DEPTH_REL_TOL);
  assert_true(fabs(with) < REST_DEPTH_REL_TOL);
  assert_true(fabs(without) > 1e3 * REST_DEPTH_REL_TOL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_moduli_and_stiffness),
      cmocka_unit_test(test_johnson_inverse_round_trip),
      cmocka_unit_test(test_laws_by_hand),
      cmocka_unit_test(test_restitution_zeta),
      cmocka_unit_test(test_erp_cfm_round_trip),
      cmocka_unit_test(test_linearize_reproduces_the_law),
      cmocka_unit_test(test_matched_poles_are_exact),
      cmocka_unit_test(test_matched_round_trip),
      cmocka_unit_test(test_matched_static_row),
      cmocka_unit_test(test_mean_force_row),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
