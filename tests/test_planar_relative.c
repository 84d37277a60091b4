/* The clearance dynamics in relative coordinates (planar_relative.h, over
 * planar_tree.h) and the reference integration on them
 * (planar_reference.h), against the absolute form (planar_dynamics.h, a
 * Schur complement in every body's coordinates: an independent path to
 * the same equations) and the closed forms (reference.c, minimal
 * coordinates by Kane's method), on the paper's four-bar, the Watt
 * six-bar, a slider-crank with clearance at its piston pin and the
 * slider of Siconos's example in its guide (undriven, a prismatic
 * clearance joint):
 *
 *            C                       the pin on body[0] of the clearance
 *           / \                      joint, the hole on body[1]; its
 *  coupler /   \ follower            coordinates e = pin - hole (a
 *      B(o)     \                    slider: its tilt and its offset
 *  crank /       \                   across the slide), the state
 *       A ------- D
 *
 * A state of the relative form is random within twice the clearance (so
 * that some pins press into their walls) and random rates; its positions
 * and velocities then make the absolute form's state. */
#include <string.h>

#include "casefile.h"
#include "fb_test.h"
#include "linkage.h"
#include "planar_case.h"
#include "planar_kinematics.h"
#include "planar_reference.h"
#include "planar_sparse.h"
#include "reference.h"

/* The two forms' accelerations and contact forces at one state: both
 * solve the equations of motion in double precision, the absolute form a
 * Schur complement of condition ~1e4 whose contact geometry carries the
 * ~1e-17 m rounding of coordinates of the mechanism's size (times the
 * stiffness, ~1e-8 N); relative to each quantity's largest over the
 * states 1e-9 holds (measured 3e-12 to 1.1e-11, FB_TEST_VERBOSE). */
#define FORMS_REL_TOL 1e-9
/* The joints that hold, at the positions solved from a state: a guess
 * within FB_PLANAR_REL_TAKE (1e-14 of the size) is taken as it is, so the
 * closure holds to ~1e-14 of the mechanism's size (0.15 to 0.5 m here);
 * a Newton step leaves the rounding of Phi (measured up to 3.9e-15 m). */
#define CLOSURE_TOL_M 1e-14
/* The velocity constraints: Phi_q q' of the joints that hold [m/s],
 * against rates of ~10 m/s: rounding (measured ~2e-15). */
#define RATE_TOL 1e-13
/* Integrated side by side over the paper case's first revolution with
 * reference.c (FOLLOW_S, its impacts and the pin's ride along the wall),
 * both with rk8pd at the reference tolerance 1e-12: they differ by their
 * integrations' errors, which the impacts amplify (docs/chaos.md): 1e-8
 * of the largest |omega| holds for this window (measured 2.5e-12). */
#define FOLLOW_S 0.059
#define FOLLOW_REL_TOL 1e-8

