/* The planar core's clearance right-hand side in absolute coordinates
 * (planar_dynamics.h: the cross-check of the reference's relative form,
 * tests/test_planar_relative.c) against the closed-form references: the four-bar's crank-coupler joint (reference.c, minimal
 * coordinates by Kane's method) and the slider-crank's piston pin
 * (slider_crank_dynamics.h). The same state gives the same accelerations
 * and contact force.
 *
 *            C                       the pin on the crank (body[0] of
 *           / \                      crank-coupler) moves in the hole at
 *  coupler /   \ follower            the coupler's B end; e = pin - hole,
 *      B(o)     \                    delta = |e| - c
 *  crank /       \
 *       A ------- D
 *
 * The four-bar's reference states are read from fb_reference_run's own
 * series (t, theta3, theta4, omega3, omega4 and its alpha3, alpha4 and
 * force at that state), so no part of reference.c is reached into; the
 * samples the reference refines at spikes (they hold an extreme from
 * between samples, not the sample's value) are left out: every local
 * extreme of a series and its neighbours. */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "linkage.h"
#include "planar_case.h"
#include "planar_dynamics.h"
#include "reference.h"
#include "slider_crank_dynamics.h"

/* Same state, same accelerations: both solve the equations of motion in
 * double precision, reference.c a 2 x 2 system in minimal coordinates,
 * the core a Schur complement of 7 rows in absolute ones (condition ~1e4);
 * the contact law's force is the same function of the same penetration,
 * which the two compute from coordinates of 0.1 to 0.3 m, each rounded to
 * ~1e-17 m: an absolute error of the force of K n delta^(n-1) 1e-17 m,
 * which is relative to the run's largest force, not to a grazing
 * contact's (at delta = 1e-12 m a relative 1e-5). So each quantity's
 * largest difference is divided by its largest magnitude over the run:
 * 1e-9 holds (measured ~1e-11 to 1e-12, FB_TEST_VERBOSE). */
#define RHS_REL_TOL 1e-9
static fb_case paper(const char **sets, int n) {
  fb_case c;
  fb_test_paper_case(&c, sets, n);
  return c;
}

/* the largest difference and the largest magnitude of one quantity */
typedef struct {
  double diff, big;
} spread;

static void spread_add(spread *s, double got, double want) {
  s->diff = fmax(s->diff, fabs(got - want));
  s->big = fmax(s->big, fabs(want));
}

static double spread_rel(const spread *s) { return s->big > 0.0 ? s->diff / s->big : s->diff; }

/* the four-bar's minimal state (theta3, theta4, omega3, omega4 at crank
 * angle theta2, speed w2) as the core's y (18): centres of mass at their
 * fractions, B's hole hanging from C (reference.h) */
static void fourbar_state(double y[18], const fb_linkage *lk, const fb_link_mass link[3],
                          double th2, double w2, double th3, double th4, double w3, double w4) {
  const double a = lk->length[FB_CRANK], b = lk->length[FB_COUPLER], cf = lk->length[FB_FOLLOWER];
  const double g = lk->length[FB_GROUND];
  const double e2[2] = {cos(th2), sin(th2)}, e3[2] = {cos(th3), sin(th3)}, e4[2] = {cos(th4), sin(th4)};
  const double p2[2] = {-e2[1], e2[0]}, p3[2] = {-e3[1], e3[0]}, p4[2] = {-e4[1], e4[0]};
  const double f2 = link[0].com_fraction, f3 = link[1].com_fraction, f4 = link[2].com_fraction;
  const double cpt[2] = {g + cf * e4[0], cf * e4[1]}, cv[2] = {cf * w4 * p4[0], cf * w4 * p4[1]};
  const double bh[2] = {cpt[0] - b * e3[0], cpt[1] - b * e3[1]};
  const double bv[2] = {cv[0] - b * w3 * p3[0], cv[1] - b * w3 * p3[1]};
  const double q[9] = {f2 * a * e2[0], f2 * a * e2[1], th2,
                       bh[0] + f3 * b * e3[0], bh[1] + f3 * b * e3[1], th3,
                       g + f4 * cf * e4[0], f4 * cf * e4[1], th4};
  const double qd[9] = {f2 * a * w2 * p2[0], f2 * a * w2 * p2[1], w2,
                        bv[0] + f3 * b * w3 * p3[0], bv[1] + f3 * b * w3 * p3[1], w3,
                        f4 * cf * w4 * p4[0], f4 * cf * w4 * p4[1], w4};
  memcpy(y, q, sizeof q);
  memcpy(y + 9, qd, sizeof qd);
}

/* 1 when sample k is a local extreme of v, or next to one (a flat run,
 * such as the zero force of free flight, is none: the reference refines
 * no sample below a fifth of the largest) */
