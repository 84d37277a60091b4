/* The four-bar in Bullet against the exact analytic solution (ideal loop),
 * the reference dynamics (crank-coupler clearance joint) and ODE (the same
 * contact row in the single impact); the slider-crank against its analytic
 * solution, its inverse dynamics and the reference at the piston pin.
 *
 *            C  planar pin rows (x, y) at every ideal joint
 *           / \
 *  coupler /   \ follower      three btRigidBody links in the plane
 *         B     \              (linear factor (1,1,0), angular (0,0,1)),
 *  crank /       \             the crank held at omega2 by an angular
 *       A ------- D            velocity row; gravity along -y
 *
 * In a build without Bullet the engine tests are skipped (cmocka skip,
 * which meson counts as skipped, exit 77 for the whole file when nothing
 * ran) and only the engine-free checks run: the [bullet] keys and the
 * refusal of the bullet-* models with the how-to. */
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "engine.h"
#include "fb_config.h"
#include "fb_test.h"
#include "impact.h"
#include "outcome_text.h"
#include "report.h"
#include "run.h"

#include <jansson.h>

/* the acceptance bound on the ideal models' omega and alpha peaks
 * against the analytic solution, at Bullet's default (mlcp-dantzig, the
 * paper case's automatic step); measured 1.2e-6 omega, 1.9e-6 alpha (ODE's
 * dWorldStep: the same 1.2e-6 / 1.8e-6) */
#define PEAK_REL_TOL 1e-4
/* crank angle: the drive row holds omega2 to the direct solver's rounding;
 * measured 1e-13 rad. 1e-9 rad is 1e-5 of one step's rotation */
#define CRANK_ANGLE_TOL_RAD 1e-9
/* the acceptance bound on bullet-clearance-impact's peak force and
 * penetration against the reference at the automatic step (matched
 * mapping); measured +0.064 % and -0.10 %, as ODE's */
#define CLEARANCE_PEAK_REL_TOL 0.01
/* Bullet and ODE solve the same row on the same semi-implicit Euler step:
 * their peak force errors on the paper case agree to the solvers'
 * rounding; measured 2e-6 apart (relative). 1e-4: well below the 1 %
 * acceptance bound, far above rounding */
#define BULLET_VS_ODE_FORCE_TOL 1e-4
/* the bound on the single impact at h omega_c = 0.1 with the
 * matched mapping (restitution and peak penetration against the GSL
 * reference); ODE measured +0.01 % / +0.05 % (hertz), -0.04 % / -0.04 %
 * (restitution law) */
#define IMPACT_MATCHED_REL_TOL 0.01
#define IMPACT_H_OMEGA 0.1
/* Bullet's single impact against ODE's with the same row: one body, one
 * row, so both direct solvers give the row's exact impulse and the
 * trajectories agree to rounding; measured 0 to 1e-12 */
#define IMPACT_BULLET_VS_ODE_TOL 1e-9
/* Bullet's own stiffness/damping conversion (secant row, erp = h k/(h k+c),
 * cfm = 1/(h k+c)) loses ~1.1 h omega_c of restitution: measured -10.9 %
 * (hertz) and -12.4 % (restitution law) at h omega_c = 0.1; the loss must
 * be at least this many times the matched row's (measured > 100x) */
#define OWN_CONVERSION_LOSS_FACTOR 5.0
/* joint reactions and drive torque of the ideal loop (pin rows' and drive
 * row's impulses / h) against the inverse dynamics of the analytic model:
 * peaks measured 2e-6 to 3e-6 apart (ODE's: the same); 1e-4 is the ideal
 * models' kinematic bound */
#define LOADS_REL_TOL 1e-4
/* sequential impulse on one soft row converges in one sweep (its diagonal
 * holds the CFM, as Bullet's contacts do): against the MLCP's exact solve */
#define SI_VS_MLCP_TOL 1e-9

