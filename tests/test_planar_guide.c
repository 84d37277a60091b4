/* A slider in its guide with clearance (planar_guide.h), the corners'
 * Delassus matrix (planar_mass.h) and the free start (planar_start.h), on
 * the slider-crank of Siconos's example (cases/slider_guide_flores_leine_
 * glocker.ini: crank 153 mm, rod 306 mm, slider 2a x 2b = 100 x 50 mm, c =
 * 1 mm), the guide's joint out of the set:
 *
 *        wall y = +(b + c) ______________________
 *     A o--crank--o B ---------rod--------- 1 +-----+ 2
 *                                              |  P  |      slider, tilt t
 *                                            3 +-----+ 4
 *        wall y = -(b + c) ----------------------
 *
 * Oracles in closed form: a corner's gap from the slider's offset y and
 * tilt t, (b + c) - tau (y + sigma a sin t + tau b cos t); the linear law's
 * force k delta + c delta'; the free start's velocities at the dead centre
 * (the slider still: l1 150 = l2 75); the Delassus matrix against the
 * midpoint identity D_cc + D_c'c' + 2 D_cc' = 4 m_mid^-1 (a rigid body's
 * point velocities are affine in the point, so two corners' rows sum to
 * twice the face midpoint's: fb_planar_cmass_tensor_points, an independent
 * path through the same Schur complement). */
#include <math.h>
#include <string.h>

#include "fb_test.h"
#include "planar_guide.h"
#include "planar_start.h"

/* geometry of rotations and sums of a few terms of O(0.1 m): rounding */
#define GAP_TOL_M 1e-15
/* a force k delta with k = 1e8 N/m, delta ~ 1e-5 m: 1e3 N, rounding */
#define FORCE_TOL_N 1e-9
/* velocities from a 6 x 6 least squares of O(1) entries: rounding */
#define START_TOL 1e-12
/* Schur complements of a 9-coordinate set, entries ~1e1 to 1e3 1/kg */
#define DELASSUS_REL_TOL 1e-10

enum { GUIDE = 3 };

static fb_planar *example(void) {
  fb_diag d;
  fb_planar *m = fb_planar_new(3, 4);
  const double c1[2] = {0.0765, 0}, c2[2] = {0.306, 0}, c3[2] = {0.459, 0};
  const double a[2] = {0, 0}, b[2] = {0.153, 0}, p[2] = {0.459, 0};
  assert_int_equal(fb_planar_add_body(m, "crank", 0.038, 7.4e-5, c1, 0.0, 0, &d), 1);
  assert_int_equal(fb_planar_add_body(m, "rod", 0.038, 5.9e-4, c2, 0.0, 0, &d), 2);
  assert_int_equal(fb_planar_add_body(m, "slider", 0.076, 2.7e-6, c3, 0.0, 0, &d), 3);
  assert_int_equal(fb_planar_add_joint(m, "ground-crank", FB_KIND_REVOLUTE, 0, 1, a, 0, &d), 0);
  assert_int_equal(fb_planar_add_joint(m, "crank-rod", FB_KIND_REVOLUTE, 1, 2, b, 0, &d), 1);
  assert_int_equal(fb_planar_add_joint(m, "rod-slider", FB_KIND_REVOLUTE, 2, 3, p, 0, &d), 2);
  assert_int_equal(fb_planar_add_joint(m, "guide", FB_KIND_PRISMATIC, 0, 3, p, 0.0, &d), 3);
  return m;
}

static const fb_planar_guide G = {0.05, 0.025, 0.001};
static const unsigned char OFF[4] = {0, 0, 0, 1};

/* the slider moved to offset y and tilt t (the rest at the assembly) */
static void place(double *q, const fb_planar *m, double y, double t) {
  fb_planar_assembly(m, q);
  q[7] = y;
  q[8] = t;
}

