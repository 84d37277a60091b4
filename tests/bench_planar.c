/* What the planar core costs against the closed forms it stands beside
 * (a benchmark, never a test: `meson test -C build --benchmark planar`, or
 * ./build/tests/bench_planar). CPU time of this process
 * (CLOCK_PROCESS_CPUTIME_ID), the best of BEST_OF repeats of each
 * measurement, so that a machine shared with other jobs loses less:
 *   kinematics  the four-bar's and slider-crank's position, velocity and
 *               acceleration at 3600 crank angles: the closed form against
 *               the core (Newton from the previous angle, then one LU);
 *   peaks       fb_analytic_peaks against fb_planar_peaks_of;
 *   rhs         one evaluation of the clearance right-hand side: the
 *               slider-crank's fb_sc_dyn_eval_at against fb_planar_rel_eval
 *               (reference.c's is static: its cost is in the next row);
 *   reference   the paper case's first revolution with clearance at
 *               crank-coupler (impact law) at the reference tolerance:
 *               fb_reference_run against fb_planar_ref_run (steps and
 *               right-hand side evaluations printed). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "analytic.h"
#include "casefile.h"
#include "linkage.h"
#include "planar_case.h"
#include "planar_path.h"
#include "planar_reference.h"
#include "reference.h"
#include "slider_crank.h"
#include "slider_crank_dynamics.h"

#define BEST_OF 5
#define ANGLES 3600

static double cpu_s(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void row(const char *what, double closed, double core, const char *unit, double per) {
  printf("%-40s %12.3f %12.3f %s %8.1fx\n", what, closed / per, core / per, unit, core / closed);
}

static volatile double sink; /* keeps the optimiser from dropping a result */

/* the closed forms of one crank angle, as the core's rival */
typedef struct {
  const fb_case *c;
  fb_slider_crank sc; /* the slider-crank's, when slider */
  int slider;
} closed_form;

static double closed_solve(const closed_form *f, double theta, double w) {
  if (f->slider) {
    fb_slider_crank_state st;
    fb_slider_crank_solve(&st, &f->sc, theta, w, 0.0, NULL);
    return st.slider_a;
  }
  fb_linkage_state st;
  fb_linkage_solve(&st, &f->c->nominal, f->c->branch, theta, w, 0.0, NULL);
  return st.coupler_alpha;
}

/* position, velocity and acceleration at ANGLES crank angles: the closed
 * form against the core on m (Newton from the previous angle, one LU) */
static void kinematics_row(const char *what, const closed_form *f, const fb_planar *m, double w) {
  fb_planar_kin *k;
  if (fb_planar_kin_new(&k, m, NULL) != FB_OK) exit(1);
  double closed = 1e30, core = 1e30;
  for (int r = 0; r < BEST_OF; r++) {
    double t0 = cpu_s();
    for (int i = 0; i < ANGLES; i++) sink = closed_solve(f, 2.0 * M_PI * i / ANGLES, w);
    closed = fmin(closed, cpu_s() - t0);
    double q[9], qd[9], qdd[9];
    fb_planar_assembly(m, q);
    t0 = cpu_s();
    for (int i = 0; i < ANGLES; i++) {
      const fb_planar_drive d = {2.0 * M_PI * i / ANGLES, w, 0.0};
      fb_planar_position(k, q, d.angle, NULL, NULL);
      fb_planar_motion(k, qd, qdd, q, &d, NULL, NULL);
      sink = qdd[5];
    }
    core = fmin(core, cpu_s() - t0);
  }
  row(what, closed, core, "us", ANGLES * 1e-6);
  fb_planar_kin_free(k);
}

static void kinematics(const fb_case *c) {
  fb_planar *m;
  if (fb_planar_fourbar(&m, &c->nominal, c->branch, c->link, 0.0, NULL) != FB_OK) exit(1);
  const closed_form f = {c, {0, 0, 0}, 0};
  kinematics_row("four-bar: position, velocity, acceleration", &f, m, fb_case_omega2(c));
  fb_planar_free(m);
  const fb_linkage lk = {{0.05, 0.2, 0.01, 0}};
  fb_link_mass link[3];
  memcpy(link, c->link, sizeof link);
  link[2] = (fb_link_mass){0.5, 1e-4, 0, 0, 0};
  if (fb_planar_slider_crank(&m, &lk, link, 0.0, NULL) != FB_OK) exit(1);
  const closed_form g = {c, fb_slider_crank_of(&lk), 1};
  kinematics_row("slider-crank: position, velocity, accel.", &g, m, 100.0);
  fb_planar_free(m);
}

static void peaks(const fb_case *c) {
  fb_planar *m;
  fb_planar_kin *k;
  if (fb_planar_fourbar(&m, &c->nominal, c->branch, c->link, 0.0, NULL) != FB_OK ||
      fb_planar_kin_new(&k, m, NULL) != FB_OK)
    exit(1);
  const double w = fb_case_omega2(c);
  double closed = 1e30, core = 1e30;
  for (int r = 0; r < BEST_OF; r++) {
    fb_peaks a;
    double t0 = cpu_s();
    fb_analytic_peaks(&a, &c->nominal, c->branch, w, NULL);
    closed = fmin(closed, cpu_s() - t0);
    fb_planar_peaks p[4];
    t0 = cpu_s();
    fb_planar_peaks_of(p, k, w, NULL);
    core = fmin(core, cpu_s() - t0);
    sink = a.coupler.alpha_max + p[2].alpha_max;
  }
  row("four-bar: peaks over a revolution", closed, core, "ms", 1e-3);
  fb_planar_kin_free(k);
  fb_planar_free(m);
}

