/* The four-bar in Simbody against the exact analytic solution (ideal loop)
 * and the reference dynamics (crank-coupler clearance joint), on the paper
 * case at its own step (h_s = auto) and Simbody's default accuracy
 * (FB_SIMBODY_ACCURACY_DEFAULT).
 *
 *            C  Pin (coupler on follower)
 *           / \
 *  coupler /   \ follower      Pin mobilizers about +z: ground -> crank (A,
 *         B     \              angle prescribed by a Motion), ground ->
 *  crank /       \             follower (D), follower -> coupler (C); B is a
 *       A ------- D            Constraint::Ball (ideal) or the contact law as
 *                              a Force::Custom (clearance); gravity along -y
 *
 * An error-controlled integrator (RungeKuttaMerson) sampled on the output
 * grid: the ideal peaks' error follows the accuracy, not h; the clearance
 * models integrate the same two-degree-of-freedom equations as the reference
 * (minimal coordinates, rk8pd at 1e-12), so they must agree with it as
 * closely as the accuracy allows.
 *
 * The slider-crank (issue 45; the tests after "the slider-crank" below) on
 * the same engine: the Pin tree ground -> crank -> rod and a Slider mobilizer
 * ground -> slider along the guide, the loop cut at the piston pin.
 *
 * In a build without Simbody every test is skipped, except the one that
 * checks the refusal and its message. */
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "engine.h"
#include "fb_config.h"
#include "fb_test.h"
#include "outcome_text.h"
#include "run.h"
#if FB_HAVE_SIMBODY
#include "simbody_scene.h"
#endif

/* the acceptance bound on the ideal models' omega and alpha peaks
 * against the analytic ones at the default accuracy (measured 1e-6: omega
 * 5.7e-7, alpha 1.9e-6) */
#define PEAK_OMEGA_REL_TOL 1e-4
#define PEAK_ALPHA_REL_TOL 1e-4
/* a position-level Motion prescribes the crank angle theta0 + omega2 t:
 * exact to round-off (1e-9 rad is 1e-10 of a revolution) */
#define CRANK_ANGLE_TOL_RAD 1e-9
/* the Ball constraint's violation, projected every step to the accuracy
 * (relative to the link lengths, ~0.3 m): 1e-6 x 0.3 m, with a factor of
 * 10 for the interpolated samples between steps */
#define DRIFT_TOL_M 3e-6
/* joint reactions and drive torque peaks against the inverse dynamics
 * (invdyn.h): the ideal motion within the omega/alpha bound */
#define LOADS_REL_TOL 1e-4
/* the acceptance bounds on the impact model's peak force and
 * penetration against the reference (measured: -0.029 %, -0.105 %) */
#define FORCE_PEAK_REL_TOL 0.01
#define PEN_PEAK_REL_TOL 0.01
/* The restitution model over revolution 2 (the reference's count and peaks
 * converge there: its error estimate 1.4e-5; revolution 3 converges at no
 * tolerance, reference.h). The rattling after the first impacts amplifies
 * every difference: at the default accuracy 1e-6 Simbody's revolution-2
 * peak force is -4.3 % off (14/14 impacts), at 1e-8 +0.24 % (penetration
 * +0.21 %). Held at 1e-8 to the impact model's 1 % bound */
#define RESTITUTION_ACCURACY "simbody.accuracy=1e-8"
#define RESTITUTION_PEAK_REL_TOL 0.01
/* the impact count over revolution 2: the sequence is chaotic after the
 * first impacts (the reference-restitution count moved 12 to 15 over an
 * 8-member ensemble of 1.45e-11 m starts, docs/chaos.md; Simbody counted 14
 * of the reference's 14 before the effective mass's closed form, 15 of 14
 * after, from a 1e-12 change of m_eff), so it is held to the 15 %
 * of the reference's count, as MuJoCo's and ODE's are */
#define RESTITUTION_IMPACTS_REL_TOL 0.15
/* a looser accuracy must cost fewer steps and give a larger error: the
 * ideal peak error at accuracy 1e-3 is at least 10 times that at 1e-8
 * (an error control that controls nothing would fail this) */
#define ACCURACY_ERROR_RATIO_MIN 10.0

/* The bound on the ideal nominal model's omega and alpha peak
 * errors (issue 43: comparable to ODE's on the same grid, 1.2e-6 and
 * 1.8e-6) with the grid filled by interpolation between the integrator's
 * steps and exact samples at the peaks (measured 3.4e-7 and 1.3e-6) */
#define PEAK_INTERPOLATED_REL_TOL 2e-6
/* The interpolation's error between the integrator's steps (1 ms on the
 * paper case at accuracy 1e-6), sample by sample against the analytic
 * solution over revolution 2, relative to the peak: omega by the cubic
 * Hermite of u and udot (measured 1.2e-5), alpha its derivative (measured
 * 4.0e-4); twice that as the bound, so that a looser interpolant fails */
