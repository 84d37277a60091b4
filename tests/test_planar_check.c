/* The checks of a planar description (planar_check.h), each error path
 * with the joint or body it must name: not joined to the ground, the
 * Gruebler-Kutzbach count, a singular Jacobian at the assembly (a toggle),
 * a description that does not close, a drive that locks within its
 * revolution (at the closed form's angle), a change point, and a valid
 * mechanism that passes.
 *
 *            C                 four-bars built from their joint positions
 *           / \                A, B, C, D (ground-crank, crank-coupler,
 *  coupler /   \ follower      coupler-follower, follower-ground), masses
 *         B     \              of 0.1 kg, 1e-4 kg m^2 at each link's middle
 *  crank /       \
 *       A ------- D */
#include <string.h>

#include "fb_test.h"
#include "linkage.h"
#include "planar_check.h"

static void add_bar(fb_planar *m, const char *name, const double p[2], const double q[2]) {
  const double c[2] = {0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])};
  fb_diag d;
  if (fb_planar_add_body(m, name, 0.1, 1e-4, c, atan2(q[1] - p[1], q[0] - p[0]), 0, &d) < 0)
    fail_msg("%s", d.msg);
}

static void add_pin(fb_planar *m, const char *name, int b0, int b1, const double at[2]) {
  fb_diag d;
  if (fb_planar_add_joint(m, name, FB_KIND_REVOLUTE, b0, b1, at, 0, &d) < 0) fail_msg("%s", d.msg);
}

static fb_planar *fourbar_at(const double a[2], const double b[2], const double c[2],
                             const double dd[2]) {
  fb_planar *m = fb_planar_new(4, 5);
  add_bar(m, "crank", a, b);
  add_bar(m, "coupler", b, c);
  add_bar(m, "follower", dd, c);
  add_pin(m, "ground-crank", 0, 1, a);
  add_pin(m, "crank-coupler", 1, 2, b);
  add_pin(m, "coupler-follower", 2, 3, c);
  add_pin(m, "follower-ground", 3, 0, dd);
  assert_int_equal(fb_planar_set_drive(m, 0, NULL), FB_OK);
  return m;
}

static const double A[2] = {0, 0}, B[2] = {0.04, 0}, C[2] = {0.1, 0.12}, D[2] = {0.15, 0};

static void expect(const fb_planar *m, fb_status st, const char *const *needles, int joint,
                   int body) {
  fb_diag d;
  fb_planar_where w;
  assert_int_equal(fb_planar_check(m, &w, &d), st);
  if (fb_test_verbose()) fprintf(stderr, "  %s\n", st == FB_OK ? "(ok)" : d.msg);
  for (int i = 0; needles && needles[i]; i++)
    if (!strstr(d.msg, needles[i])) fail_msg("'%s' lacks '%s'", d.msg, needles[i]);
  if (joint >= -1) assert_int_equal(w.joint, joint);
  if (body >= -1) assert_int_equal(w.body, body);
}

static void test_valid_crank_rocker(void **state) {
  (void)state;
  fb_planar *m = fourbar_at(A, B, C, D);
  expect(m, FB_OK, NULL, -1, -1);
  fb_planar_free(m);
}

static void test_not_joined(void **state) {
  (void)state;
  fb_planar *m = fourbar_at(A, B, C, D);
  const double e[2] = {0.3, 0.3}, f[2] = {0.4, 0.3};
  add_bar(m, "stray", e, f); /* body 4, joined to nothing */
  expect(m, FB_ERR_ARG, (const char *[]){"body 'stray'", "not joined to the ground", NULL}, -1, 4);
  fb_planar_free(m);
}

/* five bodies... a five-bar: 3 x 4 - 2 x 5 = 2 */
static void test_two_degrees_of_freedom(void **state) {
  (void)state;
  fb_planar *m = fb_planar_new(4, 5);
  const double e[2] = {0.2, 0.1}, f[2] = {0.25, 0};
  add_bar(m, "crank", A, B);
  add_bar(m, "a", B, C);
  add_bar(m, "b", C, e);
  add_bar(m, "c", f, e);
  add_pin(m, "j1", 0, 1, A);
  add_pin(m, "j2", 1, 2, B);
  add_pin(m, "j3", 2, 3, C);
  add_pin(m, "j4", 3, 4, e);
  add_pin(m, "j5", 4, 0, f);
  fb_planar_set_drive(m, 0, NULL);
  expect(m, FB_ERR_ARG,
         (const char *[]){"2 degrees of freedom", "3 x (5 - 1) - 2 x 5", "a joint is missing", NULL},
         -2, -2);
  fb_planar_free(m);
}