static fb_contact_law impact_law(void) {
  fb_contact_law l = fb_contact_law_default();
  l.kind = FB_LAW_IMPACT;
  l.stiffness = 5e10;
  l.exponent = 1.5;
  l.damping = 1e4;
  l.damping_depth = 1e-6;
  fb_contact_law_prepare(&l, NULL);
  return l;
}

static void rhs(void) {
  fb_sc_dyn_model sm;
  memset(&sm, 0, sizeof sm);
  sm.geometry = (fb_slider_crank){0.05, 0.2, 0.01};
  sm.mass = (fb_slider_crank_mass){0.2, 1e-4, 0.5, 0.4, 2e-3, 0.4, 0.6};
  sm.gravity = 9.81;
  sm.clearance = 20e-6;
  sm.law = impact_law();
  sm.impact_velocity = 1e-3;
  sm.omega2 = 150.0;
  fb_link_mass link[3] = {{0.2, 1e-4, 0, 0, 0.5}, {0.4, 2e-3, 0, 0, 0.4}, {0.6, 1e-5, 0, 0, 0}};
  const fb_linkage lk = {{0.05, 0.2, 0.01, 0}};
  fb_planar *m;
  if (fb_planar_slider_crank(&m, &lk, link, 0.0, NULL) != FB_OK) exit(1);
  unsigned char clear[4] = {0, 0, 1, 0};
  const fb_planar_dyn_model model = {m, clear, sm.law, sm.clearance, 1e-3, 9.81, 150.0, NULL, NULL, NULL};
  fb_planar_rel *dyn;
  if (fb_planar_rel_new(&dyn, &model, NULL) != FB_OK) exit(1);
  double y0[4], z[4], dz[4];
  const double ecc[2] = {15e-6, 5e-6}; /* in contact: the law evaluated too */
  fb_sc_dyn_start(y0, &sm, ecc, NULL);
  fb_planar_rel_steady(z, dyn, NULL);
  z[0] = ecc[0] / fb_planar_size(m), z[1] = ecc[1] / fb_planar_size(m);
  enum { EVALS = 200000 };
  double closed = 1e30, core = 1e30;
  for (int r = 0; r < BEST_OF; r++) {
    double t0 = cpu_s();
    for (int i = 0; i < EVALS; i++) {
      fb_sc_dyn_eval ev;
      fb_sc_dyn_eval_at(&ev, &sm, 1e-9 * i, y0);
      sink = ev.dydt[2];
    }
    closed = fmin(closed, cpu_s() - t0);
    t0 = cpu_s();
    for (int i = 0; i < EVALS; i++) {
      fb_planar_rel_eval(dyn, 1e-9 * i, z, dz, NULL);
      sink = dz[3];
    }
    core = fmin(core, cpu_s() - t0);
  }
  row("slider-crank: clearance right-hand side", closed, core, "us", EVALS * 1e-6);
  fb_planar_rel_free(dyn);
  fb_planar_free(m);
}

static void reference(const fb_case *c) {
  const fb_contact_law law = impact_law();
  fb_linkage lk;
  fb_case_stackup_lengths(c, &lk);
  fb_planar *m;
  if (fb_planar_of_case(&m, c, &lk, NULL) != FB_OK) exit(1);
  unsigned char clear[4] = {0, 1, 0, 0};
  const fb_planar_dyn_model model = {m, clear, law, c->radial_clearance, 1e-3, c->gravity,
                                     fb_case_omega2(c), NULL, NULL, NULL};
  fb_planar_rel *dyn;
  if (fb_planar_rel_new(&dyn, &model, NULL) != FB_OK) exit(1);
  const size_t n = (size_t)llround(fb_case_duration(c) / c->solver.h) + 1;
  double *y = malloc(n * 18 * sizeof *y);
  double closed = 1e30, core = 1e30;
  size_t steps = 0;
  fb_planar_ref_stats st;
  for (int r = 0; r < BEST_OF; r++) {
    fb_series s;
    double t0 = cpu_s();
    if (fb_reference_run(&s, &steps, c, &law, 0, NULL, NULL) != FB_OK) exit(1);
    closed = fmin(closed, cpu_s() - t0);
    fb_series_free(&s);
    t0 = cpu_s();
    if (fb_planar_ref_run(y, NULL, NULL, NULL, n, c->solver.h, dyn, FB_REFERENCE_TOL, &st, NULL) != FB_OK)
      exit(1);
    core = fmin(core, cpu_s() - t0);
  }
  row("paper case: reference, one revolution", closed, core, "s ", 1.0);
  printf("  (steps: reference.c %zu with its spike refinement, core %zu; core right-hand sides %zu)\n",
         steps, st.steps, st.evals);
  free(y);
  fb_planar_rel_free(dyn);
  fb_planar_free(m);
}

int main(void) {
  fb_case c;
  fb_diag d;
  const char *cases = getenv("FOURBAR_CASES_DIR");
  char path[4096];
  snprintf(path, sizeof path, "%s/paper_crank_rocker.ini", cases ? cases : "cases");
  const char *sets[] = {"run.revolutions=1", "run.peaks=all", "solver.h_s=1e-5"};
  if (fb_casefile_load(&c, path, sets, 3, &d) != FB_OK) {
    fprintf(stderr, "%s\n", d.msg);
    return 1;
  }
  printf("CPU time per call, best of %d (closed form, planar core, ratio)\n", BEST_OF);
  kinematics(&c);
  peaks(&c);
  rhs();
  reference(&c);
  return 0;
}
