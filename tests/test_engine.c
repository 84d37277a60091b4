/* The model table, the scene stage and the engine interface: the table is
 * consistent (names unique, every reference and ideal model a row of the
 * right kind), unknown names are refused with the known ones, the analytic
 * engine behind the interface is the closed form (fb_linkage_solve) at every
 * step, the scene check names a broken field, and stop reasons render to
 * the texts summary.json has always carried.
 *
 *   case --fb_scene_from_case--> scene definition (once per run)
 *        --fb_scene_select(row)--> what one model sees
 *        --engine->create / step / sample--> samples */
#include <string.h>

#include "casefile.h"
#include "clock.h"
#include "engine.h"
#include "fb_test.h"
#include "outcome_text.h"
#include "resolution.h"
#include "run.h"
#include "tolerance.h"

/* both sides evaluate the same closed form at the same time value: equal to
 * the last bit, a bound of 1e-15 rad/s only allows for nothing */
#define SAME_FORMULA_TOL 1e-15

static void test_table_is_consistent(void **state) {
  (void)state;
  for (int i = 0; i < fb_model_count; i++) {
    const fb_model *m = &fb_models[i];
    assert_ptr_equal(fb_model_find(m->name), m); /* names unique */
    assert_non_null(m->style.color);
    if (m->reference) {
      const fb_model *r = fb_model_reference_of(m);
      assert_non_null(r);
      assert_int_equal(r->engine, FB_ENGINE_REFERENCE);
      assert_int_equal(r->law, m->law); /* measured against the reference of its own law */
    }
    if (m->spikes_vs) {
      const fb_model *ideal = fb_model_ideal_of(m);
      assert_non_null(ideal);
      assert_int_equal(ideal->joints, FB_JOINTS_IDEAL);
      assert_int_equal(ideal->lengths, m->lengths);
    }
    /* a clearance model has a law and a collider, an ideal one neither */
    assert_int_equal(fb_model_has_clearance(m), m->law != FB_MODEL_LAW_NONE);
    assert_int_equal(fb_model_has_clearance(m), m->collider != FB_COLLIDER_NONE);
  }
  assert_ptr_equal(fb_model_match(FB_ENGINE_ODE, FB_LENGTHS_STACKUP, FB_JOINTS_IDEAL,
                                  FB_MODEL_LAW_NONE, FB_COLLIDER_NONE),
                   fb_model_find("ode-ideal-stackup"));
}

static void test_unknown_model_refused_with_list(void **state) {
  (void)state;
  const fb_model *m = NULL;
  fb_diag d;
  assert_int_equal(fb_model_lookup(&m, "ode-magic", &d), FB_ERR_ARG);
  assert_null(m);
  assert_non_null(strstr(d.msg, "unknown model 'ode-magic'"));
  assert_non_null(strstr(d.msg, "ode-clearance-impact"));
  assert_non_null(strstr(d.msg, "reference-restitution"));
}

static void test_analytic_engine_is_the_closed_form(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.revolutions=2", "solver.h_s=1e-4"};
  fb_test_paper_case(&c, sets, 2);
  fb_scene def;
  fb_model_scene sm;
  const fb_engine *e;
  void *self = fb_test_engine(&e, &sm, &def, &c, "analytic-stackup", NULL, NULL);
  assert_string_equal(e->name, "analytic");
  /* advance to a time: a whole number of steps */
  assert_int_equal(fb_engine_advance(e, self, 0.01, def.solver.h, NULL), FB_OK);
  fb_sample x;
  e->sample(self, &x);
  assert_near(x.t, 0.01, 0.5 * def.solver.h);
  fb_linkage_state ls;
  assert_int_equal(fb_linkage_solve(&ls, &def.lengths[FB_LENGTHS_STACKUP], def.branch,
                                    def.crank_angle0 + def.omega2 * x.t, def.omega2, 0.0, NULL),
                   FB_OK);
  assert_near(x.coupler_omega, ls.coupler_omega, SAME_FORMULA_TOL * fabs(ls.coupler_omega));
  assert_near(x.follower_omega, ls.follower_omega, SAME_FORMULA_TOL * fabs(ls.follower_omega));
  fb_engine_contact ct;
  e->contact(self, &ct);
  assert_int_equal(ct.joint, -1);
  e->destroy(self);
}