/* ---- the slider-crank ----------------------------------------------------
 *
 *              B
 *       crank / \  rod          crank and rod: planar bodies, pin rows at A
 *            /   \             and B, the crank on the drive row
 *           A     P(H)== slider == guide y = offset, a btSliderConstraint
 *                                 to the world along +x
 *
 * the piston pin P-H: a pin row pair (ideal) or the clearance contact (pin
 * P on the rod, hole H on the slider) */

/* the ideal models' peaks against the analytic solution: the bound
 * at the automatic step (1e-4). Measured on the test case below (2000 rpm,
 * offset 6 mm, stack-up corner) 1.5e-6 and on cases/slider_crank_flores.ini
 * (5000 rpm) 4.6e-6 (rod omega/alpha, slider x/v/a): semi-implicit Euler's
 * O(h omega) error, as the four-bar's 1.2e-6 */
#define SC_PEAK_REL_TOL 1e-4
/* loads of the ideal slider-crank against its inverse dynamics (peaks of
 * each joint's |reaction| and of the drive torque): measured 4e-6 (flores),
 * the kinematics' error; 1e-4 as the four-bar's LOADS_REL_TOL. The guide's
 * signed force (-N along y on the ground) too, which the magnitudes alone
 * would not catch with the wrong sign */
#define SC_LOADS_REL_TOL 1e-4
/* the bound on a clearance model's peak force and penetration
 * against the reference (1 %), applied to the first impacts, whose onset
 * states the model and the reference share. The steady window's peaks
 * compare two different impact sequences (the restitution model leaves its
 * reference at 12.8 ms on flores; the impact model's contact at 16 ms comes
 * 38 us early, at another speed), and so do the rattling re-impacts after
 * the second (the test case's third impact at half its automatic step
 * moves from -1.4 % to +4.4 % in penetration between h = 1.41e-6 and
 * 1.410265e-6 s). Measured, flores at its automatic step, restitution law:
 * -0.063 %, -0.015 % (force), -0.003 %, +0.077 % (penetration) */
#define SC_IMPACT_REL_TOL 0.01
#define SC_IMPACTS_COMPARED 2
/* the impact law's first impact at the automatic step with the default
 * damper (the test case: c_max 1e4 N s/m): its peak force is the damper's
 * c v0, reached within the damping depth (1 um) and falling over the first
 * step (m_eff / c ~ 6 us); an engine's force is a step's impulse / h, the
 * mean over that step (no onset correction for this law, contact.h
 * fb_contact_row_onset). Measured -5.5 % force, -3.3 % penetration (the test
 * case; flores before its damper was set for its restitution: -4.8 %,
 * -2.7 %); 7 % bounds them with room for rounding, and the sign is asserted
 * too. With flores' damper of 480 N s/m the first impacts are within 1 %:
 * -0.15 %, +0.03 % */
#define SC_IMPACT_ONSET_SPIKE_TOL 0.07
/* ... or at half the automatic step, which halves the spike's fall within
 * the first step (the test case, whose h omega_c is 0.39 at auto, near the
 * bound 0.5): measured impact law +0.77 % / +0.59 %, restitution law
 * -0.077 % / -0.004 % on the first impact (at the automatic step the
 * restitution law's -0.31 % / +0.01 %) */
#define SC_HALF_STEP_FACTOR 0.5

/* the tests' own slider-crank: crank 50 mm, rod 120 mm, offset 6 mm, the
 * stack-up corner +0.1 mm each, 2000 rpm clockwise from 20 deg, the piston
 * pin 10 mm with 100 um radial clearance, derived masses but the slider's */
static const char *const SC_CASE_TEXT =
    "[case]\n"
    "name = sc_bullet\n"
    "[linkage]\n"
    "type = slider-crank\n"
    "crank_mm = 50\n"
    "coupler_mm = 120\n"
    "offset_mm = 6\n"
    "crank_angle0_deg = 20\n"
    "[tolerance]\n"
    "crank_plus_minus_mm = 0.1\n"
    "coupler_plus_minus_mm = 0.1\n"
    "stackup = max\n"
    "[mass]\n"
    "slider_kg = 0.14\n"
    "[drive]\n"
    "speed_rpm = 2000\n"
    "direction = cw\n"
    "[pin]\n"
    "radial_clearance_um = 100\n"
    "[clearance]\n"
    "joints = coupler-slider\n"
    "[run]\n"
    "models = analytic\n"
    "revolutions = 2\n"
    "ensemble = 1\n";

