/* The four-bar in MuJoCo against the exact analytic solution (ideal loop)
 * and the reference dynamics (crank-coupler clearance joint).
 *
 *            C  connect equality (loop closure, direct solref k = 1/h^2, b = 1/h)
 *           / \
 *  coupler /   \ follower      hinges A, B, D (axis +z) in a kinematic tree:
 *         B     \              world -> crank -> coupler, world -> follower;
 *  crank /       \             the crank a flywheel (armature 1e6 kg m^2)
 *       A ------- D            started at the crank speed; gravity along -y
 *
 * Semi-implicit Euler on a loop closed in one step: the velocity series is
 * first-order accurate pointwise, and a peak value (where d omega/dt = 0) is
 * moved to second order, so halving h divides the peak error by about 4.
 * With a clearance joint at B the coupler is free at the crank pin and the
 * project's contact law acts through mjcb_passive; RK4 then integrates the
 * same equations as the reference (minimal coordinates, rk8pd at 1e-10). */
#include <string.h>

#include "analytic.h"
#include "casefile.h"
#include "fb_test.h"
#include "metrics.h"
#include "mujoco_scene.h"
#include "reference.h"

/* the acceptance bound on peak angular velocity at the default step
 * (measured: 1.9e-6) */
#define PEAK_OMEGA_REL_TOL 1e-4
/* alpha peaks from qacc at the same instants (measured: 2.5e-6); the
 * acceptance bound of omega, which they have no reason to exceed */
#define PEAK_ALPHA_REL_TOL 1e-4
/* the flywheel's speed changes by (reaction torque / armature) ~1e-4 rad/s^2:
 * over 3 revolutions (18 ms) ~1e-8 rad; measured 5.4e-8 rad. 1e-6 rad is
 * still 1e-4 of one step's crank rotation at h = 1e-5 s */
#define CRANK_ANGLE_TOL_RAD 1e-6
/* the loop closure's violation stays far below the smallest radial
 * clearance studied (2.5 um): measured 1.1e-7 m */
#define DRIFT_TOL_M 1e-6
/* halving h divides a second-order peak error by 4; the band allows 20 %
 * of higher-order terms and sampling of the peak on the grid */
#define SECOND_ORDER_LO 3.2
#define SECOND_ORDER_HI 4.8
/* the acceptance bound on the peak contact force of
 * mujoco-clearance-impact against the reference (measured: +0.03 %) */
#define FORCE_PEAK_REL_TOL 0.01
/* penetration peak against the reference: the force law's inverse of the
 * force bound (delta ~ F^(2/3)), measured -0.11 % */
#define PEN_PEAK_REL_TOL 0.01
/* the impact law in RK4 at h = 1e-5 s against the reference, omega peaks:
 * measured 5e-6; the ideal model's bound */
#define CLEARANCE_OMEGA_REL_TOL 1e-4

/* the mujoco models' rows as the model table will hold them (test-local
 * until the engine adapter lands with them) */
static const fb_model mj_ideal = {"mujoco-ideal-nominal", FB_ENGINE_MUJOCO, FB_LENGTHS_NOMINAL,
                                  FB_JOINTS_IDEAL, FB_MODEL_LAW_NONE, FB_COLLIDER_NONE, NULL, NULL,
                                  "MuJoCo, ideal hinges, nominal lengths"};
static const fb_model mj_impact = {"mujoco-clearance-impact", FB_ENGINE_MUJOCO, FB_LENGTHS_STACKUP,
                                   FB_JOINTS_CLEARANCE, FB_MODEL_LAW_IMPACT, FB_COLLIDER_EXACT,
                                   "reference", NULL, "MuJoCo, clearance joints, impact law"};

/* the scene of case c through the scene stage and the view of the ideal
 * (nominal lengths) or clearance impact (stack-up lengths) model on it */
