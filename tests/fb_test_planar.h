/* Test helpers of the planar core's tests: the paper's four-bar and a
 * slider-crank as descriptions with their kinematics' workspace; each
 * fails the test on an error. Include after fb_test.h and casefile.h. */
#ifndef FB_TEST_PLANAR_H
#define FB_TEST_PLANAR_H

#include "planar_case.h"
#include "planar_kinematics.h"

/* The description and kinematics of m, made by the caller's builder. */
typedef struct {
  fb_planar *m;
  fb_planar_kin *k;
} fb_test_planar;

static inline fb_test_planar fb_test_planar_kin(fb_planar *m) {
  fb_test_planar t = {m, NULL};
  fb_diag d;
  if (fb_planar_kin_new(&t.k, m, &d) != FB_OK) fail_msg("%s", d.msg);
  return t;
}

/* the paper case's four-bar (its lengths, branch, masses) at its crank angle */
static inline fb_test_planar fb_test_planar_paper(const fb_case *c, const fb_linkage *lk) {
  fb_planar *m;
  fb_diag d;
  if (fb_planar_fourbar(&m, lk, c->branch, c->link, c->crank_angle0, &d) != FB_OK)
    fail_msg("%s", d.msg);
  return fb_test_planar_kin(m);
}

/* a slider-crank of lengths lk (crank, coupler, offset) at crank angle
 * theta0, the paper's crank and coupler masses and a slider of mass
 * slider_kg [kg] and moment slider_kg_m2 [kg m^2] */
static inline fb_test_planar fb_test_planar_slider(fb_case *c, const fb_linkage *lk,
                                                   double slider_kg, double slider_kg_m2,
                                                   double theta0) {
  c->link[2] = (fb_link_mass){slider_kg, slider_kg_m2, 0, 0, 0};
  fb_planar *m;
  fb_diag d;
  if (fb_planar_slider_crank(&m, lk, c->link, theta0, &d) != FB_OK) fail_msg("%s", d.msg);
  return fb_test_planar_kin(m);
}

/* the shipped six-bar, cases/watt_sixbar.ini, loaded into *c */
static inline fb_test_planar fb_test_planar_sixbar(fb_case *c) {
  fb_diag d;
  if (fb_test_shipped_case_planar(c, "watt_sixbar.ini", &d) != FB_OK) fail_msg("%s", d.msg);
  fb_planar *m;
  if (fb_planar_of_case(&m, c, &c->nominal, &d) != FB_OK) fail_msg("%s", d.msg);
  return fb_test_planar_kin(m);
}

static inline void fb_test_planar_free(fb_test_planar *t) {
  fb_planar_kin_free(t->k);
  fb_planar_free(t->m);
}

#endif
