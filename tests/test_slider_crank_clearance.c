/* The slider-crank's clearance piston pin through the engine-free layers of
 * a run: its start state, the effective mass the mappings divide by, its
 * contact laws and automatic step, and the reference model that integrates
 * it, each against an oracle computed here or by an independent route.
 *
 *                  B
 *                 / \          A = (0, 0), B = crank u(theta2)
 *          crank /   \ coupler P = B + coupler u(theta3): the rod's pin
 *               /     \        H = (x, offset): the slider's hole
 *              A      (P)H - - guide y = offset - - -> x
 *
 *   e = P - H, |e| <= c in free flight (radial clearance c)
 *
 * Oracles: the start's geometry from its definition (loop closure, the hole
 * on the guide, the eccentricity of pin_start); the effective mass of the
 * piston pin three ways (the closed form, the general KKT form of
 * effective_mass.h with the guide's prismatic rows, and the minimal
 * coordinates of slider_crank_dynamics.h, each derived separately); the
 * reference model against the slider-crank dynamics integrated on their own
 * (fb_sc_dyn_rhs), which tests/test_slider_crank.c checks against a second
 * formulation in absolute coordinates. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "effective_mass.h"
#include "fb_test.h"
#include "joint_law.h"
#include "mech_kinematics.h"
#include "reference.h"
#include "resolution.h"
#include "slider_crank_dynamics.h"
#include "start.h"

/* ---- tolerances ----------------------------------------------------------- */

/* lengths ~0.1 m through a handful of roundings: a loop closed to a few ulp */
#define LOOP_TOL_M 1e-15
/* the start's eccentricity against pin_start's: c ~1e-4 m times the rounding
 * of cos/sin and a subtraction of two ~0.1 m coordinates: 1e-16 m, ~1e-12 of c */
#define ECC_REL_TOL 1e-9
/* two exact formulas of the same 2 x 2 tensor: the closed form (a few flops)
 * against the KKT form's 7 x 7 Cholesky solve with its 1e-15 regularisation
 * (test_effective_mass.c measured 2e-12 on the four-bar) */
#define TENSOR_REL_TOL 1e-9
/* the reference (positions as deviations from the ideal motion, the crank
 * on a clock restarted each sample: fb_sc_dyn_eval_dev) and this test (the
 * absolute form, fb_sc_dyn_rhs) integrate two forms of the same equations
 * with the same rk8pd driver settings, tolerance (1e-12) and output grid
 * from the same state: they differ by the two integrations' own errors,
 * measured with the impact law over two revolutions at 1.7e-10 of the
 * states' scales, 1.4e-9 of the clearance on the eccentricity and 1.2e-9
 * of the largest force on a force sample (issue 54); 1e-8 leaves 6x */
#define SAME_DYNAMICS_REL_TOL 1e-8
/* The restitution law's damper jumps at contact onset (c delta'), which no
 * tolerance resolves to round-off; each onset multiplies a difference about
 * tenfold (measured: 4e-13 after 2 impacts, 4e-11 after 5, 2e-7 after 12,
 * 3.5e-2 by the end). Its forms are compared over its first impacts alone. */
#define RESTITUTION_IMPACTS_COMPARED 5

/* ---- fixtures ------------------------------------------------------------- */

/* a benchmark-like slider-crank: crank 50 mm, rod 120 mm, slider 0.14 kg,
 * 5000 rpm, radial clearance 100 um at the piston pin */
static const char *const CASE_TEXT =
    "[case]\n"
    "name = sc_clearance\n"
    "[linkage]\n"
    "type = slider-crank\n"
    "crank_mm = 50\n"
    "coupler_mm = 120\n"
    "offset_mm = 6\n"
    "crank_angle0_deg = 20\n"
    "[mass]\n"
    "slider_kg = 0.14\n"
    "[drive]\n"
    "speed_rpm = 5000\n"
    "[pin]\n"
    "radial_clearance_um = 100\n"
    "[clearance]\n"
    "joints = coupler-slider\n"
    "[run]\n"
    "models = reference, reference-restitution\n"
    "revolutions = 2\n";

static void load(fb_case *c, const char **sets, int n) {
  fb_diag diag;
  if (fb_test_case_text(c, CASE_TEXT, sets, n, &diag) != FB_OK) fail_msg("case: %s", diag.msg);
}

static double dist(const double p[2], const double q[2]) { return hypot(p[0] - q[0], p[1] - q[1]); }