/* a reproducible stream of uniform numbers in [-1, 1) */
static double uni(unsigned long *s) {
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

static fb_contact_law law_of(fb_law_kind kind, double k) {
  fb_contact_law l = fb_contact_law_default();
  l.kind = kind;
  l.stiffness = k;
  if (kind == FB_LAW_IMPACT) {
    l.exponent = 1.5;
    l.damping = 1e4;
    l.damping_depth = 1e-6;
  } else {
    l.exponent = 1.0;
    l.restitution = 0.9;
  }
  assert_int_equal(fb_contact_law_prepare(&l, NULL), FB_OK);
  return l;
}

/* one description's two forms at random states: the largest relative
 * differences of the accelerations and contact forces, the closure */
typedef struct {
  double qdd, force, closure, rate;
  int contacts;
} forms;

static forms compare(const fb_planar_dyn_model *model, int nstates, double spread_m,
                     double rate_m_s) {
  const fb_planar *m = model->mech;
  fb_diag d;
  fb_planar_rel *rel;
  if (fb_planar_rel_new(&rel, model, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_planar_dyn *abs_;
  assert_int_equal(fb_planar_dyn_new(&abs_, model, &d), FB_OK);
  const int nq = fb_planar_nq(m), dim = fb_planar_rel_dim(rel), nr = dim / 2, nj = m->njoints;
  double *buf = calloc(8 * (size_t)nq + 2 * (size_t)dim + 2 * (size_t)m->nbodies, sizeof *buf);
  double *z = buf, *dz = z + dim, *q = dz + dim, *qd = q + nq, *qdd = qd + nq, *y = qdd + nq;
  double *dy = y + 2 * nq, *cs = dy + 2 * nq;
  fb_planar_contact *ct = calloc(2 * (size_t)nj, sizeof *ct), *ca = ct + nj;
  assert_int_equal(fb_planar_rel_steady(z, rel, &d), FB_OK);
  const double size = fb_planar_size(m), tau = fb_planar_rel_time_unit(model);
  forms f = {0, 0, 0, 0, 0};
  double big_qdd = 0.0, big_f = 0.0;
  unsigned long s = 11;
  const double z0_free = z[nr - 1];
  for (int k = 0; k < nstates; k++) {
    const double t = k * 7e-5;
    /* each relative coordinate in its unit (planar_relative.h): a length
     * over the size; an angle (a slider's tilt, the free coordinate) as it
     * is; rates times the time unit */
    for (int i = 0; i < nr; i++) {
      z[i] = uni(&s) * spread_m / size;
      z[nr + i] = uni(&s) * rate_m_s * tau / size;
    }
    if (m->drive < 0) z[nr - 1] = z0_free + 0.3 * k, z[dim - 1] = uni(&s) * 100.0 * tau;
    if (fb_planar_rel_eval(rel, t, z, dz, ct) != FB_OK) fail_msg("state %d: no positions", k);
    fb_planar_rel_motion(rel, q, qd, qdd);
    memcpy(y, q, (size_t)nq * sizeof *y);
    memcpy(y + nq, qd, (size_t)nq * sizeof *y);
    assert_int_equal(fb_planar_dyn_eval(abs_, t, y, dy, ca), FB_OK);
    for (int i = 0; i < nq; i++) {
      f.qdd = fmax(f.qdd, fabs(qdd[i] - dy[nq + i]));
      big_qdd = fmax(big_qdd, fabs(dy[nq + i]));
    }
    fb_planar_sq_trig(cs, m, q);
    for (int j = 0; j < nj; j++) {
      if (model->clearance[j]) {
        f.force = fmax(f.force, fabs(ct[j].force - ca[j].force));
        big_f = fmax(big_f, ca[j].force);
        f.contacts += ca[j].force > 0.0;
        continue;
      }
      double phi[2], v[2];
      fb_planar_sq_joint_phi(phi, m, j, q, cs);
      fb_planar_sq_joint_apply(v, m, j, q, cs, qd);
      const int prism = m->joint[j].kind == FB_KIND_PRISMATIC;
      f.closure = fmax(f.closure, fmax(prism ? 0.0 : fabs(phi[0]), fabs(phi[1])));
      f.rate = fmax(f.rate, fmax(fabs(v[0]), fabs(v[1])));
    }
  }
  f.qdd /= big_qdd;
  f.force = big_f > 0.0 ? f.force / big_f : f.force;
  free(buf);
  free(ct);
  fb_planar_dyn_free(abs_);
  fb_planar_rel_free(rel);
  return f;
}

static void check_forms(const char *what, const forms *f) {
  char name[160];
  snprintf(name, sizeof name, "%s: q'' (rel)", what);
  report_residual(name, f->qdd, FORMS_REL_TOL);
  snprintf(name, sizeof name, "%s: force (rel)", what);
  report_residual(name, f->force, FORMS_REL_TOL);
  snprintf(name, sizeof name, "%s: closure [m]", what);
  report_residual(name, f->closure, CLOSURE_TOL_M);
  assert_true(f->qdd <= FORMS_REL_TOL);
  assert_true(f->force <= FORMS_REL_TOL);
  assert_true(f->closure <= CLOSURE_TOL_M);
  assert_true(f->rate <= RATE_TOL);
  assert_true(f->contacts > 5); /* some states pressed a pin into its wall */
}

/* the paper's four-bar (its crank-coupler joint) and the six-bar (its
 * rod-output joint), both laws */
static void test_forms_revolute(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  fb_test_paper_case(&c, NULL, 0);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &lk, &d), FB_OK);
  unsigned char clear[4] = {0, 1, 0, 0};
  for (int k = 0; k < 2; k++) {
    const fb_planar_dyn_model model = {m, clear, law_of(k ? FB_LAW_RESTITUTION : FB_LAW_IMPACT,
                                                        k ? 1e9 : 5e10),
                                       c.radial_clearance, 1e-3, c.gravity, fb_case_omega2(&c),
                                       NULL, NULL, NULL};
    const forms f = compare(&model, 300, 2.0 * c.radial_clearance, 0.5);
    check_forms(k ? "four-bar, restitution" : "four-bar, impact", &f);
  }
  fb_planar_free(m);
  if (fb_test_shipped_case_planar(&c, "watt_sixbar.ini", &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  unsigned char six[7] = {0};
  six[fb_planar_find_joint(m, "rod-output")] = 1;
  for (int k = 0; k < 2; k++) {
    const fb_planar_dyn_model model = {m, six, law_of(k ? FB_LAW_RESTITUTION : FB_LAW_IMPACT,
                                                      k ? 1e9 : 5e10),
                                       c.radial_clearance, 1e-3, c.gravity, fb_case_omega2(&c),
                                       NULL, NULL, NULL};
    const forms f = compare(&model, 300, 2.0 * c.radial_clearance, 0.2);
    check_forms(k ? "six-bar, restitution" : "six-bar, impact", &f);
  }
  /* two clearance joints, each with its own law (joint_law): one of each
   * kind, so that a form reading the other joint's law would part */
  six[fb_planar_find_joint(m, "ternary-rod")] = 1;
  fb_contact_law own[7];
  for (int j = 0; j < 7; j++) own[j] = law_of(FB_LAW_IMPACT, 5e10);
  own[fb_planar_find_joint(m, "rod-output")] = law_of(FB_LAW_RESTITUTION, 1e9);
  const fb_planar_dyn_model two = {m, six, law_of(FB_LAW_IMPACT, 1.0), c.radial_clearance, 1e-3,
                                   c.gravity, fb_case_omega2(&c), NULL, NULL, own};
  const forms f = compare(&two, 300, 2.0 * c.radial_clearance, 0.2);
  check_forms("six-bar, two joints, a law each", &f);
  fb_planar_free(m);
}

/* joint_law is read at each clearance joint: the six-bar with clearance at
 * ternary-rod and rod-output, at one state with both pins pressed in, gives
 * at each joint the force of its own law (against the same model with that
 * law everywhere), and the shared law's where joint_law is NULL */
static void test_joint_law_each(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  if (fb_test_shipped_case_planar(&c, "watt_sixbar.ini", &d) != FB_OK) fail_msg("%s", d.msg);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  const int a = fb_planar_find_joint(m, "ternary-rod"), b = fb_planar_find_joint(m, "rod-output");
  unsigned char clear[7] = {0};
  clear[a] = clear[b] = 1;
  fb_contact_law own[7], la = law_of(FB_LAW_IMPACT, 5e10), lb = law_of(FB_LAW_IMPACT, 2e11);
  for (int j = 0; j < 7; j++) own[j] = la;
  own[b] = lb;
  const double w = fb_case_omega2(&c);
  const fb_planar_dyn_model mixed = {m, clear, la, c.radial_clearance, 1e-3, c.gravity, w, NULL,
                                     NULL, own};
  const fb_planar_dyn_model all_a = {m, clear, la, c.radial_clearance, 1e-3, c.gravity, w, NULL,
                                     NULL, NULL};
  const fb_planar_dyn_model all_b = {m, clear, lb, c.radial_clearance, 1e-3, c.gravity, w, NULL,
                                     NULL, NULL};
  const fb_planar_dyn_model *models[3] = {&mixed, &all_a, &all_b};
  double force[3][2];
  for (int k = 0; k < 3; k++) {
    fb_planar_rel *rel;
    if (fb_planar_rel_new(&rel, models[k], &d) != FB_OK) fail_msg("%s", d.msg);
    const int dim = fb_planar_rel_dim(rel), nr = dim / 2;
    double *z = calloc(2 * (size_t)dim, sizeof *z), *dz = z + dim;
    fb_planar_contact ct[7];
    assert_int_equal(fb_planar_rel_steady(z, rel, &d), FB_OK);
    /* each pin 1.5 radial clearances from its hole's centre: pressed in */
    for (int i = 0; i < nr; i++) z[i] = 0.0;
    const double size = fb_planar_size(m);
    z[0] = 1.5 * c.radial_clearance / size;
    z[2] = 1.5 * c.radial_clearance / size;
    assert_int_equal(fb_planar_rel_eval(rel, 0.0, z, dz, ct), FB_OK);
    force[k][0] = ct[a].force, force[k][1] = ct[b].force;
    free(z);
    fb_planar_rel_free(rel);
  }
  assert_true(force[0][0] > 0.0 && force[0][1] > 0.0);
  assert_true(force[0][0] == force[1][0]); /* ternary-rod: its own law, la */
  assert_true(force[0][1] == force[2][1]); /* rod-output: its own law, lb */
  assert_true(force[2][1] > 1.5 * force[1][1]); /* lb is 4x stiffer: the laws differ there */
  fb_planar_free(m);
}

/* a slider-crank with clearance at its piston pin, and the slider of
 * Siconos's example in its guide: a prismatic joint in the tree, a
 * prismatic clearance joint, an undriven description's free coordinate */
static void test_forms_prismatic(void **state) {
  (void)state;
  fb_diag d;
  fb_link_mass link[3] = {{0.2, 1e-4, 0, 0, 0.4}, {0.5, 2e-3, 0, 0, 0.4}, {0.6, 1e-5, 0, 0, 0}};
  const fb_linkage lk = {{0.05, 0.2, 0.01, 0}};
  fb_planar *m;
  assert_int_equal(fb_planar_slider_crank(&m, &lk, link, 0.3, &d), FB_OK);
  unsigned char clear[4] = {0, 0, 1, 0};
  const fb_planar_dyn_model model = {m, clear, law_of(FB_LAW_RESTITUTION, 1e9), 20e-6, 1e-3,
                                     9.81, 150.0, NULL, NULL, NULL};
  forms f = compare(&model, 300, 40e-6, 0.3);
  check_forms("slider-crank, piston pin", &f);
  fb_planar_free(m);
  fb_case c;
  if (fb_test_shipped_case_planar(&c, "slider_guide_flores_leine_glocker.ini", &d) != FB_OK)
    fail_msg("%s", d.msg);
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  const int gj = fb_planar_find_joint(m, "guide");
  unsigned char gc[4] = {0};
  gc[gj] = 1;
  fb_planar_guide guide[4];
  memset(guide, 0, sizeof guide);
  guide[gj] = (fb_planar_guide){c.planar.joint[gj].half_length, c.planar.joint[gj].half_height,
                                c.clearance.guide_clearance};
  double w0[4] = {0, 150.0, -75.0, 0};
  const fb_planar_dyn_model free_model = {m, gc, law_of(FB_LAW_RESTITUTION, 1e9), 0.0, 1e-3,
                                          9.81, 0.0, guide, w0, NULL};
  f = compare(&free_model, 300, 2.0 * c.clearance.guide_clearance, 0.5);
  check_forms("slider in its guide, undriven", &f);
  fb_planar_free(m);
}

/* springs and loads (planar_loads.h) in both forms: the six-bar with a
 * damped spring between two moving bodies, one to the ground, a force
 * and a torque; a slider-crank with a load on its slider's outstroke and
 * a spring on its rod */
static void test_forms_loaded(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  fb_planar *m;
  if (fb_test_shipped_case_planar(&c, "watt_sixbar.ini", &d) != FB_OK) fail_msg("%s", d.msg);
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  const int coupler = fb_planar_find_body(m, "coupler"), output = fb_planar_find_body(m, "output");
  const int ternary = fb_planar_find_body(m, "ternary");
  const double ends[2][2] = {{0.065, 0.080}, {0.230, 0.020}};
  const double anchor[2][2] = {{0.150, -0.080}, {0.190, 0.0}};
  const double at[2] = {0.240, 0.060}, force[2] = {30.0, -80.0};
  assert_true(fb_planar_add_spring(m, "s1", coupler, output, ends, 3e3, 0.15, 4.0, &d) >= 0);
  assert_true(fb_planar_add_spring(m, "s2", 0, ternary, anchor, 1.5e3, -1.0, 0.0, &d) >= 0);
  assert_true(fb_planar_add_load(m, "l1", output, at, force, 1.5, FB_PLANAR_LOAD_ALWAYS, -1,
                                 &d) >= 0);
  unsigned char six[7] = {0};
  six[fb_planar_find_joint(m, "rod-output")] = 1;
  for (int k = 0; k < 2; k++) {
    const fb_planar_dyn_model model = {m, six, law_of(k ? FB_LAW_RESTITUTION : FB_LAW_IMPACT,
                                                      k ? 1e9 : 5e10),
                                       c.radial_clearance, 1e-3, c.gravity, fb_case_omega2(&c),
                                       NULL, NULL, NULL};
    const forms f = compare(&model, 300, 2.0 * c.radial_clearance, 0.2);
    check_forms(k ? "six-bar loaded, restitution" : "six-bar loaded, impact", &f);
  }
  fb_planar_free(m);
  fb_link_mass link[3] = {{0.2, 1e-4, 0, 0, 0.4}, {0.5, 2e-3, 0, 0, 0.4}, {0.6, 1e-5, 0, 0, 0}};
  const fb_linkage lk = {{0.05, 0.2, 0.01, 0}};
  assert_int_equal(fb_planar_slider_crank(&m, &lk, link, 0.3, &d), FB_OK);
  int slide = -1, rod = -1;
  for (int j = 0; j < m->njoints; j++)
    if (m->joint[j].kind == FB_KIND_PRISMATIC) slide = j;
  const int slider = m->joint[slide].body[m->joint[slide].body[0] == 0 ? 1 : 0];
  for (int b = 1; b < m->nbodies; b++)
    if (b != slider && m->body[b].mass > 0.4) rod = b;
  assert_true(slide >= 0 && rod > 0);
  const double pull[2][2] = {{0.1, 0.1}, {m->body[rod].centre[0], m->body[rod].centre[1]}};
  const double push[2] = {-400.0, 0.0};
  assert_true(fb_planar_add_spring(m, "s", 0, rod, pull, 2e3, 0.05, 3.0, &d) >= 0);
  assert_true(fb_planar_add_load(m, "cut", slider, m->body[slider].centre, push, 0.0,
                                 FB_PLANAR_LOAD_OUTSTROKE, slide, &d) >= 0);
  unsigned char clear[4] = {0, 0, 1, 0};
  const fb_planar_dyn_model model = {m, clear, law_of(FB_LAW_RESTITUTION, 1e9), 20e-6, 1e-3,
                                     9.81, 150.0, NULL, NULL, NULL};
  const forms f = compare(&model, 300, 40e-6, 0.3);
  check_forms("slider-crank loaded on its outstroke", &f);
  fb_planar_free(m);
}

/* the reference integration against reference.c over the paper case's
 * first revolution from the steady start */
static void test_fourbar_integration(void **state) {
  (void)state;
  const char *sets[] = {"run.revolutions=1", "run.peaks=all", "solver.h_s=1e-5"};
  fb_case c;
  fb_test_paper_case(&c, sets, 3);
  const fb_contact_law law = law_of(FB_LAW_IMPACT, 5e10);
  fb_series s;
  size_t steps;
  fb_diag d;
  if (fb_reference_run_tol(&s, &steps, &c, &law, 0, FB_REFERENCE_TOL, NULL, &d) != FB_OK)
    fail_msg("%s", d.msg);
  fb_linkage lk;
  fb_case_stackup_lengths(&c, &lk);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &lk, &d), FB_OK);
  unsigned char clear[4] = {0, 1, 0, 0};
  const fb_planar_dyn_model model = {m, clear, law, c.radial_clearance, 1e-3, c.gravity,
                                     fb_case_omega2(&c), NULL, NULL, NULL};
  fb_planar_rel *rel;
  assert_int_equal(fb_planar_rel_new(&rel, &model, &d), FB_OK);
  const size_t n = (size_t)(FOLLOW_S / c.solver.h) + 1;
  assert_true(n <= s.n);
  double *y = calloc(n * 18, sizeof *y);
  fb_planar_ref_stats st;
  assert_int_equal(fb_planar_ref_run(y, NULL, NULL, NULL, n, c.solver.h, rel, FB_REFERENCE_TOL,
                                     &st, &d), FB_OK);
  double big = 0.0, diff = 0.0;
  for (size_t k = 0; k < n; k++) {
    big = fmax(big, fmax(fabs(s.coupler_omega[k]), fabs(s.follower_omega[k])));
    diff = fmax(diff, fmax(fabs(y[k * 18 + 9 + 5] - s.coupler_omega[k]),
                           fabs(y[k * 18 + 9 + 8] - s.follower_omega[k])));
  }
  if (fb_test_verbose())
    fprintf(stderr, "  steps: relative %zu (%zu evaluations), reference.c %zu (whole run)\n",
            st.steps, st.evals, steps);
  report_residual("relative reference vs reference.c: omega (rel)", diff / big, FOLLOW_REL_TOL);
  assert_true(diff / big <= FOLLOW_REL_TOL);
  report_residual("closure at the samples [m]", st.closure, CLOSURE_TOL_M);
  assert_true(st.closure <= CLOSURE_TOL_M);
  free(y);
  fb_planar_rel_free(rel);
  fb_planar_free(m);
  fb_series_free(&s);
}

/* The built-in mechanism's reference on the planar core
 * (reference.h fb_reference_run_planar: the path of a case with clearance
 * at several pins) against reference.c's closed form at one pin, the
 * paper case's first revolution, column by column: the same motion
 * sampled into the same series by the two paths, each with its own
 * refinement of the spikes (the same rule, peak_refine.h). Angles and
 * omegas hold FOLLOW_REL_TOL (their integrations' difference, above;
 * measured 3.4e-13); the contact columns and the alphas, relative to
 * each column's largest, too (measured 2.2e-11: the refinement searches
 * each spike's extreme to the integration's own accuracy, on either
 * path); the state column is the same rule on the same forces: equal
 * wherever the force is above SERIES_STATE_SHARE of its largest. */
#define SERIES_CONTACT_REL_TOL FOLLOW_REL_TOL
/* An ensemble member's start, the pin 3.6 um off its hole's centre
 * (fb_planar_rel_steady_offset against start.h's rule): the same
 * tolerances hold (measured 1.1e-10 on alpha, 8.5e-11 on the force);
 * the member's first-revolution contact force differs from the centred
 * run's by more than SERIES_MOVED_MOVES of its largest (a control: the
 * offset reached the start) */
#define SERIES_MOVED_MOVES 1e-4
#define SERIES_STATE_SHARE 1e-6
static double col_diff(const double *a, const double *b, size_t n, double *big) {
  double d = 0.0;
  *big = 0.0;
  for (size_t k = 0; k < n; k++) {
    *big = fmax(*big, fmax(fabs(a[k]), fabs(b[k])));
    d = fmax(d, fabs(a[k] - b[k]));
  }
  return d;
}

/* returns the planar path's contact force column's largest value [N] */
static double fourbar_series(const double offset[2], double angle_tol, double tol) {
  const char *sets[] = {"run.revolutions=1", "run.peaks=all", "solver.h_s=1e-5"};
  fb_case c;
  fb_test_paper_case(&c, sets, 3);
  c.pin_start_offset[0] = offset[0], c.pin_start_offset[1] = offset[1];
  fb_contact_law laws[FB_MECH_MAX_JOINTS];
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) laws[j] = law_of(FB_LAW_IMPACT, 5e10);
  const int cj = fb_case_mech(&c)->reference_joint;
  fb_series s, p;
  size_t steps, psteps;
  fb_diag d;
  if (fb_reference_run_tol(&s, &steps, &c, &laws[cj], 0, FB_REFERENCE_TOL, NULL, &d) != FB_OK)
    fail_msg("%s", d.msg);
  if (fb_reference_run_planar(&p, &psteps, &c, laws, FB_REFERENCE_TOL, NULL, &d) != FB_OK)
    fail_msg("%s", d.msg);
  assert_int_equal(p.n, s.n);
  assert_int_equal(p.contact_mask, s.contact_mask);
  double big, diff;
  diff = col_diff(p.t, s.t, s.n, &big);
  assert_true(diff == 0.0);
  diff = col_diff(p.crank_angle, s.crank_angle, s.n, &big);
  assert_true(diff <= 1e-15 * big);
  for (int o = 0; o < fb_series_output_count(&s); o++) {
    const double tols[3] = {angle_tol, tol, tol};
    const char *what[3] = {"angle", "omega", "alpha"};
    for (int q = 0; q < 3; q++) {
      diff = col_diff(p.body[o][q], s.body[o][q], s.n, &big);
      char name[96];
      snprintf(name, sizeof name, "planar path vs reference.c: output %d %s (rel)", o, what[q]);
      report_residual(name, diff / big, tols[q]);
      assert_true(diff / big <= tols[q]);
    }
  }
  const double *fp = p.contact[cj][FB_C_FORCE], *fs = s.contact[cj][FB_C_FORCE];
  for (int k = 0; k < FB_CONTACT_COLS - 1; k++) {
    diff = col_diff(p.contact[cj][k], s.contact[cj][k], s.n, &big);
    char name[96];
    snprintf(name, sizeof name, "planar path vs reference.c: contact column %d (rel)", k);
    report_residual(name, diff / big, tol);
    assert_true(diff / big <= tol);
  }
  const double fmaxv = fb_series_largest_abs(fs, s.n);
  size_t states = 0;
  for (size_t k = 0; k < s.n; k++) {
    if (!(fs[k] > SERIES_STATE_SHARE * fmaxv && fp[k] > SERIES_STATE_SHARE * fmaxv)) continue;
    states++;
    assert_true(p.contact[cj][FB_C_STATE][k] == s.contact[cj][FB_C_STATE][k]);
  }
  assert_true(states > 0); /* the run has impacts to classify */
  const double fbig = fb_series_largest_abs(fp, p.n);
  fb_series_free(&s);
  fb_series_free(&p);
  return fbig;
}

