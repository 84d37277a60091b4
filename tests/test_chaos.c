/* Chaotic impact sequences (issue 25): impacts paired by time, the impact
 * statistics (impact_stats.h) against hand-computed values, and the
 * distinction a run draws between a regular sequence (the paper's case:
 * every clearance model stays with its reference, impacts matched one to
 * one, an ensemble with almost no spread) and a chaotic one
 * (cases/hard/rattling_pin.ini: the model leaves the reference, the
 * reference's own peaks are unconverged, the ensemble spreads), a model
 * that keeps the reference's trajectory with wrong impacts (status error),
 * and an ensemble whose numbers do not depend on --jobs. */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "check.h"
#include "fb_test.h"
#include "impact_stats.h"
#include "metrics.h"
#include "report_chaos.h"
#include "resolution.h"
#include "run.h"

#define C_M 10e-6
#define L_COUPLER_M 0.25
#define H_S 1e-6
#define N_SAMPLES 6000
#define PERIOD_S 0.06
#define IMPACT_SAMPLES 20

/* a series with impacts starting at starts[k] (s), each IMPACT_SAMPLES long
 * with force force[k] and coupler alpha alpha[k] on its samples (1 elsewhere) */
static void make(fb_series *s, const double *starts, const double *force, const double *alpha,
                 int n) {
  assert_int_equal(fb_series_init(s, N_SAMPLES), FB_OK);
  assert_int_equal(fb_series_enable_contact(s, 1 << 1), FB_OK);
  for (int i = 0; i < N_SAMPLES; i++) {
    fb_sample x;
    memset(&x, 0, sizeof x);
    x.t = i * H_S;
    x.crank_angle = 2.0 * M_PI * x.t / PERIOD_S;
    x.coupler_alpha = x.follower_alpha = 1.0;
    for (int k = 0; k < n; k++)
      if (x.t >= starts[k] - 0.5 * H_S && x.t < starts[k] + IMPACT_SAMPLES * H_S - 0.5 * H_S) {
        x.contact[1][FB_C_STATE] = FB_STATE_IMPACT;
        x.contact[1][FB_C_FORCE] = force[k];
        x.contact[1][FB_C_PEN] = 1e-6;
        x.coupler_alpha = -alpha[k];
        x.follower_alpha = 0.5 * alpha[k];
      }
    x.contact[1][FB_C_EX] = 0.2 * C_M;
    assert_int_equal(fb_series_push(s, &x), FB_OK);
  }
}

/* exact decimal arithmetic on a few values: a few ulp */
#define REL_TOL 1e-14

/* the model has one extra impact (a rattle) between the reference's two:
 * paired by time, both of the reference's impacts find their partner and
 * the extra one none; paired k-th to k-th (before issue 25) the extra one
 * took the reference's second impact's place and the pairing stopped */
static void test_impacts_pair_by_time(void **state) {
  (void)state;
  const double ref_t[2] = {1e-3, 3e-3}, mod_t[3] = {1e-3, 2e-3, 3e-3};
  const double ref_f[2] = {1000.0, 800.0}, mod_f[3] = {1000.0, 50.0, 840.0};
  const double al[3] = {1e4, 1e4, 1e4};
  fb_series s, r;
  make(&r, ref_t, ref_f, al, 2);
  make(&s, mod_t, mod_f, al, 3);
  fb_divergence d;
  fb_diag diag;
  assert_int_equal(fb_metrics_divergence(&d, &s, &r, 1, C_M, L_COUPLER_M, PERIOD_S, &diag), FB_OK);
  assert_int_equal(d.impacts_model, 3);
  assert_int_equal(d.impacts_reference, 2);
  assert_int_equal(d.matched, 2);
  assert_false(d.one_to_one);
  /* the pairs are (1 ms, 1 ms) and (3 ms, 3 ms): 840 against 800 */
  assert_rel(d.impact[1].t, 3e-3, REL_TOL);
  assert_rel(d.impact[1].force_rel, 0.05, REL_TOL);
  assert_rel(d.force_rel_max, 0.05, REL_TOL);
  fb_series_free(&s);
  fb_series_free(&r);
}

/* ten impacts with forces 100, 200, ..., 1000 N and coupler |alpha| 10x
 * that; the first lies before the window. GSL's quantile interpolates
 * linearly between order statistics (index (n - 1) q): over the nine in
 * the window (200 .. 1000), mean 600, p50 600, p90 at index 7.2 = 920 */
