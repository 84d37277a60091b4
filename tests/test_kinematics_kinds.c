/* fourbar kinematics' kinds (kinematics_kinds.h): every mechanism type has
 * one with every entry set, its data agrees with the case key table, and
 * the study run through it gives each kind's quantities against closed
 * forms computed here by another route.
 *
 *   four-bar                          slider-crank, offset 0
 *        C                                  B
 *       / \  follower c                    / \  coupler b
 *  b   /   \                        a     /   \
 *     B     D                            A     [C] -> x   guide y = 0
 *    / a    |  ground d along +x
 *   A-------+
 *
 * Four-bar: at crank angles 0 and 180 deg the diagonal from the crank pin
 * B to the follower pivot D is d - a and d + a, and the transmission angle
 * there, by the law of cosines in triangle BCD, mu = acos((b^2 + c^2 -
 * BD^2) / (2 b c)), is the smallest and the largest of a crank-rocker
 * (Norton, Design of Machinery, sec. 4.10). The coupler's angular
 * acceleration peak over omega2^2 is docs/paper.md's 1.091571.
 * Slider-crank at offset 0: dead centres x = b + a at crank angle 0 and
 * b - a at pi, stroke 2 a, both strokes half a turn (quick-return ratio 1),
 * transmission angle pi/2 (rod along the guide) down to acos(a / b) (crank
 * perpendicular to the guide); the slider's acceleration at crank angle 0,
 * x'' = -a omega2^2 (1 + a / b), from x = a cos t + sqrt(b^2 - a^2 sin^2 t)
 * differentiated twice here, its most negative over a turn (a scan of
 * x''(t) below checks that no other crank angle goes lower). */
#include <jansson.h>

#include "casefile.h"
#include "fb_test.h"
#include "kinematics.h"
#include "kinematics_kinds.h"
#include "units.h"

/* ---- tolerances ----------------------------------------------------------- */

/* Sums and positions of lengths ~0.1 m: a few roundings of 1e-17 m. */
#define LENGTH_TOL_M 1e-15
/* An angle from acos of a ratio of O(1) terms: acos' slope at the paper's
 * ratios (0.86, 0.13) is below 2, the ratio's round-off a few 1e-16; the
 * library finds the same extremes by its own route: 1e-12 rad leaves room
 * for a minimiser's polishing. */
#define ANGLE_TOL_RAD 1e-12
/* docs/paper.md's coupler ratio is printed to 7 digits: half a unit of the
 * last one. */
#define PAPER_RATIO_TOL 5e-7
/* The slider's acceleration extreme: the library's Brent minimiser stops at
 * 1e-12 rad of crank angle, where x''' ~ 0 at the extreme, so the value
 * agrees to round-off; 1e-9 of a omega2^2 is the bound for the
 * slider-crank's kinematics against a closed form. */
#define PEAK_REL_TOL 1e-9

/* ---- helpers ---------------------------------------------------------------- */

/* k with the inputs of type t, lengths mm[0 .. n-1] [mm], rpm, dir */
static void setup(fb_kinematics *k, fb_mech_type t, const double *mm, int n, double rpm, int dir) {
  memset(k, 0, sizeof *k);
  k->mech = t;
  k->kind = fb_report_kinematics_kind(t);
  for (int i = 0; i < n; i++) {
    k->mm[i] = mm[i];
    k->lk.length[i] = mm[i] * FB_M_PER_MM;
  }
  k->rpm = rpm;
  k->dir = dir;
  k->branch = FB_BRANCH_OPEN;
  k->case_path = "";
}

/* 1 when the kind's text entry prints the class line */
static int text_has_class_line(const fb_kinematics *k) {
  char buf[8192] = "";
  FILE *f = fmemopen(buf, sizeof buf - 1, "w");
  if (!f) return 0;
  k->kind->text(f, k);
  fclose(f);
  return strstr(buf, k->grashof) != NULL;
}

/* ---- tests ------------------------------------------------------------------ */

/* every type has a kind, every entry set; its offset is the one length
 * whose case key takes a negative value; out of range: the four-bar's, as
 * fb_mech_of */