/* loads the test case (own = 1) or cases/slider_crank_flores.ini with
 * overrides; one model run per ensemble (ensemble = 1) */
static void sc_load(fb_case *c, int own, const char **sets, int n) {
  const char *all[8] = {"run.ensemble=1"};
  for (int i = 0; i < n; i++) all[i + 1] = sets[i];
  fb_diag d;
  const fb_status st = own ? fb_test_case_text(c, SC_CASE_TEXT, all, n + 1, &d)
                           : fb_test_shipped_case(c, "slider_crank_flores.ini", all, n + 1, &d);
  if (st != FB_OK) fail_msg("case: %s", d.msg);
  assert_int_equal(c->mechanism, FB_MECH_SLIDER_CRANK);
}

static void sc_run(fb_run *r, int own, const char *models, const char **sets, int n) {
  const char *all[6];
  char ms[256];
  snprintf(ms, sizeof ms, "run.models=%s", models);
  all[0] = ms;
  for (int i = 0; i < n; i++) all[i + 1] = sets[i];
  fb_case c;
  sc_load(&c, own, all, n + 1);
  fb_diag d;
  if (fb_run_case(r, &c, NULL, NULL, &d) != FB_OK) fail_msg("run failed: %s", d.msg);
  for (int i = 0; i < r->n; i++)
    if (r->model[i].run.stop.kind != FB_STOP_NONE)
      fail_msg("%s: stopped (%s)", r->model[i].run.name,
               fb_stop_kind_name(r->model[i].run.stop.kind));
}

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

static double worst(double a, double b, double c, double d) {
  return fmax(fmax(fabs(a), fabs(b)), fmax(fabs(c), fabs(d)));
}

static const fb_model_result *find(const fb_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].run.name, name) == 0) return &r->model[i];
  fail_msg("model %s did not run", name);
  return NULL;
}

#define NEEDS_BULLET()                                  \
  do {                                                  \
    if (!FB_HAVE_BULLET) {                              \
      fprintf(stderr, "  skipped: %s\n", FB_BULLET_HOWTO); \
      skip();                                           \
    }                                                   \
  } while (0)

static void test_ideal_models_match_analytic(void **state) {
  (void)state;
  NEEDS_BULLET();
  static fb_run r;
  run(&r, "bullet-ideal-nominal, bullet-ideal-stackup", NULL, 0);
  for (int i = 0; i < 2; i++) {
    const fb_model_result *m = &r.model[i];
    assert_string_equal(fb_engine_name(m->run.model->engine), "bullet");
    assert_true(m->has_error);
    const fb_error *e = &m->error;
    const double wo = worst(e->coupler.omega_max_rel, e->coupler.omega_min_rel,
                            e->follower.omega_max_rel, e->follower.omega_min_rel);
    const double wa = worst(e->coupler.alpha_max_rel, e->coupler.alpha_min_rel,
                            e->follower.alpha_max_rel, e->follower.alpha_min_rel);
    report_residual(m->run.name, 0, 0);
    report_residual("  peak omega rel", wo, PEAK_REL_TOL);
    report_residual("  peak alpha rel", wa, PEAK_REL_TOL);
    report_residual("  crank angle err [rad]", e->crank_angle_err_max, CRANK_ANGLE_TOL_RAD);
    assert_true(wo < PEAK_REL_TOL);
    assert_true(wa < PEAK_REL_TOL);
    assert_true(e->crank_angle_err_max < CRANK_ANGLE_TOL_RAD);
  }
  fb_run_free(&r);
}