static void test_impact_statistics_by_hand(void **state) {
  (void)state;
  double t[10], f[10], a[10];
  for (int k = 0; k < 10; k++) t[k] = 0.5e-3 + k * 0.5e-3, f[k] = 100.0 * (k + 1), a[k] = 10.0 * f[k];
  fb_series s;
  make(&s, t, f, a, 10);
  fb_impact_values v = {0};
  fb_diag diag;
  assert_int_equal(fb_impact_values_add(&v, &s, 1, 0.9e-3, &diag), FB_OK);
  fb_impact_stats st;
  assert_int_equal(fb_impact_stats_of(&st, &v, &diag), FB_OK);
  assert_int_equal(st.force.n, 9);
  assert_rel(st.force.mean, 600.0, REL_TOL);
  assert_rel(st.force.p50, 600.0, REL_TOL);
  assert_rel(st.force.p90, 920.0, REL_TOL);
  assert_rel(st.force.max, 1000.0, REL_TOL);
  assert_rel(st.alpha_coupler.max, 10000.0, REL_TOL);
  assert_rel(st.alpha_follower.mean, 3000.0, REL_TOL);
  /* no impact in the window: n = 0, NaN statistics */
  fb_impact_values none = {0};
  assert_int_equal(fb_impact_values_add(&none, &s, 1, 1.0, &diag), FB_OK);
  assert_int_equal(fb_impact_stats_of(&st, &none, &diag), FB_OK);
  assert_int_equal(st.force.n, 0);
  assert_true(isnan(st.force.mean));
  fb_impact_values_free(&v);
  fb_series_free(&s);
}

/* the statistics by output body on a mechanism whose second output
 * translates (the slider-crank: the rod's alpha [rad/s^2], the slider's
 * acceleration [m/s^2]), at its clearance joint coupler-slider: two impacts
 * of 5 samples, rod alpha -2000 and 4000 rad/s^2, slider acceleration 300
 * and 100 m/s^2 (1 elsewhere): each column's largest |value| per impact;
 * the four-bar's names read the same storage. Then 100 impacts pushed one
 * by one (past the first allocation of 64): values 1 .. 100, mean 50.5. */
static void test_impact_statistics_by_output_body(void **state) {
  (void)state;
  const int joint = 2, len = 5, n = 40;
  const int starts[2] = {10, 25};
  const double rod[2] = {-2000.0, 4000.0}, slider[2] = {300.0, 100.0};
  fb_series s;
  assert_int_equal(fb_series_init_mech(&s, (size_t)n, &fb_mech_slider_crank), FB_OK);
  assert_int_equal(fb_series_enable_contact(&s, 1 << joint), FB_OK);
  assert_int_equal(fb_series_output_count(&s), 2);
  for (int i = 0; i < n; i++) {
    fb_sample x;
    memset(&x, 0, sizeof x);
    x.t = i * H_S;
    x.body[0][FB_Q_ACC] = x.body[1][FB_Q_ACC] = 1.0;
    for (int k = 0; k < 2; k++)
      if (i >= starts[k] && i < starts[k] + len) {
        x.contact[joint][FB_C_STATE] = FB_STATE_IMPACT;
        x.contact[joint][FB_C_FORCE] = 100.0 * (k + 1);
        x.body[0][FB_Q_ACC] = rod[k];
        x.body[1][FB_Q_ACC] = slider[k];
      }
    assert_int_equal(fb_series_push(&s, &x), FB_OK);
  }
  fb_impact_values v = {0};
  fb_diag diag;
  assert_int_equal(fb_impact_values_add(&v, &s, joint, 0.0, &diag), FB_OK);
  assert_int_equal((int)v.n, 2);
  fb_impact_stats st;
  assert_int_equal(fb_impact_stats_of(&st, &v, &diag), FB_OK);
  assert_rel(st.force.max, 200.0, REL_TOL);
  assert_rel(st.alpha[0].max, 4000.0, REL_TOL);
  assert_rel(st.alpha[0].mean, 3000.0, REL_TOL);
  assert_rel(st.alpha[1].max, 300.0, REL_TOL);
  assert_rel(st.alpha[1].mean, 200.0, REL_TOL);
  assert_true(&st.alpha_follower == &st.alpha[1]);
  fb_impact_values_free(&v);
  fb_series_free(&s);
  for (int k = 1; k <= 100; k++) {
    const double a[FB_MECH_MAX_OUTPUTS] = {k, 2.0 * k};
    assert_int_equal(fb_impact_values_push(&v, 10.0 * k, a, &diag), FB_OK);
  }
  assert_int_equal(fb_impact_stats_of(&st, &v, &diag), FB_OK);
  assert_int_equal(st.alpha[1].n, 100);
  assert_rel(st.force.mean, 505.0, REL_TOL);
  assert_rel(st.alpha[0].mean, 50.5, REL_TOL);
  assert_rel(st.alpha[1].max, 200.0, REL_TOL);
  fb_impact_values_free(&v);
}