static fb_sc_dyn_model dyn_model(const fb_case *c, const fb_linkage *lk, const fb_contact_law *law) {
  fb_sc_dyn_model m;
  memset(&m, 0, sizeof m);
  m.geometry = (fb_slider_crank){lk->length[FB_CRANK], lk->length[FB_COUPLER],
                                 lk->length[FB_LENGTH_OFFSET]};
  const fb_link_mass *l = c->link;
  m.mass = (fb_slider_crank_mass){l[0].mass, l[0].inertia, l[0].com_fraction,
                                  l[1].mass, l[1].inertia, l[1].com_fraction, l[2].mass};
  m.gravity = c->gravity;
  m.clearance = c->radial_clearance;
  m.law = *law;
  m.impact_velocity = 1e-3;
  m.theta0 = c->crank_angle0;
  m.omega2 = fb_case_omega2(c);
  return m;
}

/* ---- the start ------------------------------------------------------------ */

/* every pin_start puts the rod's pin P at coupler from B, B at crank from A,
 * the hole H on the guide and P - H at the eccentricity pin_start asks for;
 * its velocities are fb_sc_dyn_start's (the ideal slider-crank whose guide
 * is moved by e_y) */
static void test_start_geometry(void **state) {
  (void)state;
  const char *angle[] = {"run.pin_start=-30"};
  const char *resting[] = {"run.pin_start=resting"};
  const char *rest[] = {"run.start=rest", "run.pin_start=-30"};
  const char **sets[4] = {NULL, angle, resting, rest};
  const int nsets[4] = {0, 1, 1, 2};
  for (int k = 0; k < 4; k++) {
    fb_case c;
    load(&c, sets[k], nsets[k]);
    fb_linkage lk;
    fb_case_stackup_lengths(&c, &lk);
    const int cj = fb_case_mech(&c)->reference_joint;
    assert_int_equal(cj, 2);
    fb_start_state s;
    assert_int_equal(fb_start_resolve(&s, &c, &lk, 1 << cj, NULL), FB_OK);
    const double A[2] = {0.0, 0.0};
    assert_near(dist(s.pin[1], A), lk.length[FB_CRANK], LOOP_TOL_M);
    assert_near(dist(s.pin[cj], s.hole[1]), lk.length[FB_COUPLER], LOOP_TOL_M);
    assert_near(s.hole[cj][1], lk.length[FB_LENGTH_OFFSET], LOOP_TOL_M);
    assert_true(s.body[1][FB_Q_POS] == s.hole[cj][0]);
    assert_true(s.pin[3][0] == s.hole[cj][0] && s.pin[3][1] == s.hole[cj][1]);
    const double e[2] = {s.pin[cj][0] - s.hole[cj][0], s.pin[cj][1] - s.hole[cj][1]};
    assert_near(e[0], s.ecc[cj][0], LOOP_TOL_M);
    assert_near(e[1], s.ecc[cj][1], LOOP_TOL_M);
    if (k == 0) assert_true(hypot(e[0], e[1]) <= LOOP_TOL_M);
    if (k == 1 || k == 3) {
      assert_rel(hypot(e[0], e[1]), c.radial_clearance, ECC_REL_TOL);
      assert_near(atan2(e[1], e[0]), -M_PI / 6, ECC_REL_TOL);
    }
    if (k == 2) {
      /* resting: the slider's hole leans on the pin along the static force
       * the rod puts on it (slider_crank_invdyn.h at zero speed) */
      fb_slider_crank_reactions r;
      const fb_slider_crank sc = {lk.length[0], lk.length[1], lk.length[FB_LENGTH_OFFSET]};
      const fb_slider_crank_mass m = {c.link[0].mass, c.link[0].inertia, c.link[0].com_fraction,
                                      c.link[1].mass, c.link[1].inertia, c.link[1].com_fraction,
                                      c.link[2].mass};
      assert_int_equal(fb_slider_crank_invdyn(&r, &sc, &m, c.gravity, c.crank_angle0, 0, 0, NULL),
                       FB_OK);
      const double f = hypot(r.force[2][0], r.force[2][1]);
      assert_rel(hypot(e[0], e[1]), c.radial_clearance, ECC_REL_TOL);
      assert_near(e[0] / c.radial_clearance, r.force[2][0] / f, ECC_REL_TOL);
      assert_near(e[1] / c.radial_clearance, r.force[2][1] / f, ECC_REL_TOL);
    }
    /* the velocities of the dynamics' own start for the same eccentricity */
    const fb_contact_law law = fb_contact_law_default();
    fb_sc_dyn_model dm = dyn_model(&c, &lk, &law);
    double y0[FB_SC_DYN_DIM];
    /* (|e| = c to rounding: the dynamics' own check wants it inside) */
    const double e_in[2] = {e[0] * (1.0 - 1e-12), e[1] * (1.0 - 1e-12)};
    assert_int_equal(fb_sc_dyn_start(y0, &dm, e_in, NULL), FB_OK);
    assert_near(s.coupler_angle, y0[0], 1e-15);
    assert_near(s.body[1][FB_Q_POS], y0[1], LOOP_TOL_M);
    assert_near(s.coupler_omega, y0[2], 1e-12 * fabs(y0[2]));
    /* rest: the slider, free of the rod, at rest; steady: on the motion */
    if (k == 3) assert_true(s.body[1][FB_Q_VEL] == 0.0);
    else assert_near(s.body[1][FB_Q_VEL], y0[3], 1e-12 * fabs(y0[3]) + 1e-15);
    /* the rod's point at B moves with the crank */
    assert_near(s.coupler_b_vel[0], -fb_case_omega2(&c) * s.pin[1][1], 1e-12);
    assert_near(s.coupler_b_vel[1], fb_case_omega2(&c) * s.pin[1][0], 1e-12);
  }
}

