/* Hard cases (the .ini files in cases/hard): each states its expected outcome in its
 * [expect] section (stable with error bounds at the case's step, or a clean
 * 'unstable' report with its reason); this test runs every one and checks
 * it, and that nothing non-finite was kept. */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "outcome_text.h"
#include "run.h"

static void check_case(const char *path) {
  fb_case c;
  fb_diag d;
  if (fb_casefile_load(&c, path, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  if (!c.expect.outcome[0]) fail_msg("%s: no [expect] outcome", path);
  static fb_run r;
  if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s: %s", path, d.msg);
  const fb_model_result *m = NULL;
  for (int i = 0; i < r.n; i++) {
    if (strcmp(r.model[i].run.name, c.expect.model) == 0) m = &r.model[i];
    const fb_series *s = &r.model[i].run.series;
    for (size_t k = 0; k < s->n; k++)
      if (!isfinite(s->coupler_alpha[k]) || !isfinite(s->follower_omega[k]))
        fail_msg("%s: %s kept a non-finite sample", path, r.model[i].run.name);
  }
  if (!m) fail_msg("%s: expect.model %s is not run", path, c.expect.model);
  const char *name = strrchr(path, '/') + 1;
  if (strcmp(c.expect.outcome, "unstable") == 0) {
    if (m->run.stop.kind != fb_stop_kind_parse(c.expect.reason))
      fail_msg("%s: expected stop '%s', got '%s'", name, c.expect.reason,
               fb_stop_kind_name(m->run.stop.kind));
    if (fb_test_verbose())
      fprintf(stderr, "  %-26s stopped as expected: %s at t = %g s\n", name,
              fb_stop_kind_name(m->run.stop.kind), m->run.stop.t);
  } else {
    if (m->run.stop.kind != FB_STOP_NONE)
      fail_msg("%s: expected stable, got stop '%s'", name, fb_stop_kind_name(m->run.stop.kind));
    if (c.expect.omega_peak_rel_max > 0) {
      const fb_error *e = &m->error;
      const double w = fmax(fmax(fabs(e->coupler.omega_max_rel), fabs(e->coupler.omega_min_rel)),
                            fmax(fabs(e->follower.omega_max_rel), fabs(e->follower.omega_min_rel)));
      report_residual(name, w, c.expect.omega_peak_rel_max);
      if (!(w <= c.expect.omega_peak_rel_max))
        fail_msg("%s: omega peak error %.3g > %.3g", name, w, c.expect.omega_peak_rel_max);
    }
    if (c.expect.force_peak_rel_max > 0) {
      if (!m->has_ref_error) fail_msg("%s: no reference to bound the force against", name);
      const double f = fabs(m->ref_error.force_max_rel);
      report_residual(name, f, c.expect.force_peak_rel_max);
      if (!(f <= c.expect.force_peak_rel_max))
        fail_msg("%s: force peak error %.3g > %.3g", name, f, c.expect.force_peak_rel_max);
    }
  }
  fb_run_free(&r);
}

static void check_one(const char *path, const char *name, void *user) {
  (void)name, (void)user;
  check_case(path);
}

static void test_hard_cases_meet_their_expectations(void **state) {
  (void)state;
  assert_true(fb_test_each_hard_case(check_one, NULL) >= 10);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(test_hard_cases_meet_their_expectations)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
