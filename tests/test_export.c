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
 *  A o==== ground ==o D      actuator "drive" on ground-crank */
#include <math.h>
#include <mujoco/mujoco.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"
#include "casefile.h"
#include "export.h"
#include "fb_test.h"
#include "planar_run.h"
#include "run.h"
#include "series.h"

/* the bound: coupler and follower omega peaks within 1e-3 of the
 * analytic solution (relative) at a fine step (measured within 1e-6 at the
 * file's own 3.3e-6 s and at 1e-5 s) */
#define PEAK_OMEGA_REL_TOL 1e-3
/* issue 59's bound at a user's coarse step (1 ms, 2 ms: 6 and 12 degrees of
 * crank a step): within 5 % (measured with MuJoCo 2.2.2: -0.32 % at 1 ms,
 * +0.73 % at 2 ms, the follower's largest peak at 2 ms) */
#define USER_STEP_PEAK_REL_TOL 0.05
/* the steps a user sets in <option timestep> [s]: the one the 2.2.2 test
 * used before (1e-5 s), 1 ms, and MuJoCo's default 2 ms */
static const double user_steps[] = {1e-5, 1e-3, 2e-3};
/* a plain load (mj_resetData) starts at rest; the export's drive reaches
 * the case's speed with its 10 ms time constant: after 0.1 s (10 time
 * constants) the speed error is e^-10 = 4.5e-5 of the speed, held to 1e-4 */
#define PLAIN_SPINUP_S 0.1
#define PLAIN_SPEED_REL_TOL 1e-4
/* the loop closes at qpos0 to rounding: the start's joint points agree to
 * 1e-12 m */
#define START_CLOSURE_M 1e-12

/* the bound on the clearance export: its peak contact force within
 * 10 % of the reference's (the same law, minimal coordinates, adaptive) over
 * the same two revolutions (measured +2.0 %: 5413 N against 5310 N at the
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

/* the file as a user edits it: text with its <option timestep> set to h
 * [s] into out (size bytes) */
static void with_timestep(char *out, size_t size, const char *text, double h) {
  const char *p = strstr(text, "timestep=\"");
  assert_non_null(p);
  const char *q = strchr(p + 10, '"');
  assert_non_null(q);
  const int n = snprintf(out, size, "%.*stimestep=\"%.17g%s", (int)(p - text), text, h, q);
  assert_true(n > 0 && (size_t)n < size);
}

/* the dof of joint `name` */
static int dof(const mjModel *m, const char *name) {
  const int j = mj_name2id(m, mjOBJ_JOINT, name);
  if (j < 0) fail_msg("no joint %s in the export", name);
  return m->jnt_dofadr[j];
}

/* steps from x's state: `skip` [s], then `revs` revolutions at omega2
 * [rad/s], the coupler's and the follower's omega peaks over the latter
 * into pk (max, min, max, min); fails on a non-finite state or a MuJoCo
 * warning (its "Nan, Inf or huge value in QACC") */
static void run_peaks(const mjModel *m, mjData *x, double omega2, double skip, double revs,
                      double pk[4]) {
  const int crank = dof(m, "ground-crank"), coupler = dof(m, "crank-coupler");
  const int follower = dof(m, "follower-ground");
  const double h = m->opt.timestep;
  const long n_skip = lround(skip / h);
  const long steps = n_skip + lround(revs * 2.0 * M_PI / fabs(omega2) / h);
  pk[0] = pk[2] = -INFINITY;
  pk[1] = pk[3] = INFINITY;
  for (long k = 0; k < steps; k++) {
    mj_step(m, x);
    const double wc = x->qvel[crank] + x->qvel[coupler], wf = x->qvel[follower];
    if (!isfinite(wc) || !isfinite(wf)) fail_msg("h = %g s: non-finite state at step %ld", h, k);
    if (k < n_skip) continue;
    pk[0] = fmax(pk[0], wc), pk[1] = fmin(pk[1], wc);
    pk[2] = fmax(pk[2], wf), pk[3] = fmin(pk[3], wf);
  }
  for (int i = 0; i < mjNWARNING; i++)
    if (x->warning[i].number) fail_msg("h = %g s: MuJoCo warning %d (%d times)", h, i,
                                       x->warning[i].number);
}