#define GRID_OMEGA_REL_TOL 2.5e-5
#define GRID_ALPHA_REL_TOL 8e-4
/* Exact samples (realized, not interpolated) of the ideal model over 2
 * revolutions: a peak's refined knot interval and the samples beside it
 * (measured 378 of 36,181, 1.0 %); a driver that realized every sample
 * (stepTo per sample: 100 %) fails */
#define EXACT_SAMPLES_FRACTION_MAX 0.05

static double worst(double a, double b, double c, double d) {
  return fmax(fmax(fabs(a), fabs(b)), fmax(fabs(c), fabs(d)));
}

static double omega_peak_rel(const fb_error *e) {
  return worst(e->coupler.omega_max_rel, e->coupler.omega_min_rel, e->follower.omega_max_rel,
               e->follower.omega_min_rel);
}

static double alpha_peak_rel(const fb_error *e) {
  return worst(e->coupler.alpha_max_rel, e->coupler.alpha_min_rel, e->follower.alpha_max_rel,
               e->follower.alpha_min_rel);
}

/* runs the paper case with the given models and overrides into *r */
static void run(fb_run *r, const char *models, const char **sets, int n) {
  const char *all[8];
  char ms[256];
  snprintf(ms, sizeof ms, "run.models=%s", models);
  all[0] = ms;
  for (int i = 0; i < n; i++) all[i + 1] = sets[i];
  fb_case c;
  fb_test_paper_case(&c, all, n + 1);
  fb_diag d;
  if (fb_run_case(r, &c, NULL, NULL, &d) != FB_OK) fail_msg("run failed: %s", d.msg);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].run.stop.kind != FB_STOP_NONE)
      fail_msg("%s: stopped (%s)", r->model[i].run.name,
               fb_stop_kind_name(r->model[i].run.stop.kind));
}

#define SKIP_WITHOUT_SIMBODY() \
  do {                         \
    if (!FB_HAVE_SIMBODY) skip(); \
  } while (0)

static void test_ideal_models_match_analytic(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  static fb_run r;
  run(&r, "analytic, analytic-stackup, simbody-ideal-nominal, simbody-ideal-stackup", NULL, 0);
  for (int i = 2; i < 4; i++) {
    const fb_model_result *m = &r.model[i];
    const fb_model_result *a = &r.model[i - 2]; /* analytic of the same lengths */
    assert_string_equal(fb_engine_name(m->run.model->engine), "simbody");
    assert_true(m->has_error);
    const double wo = omega_peak_rel(&m->error), wa = alpha_peak_rel(&m->error);
    report_residual(m->run.name, 0, 0);
    report_residual("  peak omega rel", wo, PEAK_OMEGA_REL_TOL);
    report_residual("  peak alpha rel", wa, PEAK_ALPHA_REL_TOL);
    report_residual("  crank angle err [rad]", m->error.crank_angle_err_max, CRANK_ANGLE_TOL_RAD);
    report_residual("  loop drift [m]", m->run.joint_drift_max, DRIFT_TOL_M);
    assert_true(wo < PEAK_OMEGA_REL_TOL);
    assert_true(wa < PEAK_ALPHA_REL_TOL);
    assert_true(m->error.crank_angle_err_max < CRANK_ANGLE_TOL_RAD);
    assert_true(m->run.joint_drift_max < DRIFT_TOL_M);
    /* loads: drive torque and every joint's reaction against the analytic
     * model's inverse dynamics, sample by sample at the peaks */
    const fb_series *s = &m->run.series, *t = &a->run.series;
    assert_true(s->has_loads && t->has_loads);
    assert_int_equal(s->n, t->n);
    double tq = 0.0, tq_ref = 0.0, rx = 0.0, rx_ref = 0.0;
    for (size_t k = 0; k < s->n; k++) {
      tq = fmax(tq, fabs(s->drive_torque[k]));
      tq_ref = fmax(tq_ref, fabs(t->drive_torque[k]));
      for (int j = 0; j < 4; j++) {
        rx = fmax(rx, hypot(s->reaction[j][0][k], s->reaction[j][1][k]));
        rx_ref = fmax(rx_ref, hypot(t->reaction[j][0][k], t->reaction[j][1][k]));
      }
    }
    report_residual("  drive torque peak rel", tq / tq_ref - 1.0, LOADS_REL_TOL);
    report_residual("  reaction peak rel", rx / rx_ref - 1.0, LOADS_REL_TOL);
    assert_true(fabs(tq / tq_ref - 1.0) < LOADS_REL_TOL);
    assert_true(fabs(rx / rx_ref - 1.0) < LOADS_REL_TOL);
  }
  fb_run_free(&r);
}

