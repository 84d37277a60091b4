/* The closed forms' tables (closed_form.h): one per mechanism type, found
 * from the type and from the description alike, every entry a caller needs
 * present, and the entries of one table consistent with each other on the
 * shipped cases (paper_crank_rocker.ini, slider_crank_flores.ini):
 *
 *   reactions(theta2_k) for k = 0 .. n-1  --max |F_j|-->  reaction_peaks
 *   start_steady(theta0)                  ==  solve(theta0) (q, q')
 *   tol_outputs slots 0..7                ==  peaks (omega, alpha extremes)
 *
 * The physics behind each entry has its own tests (test_linkage.c,
 * test_slider_crank.c, test_invdyn.c, test_tolerance.c, test_start ...);
 * these catch a table that wires an entry to the wrong function or drops
 * one (a third mechanism's table with a NULL entry fails here, not with a
 * crash in a run). */
#include <math.h>
#include <string.h>

#include "casefile.h"
#include "closed_form.h"
#include "fb_test.h"

/* two entries computing the same quantity through the same arithmetic
 * (the peak search evaluates the inverse dynamics at the same crank
 * angles; the start state copies the solve): rounding only */
#define SAME_ARITHMETIC_REL_TOL 1e-12
/* crank angles of the reaction peak search: 1 deg */
#define REACTION_SAMPLES 360

static const char *const shipped[FB_MECH_COUNT] = {"paper_crank_rocker.ini",
                                                   "slider_crank_flores.ini"};

/* the shipped case of type t into *c; its table, and its signed crank
 * speed [rad/s] into *w */
static const fb_closed_form *load(fb_case *c, int t, double *w) {
  fb_diag diag;
  if (fb_test_shipped_case(c, shipped[t], NULL, 0, &diag) != FB_OK) fail_msg("%s", diag.msg);
  assert_int_equal(c->mechanism, t);
  *w = fb_case_omega2(c);
  return fb_closed_form_of((fb_mech_type)t);
}

/* every type has its own table, the description finds the same one, and
 * what has no closed form (NULL, a planar case's description, a type out
 * of range) gets the four-bar's */
static void test_map(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_closed_form *cf = fb_closed_form_of((fb_mech_type)t);
    assert_non_null(cf);
    assert_ptr_equal(fb_closed_form_of_desc(fb_mech_of((fb_mech_type)t)), cf);
    for (int u = 0; u < t; u++) assert_ptr_not_equal(fb_closed_form_of((fb_mech_type)u), cf);
  }
  assert_ptr_equal(fb_closed_form_of(FB_MECH_FOURBAR), &fb_closed_form_fourbar);
  assert_ptr_equal(fb_closed_form_of(FB_MECH_SLIDER_CRANK), &fb_closed_form_slider_crank);
  assert_ptr_equal(fb_closed_form_of_desc(NULL), &fb_closed_form_fourbar);
  assert_ptr_equal(fb_closed_form_of((fb_mech_type)FB_MECH_COUNT), &fb_closed_form_fourbar);
  const fb_mech_desc planar = {.type = "planar"};
  assert_ptr_equal(fb_closed_form_of_desc(&planar), &fb_closed_form_fourbar);
}

/* the entries every caller reaches without a NULL test are there, the
 * outputs' names carry a unit, and the data is in range */
static void test_complete(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_closed_form *cf = fb_closed_form_of((fb_mech_type)t);
    const int present[] = {
        cf->solve != NULL,         cf->check_lengths != NULL, cf->peaks_where != NULL,
        cf->reactions != NULL,     cf->reaction_peaks != NULL,
        cf->mechanism_at != NULL,  cf->start_steady != NULL,  cf->start_resolve != NULL,
        cf->tol_names != NULL,     cf->tol_outputs != NULL,   cf->tol_sensitivities != NULL,
        cf->planar != NULL,        cf->class_text != NULL,    cf->check_case != NULL};
    for (size_t k = 0; k < sizeof present / sizeof present[0]; k++)
      if (!present[k]) fail_msg("%s: required entry %zu is NULL", fb_mech_of(t)->type, k);
    for (int i = 0; i < FB_TOL_NOUT; i++)
      if (!cf->tol_names[i] || !*fb_tol_output_unit_of((fb_mech_type)t, i))
        fail_msg("%s: tolerance output %d has no name with a unit", fb_mech_of(t)->type, i);
    assert_in_range(cf->tolerances_checked, 0, fb_mech_of(t)->nlengths);
    /* the reference integrates the ideal mechanism only through the
     * four-bar's own coordinates */
    assert_false(cf->ideal_reference && cf->reference_model);
  }
}