/* pk against the analytic peaks of case c within tol */
static void peaks_within(const double pk[4], const fb_case *c, double tol, double h) {
  fb_peaks p;
  fb_diag d;
  assert_int_equal(fb_analytic_peaks(&p, &c->nominal, c->branch, fb_case_omega2(c), &d), FB_OK);
  const double want[4] = {p.coupler.omega_max, p.coupler.omega_min, p.follower.omega_max,
                          p.follower.omega_min};
  for (int i = 0; i < 4; i++) {
    const double r = (pk[i] - want[i]) / fabs(want[i]);
    if (fb_test_verbose()) fprintf(stderr, "  h = %g s: omega peak %d: %+.3e\n", h, i, r);
    if (!(fabs(r) <= tol))
      fail_msg("h = %g s: omega peak %d: %.9g rad/s against the analytic %.9g (%+.3e, bound %g)",
               h, i, pk[i], want[i], r, tol);
  }
}

/* the file's leading comment holds no "--" before its end (XML 1.0,
 * section 2.5; MuJoCo's own parser lets it pass, Python's ElementTree does
 * not) */
static void comment_is_xml(const char *text) {
  const char *end = strstr(text, "-->");
  assert_non_null(end);
  for (const char *p = text + 4; p < end; p++)
    if (p[0] == '-' && p[1] == '-')
      fail_msg("a \"--\" inside the comment, %ld characters in", (long)(p - text));
}

/* the paper case's export (ideal, or with its clearance joint) into
 * text[size], loaded with its <option timestep> edited to h [s] as a user
 * does (h = 0: as written) */
static mjModel *paper_export(fb_case *c, char *text, size_t size, int ideal, double h) {
  static char edited[65536];
  fb_diag d;
  fb_test_paper_case(c, NULL, 0);
  assert_int_equal(fb_export_mjcf(text, size, c, ideal, &d), FB_OK);
  if (h > 0.0) with_timestep(edited, sizeof edited, text, h);
  return load(h > 0.0 ? edited : text);
}

/* the ideal export of the paper case as written (its step, 3.3e-6 s) and
 * with its timestep edited as a user does, from keyframe "start": two
 * revolutions without a warning, omega peaks within PEAK_OMEGA_REL_TOL up
 * to 1e-5 s and USER_STEP_PEAK_REL_TOL at 1 and 2 ms (before issue 59 the
 * edited file gave "Nan, Inf or huge value in QACC" at each) */
static void test_ideal_export_matches_analytic(void **state) {
  (void)state;
  static fb_case c;
  static char text[65536];
  for (int s = -1; s < (int)(sizeof user_steps / sizeof *user_steps); s++) {
    mjModel *m = paper_export(&c, text, sizeof text, 1, s < 0 ? 0.0 : user_steps[s]);
    mjData *x = mj_makeData(m);
    /* the start and drive are documented at the top of the file, in a
     * comment a strict XML parser takes (no "--" inside) */
    assert_true(strncmp(text, "<!-- fourbar export", 19) == 0);
    assert_non_null(strstr(text, "mj_resetDataKeyframe(m, d, 0)"));
    comment_is_xml(text);
    /* the names the issue gives */
    const char *bodies[] = {"crank", "coupler", "follower"};
    for (int i = 0; i < 3; i++) assert_true(mj_name2id(m, mjOBJ_BODY, bodies[i]) >= 0);
    assert_true(mj_name2id(m, mjOBJ_SITE, "crank-coupler_pin") >= 0);
    assert_true(mj_name2id(m, mjOBJ_SITE, "crank-coupler_hole") >= 0);
    assert_true(mj_name2id(m, mjOBJ_ACTUATOR, "drive") >= 0);
    assert_int_equal(m->nu, 1);
    assert_int_equal(m->neq, 1);
    assert_int_equal(m->nkey, 1);
    mj_resetDataKeyframe(m, x, 0);
    double pk[4];
    run_peaks(m, x, fb_case_omega2(&c), 0.0, REVOLUTIONS, pk);
    const double h = m->opt.timestep;
    peaks_within(pk, &c, h <= 1e-5 ? PEAK_OMEGA_REL_TOL : USER_STEP_PEAK_REL_TOL, h);
    mj_deleteData(x);
    mj_deleteModel(m);
  }
}

/* a plain load and step (mj_resetData, no keyframe), as a user's first
 * try: qpos0 is the start configuration (every joint's pin on its hole,
 * the loop closed), the drive spins the crank up from rest to the case's
 * speed with no ctrl set, and the motion then matches the analytic peaks
 * (before issue 59 a plain load stood still) */
