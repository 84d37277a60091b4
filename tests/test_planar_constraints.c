/* The planar core's constraint equations (planar_constraints.h): the
 * Jacobian against central differences of Phi, gamma against central
 * differences of Phi_q q' along q', on revolute and prismatic joints
 * between the ground and a body and between two moving bodies, with the
 * slide's axis at an angle, at arbitrary (not assembled) states.
 *
 *        ground --o-- 1 ==[ 2 ]==o-- 3        o revolute, ==[ ]== prismatic
 *                 |                  |        along an axis fixed in body 1
 *                 o------[ 3 ]-------         (and the ground's, to body 3) */
#include <string.h>

#include "fb_test.h"
#include "planar_constraints.h"

/* Central differences of step FD_H: truncation FD_H^2 |Phi'''| / 6 ~ 1e-12
 * (Phi's third derivatives are O(size) = O(0.3)), rounding eps |Phi| /
 * FD_H ~ 1e-10: 1e-8 (relative to the largest entry) covers both. */
#define FD_H 1e-6
#define FD_REL_TOL 1e-8

/* three bodies; joints: ground-1 revolute, 1-2 prismatic at 30 degrees,
 * 2-3 revolute, 3-ground prismatic at -70 degrees, 1-3 revolute */
static fb_planar *bodies_and_joints(void) {
  fb_planar *m = fb_planar_new(3, 5);
  fb_diag d;
  const double c1[2] = {0.1, 0.02}, c2[2] = {0.25, 0.1}, c3[2] = {0.18, -0.12};
  assert_int_equal(fb_planar_add_body(m, "one", 1.0, 1e-3, c1, 0.3, 0, &d), 1);
  assert_int_equal(fb_planar_add_body(m, "two", 0.5, 2e-3, c2, -0.7, 0, &d), 2);
  assert_int_equal(fb_planar_add_body(m, "three", 0.8, 3e-3, c3, 1.9, 0, &d), 3);
  const double a[2] = {0, 0}, b[2] = {0.2, 0.05}, cc[2] = {0.3, 0.0}, dd[2] = {0.2, -0.2},
               e[2] = {0.1, -0.1};
  assert_int_equal(fb_planar_add_joint(m, "g1", FB_KIND_REVOLUTE, 0, 1, a, 0, &d), 0);
  assert_int_equal(fb_planar_add_joint(m, "s12", FB_KIND_PRISMATIC, 1, 2, b, 0.52, &d), 1);
  assert_int_equal(fb_planar_add_joint(m, "r23", FB_KIND_REVOLUTE, 2, 3, cc, 0, &d), 2);
  assert_int_equal(fb_planar_add_joint(m, "s3g", FB_KIND_PRISMATIC, 3, 0, dd, -1.22, &d), 3);
  assert_int_equal(fb_planar_add_joint(m, "r13", FB_KIND_REVOLUTE, 1, 3, e, 0, &d), 4);
  assert_int_equal(fb_planar_set_drive(m, 0, &d), FB_OK);
  return m;
}

/* a state off the assembly: every coordinate moved */
static void state(double *q, double *qd, const fb_planar *m) {
  fb_planar_assembly(m, q);
  for (int i = 0; i < fb_planar_nq(m); i++) {
    q[i] += 0.01 * sin(1.3 * i + 0.4);
    qd[i] = (i % 3 == 2 ? 5.0 : 0.7) * cos(0.9 * i + 0.2);
  }
}

static void test_assembly_satisfies_every_row(void **state_) {
  (void)state_;
  fb_planar *m = bodies_and_joints();
  double q[9], phi[11];
  fb_planar_assembly(m, q);
  const fb_planar_drive d = {0, 0, 0};
  assert_int_equal(fb_planar_rows(m, NULL, 1), 11);
  fb_planar_constraints(phi, NULL, NULL, m, NULL, &d, q, NULL);
  for (int r = 0; r < 11; r++) assert_near(phi[r], 0.0, 1e-16);
  fb_planar_free(m);
}

