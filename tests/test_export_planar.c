/* fourbar export --format mjcf of a planar case (the Watt six-bar): the
 * exported file as a MuJoCo user loads it (mj_loadXML from disk,
 * mj_resetDataKeyframe "start", mj_step), stepped for two drive
 * revolutions, its every body's omega peaks against the harness's own
 * mujoco-ideal-nominal run of the case and against the analytic model.
 *
 *                 C                  G
 *                / \        rod  ____o-----__
 *       coupler /   \ ternary __/            --o F
 *    B o       \ ____/                 output
 *  crank/       o-------------o E
 *   A o         D                        drive at ground-crank (A) */
#include <math.h>
#include <mujoco/mujoco.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casefile.h"
#include "export.h"
#include "fb_test.h"
#include "planar_run.h"
#include "series.h"

/* the same file the harness compiles and the same start (the keyframe
 * holds the kit's velocities to 17 digits), stepped by mj_step where the
 * kit calls mj_forward and the integrator: the peaks agree to rounding
 * (measured: equal to the last bit, 0 relative, on every body) */
#define SAME_RUN_REL_TOL 1e-12
/* issue 58's bound on an engine's ideal six-bar: every body's omega
 * peaks within 1e-4 of the analytic ones, relative to the body's largest
 * |omega| (the harness's mujoco-ideal-nominal: 5.9e-7 at 1e-5 s) */
#define ANALYTIC_REL_TOL 1e-4
/* the case's revolutions here: two (the first the run-in, peaks over the
 * second, the harness's window) */
static const char *const sets[] = {"run.models=analytic,mujoco-ideal-nominal",
                                   "run.revolutions=2"};

static char text[1 << 20];

static void sixbar(fb_case *c) {
  char path[4096];
  const char *dir = getenv("FOURBAR_CASES_DIR");
  snprintf(path, sizeof path, "%s/watt_sixbar.ini", dir ? dir : "cases");
  fb_diag d;
  if (fb_casefile_load_planar(c, path, sets, 2, &d) != FB_OK) fail_msg("%s", d.msg);
}

static mjModel *load(const char *t) {
  char path[] = "/tmp/fourbar_export_planar_XXXXXX.xml";
  const int fd = mkstemps(path, 4);
  assert_true(fd >= 0);
  FILE *f = fdopen(fd, "w");
  assert_non_null(f);
  fputs(t, f);
  fclose(f);
  char err[1024] = "";
  mjModel *m = mj_loadXML(path, NULL, err, sizeof err);
  remove(path);
  if (!m) fail_msg("mj_loadXML: %s", err);
  return m;
}

/* r's model named name */
static const fb_planar_model *model_of(const fb_planar_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].name, name) == 0) return &r->model[i];
  fail_msg("no model %s in the run", name);
  return NULL;
}

/* the file from keyframe "start", n - 1 steps of mj_step, every body b's
 * (the file's b<k>, k = b - 1) omega extremes over the samples at t >=
 * t_window into pk[b] (max, min) */
static void file_peaks(double (*pk)[2], const mjModel *m, int nbodies, size_t n, double t_window) {
  mjData *x = mj_makeData(m);
  assert_int_equal(m->nkey, 1);
  mj_resetDataKeyframe(m, x, mj_name2id(m, mjOBJ_KEY, "start"));
  int id[16];
  for (int b = 1; b < nbodies; b++) {
    char name[16];
    snprintf(name, sizeof name, "b%d", b - 1);
    id[b] = mj_name2id(m, mjOBJ_BODY, name);
    assert_true(id[b] > 0);
    pk[b][0] = -INFINITY, pk[b][1] = INFINITY;
  }
  for (size_t i = 0; i < n; i++) {
    if (i > 0) mj_step(m, x);
    mj_kinematics(m, x);
    mj_comPos(m, x);
    mj_comVel(m, x);
    if ((double)i * m->opt.timestep < t_window) continue;
    for (int b = 1; b < nbodies; b++) {
      double v[6];
      mj_objectVelocity(m, x, mjOBJ_BODY, id[b], v, 0);
      if (!isfinite(v[2])) fail_msg("body b%d: non-finite omega at step %zu", b - 1, i);
      pk[b][0] = fmax(pk[b][0], v[2]), pk[b][1] = fmin(pk[b][1], v[2]);
    }
  }
  for (int i = 0; i < mjNWARNING; i++)
    if (x->warning[i].number) fail_msg("MuJoCo warning %d (%d times)", i, x->warning[i].number);
  mj_deleteData(x);
}