/* ---- the effective mass at the piston pin --------------------------------- */

/* closed form, KKT with the guide's prismatic rows, and the minimal
 * coordinates' 1 / (w^T M^-1 w) (slider_crank_dynamics.c), over a
 * revolution, offsets -20 .. +20 % of the crank and several directions */
static void test_piston_pin_effective_mass_three_ways(void **state) {
  (void)state;
  fb_case c;
  load(&c, NULL, 0);
  double worst_kkt = 0.0, worst_dyn = 0.0;
  for (int o = -2; o <= 2; o++) {
    fb_linkage lk = c.nominal;
    lk.length[FB_LENGTH_OFFSET] = 0.1 * o * lk.length[FB_CRANK];
    for (int k = 0; k < 72; k++) {
      const double th = 2.0 * M_PI * k / 72.0;
      fb_mechanism m;
      assert_int_equal(fb_mech_mechanism_at(&m, FB_MECH_SLIDER_CRANK, &lk, c.branch, c.link, th,
                                            1 << FB_JOINT_C, NULL),
                       FB_OK);
      assert_int_equal(m.prismatic_mask, 1 << FB_JOINT_D);
      double w[4][2][2], wk[4][2][2];
      assert_int_equal(fb_effective_mass_tensor(w, &m, NULL), FB_OK);
      assert_int_equal(fb_effective_mass_tensor_kkt(wk, &m, NULL), FB_OK);
      double d = 0.0, s = 0.0;
      for (int r = 0; r < 2; r++)
        for (int q = 0; q < 2; q++) {
          d = fmax(d, fabs(w[FB_JOINT_C][r][q] - wk[FB_JOINT_C][r][q]));
          s = fmax(s, fabs(wk[FB_JOINT_C][r][q]));
        }
      worst_kkt = fmax(worst_kkt, d / s);
      assert_true(d <= TENSOR_REL_TOL * s);
      /* the dynamics' effective mass along n: the pin P at the ideal
       * state's C and the hole at P - delta n, on a guide moved by
       * -delta n_y (the mass matrix depends on theta3 and n alone) */
      const fb_contact_law law = fb_contact_law_default();
      fb_sc_dyn_model dm = dyn_model(&c, &lk, &law);
      fb_slider_crank_state st;
      const fb_slider_crank sc = dm.geometry;
      assert_int_equal(fb_slider_crank_solve(&st, &sc, th, 0.0, 0.0, NULL), FB_OK);
      for (int q = 0; q < 8; q++) {
        const double phi = 2.0 * M_PI * (q + 0.25) / 8.0, delta = 1e-6;
        const double n[2] = {cos(phi), sin(phi)};
        dm.theta0 = th;
        dm.geometry.offset = sc.offset - delta * n[1];
        const double y[4] = {st.coupler_angle, st.slider_x - delta * n[0], 0.0, 0.0};
        fb_sc_dyn_eval ev;
        fb_sc_dyn_eval_at(&ev, &dm, 0.0, y);
        const double me = fb_effective_mass_along(w[FB_JOINT_C], n);
        worst_dyn = fmax(worst_dyn, fabs(me - ev.effective_mass) / ev.effective_mass);
        assert_rel(me, ev.effective_mass, TENSOR_REL_TOL);
      }
    }
  }
  report_residual("piston pin W, closed form vs KKT", worst_kkt, TENSOR_REL_TOL);
  report_residual("piston pin m_eff vs minimal coordinates", worst_dyn, TENSOR_REL_TOL);
}

