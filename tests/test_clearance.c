/* Clearance revolute joints in ODE: the pin-in-hole contact with mapped
 * ERP/CFM against statics, the zero-clearance limit, step convergence, and
 * the stability guard; and ODE's slider-crank (issue 45, at the end): its
 * ideal models against the analytic solution, the piston pin's effective
 * mass, contact and colliders against the reference, its adaptive step.
 *
 *          coupler hole (radius R + c)
 *            .-----.
 *           /  .-.  \      e = pin centre - hole centre
 *          |  ( o )--|-->  penetration = |e| - c when positive
 *           \  '-'  /      contact normal -e/|e| into the pin
 *            '-----'
 *        crank pin (radius R) */
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "engine.h"
#include "fb_test.h"
#include "invdyn.h"
#include "load_scale.h"
#include "mech_kinematics.h"
#include "outcome_text.h"
#include "run.h"
#include "ode_world.h" /* the ODE probe of the effective mass */
#include "slider_crank_dynamics.h"

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
 * 15 %, and its peaks are compared by the ensemble's statistics (its
 * members' test, verdict_stats.h, not different; pooled force p90 -0.1 %). */
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
      assert_true(m->has_stats_compare && m->has_test);
      report_residual("ode-clearance-restitution adaptive pooled force p90",
                      m->stats_compare.rel.force.p90, FB_MATCHED_IMPACT_ERROR_BOUND);
      /* its members' statistics are not shown outside the verdict's margins
       * (verdict_stats.h; one look of 8 members at the full level) */
      assert_int_not_equal(m->test.decision, FB_EQUIV_DIFFERENT);
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

/* ---- the slider-crank in ODE (issue 45) ------------------------------------
 *
 *                  B            crank and rod hinged at A (driven) and B; the
 *                 / \           slider a body at the piston pin's hole centre
 *          crank /   \ rod      H on the guide y = offset, held by ODE's slider
 *               /     \         joint; at the piston pin C a hinge (ideal
 *              A      [H]--->x  models) or the pin-in-hole contact (pin on
 *                               the rod, hole on the slider)
 *
 * Two cases: SC_CASE_TEXT, a milder benchmark-like one written here (Flores
 * and Ambrosio's masses and pin, 100 um at the piston pin, 2000 rpm, a 6 mm
 * guide offset and tolerances so that the stack-up differs from the
 * nominal), and the shipped cases/slider_crank_flores.ini (500 um, 5000
 * rpm). */
static const char *const SC_CASE_TEXT =
    "[case]\n"
    "name = sc_ode\n"
    "[linkage]\n"
    "type = slider-crank\n"
    "crank_mm = 50\n"
    "coupler_mm = 120\n"
    "offset_mm = 6\n"
    "crank_angle0_deg = 20\n"
    "[tolerance]\n"
    "crank_plus_minus_mm = 0.05\n"
    "coupler_plus_minus_mm = 0.1\n"
    "offset_plus_minus_mm = 0.2\n"
    "stackup = max\n"
    "[mass]\n"
    "crank_kg = 0.30\n"
    "crank_inertia_kg_mm2 = 100\n"
    "crank_inertia_long_kg_mm2 = 5\n"
    "crank_inertia_transverse_kg_mm2 = 95\n"
    "coupler_kg = 0.21\n"
    "coupler_inertia_kg_mm2 = 250\n"
    "coupler_inertia_long_kg_mm2 = 10\n"
    "coupler_inertia_transverse_kg_mm2 = 240\n"
    "slider_kg = 0.14\n"
    "[drive]\n"
    "speed_rpm = 2000\n"
    "[pin]\n"
    "diameter_mm = 20\n"
    "radial_clearance_um = 100\n"
    "length_mm = 20\n"
    "[material]\n"
    "youngs_modulus_gpa = 207\n"
    "poisson_ratio = 0.3\n"
    "[clearance]\n"
    "joints = coupler-slider\n"
    "penalty = goldsmith\n"
    "restitution = 0.9\n"
    "[run]\n"
    "revolutions = 2\n"
    "ensemble = 1\n";

/* the test's slider-crank case (sc = 1) or the shipped Flores case (sc = 0)
 * with overrides */
static void load_sc(fb_case *c, int sc, const char **sets, int n) {
  fb_diag diag;
  const fb_status st = sc ? fb_test_case_text(c, SC_CASE_TEXT, sets, n, &diag)
                          : fb_test_shipped_case(c, "slider_crank_flores.ini", sets, n, &diag);
  if (st != FB_OK) fail_msg("case: %s", diag.msg);
}

