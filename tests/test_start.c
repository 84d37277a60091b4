/* The start of a run ([run] start, pin_start) and its peak windows ([run]
 * peaks): the start state's geometry, ODE's clearance models against the
 * reference and a closed form on the first impact of the rest start, the
 * penetration limit and the validity warning on every model, the start-up
 * peak inside the whole-run window, and the steady start and window leaving
 * every `fourbar check` baseline where it was.
 *
 *   rest start, pin centred (crank-coupler joint B):
 *
 *          B_pin -> v = a omega2 (crank tip, full speed from t = 0)
 *        ( o )     hole on the coupler, at rest: the pin crosses the radial
 *                  clearance c in free flight and hits the wall at
 *                  t1 = c / (a |omega2|), speed a |omega2|
 *
 * Usage: test_start PATH_TO_FOURBAR (for the check part). */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "outcome_text.h"
#include "resolution.h"
#include "run.h"
#include "start.h"

/* lengths are metres around 0.1-0.3: a loop closed to a few ulp */
#define LOOP_TOL_M 1e-15
/* ODE's semi-implicit Euler and the reference's rk8pd integrate the same
 * free flight of ~1.3 us (gravity changes the speed by g t ~ 1e-5 m/s):
 * measured agreement 2.4e-7 in time and speed at h = 1e-6 s */
#define FIRST_IMPACT_REL_TOL 1e-5
/* the closed form neglects the hole's fall under gravity (g t^2 / 2 ~ 1e-11 m
 * of 14.5 um) and the crank tip's arc over 1.3e-4 rad (chord - arc ~ 1e-13 m):
 * both below 1e-6 relative; the estimator's secant speed is exact in free
 * flight */
#define CLOSED_FORM_REL_TOL 1e-5

static const char *fourbar_exe;

static void load(fb_case *c, const char *file, const char **sets, int n) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", d ? d : "cases", file);
  fb_diag diag;
  if (fb_casefile_load(c, path, sets, n, &diag) != FB_OK) fail_msg("%s: %s", path, diag.msg);
}

static double dist(const double p[2], const double q[2]) { return hypot(p[0] - q[0], p[1] - q[1]); }

static void test_steady_centred_start_is_the_ideal_state(void **state) {
  (void)state;
  fb_case c;
  fb_test_paper_case(&c, NULL, 0);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  fb_start_state s;
  fb_linkage_state x;
  assert_int_equal(fb_start_resolve(&s, &c, &lk, c.clearance.mask, NULL), FB_OK);
  assert_int_equal(fb_linkage_solve(&x, &lk, c.branch, c.crank_angle0, fb_case_omega2(&c), 0, NULL),
                   FB_OK);
  /* bit-identical: the steady start of every model before start states existed */
  assert_true(s.coupler_angle == x.coupler_angle && s.follower_angle == x.follower_angle);
  assert_true(s.coupler_omega == x.coupler_omega && s.follower_omega == x.follower_omega);
  assert_true(s.pin[FB_JOINT_B][0] == x.b[0] && s.hole[FB_JOINT_C][1] == x.c[1]);
}

/* eccentric pins: every body keeps its length between its own points, the
 * loop closes through the offsets, |e| = c at the clearance joint */
static void check_geometry(const fb_start_state *s, const fb_linkage *lk, double clearance) {
  assert_near(dist(s->pin[FB_JOINT_A], s->pin[FB_JOINT_B]), lk->length[FB_CRANK], LOOP_TOL_M);
  assert_near(dist(s->hole[FB_JOINT_B], s->pin[FB_JOINT_C]), lk->length[FB_COUPLER], LOOP_TOL_M);
  assert_near(dist(s->pin[FB_JOINT_D], s->hole[FB_JOINT_C]), lk->length[FB_FOLLOWER], LOOP_TOL_M);
  assert_near(s->hole[FB_JOINT_D][0], lk->length[FB_GROUND], LOOP_TOL_M);
  assert_near(dist(s->pin[FB_JOINT_B], s->hole[FB_JOINT_B]), clearance, LOOP_TOL_M);
  /* the bodies' angles are those of their points */
  assert_near(atan2(s->pin[FB_JOINT_C][1] - s->hole[FB_JOINT_B][1],
                    s->pin[FB_JOINT_C][0] - s->hole[FB_JOINT_B][0]),
              s->coupler_angle, 1e-14);
}