/* The grid between the integrator's steps is interpolated (positions and
 * velocities Simbody's cubic Hermite, accelerations its derivative), the
 * peaks realized exactly: sample by sample within the interpolation's
 * error, the peaks within the 2e-6, and exact samples only around
 * the peaks */
static void test_grid_interpolated_peaks_exact(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  static fb_run r;
  const char *sets[] = {"run.revolutions=2"};
  run(&r, "analytic, simbody-ideal-nominal", sets, 1);
  const fb_model_result *a = &r.model[0], *m = &r.model[1];
  const double wo = omega_peak_rel(&m->error), wa = alpha_peak_rel(&m->error);
  report_residual("interpolated grid: peak omega rel", wo, PEAK_INTERPOLATED_REL_TOL);
  report_residual("interpolated grid: peak alpha rel", wa, PEAK_INTERPOLATED_REL_TOL);
  assert_true(wo <= PEAK_INTERPOLATED_REL_TOL);
  assert_true(wa <= PEAK_INTERPOLATED_REL_TOL);
  const fb_series *s = &m->run.series, *t = &a->run.series;
  assert_int_equal(s->n, t->n);
  const double wmax = fmax(fb_series_largest_abs(t->coupler_omega, t->n),
                           fb_series_largest_abs(t->follower_omega, t->n));
  const double amax = fmax(fb_series_largest_abs(t->coupler_alpha, t->n),
                           fb_series_largest_abs(t->follower_alpha, t->n));
  double dw = 0.0, da = 0.0;
  for (size_t k = 0; k < s->n; k++) {
    if (s->t[k] < r.t_window) continue;
    dw = fmax(dw, fmax(fabs(s->coupler_omega[k] - t->coupler_omega[k]),
                       fabs(s->follower_omega[k] - t->follower_omega[k])));
    da = fmax(da, fmax(fabs(s->coupler_alpha[k] - t->coupler_alpha[k]),
                       fabs(s->follower_alpha[k] - t->follower_alpha[k])));
  }
  report_residual("interpolated grid: omega rel, every sample", dw / wmax, GRID_OMEGA_REL_TOL);
  report_residual("interpolated grid: alpha rel, every sample", da / amax, GRID_ALPHA_REL_TOL);
  assert_true(dw / wmax <= GRID_OMEGA_REL_TOL);
  assert_true(da / amax <= GRID_ALPHA_REL_TOL);
  fb_run_free(&r);
#if FB_HAVE_SIMBODY
  /* the engine on its own: how many samples it realized exactly */
  static fb_case c;
  const char *one[] = {"run.revolutions=2", "run.models=simbody-ideal-nominal"};
  fb_test_paper_case(&c, one, 2);
  static fb_scene def;
  fb_model_scene sm;
  fb_diag d;
  if (fb_scene_from_case(&def, &c, &d) != FB_OK) fail_msg("scene: %s", d.msg);
  if (fb_scene_select(&sm, &def, fb_model_find("simbody-ideal-nominal"), &d) != FB_OK)
    fail_msg("select: %s", d.msg);
  const fb_engine *e = fb_engine_get(FB_ENGINE_SIMBODY, &d);
  void *self = NULL;
  if (!e || e->create(&self, &sm, &d) != FB_OK) fail_msg("create: %s", d.msg);
  for (size_t k = 0; k < def.steps; k++)
    if (e->step(self, &d) != FB_OK) fail_msg("step %zu: %s", k, d.msg);
  const double exact = (double)fb_simbody_scene_exact_samples(self) / (double)def.steps;
  report_residual("exact samples, fraction of the grid", exact, EXACT_SAMPLES_FRACTION_MAX);
  assert_true(exact > 0.0);
  assert_true(exact <= EXACT_SAMPLES_FRACTION_MAX);
  e->destroy(self);
#endif
}

static void test_clearance_impact_matches_reference(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  static fb_run r;
  run(&r, "simbody-clearance-impact, reference", NULL, 0);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  assert_string_equal(m->ref_name, "reference");
  const fb_reference_error *re = &m->ref_error;
  report_residual("simbody impact force peak rel", re->force_max_rel, FORCE_PEAK_REL_TOL);
  report_residual("simbody impact penetration peak rel", re->penetration_max_rel, PEN_PEAK_REL_TOL);
  report_residual("simbody impacts", re->impacts, re->impacts_reference);
  assert_true(fabs(re->force_max_rel) < FORCE_PEAK_REL_TOL);
  assert_true(fabs(re->penetration_max_rel) < PEN_PEAK_REL_TOL);
  assert_true(re->impacts > 0);
  assert_int_equal(re->impacts, re->impacts_reference);
  /* Simbody maps nothing: no ERP, CFM or h omega_c; the effective mass is
   * kept only for the restitution law's damper */
  const fb_contact_provenance *p = &m->run.provenance[FB_JOINT_B];
  assert_true(p->contact_steps > 0);
  assert_true(isnan(p->erp_max) && isnan(p->h_omega_max));
  fb_run_free(&r);
}