static int near_extreme(const double *v, size_t k, size_t n) {
  for (size_t i = k > 1 ? k - 1 : 1; i <= k + 1 && i + 1 < n; i++) {
    const int flat = v[i] == v[i - 1] && v[i] == v[i + 1];
    if (!flat && ((v[i] >= v[i - 1] && v[i] >= v[i + 1]) || (v[i] <= v[i - 1] && v[i] <= v[i + 1])))
      return 1;
  }
  return 0;
}

static fb_contact_law law_of(fb_law_kind kind) {
  fb_contact_law l = fb_contact_law_default();
  l.kind = kind;
  if (kind == FB_LAW_IMPACT) {
    l.stiffness = 5e10;
    l.exponent = 1.5;
    l.damping = 1e4;
    l.damping_depth = 1e-6;
  } else {
    l.stiffness = 1e9;
    l.exponent = 1.0;
    l.restitution = 0.9;
  }
  assert_int_equal(fb_contact_law_prepare(&l, NULL), FB_OK);
  return l;
}

/* the core's model of case c (stack-up lengths, clearance at crank-coupler) */
typedef struct {
  fb_planar *m;
  unsigned char clear[4];
  fb_planar_dyn *dyn;
  fb_linkage lk;
} fourbar_core;

static void fourbar_core_new(fourbar_core *fc, const fb_case *c, const fb_contact_law *law) {
  fb_diag d;
  fb_case_stackup_lengths(c, &fc->lk);
  assert_int_equal(fb_planar_of_case(&fc->m, c, &fc->lk, &d), FB_OK);
  memset(fc->clear, 0, sizeof fc->clear);
  fc->clear[FB_JOINT_B] = 1;
  const fb_planar_dyn_model model = {fc->m, fc->clear, *law, c->radial_clearance, 1e-3,
                                     c->gravity, fb_case_omega2(c), NULL, NULL, NULL};
  if (fb_planar_dyn_new(&fc->dyn, &model, &d) != FB_OK) fail_msg("%s", d.msg);
}

static void fourbar_core_free(fourbar_core *fc) {
  fb_planar_dyn_free(fc->dyn);
  fb_planar_free(fc->m);
}

