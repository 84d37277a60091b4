/* Clearance revolute joints in ODE: the pin-in-hole contact with mapped
 * ERP/CFM against statics, the zero-clearance limit, step convergence, and
 * the stability guard.
 *
 *          coupler hole (radius R + c)
 *            .-----.
 *           /  .-.  \      e = pin centre - hole centre
 *          |  ( o )--|-->  penetration = |e| - c when positive
 *           \  '-'  /      contact normal -e/|e| into the pin
 *            '-----'
 *        crank pin (radius R) */
#include <string.h>

#include "casefile.h"
#include "engine.h"
#include "fb_test.h"
#include "invdyn.h"
#include "outcome_text.h"
#include "run.h"
#include "ode_world.h" /* the ODE probe of the effective mass */

/* statics: the issue allows 2 %; after 1 s of settling with velocity damping
 * the residual is 4e-5 (the 14.5 um clearance shifts the geometry, and so
 * the reaction, by ~1e-4 at most): 1e-3 is a bound that can still fail */
#define STATIC_REL_TOL 1e-3
/* the bound on the zero-clearance limit (measured at c = 0.01 um
 * with K = 1e11 N/m^1.5, p = 1e9 N/m: omega peaks 2e-4, alpha peaks 2.5e-3) */
#define SMALL_CLEARANCE_REL_TOL 0.01
/* spike metrics at h = 5e-6 and 2.5e-6 s (3 revolutions, paper case):
 * measured differences 4.3 % (coupler alpha ratio, impact model), 3.4 %
 * (force), 3.3 % (penetration); at h = 1e-5 against 5e-6 they reach 33 %,
 * so the default step is not converged for spikes (said in docs/models.md).
 * Bound: 10 %. Impact counts and free-flight fractions do not converge (the
 * contact sequence is chaotic) and are not compared. */
#define SPIKE_CONVERGENCE_REL_TOL 0.10

static char paper_path[4096];

static void load(fb_case *c, const char **sets, int n) {
  fb_diag d;
  if (fb_casefile_load(c, paper_path, sets, n, &d) != FB_OK) fail_msg("%s", d.msg);
}

/* the crank held still at theta by the drive, body velocities damped by
 * damping per step, step 1e-5 s */
struct hold {
  double theta, damping;
};

static void hold_crank(fb_scene *def, void *user) {
  const struct hold *h = user;
  def->solver.h = 1e-5;
  def->settle_damping = h->damping;
  assert_int_equal(fb_scene_set_start(def, h->theta, 0.0, NULL), FB_OK);
}

static void test_static_penetration_matches_law(void **state) {
  (void)state;
  fb_case c;
  /* the secant row's statics are the law's; a matched row's static
   * stiffness is its a = k (1 - (omega h)^2 / 12 + zeta omega h + ...), not k
   * (contact.h), so this oracle holds the secant mapping at h = 1e-5 */
  const char *secant[] = {"clearance.mapping=secant", "solver.h_s=1e-5"};
  load(&c, secant, 2);
  fb_linkage su;
  fb_case_stackup_lengths(&c, &su);
  const double theta = 60.0 * M_PI / 180.0;
  fb_reactions rr;
  assert_int_equal(fb_invdyn_solve(&rr, &su, c.branch, c.link, c.gravity, theta, 1e-12, NULL), FB_OK);
  const double load_b = hypot(rr.force[1][0], rr.force[1][1]);
  const char *models[2] = {"ode-clearance-restitution", "ode-clearance-impact"};
  for (int model = 0; model < 2; model++) {
    /* the crank held at theta by the drive; frictionless: without velocity
     * damping the pin slides along the wall */
    fb_scene def;
    fb_model_scene sm;
    const fb_engine *e;
    const struct hold hold = {theta, 1e-3};
    void *s = fb_test_engine(&e, &sm, &def, &c, models[model], hold_crank, (void *)&hold);
    for (int k = 0; k < 100000; k++) e->step(s, NULL);
    fb_sample x;
    e->sample(s, &x);
    e->destroy(s);
    const fb_contact_law *l = &sm.law[FB_JOINT_B];
    const double want = l->kind == FB_LAW_IMPACT ? pow(load_b / l->stiffness, 1.0 / l->exponent)
                                                 : load_b / l->stiffness;
    const double pen = x.contact[FB_JOINT_B][FB_C_PEN];
    char name[64];
    snprintf(name, sizeof name, "static penetration, %s law", fb_law_name(l->kind));
    report_residual(name, fabs(pen - want) / want, STATIC_REL_TOL);
    assert_rel(pen, want, STATIC_REL_TOL);
    assert_rel(x.contact[FB_JOINT_B][FB_C_FORCE], load_b, STATIC_REL_TOL);
    /* the pin rests where the load points: e parallel to the force on the coupler */
    const double ex = x.contact[FB_JOINT_B][FB_C_EX], ey = x.contact[FB_JOINT_B][FB_C_EY];
    assert_near(atan2(ey, ex), atan2(rr.force[1][1], rr.force[1][0]), 1e-3);
  }
}