static const char *const SC_CASE_NAME[2] = {"slider_crank_flores.ini", "the test's case"};

/* The done-when for the ideal models: every peak of the rod
 * (omega, alpha) and of the slider (v, a) within 1e-4 of the exact analytic
 * peaks of the same lengths, at the automatic step. Measured: 4.4e-6 on
 * both cases (Flores 2e-6 s, the test's case 5e-6 s), the semi-implicit
 * step's first-order error in alpha. The joint reactions' peaks (ODE's
 * joint feedback; the guide's from its slider joint) against the analytic
 * model's inverse dynamics: measured 5.5e-6, the same step's error carried
 * by the accelerations; bound 1e-4 as the peaks'. The hinges' and the
 * guide's drift: measured 9.7e-8 m on both cases (the four-bar's
 * cases/engines.ini: 3.5e-8 m), what world ERP 0.2 leaves of each step's
 * position error; bound 1e-6 m, 1 % of the test's clearance. */
#define SC_IDEAL_PEAK_REL_TOL 1e-4
#define SC_REACTION_REL_TOL 1e-4
#define SC_DRIFT_M 1e-6
/* the slider's x at the dead centres, sampled, against the exact ends of
 * the stroke: v = 0 there, so a sample h / 2 off misses by a h^2 / 8
 * ~ 1e-8 m (a ~ 2e4 m/s^2, h 2e-6 to 5e-6 s), and the loop's drift (above)
 * moves it by as much as its own 1e-7 m; measured 1.9e-7 m; bound 1e-6 m
 * (a four-bar's follower angle or the rod's in its place would be off by
 * centimetres) */
#define SC_STROKE_M 1e-6

/* largest reaction magnitude of joint j over the window t >= t0 */
static double reaction_peak(const fb_series *s, int j, double t0) {
  double m = 0.0;
  for (size_t k = 0; k < s->n; k++)
    if (s->t[k] >= t0) m = fmax(m, hypot(s->reaction[j][0][k], s->reaction[j][1][k]));
  return m;
}

static const fb_model_result *sc_result(const fb_run *r, const char *name) {
  for (int i = 0; i < r->n; i++)
    if (strcmp(r->model[i].run.name, name) == 0) return &r->model[i];
  fail_msg("model %s did not run", name);
  return NULL;
}

static void test_sc_ideal_against_analytic(void **state) {
  (void)state;
  double worst = 0.0, worst_r = 0.0, worst_d = 0.0, worst_x = 0.0;
  for (int sc = 0; sc < 2; sc++) {
    const char *sets[] = {"run.models=analytic,analytic-stackup,ode-ideal-nominal,ode-ideal-stackup",
                          "run.ensemble=1"};
    fb_case c;
    load_sc(&c, sc, sets, 2);
    static fb_run r;
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const char *pairs[2][2] = {{"ode-ideal-nominal", "analytic"},
                               {"ode-ideal-stackup", "analytic-stackup"}};
    for (int p = 0; p < 2; p++) {
      const fb_model_result *m = sc_result(&r, pairs[p][0]), *a = sc_result(&r, pairs[p][1]);
      assert_int_equal(m->run.stop.kind, FB_STOP_NONE);
      assert_true(m->has_error);
      for (int b = 0; b < 2; b++) { /* the rod, the slider */
        const fb_body_error *e = &m->error.body[b];
        const double rel[4] = {e->omega_max_rel, e->omega_min_rel, e->alpha_max_rel,
                               e->alpha_min_rel};
        for (int q = 0; q < 4; q++) {
          worst = fmax(worst, fabs(rel[q]));
          if (!(fabs(rel[q]) < SC_IDEAL_PEAK_REL_TOL))
            fail_msg("%s, %s body %d peak %d: %.3g", SC_CASE_NAME[sc], pairs[p][0], b, q, rel[q]);
        }
      }
      /* the slider's x is the analytic one (not the rod's angle or a
       * four-bar's follower): its stroke's ends */
      const double dx[2] = {m->peaks.body[1].pos_max - a->peaks.body[1].pos_max,
                            m->peaks.body[1].pos_min - a->peaks.body[1].pos_min};
      for (int q = 0; q < 2; q++) {
        worst_x = fmax(worst_x, fabs(dx[q]));
        assert_true(fabs(dx[q]) < SC_STROKE_M);
      }
      for (int j = 0; j < 4; j++) {
        const double got = reaction_peak(&m->run.series, j, r.t_window);
        const double want = reaction_peak(&a->run.series, j, r.t_window);
        worst_r = fmax(worst_r, fabs(got / want - 1.0));
        assert_rel(got, want, SC_REACTION_REL_TOL);
      }
      worst_d = fmax(worst_d, m->run.joint_drift_max);
      assert_true(m->run.joint_drift_max < SC_DRIFT_M);
    }
    fb_run_free(&r);
  }
  report_residual("slider-crank ideal peaks vs analytic", worst, SC_IDEAL_PEAK_REL_TOL);
  report_residual("slider-crank ideal reactions vs analytic", worst_r, SC_REACTION_REL_TOL);
  report_residual("slider-crank ideal joint drift [m]", worst_d, SC_DRIFT_M);
  report_residual("slider-crank ideal stroke ends [m]", worst_x, SC_STROKE_M);
}

