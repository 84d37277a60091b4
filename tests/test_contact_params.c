/* fourbar contact-params: the translations of a linear contact into ODE,
 * Gazebo, MuJoCo and Bullet parameters (engine_params.h), each verified by a single
 * impact simulated in the engine with exactly those parameters against the
 * continuous law (the GSL reference of impact.h).
 *
 *      v0 |
 *         v
 *        ( m )      one body, no gravity, meets the ground plane
 *   ==============  spring k, damper c (cr 0.9 at the design mass) */
#include <math.h>
#include <string.h>

#include "contact_params.h"
#include "engine_params.h"
#include "fb_config.h"
#include "fb_test.h"
#include "impact.h"
#include "impact_bullet.h"
#include "impact_mujoco.h"
#include "kit_impact.h"
#include "ode_kit.h"
#include "resolution.h"

/* the issue's acceptance bounds: restitution within 1 %, peak penetration
 * within 2 % of the continuous law's */
#define RESTITUTION_REL_TOL 0.01
#define PENETRATION_REL_TOL 0.02
/* what the standard row and the continuous MuJoCo form must be seen to lose
 * (so the tests discriminate): measured -14 % (standard, h omega 0.1) and
 * -46 % penetration (MuJoCo designed at 0.29 kg used at 0.95 kg); a quarter
 * of each */
#define STANDARD_LOSS_MIN 0.035
#define MASS_MISMATCH_LOSS_MIN 0.1
/* round trip through Gazebo's kp/kd formula: a few ulp of ERP and CFM */
#define ROUND_TRIP_REL_TOL 1e-12

static const double K = 1e7, CR = 0.9, V = 1.0;

typedef struct {
  fb_impact_result ref;
  double t_max;
} target;

static target law_impact(const fb_linear_contact *lc) {
  fb_impact_def d;
  memset(&d, 0, sizeof d);
  d.law = fb_contact_law_default();
  d.law.kind = FB_LAW_LINEAR;
  d.law.stiffness = lc->k;
  d.law.exponent = 1.0;
  d.law.damping = lc->c;
  d.law.mass = lc->m;
  d.mass = lc->m;
  d.speed = V;
  d.h = lc->h;
  d.stepper = FB_STEPPER_WORLD;
  d.quick_iterations = 20;
  fb_diag diag;
  target t;
  assert_int_equal(fb_impact_reference(&t.ref, &d, &diag), FB_OK);
  t.t_max = 100.0 * t.ref.contact_duration;
  return t;
}

static double rel(double x, double ref) { return (x - ref) / fabs(ref); }

static void expect_close(const char *what, const fb_impact_result *r, const target *t) {
  const double er = rel(r->restitution, t->ref.restitution);
  const double ep = rel(r->penetration_max, t->ref.penetration_max);
  if (fb_test_verbose())
    fprintf(stderr, "  %-32s restitution %+.3e  penetration %+.3e\n", what, er, ep);
  if (!(fabs(er) <= RESTITUTION_REL_TOL && fabs(ep) <= PENETRATION_REL_TOL))
    fail_msg("%s: restitution %+.3e, penetration %+.3e against the law", what, er, ep);
}

/* the issue's single impact: 0.1 kg at 1 m/s, k = 1e7 N/m, cr 0.9,
 * h omega_c = 0.1 */
static fb_linear_contact single(void) {
  const double m = 0.1;
  fb_linear_contact lc = {K, fb_params_damper_for_restitution(K, m, CR), m, 0.1 / sqrt(K / m)};
  return lc;
}

/* a fixed row's single impact in ODE, as contact-params verifies it (the
 * world ODE's kit binding builds) */
static fb_status ode_row(fb_impact_result *out, double mass, double speed, double h, double erp,
                         double cfm, double max_vel, double t_max, double onset_phase,
                         fb_diag *diag) {
  return fb_kit_impact_row(out, &fb_ode_kit, mass, speed, h, erp, cfm, max_vel, t_max,
                           onset_phase, diag);
}

/* a binding without ODE's correcting speed limit is refused a finite one by
 * name, not run without it */
