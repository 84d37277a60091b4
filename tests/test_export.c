/* fourbar export --format mjcf: the exported file as a MuJoCo user loads
 * it (mj_loadXML from disk, mj_resetDataKeyframe "start", mj_step with the
 * file's own drive), stepped for two crank revolutions, against the exact
 * analytic solution.
 *
 *        coupler
 *     B o-------o C
 *      /         \   follower
 * crank           \
 *    /             \
 *  A o==== ground ==o D      velocity actuator "drive" on ground-crank */
#include <math.h>
#include <mujoco/mujoco.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"
#include "casefile.h"
#include "export.h"
#include "fb_test.h"
#include "run.h"

/* the bound: coupler and follower omega peaks within 1e-3 of the
 * analytic solution (relative) */
#define PEAK_OMEGA_REL_TOL 1e-3
/* the step of the ideal export: test_mujoco measured the same loop and
 * flywheel at 1e-5 s within its 1e-4 bound */
#define IDEAL_H "solver.h_s=1e-5"

/* the bound on the clearance export: its peak contact force within
 * 10 % of the reference's (the same law, minimal coordinates, adaptive) over
 * the same two revolutions (measured +2.0 %: 5415 N against 5310 N at the
 * case's automatic step 3.3e-6 s; the export's damper is on the law's
 * design mass where the scene's own model uses the effective mass) */
#define CLEARANCE_FORCE_REL_TOL 0.10
/* revolutions stepped and compared: the two */
#define REVOLUTIONS 2.0

static mjModel *load(const char *text) {
  char path[] = "/tmp/fourbar_export_XXXXXX.xml";
  const int fd = mkstemps(path, 4);
  assert_true(fd >= 0);
  FILE *f = fdopen(fd, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
  char err[1024] = "";
  mjModel *m = mj_loadXML(path, NULL, err, sizeof err);
  remove(path);
  if (!m) fail_msg("mj_loadXML: %s", err);
  return m;
}

static void test_ideal_export_matches_analytic(void **state) {
  (void)state;
  static fb_case c;
  const char *sets[] = {IDEAL_H};
  fb_test_paper_case(&c, sets, 1);
  static char text[65536];
  fb_diag d;
  assert_int_equal(fb_export_mjcf(text, sizeof text, &c, 1, &d), FB_OK);
  mjModel *m = load(text);
  mjData *x = mj_makeData(m);
  /* the names the issue gives */
  const char *bodies[] = {"crank", "coupler", "follower"};
  for (int i = 0; i < 3; i++) assert_true(mj_name2id(m, mjOBJ_BODY, bodies[i]) >= 0);
  assert_true(mj_name2id(m, mjOBJ_SITE, "crank-coupler_pin") >= 0);
  assert_true(mj_name2id(m, mjOBJ_SITE, "crank-coupler_hole") >= 0);
  assert_int_equal(m->nu, 1);
  assert_int_equal(m->neq, 1);
  assert_int_equal(m->nkey, 1);
  mj_resetDataKeyframe(m, x, 0);
  const int crank = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "ground-crank")];
  const int coupler = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "crank-coupler")];
  const int follower = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "follower-ground")];
  const double omega2 = fb_case_omega2(&c);
  const long steps = lround(2.0 * 2.0 * M_PI / fabs(omega2) / m->opt.timestep);
  double cmax = -INFINITY, cmin = INFINITY, fmax_ = -INFINITY, fmin_ = INFINITY;
  for (long k = 0; k < steps; k++) {
    mj_step(m, x);
    const double wc = x->qvel[crank] + x->qvel[coupler], wf = x->qvel[follower];
    cmax = fmax(cmax, wc), cmin = fmin(cmin, wc);
    fmax_ = fmax(fmax_, wf), fmin_ = fmin(fmin_, wf);
  }
  fb_peaks p;
  assert_int_equal(fb_analytic_peaks(&p, &c.nominal, c.branch, omega2, &d), FB_OK);
  const double got[4] = {cmax, cmin, fmax_, fmin_};
  const double want[4] = {p.coupler.omega_max, p.coupler.omega_min, p.follower.omega_max,
                          p.follower.omega_min};
  for (int i = 0; i < 4; i++) {
    const double r = (got[i] - want[i]) / fabs(want[i]);
    if (fb_test_verbose()) fprintf(stderr, "  omega peak %d: %+.3e\n", i, r);
    if (!(fabs(r) <= PEAK_OMEGA_REL_TOL))
      fail_msg("omega peak %d: %.9g rad/s against the analytic %.9g (%+.3e)", i, got[i], want[i], r);
  }
  mj_deleteData(x);
  mj_deleteModel(m);
}

/* the largest limit force of the bore tendons in this forward pass [N] */
static double bore_force(const mjModel *m, const mjData *x) {
  double f = 0.0;
  for (int i = 0; i < x->nefc; i++)
    if (x->efc_type[i] == mjCNSTR_LIMIT_TENDON) f = fmax(f, x->efc_force[i]);
  (void)m;
  return f;
}