static void test_clearance_impact_matches_reference_and_ode(void **state) {
  (void)state;
  NEEDS_BULLET();
  static fb_run r;
  /* the paper case as shipped: h_s = auto, matched mapping */
  run(&r, "bullet-clearance-impact, ode-clearance-impact, reference", NULL, 0);
  const fb_model_result *b = find(&r, "bullet-clearance-impact");
  const fb_model_result *o = find(&r, "ode-clearance-impact");
  assert_true(b->has_ref_error);
  assert_string_equal(b->ref_name, "reference");
  const fb_reference_error *re = &b->ref_error;
  report_residual("bullet impact force peak rel", re->force_max_rel, CLEARANCE_PEAK_REL_TOL);
  report_residual("bullet impact penetration peak rel", re->penetration_max_rel,
                  CLEARANCE_PEAK_REL_TOL);
  assert_true(fabs(re->force_max_rel) < CLEARANCE_PEAK_REL_TOL);
  assert_true(fabs(re->penetration_max_rel) < CLEARANCE_PEAK_REL_TOL);
  assert_true(re->impacts > 0);
  assert_int_equal(re->impacts, re->impacts_reference);
  /* cross-check: the same row as ODE's contact joint */
  report_residual("bullet vs ode force peak rel", re->force_max_rel - o->ref_error.force_max_rel,
                  BULLET_VS_ODE_FORCE_TOL);
  assert_true(fabs(re->force_max_rel - o->ref_error.force_max_rel) < BULLET_VS_ODE_FORCE_TOL);
  /* provenance: matched rows (ERP may exceed 1) on the true effective mass */
  const fb_contact_provenance *p = &b->run.provenance[FB_JOINT_B];
  assert_true(p->contact_steps > 0);
  assert_true(p->mass_eff_min > 0.0 && p->mass_eff_min < p->mass_eff_max);
  assert_true(p->cfm_min > 0.0);
  fb_run_free(&r);
}

static double load(json_t *sum, int i, const char *key, const char *joint) {
  json_t *l = json_object_get(json_array_get(json_object_get(sum, "models"), (size_t)i), "loads");
  if (joint) l = json_object_get(json_object_get(l, "reaction_max_n"), joint);
  else l = json_object_get(l, key);
  assert_true(json_is_number(l));
  return json_number_value(l);
}

static void test_reactions_match_inverse_dynamics(void **state) {
  (void)state;
  NEEDS_BULLET();
  static fb_run r;
  run(&r, "analytic, bullet-ideal-nominal", NULL, 0);
  json_t *sum = fb_report_summary_json(&r, NULL);
  const char *joints[4] = {"ground_crank", "crank_coupler", "coupler_follower", "follower_ground"};
  double w = 0.0;
  for (int j = 0; j < 4; j++) {
    const double a = load(sum, 0, NULL, joints[j]), b = load(sum, 1, NULL, joints[j]);
    w = fmax(w, fabs(b - a) / a);
  }
  const double ta = load(sum, 0, "drive_torque_abs_max_n_m", NULL);
  const double tb = load(sum, 1, "drive_torque_abs_max_n_m", NULL);
  report_residual("bullet reaction peaks vs inverse dynamics", w, LOADS_REL_TOL);
  report_residual("bullet drive torque peak vs inverse dynamics", fabs(tb - ta) / ta, LOADS_REL_TOL);
  assert_true(w < LOADS_REL_TOL);
  assert_true(fabs(tb - ta) / ta < LOADS_REL_TOL);
  json_decref(sum);
  fb_run_free(&r);
}

#if FB_HAVE_BULLET /* used only by the single-impact test of builds with Bullet */
/* engine id's single impact of d as fourbar impact runs it (its table's
 * law: the world its kit binding builds), Bullet's settings bt */
static fb_status engine_impact(fb_engine_id id, fb_impact_result *out, const fb_impact_def *d,
                               const fb_bullet_opts *bt) {
  const fb_engine *e = fb_engine_get(id, NULL);
  assert_non_null(e);
  assert_non_null(e->impact);
  fb_impact_opts o = {.bullet = *bt};
  return e->impact->law(out, d, &o, NULL);
}