/* got's omega peaks of every body within tol of want's, relative to the
 * body's largest |omega| */
static void peaks_within(double (*got)[2], const fb_planar_run *r, const fb_planar_model *want,
                         double tol) {
  for (int b = 1; b < r->m->nbodies; b++) {
    const fb_body_peaks *w = &want->peaks[b];
    const double scale = fmax(fabs(w->omega_max), fabs(w->omega_min));
    const double e[2] = {(got[b][0] - w->omega_max) / scale, (got[b][1] - w->omega_min) / scale};
    for (int k = 0; k < 2; k++) {
      if (fb_test_verbose())
        fprintf(stderr, "  %s omega %s vs %s: %+.3e\n", r->m->body[b].name, k ? "min" : "max",
                want->name, e[k]);
      if (!(fabs(e[k]) <= tol))
        fail_msg("%s omega %s: the file's %.12g rad/s against %s's %.12g (%+.3e, bound %g)",
                 r->m->body[b].name, k ? "min" : "max", got[b][k],
                 want->name, k ? w->omega_min : w->omega_max, e[k], tol);
    }
  }
}

/* the exported six-bar, loaded and stepped by MuJoCo's own loader and
 * stepper, against the harness's run of the same model and the analytic */
static void test_sixbar_export_runs_as_the_harness(void **state) {
  (void)state;
  static fb_case c;
  static fb_planar_run r;
  fb_diag d;
  sixbar(&c);
  assert_int_equal(fb_export_mjcf(text, sizeof text, &c, 1, &d), FB_OK);
  assert_true(strncmp(text, "<!-- fourbar export of case watt_sixbar", 39) == 0);
  assert_non_null(strstr(text, "body b3 is rod"));
  mjModel *m = load(text);
  if (fb_planar_run_case(&r, &c, &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_planar_model *mj = model_of(&r, "mujoco-ideal-nominal");
  assert_true(fabs(m->opt.timestep - mj->h) <= 0.0);
  assert_int_equal(m->nbody, r.m->nbodies); /* the world and every moving body */
  double pk[16][2];
  file_peaks(pk, m, r.m->nbodies, mj->n, r.t_window);
  peaks_within(pk, &r, mj, SAME_RUN_REL_TOL);
  peaks_within(pk, &r, model_of(&r, "analytic"), ANALYTIC_REL_TOL);
  fb_planar_run_free(&r);
  mj_deleteModel(m);
}

/* the clearance joint is not in an MJCF (MuJoCo's planar clearance models
 * apply the law through the passive-force hook): without --ideal the
 * export is refused naming the flag; SDF of a planar case is refused
 * naming the format and the case type */
static void test_sixbar_refusals(void **state) {
  (void)state;
  static fb_case c;
  fb_diag d;
  sixbar(&c);
  assert_true(c.clearance.mask != 0);
  assert_int_equal(fb_export_mjcf(text, sizeof text, &c, 0, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "--ideal"));
  assert_int_equal(fb_export_sdf(text, sizeof text, &c, 1, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "--format sdf"));
  assert_non_null(strstr(d.msg, "type = planar"));
  /* a buffer too small: an error, never a cut file */
  assert_int_equal(fb_export_mjcf(text, 2048, &c, 1, &d), FB_ERR_RANGE);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_sixbar_export_runs_as_the_harness),
      cmocka_unit_test(test_sixbar_refusals),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