/* the clearance export of the paper case (crank-coupler, restitution law at
 * the case's automatic step) as a user runs it: its peak tendon-limit force
 * over two revolutions against the reference's peak over the same two
 * revolutions from the same start */
static void test_clearance_export_force_matches_reference(void **state) {
  (void)state;
  static fb_case c;
  fb_test_paper_case(&c, NULL, 0);
  static char text[65536];
  fb_diag d;
  assert_int_equal(fb_export_mjcf(text, sizeof text, &c, 0, &d), FB_OK);
  mjModel *m = load(text);
  mjData *x = mj_makeData(m);
  assert_true(mj_name2id(m, mjOBJ_TENDON, "crank-coupler_bore") >= 0);
  assert_true(mj_name2id(m, mjOBJ_SITE, "crank-coupler_pin") >= 0);
  assert_true(mj_name2id(m, mjOBJ_SITE, "crank-coupler_hole") >= 0);
  mj_resetDataKeyframe(m, x, 0);
  const double h = m->opt.timestep;
  const double omega2 = fb_case_omega2(&c);
  const long steps = lround(REVOLUTIONS * 2.0 * M_PI / fabs(omega2) / m->opt.timestep);
  double fmax_all = 0.0;
  for (long k = 0; k < steps; k++) {
    mj_step(m, x);
    /* efc_force of the state after the step: the forward pass of the next */
    mj_forward(m, x);
    fmax_all = fmax(fmax_all, bore_force(m, x));
    if (!isfinite(x->qvel[0])) fail_msg("exported model diverged at step %ld", k);
  }
  mj_deleteData(x);
  mj_deleteModel(m);
  /* the reference: the harness's model of the same law over the same span */
  static fb_run r;
  static fb_case rc;
  const char *sets[] = {"run.models=reference-restitution", "run.revolutions=2"};
  fb_test_paper_case(&rc, sets, 2);
  if (fb_run_case(&r, &rc, NULL, NULL, &d) != FB_OK) fail_msg("reference run failed: %s", d.msg);
  const fb_model_result *ref = &r.model[0];
  assert_int_equal(ref->run.stop.kind, FB_STOP_NONE);
  assert_true(ref->has_spikes);
  const double fref = fmax(ref->startup_force_max, ref->spikes.force_max);
  const double rel = (fmax_all - fref) / fref;
  if (fb_test_verbose())
    fprintf(stderr, "  clearance export peak force %.6g N, reference %.6g N: %+.3e (step %.6g s)\n",
            fmax_all, fref, rel, h);
  fb_run_free(&r);
  if (!(fabs(rel) <= CLEARANCE_FORCE_REL_TOL))
    fail_msg("exported peak contact force %.6g N against the reference's %.6g N (%+.3e)", fmax_all,
             fref, rel);
}

/* an export at a step beyond the run's resolution rule is written, and
 * says so (the note the command prints as a warning); so is one within it
 * whose contact fails contact-params' verification (the paper case at its
 * own step: h omega_c 0.43 at the law's design mass, its largest faithful
 * step 1.02e-6 s); at a step below that one it says nothing */
static void test_export_notes_an_unresolved_contact(void **state) {
  (void)state;
  static fb_case c;
  static char text[1 << 20];
  fb_diag d;
  fb_test_paper_case(&c, NULL, 0);
  assert_int_equal(fb_export_sdf(text, sizeof text, &c, 0, &d), FB_OK);
  assert_non_null(strstr(d.msg, "crank-coupler: at h = 3.317e-06 s this contact fails "
                                "contact-params' verification"));
  assert_non_null(strstr(d.msg, "its largest faithful step: 1.02e-06 s"));
  assert_int_equal(fb_export_mjcf(text, sizeof text, &c, 0, &d), FB_OK);
  assert_non_null(strstr(d.msg, "fails contact-params' verification"));
  const char *fine[] = {"solver.h_s=1e-6"};
  fb_test_paper_case(&c, fine, 1);
  assert_int_equal(fb_export_sdf(text, sizeof text, &c, 0, &d), FB_OK);
  assert_string_equal(d.msg, "");
  assert_int_equal(fb_export_mjcf(text, sizeof text, &c, 0, &d), FB_OK);
  assert_string_equal(d.msg, "");
  const char *sets[] = {"solver.h_s=2e-3"};
  fb_test_paper_case(&c, sets, 1);
  assert_int_equal(fb_export_sdf(text, sizeof text, &c, 0, &d), FB_OK);
  assert_non_null(strstr(d.msg, "crank-coupler: h omega_c"));
  assert_non_null(strstr(text, "<max_step_size>0.002</max_step_size>"));
  assert_int_equal(fb_export_mjcf(text, sizeof text, &c, 0, &d), FB_OK);
  assert_non_null(strstr(d.msg, "not faithful at this step"));
  /* the ideal mechanism has no contact to note */
  assert_int_equal(fb_export_sdf(text, sizeof text, &c, 1, &d), FB_OK);
  assert_string_equal(d.msg, "");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_ideal_export_matches_analytic),
      cmocka_unit_test(test_clearance_export_force_matches_reference),
      cmocka_unit_test(test_export_notes_an_unresolved_contact),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