/* two exact formulas of the same 2 x 2 tensor (test_slider_crank_clearance.c's
 * TENSOR_REL_TOL: the closed form against the KKT form's Cholesky solve) */
#define SC_TENSOR_REL_TOL 1e-9

/* ODE's probe of the piston pin's effective mass against the closed form
 * (effective_mass.h: the rod about the held B and the slider along x) on
 * the world's own configuration, at h = 1e-6 s: the same bound and reasons
 * as the four-bar's PROBE_REL_TOL; measured 1.8e-4. */
static void test_sc_effective_mass_matches_ode_probe(void **state) {
  (void)state;
  fb_case c;
  load_sc(&c, 0, NULL, 0);
  double worst = 0.0;
  for (double theta = 0.3; theta < 6.3; theta += 1.1) {
    fb_scene def;
    fb_model_scene sm;
    const fb_engine *e;
    const double start[2] = {theta, 1e-6};
    fb_ode_world *s = fb_test_engine(&e, &sm, &def, &c, "ode-clearance-impact", probe_start,
                                     (void *)start);
    fb_mechanism m;
    fb_ode_world_mechanism(s, &m);
    assert_int_equal(m.prismatic_mask, 1 << FB_JOINT_D);
    assert_int_equal(m.clearance_mask, 1 << FB_JOINT_C);
    double w[4][2][2], wk[4][2][2];
    assert_int_equal(fb_effective_mass_tensor(w, &m, NULL), FB_OK);
    /* the closed form is the general KKT form with the guide's rows */
    assert_int_equal(fb_effective_mass_tensor_kkt(wk, &m, NULL), FB_OK);
    for (int a = 0; a < 2; a++)
      for (int b = 0; b < 2; b++)
        assert_near(w[2][a][b], wk[2][a][b], SC_TENSOR_REL_TOL * fabs(w[2][0][0]));
    for (double phi = 0.2; phi < 2.0 * M_PI; phi += 1.3) {
      const double n[2] = {cos(phi), sin(phi)};
      const double me = fb_effective_mass_along(w[FB_JOINT_C], n);
      double inv;
      assert_int_equal(fb_ode_world_probe_inverse_mass(s, FB_JOINT_C, n, 1e-3 * me / def.solver.h,
                                                       &inv, NULL),
                       FB_OK);
      worst = fmax(worst, fabs(1.0 / inv / me - 1.0));
      assert_rel(1.0 / inv, me, PROBE_REL_TOL);
    }
    e->destroy(s);
  }
  report_residual("slider-crank ODE probe vs effective mass", worst, PROBE_REL_TOL);
}

/* The adaptive step's load schedule (load_scale.h) of a slider-crank is its
 * own inverse dynamics: the table's largest piston-pin and guide loads over
 * a revolution are slider_crank_invdyn's peaks on the same crank angles
 * (fb_mech_reaction_peaks; the same formula at the same angles: 1e-12);
 * the four-bar's call is the four-bar's table (fb_load_scale_build). */