static fb_impact_def impact_def(fb_law_kind kind) {
  fb_impact_def d;
  memset(&d, 0, sizeof d);
  d.law = fb_contact_law_default();
  d.law.kind = kind;
  d.law.restitution = 0.9;
  if (kind == FB_LAW_RESTITUTION) d.law.exponent = 1.0;
  d.mass = 1.0;
  d.speed = 1.0;
  d.stepper = FB_STEPPER_WORLD;
  d.quick_iterations = 20;
  d.law.mass = d.mass;
  d.h = 1e-6;
  return d;
}
#endif

static void test_single_impact_matched_and_own_conversion(void **state) {
  (void)state;
  NEEDS_BULLET();
#if FB_HAVE_BULLET
  const fb_law_kind kinds[2] = {FB_LAW_HERTZ, FB_LAW_RESTITUTION};
  for (int i = 0; i < 2; i++) {
    fb_impact_def d = impact_def(kinds[i]);
    fb_impact_result ref, ode, bt, own, ode_own, si;
    assert_int_equal(fb_impact_reference(&ref, &d, NULL), FB_OK);
    d.h = IMPACT_H_OMEGA * ref.contact_duration / M_PI;
    fb_bullet_opts o = fb_bullet_opts_default();
    d.mapping = FB_MAPPING_MATCHED;
    assert_int_equal(engine_impact(FB_ENGINE_ODE, &ode, &d, &o), FB_OK);
    assert_int_equal(engine_impact(FB_ENGINE_BULLET, &bt, &d, &o), FB_OK);
    fb_bullet_opts o_si = o;
    o_si.solver = FB_BULLET_SEQUENTIAL_IMPULSE;
    assert_int_equal(engine_impact(FB_ENGINE_BULLET, &si, &d, &o_si), FB_OK);
    d.mapping = FB_MAPPING_SECANT; /* Bullet's own k, c -> ERP, CFM */
    assert_int_equal(engine_impact(FB_ENGINE_BULLET, &own, &d, &o), FB_OK);
    assert_int_equal(engine_impact(FB_ENGINE_ODE, &ode_own, &d, &o), FB_OK);
    const double er = (bt.restitution - ref.restitution) / ref.restitution;
    const double ep = (bt.penetration_max - ref.penetration_max) / ref.penetration_max;
    const double eo = (own.restitution - ref.restitution) / ref.restitution;
    report_residual(fb_law_name(kinds[i]), 0, 0);
    report_residual("  bullet matched restitution rel", er, IMPACT_MATCHED_REL_TOL);
    report_residual("  bullet matched penetration rel", ep, IMPACT_MATCHED_REL_TOL);
    report_residual("  bullet own conversion restitution rel", eo, 0);
    report_residual("  bullet vs ode restitution", bt.restitution - ode.restitution,
                    IMPACT_BULLET_VS_ODE_TOL);
    assert_true(fabs(er) < IMPACT_MATCHED_REL_TOL);
    assert_true(fabs(ep) < IMPACT_MATCHED_REL_TOL);
    assert_near(bt.restitution, ode.restitution, IMPACT_BULLET_VS_ODE_TOL);
    assert_near(bt.penetration_max / ref.penetration_max,
                ode.penetration_max / ref.penetration_max, IMPACT_BULLET_VS_ODE_TOL);
    assert_near(si.restitution, bt.restitution, SI_VS_MLCP_TOL);
    /* Bullet's own conversion: the loss users see, the same as ODE's
     * standard map */
    assert_true(eo < 0.0);
    assert_true(fabs(eo) > OWN_CONVERSION_LOSS_FACTOR * fabs(er));
    assert_near(own.restitution, ode_own.restitution, IMPACT_BULLET_VS_ODE_TOL);
  }
#endif
}

/* the ideal models (nominal and stack-up) against the analytic peaks of
 * their own lengths: rod omega and alpha, slider x, v and a, on the test
 * case and on flores, each at its automatic step */