static void test_eccentric_and_rest_starts(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.start=rest", "run.pin_start=-30"};
  fb_test_paper_case(&c, sets, 2);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  fb_start_state s;
  assert_int_equal(fb_start_resolve(&s, &c, &lk, c.clearance.mask, NULL), FB_OK);
  check_geometry(&s, &lk, c.radial_clearance);
  assert_near(atan2(s.ecc[FB_JOINT_B][1], s.ecc[FB_JOINT_B][0]), -M_PI / 6, 1e-12);
  /* rest: coupler and follower still, the crank at full speed */
  assert_true(s.coupler_omega == 0.0 && s.follower_omega == 0.0);
  assert_true(s.coupler_b_vel[0] == 0.0 && s.coupler_b_vel[1] == 0.0);
  assert_true(s.crank_omega == fb_case_omega2(&c));
  /* an ideal model has no free coupler: the joints' velocities, as steady */
  fb_start_state ideal;
  fb_linkage_state x;
  assert_int_equal(fb_start_resolve(&ideal, &c, &lk, 0, NULL), FB_OK);
  fb_linkage_solve(&x, &lk, c.branch, c.crank_angle0, fb_case_omega2(&c), 0, NULL);
  assert_true(ideal.coupler_omega == x.coupler_omega && ideal.follower_omega == x.follower_omega);
  /* resting: the coupler hangs on the pin, so the hole's upper wall sits on
   * it: the pin centre lies above the hole centre */
  const char *rest[] = {"run.pin_start=resting"};
  fb_test_paper_case(&c, rest, 1);
  assert_int_equal(fb_start_resolve(&s, &c, &lk, c.clearance.mask, NULL), FB_OK);
  check_geometry(&s, &lk, c.radial_clearance);
  assert_true(s.ecc[FB_JOINT_B][1] > 0.0);
  /* steady with an eccentric pin: the pin moves with its hole */
  assert_near(s.coupler_b_vel[0], -fb_case_omega2(&c) * s.pin[FB_JOINT_B][1], 1e-15);
}

/* 1 when model m carries a warning of kind what */
static int has_warning(const fb_model_result *m, fb_warning_kind what) {
  for (int k = 0; k < m->warning_count; k++)
    if (m->warnings[k].kind == what) return 1;
  return 0;
}

/* first impact of the rest start: ODE and the reference, each law, against
 * each other and the closed form; the default limit (the clearance) stops
 * every model, the reference included, just after it */
static void test_rest_start_first_impact(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.start=rest", "run.peaks=all", "run.revolutions=1", "solver.h_s=1e-6",
                        "solver.drive_torque_max_n_m=1e7",
                        "run.models=ode-clearance-impact,reference,ode-clearance-restitution,"
                        "reference-restitution"};
  fb_test_paper_case(&c, sets, 6);
  fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  const double v = lk.length[FB_CRANK] * c.crank_speed, t1 = c.radial_clearance / v;
  for (int i = 0; i < r.n; i += 2) {
    const fb_model_result *ode = &r.model[i], *ref = &r.model[i + 1];
    assert_true(ode->first_impact.found && ref->first_impact.found);
    const double dt = fabs(ode->first_impact.t - ref->first_impact.t) / ref->first_impact.t;
    const double dv = fabs(ode->first_impact.speed - ref->first_impact.speed) / ref->first_impact.speed;
    report_residual("first impact time, ODE vs reference", dt, FIRST_IMPACT_REL_TOL);
    report_residual("first impact speed, ODE vs reference", dv, FIRST_IMPACT_REL_TOL);
    assert_true(dt < FIRST_IMPACT_REL_TOL && dv < FIRST_IMPACT_REL_TOL);
    assert_rel(ref->first_impact.t, t1, CLOSED_FORM_REL_TOL);
    assert_rel(ref->first_impact.speed, v, CLOSED_FORM_REL_TOL);
    /* the limit applies to both engines */
    assert_int_equal(ode->run.stop.kind, FB_STOP_PENETRATION);
    assert_int_equal(ref->run.stop.kind, FB_STOP_PENETRATION);
  }
  fb_run_free(&r);
}