static const fb_model_result *find(const fb_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].run.name, name) == 0) return &r->model[i];
  fail_msg("model %s not run", name);
  return NULL;
}

static void load(fb_case *c, const char *file, const char **sets, int n) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", d ? d : "cases", file);
  fb_diag diag;
  if (fb_casefile_load(c, path, sets, n, &diag) != FB_OK) fail_msg("%s: %s", path, diag.msg);
}

/* the paper case's ensemble: a regular sequence moves its statistics by
 * ~1e-4 relative under a 1e-2 x clearance start (ensemble.h,
 * FB_ENSEMBLE_ECC_FRACTION; measured 1.6e-4 on ODE's force mean, 1.7e-5 on
 * the reference's; ~1e-8 under the 1e-6 start before issue 55); 1e-3
 * leaves room and is still 10 times below the chaotic case's spread */
#define REGULAR_SPREAD_REL 1e-3
/* the rattling pin's ensemble: measured spread of the reference's mean
 * impact force 0.26 of its value over 5 members; 1e-2 is far below that
 * and 100 times above the regular bound */
#define CHAOTIC_SPREAD_REL 1e-2

static void test_regular_paper_case(void **state) {
  (void)state;
  const char *sets[] = {"run.models=ode-clearance-impact, reference", "run.revolutions=2",
                        "run.ensemble=3"};
  fb_case c;
  load(&c, "paper_crank_rocker.ini", sets, 3);
  static fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  const fb_model_result *m = find(&r, "ode-clearance-impact"), *ref = find(&r, "reference");
  assert_true(m->has_divergence);
  if (m->divergence.diverged) fail_msg("paper case diverged at t = %g s", m->divergence.t);
  assert_true(m->divergence.one_to_one);
  assert_int_equal(m->divergence.matched, m->divergence.impacts_reference);
  assert_false(m->matched_error);
  assert_false(m->peaks_unconverged);
  assert_false(ref->peaks_unconverged);
  const fb_ensemble *e[2] = {&m->ensemble, &ref->ensemble};
  for (int k = 0; k < 2; k++) {
    assert_int_equal(e[k]->members, 3);
    assert_int_equal(e[k]->impacts_min, e[k]->impacts_max);
    const double rel = e[k]->spread.force.mean / e[k]->pooled.force.mean;
    report_residual("paper ensemble force-mean spread", rel, REGULAR_SPREAD_REL);
    if (!(rel <= REGULAR_SPREAD_REL)) fail_msg("regular spread %g", rel);
  }
  /* its members' statistics equal the reference's to the spread: the test
   * shows them equivalent, and no member parts from the run itself */
  assert_true(m->has_test);
  assert_int_equal(m->test.decision, FB_EQUIV_EQUIVALENT);
  for (int k = 1; k < ref->ensemble.members; k++) assert_true(isinf(ref->ensemble.member[k].t_part));
  assert_true(r.h_omega_c_max > 0.0 && r.h_omega_c_max <= FB_H_OMEGA_C_BOUND);
  fb_run_free(&r);
}