#define SC_SAME_FORMULA_REL_TOL 1e-12
static void test_sc_load_schedule_is_its_own(void **state) {
  (void)state;
  fb_case c;
  load_sc(&c, 0, NULL, 0);
  const double w = fb_case_omega2(&c);
  fb_load_scale ls;
  assert_int_equal(fb_load_scale_build_mech(&ls, FB_MECH_SLIDER_CRANK, &c.nominal, c.branch,
                                            c.link, c.gravity, w, (1 << 2) | (1 << 3), 0.0, NULL),
                   FB_OK);
  double peak[4];
  assert_int_equal(fb_mech_reaction_peaks(peak, FB_MECH_SLIDER_CRANK, &c.nominal, c.branch,
                                          c.link, c.gravity, w, FB_LOAD_SCALE_SAMPLES, NULL),
                   FB_OK);
  for (int j = 2; j < 4; j++) {
    double most = 0.0;
    for (int k = 0; k < ls.n; k++) {
      double tau, f;
      fb_load_scale_at(&ls, j, 2.0 * M_PI * (k + 0.5) / ls.n, &tau, &f);
      most = fmax(most, f);
      assert_true(tau > 0.0);
    }
    assert_rel(most, peak[j], SC_SAME_FORMULA_REL_TOL);
  }
  fb_load_scale_free(&ls);
}

/* The impact model against the reference (matched impacts: the same impact
 * of both, paired by onset; their peak force and penetration).
 * - The test's case at h = 1.25e-7 s, one revolution (peaks over all of
 *   it): it keeps the reference's trajectory, its impacts and the run's
 *   force and penetration peaks within the 1 %; measured +0.21 % /
 *   -0.02 % (the first impact, the run's peak). Its second force pulse
 *   (+0.08 % / -0.07 %) belongs to the same contact (metrics.h,
 *   fb_metrics_next_impact): the damper clamps the force to zero for 44 us
 *   while the pin stays 0.98 um in, in the reference as in the model. The
 *   first impact's force converges as h^2: +3.6 %, +0.98 %, +0.62 % at
 *   5e-7, 2.5e-7, 2e-7 s (the reason below).
 * - Flores's case as shipped (its impact damper 480 N s/m, the case's
 *   restitution 0.9) at its automatic step (2e-6 s): the pin rattles and the
 *   model leaves the reference's trajectory after about 25 impacts (8.6 ms,
 *   chaos: its verdict is then statistical, docs/chaos.md); the first
 *   FB_FIRST_IMPACTS impacts, before it leaves, within 1 %: measured -0.15 %
 *   / +0.03 %, -0.25 % / -0.02 %, -0.25 % / -0.06 % (force / penetration).
 * - With the four-bar's damper, c_max = 1e4 N s/m (the test's case), the
 *   first impact is the damper's onset: STEP(delta, 0, 0, d_max, c_max)
 *   reaches c_max at d_max = 1 um of penetration, crossed within one step
 *   at the automatic step, and its force c_max v peaks there and decays
 *   with m_eff / c_max = 6 to 19 us, so the force peak is the onset's kink
 *   inside one step (fb_contact_row_onset corrects an onset for the linear
 *   and restitution laws only): Flores so was -4.8 % / -2.7 % at 2e-6 s;
 *   the test's case at 0.74 m/s, where d_max takes 1.3 us, is within 0.05 %
 *   from 1e-6 s on and -20 % at its automatic 5e-6 s. */
#define SC_MATCHED_REL_TOL 0.01

static void test_sc_impact_against_reference(void **state) {
  (void)state;
  for (int sc = 1; sc >= 0; sc--) {
    const char *sets[] = {"run.models=ode-clearance-impact,reference", "run.ensemble=1",
                          "solver.h_s=1.25e-7", "run.revolutions=1", "run.peaks=all"};
    fb_case c;
    load_sc(&c, sc, sets, sc ? 5 : 2);
    static fb_run r;
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const fb_model_result *m = sc_result(&r, "ode-clearance-impact");
    assert_int_equal(m->run.stop.kind, FB_STOP_NONE);
    assert_true(m->has_divergence && m->has_ref_error);
    const fb_divergence *v = &m->divergence;
    if (sc) assert_false(v->diverged);
    assert_true(v->matched >= (sc ? 1 : 2));
    /* Flores: its first impacts, before its rattling leaves the reference */
    const int n = sc ? v->matched : FB_FIRST_IMPACTS;
    assert_true(v->matched >= n);
    for (int i = 0; i < n && i < FB_DIVERGE_MAX_IMPACTS; i++) {
      const double tol = SC_MATCHED_REL_TOL;
      char name[96];
      snprintf(name, sizeof name, "%s impact %d force", SC_CASE_NAME[sc], i + 1);
      report_residual(name, v->impact[i].force_rel, tol);
      snprintf(name, sizeof name, "%s impact %d penetration", SC_CASE_NAME[sc], i + 1);
      report_residual(name, v->impact[i].penetration_rel, tol);
      assert_true(fabs(v->impact[i].force_rel) < tol);
      assert_true(fabs(v->impact[i].penetration_rel) < tol);
    }
    if (sc) {
      const fb_reference_error *e = &m->ref_error;
      report_residual("test's case force peak", e->force_max_rel, SC_MATCHED_REL_TOL);
      report_residual("test's case penetration peak", e->penetration_max_rel,
                      SC_MATCHED_REL_TOL);
      assert_true(fabs(e->force_max_rel) < SC_MATCHED_REL_TOL);
      assert_true(fabs(e->penetration_max_rel) < SC_MATCHED_REL_TOL);
    }
    fb_run_free(&r);
  }
}