static void scene_model(fb_scene_model *sm, const fb_case *c, int clearance) {
  static fb_scene_def scene; /* the view points into it */
  fb_case k = *c;
  k.model_count = 1; /* a listed model with the impact law: its law is resolved */
  snprintf(k.models[0], sizeof k.models[0], "%s", clearance ? "reference" : "analytic");
  fb_diag d;
  if (fb_scene_def_from_case(&scene, &k, &d) != FB_OK) fail_msg("%s", d.msg);
  if (fb_scene_def_select(sm, &scene, clearance ? &mj_impact : &mj_ideal, &d) != FB_OK)
    fail_msg("%s", d.msg);
}

/* runs the scene over the case's duration into s (initialised here) */
static double run_scene(fb_series *s, const fb_scene_model *def, const fb_case *c) {
  fb_mujoco_scene *sc = NULL;
  fb_diag d;
  if (fb_mujoco_scene_create(&sc, def, &c->mujoco, &d) != FB_OK) fail_msg("%s", d.msg);
  const size_t n = (size_t)llround(fb_case_duration(c) / c->solver.h);
  assert_int_equal(fb_series_init(s, n + 1), FB_OK);
  assert_int_equal(fb_series_enable_contact(s, def->clearance_mask), FB_OK);
  fb_sample x;
  double drift = 0.0;
  fb_mujoco_scene_sample(sc, &x);
  fb_series_push(s, &x);
  for (size_t k = 1; k <= n; k++) {
    assert_int_equal(fb_mujoco_scene_step(sc, &d), FB_OK);
    fb_mujoco_scene_sample(sc, &x);
    if (!isfinite(x.coupler_omega) || !isfinite(x.coupler_alpha)) fail_msg("nan at t = %g", x.t);
    fb_series_push(s, &x);
    drift = fmax(drift, fb_mujoco_scene_joint_drift(sc));
  }
  assert_int_equal(fb_mujoco_scene_steps(sc), n);
  fb_mujoco_scene_destroy(sc);
  return drift;
}

static double window(const fb_case *c) { return 2.0 * M_PI / c->crank_speed - 0.5 * c->solver.h; }

static double worst(double a, double b, double c, double d) {
  return fmax(fmax(fabs(a), fabs(b)), fmax(fabs(c), fabs(d)));
}

/* ideal nominal model at step h: error against the analytic solution */
static void ideal_error(fb_error *e, double *drift, const char *h) {
  char hs[64];
  snprintf(hs, sizeof hs, "solver.h_s=%s", h);
  const char *sets[] = {hs};
  fb_case c;
  fb_test_paper_case(&c, sets, 1);
  fb_scene_model def;
  scene_model(&def, &c, 0);
  fb_series s;
  *drift = run_scene(&s, &def, &c);
  fb_peaks exact;
  fb_diag d;
  assert_int_equal(fb_analytic_peaks(&exact, &c.nominal, c.branch, fb_case_omega2(&c), &d), FB_OK);
  assert_int_equal(fb_metrics_error(e, &s, window(&c), &c.nominal, c.branch, c.crank_angle0,
                                    fb_case_omega2(&c), &exact, &d),
                   FB_OK);
  fb_series_free(&s);
}

static void test_ideal_matches_analytic(void **state) {
  (void)state;
  fb_error e;
  double drift;
  ideal_error(&e, &drift, "1e-5");
  const double wo = worst(e.coupler.omega_max_rel, e.coupler.omega_min_rel,
                          e.follower.omega_max_rel, e.follower.omega_min_rel);
  const double wa = worst(e.coupler.alpha_max_rel, e.coupler.alpha_min_rel,
                          e.follower.alpha_max_rel, e.follower.alpha_min_rel);
  report_residual("mujoco peak omega rel, h = 1e-5", wo, PEAK_OMEGA_REL_TOL);
  report_residual("mujoco peak alpha rel, h = 1e-5", wa, PEAK_ALPHA_REL_TOL);
  report_residual("mujoco crank angle err [rad]", e.crank_angle_err_max, CRANK_ANGLE_TOL_RAD);
  report_residual("mujoco loop drift [m]", drift, DRIFT_TOL_M);
  assert_true(wo < PEAK_OMEGA_REL_TOL);
  assert_true(wa < PEAK_ALPHA_REL_TOL);
  assert_true(e.crank_angle_err_max < CRANK_ANGLE_TOL_RAD);
  assert_true(drift < DRIFT_TOL_M);
}