static void test_every_type_has_a_kind(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_kinematics_kind *kind = fb_report_kinematics_kind((fb_mech_type)t);
    const fb_mech_desc *m = fb_mech_of((fb_mech_type)t);
    assert_non_null(kind);
    assert_non_null(kind->run);
    assert_non_null(kind->text);
    assert_non_null(kind->json);
    assert_true(kind->offset_length >= -1 && kind->offset_length < m->nlengths);
    for (int i = 0; i < m->nlengths; i++) {
      char key[48];
      snprintf(key, sizeof key, "%s_mm", m->length[i]);
      fb_diag d;
      const int signed_ok = fb_casefile_check_range("linkage", key, -1.0, key, &d) == FB_OK;
      if (signed_ok != (i == kind->offset_length))
        fail_msg("%s: length %s: its case key %s a negative value, the kind's offset_length "
                 "is %d", m->type, m->length[i], signed_ok ? "takes" : "refuses",
                 kind->offset_length);
    }
  }
  assert_ptr_equal(fb_report_kinematics_kind(FB_MECH_COUNT),
                   fb_report_kinematics_kind(fb_mech_find("four-bar")));
  /* without a kind the run says so, not a crash */
  static fb_kinematics k;
  memset(&k, 0, sizeof k);
  fb_diag d;
  assert_int_equal(fb_kinematics_run(&k, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "no kind"));
}

static void test_fourbar_through_its_kind(void **state) {
  (void)state;
  static const double mm[4] = {108, 279.4, 270.5, 254}; /* the paper's */
  static fb_kinematics k;
  setup(&k, (fb_mech_type)fb_mech_find("four-bar"), mm, 4, 1000, -1);
  fb_diag d;
  assert_int_equal(fb_kinematics_run(&k, &d), FB_OK);
  const double a = 0.108, b = 0.2794, c = 0.2705, g = 0.254;
  assert_int_equal(k.g, FB_GRASHOF_CRANK_ROCKER);
  assert_near(k.sl, a + b, LENGTH_TOL_M);
  assert_near(k.pq, c + g, LENGTH_TOL_M);
  assert_near(k.mu_min, acos((b * b + c * c - (g - a) * (g - a)) / (2 * b * c)), ANGLE_TOL_RAD);
  assert_near(k.mu_max, acos((b * b + c * c - (g + a) * (g + a)) / (2 * b * c)), ANGLE_TOL_RAD);
  const double w = 1000 * FB_RAD_S_PER_RPM;
  assert_near(-k.p.body[0].alpha_min / (w * w), 1.091571, PAPER_RATIO_TOL);
  assert_true(text_has_class_line(&k));
  json_t *o = json_object();
  k.kind->json(o, &k);
  assert_string_equal(json_string_value(json_object_get(o, "grashof")), "crank-rocker");
  json_decref(o);
}

static void test_slider_crank_through_its_kind(void **state) {
  (void)state;
  static const double mm[3] = {50, 120, 0};
  static fb_kinematics k;
  setup(&k, (fb_mech_type)fb_mech_find("slider-crank"), mm, 3, 3000, +1);
  fb_diag d;
  assert_int_equal(fb_kinematics_run(&k, &d), FB_OK);
  const double a = 0.05, b = 0.12, w = 3000 * FB_RAD_S_PER_RPM;
  assert_near(k.lim.stroke, 2 * a, LENGTH_TOL_M);
  assert_near(k.lim.x_max, b + a, LENGTH_TOL_M);
  assert_near(k.lim.x_min, b - a, LENGTH_TOL_M);
  assert_near(k.quick_return, 1.0, ANGLE_TOL_RAD);
  assert_near(k.outstroke_angle, M_PI, ANGLE_TOL_RAD);
  assert_near(k.outstroke_time, M_PI / w, ANGLE_TOL_RAD / w);
  assert_near(k.mu_max, 0.5 * M_PI, ANGLE_TOL_RAD);
  assert_near(k.mu_min, acos(a / b), ANGLE_TOL_RAD);
  /* the slider's acceleration, x'' = -a w^2 (cos t + l cos 2t / (1 - l^2 sin^2 t)^(1/2) +
   * l^3 sin^2 2t / (4 (1 - l^2 sin^2 t)^(3/2))), l = a / b: scanned for its minimum */
  const double l = a / b;
  double least = 0.0;
  for (int i = 0; i < 100000; i++) {
    const double t = 2 * M_PI * i / 100000, s = 1 - l * l * sin(t) * sin(t);
    const double xdd = -a * w * w * (cos(t) + l * cos(2 * t) / sqrt(s) +
                                     l * l * l * sin(2 * t) * sin(2 * t) / (4 * s * sqrt(s)));
    least = fmin(least, xdd);
  }
  assert_near(least, -a * w * w * (1 + l), PEAK_REL_TOL * a * w * w);
  assert_near(k.p.body[1].alpha_min, -a * w * w * (1 + l), PEAK_REL_TOL * a * w * w);
  assert_true(text_has_class_line(&k));
  json_t *o = json_object();
  k.kind->json(o, &k);
  assert_near(json_real_value(json_object_get(o, "stroke_m")), 2 * a, LENGTH_TOL_M);
  json_decref(o);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_every_type_has_a_kind),
      cmocka_unit_test(test_fourbar_through_its_kind),
      cmocka_unit_test(test_slider_crank_through_its_kind),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