static void test_fixed_row_needs_the_speed_limit(void **state) {
  (void)state;
  fb_kit_binding no_limit = fb_ode_kit;
  no_limit.contact_speed_limit = 0;
  fb_impact_result r;
  fb_diag d;
  assert_int_equal(fb_kit_impact_row(&r, &no_limit, 0.1, V, 1e-5, 0.2, 1e-7, 0.01, 0.01, 0.0, &d),
                   FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "max_vel 0.01 m/s"));
  assert_int_equal(fb_kit_impact_row(&r, &no_limit, 0.1, V, 1e-5, 0.2, 1e-7, INFINITY, 0.01, 0.0,
                                     &d), FB_OK);
}

static void test_ode_and_gazebo_single_impact(void **state) {
  (void)state;
  fb_linear_contact lc = single();
  target t = law_impact(&lc);
  assert_near(t.ref.restitution, CR, 1e-6); /* the damper gives cr */
  fb_diag d;
  fb_ode_row matched, standard, gz_row;
  assert_int_equal(fb_params_ode_matched(&lc, &matched, &d), FB_OK);
  assert_int_equal(fb_params_ode_standard(&lc, &standard, &d), FB_OK);
  fb_impact_result r;
  assert_int_equal(ode_row(&r, lc.m, V, lc.h, matched.erp, matched.cfm, INFINITY, t.t_max,
                           0.0, &d), FB_OK);
  expect_close("ode matched", &r, &t);
  /* Gazebo: kp, kd printed, then Gazebo's own formula back to ERP/CFM */
  fb_spring_damper gz;
  fb_params_spring_damper_of_row(&matched, lc.h, &gz);
  assert_int_equal(fb_params_row_of_spring_damper(&gz, lc.h, &gz_row, &d), FB_OK);
  assert_near(gz_row.erp, matched.erp, ROUND_TRIP_REL_TOL * matched.erp);
  assert_near(gz_row.cfm, matched.cfm, ROUND_TRIP_REL_TOL * matched.cfm);
  const double speed_needed = fb_params_correcting_velocity(&matched, lc.h, t.ref.penetration_max);
  assert_int_equal(ode_row(&r, lc.m, V, lc.h, gz_row.erp, gz_row.cfm, 1.01 * speed_needed,
                           t.t_max, 0.0, &d), FB_OK);
  expect_close("gazebo kp/kd (max_vel just enough)", &r, &t);
  /* the standard row (what the kp/kd formula gives from k and c) loses */
  assert_int_equal(ode_row(&r, lc.m, V, lc.h, standard.erp, standard.cfm, INFINITY, t.t_max,
                           0.0, &d), FB_OK);
  assert_true(rel(r.restitution, t.ref.restitution) < -STANDARD_LOSS_MIN);
  /* Gazebo's default max_vel 0.01 m/s cuts the spring: the body sinks */
  (void)ode_row(&r, lc.m, V, lc.h, gz_row.erp, gz_row.cfm, 0.01, t.t_max, 0.0, &d);
  assert_true(r.penetration_max > (1.0 + MASS_MISMATCH_LOSS_MIN) * t.ref.penetration_max);
}

/* the paper's crank-coupler joint: effective mass 0.09 to 0.95 kg; the ODE
 * row is a force law (a spring a, a damper b), so one row designed at the
 * geometric mean holds over the range */
static void test_ode_over_the_mass_range(void **state) {
  (void)state;
  const double m_min = 0.09, m_max = 0.95, m0 = sqrt(m_min * m_max);
  const double c = fb_params_damper_for_restitution(K, m0, CR);
  const double h = 0.1 / sqrt(K / m_min);
  fb_linear_contact lc0 = {K, c, m0, h};
  fb_diag d;
  fb_ode_row row;
  assert_int_equal(fb_params_ode_matched(&lc0, &row, &d), FB_OK);
  const double masses[2] = {m_min, m_max};
  for (int i = 0; i < 2; i++) {
    fb_linear_contact lc = {K, c, masses[i], h};
    target t = law_impact(&lc);
    fb_impact_result r;
    assert_int_equal(ode_row(&r, lc.m, V, h, row.erp, row.cfm, INFINITY, t.t_max, 0.0, &d),
                     FB_OK);
    expect_close(i ? "ode matched at 0.95 kg" : "ode matched at 0.09 kg", &r, &t);
  }
}