static void test_clearance_restitution_matches_reference(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  static fb_run r;
  const char *sets[] = {"run.revolutions=2", RESTITUTION_ACCURACY};
  run(&r, "simbody-clearance-restitution, reference-restitution", sets, 2);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  assert_string_equal(m->ref_name, "reference-restitution");
  const fb_reference_error *re = &m->ref_error;
  report_residual("simbody restitution force peak rel", re->force_max_rel, RESTITUTION_PEAK_REL_TOL);
  report_residual("simbody restitution penetration peak rel", re->penetration_max_rel,
                  RESTITUTION_PEAK_REL_TOL);
  const double off = fabs((double)(re->impacts - re->impacts_reference));
  report_residual("simbody restitution impacts off (count)", off,
                  RESTITUTION_IMPACTS_REL_TOL * re->impacts_reference);
  assert_true(fabs(re->force_max_rel) < RESTITUTION_PEAK_REL_TOL);
  assert_true(fabs(re->penetration_max_rel) < RESTITUTION_PEAK_REL_TOL);
  assert_true(re->impacts_reference > 0);
  assert_true(off <= RESTITUTION_IMPACTS_REL_TOL * re->impacts_reference);
  /* the damper's mass: the effective mass along the normal was evaluated */
  const fb_contact_provenance *p = &m->run.provenance[FB_JOINT_B];
  assert_true(p->mass_eff_min > 0.0 && p->mass_eff_max >= p->mass_eff_min);
  fb_run_free(&r);
}

/* every integrator runs; the accuracy knob moves error and cost */
static void test_integrators_and_accuracy(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  const char *names[] = {"rkmerson", "rkfeldberg", "rk3", "cpodes", "verlet"};
  for (int i = 0; i < 5; i++) {
    static fb_run r;
    char integ[64];
    snprintf(integ, sizeof integ, "simbody.integrator=%s", names[i]);
    const char *sets[] = {integ, "run.revolutions=2", "simbody.accuracy=1e-5"};
    run(&r, "simbody-ideal-nominal", sets, 3);
    const double wo = omega_peak_rel(&r.model[0].error);
    report_residual(names[i], wo, PEAK_OMEGA_REL_TOL);
    assert_true(wo < PEAK_OMEGA_REL_TOL);
    assert_true(r.model[0].run.steps > 0);
    fb_run_free(&r);
  }
  static fb_run lo, hi;
  const char *s_lo[] = {"run.revolutions=2", "simbody.accuracy=1e-3"};
  const char *s_hi[] = {"run.revolutions=2", "simbody.accuracy=1e-8"};
  run(&lo, "simbody-ideal-nominal", s_lo, 2);
  run(&hi, "simbody-ideal-nominal", s_hi, 2);
  const double e_lo = alpha_peak_rel(&lo.model[0].error), e_hi = alpha_peak_rel(&hi.model[0].error);
  report_residual("alpha peak err at 1e-3 / at 1e-8", e_lo / e_hi, ACCURACY_ERROR_RATIO_MIN);
  assert_true(e_lo > ACCURACY_ERROR_RATIO_MIN * e_hi);
  assert_true(lo.model[0].run.steps < hi.model[0].run.steps);
  fb_run_free(&lo);
  fb_run_free(&hi);
}

/* [simbody] keys: bad values are refused naming the key; without Simbody
 * the models are refused with how to enable them */
static void test_keys_and_refusal(void **state) {
  (void)state;
  static fb_case c;
  fb_diag d;
#define LOAD(text) fb_casefile_load_text(&c, "t.ini", text, strlen(text), &d)
  assert_int_not_equal(LOAD("[simbody]\nintegrator = rk4\n"), FB_OK);
  assert_non_null(strstr(d.msg, "integrator"));
  assert_non_null(strstr(d.msg, "rkmerson"));
  assert_int_not_equal(LOAD("[simbody]\naccuracy = 1\n"), FB_OK);
  assert_non_null(strstr(d.msg, "accuracy"));
  assert_int_not_equal(LOAD("[simbody]\naccuracy = 1e-13\n"), FB_OK);
  assert_non_null(strstr(d.msg, "accuracy"));
  assert_int_equal(LOAD("[simbody]\nintegrator = cpodes\naccuracy = 1e-8\n"), FB_OK);
  assert_int_equal(c.simbody.integrator, FB_SIMBODY_CPODES);
  assert_true(c.simbody.accuracy == 1e-8);
  const fb_status st = LOAD("[run]\nmodels = simbody-ideal-nominal\n");
#undef LOAD
  if (FB_HAVE_SIMBODY) {
    assert_int_equal(st, FB_OK);
    assert_true(fb_engine_available(FB_ENGINE_SIMBODY));
    assert_non_null(fb_engine_get(FB_ENGINE_SIMBODY, &d));
    /* the tree is cut at the crank-coupler joint only: clearance elsewhere
     * is refused before any step in Simbody's own world, and the message
     * names the kit, which builder = auto takes there */
    static fb_case k;
    const char *sets[] = {"run.models=simbody-clearance-impact", "clearance.joints=coupler-follower",
                          "run.revolutions=2", "solver.builder=hand"};
    fb_test_paper_case(&k, sets, 4);
    static fb_run r;
    assert_int_equal(fb_run_case(&r, &k, NULL, NULL, &d), FB_ERR_ARG);
    assert_non_null(strstr(d.msg, "crank-coupler joint only"));
    assert_non_null(strstr(d.msg, "builder = auto or kit"));
    fb_run_free(&r);
  } else {
    assert_int_not_equal(st, FB_OK);
    assert_non_null(strstr(d.msg, "simbody-ideal-nominal"));
    assert_non_null(strstr(d.msg, "libsimbody-dev"));
    assert_non_null(strstr(d.msg, "-Dsimbody=enabled"));
    assert_null(fb_engine_get(FB_ENGINE_SIMBODY, &d));
    assert_non_null(strstr(d.msg, "-Dsimbody=enabled"));
  }
}

