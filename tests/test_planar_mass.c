/* The planar core's constrained inverse mass (planar_mass.h): the effective
 * mass at any joint against effective_mass.h (the four-bar's KKT form and
 * its crank-pin closed form; the slider-crank's piston pin), the
 * accelerations under a force against a closed form, and the projection
 * onto the constraints.
 *
 *            C           the clearance joint's rows leave the set; the
 *           / \          drive stays (an infinitely heavy motor); W is
 *  coupler /   \         the inverse mass of the pin's motion relative to
 *         B     \        its hole: m_eff(n) = 1 / (n^T W n)
 *  crank /       \
 *       A ------- D */
#include <string.h>

#include "casefile.h"
#include "effective_mass.h"
#include "fb_test.h"
#include "fb_test_planar.h"
#include "planar_case.h"
#include "planar_kinematics.h"
#include "planar_mass.h"

/* Two exact forms of the same 2 x 2 tensor: the core's Schur complement
 * over the description's rows and effective_mass.c's over its own, both
 * with FB_EFFECTIVE_MASS_REG; entries ~1e1 to 1e3 1/kg through a 7 x 7
 * Cholesky of condition ~1e4: 1e-10 relative to the tensor's largest
 * entry holds both (measured ~1e-14). */
#define TENSOR_REL_TOL 1e-10
/* Projection: Gauss-Newton steps converge quadratically from a 1e-4 m
 * perturbation (1e-8, 1e-16): the rows' rounding of a 0.3 m mechanism. */
#define PROJECT_TOL_M 1e-15

/* every clearance mask of one or two four-bar joints, at 12 crank angles */
static void test_fourbar_against_effective_mass(void **state) {
  (void)state;
  const fb_case c = fb_test_paper_once();
  fb_linkage su;
  fb_case_stackup_lengths(&c, &su);
  fb_test_planar t = fb_test_planar_paper(&c, &su);
  fb_planar *m = t.m;
  fb_diag d;
  double q[9], worst = 0.0;
  fb_planar_assembly(m, q);
  const int masks[] = {1 << FB_JOINT_B, 1 << FB_JOINT_A, 1 << FB_JOINT_C, 1 << FB_JOINT_D,
                       (1 << FB_JOINT_B) | (1 << FB_JOINT_C), (1 << FB_JOINT_A) | (1 << FB_JOINT_D)};
  for (int i = 0; i < 12; i++) {
    const double phi = i * 30.0 * M_PI / 180.0;
    assert_int_equal(fb_planar_position(t.k, q, phi, NULL, &d), FB_OK);
    fb_linkage_state st;
    assert_int_equal(fb_linkage_solve(&st, &su, c.branch, phi, 0, 0, &d), FB_OK);
    for (size_t x = 0; x < sizeof masks / sizeof masks[0]; x++) {
      fb_mechanism fm;
      fb_mechanism_from_state(&fm, &su, &st, c.link, masks[x]);
      double want[4][2][2];
      assert_int_equal(fb_effective_mass_tensor_kkt(want, &fm, &d), FB_OK);
      unsigned char off[4];
      for (int j = 0; j < 4; j++) off[j] = (masks[x] >> j) & 1;
      for (int j = 0; j < 4; j++) {
        if (!off[j]) continue;
        double w[2][2];
        assert_int_equal(fb_planar_effective_mass_tensor(w, m, q, off, j, &d), FB_OK);
        worst = fmax(worst, fb_test_tensor_rel_diff(w, want[j]));
      }
    }
  }
  report_residual("four-bar W, core vs effective_mass.h (rel)", worst, TENSOR_REL_TOL);
  assert_true(worst <= TENSOR_REL_TOL);
  /* a joint in the set has no effective mass of its own */
  unsigned char off[4] = {0, 1, 0, 0};
  double w[2][2];
  assert_int_equal(fb_planar_effective_mass_tensor(w, m, q, off, 2, &d), FB_ERR_ARG);
  fb_test_planar_free(&t);
}

/* the slider-crank's piston pin: the core against the closed form
 * (fb_effective_mass_tensor's W = p p^T / I_B + x x^T / m_slider) */