static void test_plain_load_moves(void **state) {
  (void)state;
  static fb_case c;
  static char text[65536];
  mjModel *m = paper_export(&c, text, sizeof text, 1, 1e-3);
  mjData *x = mj_makeData(m);
  mj_resetData(m, x);
  mj_forward(m, x);
  static const char *const joints[] = {"ground-crank", "crank-coupler", "coupler-follower",
                                       "follower-ground"};
  for (int j = 0; j < 4; j++) {
    char pin[64], hole[64];
    snprintf(pin, sizeof pin, "%s_pin", joints[j]);
    snprintf(hole, sizeof hole, "%s_hole", joints[j]);
    const int a = mj_name2id(m, mjOBJ_SITE, pin), b = mj_name2id(m, mjOBJ_SITE, hole);
    assert_true(a >= 0 && b >= 0);
    const double dx = x->site_xpos[3 * a] - x->site_xpos[3 * b];
    const double dy = x->site_xpos[3 * a + 1] - x->site_xpos[3 * b + 1];
    if (!(hypot(dx, dy) <= START_CLOSURE_M))
      fail_msg("qpos0: joint %s's pin %.3g m from its hole", joints[j], hypot(dx, dy));
  }
  double pk[4];
  run_peaks(m, x, fb_case_omega2(&c), PLAIN_SPINUP_S, REVOLUTIONS, pk);
  const double w = x->qvel[dof(m, "ground-crank")], want = fb_case_omega2(&c);
  if (!(fabs(w - want) <= PLAIN_SPEED_REL_TOL * fabs(want)))
    fail_msg("plain load: crank at %.9g rad/s after %g s, the case's %.9g", w, PLAIN_SPINUP_S, want);
  peaks_within(pk, &c, USER_STEP_PEAK_REL_TOL, m->opt.timestep);
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

/* the clearance export with its timestep edited to 1e-5 s, three times
 * its own step and below the limit its header comment states (h omega_c
 * 2.8 at the law's design mass: 2.1e-5 s): two revolutions without a
 * warning (its contact, unlike the loop and the drive, is sized for the
 * written step; measured: it diverges between 2e-5 and 5e-5 s) */
static void test_clearance_export_edited_step_holds(void **state) {
  (void)state;
  static fb_case c;
  static char text[65536];
  mjModel *m = paper_export(&c, text, sizeof text, 0, 1e-5);
  assert_non_null(strstr(text, "it does not follow timestep"));
  comment_is_xml(text);
  mjData *x = mj_makeData(m);
  mj_resetDataKeyframe(m, x, 0);
  double pk[4];
  run_peaks(m, x, fb_case_omega2(&c), 0.0, REVOLUTIONS, pk);
  mj_deleteData(x);
  mj_deleteModel(m);
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

/* ---- a planar case (the Watt six-bar; the suite's quick-return): the
 * MJCF MuJoCo's kit binding writes for a user (mujoco-ideal-nominal's
 * mechanism, with the export's drive, loop and step rule), loaded by
 * mj_loadXML and stepped by mj_step as written and with its timestep
 * edited as a user does, against the analytic ----
 *
 *                 C                  G
 *                / \        rod  ____o-----__
 *       coupler /   \ ternary __/            --o F
 *    B o       \ ____/                 output
 *  crank/       o-------------o E
 *   A o         D                        drive at ground-crank (A) */

/* the file as written (the case's step): every body's omega peaks within
 * 1e-4 of the analytic ones, relative to the body's largest |omega|, the
 * bound on an engine's ideal six-bar (measured in 2.2.2, RK4 with the
 * loop's time-constant form: the six-bar 3.9e-8 at its 5e-6 s, the
 * quick-return 1.7e-6 at its 1e-5 s) */
#define ANALYTIC_REL_TOL 1e-4
/* at a user's step (1 ms, 2 ms): within 1 % (measured in 2.2.2, worst
 * body: the six-bar -0.035 % and +0.23 %, the quick-return -0.09 % and
 * -0.57 %; a 2 ms step turns its lever by up to 0.17 rad) */
#define PLANAR_USER_STEP_REL_TOL 1e-2
/* a step that resolves the six-bar's contact (its header's rule: 2.97e-6 s
 * or smaller at the rod-output joint's smallest effective mass) [s] */
#define SIXBAR_RESOLVED_H_S "2e-6"
/* the case's revolutions here: two (the first the run-in, peaks over the
 * second, the harness's window) */
static const char *const sets[] = {"run.models=analytic", "run.revolutions=2"};

static char planar_text[1 << 20];
static char planar_edited[1 << 20];

/* planar case file (under the shipped cases' folder) into *c with the
 * --set values set[n] */
static void planar_case_with(fb_case *c, const char *file, const char *const *set, int n) {
  char path[4096];
  const char *dir = getenv("FOURBAR_CASES_DIR");
  snprintf(path, sizeof path, "%s/%s", dir ? dir : "cases", file);
  fb_diag d;
  if (fb_casefile_load_planar(c, path, set, n, &d) != FB_OK) fail_msg("%s", d.msg);
}

static void planar_case(fb_case *c, const char *file) { planar_case_with(c, file, sets, 2); }

/* r's model named name */
static const fb_planar_model *model_of(const fb_planar_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].name, name) == 0) return &r->model[i];
  fail_msg("no model %s in the run", name);
  return NULL;
}

