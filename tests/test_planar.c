/* The planar description (model/mech/planar.h): bodies and joints added
 * and found by name, each joint's points in its bodies' frames, the
 * Gruebler-Kutzbach count, the drive's bodies, and the refusals.
 *
 *   ground --o-- crank --o-- rod      o: revolute joints at their
 *            A          B             assembly positions */
#include <string.h>

#include "fb_test.h"
#include "planar.h"

/* a point taken into a body's frame and back: a rotation of a 0.1 m
 * vector, rounding ~1e-17 m */
#define FRAME_TOL_M 1e-16

static fb_planar *crank_and_rod(void) {
  fb_planar *m = fb_planar_new(3, 4); /* room to spare */
  assert_non_null(m);
  const double c1[2] = {0.03, 0.04}, c2[2] = {0.1, 0.1}, a[2] = {0, 0}, b[2] = {0.06, 0.08};
  fb_diag d;
  assert_int_equal(fb_planar_add_body(m, "crank", 0.1, 1e-4, c1, atan2(0.08, 0.06), 0, &d), 1);
  assert_int_equal(fb_planar_add_body(m, "rod", 0.2, 2e-4, c2, 0.25, FB_PLANAR_DERIVED_MASS, &d), 2);
  assert_int_equal(fb_planar_add_joint(m, "ground-crank", FB_KIND_REVOLUTE, 0, 1, a, 0, &d), 0);
  assert_int_equal(fb_planar_add_joint(m, "crank-rod", FB_KIND_REVOLUTE, 1, 2, b, 0, &d), 1);
  return m;
}

static void test_build_and_find(void **state) {
  (void)state;
  fb_planar *m = crank_and_rod();
  assert_int_equal(m->nbodies, 3);
  assert_string_equal(m->body[0].name, "ground");
  assert_int_equal(fb_planar_find_body(m, "rod"), 2);
  assert_int_equal(fb_planar_find_body(m, "nope"), -1);
  assert_int_equal(fb_planar_find_joint(m, "crank-rod"), 1);
  assert_int_equal(fb_planar_nq(m), 6);
  assert_int_equal(fb_planar_gruebler(m), 2); /* 3 x 2 - 2 x 2 */
  /* B in the crank's frame: along its x axis, 0.05 m from its centre */
  assert_near(m->joint[1].point[0][0], 0.05, FRAME_TOL_M);
  assert_near(m->joint[1].point[0][1], 0.0, FRAME_TOL_M);
  /* the assembly: every body at (centre, angle0) */
  double q[6];
  fb_planar_assembly(m, q);
  assert_near(q[3], 0.1, 0.0);
  assert_near(q[5], 0.25, 0.0);
  /* the size: joints 0.1 m apart, 0.05 m from their mean */
  assert_near(fb_planar_size(m), 0.05, 1e-17);
  fb_planar_free(m);
}

static void test_drive_bodies(void **state) {
  (void)state;
  fb_planar *m = crank_and_rod();
  int from, to;
  assert_int_equal(fb_planar_set_drive(m, 0, NULL), FB_OK);
  fb_planar_drive_bodies(m, &from, &to);
  assert_int_equal(from, 0);
  assert_int_equal(to, 1);
  /* a drive between two moving bodies: body[1] turns relative to body[0] */
  assert_int_equal(fb_planar_set_drive(m, 1, NULL), FB_OK);
  fb_planar_drive_bodies(m, &from, &to);
  assert_int_equal(from, 1);
  assert_int_equal(to, 2);
  fb_planar_free(m);
}