static void test_ideal_second_order_peaks(void **state) {
  (void)state;
  fb_error e1, e2;
  double drift;
  ideal_error(&e1, &drift, "4e-5");
  ideal_error(&e2, &drift, "2e-5");
  const double r = fabs(e1.coupler.omega_max_rel) / fabs(e2.coupler.omega_max_rel);
  report_residual("peak omega error ratio h / (h/2)", r, SECOND_ORDER_LO);
  assert_true(r > SECOND_ORDER_LO && r < SECOND_ORDER_HI);
}

static void test_clearance_impact_matches_reference(void **state) {
  (void)state;
  fb_case c;
  fb_test_paper_case(&c, NULL, 0);
  fb_scene_model def;
  scene_model(&def, &c, 1);
  assert_int_equal(fb_mujoco_integrator_for(&c.mujoco, def.clearance_mask), FB_MUJOCO_RK4);
  fb_series s, ref;
  run_scene(&s, &def, &c);
  size_t steps;
  fb_diag d;
  assert_int_equal(fb_reference_run(&ref, &steps, &c, &def.law[FB_JOINT_B], 0, &d), FB_OK);
  fb_reference_error re;
  assert_int_equal(fb_metrics_vs_reference(&re, &s, &ref, window(&c), FB_JOINT_B, &d), FB_OK);
  report_residual("mujoco impact force peak rel", re.force_max_rel, FORCE_PEAK_REL_TOL);
  report_residual("mujoco impact penetration peak rel", re.penetration_max_rel, PEN_PEAK_REL_TOL);
  const double wo = worst(re.coupler.omega_max_rel, re.coupler.omega_min_rel,
                          re.follower.omega_max_rel, re.follower.omega_min_rel);
  report_residual("mujoco impact omega peak rel vs reference", wo, CLEARANCE_OMEGA_REL_TOL);
  assert_true(fabs(re.force_max_rel) < FORCE_PEAK_REL_TOL);
  assert_true(fabs(re.penetration_max_rel) < PEN_PEAK_REL_TOL);
  assert_true(wo < CLEARANCE_OMEGA_REL_TOL);
  assert_int_equal(re.impacts, re.impacts_reference);
  fb_series_free(&s);
  fb_series_free(&ref);
}

static void test_mjcf_from_the_definition(void **state) {
  (void)state;
  fb_case c;
  fb_test_paper_case(&c, NULL, 0);
  fb_scene_model def;
  scene_model(&def, &c, 0);
  static char buf[16384];
  fb_diag d;
  assert_int_equal(fb_mujoco_mjcf(buf, sizeof buf, &def, &c.mujoco, &d), FB_OK);
  /* the lengths round-trip: printed with 17 significant digits */
  assert_non_null(strstr(buf, "<body name=\"coupler\" pos=\"0.108 0 0\""));
  assert_non_null(strstr(buf, "<connect name=\"loop\""));
  assert_non_null(strstr(buf, "integrator=\"Euler\""));
  /* a clearance joint at C: no loop equality, the contact closes the loop */
  def.clearance_mask = 1 << FB_JOINT_C;
  assert_int_equal(fb_mujoco_mjcf(buf, sizeof buf, &def, &c.mujoco, &d), FB_OK);
  assert_null(strstr(buf, "<connect"));
  assert_non_null(strstr(buf, "integrator=\"RK4\""));
  /* too small a buffer is an error, not a truncated model */
  assert_int_equal(fb_mujoco_mjcf(buf, 100, &def, &c.mujoco, &d), FB_ERR_RANGE);
  /* a linkage that does not assemble */
  def.lengths.length[FB_COUPLER] = 10.0;
  fb_mujoco_scene *s = NULL;
  assert_int_equal(fb_mujoco_scene_create(&s, &def, &c.mujoco, &d), FB_ERR_ASSEMBLY);
  assert_null(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_mjcf_from_the_definition),
      cmocka_unit_test(test_ideal_matches_analytic),
      cmocka_unit_test(test_ideal_second_order_peaks),
      cmocka_unit_test(test_clearance_impact_matches_reference),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