static void test_slider_crank_ideal_matches_analytic(void **state) {
  (void)state;
  NEEDS_BULLET();
  for (int own = 1; own >= 0; own--) {
    static fb_run r;
    sc_run(&r, own, "bullet-ideal-nominal, bullet-ideal-stackup", NULL, 0);
    assert_true(r.h_auto);
    for (int i = 0; i < 2; i++) {
      const fb_model_result *m = &r.model[i];
      assert_true(m->has_error);
      const fb_body_error *rod = &m->error.body[0], *sl = &m->error.body[1];
      const double wo = worst(rod->omega_max_rel, rod->omega_min_rel, rod->alpha_max_rel,
                              rod->alpha_min_rel);
      const double ws = fmax(worst(sl->omega_max_rel, sl->omega_min_rel, sl->alpha_max_rel,
                                   sl->alpha_min_rel),
                             fmax(fabs(sl->pos_max_rel), fabs(sl->pos_min_rel)));
      report_residual(m->run.name, 0, 0);
      report_residual(own ? "  test case rod omega/alpha rel" : "  flores rod omega/alpha rel", wo,
                      SC_PEAK_REL_TOL);
      report_residual(own ? "  test case slider x/v/a rel" : "  flores slider x/v/a rel", ws,
                      SC_PEAK_REL_TOL);
      assert_true(wo < SC_PEAK_REL_TOL);
      assert_true(ws < SC_PEAK_REL_TOL);
      assert_true(m->error.crank_angle_err_max < CRANK_ANGLE_TOL_RAD);
    }
    fb_run_free(&r);
  }
}

/* signed extremes of a series column over t >= t0 */
static void column_range(const fb_series *s, const double *v, double t0, double *lo, double *hi) {
  *lo = INFINITY, *hi = -INFINITY;
  for (size_t k = 0; k < s->n; k++)
    if (s->t[k] >= t0) *lo = fmin(*lo, v[k]), *hi = fmax(*hi, v[k]);
}

/* the ideal slider-crank's reactions (pin rows', guide's) and drive torque
 * against its inverse dynamics (the analytic model's loads) */
static void test_slider_crank_reactions_match_inverse_dynamics(void **state) {
  (void)state;
  NEEDS_BULLET();
  static fb_run r;
  sc_run(&r, 0, "analytic, bullet-ideal-nominal", NULL, 0);
  json_t *sum = fb_report_summary_json(&r, NULL);
  const char *joints[4] = {"ground_crank", "crank_coupler", "coupler_slider", "slider_ground"};
  double w = 0.0;
  for (int j = 0; j < 4; j++) {
    const double a = load(sum, 0, NULL, joints[j]), b = load(sum, 1, NULL, joints[j]);
    w = fmax(w, fabs(b - a) / a);
  }
  const double ta = load(sum, 0, "drive_torque_abs_max_n_m", NULL);
  const double tb = load(sum, 1, "drive_torque_abs_max_n_m", NULL);
  /* the guide's force on the ground, signed: (0, -N) */
  const fb_series *sa = &r.model[0].run.series, *sb = &r.model[1].run.series;
  assert_true(sa->has_loads && sb->has_loads);
  double alo, ahi, blo, bhi, xlo, xhi;
  column_range(sa, sa->reaction[3][1], r.t_window, &alo, &ahi);
  column_range(sb, sb->reaction[3][1], r.t_window, &blo, &bhi);
  column_range(sb, sb->reaction[3][0], r.t_window, &xlo, &xhi);
  const double scale = fmax(fabs(alo), fabs(ahi));
  const double wg = fmax(fabs(blo - alo), fabs(bhi - ahi)) / scale;
  report_residual("slider-crank reaction peaks vs inverse dynamics", w, SC_LOADS_REL_TOL);
  report_residual("slider-crank drive torque peak", fabs(tb - ta) / ta, SC_LOADS_REL_TOL);
  report_residual("slider-crank guide force y, signed extremes", wg, SC_LOADS_REL_TOL);
  assert_true(w < SC_LOADS_REL_TOL);
  assert_true(fabs(tb - ta) / ta < SC_LOADS_REL_TOL);
  assert_true(wg < SC_LOADS_REL_TOL);
  /* a frictionless guide: no force along x */
  assert_true(fmax(fabs(xlo), fabs(xhi)) <= SC_LOADS_REL_TOL * scale);
  json_decref(sum);
  fb_run_free(&r);
}