/* The restitution model's first three impacts (from t = 0, before its
 * rattling parts from the reference's) within 1 %: Flores at its automatic
 * step, measured 0.22 % at most; the test's case at h = 1e-6 s, 0.05 % at
 * most (1.1 % at its automatic 5e-6 s: the third impact's force). Later impacts
 * part (Flores: 16 matched within 1 %, it leaves the reference at 12.8 ms):
 * chaos, compared by statistics (docs/chaos.md), not asserted here. */
static void test_sc_restitution_first_impacts(void **state) {
  (void)state;
  for (int sc = 0; sc < 2; sc++) {
    const char *sets[] = {"run.models=ode-clearance-restitution,reference-restitution",
                          "run.ensemble=1", "run.revolutions=1", "run.peaks=all",
                          "solver.h_s=1e-6"};
    fb_case c;
    load_sc(&c, sc, sets, sc ? 5 : 4);
    static fb_run r;
    fb_diag d;
    if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
    const fb_reference_error *e = &sc_result(&r, "ode-clearance-restitution")->ref_error;
    assert_int_equal(e->first_impacts, FB_FIRST_IMPACTS);
    double worst = 0.0;
    for (int k = 0; k < FB_FIRST_IMPACTS; k++)
      worst = fmax(worst, fmax(fabs(e->first_impact_force_rel[k]),
                               fabs(e->first_impact_penetration_rel[k])));
    char name[96];
    snprintf(name, sizeof name, "%s restitution first three", SC_CASE_NAME[sc]);
    report_residual(name, worst, SC_MATCHED_REL_TOL);
    assert_true(worst < SC_MATCHED_REL_TOL);
    fb_run_free(&r);
  }
}

/* The generic colliders at the piston pin: the libccd bore (256 segments)
 * holds the same first impact as the exact contact, Flores's case at its
 * automatic step: force and penetration peaks within 1 % (measured +0.014 %,
 * +0.011 %: the same law at the same step, the polygon's sagitta 0.8 um
 * against 76 um of penetration); the ring of 256 ODE boxes within its own
 * accuracy (SC_FACETED_REL_TOL; its penetration is the pin's eccentricity
 * beyond the circle, which its facets let grow, not compared). */
#define SC_COLLIDER_REL_TOL 0.01
/* The ring of boxes is the approximate collider it is on the four-bar:
 * docs/colliders.md measures its peak force -15 % to -25 % off the exact
 * collider's (its split of the law by contact count, its facets' depth);
 * here, with Flores's damper set for its restitution so that the spring
 * carries the force, measured -12 % (256 boxes; -21 % with 64). */
#define SC_FACETED_REL_TOL 0.25

/* largest force and penetration of joint j's first impact episode */
static void first_episode(const fb_series *s, int j, double *force, double *pen) {
  *force = *pen = 0.0;
  size_t first, last;
  if (fb_metrics_impact_episodes(s, j, INFINITY, &first, &last, 1) < 1) return;
  for (size_t k = first; k <= last; k++) {
    *force = fmax(*force, s->contact[j][FB_C_FORCE][k]);
    *pen = fmax(*pen, s->contact[j][FB_C_PEN][k]);
  }
}