/* a fifth joint pins the coupler to the ground too: 3 x 3 - 2 x 5 = -1 */
static void test_over_constrained(void **state) {
  (void)state;
  fb_planar *m = fourbar_at(A, B, C, D);
  const double e[2] = {0.07, 0.06};
  add_pin(m, "coupler-ground", 2, 0, e);
  expect(m, FB_ERR_ARG, (const char *[]){"-1 degrees of freedom", "over-constrained", NULL}, -2, -2);
  fb_planar_free(m);
}

/* assembled at a toggle (coupler and follower in line through C): the
 * count is right, the Jacobian singular */
static void test_toggle_at_assembly(void **state) {
  (void)state;
  const double c[2] = {0.1, 0}, d[2] = {0.2, 0};
  fb_planar *m = fourbar_at(A, B, c, d);
  expect(m, FB_ERR_ARG,
         (const char *[]){"dependent at the assembly configuration", "can move there with the "
                          "drive held", "toggle", NULL},
         -2, -2);
  fb_planar_free(m);
}

/* the follower's pin moved away on the follower: no position closes */
static void test_does_not_close(void **state) {
  (void)state;
  fb_planar *m = fourbar_at(A, B, C, D);
  m->joint[2].point[1][0] *= 3.0; /* C three times as far from the follower's centre */
  expect(m, FB_ERR_ASSEMBLY, (const char *[]){"does not close", "no solution", "joint '", NULL},
         -2, -2);
  fb_planar_where w;
  fb_planar_check(m, &w, NULL);
  assert_true(w.joint >= 0);
  fb_planar_free(m);
}

/* a crank too long for its loop: it locks where |BD| = coupler + follower,
 * the closed form's crank range (linkage.h) */
static void test_locks_within_revolution(void **state) {
  (void)state;
  const double b[2] = {0.2, 0}, d[2] = {0.25, 0};
  /* C at the intersection of |BC| = 0.15, |DC| = 0.12 */
  const double bd = 0.05, x = (0.15 * 0.15 - 0.12 * 0.12 + bd * bd) / (2 * bd);
  const double c[2] = {0.2 + x, sqrt(0.15 * 0.15 - x * x)};
  fb_planar *m = fourbar_at(A, b, c, d);
  fb_diag dg;
  fb_planar_where w;
  assert_int_equal(fb_planar_check(m, &w, &dg), FB_ERR_ASSEMBLY);
  if (fb_test_verbose()) fprintf(stderr, "  %s\n", dg.msg);
  const fb_linkage lk = {{0.2, 0.15, 0.12, 0.25}};
  double lo, hi;
  int full;
  assert_int_equal(fb_linkage_crank_range(&lk, &lo, &hi, &full, NULL), FB_OK);
  char angle[32];
  snprintf(angle, sizeof angle, "locks at %.2f", hi * 180.0 / M_PI);
  assert_non_null(strstr(dg.msg, angle));
  assert_non_null(strstr(dg.msg, "'coupler' and 'follower'"));
  assert_non_null(strstr(dg.msg, "joint 'coupler-follower'"));
  assert_int_equal(w.joint, 2);
  fb_planar_free(m);
}

/* a parallelogram is a change-point linkage: it passes a singular
 * position (all four pins in line) when the crank lies along the ground */
static void test_change_point(void **state) {
  (void)state;
  const double b[2] = {0.05 * cos(1.0), 0.05 * sin(1.0)}, d[2] = {0.1, 0};
  const double c[2] = {0.1 + b[0], b[1]};
  fb_planar *m = fourbar_at(A, b, c, d);
  fb_diag dg;
  assert_int_equal(fb_planar_check(m, NULL, &dg), FB_ERR_ASSEMBLY);
  if (fb_test_verbose()) fprintf(stderr, "  %s\n", dg.msg);
  /* at pi - 1 rad of drive angle the crank lies along -x */
  char angle[32];
  snprintf(angle, sizeof angle, "at %.2f", (M_PI - 1.0) * 180.0 / M_PI);
  assert_non_null(strstr(dg.msg, angle));
  fb_planar_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_valid_crank_rocker),
      cmocka_unit_test(test_not_joined),
      cmocka_unit_test(test_two_degrees_of_freedom),
      cmocka_unit_test(test_over_constrained),
      cmocka_unit_test(test_toggle_at_assembly),
      cmocka_unit_test(test_does_not_close),
      cmocka_unit_test(test_locks_within_revolution),
      cmocka_unit_test(test_change_point),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