static void test_mujoco_forms(void **state) {
  (void)state;
  fb_linear_contact lc = single();
  fb_mujoco_params direct, cont, std;
  fb_params_mujoco_direct_matched(&lc, &direct);
  fb_params_mujoco_direct_continuous(&lc, &cont);
  fb_diag d;
  assert_int_equal(fb_params_mujoco_standard(&lc, &std, &d), FB_OK);
  /* oracle: the matched form tends to the continuous one as h -> 0
   * (kappa = k/m (1 + O(h)), beta = c/m (1 + O(h))) */
  fb_linear_contact fine = lc;
  fine.h = lc.h * 1e-4;
  fb_mujoco_params df;
  fb_params_mujoco_direct_matched(&fine, &df);
  assert_near(df.kappa, cont.kappa, 1e-3 * cont.kappa);
  assert_near(df.beta, cont.beta, 1e-3 * cont.beta);
  /* the standard form stands for the same kappa, beta */
  assert_near(2.0 / std.solref[0], direct.beta, 1e-12 * direct.beta);
  /* no damper, or a time constant below 2 h: refused with the reason */
  fb_mujoco_params hs_unused;
  fb_linear_contact undamped = lc;
  undamped.c = 0.0;
  assert_int_equal(fb_params_mujoco_standard(&undamped, &hs_unused, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "direct form"));
  /* a damper with c/m = 3/h would ask for timeconst 2h/3, below MuJoCo's
   * clamp 2 h; the matched beta = (1 - e^{-c h/m})/h < 1/h keeps it above */
  fb_linear_contact heavy = lc;
  heavy.c = 3.0 * lc.m / lc.h;
  fb_mujoco_params hs;
  assert_int_equal(fb_params_mujoco_standard(&heavy, &hs, &d), FB_OK);
  assert_true(hs.solref[0] >= 2.0 * lc.h);
#if FB_HAVE_MUJOCO
  target t = law_impact(&lc);
  fb_impact_result r;
  assert_int_equal(fb_impact_mujoco(&r, lc.m, V, lc.h, direct.solref, direct.solimp, t.t_max, 0.0, &d),
                   FB_OK);
  expect_close("mujoco direct", &r, &t);
  assert_int_equal(fb_impact_mujoco(&r, lc.m, V, lc.h, std.solref, std.solimp, t.t_max, 0.0, &d),
                   FB_OK);
  expect_close("mujoco standard", &r, &t);
  /* MuJoCo's parameters are per unit of effective mass: the form designed
   * at 0.29 kg, handed a 0.95 kg body, keeps the light body's motion */
  const double m0 = sqrt(0.09 * 0.95);
  fb_linear_contact design = {K, fb_params_damper_for_restitution(K, m0, CR), m0,
                              0.1 / sqrt(K / 0.09)};
  fb_linear_contact heavy_body = design;
  heavy_body.m = 0.95;
  fb_mujoco_params at_design, at_mass;
  fb_params_mujoco_direct_matched(&design, &at_design);
  fb_params_mujoco_direct_matched(&heavy_body, &at_mass);
  target th = law_impact(&heavy_body);
  assert_int_equal(fb_impact_mujoco(&r, 0.95, V, design.h, at_design.solref, at_design.solimp,
                                    th.t_max, 0.0, &d), FB_OK);
  assert_true(rel(r.penetration_max, th.ref.penetration_max) < -MASS_MISMATCH_LOSS_MIN);
  assert_int_equal(fb_impact_mujoco(&r, 0.95, V, design.h, at_mass.solref, at_mass.solimp,
                                    th.t_max, 0.0, &d), FB_OK);
  expect_close("mujoco direct at the body's mass", &r, &th);
#endif
}

/* Bullet: the printed stiffness and damping through Bullet's own contact
 * (setContactStiffnessAndDamping, btSequentialImpulseConstraintSolver), on
 * the single impact and at both ends of the paper joint's mass range; the
 * law's k and c pasted as they are lose like ODE's standard row */