/* ---- the slider-crank -----------------------------------------------------
 *
 *                  B  Pin (rod on crank)
 *                 / \
 *          crank /   \ rod           Pin mobilizers about +z: ground -> crank
 *               /     \              (A, angle prescribed), crank -> rod (B);
 *              A       [P H]  - - -> a Slider mobilizer ground -> slider
 *                 guide y = offset   along +x at y = offset (its frame at the
 *                                    hole centre H); the piston pin P on the
 *                                    rod, a Constraint::Ball to H (ideal) or
 *                                    the contact law as a Force::Custom
 *                                    (clearance, pin P in the hole H)
 *
 * Ideal models against the exact slider-crank (slider_crank.h, the analytic
 * model of the same lengths) and its inverse dynamics
 * (slider_crank_invdyn.h); clearance models against the reference
 * (slider_crank_dynamics.h integrated by rk8pd), on a milder case of this
 * file and on the shipped cases/slider_crank_flores.ini. */

/* the acceptance bound on the ideal models' peaks against the
 * analytic ones at the automatic step: the rod's omega and alpha, the
 * slider's x, v and a (measured at the default accuracy 1e-6, the worst of
 * nominal and stack-up: flores rod omega / alpha 5.7e-8 / 1.3e-6, slider
 * v / a 2.8e-7 / 2.1e-7; the mild case 4.4e-8 / 1.3e-6 and 1.4e-7 /
 * 3.1e-7, its slider x 1.7e-6) */
#define SC_PEAK_REL_TOL 1e-4
/* the Ball at the piston pin, projected every step to the accuracy: the
 * four-bar's bound (DRIFT_TOL_M) on a smaller mechanism (crank 50, rod
 * 120 mm; measured 1.7e-7 m on both cases) */
#define SC_DRIFT_TOL_M DRIFT_TOL_M
/* the drive torque and the four joints' reaction peaks (the guide's normal
 * force among them) against the slider-crank's inverse dynamics: the ideal
 * motion's bound, as the four-bar's LOADS_REL_TOL (measured at most 1.2e-6,
 * the guide's on the mild case; the pins' 1e-13 to 2e-8) */
#define SC_LOADS_REL_TOL 1e-4
/* the clearance models' peak force and penetration against the reference:
 * the 1 % (measured on flores at the default accuracy: impact
 * -0.38 % / -2.4e-6, restitution +0.15 % / +0.13 %) */
#define SC_CONTACT_PEAK_REL_TOL 0.01
/* The mild case's impact model at accuracy 1e-8. At the default 1e-6 it
 * leaves the reference at 45.2 ms (197 deg into revolution 2), 10 of 11
 * impacts matched before, and its verdict is statistical; at 1e-8 it stays
 * with it over the run, 11 of 11 matched, peak force +0.14 %, penetration
 * +0.11 %. Its matched impacts agree within 0.7 % but for two grazes (24
 * and 14 N, 0.46 and 0.31 um, at the tail of an impact whose force the
 * impact law clips at zero while the pin withdraws): force within 1.9 %,
 * penetration up to 67 %, which fails the verdict's matched-impact bound
 * (0.05) though not the peaks; so the peaks and the matching are held
 * here, not the verdict */
#define SC_MILD_IMPACT_ACCURACY "simbody.accuracy=1e-8"
/* The mild case's restitution model rattles (110 impacts in 2
 * revolutions) and leaves the reference however tight the accuracy: at
 * 10.3 ms at 1e-6, 16.1 ms at 1e-8, 29.4 ms at 1e-9 (its peaks then compare
 * two histories: -8 %, +0.6 %, -31 %), so the start-up's first impacts, before
 * it leaves, are held to the 1 % (measured within 3.1e-3) */