/* ---- laws and the automatic step ------------------------------------------ */

/* the laws sit at the piston pin alone; the physical penalty's working force
 * is the pin's largest inverse-dynamics reaction; the restitution law's mass
 * the rod and slider's reduced mass; the automatic step resolves the
 * stiffer law against the smallest effective mass over a revolution */
static void test_laws_and_automatic_step(void **state) {
  (void)state;
  fb_case c;
  load(&c, NULL, 0);
  fb_contact_law imp[4], res[4];
  memset(imp, 0, sizeof imp);
  memset(res, 0, sizeof res);
  assert_int_equal(fb_joint_laws(imp, res, &c, NULL), FB_OK);
  for (int j = 0; j < 4; j++) assert_true((imp[j].stiffness > 0.0) == (j == FB_JOINT_C));
  const double m3 = c.link[1].mass, m4 = c.link[2].mass;
  assert_rel(res[FB_JOINT_C].mass, m3 * m4 / (m3 + m4), 1e-15);
  fb_contact_estimate est[4];
  assert_int_equal(fb_contact_estimates(est, &c, imp, NULL), FB_OK);
  /* smallest m_eff: the slider alone when the normal runs along the guide
   * and the rod's pin cannot move along it (rod along the guide), never more
   * than m_slider; positive */
  assert_true(est[FB_JOINT_C].m_eff_min > 0.0 && est[FB_JOINT_C].m_eff_min <= m4 * (1 + 1e-12));
  fb_linkage su;
  fb_case_stackup_lengths(&c, &su);
  double fmax[4];
  assert_int_equal(fb_mech_reaction_peaks(fmax, FB_MECH_SLIDER_CRANK, &su, c.branch, c.link,
                                          c.gravity, fb_case_omega2(&c), 3600, NULL),
                   FB_OK);
  assert_rel(est[FB_JOINT_C].force_expected, FB_IMPACT_LOAD_FACTOR * fmax[FB_JOINT_C], 1e-15);
  double h, wmax;
  assert_int_equal(fb_step_auto(&h, &wmax, &c, NULL), FB_OK);
  assert_true(wmax >= est[FB_JOINT_C].omega_c);
  assert_near(h, fmin(FB_H_OMEGA_C_BOUND / wmax,
                      2.0 * M_PI / (c.crank_speed * FB_H_AUTO_STEPS_PER_REV)),
              1e-18);
}

/* the paper's stiffness recipe is the four-bar's: refused for a slider-crank,
 * and so is clearance at a joint that is not the piston pin */
static void test_refusals(void **state) {
  (void)state;
  fb_case c;
  fb_diag diag;
  const char *paper[] = {"clearance.penalty=paper"};
  assert_int_equal(fb_test_case_text(&c, CASE_TEXT, paper, 1, &diag), FB_ERR_ARG);
  assert_non_null(strstr(diag.msg, "penalty = paper"));
  const char *crank[] = {"clearance.joints=crank-coupler"};
  assert_int_equal(fb_test_case_text(&c, CASE_TEXT, crank, 1, &diag), FB_ERR_ARG);
  assert_non_null(strstr(diag.msg, "coupler-slider"));
}

/* ---- the reference -------------------------------------------------------- */

/* the slider-crank dynamics on their own: rk8pd at FB_REFERENCE_TOL from y0,
 * sampled at k h with the evaluation's contact (the reference's driver
 * settings: first step h / 1000, no step limit) */
static void integrate(fb_sc_dyn_sample *out, size_t n, double h, const double y0[4],
                      fb_sc_dyn_model *m) {
  assert_int_equal(fb_sc_dyn_check(m, NULL), FB_OK);
  assert_int_equal(fb_contact_law_prepare(&m->law, NULL), FB_OK);
  double y[4] = {y0[0], y0[1], y0[2], y0[3]}, t = 0.0;
  gsl_odeiv2_system sys = {fb_sc_dyn_rhs, NULL, 4, m};
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h * 1e-3, FB_REFERENCE_TOL,
                                    FB_REFERENCE_TOL);
  assert_non_null(drv);
  gsl_odeiv2_driver_set_nmax(drv, 0);
  for (size_t k = 0; k < n; k++) {
    if (k > 0) assert_int_equal(gsl_odeiv2_driver_apply(drv, &t, (double)k * h, y), GSL_SUCCESS);
    fb_sc_dyn_eval ev;
    fb_sc_dyn_eval_at(&ev, m, (double)k * h, y);
    out[k].coupler_angle = y[0];
    out[k].slider_x = y[1];
    out[k].coupler_omega = y[2];
    out[k].slider_v = y[3];
    out[k].force = ev.force;
    out[k].ecc[0] = ev.ecc[0];
    out[k].ecc[1] = ev.ecc[1];
  }
  gsl_odeiv2_driver_free(drv);
}