static void test_gaps_and_forces(void **state) {
  (void)state;
  fb_planar *m = example();
  fb_planar_cmass *cm;
  assert_int_equal(fb_planar_cmass_new(&cm, m, OFF, NULL), FB_OK);
  fb_contact_law law = fb_contact_law_default();
  law.kind = FB_LAW_LINEAR;
  law.stiffness = 1e8;
  law.exponent = 1.0;
  law.damping = 50.0;
  const double cases[][3] = {{0.0, 0.0, 0.0}, {0.00102, 0.0, 0.0}, {-0.00105, 0.0, 0.0},
                             {0.0, 0.03, 0.2}, {0.0002, -0.05, -0.3}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    double q[9], qd[9] = {0}, f[9] = {0};
    const double y = cases[k][0], t = cases[k][1], vy = cases[k][2];
    place(q, m, y, t);
    qd[7] = vy;
    fb_planar_guide_state st;
    fb_planar_guide_contact(f, &st, cm, m, GUIDE, &G, &law, 1e-3, q, qd);
    double fy = 0.0;
    for (int c = 0; c < 4; c++) {
      const double sigma = c % 2 ? 1.0 : -1.0, tau = c < 2 ? 1.0 : -1.0;
      const double yc = y + sigma * G.half_length * sin(t) + tau * G.half_height * cos(t);
      const double gap = G.half_height + G.clearance - tau * yc;
      assert_near(st.gap[c], gap, GAP_TOL_M);
      assert_near(st.rate[c], tau * vy, GAP_TOL_M);
      const double want = gap < 0.0 ? fmax(0.0, 1e8 * -gap + 50.0 * tau * vy) : 0.0;
      assert_near(st.force[c], want, FORCE_TOL_N);
      fy -= tau * want;
    }
    assert_near(st.tilt, t, GAP_TOL_M);
    /* the walls' forces on the slider, its y row of the generalised forces */
    assert_near(f[7], fy, FORCE_TOL_N);
  }
  fb_planar_cmass_free(cm);
  fb_planar_free(m);
}

static void test_delassus_midpoint(void **state) {
  (void)state;
  fb_planar *m = example();
  fb_planar_cmass *cm;
  assert_int_equal(fb_planar_cmass_new(&cm, m, OFF, NULL), FB_OK);
  double q[9];
  place(q, m, 0.0004, 0.02);
  q[2] = 0.3; /* the crank off its dead centre, the rod along */
  assert_int_equal(fb_planar_cmass_factor(cm, q, 0.0, NULL), FB_OK);
  /* the upper face's corners 1 and 2 in the slider's frame, their ground points */
  const double s[2][2] = {{-0.05, 0.025}, {0.05, 0.025}}, mid[2] = {0.0, 0.025};
  double sg[2][2], pm[2];
  for (int c = 0; c < 2; c++) fb_planar_point(sg[c], m, q, 3, s[c]);
  fb_planar_point(pm, m, q, 3, mid);
  const double n[2][2] = {{0.0, 1.0}, {0.0, 1.0}};
  const int b0[2] = {3, 3}, b1[2] = {0, 0};
  double dl[4], w[2][2];
  fb_planar_cmass_delassus(cm, dl, 2, b0, s, b1, (const double(*)[2])sg, n, q);
  fb_planar_cmass_tensor_points(cm, w, 3, mid, 0, pm, q);
  const double lhs = dl[0] + dl[3] + 2.0 * dl[1], rhs = 4.0 * w[1][1];
  assert_near(lhs, rhs, DELASSUS_REL_TOL * fabs(rhs));
  assert_near(dl[1], dl[2], DELASSUS_REL_TOL * fabs(dl[0]));
  fb_planar_cmass_free(cm);
  fb_planar_free(m);
}

static void test_free_start(void **state) {
  (void)state;
  fb_planar *m = example();
  double y0[18], w[4] = {0.0, 150.0, -75.0, 0.0};
  fb_diag d;
  assert_int_equal(fb_planar_free_start(y0, m, OFF, w, &d), FB_OK);
  const double *v = y0 + 9;
  /* crank's centre: 76.5 mm x 150 rad/s up; rod's: B's 153 x 150 less 153 x 75 */
  const double want[9] = {0, 0.0765 * 150.0, 150.0, 0, 0.153 * 150.0 - 0.153 * 75.0, -75.0,
                          0, 0, 0};
  for (int i = 0; i < 9; i++) assert_near(v[i], want[i], START_TOL);
  /* the guide held (not a clearance joint): a slider's rate it forbids */
  w[3] = 5.0;
  assert_int_equal(fb_planar_free_start(y0, m, NULL, w, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "'guide'"));
  fb_planar_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_gaps_and_forces),
      cmocka_unit_test(test_delassus_midpoint),
      cmocka_unit_test(test_free_start),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