/* the first n impacts' peak force and penetration against the reference's */
static double sc_first_impacts(const fb_model_result *m, int n, const char *what) {
  assert_true(m->has_ref_error);
  assert_true(m->ref_error.first_impacts >= n);
  double w = 0.0;
  for (int i = 0; i < n; i++) {
    char name[96];
    snprintf(name, sizeof name, "  %s impact %d force rel", what, i + 1);
    report_residual(name, m->ref_error.first_impact_force_rel[i], SC_IMPACT_REL_TOL);
    snprintf(name, sizeof name, "  %s impact %d penetration rel", what, i + 1);
    report_residual(name, m->ref_error.first_impact_penetration_rel[i], SC_IMPACT_REL_TOL);
    w = fmax(w, fmax(fabs(m->ref_error.first_impact_force_rel[i]),
                     fabs(m->ref_error.first_impact_penetration_rel[i])));
  }
  return w;
}

/* the impact law's first impact at the automatic step: the step's mean
 * under its onset spike, below the reference's peak */
static void sc_onset_spike(const fb_model_result *imp) {
  const double f1 = imp->ref_error.first_impact_force_rel[0];
  const double p1 = imp->ref_error.first_impact_penetration_rel[0];
  report_residual("  impact law, impact 1 force rel (onset spike)", f1, SC_IMPACT_ONSET_SPIKE_TOL);
  report_residual("  impact law, impact 1 penetration rel", p1, SC_IMPACT_ONSET_SPIKE_TOL);
  assert_true(f1 < 0.0 && f1 > -SC_IMPACT_ONSET_SPIKE_TOL);
  assert_true(p1 < 0.0 && p1 > -SC_IMPACT_ONSET_SPIKE_TOL);
}

/* flores as shipped (h = auto, matched mapping; its impact law's damper
 * set for the case's restitution, 480 N s/m): both laws' first impacts
 * within 1 % of the reference's */
static void test_slider_crank_clearance_matches_reference(void **state) {
  (void)state;
  NEEDS_BULLET();
  static fb_run r;
  sc_run(&r, 0,
         "bullet-clearance-impact, bullet-clearance-restitution, reference, reference-restitution",
         NULL, 0);
  assert_true(r.h_auto);
  const fb_model_result *imp = find(&r, "bullet-clearance-impact");
  const fb_model_result *res = find(&r, "bullet-clearance-restitution");
  assert_string_equal(imp->ref_name, "reference");
  assert_string_equal(res->ref_name, "reference-restitution");
  report_residual("flores, automatic step", 0, 0);
  assert_true(sc_first_impacts(res, SC_IMPACTS_COMPARED, "restitution") < SC_IMPACT_REL_TOL);
  assert_true(sc_first_impacts(imp, SC_IMPACTS_COMPARED, "impact law") < SC_IMPACT_REL_TOL);
  /* the effective mass the rows were matched on: the rod about B and the
   * slider along x, positive, varying with the configuration, below the
   * two bodies' masses */
  const fb_contact_provenance *p = &imp->run.provenance[FB_JOINT_C];
  assert_true(p->contact_steps > 0);
  assert_true(p->mass_eff_min > 0.0 && p->mass_eff_min < p->mass_eff_max);
  assert_true(p->mass_eff_max <= r.c.link[1].mass + r.c.link[2].mass);
  fb_run_free(&r);
}

/* the test case: at its automatic step the restitution law's first impact
 * within 1 % and the impact law's the step's mean under its onset spike;
 * at half that step both laws' first impact within 1 % */