/* the reference model's series is the slider-crank dynamics integrated on
 * their own from the same start, for both laws (positions and velocities at
 * every sample; the contact force away from the refined spikes) */
static void test_reference_is_the_slider_crank_dynamics(void **state) {
  (void)state;
  const char *sets[] = {"solver.h_s=1e-5", "run.pin_start=-30"};
  fb_case c;
  load(&c, sets, 2);
  fb_contact_law laws[2][4];
  assert_int_equal(fb_joint_laws(laws[0], laws[1], &c, NULL), FB_OK);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  fb_start_state s;
  assert_int_equal(fb_start_resolve(&s, &c, &lk, 1 << FB_JOINT_C, NULL), FB_OK);
  for (int law = 0; law < 2; law++) {
    fb_series ref;
    memset(&ref, 0, sizeof ref);
    size_t steps = 0;
    fb_stop stop;
    assert_int_equal(fb_reference_run_tol(&ref, &steps, &c, &laws[law][FB_JOINT_C], 0,
                                          FB_REFERENCE_TOL, &stop, NULL),
                     FB_OK);
    assert_int_equal(stop.kind, FB_STOP_NONE);
    assert_ptr_equal(ref.mech, &fb_mech_slider_crank);
    assert_true(ref.contact_mask == 1 << FB_JOINT_C);
    fb_sc_dyn_model dm = dyn_model(&c, &lk, &laws[law][FB_JOINT_C]);
    const double y0[4] = {s.coupler_angle, s.body[1][FB_Q_POS], s.coupler_omega,
                          s.body[1][FB_Q_VEL]};
    fb_sc_dyn_sample *own = calloc(ref.n, sizeof *own);
    assert_non_null(own);
    integrate(own, ref.n, c.solver.h, y0, &dm);
    double worst = 0.0, fbig = 0.0;
    size_t impacts = 0;
    for (size_t k = 0; k < ref.n; k++) fbig = fmax(fbig, own[k].force);
    for (size_t k = 0; k < ref.n; k++) {
      impacts += ref.contact[FB_JOINT_C][FB_C_STATE][k] == FB_STATE_IMPACT &&
                 (k == 0 || ref.contact[FB_JOINT_C][FB_C_STATE][k - 1] == FB_STATE_FREE);
      if (law == 1 && impacts > RESTITUTION_IMPACTS_COMPARED) break;
      const double d[4] = {(ref.body[0][FB_Q_POS][k] - own[k].coupler_angle) / M_PI,
                           (ref.body[1][FB_Q_POS][k] - own[k].slider_x) / lk.length[FB_COUPLER],
                           (ref.body[0][FB_Q_VEL][k] - own[k].coupler_omega) / fabs(dm.omega2),
                           (ref.body[1][FB_Q_VEL][k] - own[k].slider_v) /
                               (fabs(dm.omega2) * lk.length[FB_CRANK])};
      for (int q = 0; q < 4; q++) worst = fmax(worst, fabs(d[q]));
      assert_near(ref.contact[FB_JOINT_C][FB_C_EX][k], own[k].ecc[0],
                  SAME_DYNAMICS_REL_TOL * c.radial_clearance);
      /* refinement moves a spike's sample to its extreme: only up */
      assert_true(ref.contact[FB_JOINT_C][FB_C_FORCE][k] >= own[k].force - SAME_DYNAMICS_REL_TOL * fbig);
    }
    report_residual(law ? "reference vs sc dynamics (restitution)" : "reference vs sc dynamics (impact)",
                    worst, SAME_DYNAMICS_REL_TOL);
    assert_true(worst <= SAME_DYNAMICS_REL_TOL);
    /* the pin does rattle in this case: the comparison covers impacts */
    assert_true(impacts >= 2);
    free(own);
    fb_series_free(&ref);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_start_geometry),
      cmocka_unit_test(test_piston_pin_effective_mass_three_ways),
      cmocka_unit_test(test_laws_and_automatic_step),
      cmocka_unit_test(test_refusals),
      cmocka_unit_test(test_reference_is_the_slider_crank_dynamics),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