static void test_bullet_contact(void **state) {
  (void)state;
#if !FB_HAVE_BULLET
  skip(); /* fb_impact_bullet_contact exists only in builds with Bullet */
#else
  fb_linear_contact lc = single();
  target t = law_impact(&lc);
  fb_diag d;
  fb_ode_row matched;
  assert_int_equal(fb_params_ode_matched(&lc, &matched, &d), FB_OK);
  fb_spring_damper sd;
  fb_params_spring_damper_of_row(&matched, lc.h, &sd);
  fb_impact_result r;
  assert_int_equal(fb_impact_bullet_contact(&r, lc.m, V, lc.h, sd.kp, sd.kd, t.t_max, 0.0, &d), FB_OK);
  expect_close("bullet stiffness/damping", &r, &t);
  assert_int_equal(fb_impact_bullet_contact(&r, lc.m, V, lc.h, lc.k, lc.c, t.t_max, 0.0, &d), FB_OK);
  assert_true(rel(r.restitution, t.ref.restitution) < -STANDARD_LOSS_MIN);
  /* the paper's crank-coupler joint: one pair designed at the geometric mean */
  const double m_min = 0.09, m_max = 0.95, m0 = sqrt(m_min * m_max);
  const double c = fb_params_damper_for_restitution(K, m0, CR);
  const double h = 0.1 / sqrt(K / m_min);
  fb_linear_contact lc0 = {K, c, m0, h};
  assert_int_equal(fb_params_ode_matched(&lc0, &matched, &d), FB_OK);
  fb_params_spring_damper_of_row(&matched, h, &sd);
  const double masses[2] = {m_min, m_max};
  for (int i = 0; i < 2; i++) {
    fb_linear_contact lm = {K, c, masses[i], h};
    target tm = law_impact(&lm);
    assert_int_equal(fb_impact_bullet_contact(&r, lm.m, V, h, sd.kp, sd.kd, tm.t_max, 0.0, &d), FB_OK);
    expect_close(i ? "bullet at 0.95 kg" : "bullet at 0.09 kg", &r, &tm);
  }
  /* bad input: h k + c <= 0 is refused with the rule */
  assert_int_equal(fb_impact_bullet_contact(&r, 0.1, V, 1e-5, 1e6, -20.0, 1.0, 0.0, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "h stiffness + damping > 0"));
#endif
}

/* ---- contact-params as a user runs it (contact_params.h, issue 44) ------- */

/* the linear equivalent of a law's impact, against the linear law's closed
 * form: the same restitution and peak penetration to rounding (the closed
 * form and the equivalent invert each other) */
#define EQUIVALENT_REL_TOL 1e-9

static void test_linear_equivalent(void **state) {
  (void)state;
  const double crs[] = {0.3, 0.8, 0.999, 1.0};
  for (int i = 0; i < 4; i++) {
    double k, c;
    fb_diag d;
    assert_int_equal(fb_params_linear_equivalent(crs[i], 2.5e-5, 0.5, 0.3, &k, &c, &d), FB_OK);
    fb_linear_contact lc = {k, c, 0.5, 1e-7};
    fb_impact_def def;
    memset(&def, 0, sizeof def);
    def.law = fb_contact_law_default();
    def.law.kind = FB_LAW_LINEAR;
    def.law.stiffness = k;
    def.law.exponent = 1.0;
    def.law.damping = c;
    def.law.mass = lc.m;
    def.mass = lc.m;
    def.speed = 0.3;
    def.h = lc.h;
    fb_impact_result r;
    assert_true(fb_impact_closed_form(&r, &def));
    assert_near(r.restitution, crs[i], EQUIVALENT_REL_TOL);
    assert_near(r.penetration_max, 2.5e-5, EQUIVALENT_REL_TOL * 2.5e-5);
  }
  /* undamped: peak factor 1, delta = v / omega */
  assert_near(fb_params_peak_factor(0.0), 1.0, 1e-15);
  double k, c;
  fb_diag d;
  assert_int_equal(fb_params_linear_equivalent(0.1, 2.5e-5, 0.5, 0.3, &k, &c, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "restitution 0.1"));
}

/* every number a row prints is finite, and what ODE, Gazebo and Bullet
 * need positive is positive (CFM, kp, max_vel; MuJoCo's direct solref
 * negative, solimp in (0, 1)) */