static void test_refusals(void **state) {
  (void)state;
  fb_planar *m = crank_and_rod();
  fb_diag d;
  const double c[2] = {0, 0};
  assert_int_equal(fb_planar_add_body(m, "rod", 1, 1, c, 0, 0, &d), -1); /* taken */
  assert_non_null(strstr(d.msg, "named twice"));
  assert_int_equal(fb_planar_add_body(m, "ground", 1, 1, c, 0, 0, &d), -1);
  /* one word in CSV columns and JSON keys ('-' as '_', names.h), across kinds */
  assert_int_equal(fb_planar_add_joint(m, "crank_rod", FB_KIND_REVOLUTE, 1, 2, c, 0, &d), -1);
  assert_non_null(strstr(d.msg, "joint 'crank_rod' and joint 'crank-rod' both write one word"));
  assert_int_equal(fb_planar_add_body(m, "crank-rod", 1, 1, c, 0, 0, &d), -1);
  assert_non_null(strstr(d.msg, "body 'crank-rod' and joint 'crank-rod'"));
  assert_int_equal(fb_planar_add_joint(m, "rod", FB_KIND_REVOLUTE, 1, 2, c, 0, &d), -1);
  assert_non_null(strstr(d.msg, "joint 'rod' and body 'rod'"));
  assert_int_equal(fb_planar_add_body(m, "drive", 1, 1, c, 0, 0, &d), -1); /* drive_angle_rad */
  assert_non_null(strstr(d.msg, "drive_angle_rad"));
  assert_int_equal(fb_planar_add_body(m, "", 1, 1, c, 0, 0, &d), -1);
  assert_int_equal(fb_planar_add_joint(m, "x", FB_KIND_REVOLUTE, 1, 1, c, 0, &d), -1);
  assert_non_null(strstr(d.msg, "two different bodies"));
  assert_int_equal(fb_planar_add_joint(m, "x", FB_KIND_REVOLUTE, 1, 7, c, 0, &d), -1);
  const double bad[2] = {NAN, 0};
  assert_int_equal(fb_planar_add_joint(m, "x", FB_KIND_REVOLUTE, 1, 2, bad, 0, &d), -1);
  /* full: room for 2 bodies and 2 joints */
  fb_planar *full = fb_planar_new(1, 1);
  assert_int_equal(fb_planar_add_body(full, "one", 1, 1, c, 0, 0, &d), 1);
  assert_int_equal(fb_planar_add_body(full, "two", 1, 1, c, 0, 0, &d), -1);
  assert_non_null(strstr(d.msg, "holds 1 moving bodies"));
  fb_planar_free(full);
  fb_planar *neg = fb_planar_new(1, 1);
  assert_int_equal(fb_planar_add_body(neg, "one", 0.0, 1, c, 0, 0, &d), -1);
  assert_non_null(strstr(d.msg, "positive"));
  fb_planar_free(neg);
  /* a prismatic joint cannot be driven at speed_rpm */
  const double p[2] = {0.1, 0.1};
  assert_int_equal(fb_planar_add_joint(m, "slide", FB_KIND_PRISMATIC, 2, 0, p, 0.0, &d), 2);
  assert_false(m->joint[2].clearance_ok);
  assert_int_equal(fb_planar_set_drive(m, 2, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "prismatic"));
  assert_null(fb_planar_new(0, 1));
  fb_planar_free(m);
}

/* a prismatic joint's axis is kept in its first body's frame */
static void test_prismatic_axis(void **state) {
  (void)state;
  fb_planar *m = fb_planar_new(1, 1);
  const double c[2] = {0.1, 0.0}, at[2] = {0.1, 0.0};
  assert_int_equal(fb_planar_add_body(m, "slider", 1, 1e-3, c, M_PI / 2, 0, NULL), 1);
  assert_int_equal(fb_planar_add_joint(m, "slider-ground", FB_KIND_PRISMATIC, 1, 0, at, 0.0, NULL), 0);
  /* the world's +x seen from a body turned by 90 degrees: -y */
  assert_near(m->joint[0].axis[0], 0.0, 1e-16);
  assert_near(m->joint[0].axis[1], -1.0, 1e-16);
  fb_planar_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_build_and_find),
      cmocka_unit_test(test_drive_bodies),
      cmocka_unit_test(test_refusals),
      cmocka_unit_test(test_prismatic_axis),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