/* settles the crank-coupler pin statically (crank held at 60 deg, impact
 * law) with the exact collider (facets = 0) or a ring of facets boxes */
static fb_sample settle(const fb_case *c, int facets, int steps, double damping) {
  fb_case k = *c;
  if (facets) k.clearance.faceted_n = facets;
  fb_scene def;
  fb_model_scene sm;
  const fb_engine *e;
  const struct hold hold = {60.0 * M_PI / 180.0, damping};
  void *s = fb_test_engine(&e, &sm, &def, &k, facets ? "ode-clearance-faceted" : "ode-clearance-impact",
                           hold_crank, (void *)&hold);
  for (int i = 0; i < steps; i++) e->step(s, NULL);
  fb_sample x;
  e->sample(s, &x);
  e->destroy(s);
  return x;
}

static void test_faceted_gap_shrinks_with_n(void **state) {
  (void)state;
  /* measured static penetration gap to the exact collider: 0.284 um (16
   * boxes), 0.030 um (48), 0.0096 um (128); the contact force is the same
   * 1.2868 N in all: the wall's shape, not the law, makes the gap */
  fb_case c;
  load(&c, NULL, 0);
  const int facets[3] = {16, 48, 128};
  const fb_sample exact = settle(&c, 0, 30000, 3e-3);
  double prev = INFINITY;
  for (int i = 0; i < 3; i++) {
    const fb_sample f = settle(&c, facets[i], 30000, 3e-3);
    const double gap = fabs(f.contact[FB_JOINT_B][FB_C_PEN] - exact.contact[FB_JOINT_B][FB_C_PEN]);
    char name[64];
    snprintf(name, sizeof name, "faceted static gap, %d boxes [m]", facets[i]);
    report_residual(name, gap, prev);
    assert_true(gap < prev);
    prev = gap;
    assert_rel(f.contact[FB_JOINT_B][FB_C_FORCE], exact.contact[FB_JOINT_B][FB_C_FORCE], STATIC_REL_TOL);
  }
}

static const fb_peaks *peaks_of(const fb_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].run.name, name) == 0) return &r->model[i].peaks;
  fail_msg("model %s not run", name);
  return NULL;
}

static void test_small_clearance_approaches_ideal(void **state) {
  (void)state;
  const char *sets[] = {"run.models=ode-ideal-stackup,ode-clearance-restitution,ode-clearance-impact",
                        "run.revolutions=2", "clearance.penalty=explicit",
                        "clearance.penetration_limit_um=10"};
  fb_case c;
  load(&c, sets, 4);
  c.radial_clearance = 0.01e-6; /* 0.01 um (below the case-file's useful range) */
  static fb_run r;
  fb_diag d;
  if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_peaks *ideal = peaks_of(&r, "ode-ideal-stackup");
  const char *models[2] = {"ode-clearance-restitution", "ode-clearance-impact"};
  double worst = 0;
  for (int m = 0; m < 2; m++) {
    const fb_peaks *p = peaks_of(&r, models[m]);
    const double got[8] = {p->coupler.omega_max, p->coupler.omega_min, p->coupler.alpha_max,
                           p->coupler.alpha_min, p->follower.omega_max, p->follower.omega_min,
                           p->follower.alpha_max, p->follower.alpha_min};
    const double ref[8] = {ideal->coupler.omega_max, ideal->coupler.omega_min,
                           ideal->coupler.alpha_max, ideal->coupler.alpha_min,
                           ideal->follower.omega_max, ideal->follower.omega_min,
                           ideal->follower.alpha_max, ideal->follower.alpha_min};
    for (int i = 0; i < 8; i++) {
      worst = fmax(worst, fabs(got[i] - ref[i]) / fabs(ref[i]));
      assert_rel(got[i], ref[i], SMALL_CLEARANCE_REL_TOL);
    }
  }
  report_residual("clearance 0.01 um vs ideal peaks", worst, SMALL_CLEARANCE_REL_TOL);
  fb_run_free(&r);
}