static void test_chaotic_rattling_pin(void **state) {
  (void)state;
  const char *sets[] = {"run.ensemble=3"};
  fb_case c;
  load(&c, "hard/rattling_pin.ini", sets, 1);
  static fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  const fb_model_result *m = find(&r, "ode-clearance-impact"), *ref = find(&r, "reference");
  assert_true(m->divergence.diverged);
  assert_true(m->divergence.t < m->divergence.t_end);
  assert_true(m->peaks_unconverged);
  /* whether the reference's own check integration (tolerance / 100) parts
   * from it within the run is itself an outcome of the chaos: it did before
   * the effective mass's closed form (2ec98b8 moved m_eff by 1e-12) and does
   * not since; what check takes from each model follows it (below) */
  /* the first impact happens before the chaos: matched within the bound */
  assert_true(m->divergence.matched >= 1);
  if (!(fabs(m->divergence.impact[0].force_rel) <= FB_MATCHED_IMPACT_ERROR_BOUND))
    fail_msg("first impact force error %g", m->divergence.impact[0].force_rel);
  /* divergent, so not an error: compared by statistics; where its matched
   * impacts before the divergence miss the bound, its status says
   * "divergent", never "ok" (issue 25) */
  assert_int_not_equal(m->matched_error, FB_MATCHED_ERROR_KEPT);
  char status[512];
  fb_report_model_status(status, sizeof status, m);
  if (fmax(m->divergence.force_rel_max, m->divergence.penetration_rel_max) >
      FB_MATCHED_IMPACT_ERROR_BOUND) {
    assert_int_equal(m->matched_error, FB_MATCHED_ERROR_THEN_DIVERGENT);
    assert_non_null(strstr(status, "divergent: matched-impact peak error"));
  } else {
    assert_string_equal(status, "ok");
  }
  assert_true(m->has_stats_compare);
  const double rel = ref->ensemble.spread.force.mean / ref->ensemble.pooled.force.mean;
  report_residual("rattling ensemble force-mean spread (must exceed)", rel, CHAOTIC_SPREAD_REL);
  if (!(rel >= CHAOTIC_SPREAD_REL)) fail_msg("chaotic spread only %g", rel);
  /* check takes its statistics, not its peaks */
  static fb_metric met[FB_CHECK_MAX_METRICS];
  const int n = fb_check_metrics(&r, met, FB_CHECK_MAX_METRICS);
  int stats = 0, peaks = 0, ref_stats = 0, ref_peaks = 0;
  for (int i = 0; i < n; i++) {
    stats += strcmp(met[i].name, "ode-clearance-impact.stats.impact_force_p90_n") == 0 &&
             met[i].ensemble_sd > 0.0;
    peaks += strncmp(met[i].name, "ode-clearance-impact.spikes.", 28) == 0;
    ref_stats += strcmp(met[i].name, "reference.stats.impact_force_p90_n") == 0 &&
                 met[i].ensemble_sd > 0.0;
    ref_peaks += strncmp(met[i].name, "reference.spikes.", 17) == 0;
  }
  assert_int_equal(stats, 1);
  assert_int_equal(peaks, 0); /* unconverged: statistics alone */
  assert_int_equal(ref_stats, 1);
  if (ref->peaks_unconverged) assert_int_equal(ref_peaks, 0);
  else assert_true(ref_peaks > 0);
  /* a study's row: check's metrics, in the same order, then nothing but
   * each clearance model's first impact (check's baselines hold none) */
  static fb_metric study[FB_CHECK_MAX_METRICS];
  const int ns = fb_study_metrics(&r, study, FB_CHECK_MAX_METRICS);
  int first = 0, same = 0;
  for (int i = 0, k = 0; i < ns; i++) {
    if (strstr(study[i].name, ".first_impact.")) {
      first++;
      continue;
    }
    same += k < n && strcmp(study[i].name, met[k].name) == 0 && study[i].value == met[k].value;
    k++;
  }
  for (int i = 0; i < n; i++) assert_null(strstr(met[i].name, ".first_impact."));
  assert_int_equal(same, n);
  assert_int_equal(ns, n + first);
  int touched = 0; /* clearance models whose pin touched the wall, each with time and speed */
  for (int i = 0; i < r.n; i++) touched += r.model[i].first_impact_joint >= 0 && r.model[i].first_impact.found;
  assert_true(touched >= 2);
  assert_true(first >= 2 * touched);
  fb_run_free(&r);
}

/* the rattling case's check metrics with 1 and 2 worker processes: the
 * same bit for bit, and each within the committed baseline's tolerance
 * (results/baselines/rattling_pin.json): `fourbar check` passes on
 * repeated runs and on --jobs 1 against --jobs 2 */