static void expect_printable(const char *what, const fb_cp_rows *rw) {
  const double xs[] = {rw->ode.erp, rw->ode.cfm, rw->gazebo.kp, rw->gazebo.kd, rw->max_vel,
                       rw->mj_direct.solref[0], rw->mj_direct.solref[1], rw->mj_at[0].solref[0],
                       rw->mj_at[0].solref[1]};
  for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++)
    if (!isfinite(xs[i])) fail_msg("%s: value %zu of its rows is %g", what, i, xs[i]);
  if (!(rw->ode.erp > 0.0 && rw->ode.cfm > 0.0 && rw->gazebo.kp > 0.0 && rw->max_vel > 0.0 &&
        rw->gazebo.kp * rw->lc.h + rw->gazebo.kd > 0.0 && rw->mj_direct.solref[0] < 0.0 &&
        rw->mj_direct.solref[1] <= 0.0 && rw->mj_direct.solimp[0] > 0.0 &&
        rw->mj_direct.solimp[0] < 1.0))
    fail_msg("%s: a value outside its engine's range (ERP %g, CFM %g, kp %g, kd %g, max_vel %g, "
             "solref %g %g)", what, rw->ode.erp, rw->ode.cfm, rw->gazebo.kp, rw->gazebo.kd,
             rw->max_vel, rw->mj_direct.solref[0], rw->mj_direct.solref[1]);
}

/* the checks of a step: every recommended one faithful within the issue's
 * bounds (restated here: the checks' own flag is what is tested); returns
 * the engines seen among the recommended, as a bit set (ode 1, gazebo 2,
 * mujoco 4, bullet 8) */
static int expect_faithful(const char *what, const fb_cp_step *st) {
  int seen = 0;
  for (int i = 0; i < st->n_checks; i++) {
    const fb_cp_check *x = &st->checks[i];
    if (!x->recommended) continue;
    if (fb_test_verbose())
      fprintf(stderr, "  %-10s %-8s %-15s %6.3g kg restitution %+.2e penetration %+.2e\n", what,
              x->engine, x->form, x->mass, x->restitution_rel, x->penetration_rel);
    if (!(x->ran && x->faithful && fabs(x->restitution_rel) <= RESTITUTION_REL_TOL &&
          fabs(x->penetration_rel) <= PENETRATION_REL_TOL))
      fail_msg("%s: %s %s at %g kg: restitution %+.3e, penetration %+.3e (%s)", what, x->engine,
               x->form, x->mass, x->restitution_rel, x->penetration_rel, x->ran ? "ran" : x->why);
    seen |= strcmp(x->engine, "ode") == 0 ? 1 : strcmp(x->engine, "gazebo") == 0 ? 2
          : strcmp(x->engine, "mujoco") == 0 ? 4 : 8;
  }
  return seen;
}

static int engines_built(void) { return 1 | 2 | (FB_HAVE_MUJOCO ? 4 : 0) | (FB_HAVE_BULLET ? 8 : 0); }

/* the issue's user: 0.5 kg at 0.3 m/s on steel Hertz (K = 1.5e10 N/m^1.5),
 * restitution 0.8, at 2.5e-4 s, MuJoCo's 2 ms and Gazebo's 1 ms. Before:
 * rows printed at 2.5e-4 s with restitution 1.67 and 2.52, exit 0. Now:
 * the contact itself is not recommended at those steps (h omega_c >= 2.5),
 * largest_step_s is given, and at_step rows are verified in every engine */
static void test_issue_user_at_coarse_steps(void **state) {
  (void)state;
  const double hs[] = {2.5e-4, 2e-3, 1e-3};
  for (int i = 0; i < 3; i++) {
    fb_cp_request q;
    fb_cp_request_default(&q);
    q.law = FB_LAW_HERTZ;
    q.stiffness = 1.5e10;
    q.restitution = 0.8;
    q.mass_min = q.mass_max = 0.5;
    q.speed = 0.3;
    q.h = hs[i];
    static fb_cp_result o;
    fb_diag d;
    assert_int_equal(fb_cp_run(&o, &q, &d), FB_OK);
    assert_int_equal(o.failed, 0);
    assert_false(o.given.recommended);
    assert_int_equal(o.given.n_checks, 0); /* beyond the rule: no rows shown as verified */
    assert_true(isfinite(o.largest_step) && o.largest_step > 0.0 && o.largest_step < hs[i]);
    assert_true(o.largest_h_omega <= FB_H_OMEGA_C_BOUND);
    assert_true(o.has_at_step);
    char what[64];
    snprintf(what, sizeof what, "at_step %g s", hs[i]);
    assert_int_equal(expect_faithful(what, &o.at_step), engines_built());
    expect_printable(what, &o.at_step.rows);
    /* the same restitution (the contact's own, linear) and a softer spring */
    assert_near(o.at_step.rows.restitution[0], 0.8, 1e-6);
    assert_true(o.at_k < o.k);
  }
}