static void test_sc_colliders(void **state) {
  (void)state;
  const char *sets[] = {"run.models=ode-clearance-impact,ode-clearance-faceted,ode-clearance-ccd",
                        "run.ensemble=1", "run.revolutions=1", "run.peaks=all",
                        "clearance.segments=256"};
  fb_case c;
  load_sc(&c, 0, sets, 5);
  static fb_run r;
  fb_diag d;
  if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  double f0, p0;
  first_episode(&sc_result(&r, "ode-clearance-impact")->run.series, FB_JOINT_C, &f0, &p0);
  assert_true(f0 > 0.0 && p0 > 0.0);
  const char *others[2] = {"ode-clearance-ccd", "ode-clearance-faceted"};
  for (int i = 0; i < 2; i++) {
    const fb_model_result *m = sc_result(&r, others[i]);
    assert_int_equal(m->run.stop.kind, FB_STOP_NONE);
    double f, p;
    first_episode(&m->run.series, FB_JOINT_C, &f, &p);
    char name[96];
    snprintf(name, sizeof name, "%s first impact force vs exact", others[i]);
    const double tol = i == 0 ? SC_COLLIDER_REL_TOL : SC_FACETED_REL_TOL;
    report_residual(name, f / f0 - 1.0, tol);
    assert_rel(f, f0, tol);
    if (i == 0) {
      report_residual("ccd first impact penetration vs exact", p / p0 - 1.0, SC_COLLIDER_REL_TOL);
      assert_rel(p, p0, SC_COLLIDER_REL_TOL);
    }
  }
  fb_run_free(&r);
}

/* [solver] h_s = adaptive builds the slider-crank (its load schedule from
 * the slider-crank's own inverse dynamics): the test's case, impact model,
 * runs to its end beside the reference without leaving it, in 6148 steps
 * for 60000 samples, none above h_max. Its accuracy here is not the
 * four-bar's 1 %: measured impacts -1.4 % / +0.2 % and +2.8 % / -1.9 %
 * (force / penetration), window peaks +2.2 % / -1.9 % at the default
 * accuracy 0.3; at 0.1 the first impact's force is +9.9 %: the step rule
 * follows h omega_c, not the impact law's damper time m_eff / c_max (6 to
 * 19 us here) that the onset needs. So its peaks are reported
 * (FB_TEST_VERBOSE), not asserted; the run, the trajectory and the steps
 * are. */
