/* Effective mass along a clearance joint's normal: the KKT form in maximal
 * coordinates against closed forms (a free coupler) and against an
 * independent minimal-coordinate derivation (the reference model's mass
 * matrix); the paper four-bar's range over a revolution.
 *
 *            C o-----------o         coupler B-C, follower D-C,
 *             /     3       \        crank A-B driven (infinitely heavy
 *          B o               \ 4     in rotation); the clearance joint's
 *           /                 \      pin is on the first body of the
 *        2 /                   \     joint, its hole on the second
 *         A o===================o D */
#include <string.h>

#include "casefile.h"
#include "effective_mass.h"
#include "fb_test.h"

/* two exact formulas for the same 2 x 2 tensor evaluated in double precision
 * through a 7 x 7 Cholesky solve of entries ~1e2 to 1e4: ~1e-12 relative;
 * the regularisation FB_EFFECTIVE_MASS_REG adds 1e-15 times the condition
 * number of G M^-1 G^T (measured: 2e-12 worst) */
#define TENSOR_REL_TOL 1e-9

static void paper_state(fb_case *c, fb_linkage *su, fb_linkage_state *st, double crank) {
  *c = fb_test_paper_once(); /* the case file is read once */
  fb_case_stackup_lengths(c, su);
  assert_int_equal(fb_linkage_solve(st, su, c->branch, crank, fb_case_omega2(c), 0.0, NULL), FB_OK);
}

/* r-perp r-perp^T / I + I2 / m */
static void body_tensor(double w[2][2], double m, double inertia, const double r[2]) {
  const double p[2] = {-r[1], r[0]};
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) w[a][b] += (a == b ? 1.0 / m : 0.0) + p[a] * p[b] / inertia;
}

static void test_free_coupler_closed_form(void **state) {
  (void)state;
  fb_case c;
  fb_linkage su;
  fb_linkage_state st;
  for (double crank = 0.0; crank < 6.3; crank += 0.7) {
    paper_state(&c, &su, &st, crank);
    fb_mechanism m;
    fb_mechanism_from_state(&m, &su, &st, c.link, (1 << FB_JOINT_B) | (1 << FB_JOINT_C));
    double w[4][2][2];
    assert_int_equal(fb_effective_mass_tensor(w, &m, NULL), FB_OK);
    /* B: the crank is fixed (hinge A and the drive); the coupler is free */
    double wb[2][2] = {{0, 0}, {0, 0}}, wc[2][2] = {{0, 0}, {0, 0}};
    const double rb[2] = {m.joint[1][0] - m.com[1][0], m.joint[1][1] - m.com[1][1]};
    body_tensor(wb, m.mass[1], m.inertia[1], rb);
    /* C: the free coupler plus the follower turning about D */
    const double rc[2] = {m.joint[2][0] - m.com[1][0], m.joint[2][1] - m.com[1][1]};
    body_tensor(wc, m.mass[1], m.inertia[1], rc);
    const double rd[2] = {m.joint[2][0] - m.joint[3][0], m.joint[2][1] - m.joint[3][1]};
    const double gd[2] = {m.com[2][0] - m.joint[3][0], m.com[2][1] - m.joint[3][1]};
    const double i_d = m.inertia[2] + m.mass[2] * (gd[0] * gd[0] + gd[1] * gd[1]);
    const double p[2] = {-rd[1], rd[0]};
    for (int a = 0; a < 2; a++)
      for (int b = 0; b < 2; b++) wc[a][b] += p[a] * p[b] / i_d;
    report_residual("free coupler at B", fb_test_tensor_rel_diff(w[1], wb), TENSOR_REL_TOL);
    report_residual("coupler + pivoted follower at C", fb_test_tensor_rel_diff(w[2], wc), TENSOR_REL_TOL);
    assert_true(fb_test_tensor_rel_diff(w[1], wb) < TENSOR_REL_TOL);
    assert_true(fb_test_tensor_rel_diff(w[2], wc) < TENSOR_REL_TOL);
    /* ideal joints carry no tensor */
    assert_true(w[0][0][0] == 0.0 && w[3][1][1] == 0.0);
  }
}

/* the reference model's minimal coordinates (reference.h): q = (theta3,
 * theta4), the hole B = C - b e3 moves with J_B = [b e3', c e4'] ... */