static void rhs_against_reference(fb_law_kind kind) {
  const char *sets[] = {"run.revolutions=1", "run.peaks=all", "solver.h_s=1e-5"};
  const fb_case c = paper(sets, 3);
  const fb_contact_law law = law_of(kind);
  fb_series s;
  size_t steps;
  fb_diag d;
  if (fb_reference_run(&s, &steps, &c, &law, 0, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  fourbar_core fc;
  fourbar_core_new(&fc, &c, &law);
  const double w2 = fb_case_omega2(&c);
  spread alpha = {0, 0}, force = {0, 0};
  size_t compared = 0, in_contact = 0;
  double *f = s.contact[FB_JOINT_B][FB_C_FORCE], *pen = s.contact[FB_JOINT_B][FB_C_PEN];
  for (size_t k = 1; k + 1 < s.n; k++) {
    if (near_extreme(s.coupler_alpha, k, s.n) || near_extreme(s.follower_alpha, k, s.n) ||
        near_extreme(f, k, s.n) || near_extreme(pen, k, s.n))
      continue;
    double y[18], dy[18];
    fourbar_state(y, &fc.lk, c.link, c.crank_angle0 + w2 * s.t[k], w2, s.coupler_angle[k],
                  s.follower_angle[k], s.coupler_omega[k], s.follower_omega[k]);
    fb_planar_contact ct[4];
    assert_int_equal(fb_planar_dyn_eval(fc.dyn, s.t[k], y, dy, ct), FB_OK);
    spread_add(&alpha, dy[9 + 5], s.coupler_alpha[k]);
    spread_add(&alpha, dy[9 + 8], s.follower_alpha[k]);
    spread_add(&force, ct[FB_JOINT_B].force, f[k]);
    compared++;
    in_contact += f[k] > 0.0;
  }
  if (fb_test_verbose())
    fprintf(stderr, "  %s: %zu samples compared, %zu in contact\n", fb_law_name(kind), compared,
            in_contact);
  report_residual("core vs reference.c: alpha (rel)", spread_rel(&alpha), RHS_REL_TOL);
  report_residual("core vs reference.c: contact force (rel)", spread_rel(&force), RHS_REL_TOL);
  /* the comparison saw contact, and most of the run */
  assert_true(in_contact > 50);
  assert_true(compared > s.n / 2);
  assert_true(spread_rel(&alpha) <= RHS_REL_TOL);
  assert_true(spread_rel(&force) <= RHS_REL_TOL);
  fourbar_core_free(&fc);
  fb_series_free(&s);
}

static void test_fourbar_rhs_impact(void **state) {
  (void)state;
  rhs_against_reference(FB_LAW_IMPACT);
}

/* the restitution law's damper sits on the effective mass along n: the
 * core's (planar_mass.h) against reference.c's minimal-coordinate one */
static void test_fourbar_rhs_restitution(void **state) {
  (void)state;
  rhs_against_reference(FB_LAW_RESTITUTION);
}

/* the slider-crank's piston pin: the core against fb_sc_dyn_eval_at at the
 * states of an integration of slider_crank_dynamics.h */
static void test_slider_crank_rhs(void **state) {
  (void)state;
  fb_sc_dyn_model sm;
  memset(&sm, 0, sizeof sm);
  sm.geometry = (fb_slider_crank){0.05, 0.2, 0.01};
  sm.mass = (fb_slider_crank_mass){0.2, 1e-4, 0.5, 0.4, 2e-3, 0.4, 0.6};
  sm.gravity = 9.81;
  sm.clearance = 20e-6;
  sm.law = law_of(FB_LAW_RESTITUTION);
  sm.impact_velocity = 1e-3;
  sm.theta0 = 0.3;
  sm.omega2 = 150.0;
  double y0[4];
  const double ecc0[2] = {0.0, 0.0};
  assert_int_equal(fb_sc_dyn_start(y0, &sm, ecc0, NULL), FB_OK);
  enum { N = 600 };
  static fb_sc_dyn_sample smp[N];
  fb_diag d;
  if (fb_sc_dyn_run(smp, N, 2e-5, y0, &sm, 1e-11, 0, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  /* the same slider-crank as a description */
  fb_link_mass link[3];
  memset(link, 0, sizeof link);
  link[0] = (fb_link_mass){sm.mass.crank_mass, sm.mass.crank_inertia, 0, 0, sm.mass.crank_com_fraction};
  link[1] = (fb_link_mass){sm.mass.coupler_mass, sm.mass.coupler_inertia, 0, 0,
                           sm.mass.coupler_com_fraction};
  link[2] = (fb_link_mass){sm.mass.slider_mass, 1e-5, 0, 0, 0};
  const fb_linkage lk = {{sm.geometry.crank, sm.geometry.coupler, sm.geometry.offset, 0}};
  fb_planar *m;
  assert_int_equal(fb_planar_slider_crank(&m, &lk, link, sm.theta0, &d), FB_OK);
  unsigned char clear[4] = {0, 0, 1, 0};
  const fb_planar_dyn_model model = {m, clear, sm.law, sm.clearance, sm.impact_velocity,
                                     sm.gravity, sm.omega2, NULL, NULL, NULL};
  fb_planar_dyn *dyn;
  assert_int_equal(fb_planar_dyn_new(&dyn, &model, &d), FB_OK);
  const double a = lk.length[0], b = lk.length[1], f3 = link[1].com_fraction;
  spread rod = {0, 0}, slider = {0, 0}, force = {0, 0};
  int contact = 0;
  for (int k = 0; k < N; k++) {
    const fb_sc_dyn_sample *x = &smp[k];
    const double t2 = x->crank_angle, t3 = x->coupler_angle, w3 = x->coupler_omega, w2 = sm.omega2;
    const double u2[2] = {cos(t2), sin(t2)}, u3[2] = {cos(t3), sin(t3)};
    const double y[18] = {0.5 * a * u2[0], 0.5 * a * u2[1], t2,
                          a * u2[0] + f3 * b * u3[0], a * u2[1] + f3 * b * u3[1], t3,
                          x->slider_x, lk.length[2], 0.0,
                          -0.5 * a * w2 * u2[1], 0.5 * a * w2 * u2[0], w2,
                          -a * w2 * u2[1] - f3 * b * w3 * u3[1], a * w2 * u2[0] + f3 * b * w3 * u3[0], w3,
                          x->slider_v, 0.0, 0.0};
    double dy[18];
    fb_planar_contact ct[4];
    assert_int_equal(fb_planar_dyn_eval(dyn, x->t, y, dy, ct), FB_OK);
    const double yy[4] = {t3, x->slider_x, w3, x->slider_v};
    fb_sc_dyn_eval ev;
    fb_sc_dyn_eval_at(&ev, &sm, x->t, yy);
    spread_add(&rod, dy[9 + 5], ev.dydt[2]);
    spread_add(&slider, dy[9 + 6], ev.dydt[3]);
    spread_add(&force, ct[2].force, ev.force);
    contact += ev.force > 0.0;
  }
  const double worst = fmax(spread_rel(&rod), fmax(spread_rel(&slider), spread_rel(&force)));
  report_residual("core vs slider_crank_dynamics.h (rel)", worst, RHS_REL_TOL);
  assert_true(contact > 20);
  assert_true(worst <= RHS_REL_TOL);
  fb_planar_dyn_free(dyn);
  fb_planar_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_fourbar_rhs_impact),
      cmocka_unit_test(test_fourbar_rhs_restitution),
      cmocka_unit_test(test_slider_crank_rhs),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