/* peaks = all over two revolutions: the coupler's alpha peak is the start-up
 * spike (its time lies in revolution 1, it equals the start-up block's and
 * exceeds the steady window's); no limit, so the warning names the validity */
static void test_whole_run_window_holds_the_startup_peak(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"solver.h_s=1e-5", "run.revolutions=2", "run.models=ode-clearance-impact,reference"};
  load(&c, "paper_adams.ini", sets, 3);
  fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  const double period = 2 * M_PI / c.crank_speed;
  for (int i = 0; i < r.n; i++) {
    const fb_model_result *m = &r.model[i];
    assert_true(m->has_peaks && m->has_startup);
    assert_true(m->peaks_at.coupler.alpha_max.t < period);
    assert_true(m->peaks.coupler.alpha_max == m->startup.coupler.alpha_max);
    fb_peaks steady;
    assert_int_equal(fb_metrics_peaks(&steady, &m->run.series, period - 0.5 * c.solver.h, NULL), FB_OK);
    assert_true(m->peaks.coupler.alpha_max > steady.coupler.alpha_max);
    if (!has_warning(m, FB_WARN_PENALTY_VALIDITY))
      fail_msg("%s: no validity warning (penetration %g m)", m->run.name, m->penetration_max_run);
  }
  fb_run_free(&r);
}

/* a rest start's first impacts need ~1e5 N m at the crank with the physical
 * stiffness: ODE's motor capped at the default 1e4 N m yields and the run
 * says so; with the cap raised it holds the crank and the warning goes */
static void test_saturated_drive_is_named(void **state) {
  (void)state;
  const char *sets[] = {"run.start=rest", "run.peaks=all", "run.revolutions=1",
                        "clearance.penetration_limit_um=none", "solver.h_s=5e-6",
                        "run.models=ode-clearance-impact", "solver.drive_torque_max_n_m=1e7"};
  for (int raised = 0; raised < 2; raised++) {
    fb_case c;
    fb_test_paper_case(&c, sets, raised ? 7 : 6);
    fb_run r;
    fb_diag d;
    assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
    assert_int_equal(has_warning(&r.model[0], FB_WARN_DRIVE_SATURATED), !raised);
    fb_run_free(&r);
  }
}

/* h_s = auto meets its bound: at 100 rpm its estimate (a force of 2 x the
 * ideal reaction) is exceeded by the contacts (measured h omega_c 0.745 at
 * h = 4.8e-6 s before issue 25), so the run re-chooses the step from the
 * stiffest contact it met and is redone: no under-resolved warning, the
 * re-choice counted, h omega_c within the bound. A fixed 2e-5 s (h omega_c
 * ~3) is told to use auto or a smaller step, and that step, followed, draws
 * no new warning. */
static const fb_warning *under_resolved(const fb_model_result *m) {
  const fb_warning *w = NULL;
  for (int k = 0; k < m->warning_count; k++)
    if (m->warnings[k].kind == FB_WARN_UNDER_RESOLVED) w = &m->warnings[k];
  return w;
}