static void test_scene_check_names_the_field(void **state) {
  (void)state;
  fb_case c;
  const char *sets[] = {"run.models=analytic,ode-ideal-stackup"};
  fb_test_paper_case(&c, sets, 1);
  fb_scene def;
  fb_diag d;
  assert_int_equal(fb_scene_from_case(&def, &c, &d), FB_OK);
  assert_int_equal(fb_scene_check(&def, &d), FB_OK);
  def.solver.world_erp = 1.5;
  assert_int_equal(fb_scene_check(&def, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "world_erp"));
  /* a model the scene resolved no law for (none of the case's models uses
   * it) is refused, not run with zeros */
  fb_model_scene sm;
  assert_int_equal(fb_scene_select(&sm, &def, fb_model_find("ode-clearance-impact"), &d),
                   FB_ERR_ARG);
}

static void test_stop_texts(void **state) {
  (void)state;
  char buf[256];
  fb_stop s;
  memset(&s, 0, sizeof s);
  s.engine = "ode";
  assert_string_equal(fb_stop_text(buf, sizeof buf, &s), "ok");
  s.kind = FB_STOP_PENETRATION;
  s.joint = FB_JOINT_B;
  s.value = 20e-6;
  s.limit = 14.5e-6;
  s.t = 0.0125;
  s.step = 1250;
  assert_string_equal(fb_stop_text(buf, sizeof buf, &s),
                      "unstable: penetration 20 um at the crank-coupler joint exceeds the limit "
                      "14.5 um at t = 0.0125 s (step 1250)");
  s.kind = FB_STOP_SOLVER;
  snprintf(s.detail, sizeof s.detail, "LCP internal error");
  assert_string_equal(fb_stop_text(buf, sizeof buf, &s),
                      "ode-error: LCP internal error at t = 0.0125 s (step 1250)");
  for (int k = 0; k < FB_STOP_COUNT; k++)
    assert_int_equal(fb_stop_kind_parse(fb_stop_kind_name((fb_stop_kind)k)), k);
  assert_int_equal(fb_stop_kind_parse("nan"), FB_STOP_NONFINITE);
  assert_int_equal(fb_stop_kind_parse("wobble"), FB_STOP_COUNT);
}

/* [run] max_wall_s holds for every kind of model while it runs (issue 41):
 * with the run's deadline already past, the analytic model (replayed), an
 * ODE model (stepped), the reference (integrated in its create) and a
 * clearance model each stop at once with the wall-time reason; the up-front
 * estimate counts an ensemble's members and an engine's options */
static void test_wall_time_limit_holds(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  const char *sets[] = {"run.revolutions=2",
                        "run.models=analytic,ode-ideal-nominal,ode-clearance-impact,reference"};
  char paper[4096];
  const char *dir = getenv("FOURBAR_CASES_DIR");
  snprintf(paper, sizeof paper, "%s/paper_crank_rocker.ini", dir ? dir : "cases");
  if (fb_casefile_load(&c, paper, sets, 2, &d) != FB_OK) fail_msg("%s", d.msg);
  c.member = 1;                      /* keeps the deadline it is given */
  c.wall_deadline = fb_clock_s() - 1; /* already past */
  static fb_run r;
  if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  for (int i = 0; i < r.n; i++) {
    const fb_model_result *m = &r.model[i];
    if (m->run.stop.kind != FB_STOP_WALL_TIME)
      fail_msg("%s: stop kind %d, expected the wall-time limit", m->run.name, m->run.stop.kind);
    /* stopped within FB_WALL_CHECK_STEPS steps of its start (the reference:
     * within 16 samples, reference.c) */
    assert_true(m->run.series.n <= FB_WALL_CHECK_STEPS + 1);
  }
  char text[512];
  assert_non_null(strstr(fb_stop_text(text, sizeof text, &r.model[0].run.stop),
                         "[run] max_wall_s"));
  fb_run_free(&r);
  /* the estimate: 8 members cost about 8 runs of the clearance model, 2000
   * quick-step iterations about 60 world steps each */
  double b1, s1, b8, s8, sq;
  c.member = 0;
  c.wall_deadline = 0;
  c.model_count = 1;
  snprintf(c.models[0], sizeof c.models[0], "ode-clearance-impact");
  fb_run_estimate(&c, &b1, &s1);
  c.ensemble = 8;
  fb_run_estimate(&c, &b8, &s8);
  assert_near(s8 / s1, 8.0, 1e-12);
  c.ensemble = 1;
  c.solver.stepper = FB_STEPPER_QUICK;
  c.solver.quick_iterations = 2000;
  fb_run_estimate(&c, &b1, &sq);
  assert_true(sq / s1 > 100.0);
}