#define SC_FIRST_IMPACT_REL_TOL 0.01
/* the restitution model's impact count on flores against the reference's
 * (44 of 45 at 1e-6): the same 15 % as the four-bar's
 * RESTITUTION_IMPACTS_REL_TOL, for the same reason (a graze more or less
 * in a rattle) */
#define SC_RESTITUTION_IMPACTS_REL_TOL 0.15

/* a milder slider-crank than flores: 2000 rpm, radial clearance 100 um, an
 * offset guide, a crank started at 20 deg, and tolerances so that the
 * stack-up lengths differ from the nominal ones */
static const char *const SC_MILD_CASE =
    "[case]\n"
    "name = simbody_sc_mild\n"
    "[linkage]\n"
    "type = slider-crank\n"
    "crank_mm = 50\n"
    "coupler_mm = 120\n"
    "offset_mm = 6\n"
    "crank_angle0_deg = 20\n"
    "[tolerance]\n"
    "crank_plus_minus_mm = 0.05\n"
    "coupler_plus_minus_mm = 0.05\n"
    "offset_plus_minus_mm = 0.05\n"
    "stackup = max\n"
    "[mass]\n"
    "slider_kg = 0.14\n"
    "[drive]\n"
    "speed_rpm = 2000\n"
    "[pin]\n"
    "radial_clearance_um = 100\n"
    "[clearance]\n"
    "joints = coupler-slider\n"
    "[run]\n"
    "revolutions = 2\n";

enum { SC_MILD = 0, SC_FLORES = 1 };
/* the slider-crank's coupler-slider joint, the piston pin (mechanism.h's
 * fb_mech_slider_crank: its reference_joint) */
#define FB_SC_PISTON_PIN 2
static const char *const sc_case_name[2] = {"mild", "flores"};

/* loads slider-crank case `which` with overrides into *c */
static void sc_load(fb_case *c, int which, const char **sets, int n) {
  fb_diag d;
  const fb_status st = which == SC_FLORES
                           ? fb_test_shipped_case(c, "slider_crank_flores.ini", sets, n, &d)
                           : fb_test_case_text(c, SC_MILD_CASE, sets, n, &d);
  if (st != FB_OK) fail_msg("slider-crank case %s: %s", sc_case_name[which], d.msg);
}

/* runs slider-crank case `which` with the given models and overrides */
static void sc_run(fb_run *r, int which, const char *models, const char **sets, int n) {
  const char *all[8];
  char ms[256];
  snprintf(ms, sizeof ms, "run.models=%s", models);
  all[0] = ms;
  for (int i = 0; i < n; i++) all[i + 1] = sets[i];
  static fb_case c;
  sc_load(&c, which, all, n + 1);
  assert_int_equal(c.mechanism, FB_MECH_SLIDER_CRANK);
  fb_diag d;
  if (fb_run_case(r, &c, NULL, NULL, &d) != FB_OK) fail_msg("run failed: %s", d.msg);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].run.stop.kind != FB_STOP_NONE)
      fail_msg("%s: stopped (%s)", r->model[i].run.name,
               fb_stop_kind_name(r->model[i].run.stop.kind));
}

/* the largest |relative peak error| of output body b: velocity and
 * acceleration max and min, and for the slider its position's */
static double sc_peak_rel(const fb_body_error *e, int with_position) {
  double w = worst(e->omega_max_rel, e->omega_min_rel, e->alpha_max_rel, e->alpha_min_rel);
  if (with_position) w = fmax(w, fmax(fabs(e->pos_max_rel), fabs(e->pos_min_rel)));
  return w;
}

static double series_peak(const double *v, size_t n) { return fb_series_largest_abs(v, n); }