static void minimal_tensor(double w[2][2], const fb_case *c, const fb_linkage *su,
                           const fb_linkage_state *st) {
  const double b = su->length[FB_COUPLER], cl = su->length[FB_FOLLOWER];
  const double f3 = c->link[FB_COUPLER].com_fraction, f4 = c->link[FB_FOLLOWER].com_fraction;
  const double m3 = c->link[FB_COUPLER].mass, m4 = c->link[FB_FOLLOWER].mass;
  const double i3 = c->link[FB_COUPLER].inertia, i4 = c->link[FB_FOLLOWER].inertia;
  const double th3 = st->coupler_angle, th4 = st->follower_angle;
  const double m11 = m3 * (1 - f3) * (1 - f3) * b * b + i3;
  const double m12 = -m3 * cl * (1 - f3) * b * cos(th4 - th3);
  const double m22 = m3 * cl * cl + m4 * f4 * f4 * cl * cl + i4;
  const double det = m11 * m22 - m12 * m12;
  const double mi[2][2] = {{m22 / det, -m12 / det}, {-m12 / det, m11 / det}};
  /* hole B = D + c e4 - b e3: columns d/dtheta3 = b (s3, -c3), d/dtheta4 = c (-s4, c4) */
  const double jb[2][2] = {{b * sin(th3), -cl * sin(th4)}, {-b * cos(th3), cl * cos(th4)}};
  for (int r = 0; r < 2; r++)
    for (int q = 0; q < 2; q++) {
      double v = 0.0;
      for (int a = 0; a < 2; a++)
        for (int k = 0; k < 2; k++) v += jb[r][a] * mi[a][k] * jb[q][k];
      w[r][q] = v;
    }
}

static void test_matches_minimal_coordinates(void **state) {
  (void)state;
  fb_case c;
  fb_linkage su;
  fb_linkage_state st;
  double worst = 0.0, worst_closed = 0.0;
  for (double crank = 0.0; crank < 6.3; crank += 0.1) {
    paper_state(&c, &su, &st, crank);
    fb_mechanism m;
    fb_mechanism_from_state(&m, &su, &st, c.link, 1 << FB_JOINT_B);
    double w[4][2][2], wk[4][2][2], wm[2][2];
    /* the closed form (B alone, crank driven) and the general KKT solve */
    assert_int_equal(fb_effective_mass_tensor(w, &m, NULL), FB_OK);
    assert_int_equal(fb_effective_mass_tensor_kkt(wk, &m, NULL), FB_OK);
    minimal_tensor(wm, &c, &su, &st);
    worst = fmax(worst, fb_test_tensor_rel_diff(wk[1], wm));
    worst_closed = fmax(worst_closed, fmax(fb_test_tensor_rel_diff(w[1], wm), fb_test_tensor_rel_diff(w[1], wk[1])));
    for (int j = 0; j < 4; j++) /* the other joints' tensors are zero in both */
      if (j != 1)
        for (int r = 0; r < 4; r++) assert_true(w[j][r / 2][r % 2] == 0.0 && wk[j][r / 2][r % 2] == 0.0);
  }
  report_residual("KKT vs minimal coordinates (B)", worst, TENSOR_REL_TOL);
  report_residual("closed form vs KKT and minimal coordinates (B)", worst_closed, TENSOR_REL_TOL);
  assert_true(worst < TENSOR_REL_TOL);
  assert_true(worst_closed < TENSOR_REL_TOL);
}

/* the measured range of the paper four-bar's effective mass at the
 * crank-coupler joint, 0.092 to 0.95 kg, printed to two digits */
#define PAPER_RANGE_REL_TOL 0.03

static void test_paper_range_over_a_revolution(void **state) {
  (void)state;
  fb_case c;
  fb_linkage su;
  fb_linkage_state st;
  double lo = INFINITY, hi = 0.0;
  for (int k = 0; k < 3600; k++) {
    paper_state(&c, &su, &st, 2.0 * M_PI * k / 3600.0);
    fb_mechanism m;
    fb_mechanism_from_state(&m, &su, &st, c.link, 1 << FB_JOINT_B);
    double w[4][2][2], a, b;
    assert_int_equal(fb_effective_mass_tensor(w, &m, NULL), FB_OK);
    fb_effective_mass_range(w[1], &a, &b);
    lo = fmin(lo, a);
    hi = fmax(hi, b);
    /* the range bounds every direction */
    for (double phi = 0.0; phi < M_PI; phi += 0.3) {
      const double n[2] = {cos(phi), sin(phi)};
      const double me = fb_effective_mass_along(w[1], n);
      assert_true(me >= a * (1 - 1e-12) && me <= b * (1 + 1e-12));
    }
  }
  if (fb_test_verbose()) fprintf(stderr, "  paper B effective mass %.4f .. %.4f kg\n", lo, hi);
  assert_rel(lo, 0.092, PAPER_RANGE_REL_TOL);
  assert_rel(hi, 0.95, PAPER_RANGE_REL_TOL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_free_coupler_closed_form),
      cmocka_unit_test(test_matches_minimal_coordinates),
      cmocka_unit_test(test_paper_range_over_a_revolution),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