/* item 2 "without special flags": the issue's user with no step (the
 * automatic one) and engine_steps on (the CLI without --h-s) gets the
 * at_step contact at MuJoCo's 2 ms and Gazebo's 1 ms as well, each with the
 * same restitution, verified in every engine; without engine_steps none */
static void test_engine_default_steps(void **state) {
  (void)state;
  fb_cp_request q;
  fb_cp_request_default(&q);
  q.law = FB_LAW_HERTZ;
  q.stiffness = 1.5e10;
  q.restitution = 0.8;
  q.mass_min = q.mass_max = 0.5;
  q.speed = 0.3;
  static fb_cp_result o;
  fb_diag d;
  assert_int_equal(fb_cp_run(&o, &q, &d), FB_OK);
  assert_int_equal(o.n_engine_steps, 0);
  q.engine_steps = 1;
  assert_int_equal(fb_cp_run(&o, &q, &d), FB_OK);
  assert_int_equal(o.failed, 0);
  assert_true(o.given.recommended);
  assert_int_equal(o.n_engine_steps, FB_CP_ENGINE_STEPS);
  const char *engines[] = {"mujoco", "gazebo"};
  const double hs[] = {2e-3, 1e-3};
  for (int i = 0; i < FB_CP_ENGINE_STEPS; i++) {
    assert_string_equal(o.engine_step[i].engine, engines[i]);
    assert_near(o.engine_step[i].h, hs[i], 0.0);
    assert_near(o.engine_step[i].step.rows.lc.h, hs[i], 0.0);
    char what[64];
    snprintf(what, sizeof what, "%s default %g s", engines[i], hs[i]);
    assert_int_equal(expect_faithful(what, &o.engine_step[i].step), engines_built());
    expect_printable(what, &o.engine_step[i].step.rows);
    assert_near(o.engine_step[i].step.rows.restitution[0], 0.8, 1e-6);
    /* the largest faithful step's h omega_c, so the same at both steps */
    assert_near(o.engine_step[i].step.rows.h_omega_c, o.largest_h_omega, 1e-9 * o.largest_h_omega);
  }
  /* at half the step, four times the stiffness (k' = k (h* / h)^2) */
  assert_near(o.engine_step[1].k, 4.0 * o.engine_step[0].k, 1e-9 * o.engine_step[1].k);
}

/* the damped Hertz laws in one command: the linear spring-damper with the
 * law's own restitution and peak penetration, every recommended row
 * verified at the automatic step; the issue's command (lankarani-nikravesh,
 * 1.5e10, n 1.5, cr 0.8, 0.5 kg, 0.3 m/s) among them */
static void test_damped_hertz_laws(void **state) {
  (void)state;
  const fb_law_kind laws[] = {FB_LAW_LANKARANI_NIKRAVESH, FB_LAW_HUNT_CROSSLEY, FB_LAW_FLORES,
                              FB_LAW_GONTHIER};
  for (int i = 0; i < 4; i++) {
    fb_cp_request q;
    fb_cp_request_default(&q);
    q.law = laws[i];
    q.stiffness = 1.5e10;
    q.exponent = 1.5;
    q.restitution = 0.8;
    q.mass_min = q.mass_max = 0.5;
    q.speed = 0.3;
    static fb_cp_result o;
    fb_diag d;
    assert_int_equal(fb_cp_run(&o, &q, &d), FB_OK);
    assert_int_equal(o.failed, 0);
    assert_true(o.given.recommended);
    assert_int_equal(expect_faithful(fb_law_name(laws[i]), &o.given), engines_built());
    expect_printable(fb_law_name(laws[i]), &o.given.rows);
    /* the translation holds the law's impact: the linear contact's closed
     * form at the design mass leaves with the law's restitution and peak */
    assert_near(o.given.rows.restitution[0], o.law_restitution,
                EQUIVALENT_REL_TOL * o.law_restitution);
    assert_near(o.given.rows.penetration[0], o.law_penetration,
                EQUIVALENT_REL_TOL * o.law_penetration);
    assert_true(o.per_step.present && o.per_step.check.faithful);
  }
}