static void test_under_resolved_says_what_to_change(void **state) {
  (void)state;
  const char *sets[] = {"drive.speed_rpm=100", "run.revolutions=2",
                        "run.models=ode-clearance-impact", "solver.h_s=2e-5"};
  for (int fixed = 0; fixed < 2; fixed++) {
    fb_case c;
    fb_test_paper_case(&c, sets, fixed ? 4 : 3);
    fb_run r;
    fb_diag d;
    assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
    const fb_warning *w = under_resolved(&r.model[0]);
    if (!fixed) {
      if (w) fail_msg("auto run: under-resolved at h omega_c %g", w->value);
      if (!(r.h_auto && r.h_rechosen >= 1)) fail_msg("auto run: step not re-chosen");
      if (!(r.h_omega_c_max > 0.0 && r.h_omega_c_max <= FB_H_OMEGA_C_BOUND))
        fail_msg("auto run: h omega_c %g", r.h_omega_c_max);
      fb_run_free(&r);
      continue;
    }
    if (!w) fail_msg("fixed run: no under-resolved warning");
    char t[512];
    fb_warning_text(t, sizeof t, w);
    assert_int_equal(w->h_auto, FB_WARN_STEP_FIXED);
    if (!strstr(t, "set [solver] h_s = auto, or a fixed step of")) fail_msg("fixed: %s", t);
    /* the advised step: the bound at the measured h omega_c, with auto's margin */
    char want[64];
    snprintf(want, sizeof want, "%.2g", w->h * FB_H_OMEGA_C_BOUND / w->value * FB_H_AUTO_MARGIN);
    if (!strstr(t, want)) fail_msg("no advised step %s in: %s", want, t);
    fb_run_free(&r);
    /* followed: no new warning */
    char set_h[80];
    snprintf(set_h, sizeof set_h, "solver.h_s=%s", want);
    const char *follow[] = {"drive.speed_rpm=100", "run.revolutions=2",
                            "run.models=ode-clearance-impact", set_h};
    fb_test_paper_case(&c, follow, 4);
    assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
    w = under_resolved(&r.model[0]);
    if (w) fail_msg("the advice h_s = %s followed: under-resolved again at %g", want, w->value);
    fb_run_free(&r);
  }
}

/* the paper case's analytic row is `fourbar kinematics` of the nominal lengths */
static void test_paper_adams_analytic_row_is_the_kinematics(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.models=analytic"};
  load(&c, "paper_adams.ini", sets, 1);
  fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  fb_peaks k;
  assert_int_equal(fb_analytic_peaks(&k, &c.nominal, c.branch, fb_case_omega2(&c), &d), FB_OK);
  assert_true(memcmp(&k, &r.model[0].peaks, sizeof k) == 0);
  fb_run_free(&r);
}

/* runs `fourbar check --json` with extra --set arguments into buf */
static void check_json(char *buf, size_t size, const char *sets) {
  char cmd[4096];
  snprintf(cmd, sizeof cmd,
           "'%s' check --json --cases paper_crank_rocker,speed_3000rpm,two_clearance_joints %s",
           fourbar_exe, sets);
  FILE *p = popen(cmd, "r");
  assert_non_null(p);
  size_t n = fread(buf, 1, size - 1, p);
  buf[n] = '\0';
  pclose(p);
}

/* the steady start and window, stated explicitly, give every baseline the
 * same value as the defaults, and every comparison passes. The ODE cases
 * only: the start state and the peak windows are set before any engine runs
 * (src/physics/start.c), the whole `fourbar check` runs in the test command
 * anyway, and the four-engine cases cost 28 s here and over 300 s in the
 * sanitizer build */
static void test_steady_start_and_window_keep_the_baselines(void **state) {
  (void)state;
  if (!fourbar_exe) skip();
  static char a[1 << 20], b[1 << 20];
  check_json(a, sizeof a, "");
  check_json(b, sizeof b,
             "--set run.start=steady --set run.peaks=steady --set run.pin_start=centred");
  assert_non_null(strstr(b, "\"failed\": 0"));
  assert_non_null(strstr(b, "two_clearance_joints")); /* the three cases ran */
  assert_non_null(strstr(b, "speed_3000rpm"));
  assert_null(strstr(b, "\"pass\": false"));
  assert_string_equal(a, b);
}

int main(int argc, char **argv) {
  fourbar_exe = argc > 1 ? argv[1] : NULL;
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_steady_centred_start_is_the_ideal_state),
      cmocka_unit_test(test_eccentric_and_rest_starts),
      cmocka_unit_test(test_rest_start_first_impact),
      cmocka_unit_test(test_whole_run_window_holds_the_startup_peak),
      cmocka_unit_test(test_saturated_drive_is_named),
      cmocka_unit_test(test_under_resolved_says_what_to_change),
      cmocka_unit_test(test_paper_adams_analytic_row_is_the_kinematics),
      cmocka_unit_test(test_steady_start_and_window_keep_the_baselines),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