/* the file from keyframe "start", two revolutions at omega [rad/s] of
 * mj_step, every moving body b's (by its name in the case) omega extremes
 * over the second into pk[b] (max, min); each sample's velocities from
 * MuJoCo's kinematics at the state mj_step reached (its RK4 stages leave
 * cvel at an intermediate one) */
static void file_peaks(double (*pk)[2], const mjModel *m, const fb_planar *mech, double omega) {
  mjData *x = mj_makeData(m);
  assert_int_equal(m->nkey, 1);
  mj_resetDataKeyframe(m, x, mj_name2id(m, mjOBJ_KEY, "start"));
  int id[16];
  for (int b = 1; b < mech->nbodies; b++) {
    id[b] = mj_name2id(m, mjOBJ_BODY, mech->body[b].name);
    if (id[b] <= 0) fail_msg("no body %s in the export", mech->body[b].name);
    pk[b][0] = -INFINITY, pk[b][1] = INFINITY;
  }
  const double h = m->opt.timestep, period = 2.0 * M_PI / fabs(omega);
  const long n = lround(2.0 * period / h);
  for (long i = 1; i <= n; i++) {
    mj_step(m, x);
    mj_kinematics(m, x);
    mj_comPos(m, x);
    mj_comVel(m, x);
    if ((double)i * h < period) continue;
    for (int b = 1; b < mech->nbodies; b++) {
      double v[6];
      mj_objectVelocity(m, x, mjOBJ_BODY, id[b], v, 0);
      if (!isfinite(v[2]))
        fail_msg("h = %g s: body %s: non-finite omega at step %ld", h, mech->body[b].name, i);
      pk[b][0] = fmax(pk[b][0], v[2]), pk[b][1] = fmin(pk[b][1], v[2]);
    }
  }
  for (int i = 0; i < mjNWARNING; i++)
    if (x->warning[i].number)
      fail_msg("h = %g s: MuJoCo warning %d (%d times)", h, i, x->warning[i].number);
  mj_deleteData(x);
}

/* got's omega peaks of every body within tol of want's, relative to the
 * body's largest |omega| (a body that does not turn: within tol rad/s) */
static void body_peaks_within(double (*got)[2], const fb_planar_run *r, const fb_planar_model *want,
                              double tol, double h) {
  for (int b = 1; b < r->m->nbodies; b++) {
    const fb_body_peaks *w = &want->peaks[b];
    const double scale = fmax(fmax(fabs(w->omega_max), fabs(w->omega_min)), 1.0);
    const double e[2] = {(got[b][0] - w->omega_max) / scale, (got[b][1] - w->omega_min) / scale};
    for (int k = 0; k < 2; k++) {
      if (fb_test_verbose())
        fprintf(stderr, "  h = %g s: %s omega %s vs %s: %+.3e\n", h, r->m->body[b].name,
                k ? "min" : "max", want->name, e[k]);
      if (!(fabs(e[k]) <= tol))
        fail_msg("h = %g s: %s omega %s: the file's %.12g rad/s against %s's %.12g (%+.3e, "
                 "bound %g)", h, r->m->body[b].name, k ? "min" : "max", got[b][k],
                 want->name, k ? w->omega_min : w->omega_max, e[k], tol);
    }
  }
}