/* a recommended row that fails its verification is counted: the rows of
 * a contact at h omega_c = 0.45 (inside the rule, beyond the largest
 * faithful step of the issue's contact, 0.13) fail when verified as
 * recommended */
static void test_failed_row_counts(void **state) {
  (void)state;
  const double k = 6e7, m = 0.5, v = 0.3;
  const double c = fb_params_damper_for_restitution(k, m, 0.8);
  fb_cp_step st;
  memset(&st, 0, sizeof st);
  fb_diag d;
  assert_int_equal(fb_cp_rows_make(&st.rows, k, c, m, m, 0.45 / sqrt(k / m), v, &d), FB_OK);
  assert_true(fb_cp_verify(&st, v, 1) > 0);
  int unfaithful = 0;
  for (int i = 0; i < st.n_checks; i++) unfaithful += st.checks[i].recommended && !st.checks[i].faithful;
  assert_true(unfaithful > 0);
}

/* rows_of = "ode" (fourbar run's step check, the export's note) verifies
 * ODE's recommended rows alone and skips at_step: what those callers read,
 * the largest faithful step (every engine's rows) and ODE's matched row at
 * each mass, equal to the bit to the full request's. The paper case's
 * contact (k 1.45e9 N/m, cr 0.9, 0.092 to 0.95 kg, 1 m/s) at its automatic
 * step 3.317e-6 s, where the verification fails (restitution +4.6 % at the
 * lightest mass, docs/contact-params.md), and at 1e-6 s, where it holds */
static void test_ode_rows_alone_read_the_same(void **state) {
  (void)state;
  static const double steps[2] = {3.317e-6, 1e-6};
  for (int s = 0; s < 2; s++) {
    static fb_cp_result all, ode;
    fb_cp_request q;
    fb_cp_request_default(&q);
    q.stiffness = 1.452e9;
    q.restitution = 0.9;
    q.mass_min = 0.092;
    q.mass_max = 0.95;
    q.h = steps[s];
    fb_diag d;
    assert_int_equal(fb_cp_run(&all, &q, &d), FB_OK);
    q.rows_of = "ode";
    assert_int_equal(fb_cp_run(&ode, &q, &d), FB_OK);
    assert_true(isfinite(all.largest_step));
    assert_true(ode.largest_step == all.largest_step);
    assert_int_equal(ode.given.recommended, all.given.recommended);
    assert_int_equal(ode.has_at_step, 0);
    int matched = 0;
    for (int i = 0; i < ode.given.n_checks; i++) {
      const fb_cp_check *x = &ode.given.checks[i];
      assert_string_equal(x->engine, "ode");
      int found = 0;
      for (int k = 0; k < all.given.n_checks; k++) {
        const fb_cp_check *y = &all.given.checks[k];
        if (strcmp(y->engine, x->engine) || strcmp(y->form, x->form) || y->mass != x->mass)
          continue;
        found = 1;
        assert_true(x->restitution_rel == y->restitution_rel);
        assert_true(x->penetration_rel == y->penetration_rel);
        assert_int_equal(x->faithful, y->faithful);
      }
      assert_true(found);
      matched += strcmp(x->form, "matched") == 0;
    }
    assert_true(matched >= 2); /* the range's ends */
    /* the full request's other engines' rows and comparisons are there */
    assert_true(all.given.n_checks > ode.given.n_checks);
    /* the two steps are on either side of the verification */
    int faithful = 1;
    for (int i = 0; i < ode.given.n_checks; i++) faithful &= ode.given.checks[i].faithful;
    assert_int_equal(faithful, s == 1);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_fixed_row_needs_the_speed_limit),
      cmocka_unit_test(test_ode_and_gazebo_single_impact),
      cmocka_unit_test(test_ode_over_the_mass_range),
      cmocka_unit_test(test_mujoco_forms),
      cmocka_unit_test(test_bullet_contact),
      cmocka_unit_test(test_linear_equivalent),
      cmocka_unit_test(test_issue_user_at_coarse_steps),
      cmocka_unit_test(test_engine_default_steps),
      cmocka_unit_test(test_damped_hertz_laws),
      cmocka_unit_test(test_failed_row_counts),
      cmocka_unit_test(test_ode_rows_alone_read_the_same),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