static void test_sc_adaptive_runs(void **state) {
  (void)state;
  const char *sets[] = {"run.models=ode-clearance-impact,reference", "run.ensemble=1",
                        "solver.h_s=adaptive"};
  fb_case c;
  load_sc(&c, 1, sets, 3);
  static fb_run r;
  fb_diag d;
  if (fb_run_case(&r, &c, NULL, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  const fb_model_result *m = sc_result(&r, "ode-clearance-impact");
  assert_int_equal(m->run.stop.kind, FB_STOP_NONE);
  assert_true(m->has_divergence);
  assert_false(m->divergence.diverged);
  report_residual("slider-crank adaptive window force", m->ref_error.force_max_rel,
                  FB_MATCHED_IMPACT_ERROR_BOUND);
  report_residual("slider-crank adaptive window penetration", m->ref_error.penetration_max_rel,
                  FB_MATCHED_IMPACT_ERROR_BOUND);
  assert_true(m->run.has_step_stats);
  assert_true(m->run.step_stats.steps < m->run.series.n / 5);
  assert_true(m->run.step_stats.h_max <= c.solver.h_max * (1 + 1e-12));
  fb_run_free(&r);
}

/* Riding the wall at 3000 rpm (docs/models.md, "Riding the wall"): the
 * Flores case at 3000 rpm, whose reference rattles until 11 ms and then
 * rides the wall through revolution 2 (0 impacts) while ODE at the
 * automatic step leaves it at 26.0 ms and strikes 17 times. Whether the pin
 * stays through the load's reversal at 24 ms (crank 72 deg, the pin's load
 * down to 168 N and turning 180 deg in 2 ms) is set by the state it brings
 * from the start-up's rattling, which a change of the law's damper by 0.4 %
 * flips in the reference itself; the contact row in persistent contact is
 * not the cause. This holds that part: ODE at the automatic step
 * (3.3e-6 s, h omega_c 0.31), started on the exact motion's state at 12 ms
 * (the pin on the wall), follows that motion through revolution 2.
 * Measured: 0 window impacts (exact: 0), eccentricity within 3.4 um of the
 * exact one over 12 to 40 ms (0.7 % of the 500 um clearance), window force
 * peak -0.16 %. Bounds: no impact, 10 um, 1 %. */
#define SC_RIDE_T0_S 0.012
#define SC_RIDE_ECC_M 10e-6
#define SC_RIDE_FORCE_REL 1e-2

/* the joint points and velocities of the slider-crank's state s (start.h,
 * as sc_fill in start.c) */
static void sc_state_start(fb_start_state *st, const fb_sc_dyn_sample *s, const fb_slider_crank *g,
                           double omega2) {
  memset(st, 0, sizeof *st);
  st->crank_angle = s->crank_angle;
  st->crank_omega = omega2;
  st->coupler_angle = s->coupler_angle;
  st->coupler_omega = s->coupler_omega;
  const double b[2] = {g->crank * cos(s->crank_angle), g->crank * sin(s->crank_angle)};
  const double p[2] = {b[0] + g->coupler * cos(s->coupler_angle),
                       b[1] + g->coupler * sin(s->coupler_angle)};
  const double hole[2] = {s->slider_x, g->offset};
  for (int k = 0; k < 2; k++) {
    st->pin[FB_SC_JOINT_CRANK_COUPLER][k] = st->hole[FB_SC_JOINT_CRANK_COUPLER][k] = b[k];
    st->pin[FB_SC_JOINT_COUPLER_SLIDER][k] = p[k];
    st->hole[FB_SC_JOINT_COUPLER_SLIDER][k] = hole[k];
    st->ecc[FB_SC_JOINT_COUPLER_SLIDER][k] = p[k] - hole[k];
    st->pin[FB_SC_JOINT_SLIDER_GROUND][k] = st->hole[FB_SC_JOINT_SLIDER_GROUND][k] = hole[k];
  }
  st->body[1][FB_Q_POS] = s->slider_x;
  st->body[1][FB_Q_VEL] = s->slider_v;
  st->coupler_b_vel[0] = -omega2 * b[1];
  st->coupler_b_vel[1] = omega2 * b[0];
}

/* contact onsets at t >= t_win and the largest force there, of n samples */
static int sc_window_impacts(const double *t, const double *pen, const double *f, size_t n,
                             double t_win, double *f_max) {
  int k = 0;
  *f_max = 0.0;
  for (size_t i = 0; i < n; i++) {
    if (t[i] < t_win) continue;
    if (i > 0 && pen[i] > 0.0 && !(pen[i - 1] > 0.0)) k++;
    *f_max = fmax(*f_max, f[i]);
  }
  return k;
}

static void test_sc_rides_wall_from_exact_state(void **state) {
  (void)state;
  const char *sets[] = {"drive.speed_rpm=3000", "run.models=ode-clearance-impact",
                        "run.ensemble=1"};
  fb_case c;
  load_sc(&c, 0, sets, 3);
  static fb_scene def;
  fb_diag d;
  if (fb_scene_from_case(&def, &c, &d) != FB_OK) fail_msg("scene: %s", d.msg);
  const fb_model *row = fb_model_find("ode-clearance-impact");
  const fb_linkage *lk = &def.lengths[row->lengths];
  const fb_slider_crank g = fb_slider_crank_of(lk);
  const double h = def.solver.h, period = 2.0 * M_PI / fabs(def.omega2);
  fb_sc_dyn_model m;
  memset(&m, 0, sizeof m);
  m.geometry = g;
  m.mass = fb_slider_crank_mass_of(def.link);
  m.gravity = def.gravity;
  m.clearance = def.radial_clearance;
  m.law = def.law[FB_MODEL_LAW_IMPACT][FB_SC_JOINT_COUPLER_SLIDER];
  m.impact_velocity = 1e-3;
  m.theta0 = def.crank_angle0;
  m.omega2 = def.omega2;
  /* the exact motion from the case's start to t0, then on to two revolutions */
  const fb_start_state *s0 = &def.start[row->lengths][row->joints];
  const double y0[FB_SC_DYN_DIM] = {s0->coupler_angle, s0->body[1][FB_Q_POS], s0->coupler_omega,
                                    s0->body[1][FB_Q_VEL]};
  const size_t n0 = (size_t)floor(SC_RIDE_T0_S / h + 0.5) + 1;
  const size_t n = (size_t)floor((2.0 * period - (n0 - 1) * h) / h + 0.5);
  fb_sc_dyn_sample *ex = calloc(n0 > n + 1 ? n0 : n + 1, sizeof *ex);
  assert_non_null(ex);
  if (fb_sc_dyn_run(ex, n0, h, y0, &m, 1e-12, 0, NULL, NULL, &d) != FB_OK)
    fail_msg("exact to t0: %s", d.msg);
  const fb_sc_dyn_sample at0 = ex[n0 - 1];
  const double t0 = at0.t;
  const double y1[FB_SC_DYN_DIM] = {at0.coupler_angle, at0.slider_x, at0.coupler_omega,
                                    at0.slider_v};
  m.theta0 = at0.crank_angle;
  if (fb_sc_dyn_run(ex, n + 1, h, y1, &m, 1e-12, 0, NULL, NULL, &d) != FB_OK)
    fail_msg("exact from t0: %s", d.msg);
  assert_true(at0.penetration > 0.0); /* on the wall at t0 */
  /* ODE from the same state */
  fb_start_state st;
  sc_state_start(&st, &at0, &g, def.omega2);
  def.start[row->lengths][row->joints] = st;
  def.crank_angle0 = at0.crank_angle;
  def.steps = n;
  def.duration = (double)n * h;
  fb_model_scene sm;
  if (fb_scene_select(&sm, &def, row, &d) != FB_OK) fail_msg("select: %s", d.msg);
  const fb_engine *e = fb_engine_get(row->engine, &d);
  assert_non_null(e);
  void *self = NULL;
  if (e->create(&self, &sm, &d) != FB_OK) fail_msg("create: %s", d.msg);
  double *col = calloc(6 * (n + 1), sizeof *col);
  assert_non_null(col);
  double *t = col, *pen = col + (n + 1), *f = col + 2 * (n + 1);
  double *te = col + 3 * (n + 1), *pene = col + 4 * (n + 1), *fe = col + 5 * (n + 1);
  double ecc_dev = 0.0;
  for (size_t i = 1; i <= n; i++) {
    if (e->step(self, &d) != FB_OK) fail_msg("step %zu: %s", i, d.msg);
    fb_sample x;
    e->sample(self, &x);
    const double *cj = x.contact[FB_SC_JOINT_COUPLER_SLIDER];
    t[i] = t0 + x.t;
    pen[i] = cj[FB_C_PEN];
    f[i] = cj[FB_C_FORCE];
    te[i] = t0 + ex[i].t;
    pene[i] = ex[i].penetration;
    fe[i] = ex[i].force;
    ecc_dev = fmax(ecc_dev, hypot(cj[FB_C_EX] - ex[i].ecc[0], cj[FB_C_EY] - ex[i].ecc[1]));
  }
  e->destroy(self);
  t[0] = te[0] = t0;
  pen[0] = pene[0] = at0.penetration;
  f[0] = fe[0] = at0.force;
  double f_ode, f_ex;
  const int k_ode = sc_window_impacts(t + 1, pen + 1, f + 1, n, period, &f_ode);
  const int k_ex = sc_window_impacts(te + 1, pene + 1, fe + 1, n, period, &f_ex);
  if (getenv("FB_TEST_VERBOSE"))
    printf("    riding the wall from %.4g s: window impacts %d (exact %d), force peak %.6g N "
           "(exact %.6g N)\n",
           t0, k_ode, k_ex, f_ode, f_ex);
  report_residual("riding the wall: eccentricity [m] against the exact motion", ecc_dev,
                  SC_RIDE_ECC_M);
  report_residual("riding the wall: window force peak", f_ode / f_ex - 1.0, SC_RIDE_FORCE_REL);
  assert_int_equal(k_ex, 0);
  assert_int_equal(k_ode, 0);
  assert_true(ecc_dev <= SC_RIDE_ECC_M);
  assert_rel(f_ode, f_ex, SC_RIDE_FORCE_REL);
  free(col);
  free(ex);
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
      cmocka_unit_test(test_sc_ideal_against_analytic),
      cmocka_unit_test(test_sc_effective_mass_matches_ode_probe),
      cmocka_unit_test(test_sc_load_schedule_is_its_own),
      cmocka_unit_test(test_sc_impact_against_reference),
      cmocka_unit_test(test_sc_restitution_first_impacts),
      cmocka_unit_test(test_sc_colliders),
      cmocka_unit_test(test_sc_adaptive_runs),
      cmocka_unit_test(test_sc_rides_wall_from_exact_state),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