static void test_jacobian_by_differences(void **state_) {
  (void)state_;
  fb_planar *m = bodies_and_joints();
  const int nq = 9, rows = 11;
  double q[9], qd[9], jac[11 * 9], pp[11], pm[11];
  state(q, qd, m);
  const fb_planar_drive d = {0.4, 0, 0};
  fb_planar_constraints(NULL, jac, NULL, m, NULL, &d, q, NULL);
  double worst = 0.0, big = 0.0;
  for (int i = 0; i < nq; i++) {
    double qp[9], qm[9];
    memcpy(qp, q, sizeof qp);
    memcpy(qm, q, sizeof qm);
    qp[i] += FD_H;
    qm[i] -= FD_H;
    fb_planar_constraints(pp, NULL, NULL, m, NULL, &d, qp, NULL);
    fb_planar_constraints(pm, NULL, NULL, m, NULL, &d, qm, NULL);
    for (int r = 0; r < rows; r++) {
      worst = fmax(worst, fabs((pp[r] - pm[r]) / (2 * FD_H) - jac[r * nq + i]));
      big = fmax(big, fabs(jac[r * nq + i]));
    }
  }
  report_residual("Jacobian vs differences (rel)", worst / big, FD_REL_TOL);
  assert_true(worst / big <= FD_REL_TOL);
  fb_planar_free(m);
}

static void test_gamma_by_differences(void **state_) {
  (void)state_;
  fb_planar *m = bodies_and_joints();
  const int nq = 9, rows = 11;
  double q[9], qd[9], gamma[11], jp[11 * 9], jm[11 * 9];
  state(q, qd, m);
  const fb_planar_drive d = {0.4, 2.0, 0.0};
  fb_planar_constraints(NULL, NULL, gamma, m, NULL, &d, q, qd);
  double qp[9], qm[9];
  for (int i = 0; i < nq; i++) {
    qp[i] = q[i] + FD_H * qd[i];
    qm[i] = q[i] - FD_H * qd[i];
  }
  fb_planar_constraints(NULL, jp, NULL, m, NULL, &d, qp, NULL);
  fb_planar_constraints(NULL, jm, NULL, m, NULL, &d, qm, NULL);
  double worst = 0.0, big = 0.0;
  for (int r = 0; r < rows; r++) {
    /* gamma = -(d/dt Phi_q) q' (the drive's angle is linear in time) */
    double v = 0.0;
    for (int i = 0; i < nq; i++) v += (jp[r * nq + i] - jm[r * nq + i]) / (2 * FD_H) * qd[i];
    worst = fmax(worst, fabs(gamma[r] + v));
    big = fmax(big, fabs(gamma[r]));
  }
  report_residual("gamma vs differences (rel)", worst / big, FD_REL_TOL);
  assert_true(worst / big <= FD_REL_TOL);
  fb_planar_free(m);
}

/* leaving a joint out drops its two rows, and the drive's row is last */
static void test_rows_of_a_subset(void **state_) {
  (void)state_;
  fb_planar *m = bodies_and_joints();
  const unsigned char off[5] = {0, 1, 0, 0, 1};
  assert_int_equal(fb_planar_rows(m, off, 0), 6);
  assert_int_equal(fb_planar_rows(m, off, 1), 7);
  double q[9], qd[9], jac[7 * 9], full[11 * 9];
  state(q, qd, m);
  const fb_planar_drive d = {0.1, 0, 0};
  fb_planar_constraints(NULL, jac, NULL, m, off, &d, q, NULL);
  fb_planar_constraints(NULL, full, NULL, m, NULL, &d, q, NULL);
  /* rows of g1 (0, 1), r23 (4, 5 of the full set), s3g (6, 7), the drive (10) */
  const int from[7] = {0, 1, 4, 5, 6, 7, 10};
  for (int r = 0; r < 7; r++)
    for (int i = 0; i < 9; i++) assert_true(jac[r * 9 + i] == full[from[r] * 9 + i]);
  fb_planar_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_assembly_satisfies_every_row),
      cmocka_unit_test(test_jacobian_by_differences),
      cmocka_unit_test(test_gamma_by_differences),
      cmocka_unit_test(test_rows_of_a_subset),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