static void test_slider_crank_clearance_test_case(void **state) {
  (void)state;
  NEEDS_BULLET();
  static fb_run r;
  const char *models =
      "bullet-clearance-impact, bullet-clearance-restitution, reference, reference-restitution";
  sc_run(&r, 1, models, NULL, 0);
  assert_true(r.h_auto);
  const double h = r.scene.solver.h;
  report_residual("test case, automatic step [s]", h, 0);
  assert_true(sc_first_impacts(find(&r, "bullet-clearance-restitution"), 1, "restitution") <
              SC_IMPACT_REL_TOL);
  sc_onset_spike(find(&r, "bullet-clearance-impact"));
  fb_run_free(&r);
  char hs[64];
  snprintf(hs, sizeof hs, "solver.h_s=%.17g", SC_HALF_STEP_FACTOR * h);
  const char *sets[] = {hs};
  sc_run(&r, 1, models, sets, 1);
  report_residual("test case, half the automatic step [s]", SC_HALF_STEP_FACTOR * h, 0);
  assert_true(sc_first_impacts(find(&r, "bullet-clearance-impact"), 1, "impact law") <
              SC_IMPACT_REL_TOL);
  assert_true(sc_first_impacts(find(&r, "bullet-clearance-restitution"), 1, "restitution") <
              SC_IMPACT_REL_TOL);
  fb_run_free(&r);
}

static void test_bullet_keys_and_refusal(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  const char *bad_solver[] = {"bullet.solver=pgs"};
  fb_test_paper_case(&c, NULL, 0);
  assert_int_equal(c.bullet.solver, FB_BULLET_MLCP_DANTZIG);
  assert_int_equal(c.bullet.iterations, 100);
  const char *path = getenv("FOURBAR_CASES_DIR");
  char p[4096];
  snprintf(p, sizeof p, "%s/paper_crank_rocker.ini", path ? path : "cases");
  assert_int_not_equal(fb_casefile_load(&c, p, bad_solver, 1, &d), FB_OK);
  assert_non_null(strstr(d.msg, "sequential-impulse or mlcp-dantzig"));
  const char *bad_iter[] = {"bullet.iterations=0"};
  assert_int_equal(fb_casefile_load(&c, p, bad_iter, 1, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "iterations must be 1 to 100000"));
  const char *si[] = {"bullet.solver=sequential-impulse", "bullet.iterations=50"};
  assert_int_equal(fb_casefile_load(&c, p, si, 2, &d), FB_OK);
  assert_int_equal(c.bullet.solver, FB_BULLET_SEQUENTIAL_IMPULSE);
  assert_int_equal(c.bullet.iterations, 50);
  /* a build without Bullet refuses its models with the how-to */
  const char *models[] = {"run.models=bullet-clearance-impact"};
  fb_status st = fb_casefile_load(&c, p, models, 1, &d);
  if (FB_HAVE_BULLET) {
    assert_int_equal(st, FB_OK);
    assert_true(fb_engine_available(FB_ENGINE_BULLET));
  } else {
    assert_int_not_equal(st, FB_OK);
    assert_non_null(strstr(d.msg, "libbullet-dev"));
    assert_non_null(strstr(d.msg, "-Dbullet=enabled"));
    assert_null(fb_engine_get(FB_ENGINE_BULLET, &d));
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_bullet_keys_and_refusal),
      cmocka_unit_test(test_ideal_models_match_analytic),
      cmocka_unit_test(test_clearance_impact_matches_reference_and_ode),
      cmocka_unit_test(test_reactions_match_inverse_dynamics),
      cmocka_unit_test(test_single_impact_matched_and_own_conversion),
      cmocka_unit_test(test_slider_crank_ideal_matches_analytic),
      cmocka_unit_test(test_slider_crank_reactions_match_inverse_dynamics),
      cmocka_unit_test(test_slider_crank_clearance_matches_reference),
      cmocka_unit_test(test_slider_crank_clearance_test_case),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