static void test_fourbar_series(void **state) {
  (void)state;
  const double centred[2] = {0.0, 0.0}, moved[2] = {3e-6, -2e-6};
  const double a = fourbar_series(centred, FOLLOW_REL_TOL, SERIES_CONTACT_REL_TOL);
  const double b = fourbar_series(moved, FOLLOW_REL_TOL, SERIES_CONTACT_REL_TOL);
  if (fb_test_verbose()) fprintf(stderr, "  largest force centred %.9g N, moved %.9g N\n", a, b);
  assert_true(fabs(a - b) > SERIES_MOVED_MOVES * a);
}

/* the six-bar with its clearance joint (rod-output, cases/watt_sixbar.ini)
 * in the limit of no clearance and a stiff law: a pin held in its hole by
 * a spring of SIXBAR_K (a restitution-law damper of cr 0.5) follows the
 * ideal motion to the spring's give, F / k ~ 1e-8 m against links of
 * 60 mm, so the output's omega to ~1e-7 of its peak (measured 1.5e-7);
 * 1e-5 leaves a factor of 60. Then with the case's clearance, a run whose
 * pin stays within the law's validity (penetration below the radial
 * clearance). */
#define SIXBAR_K 1e9
#define SIXBAR_LIMIT_REL 1e-5
static void sixbar_run(double clearance, double *dev, double *pen_max) {
  fb_case c;
  fb_diag d;
  if (fb_test_shipped_case_planar(&c, "watt_sixbar.ini", &d) != FB_OK) fail_msg("%s", d.msg);
  fb_planar *m;
  assert_int_equal(fb_planar_of_case(&m, &c, &c.nominal, &d), FB_OK);
  unsigned char clear[7] = {0};
  const int cj = fb_planar_find_joint(m, "rod-output");
  clear[cj] = 1;
  fb_contact_law law = law_of(FB_LAW_RESTITUTION, SIXBAR_K);
  law.restitution = 0.5;
  assert_int_equal(fb_contact_law_prepare(&law, NULL), FB_OK);
  const double w = fb_case_omega2(&c);
  const fb_planar_dyn_model model = {m, clear, law, clearance, 1e-3, c.gravity, w, NULL, NULL, NULL};
  fb_planar_rel *rel;
  assert_int_equal(fb_planar_rel_new(&rel, &model, &d), FB_OK);
  enum { N = 1001 };
  const double h = 2.0 * M_PI / fabs(w) / (N - 1);
  static double y[N * 30];
  static fb_planar_contact ct[N * 7];
  fb_planar_ref_stats st;
  if (fb_planar_ref_run(y, NULL, ct, NULL, N, h, rel, 1e-10, &st, &d) != FB_OK) fail_msg("%s", d.msg);
  /* the ideal motion at the same drive angles */
  fb_planar_kin *k;
  assert_int_equal(fb_planar_kin_new(&k, m, &d), FB_OK);
  double q[15], qd[15], big = 0.0, diff = 0.0;
  fb_planar_assembly(m, q);
  *pen_max = 0.0;
  for (int i = 0; i < N; i++) {
    assert_int_equal(fb_planar_position(k, q, w * h * i, NULL, &d), FB_OK);
    const fb_planar_drive dr = {w * h * i, w, 0};
    assert_int_equal(fb_planar_motion(k, qd, NULL, q, &dr, NULL, &d), FB_OK);
    big = fmax(big, fabs(qd[14]));
    diff = fmax(diff, fabs(y[i * 30 + 15 + 14] - qd[14])); /* the output's omega */
    *pen_max = fmax(*pen_max, ct[i * 7 + cj].penetration);
  }
  *dev = diff / big;
  if (fb_test_verbose())
    fprintf(stderr, "  six-bar, clearance %g m: %zu steps, %zu evaluations, output omega off the "
            "ideal by %.3g (rel), penetration up to %.3g m, closure %.3g m\n", clearance, st.steps,
            st.evals, *dev, *pen_max, st.closure);
  assert_true(st.closure <= CLOSURE_TOL_M);
  fb_planar_kin_free(k);
  fb_planar_rel_free(rel);
  fb_planar_free(m);
}

static void test_sixbar_clearance(void **state) {
  (void)state;
  double dev, pen;
  sixbar_run(0.0, &dev, &pen);
  report_residual("six-bar, no clearance: output omega vs ideal (rel)", dev, SIXBAR_LIMIT_REL);
  assert_true(dev <= SIXBAR_LIMIT_REL);
  fb_case c;
  fb_diag d;
  assert_int_equal(fb_test_shipped_case_planar(&c, "watt_sixbar.ini", &d), FB_OK);
  sixbar_run(c.radial_clearance, &dev, &pen);
  assert_true(pen < c.radial_clearance);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_forms_revolute),
      cmocka_unit_test(test_joint_law_each),
      cmocka_unit_test(test_forms_prismatic),
      cmocka_unit_test(test_forms_loaded),
      cmocka_unit_test(test_fourbar_integration),
      cmocka_unit_test(test_fourbar_series),
      cmocka_unit_test(test_sixbar_clearance),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