static void test_slider_crank_ideal_matches_analytic(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  for (int which = 0; which < 2; which++) {
    static fb_run r;
    sc_run(&r, which, "analytic, analytic-stackup, simbody-ideal-nominal, simbody-ideal-stackup",
           NULL, 0);
    for (int i = 2; i < 4; i++) {
      const fb_model_result *m = &r.model[i];
      const fb_model_result *a = &r.model[i - 2]; /* analytic of the same lengths */
      assert_string_equal(fb_engine_name(m->run.model->engine), "simbody");
      assert_true(m->has_error);
      const double rod = sc_peak_rel(&m->error.body[0], 0);
      const double slider = sc_peak_rel(&m->error.body[1], 1);
      char name[128];
      snprintf(name, sizeof name, "slider-crank %s: %s", sc_case_name[which], m->run.name);
      report_residual(name, 0, 0);
      report_residual("  rod omega/alpha peak rel", rod, SC_PEAK_REL_TOL);
      report_residual("    rod omega peak rel",
                      fmax(fabs(m->error.body[0].omega_max_rel), fabs(m->error.body[0].omega_min_rel)),
                      SC_PEAK_REL_TOL);
      report_residual("  slider x/v/a peak rel", slider, SC_PEAK_REL_TOL);
      report_residual("    slider v peak rel",
                      fmax(fabs(m->error.body[1].omega_max_rel), fabs(m->error.body[1].omega_min_rel)),
                      SC_PEAK_REL_TOL);
      report_residual("    slider a peak rel",
                      fmax(fabs(m->error.body[1].alpha_max_rel), fabs(m->error.body[1].alpha_min_rel)),
                      SC_PEAK_REL_TOL);
      report_residual("  crank angle err [rad]", m->error.crank_angle_err_max, CRANK_ANGLE_TOL_RAD);
      report_residual("  loop drift at the piston pin [m]", m->run.joint_drift_max, SC_DRIFT_TOL_M);
      assert_true(rod < SC_PEAK_REL_TOL);
      assert_true(slider < SC_PEAK_REL_TOL);
      assert_true(m->error.crank_angle_err_max < CRANK_ANGLE_TOL_RAD);
      assert_true(m->run.joint_drift_max < SC_DRIFT_TOL_M);
      /* the drive torque and each joint's reaction (ground-crank,
       * crank-coupler, coupler-slider, the guide's slider-ground) against
       * the analytic model's inverse dynamics */
      const fb_series *s = &m->run.series, *t = &a->run.series;
      assert_true(s->has_loads && t->has_loads);
      assert_int_equal(s->n, t->n);
      const double tq = series_peak(s->drive_torque, s->n) / series_peak(t->drive_torque, t->n) - 1.0;
      report_residual("  drive torque peak rel", tq, SC_LOADS_REL_TOL);
      assert_true(fabs(tq) < SC_LOADS_REL_TOL);
      for (int j = 0; j < 4; j++) {
        double rx = 0.0, rx_ref = 0.0;
        for (size_t k = 0; k < s->n; k++) {
          rx = fmax(rx, hypot(s->reaction[j][0][k], s->reaction[j][1][k]));
          rx_ref = fmax(rx_ref, hypot(t->reaction[j][0][k], t->reaction[j][1][k]));
        }
        snprintf(name, sizeof name, "  %s reaction peak rel", fb_mech_joint_name(s->mech, j));
        report_residual(name, rx / rx_ref - 1.0, SC_LOADS_REL_TOL);
        assert_true(rx_ref > 0.0);
        assert_true(fabs(rx / rx_ref - 1.0) < SC_LOADS_REL_TOL);
      }
      /* the guide's reaction is normal to it: no force along the guide */
      double gx = 0.0;
      for (size_t k = 0; k < s->n; k++) gx = fmax(gx, fabs(s->reaction[3][0][k]));
      assert_true(gx == 0.0);
    }
    fb_run_free(&r);
  }
}

/* one clearance model against its reference: peak force and penetration */
static void sc_check_peaks(const fb_model_result *m, const char *ref, const char *what) {
  assert_true(m->has_ref_error);
  assert_string_equal(m->ref_name, ref);
  const fb_reference_error *re = &m->ref_error;
  char name[160];
  snprintf(name, sizeof name, "%s force peak rel", what);
  report_residual(name, re->force_max_rel, SC_CONTACT_PEAK_REL_TOL);
  snprintf(name, sizeof name, "%s penetration peak rel", what);
  report_residual(name, re->penetration_max_rel, SC_CONTACT_PEAK_REL_TOL);
  snprintf(name, sizeof name, "%s impacts (reference's as tol)", what);
  report_residual(name, re->impacts, re->impacts_reference);
  assert_true(fabs(re->force_max_rel) < SC_CONTACT_PEAK_REL_TOL);
  assert_true(fabs(re->penetration_max_rel) < SC_CONTACT_PEAK_REL_TOL);
  /* the contact was evaluated at the piston pin, and nowhere else */
  assert_true(m->run.provenance[FB_SC_PISTON_PIN].contact_steps > 0);
  assert_int_equal(m->run.provenance[FB_JOINT_B].contact_steps, 0);
}