static void test_spike_step_convergence(void **state) {
  (void)state;
  static fb_run a, b;
  const char *sa[] = {"run.models=ode-ideal-stackup,ode-clearance-restitution,ode-clearance-impact",
                      "solver.h_s=5e-6"};
  const char *sb[] = {"run.models=ode-ideal-stackup,ode-clearance-restitution,ode-clearance-impact",
                      "solver.h_s=2.5e-6"};
  fb_case ca, cb;
  load(&ca, sa, 2);
  load(&cb, sb, 2);
  fb_diag d;
  if (fb_run_case(&a, &ca, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  if (fb_run_case(&b, &cb, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  double worst = 0;
  for (int m = 1; m < 3; m++) {
    const fb_spikes *x = &a.model[m].spikes, *y = &b.model[m].spikes;
    assert_true(a.model[m].has_spikes && b.model[m].has_spikes);
    const double u[3] = {x->alpha_peak_ratio_coupler, x->force_max, x->penetration_max};
    const double v[3] = {y->alpha_peak_ratio_coupler, y->force_max, y->penetration_max};
    for (int i = 0; i < 3; i++) {
      worst = fmax(worst, fabs(u[i] - v[i]) / fabs(v[i]));
      assert_rel(u[i], v[i], SPIKE_CONVERGENCE_REL_TOL);
    }
  }
  report_residual("spikes h = 5e-6 vs 2.5e-6", worst, SPIKE_CONVERGENCE_REL_TOL);
  fb_run_free(&a);
  fb_run_free(&b);
}

static void run_joints(const char *joints) {
  char js[128];
  snprintf(js, sizeof js, "clearance.joints=%s", joints);
  const char *sets[] = {js, "run.models=ode-clearance-impact,ode-clearance-restitution",
                        "run.revolutions=2"};
  fb_case c;
  load(&c, sets, 3);
  static fb_run r;
  fb_diag d;
  if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s: %s", joints, d.msg);
  for (int m = 0; m < r.n; m++) {
    if (r.model[m].run.stop.kind != FB_STOP_NONE)
      fail_msg("%s, %s: stopped (kind %d)", joints, r.model[m].run.name, (int)r.model[m].run.stop.kind);
    assert_true(r.model[m].has_spikes);
    assert_int_equal(r.model[m].run.series.contact_mask, c.clearance.mask);
    assert_true(r.model[m].spikes.force_max > 0.0);
  }
  fb_run_free(&r);
}

static void test_two_clearance_joints_run(void **state) {
  (void)state;
  run_joints("crank-coupler, coupler-follower");
  run_joints("ground-crank, follower-ground"); /* drive through the angular motor */
}

static void test_stability_guard_names_reason(void **state) {
  (void)state;
  /* the paper's penalty read in N/mm is far too soft for the real joint
   * reaction: the pin sinks beyond the clearance and the model must stop
   * with a reason while the others run on */
  const char *sets[] = {"clearance.penalty=paper",
                        "run.models=ode-clearance-restitution,ode-ideal-stackup",
                        "run.revolutions=2"};
  fb_case c;
  load(&c, sets, 3);
  static fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  assert_int_equal(r.model[0].run.stop.kind, FB_STOP_PENETRATION);
  assert_int_equal(r.model[0].run.stop.joint, FB_JOINT_B);
  assert_true(r.model[0].run.stop.value > r.model[0].run.stop.limit);
  assert_int_equal(r.model[1].run.stop.kind, FB_STOP_NONE);
  /* what was kept is finite */
  const fb_series *s = &r.model[0].run.series;
  for (size_t i = 0; i < s->n; i++) assert_true(isfinite(s->coupler_alpha[i]));
  fb_run_free(&r);
}

/* issue 28 item 2: a step at which the matched row aliases (omega_d h past
 * FB_MATCHED_ALIAS_BOUND) is refused at the first such contact step with
 * the largest usable step, instead of running on a row that has lost its
 * spring (the paper case at 5e-5 s used to stop "unstable": the pin left the
 * hole). 2e-5 s (largest omega_d h ~2.6 measured) still finishes; the
 * tangent row, which has no aliasing, is not refused at 5e-5 s. */
static void test_aliased_step_is_refused(void **state) {
  (void)state;
  const char *sets[] = {"solver.h_s=5e-5", "run.revolutions=2",
                        "run.models=ode-clearance-impact,ode-clearance-restitution"};
  fb_case c;
  load(&c, sets, 3);
  static fb_run r;
  fb_diag d;
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  for (int m = 0; m < 2; m++) {
    const fb_stop *st = &r.model[m].run.stop;
    assert_int_equal(st->kind, FB_STOP_ALIASED);
    assert_int_equal(st->joint, FB_JOINT_B);
    assert_true(st->value > FB_MATCHED_ALIAS_BOUND);
    assert_near(st->limit, FB_MATCHED_ALIAS_BOUND, 0.0);
    /* the named step is the one that brings this contact's omega_d h to the bound */
    assert_rel(st->h_max, 5e-5 * FB_MATCHED_ALIAS_BOUND / st->value, 1e-12);
    assert_true(st->h_max < 5e-5);
    char text[512];
    fb_stop_text(text, sizeof text, st);
    assert_non_null(strstr(text, "aliased"));
    assert_non_null(strstr(text, "largest usable step"));
  }
  fb_run_free(&r);
  const char *fine[] = {"solver.h_s=2e-5", "run.revolutions=2",
                        "run.models=ode-clearance-impact,ode-clearance-restitution"};
  load(&c, fine, 3);
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  for (int m = 0; m < 2; m++) assert_int_equal(r.model[m].run.stop.kind, FB_STOP_NONE);
  fb_run_free(&r);
  const char *tangent[] = {"solver.h_s=5e-5", "run.revolutions=2", "clearance.mapping=tangent",
                           "run.models=ode-clearance-impact"};
  load(&c, tangent, 4);
  assert_int_equal(fb_run_case(&r, &c, NULL, NULL, &d), FB_OK);
  assert_true(r.model[0].run.stop.kind != FB_STOP_ALIASED);
  fb_run_free(&r);
}

/* ODE's probe against the engine-free KKT effective mass, at h = 1e-6 s:
 * the probe's velocity change (~1e-3 m/s against speeds ~10 m/s) carries
 * ~1e-12 of rounding; the hinges' world CFM (1e-10 m/(N s)) softens them by
 * CFM / (h w^T M^-1 w) ~ 1e-5; the bodies move by h v ~ 1e-5 m during the
 * probe's step, which the KKT form (at the start of the step) does not see.
 * Measured: 2.2e-4 at h = 1e-6 (1.4e-3 at 1e-5: the step's motion
 * dominates). Bound 1e-3. */
#define PROBE_REL_TOL 1e-3

/* the crank at start[0] turning at the case's speed, step start[1] */
static void probe_start(fb_scene *def, void *user) {
  const double *start = user;
  def->solver.h = start[1];
  assert_int_equal(fb_scene_set_start(def, start[0], def->omega2, NULL), FB_OK);
}

static void test_effective_mass_matches_ode_probe(void **state) {
  (void)state;
  fb_case c;
  load(&c, NULL, 0);
  /* one joint at a time, and the two coupler pins at once */
  const int masks[4] = {1 << FB_JOINT_A, 1 << FB_JOINT_B, 1 << FB_JOINT_D,
                        (1 << FB_JOINT_B) | (1 << FB_JOINT_C)};
  double worst = 0.0;
  for (int mi = 0; mi < 4; mi++)
    for (double theta = 0.3; theta < 6.3; theta += 1.5) {
      fb_case k = c;
      k.clearance.mask = masks[mi];
      fb_scene def;
      fb_model_scene sm;
      const fb_engine *e;
      const double start[2] = {theta, 1e-6};
      fb_ode_world *s = fb_test_engine(&e, &sm, &def, &k, "ode-clearance-impact", probe_start,
                                   (void *)start);
      fb_mechanism m;
      fb_ode_world_mechanism(s, &m);
      double w[4][2][2];
      assert_int_equal(fb_effective_mass_tensor(w, &m, NULL), FB_OK);
      for (int j = 0; j < 4; j++) {
        if (!(masks[mi] & (1 << j))) continue;
        for (double phi = 0.2; phi < 2.0 * M_PI; phi += 1.3) {
          const double n[2] = {cos(phi), sin(phi)};
          const double me = fb_effective_mass_along(w[j], n);
          double inv;
          /* a force giving a velocity change of ~1e-3 m/s */
          assert_int_equal(fb_ode_world_probe_inverse_mass(s, j, n, 1e-3 * me / def.solver.h, &inv, NULL),
                           FB_OK);
          worst = fmax(worst, fabs(1.0 / inv / me - 1.0));
          assert_rel(1.0 / inv, me, PROBE_REL_TOL);
        }
      }
      e->destroy(s);
    }
  report_residual("ODE probe vs KKT effective mass", worst, PROBE_REL_TOL);
}

/* The acceptance figures for the matched mapping with the true
 * effective mass, paper case (3 revolutions, peaks over revolutions 2-3,
 * both models' spikes refined between samples). Measured: impact model
 * force / penetration +0.19 % / -0.03 % at h = 5e-6, +0.01 % / -0.13 % at
 * 2e-6, coupler spike +0.14 % at 2e-6; restitution model first three impacts
 * within 1.7 % at 5e-6 (the second impact's penetration), impact count 29
 * against 29 at 2e-6. */
#define MATCHED_5E6_REL_TOL 0.01
#define MATCHED_2E6_REL_TOL 0.005
#define MATCHED_SPIKE_2E6_REL_TOL 0.02
#define FIRST_IMPACTS_REL_TOL 0.02
#define IMPACT_COUNT_REL_TOL 0.15

static double spike(const fb_peaks *p) {
  return fmax(fabs(p->coupler.alpha_max), fabs(p->coupler.alpha_min));
}

static const fb_model_result *result_of(const fb_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].run.name, name) == 0) return &r->model[i];
  fail_msg("model %s did not run", name);
  return NULL;
}

static void test_matched_impact_model_against_reference(void **state) {
  (void)state;
  const char *hs[2] = {"solver.h_s=5e-6", "solver.h_s=2e-6"};
  const double tol[2] = {MATCHED_5E6_REL_TOL, MATCHED_2E6_REL_TOL};
  for (int i = 0; i < 2; i++) {
    static fb_run r;
    const char *sets[] = {"run.models=ode-clearance-impact,reference", "clearance.mapping=matched",
                          hs[i]};
    fb_case c;
    load(&c, sets, 3);
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const fb_model_result *m = result_of(&r, "ode-clearance-impact");
    const fb_model_result *ref = result_of(&r, "reference");
    assert_true(m->has_ref_error);
    char name[96];
    snprintf(name, sizeof name, "matched impact force, %s", hs[i]);
    report_residual(name, m->ref_error.force_max_rel, tol[i]);
    snprintf(name, sizeof name, "matched impact penetration, %s", hs[i]);
    report_residual(name, m->ref_error.penetration_max_rel, tol[i]);
    assert_true(fabs(m->ref_error.force_max_rel) < tol[i]);
    assert_true(fabs(m->ref_error.penetration_max_rel) < tol[i]);
    if (i == 1) {
      const double rel = spike(&m->peaks) / spike(&ref->peaks) - 1.0;
      report_residual("matched coupler alpha spike, h = 2e-6", rel, MATCHED_SPIKE_2E6_REL_TOL);
      assert_true(fabs(rel) < MATCHED_SPIKE_2E6_REL_TOL);
    }
    fb_run_free(&r);
  }
}

static void test_matched_restitution_model_against_reference(void **state) {
  (void)state;
  const char *hs[2] = {"solver.h_s=5e-6", "solver.h_s=2e-6"};
  for (int i = 0; i < 2; i++) {
    static fb_run r;
    const char *sets[] = {"run.models=ode-clearance-restitution,reference-restitution",
                          "clearance.mapping=matched", hs[i]};
    fb_case c;
    load(&c, sets, 3);
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const fb_reference_error *e = &result_of(&r, "ode-clearance-restitution")->ref_error;
    if (i == 0) {
      assert_int_equal(e->first_impacts, FB_FIRST_IMPACTS);
      double worst = 0.0;
      for (int k = 0; k < FB_FIRST_IMPACTS; k++) {
        worst = fmax(worst, fmax(fabs(e->first_impact_force_rel[k]),
                                 fabs(e->first_impact_penetration_rel[k])));
        assert_true(fabs(e->first_impact_force_rel[k]) < FIRST_IMPACTS_REL_TOL);
        assert_true(fabs(e->first_impact_penetration_rel[k]) < FIRST_IMPACTS_REL_TOL);
      }
      report_residual("restitution first three impacts, h = 5e-6", worst, FIRST_IMPACTS_REL_TOL);
    } else {
      const double rel = (double)e->impacts / e->impacts_reference - 1.0;
      report_residual("restitution impact count, h = 2e-6", rel, IMPACT_COUNT_REL_TOL);
      assert_true(e->impacts_reference > 0 && fabs(rel) <= IMPACT_COUNT_REL_TOL);
    }
    fb_run_free(&r);
  }
}

/* issue 28 item 1, the done-when: the persistent-contact penetration
 * (summary.json's persistent_penetration_rel: penetration summed over the
 * samples where model and reference are both in continuous contact) of
 * the paper case at the automatic step within 1 % of the reference with
 * mapping = matched-static, for the impact law and the restitution law at
 * cr 0.9 and the heavily damped cr 0.14. Measured: impact -0.005 %,
 * restitution +0.19 % (cr 0.9) and -0.03 % (cr 0.14); the matched mapping
 * gives -0.59 %, +0.09 % and -7.1 % (its static stiffness a > k, and the
 * steady drift of ODE's position update that its damper sees: contact.md),
 * so the heavily damped case also shows the test can fail. */
#define PERSISTENT_PENETRATION_REL_TOL 0.01

static void test_persistent_contact_penetration(void **state) {
  (void)state;
  const char *crs[2] = {"clearance.restitution=0.14", "clearance.restitution=0.9"};
  for (int i = 0; i < 2; i++) {
    const char *maps[2] = {"clearance.mapping=matched-static", "clearance.mapping=matched"};
    for (int k = 0; k < (i == 0 ? 2 : 1); k++) {
      const char *sets[] = {i == 0 && k == 0
                                ? "run.models=ode-clearance-restitution,reference-restitution,"
                                  "ode-clearance-impact,reference"
                                : "run.models=ode-clearance-restitution,reference-restitution",
                            maps[k], crs[i]};
      fb_case c;
      load(&c, sets, 3);
      static fb_run r;
      fb_diag d;
      if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
      const char *models[2] = {"ode-clearance-restitution", "ode-clearance-impact"};
      for (int m = 0; m < (i == 0 && k == 0 ? 2 : 1); m++) {
        const fb_reference_error *e = &result_of(&r, models[m])->ref_error;
        assert_true(e->persistent_samples > 1000);
        char name[128];
        snprintf(name, sizeof name, "persistent penetration, %s, %s, %s", models[m], maps[k] + 18,
                 crs[i] + 10);
        report_residual(name, e->persistent_penetration_rel, PERSISTENT_PENETRATION_REL_TOL);
        if (k == 0) assert_true(fabs(e->persistent_penetration_rel) < PERSISTENT_PENETRATION_REL_TOL);
        else assert_true(fabs(e->persistent_penetration_rel) > PERSISTENT_PENETRATION_REL_TOL);
      }
      fb_run_free(&r);
    }
  }
}

/* [solver] h_s = adaptive in ODE (step_control.h: persistent contact on the
 * ideal load's schedule, the step held inside impacts), paper case, 2
 * revolutions against the reference. Impact model (it follows the
 * reference through revolution 2): measured force -8.2e-3, penetration
 * +3.0e-3, coupler spike +4.0e-4, impacts 3 / 3; over load shares 0.004 to
 * 0.008 (before the hold) force and penetration stayed within 8.4e-3 and
 * the spike within 1.1e-2 (docs/step-size.md). Bounds: 1e-2 (force,
 * penetration) and 2e-2 (spike), which the penetration-rate rule before the
 * schedule missed (force -4.2e-3, penetration +6.4e-3, coupler spike
 * +2.4e-2). Restitution model: its first three impacts (from t = 0, before
 * any chaos) to the 2 % (measured 0.75 %, force or penetration;
 * +8.5 % without the hold); after its sixth impact in revolution 2 it parts
 * from the reference, whose own count spans 12 to 15 over starts 1.45e-11 m
 * apart, so its count is the mean over an 8-member ensemble (run.ensemble,
 * docs/chaos.md; measured 14.9 against 13.75, +8 %) held to the issue's
 * 15 %, and its peaks are compared by the ensemble's statistics (agree:
 * every pooled statistic within the product's bound; force p90 -0.1 %). */
#define ODE_ADAPTIVE_PEAK_REL_TOL 1e-2
#define ODE_ADAPTIVE_SPIKE_REL_TOL 2e-2
static void test_adaptive_against_reference(void **state) {
  (void)state;
  const char *models[2][2] = {{"ode-clearance-impact", "reference"},
                              {"ode-clearance-restitution", "reference-restitution"}};
  for (int i = 0; i < 2; i++) {
    char list[128];
    snprintf(list, sizeof list, "run.models=%s,%s", models[i][0], models[i][1]);
    const char *sets[] = {list, "solver.h_s=adaptive", "run.revolutions=2", "run.ensemble=8"};
    fb_case c;
    load(&c, sets, i == 0 ? 3 : 4);
    static fb_run r;
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const fb_model_result *m = result_of(&r, models[i][0]), *ref = result_of(&r, models[i][1]);
    assert_true(m->has_ref_error);
    const fb_reference_error *e = &m->ref_error;
    const double sp = spike(&m->peaks) / spike(&ref->peaks) - 1.0;
    /* the impact model's count in its one run; the restitution model's
     * ensemble mean against the reference's */
    const double count =
        i == 0 ? (double)e->impacts / e->impacts_reference - 1.0
               : ((double)m->ensemble.pooled.force.n / m->ensemble.members) /
                         ((double)ref->ensemble.pooled.force.n / ref->ensemble.members) -
                     1.0;
    if (i == 1) {
      /* the first three impacts (from t = 0, before any chaos) */
      assert_int_equal(m->ensemble.members, 8);
      assert_int_equal(e->first_impacts, FB_FIRST_IMPACTS);
      double worst = 0.0;
      for (int k = 0; k < FB_FIRST_IMPACTS; k++)
        worst = fmax(worst, fmax(fabs(e->first_impact_force_rel[k]),
                                 fabs(e->first_impact_penetration_rel[k])));
      report_residual("ode-clearance-restitution adaptive first three impacts", worst,
                      FIRST_IMPACTS_REL_TOL);
      assert_true(worst < FIRST_IMPACTS_REL_TOL);
    }
    char name[128];
    snprintf(name, sizeof name, "%s adaptive force", models[i][0]);
    report_residual(name, e->force_max_rel, ODE_ADAPTIVE_PEAK_REL_TOL);
    snprintf(name, sizeof name, "%s adaptive penetration", models[i][0]);
    report_residual(name, e->penetration_max_rel, ODE_ADAPTIVE_PEAK_REL_TOL);
    snprintf(name, sizeof name, "%s adaptive coupler spike", models[i][0]);
    report_residual(name, sp, ODE_ADAPTIVE_SPIKE_REL_TOL);
    snprintf(name, sizeof name, "%s adaptive impact count", models[i][0]);
    report_residual(name, count, IMPACT_COUNT_REL_TOL);
    if (i == 0) {
      assert_false(m->divergence.diverged);
      assert_true(fabs(e->force_max_rel) < ODE_ADAPTIVE_PEAK_REL_TOL);
      assert_true(fabs(e->penetration_max_rel) < ODE_ADAPTIVE_PEAK_REL_TOL);
      assert_true(fabs(sp) < ODE_ADAPTIVE_SPIKE_REL_TOL);
    } else {
      /* the restitution model parts from the reference after its sixth
       * impact in revolution 2: its window peaks are one sample of a chaotic
       * sequence, compared by the ensemble's statistics (docs/chaos.md) */
      assert_true(m->has_stats_compare);
      report_residual("ode-clearance-restitution adaptive pooled force p90",
                      m->stats_compare.rel.force.p90, FB_MATCHED_IMPACT_ERROR_BOUND);
      assert_int_equal(m->stats_compare.agree, 1);
    }
    assert_true(e->impacts_reference > 0 && fabs(count) <= IMPACT_COUNT_REL_TOL);
    /* the steps: on the grid, far fewer than the samples, none above h_max */
    assert_true(m->run.has_step_stats);
    assert_true(m->run.step_stats.steps < m->run.series.n / 5);
    assert_true(m->run.step_stats.h_max <= 2e-5 * (1 + 1e-12));
    fb_run_free(&r);
  }
}

/* [solver] rocking_h_omega (step_control.h, contact.h; docs/step-size.md):
 * ODE's adaptive row with the rocking bound keeps the phase of the pin's
 * rocking along the wall, which times the sliding hit of revolution 2; the
 * shipped row (bound off) loses it. Paper case, impact model, 2 revolutions
 * against the reference, measured: with the bound 0.1 force +1.6e-3,
 * penetration -8.1e-5, direction error 4.3e-3 rad (+1.2e-3 to +1.8e-3 and
 * -3.2e-4 to +5e-7 over h_max_s 1e-5 to 3e-5 and accuracy 0.1); without it
 * -8.2e-3, +3.0e-3 and 3.45e-2 rad (the rocking's own amplitude). */
#define ROCKING_PEAK_REL_TOL 2e-3      /* issue 43's target on force and penetration */
#define ROCKING_DIRECTION_KEPT_RAD 1e-2 /* kept: below a third of the swing's amplitude */
#define ROCKING_DIRECTION_LOST_RAD 2e-2 /* lost: above two thirds of it */
static void test_adaptive_rocking_bound(void **state) {
  (void)state;
  double dir[2];
  for (int on = 0; on < 2; on++) {
    const char *sets[] = {"run.models=ode-clearance-impact,reference", "solver.h_s=adaptive",
                          "run.revolutions=2",
                          on ? "solver.rocking_h_omega=0.1" : "solver.rocking_h_omega=0"};
    fb_case c;
    load(&c, sets, 4);
    static fb_run r;
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const fb_model_result *m = result_of(&r, "ode-clearance-impact");
    assert_true(m->has_ref_error);
    const fb_reference_error *e = &m->ref_error;
    dir[on] = e->ecc_direction_rms;
    report_residual(on ? "rocking 0.1 direction [rad]" : "rocking off direction [rad]", dir[on],
                    on ? ROCKING_DIRECTION_KEPT_RAD : ROCKING_DIRECTION_LOST_RAD);
    if (on) {
      report_residual("rocking 0.1 force", e->force_max_rel, ROCKING_PEAK_REL_TOL);
      report_residual("rocking 0.1 penetration", e->penetration_max_rel, ROCKING_PEAK_REL_TOL);
      assert_true(fabs(e->force_max_rel) < ROCKING_PEAK_REL_TOL);
      assert_true(fabs(e->penetration_max_rel) < ROCKING_PEAK_REL_TOL);
      /* none of its steps above h_max */
      assert_true(m->run.step_stats.h_max <= 2e-5 * (1 + 1e-12));
    }
    fb_run_free(&r);
  }
  assert_true(dir[1] < ROCKING_DIRECTION_KEPT_RAD);
  assert_true(dir[0] > ROCKING_DIRECTION_LOST_RAD);
}

int main(void) {
  const char *d = getenv("FOURBAR_CASES_DIR");
  snprintf(paper_path, sizeof paper_path, "%s/paper_crank_rocker.ini", d ? d : "cases");
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_static_penetration_matches_law),
      cmocka_unit_test(test_small_clearance_approaches_ideal),
      cmocka_unit_test(test_spike_step_convergence),
      cmocka_unit_test(test_two_clearance_joints_run),
      cmocka_unit_test(test_stability_guard_names_reason),
      cmocka_unit_test(test_aliased_step_is_refused),
      cmocka_unit_test(test_faceted_gap_shrinks_with_n),
      cmocka_unit_test(test_effective_mass_matches_ode_probe),
      cmocka_unit_test(test_matched_impact_model_against_reference),
      cmocka_unit_test(test_matched_restitution_model_against_reference),
      cmocka_unit_test(test_persistent_contact_penetration),
      cmocka_unit_test(test_adaptive_against_reference),
      cmocka_unit_test(test_adaptive_rocking_bound),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