/* the largest |reaction| of the peak search is the largest over the same
 * crank angles of the reactions, joint by joint (a prismatic guide's
 * (0, -N) row as |N|) */
static void test_reactions_against_peaks(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    fb_case c;
    double w;
    const fb_closed_form *cf = load(&c, t, &w);
    double peak[4] = {0}, most[4] = {0};
    assert_int_equal(cf->reaction_peaks(peak, &c.nominal, c.branch, c.link, c.gravity, w,
                                        REACTION_SAMPLES, NULL),
                     FB_OK);
    for (int k = 0; k < REACTION_SAMPLES; k++) {
      double f[4][2] = {{0}}, tau = NAN;
      assert_int_equal(cf->reactions(f, &tau, &c.nominal, c.branch, c.link, c.gravity,
                                     2.0 * M_PI * k / REACTION_SAMPLES, w, NULL),
                       FB_OK);
      assert_true(isfinite(tau));
      for (int j = 0; j < fb_mech_of(t)->njoints; j++) most[j] = fmax(most[j], hypot(f[j][0], f[j][1]));
    }
    for (int j = 0; j < fb_mech_of(t)->njoints; j++) {
      report_residual(fb_mech_joint_name(fb_mech_of(t), j), fabs(most[j] - peak[j]) / peak[j],
                      SAME_ARITHMETIC_REL_TOL);
      assert_rel(most[j], peak[j], SAME_ARITHMETIC_REL_TOL);
    }
  }
}

/* the steady start is the exact solution at the start angle */
static void test_start_against_solve(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    fb_case c;
    double w;
    const fb_closed_form *cf = load(&c, t, &w);
    fb_start_state s;
    double q[FB_MECH_MAX_OUTPUTS][3];
    assert_int_equal(cf->start_steady(&s, &c.nominal, c.branch, c.crank_angle0, w, NULL), FB_OK);
    assert_int_equal(cf->solve(q, &c.nominal, c.branch, c.crank_angle0, w, 0.0, NULL), FB_OK);
    assert_near(s.crank_angle, c.crank_angle0, 0.0);
    for (int b = 0; b < FB_MECH_MAX_OUTPUTS; b++)
      for (int k = FB_Q_POS; k <= FB_Q_VEL; k++)
        assert_near(s.body[b][k], q[b][k], SAME_ARITHMETIC_REL_TOL * fmax(1.0, fabs(q[b][k])));
  }
}

/* the stack-up's first eight outputs are the peaks' extremes */
static void test_tolerance_outputs_against_peaks(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    fb_case c;
    double w;
    const fb_closed_form *cf = load(&c, t, &w);
    fb_peaks p;
    double o[FB_TOL_NOUT];
    assert_int_equal(cf->peaks_where(&p, NULL, &c.nominal, c.branch, w, NULL), FB_OK);
    assert_int_equal(cf->tol_outputs(o, &c.nominal, c.branch, w, NULL), FB_OK);
    for (int b = 0; b < FB_MECH_MAX_OUTPUTS; b++) {
      const double v[4] = {p.body[b].omega_max, p.body[b].omega_min, p.body[b].alpha_max,
                           p.body[b].alpha_min};
      for (int i = 0; i < 4; i++) assert_near(o[4 * b + i], v[i], 0.0);
    }
  }
}

/* lengths that make no mechanism are refused by the table's own check */
static void test_check_lengths(void **state) {
  (void)state;
  fb_diag diag;
  const fb_linkage no_fourbar = {{0.1, -0.28, 0.27, 0.25}}; /* a length must be positive */
  assert_int_not_equal(fb_closed_form_of(FB_MECH_FOURBAR)->check_lengths(&no_fourbar, &diag), FB_OK);
  const fb_linkage short_rod = {{0.05, 0.04, 0.0, 0.0}}; /* coupler < crank + |offset| */
  assert_int_not_equal(fb_closed_form_of(FB_MECH_SLIDER_CRANK)->check_lengths(&short_rod, &diag),
                       FB_OK);
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    fb_case c;
    double w;
    assert_int_equal(load(&c, t, &w)->check_lengths(&c.nominal, &diag), FB_OK);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_map),
      cmocka_unit_test(test_complete),
      cmocka_unit_test(test_reactions_against_peaks),
      cmocka_unit_test(test_start_against_solve),
      cmocka_unit_test(test_tolerance_outputs_against_peaks),
      cmocka_unit_test(test_check_lengths),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