/* the exported planar case `file`: its comment, the case's names for every
 * body, every tree joint and every loop's connect, the drive's actuator,
 * one keyframe; stepped by MuJoCo's own loader and stepper as written and
 * at 1 ms and 2 ms against the analytic */
static void planar_export_holds(const char *file, const char *name, int loops) {
  static fb_case c;
  static fb_planar_run r;
  fb_diag d;
  planar_case(&c, file);
  assert_int_equal(fb_export_mjcf(planar_text, sizeof planar_text, &c, 1, &d), FB_OK);
  char head[128];
  snprintf(head, sizeof head, "<!-- fourbar export of case %s", name);
  assert_true(strncmp(planar_text, head, strlen(head)) == 0);
  comment_is_xml(planar_text);
  assert_non_null(strstr(planar_text, "mj_resetDataKeyframe(m, d, 0)"));
  if (fb_planar_run_case(&r, &c, &d) != FB_OK) fail_msg("%s", d.msg);
  const double steps[] = {0.0, 1e-3, 2e-3};
  for (size_t s = 0; s < sizeof steps / sizeof *steps; s++) {
    if (steps[s] > 0.0) with_timestep(planar_edited, sizeof planar_edited, planar_text, steps[s]);
    mjModel *m = load(steps[s] > 0.0 ? planar_edited : planar_text);
    assert_int_equal(m->nbody, r.m->nbodies); /* the world and every moving body */
    for (int j = 0; j < r.m->njoints; j++) /* a joint of the tree, or a loop's connect */
      if (mj_name2id(m, mjOBJ_JOINT, r.m->joint[j].name) < 0 &&
          mj_name2id(m, mjOBJ_EQUALITY, r.m->joint[j].name) < 0)
        fail_msg("joint %s is neither a <joint> nor a <connect> of the export",
                 r.m->joint[j].name);
    assert_int_equal(m->neq, loops);
    assert_int_equal(m->nu, 1);
    assert_true(mj_name2id(m, mjOBJ_ACTUATOR, "drive") >= 0);
    double pk[16][2];
    file_peaks(pk, m, r.m, fb_case_omega2(&c));
    body_peaks_within(pk, &r, model_of(&r, "analytic"),
                      steps[s] > 0.0 ? PLANAR_USER_STEP_REL_TOL : ANALYTIC_REL_TOL,
                      m->opt.timestep);
    mj_deleteModel(m);
  }
  fb_planar_run_free(&r);
}

/* the six-bar: seven revolute joints, two loops */
static void test_sixbar_export_holds(void **state) {
  (void)state;
  planar_export_holds("watt_sixbar.ini", "watt_sixbar", 2);
}

/* the quick-return: two prismatic joints in its two loops, each closed at
 * a pin (a connect holds a pin only) */
static void test_quick_return_export_holds(void **state) {
  (void)state;
  planar_export_holds("../tests/cases/quick_return.ini", "quick_return", 2);
}

/* the six-bar's clearance export (rod-output as MuJoCo's bore, model
 * mujoco-clearance-native's law) at a step that resolves its contact: the
 * case's names on the tendon and its sites, no note; its peak tendon-limit
 * force over two revolutions from keyframe "start" in MuJoCo's own
 * loader and stepper against reference-restitution's over the same two
 * revolutions from the same start (the four-bar's bound,
 * CLEARANCE_FORCE_REL_TOL) */