static void test_slider_crank_clearance_impact_matches_reference(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  /* flores as shipped (its impact damper set for its restitution 0.9: the
   * pin rattles, and every engine's sequence parts from the reference's
   * after about 25 impacts, a statistical verdict) at the default accuracy:
   * its first impacts, before it parts, within 1 % */
  static fb_run r;
  sc_run(&r, SC_FLORES, "simbody-clearance-impact, reference", NULL, 0);
  const fb_model_result *m = &r.model[0];
  assert_true(m->has_ref_error);
  assert_string_equal(m->ref_name, "reference");
  assert_int_equal(m->ref_error.first_impacts, FB_FIRST_IMPACTS);
  for (int k = 0; k < FB_FIRST_IMPACTS; k++) {
    report_residual("slider-crank flores: impact k force rel", m->ref_error.first_impact_force_rel[k],
                    SC_CONTACT_PEAK_REL_TOL);
    report_residual("slider-crank flores: impact k penetration rel",
                    m->ref_error.first_impact_penetration_rel[k], SC_CONTACT_PEAK_REL_TOL);
    assert_true(fabs(m->ref_error.first_impact_force_rel[k]) < SC_CONTACT_PEAK_REL_TOL);
    assert_true(fabs(m->ref_error.first_impact_penetration_rel[k]) < SC_CONTACT_PEAK_REL_TOL);
  }
  assert_true(m->run.provenance[FB_SC_PISTON_PIN].contact_steps > 0);
  fb_run_free(&r);
  /* the mild case, at the accuracy that keeps it with the reference */
  const char *sets[] = {SC_MILD_IMPACT_ACCURACY};
  sc_run(&r, SC_MILD, "simbody-clearance-impact, reference", sets, 1);
  m = &r.model[0];
  sc_check_peaks(m, "reference", "slider-crank mild: impact");
  report_residual("slider-crank mild: impact, impacts matched", m->divergence.matched,
                  m->divergence.impacts_reference);
  assert_true(m->has_divergence && !m->divergence.diverged);
  assert_true(m->divergence.matched > 0);
  assert_int_equal(m->divergence.matched, m->divergence.impacts_reference);
  fb_run_free(&r);
}

static void test_slider_crank_clearance_restitution_matches_reference(void **state) {
  (void)state;
  SKIP_WITHOUT_SIMBODY();
  /* flores at the default accuracy: the peaks, the count, the damper's mass */
  static fb_run r;
  sc_run(&r, SC_FLORES, "simbody-clearance-restitution, reference-restitution", NULL, 0);
  const fb_model_result *m = &r.model[0];
  sc_check_peaks(m, "reference-restitution", "slider-crank flores: restitution");
  const fb_reference_error *re = &m->ref_error;
  const double off = fabs((double)(re->impacts - re->impacts_reference));
  report_residual("slider-crank flores: restitution impacts off (count)", off,
                  SC_RESTITUTION_IMPACTS_REL_TOL * re->impacts_reference);
  assert_true(re->impacts_reference > 0);
  assert_true(off <= SC_RESTITUTION_IMPACTS_REL_TOL * re->impacts_reference);
  const fb_contact_provenance *p = &m->run.provenance[FB_SC_PISTON_PIN];
  report_residual("slider-crank flores: m_eff min [kg]", p->mass_eff_min, 0);
  report_residual("slider-crank flores: m_eff max [kg]", p->mass_eff_max, 0);
  assert_true(p->mass_eff_min > 0.0 && p->mass_eff_max >= p->mass_eff_min);
  /* the damper's mass cannot exceed the slider's and the rod's together */
  assert_true(p->mass_eff_max <= r.scene.source.link[1].mass + r.scene.source.link[2].mass);
  fb_run_free(&r);
  /* the mild case rattles: its first impacts, before it leaves the reference */
  sc_run(&r, SC_MILD, "simbody-clearance-restitution, reference-restitution", NULL, 0);
  m = &r.model[0];
  assert_true(m->has_ref_error);
  re = &m->ref_error;
  assert_true(re->first_impacts > 0);
  for (int k = 0; k < re->first_impacts; k++) {
    report_residual("slider-crank mild: restitution, first impacts' force rel",
                    re->first_impact_force_rel[k], SC_FIRST_IMPACT_REL_TOL);
    report_residual("slider-crank mild: restitution, first impacts' penetration rel",
                    re->first_impact_penetration_rel[k], SC_FIRST_IMPACT_REL_TOL);
    assert_true(fabs(re->first_impact_force_rel[k]) < SC_FIRST_IMPACT_REL_TOL);
    assert_true(fabs(re->first_impact_penetration_rel[k]) < SC_FIRST_IMPACT_REL_TOL);
  }
  report_residual("slider-crank mild: restitution leaves the reference at [s]", m->divergence.t, 0);
  fb_run_free(&r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_keys_and_refusal),
      cmocka_unit_test(test_ideal_models_match_analytic),
      cmocka_unit_test(test_grid_interpolated_peaks_exact),
      cmocka_unit_test(test_clearance_impact_matches_reference),
      cmocka_unit_test(test_clearance_restitution_matches_reference),
      cmocka_unit_test(test_integrators_and_accuracy),
      cmocka_unit_test(test_slider_crank_ideal_matches_analytic),
      cmocka_unit_test(test_slider_crank_clearance_impact_matches_reference),
      cmocka_unit_test(test_slider_crank_clearance_restitution_matches_reference),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