static void test_jobs_do_not_change_the_numbers(void **state) {
  (void)state;
  static fb_metric met[2][FB_CHECK_MAX_METRICS];
  int n[2];
  fb_ensemble e[2];
  for (int jobs = 1; jobs <= 2; jobs++) {
    fb_case c;
    load(&c, "hard/rattling_pin.ini", NULL, 0);
    c.jobs = jobs;
    static fb_run r;
    fb_diag d;
    assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
    e[jobs - 1] = find(&r, "reference")->ensemble;
    n[jobs - 1] = fb_check_metrics(&r, met[jobs - 1], FB_CHECK_MAX_METRICS);
    fb_run_free(&r);
  }
  assert_int_equal(e[0].members, 5);
  assert_memory_equal(&e[0], &e[1], sizeof e[0]);
  assert_int_equal(n[0], n[1]);
  const char *dir = getenv("FOURBAR_CASES_DIR");
  char path[4096];
  snprintf(path, sizeof path, "%s/../results/baselines/rattling_pin.json", dir ? dir : "cases");
  json_error_t je;
  json_t *b = json_load_file(path, 0, &je);
  if (!b) fail_msg("%s: %s", path, je.text);
  json_t *list = json_object_get(b, "metrics");
  assert_int_equal((int)json_array_size(list), n[0]);
  for (int i = 0; i < n[0]; i++) {
    assert_string_equal(met[0][i].name, met[1][i].name);
    assert_true(met[0][i].value == met[1][i].value);
    json_t *x = json_array_get(list, (size_t)i);
    assert_string_equal(json_string_value(json_object_get(x, "name")), met[0][i].name);
    const double v = json_number_value(json_object_get(x, "value"));
    const double tol = json_number_value(json_object_get(x, "tolerance"));
    if (!(fabs(met[0][i].value - v) <= tol))
      fail_msg("%s: %g against the baseline %g (tolerance %g)", met[0][i].name, met[0][i].value, v,
               tol);
  }
  json_decref(b);
}

/* the paper case at a fixed h = 1e-5 s (h omega_c ~1.1): the model keeps
 * the reference's trajectory but its impacts are off by more than the
 * bound: status "error", not "ok" */
static void test_wrong_impacts_on_the_same_trajectory_are_an_error(void **state) {
  (void)state;
  const char *sets[] = {"run.models=ode-clearance-impact, reference", "run.revolutions=2",
                        "solver.h_s=1e-5"};
  fb_case c;
  load(&c, "paper_crank_rocker.ini", sets, 3);
  static fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  const fb_model_result *m = find(&r, "ode-clearance-impact");
  if (m->divergence.diverged) fail_msg("diverged at %g s: pick another step", m->divergence.t);
  const double worst = fmax(m->divergence.force_rel_max, m->divergence.penetration_rel_max);
  report_residual("h = 1e-5 s matched-impact error (must exceed)", worst,
                  FB_MATCHED_IMPACT_ERROR_BOUND);
  assert_true(worst > FB_MATCHED_IMPACT_ERROR_BOUND);
  assert_int_equal(m->matched_error, FB_MATCHED_ERROR_KEPT);
  fb_run_free(&r);
}

/* h_s = auto keeps h omega_c <= 0.5 on the paper case away from 1000 rpm
 * (100 rpm: test_start.c; measured 0.449 at 300 rpm after one re-choice
 * from 4.17e-6 to 3.58e-6 s, 0.307 at 1500 rpm with none; with the
 * restitution model too, 0.453 at 100 rpm and 0.434 at 1500 rpm) */
static void test_auto_step_keeps_its_bound(void **state) {
  (void)state;
  const char *speeds[2] = {"drive.speed_rpm=300", "drive.speed_rpm=1500"};
  for (int k = 0; k < 2; k++) {
    const char *sets[] = {speeds[k], "run.revolutions=2", "run.models=ode-clearance-impact"};
    fb_case c;
    load(&c, "paper_crank_rocker.ini", sets, 3);
    static fb_run r;
    fb_diag d;
    assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
    assert_true(r.h_auto);
    report_residual(speeds[k], r.h_omega_c_max, FB_H_OMEGA_C_BOUND);
    if (!(r.h_omega_c_max > 0.0 && r.h_omega_c_max <= FB_H_OMEGA_C_BOUND))
      fail_msg("%s: h omega_c %g after %d re-choices", speeds[k], r.h_omega_c_max, r.h_rechosen);
    for (int w = 0; w < r.model[0].warning_count; w++)
      assert_int_not_equal(r.model[0].warnings[w].kind, FB_WARN_UNDER_RESOLVED);
    fb_run_free(&r);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_impacts_pair_by_time),
      cmocka_unit_test(test_impact_statistics_by_hand),
      cmocka_unit_test(test_impact_statistics_by_output_body),
      cmocka_unit_test(test_regular_paper_case),
      cmocka_unit_test(test_chaotic_rattling_pin),
      cmocka_unit_test(test_jobs_do_not_change_the_numbers),
      cmocka_unit_test(test_wrong_impacts_on_the_same_trajectory_are_an_error),
      cmocka_unit_test(test_auto_step_keeps_its_bound),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