static void test_piston_pin(void **state) {
  (void)state;
  fb_case c = fb_test_paper_once();
  const fb_linkage lk = {{0.05, 0.2, 0.01, 0}};
  fb_test_planar t = fb_test_planar_slider(&c, &lk, 0.6, 1e-4, 0.0);
  fb_planar *m = t.m;
  fb_diag d;
  const fb_slider_crank sc = fb_slider_crank_of(&lk);
  double q[9], worst = 0.0;
  fb_planar_assembly(m, q);
  for (int i = 0; i < 12; i++) {
    const double phi = i * 30.0 * M_PI / 180.0;
    assert_int_equal(fb_planar_position(t.k, q, phi, NULL, &d), FB_OK);
    fb_slider_crank_state st;
    assert_int_equal(fb_slider_crank_solve(&st, &sc, phi, 0, 0, &d), FB_OK);
    fb_mechanism fm;
    fb_mechanism_from_slider_crank(&fm, &st, c.link, 1 << FB_JOINT_C);
    double want[4][2][2], w[2][2];
    assert_int_equal(fb_effective_mass_tensor(want, &fm, &d), FB_OK);
    const unsigned char off[4] = {0, 0, 1, 0};
    assert_int_equal(fb_planar_effective_mass_tensor(w, m, q, off, 2, &d), FB_OK);
    worst = fmax(worst, fb_test_tensor_rel_diff(w, want[FB_JOINT_C]));
  }
  report_residual("piston pin W, core vs closed form (rel)", worst, TENSOR_REL_TOL);
  assert_true(worst <= TENSOR_REL_TOL);
  fb_test_planar_free(&t);
}

/* a crank alone, driven: every force leaves it unmoved but for the drive's
 * prescribed motion; with the drive's joint a clearance joint, a force on
 * the free crank accelerates its centre by F / m and turns it not at all
 * (the drive holds its angle) */
static void test_accel_free_body(void **state) {
  (void)state;
  fb_planar *m = fb_planar_new(1, 1);
  fb_diag d;
  const double c0[2] = {0.05, 0.0}, a[2] = {0.0, 0.0};
  assert_int_equal(fb_planar_add_body(m, "crank", 2.0, 1e-3, c0, 0.0, 0, &d), 1);
  assert_int_equal(fb_planar_add_joint(m, "ground-crank", FB_KIND_REVOLUTE, 0, 1, a, 0, &d), 0);
  assert_int_equal(fb_planar_set_drive(m, 0, &d), FB_OK);
  const unsigned char off[1] = {1};
  fb_planar_cmass *cm;
  assert_int_equal(fb_planar_cmass_new(&cm, m, off, &d), FB_OK);
  assert_int_equal(fb_planar_cmass_rows(cm), 1);
  double q[3] = {0.05, 0.0, 0.0};
  assert_int_equal(fb_planar_cmass_factor(cm, q, 0.0, &d), FB_OK);
  const double force[3] = {3.0, -4.0, 0.7}, gamma[1] = {0.0};
  double qdd[3], lambda[1];
  fb_planar_cmass_accel(cm, qdd, lambda, force, gamma);
  assert_near(qdd[0], 1.5, 1e-15);
  assert_near(qdd[1], -2.0, 1e-15);
  assert_near(qdd[2], 0.0, 1e-15);
  /* the drive's reaction torque balances the applied moment: -lambda = -0.7 */
  assert_near(lambda[0], 0.7, 1e-15);
  fb_planar_cmass_free(cm);
  fb_planar_free(m);
}

/* a perturbed four-bar state comes back onto its constraints */
static void test_projection(void **state) {
  (void)state;
  const fb_case c = fb_test_paper_once();
  fb_planar *m;
  fb_diag d;
  assert_int_equal(fb_planar_fourbar(&m, &c.nominal, c.branch, c.link, 0.3, &d), FB_OK);
  const unsigned char off[4] = {0, 1, 0, 0}; /* the crank-coupler joint free, as a clearance joint */
  fb_planar_cmass *cm;
  assert_int_equal(fb_planar_cmass_new(&cm, m, off, &d), FB_OK);
  double q[9], qd[9] = {0.01, -0.02, 0.5, 0.3, 0.1, -2.0, 0.2, 0.4, 1.0};
  fb_planar_assembly(m, q);
  for (int i = 0; i < 9; i++) q[i] += 1e-4 * ((i * 7) % 5 - 2);
  const fb_planar_drive dr = {0.0, -104.7, 0.0};
  double before, vbefore;
  assert_int_equal(fb_planar_cmass_project(cm, q, qd, &dr, &before, &vbefore, &d), FB_OK);
  double after, vafter;
  assert_int_equal(fb_planar_cmass_project(cm, q, qd, &dr, &after, &vafter, &d), FB_OK);
  if (fb_test_verbose())
    fprintf(stderr, "  projection: |Phi| %.3g -> %.3g m, |G q' - nu| %.3g -> %.3g m/s\n", before,
            after, vbefore, vafter);
  assert_true(before > 1e-5);
  assert_true(after <= PROJECT_TOL_M);
  assert_true(vafter <= 1e-12);
  fb_planar_cmass_free(cm);
  fb_planar_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_fourbar_against_effective_mass),
      cmocka_unit_test(test_piston_pin),
      cmocka_unit_test(test_accel_free_body),
      cmocka_unit_test(test_projection),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