/* The up-front estimate (fb_run_estimate) against what it stands for,
 * measured: the models' CPU time, their check integrations and the case's
 * ensemble members (timing.json estimate.models_cpu_s; a quiet moment of
 * the shared 2-core machine, issue 54): the paper case 0.85 s,
 * hard/slider_crank_rattling.ini (2 revolutions, an ensemble of 5) 0.42 s.
 * The estimate is to be conservative but within 2x. The example of issue
 * 54's brief: that slider-crank, estimated at 7.38 s before (fourbar run
 * cases/hard/slider_crank_rattling.ini --set run.max_wall_s=2 on main), was
 * refused at [run] max_wall_s = 2; it runs now. The comparison is with
 * these committed figures only: CPU time measured inside the test grows
 * with the machine's load as wall time does (0.47 s estimated against
 * 1.07 and 1.17 s measured on busy machines), so no verdict here reads a
 * clock; a run's timing.json holds both side by side (estimate.wall_s,
 * estimate.models_cpu_s), for a measurement on a quiet machine. */
#define PAPER_MODELS_CPU_S 0.85
#define RATTLING_SC_MODELS_CPU_S 0.42
#define ESTIMATE_OVER_MEASURED_MAX 2.0

static double resolved_estimate(const fb_case *c) {
  static fb_case k;
  k = *c;
  fb_diag d;
  if (fb_tol_resolve_worst(&k, &d) != FB_OK || fb_case_resolve_step(&k, &d) != FB_OK)
    fail_msg("%s", d.msg);
  double bytes, seconds;
  fb_run_estimate(&k, &bytes, &seconds);
  return seconds;
}

static void test_estimate_within_twice_measured(void **state) {
  (void)state;
  static fb_case c;
  fb_diag d;
  const char *cases[2] = {"paper_crank_rocker.ini", "hard/slider_crank_rattling.ini"};
  const double measured[2] = {PAPER_MODELS_CPU_S, RATTLING_SC_MODELS_CPU_S};
  for (int i = 0; i < 2; i++) {
    const char *sets[] = {"run.max_wall_s=2"};
    if (fb_test_shipped_case(&c, cases[i], sets, 1, &d) != FB_OK) fail_msg("%s", d.msg);
    const double est = resolved_estimate(&c);
    if (fb_test_verbose())
      fprintf(stderr, "  %s: estimated %.3f s, measured %.3f s\n", cases[i], est, measured[i]);
    if (!(est >= measured[i] && est <= ESTIMATE_OVER_MEASURED_MAX * measured[i]))
      fail_msg("%s: estimated %.3g s against %.3g s measured", cases[i], est, measured[i]);
    int over_cost = 0;
    if (fb_run_preflight(&c, &over_cost, &d) != FB_OK)
      fail_msg("%s refused at max_wall_s = 2: %s", cases[i], d.msg);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_table_is_consistent),
      cmocka_unit_test(test_unknown_model_refused_with_list),
      cmocka_unit_test(test_analytic_engine_is_the_closed_form),
      cmocka_unit_test(test_scene_check_names_the_field),
      cmocka_unit_test(test_stop_texts),
      cmocka_unit_test(test_wall_time_limit_holds),
      cmocka_unit_test(test_estimate_within_twice_measured),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
