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

/* the bound: coupler and follower omega peaks within 1e-3 of the
 * analytic solution (relative) */
#define PEAK_OMEGA_REL_TOL 1e-3
/* the step of the ideal export: test_mujoco measured the same loop and
 * flywheel at 1e-5 s within its 1e-4 bound */
#define IDEAL_H "solver.h_s=1e-5"

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

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_ideal_export_matches_analytic),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