static void test_sixbar_clearance_export_force(void **state) {
  (void)state;
  static fb_case c;
  static fb_planar_run r;
  fb_diag d;
  const char *fine[] = {"run.models=reference-restitution", "run.revolutions=2",
                        "solver.h_s=" SIXBAR_RESOLVED_H_S};
  planar_case_with(&c, "watt_sixbar.ini", fine, 3);
  assert_int_equal(fb_export_mjcf(planar_text, sizeof planar_text, &c, 0, &d), FB_OK);
  assert_string_equal(d.msg, "");
  comment_is_xml(planar_text);
  assert_non_null(strstr(planar_text, "model mujoco-clearance-native"));
  assert_non_null(strstr(planar_text, "does not follow timestep"));
  mjModel *m = load(planar_text);
  assert_true(mj_name2id(m, mjOBJ_TENDON, "rod-output_bore") >= 0);
  assert_true(mj_name2id(m, mjOBJ_SITE, "rod-output_pin") >= 0);
  assert_true(mj_name2id(m, mjOBJ_SITE, "rod-output_hole") >= 0);
  assert_true(mj_name2id(m, mjOBJ_EQUALITY, "rod-output") < 0); /* the bore, not a loop */
  mjData *x = mj_makeData(m);
  mj_resetDataKeyframe(m, x, 0);
  const long steps = lround(REVOLUTIONS * 2.0 * M_PI / fabs(fb_case_omega2(&c)) / m->opt.timestep);
  double fmax_file = 0.0;
  for (long k = 0; k < steps; k++) {
    mj_step(m, x);
    mj_forward(m, x); /* efc_force at the state reached */
    fmax_file = fmax(fmax_file, bore_force(m, x));
    if (!isfinite(x->qvel[0])) fail_msg("the six-bar's clearance export diverged at step %ld", k);
  }
  for (int i = 0; i < mjNWARNING; i++)
    if (x->warning[i].number) fail_msg("MuJoCo warning %d (%d times)", i, x->warning[i].number);
  mj_deleteData(x);
  mj_deleteModel(m);
  if (fb_planar_run_case(&r, &c, &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_planar_model *ref = model_of(&r, "reference-restitution");
  assert_false(ref->ref.failed);
  double fref = 0.0;
  for (size_t i = 0; i < ref->n; i++)
    if (isfinite(ref->force[i])) fref = fmax(fref, ref->force[i]);
  fb_planar_run_free(&r);
  const double rel = (fmax_file - fref) / fref;
  if (fb_test_verbose())
    fprintf(stderr, "  six-bar clearance export peak force %.6g N, reference %.6g N: %+.3e\n",
            fmax_file, fref, rel);
  if (!(fabs(rel) <= CLEARANCE_FORCE_REL_TOL))
    fail_msg("the six-bar's exported peak contact force %.6g N against the reference's %.6g N "
             "(%+.3e)", fmax_file, fref, rel);
}

/* SDF of a planar case is refused naming the format and the case type; a
 * clearance export at the case's own step (5e-6 s: h omega_c 0.84 at the
 * joint's smallest effective mass) is written with the note that its
 * contact is not faithful there; a slider in its guide (a prismatic
 * clearance joint) is no MuJoCo bore: refused naming --ideal */
static void test_sixbar_refusals(void **state) {
  (void)state;
  static fb_case c;
  fb_diag d;
  planar_case(&c, "watt_sixbar.ini");
  assert_true(c.clearance.mask != 0);
  assert_int_equal(fb_export_mjcf(planar_text, sizeof planar_text, &c, 0, &d), FB_OK);
  assert_non_null(strstr(d.msg, "rod-output: h x omega_c = 0.842 at h = 5e-06 s passes 0.5"));
  assert_non_null(strstr(d.msg, "not faithful at this step"));
  static fb_case q;
  const char *loose[] = {"clearance.joints=ram-guide", "joint.ram-guide.slider_half_length_mm=20",
                         "joint.ram-guide.slider_half_height_mm=10",
                         "clearance.guide_clearance_mm=0.05", "clearance.penalty=explicit",
                         "clearance.penalty_n_m=1e8"};
  planar_case_with(&q, "../tests/cases/quick_return.ini", loose, 6);
  assert_int_equal(fb_export_mjcf(planar_text, sizeof planar_text, &q, 0, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "ram-guide"));
  assert_non_null(strstr(d.msg, "--ideal"));
  assert_int_equal(fb_export_sdf(planar_text, sizeof planar_text, &c, 1, &d), FB_ERR_ARG);
  assert_non_null(strstr(d.msg, "--format sdf"));
  assert_non_null(strstr(d.msg, "type = planar"));
  /* a buffer too small: an error, never a cut file */
  assert_int_equal(fb_export_mjcf(planar_text, 2048, &c, 1, &d), FB_ERR_RANGE);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_ideal_export_matches_analytic),
      cmocka_unit_test(test_plain_load_moves),
      cmocka_unit_test(test_clearance_export_force_matches_reference),
      cmocka_unit_test(test_clearance_export_edited_step_holds),
      cmocka_unit_test(test_export_notes_an_unresolved_contact),
      cmocka_unit_test(test_sixbar_export_holds),
      cmocka_unit_test(test_quick_return_export_holds),
      cmocka_unit_test(test_sixbar_clearance_export_force),
      cmocka_unit_test(test_sixbar_refusals),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
