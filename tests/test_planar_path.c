/* The planar core's motion over a drive revolution (planar_path.h): the
 * peaks of every body's angular velocity and acceleration against the
 * four-bar's exact peaks (analytic.h: Taylor series refined to 1e-12 rad,
 * an independent method), and the Watt II six-bar of cases/watt_sixbar.ini
 * against an independent position analysis written here: closed-form dyads
 * (two circles' intersection for each of the two loops, their velocity
 * equations solved by hand), no part of the core.
 *
 *                 C                        G
 *                / \                 ___--o
 *       coupler /   \ ternary  rod __-     / output
 *              /     \      __--          /
 *           B o       o E--              o F
 *      crank /       /
 *         A o       o D           ground: A, D, F */
#include <string.h>

#include "analytic.h"
#include "casefile.h"
#include "fb_test.h"
#include "fb_test_planar.h"
#include "mech_kinematics.h"
#include "planar_case.h"
#include "planar_path.h"

/* The bound for the four-bar written as a planar description
 * against the built-in four-bar's analytic peaks (and here for the
 * slider-crank's rod against mech_kinematics.h's), relative to each peak:
 * both are refined to 1e-9 rad (Brent) or 1e-12 rad (the series) in crank
 * angle at an extreme, where the value's error is quadratic in that
 * (below 1e-16), and both evaluate the motion at machine precision
 * (test_planar_kinematics.c: 1e-15). Measured: ~1e-14. */
#define FOURBAR_PEAK_REL 1e-9
/* The bound for the six-bar's omega peaks against the dyads. The
 * dyads here are exact closed forms; their extremes are refined by golden
 * section to DYAD_ANGLE_TOL (value error quadratic in it: ~1e-14).
 * Measured: ~1e-13. */
#define SIXBAR_OMEGA_REL 1e-6
/* Golden-section stopping width of the dyads' extremes [rad]. */
#define DYAD_ANGLE_TOL 1e-7
/* Where an extreme lies [rad of drive angle]: Brent locates a flat
 * extreme to about the square root of the value's precision (1e-8 of the
 * curvature's scale); 1e-5 rad holds it with a margin. */
#define WHERE_TOL_RAD 1e-5

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* the paper's four-bar (nominal lengths, its branch, its drive) through the
 * core against fb_analytic_peaks_where */
static void test_fourbar_peaks(void **state) {
  (void)state;
  const fb_case c = fb_test_paper_once();
  fb_test_planar t = fb_test_planar_paper(&c, &c.nominal);
  fb_diag d;
  fb_planar_peaks p[4];
  const double omega = fb_case_omega2(&c);
  if (fb_planar_peaks_of(p, t.k, omega, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_peaks a;
  double where[8];
  assert_int_equal(fb_analytic_peaks_where(&a, where, &c.nominal, c.branch, omega, &d), FB_OK);
  const fb_body_peaks *ab[2] = {&a.coupler, &a.follower};
  double worst = 0.0, worst_at = 0.0;
  for (int b = 0; b < 2; b++) {
    const fb_planar_peaks *pb = &p[2 + b];
    const double got[4] = {pb->omega_max, pb->omega_min, pb->alpha_max, pb->alpha_min};
    const double want[4] = {ab[b]->omega_max, ab[b]->omega_min, ab[b]->alpha_max, ab[b]->alpha_min};
    for (int x = 0; x < 4; x++) {
      worst = fmax(worst, rel(got[x], want[x]));
      const double dw = remainder(pb->where[x] + c.crank_angle0 - where[4 * b + x], 2.0 * M_PI);
      worst_at = fmax(worst_at, fabs(dw));
    }
  }
  report_residual("four-bar peaks, planar core vs analytic (rel)", worst, FOURBAR_PEAK_REL);
  report_residual("four-bar peaks' crank angles [rad]", worst_at, WHERE_TOL_RAD);
  assert_true(worst <= FOURBAR_PEAK_REL);
  assert_true(worst_at <= WHERE_TOL_RAD);
  /* the driven crank turns at the drive's speed, without acceleration */
  assert_near(p[1].omega_max, omega, 1e-12 * fabs(omega));
  assert_near(p[1].omega_min, omega, 1e-12 * fabs(omega));
  assert_near(p[1].alpha_max, 0.0, 1e-9 * omega * omega);
  fb_test_planar_free(&t);
}

/* the slider-crank's rod through the core against mech_kinematics.h's
 * peaks (the closed form, bracketed and refined by Brent to 1e-12 rad) */
static void test_slider_crank_peaks(void **state) {
  (void)state;
  fb_case c = fb_test_paper_once();
  const fb_linkage lk = {{0.05, 0.18, 0.012, 0}};
  fb_test_planar t = fb_test_planar_slider(&c, &lk, 0.4, 1e-4, 0.0);
  fb_diag d;
  const double omega = -150.0;
  fb_planar_peaks p[4];
  if (fb_planar_peaks_of(p, t.k, omega, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_peaks a;
  assert_int_equal(fb_mech_peaks(&a, FB_MECH_SLIDER_CRANK, &lk, FB_BRANCH_OPEN, omega, &d), FB_OK);
  const double got[4] = {p[2].omega_max, p[2].omega_min, p[2].alpha_max, p[2].alpha_min};
  const double want[4] = {a.body[0].omega_max, a.body[0].omega_min, a.body[0].alpha_max,
                          a.body[0].alpha_min};
  double worst = 0.0;
  for (int x = 0; x < 4; x++) worst = fmax(worst, rel(got[x], want[x]));
  report_residual("slider-crank rod peaks, core vs mech_kinematics (rel)", worst, FOURBAR_PEAK_REL);
  assert_true(worst <= FOURBAR_PEAK_REL);
  /* the slider never turns */
  assert_near(p[3].omega_max, 0.0, 1e-12);
  assert_near(p[3].omega_min, 0.0, 1e-12);
  fb_test_planar_free(&t);
}

/* ---- the six-bar's dyads ------------------------------------------------ */

/* the six-bar's geometry, read from the loaded case (joint positions) */
typedef struct {
  double a[2], b[2], c[2], d[2], e[2], f[2], g[2]; /* assembly positions [m] */
  double crank, coupler, rocker, de, rod, output; /* lengths [m] */
  double theta0, ang_c0, ang_e0;                  /* crank, D->C, D->E at assembly [rad] */
} sixbar;

/* the intersection of circles (p, rp) and (q, rq) nearer ref */
static void circles(double out[2], const double p[2], double rp, const double q[2], double rq,
                    const double ref[2]) {
  const double dx = q[0] - p[0], dy = q[1] - p[1], dd = hypot(dx, dy);
  const double a = (rp * rp - rq * rq + dd * dd) / (2.0 * dd), h = sqrt(rp * rp - a * a);
  const double mx = p[0] + a * dx / dd, my = p[1] + a * dy / dd;
  const double s1[2] = {mx - h * dy / dd, my + h * dx / dd}, s2[2] = {mx + h * dy / dd, my - h * dx / dd};
  const int first = hypot(s1[0] - ref[0], s1[1] - ref[1]) <= hypot(s2[0] - ref[0], s2[1] - ref[1]);
  out[0] = first ? s1[0] : s2[0];
  out[1] = first ? s1[1] : s2[1];
}

/* the velocity x' of a point x on circles about p (moving at pv) and q
 * (fixed): (x - p).(x' - pv) = 0, (x - q).x' = 0 */
static void dyad_velocity(double out[2], const double x[2], const double p[2], const double pv[2],
                          const double q[2]) {
  const double a11 = x[0] - p[0], a12 = x[1] - p[1], a21 = x[0] - q[0], a22 = x[1] - q[1];
  const double r1 = a11 * pv[0] + a12 * pv[1], det = a11 * a22 - a12 * a21;
  out[0] = r1 * a22 / det;
  out[1] = -r1 * a21 / det;
}

/* omega of the link from p to x */
static double link_omega(const double x[2], const double xv[2], const double p[2],
                         const double pv[2]) {
  const double r[2] = {x[0] - p[0], x[1] - p[1]}, v[2] = {xv[0] - pv[0], xv[1] - pv[1]};
  return (r[0] * v[1] - r[1] * v[0]) / (r[0] * r[0] + r[1] * r[1]);
}

/* every body's omega (crank, coupler, ternary, rod, output) at drive angle
 * phi from the assembly and speed w; c_ref, g_ref: the branch (the
 * previous positions), updated */
static void dyads(double om[5], const sixbar *s, double phi, double w, double c_ref[2],
                  double g_ref[2]) {
  const double t = s->theta0 + phi;
  const double b[2] = {s->a[0] + s->crank * cos(t), s->a[1] + s->crank * sin(t)};
  const double bv[2] = {-w * s->crank * sin(t), w * s->crank * cos(t)};
  double c[2], cv[2];
  circles(c, b, s->coupler, s->d, s->rocker, c_ref);
  dyad_velocity(cv, c, b, bv, s->d);
  const double zero[2] = {0, 0};
  const double wt = link_omega(c, cv, s->d, zero);
  const double ang = atan2(c[1] - s->d[1], c[0] - s->d[0]) - s->ang_c0 + s->ang_e0;
  const double e[2] = {s->d[0] + s->de * cos(ang), s->d[1] + s->de * sin(ang)};
  const double ev[2] = {-wt * (e[1] - s->d[1]), wt * (e[0] - s->d[0])};
  double g[2], gv[2];
  circles(g, e, s->rod, s->f, s->output, g_ref);
  dyad_velocity(gv, g, e, ev, s->f);
  om[0] = w;
  om[1] = link_omega(c, cv, b, bv);
  om[2] = wt;
  om[3] = link_omega(g, gv, e, ev);
  om[4] = link_omega(g, gv, s->f, zero);
  memcpy(c_ref, c, sizeof c);
  memcpy(g_ref, g, sizeof g);
}

static void sixbar_of(sixbar *s, const fb_case *c) {
  const fb_planar_spec *p = &c->planar;
  double *pt[7] = {s->a, s->b, s->c, s->d, s->e, s->g, s->f}; /* in the file's joint order */
  assert_int_equal(p->njoints, 7);
  for (int j = 0; j < 7; j++) memcpy(pt[j], p->joint[j].at, 2 * sizeof(double));
  s->crank = hypot(s->b[0] - s->a[0], s->b[1] - s->a[1]);
  s->coupler = hypot(s->c[0] - s->b[0], s->c[1] - s->b[1]);
  s->rocker = hypot(s->c[0] - s->d[0], s->c[1] - s->d[1]);
  s->de = hypot(s->e[0] - s->d[0], s->e[1] - s->d[1]);
  s->rod = hypot(s->g[0] - s->e[0], s->g[1] - s->e[1]);
  s->output = hypot(s->g[0] - s->f[0], s->g[1] - s->f[1]);
  s->theta0 = atan2(s->b[1] - s->a[1], s->b[0] - s->a[0]);
  s->ang_c0 = atan2(s->c[1] - s->d[1], s->c[0] - s->d[0]);
  s->ang_e0 = atan2(s->e[1] - s->d[1], s->e[0] - s->d[0]);
}

/* golden-section extreme of sense * omega of body i on [lo, hi], the
 * branch references taken at lo */
typedef struct {
  const sixbar *s;
  double w, c0[2], g0[2];
  int body;
} dyad_fn;

static double dyad_value(const dyad_fn *f, double phi) {
  double om[5], c[2], g[2];
  memcpy(c, f->c0, sizeof c);
  memcpy(g, f->g0, sizeof g);
  dyads(om, f->s, phi, f->w, c, g);
  return om[f->body];
}

static double golden(const dyad_fn *f, double lo, double hi, double sense) {
  const double r = 0.5 * (sqrt(5.0) - 1.0);
  double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
  double f1 = sense * dyad_value(f, x1), f2 = sense * dyad_value(f, x2);
  while (hi - lo > DYAD_ANGLE_TOL) {
    if (f1 > f2) {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + r * (hi - lo), f2 = sense * dyad_value(f, x2);
    } else {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - r * (hi - lo), f1 = sense * dyad_value(f, x1);
    }
  }
  return sense * fmin(f1, f2);
}

static void test_sixbar_against_dyads(void **state) {
  (void)state;
  fb_case c;
  fb_diag d;
  fb_test_planar t = fb_test_planar_sixbar(&c);
  const fb_planar *m = t.m;
  assert_int_equal(m->nbodies, 6);
  const double w = fb_case_omega2(&c);
  fb_planar_peaks p[6];
  if (fb_planar_peaks_of(p, t.k, w, &d) != FB_OK) fail_msg("%s", d.msg);
  sixbar s;
  sixbar_of(&s, &c);
  /* the dyads' extremes: a pass over N drive angles, each extreme then
   * refined over its neighbours */
  enum { N = 3600 };
  static double om[N][5], cref[N][2], gref[N][2];
  double cr[2], gr[2];
  memcpy(cr, s.c, sizeof cr);
  memcpy(gr, s.g, sizeof gr);
  for (int i = 0; i < N; i++) {
    memcpy(cref[i], cr, sizeof cr);
    memcpy(gref[i], gr, sizeof gr);
    dyads(om[i], &s, 2.0 * M_PI * i / N, w, cr, gr);
  }
  const char *names[5] = {"crank", "coupler", "ternary", "rod", "output"};
  double worst = 0.0;
  for (int b = 0; b < 5; b++) {
    assert_string_equal(m->body[b + 1].name, names[b]);
    for (int sense = -1; sense <= 1; sense += 2) {
      int best = 0;
      for (int i = 1; i < N; i++)
        if (sense * om[i][b] < sense * om[best][b]) best = i;
      const int lo = (best + N - 1) % N;
      dyad_fn f = {&s, w, {cref[lo][0], cref[lo][1]}, {gref[lo][0], gref[lo][1]}, b};
      const double phi = 2.0 * M_PI * best / N, h = 2.0 * M_PI / N;
      const double want = b == 0 ? om[best][b] : golden(&f, phi - h, phi + h, sense);
      const double got = sense > 0 ? p[b + 1].omega_min : p[b + 1].omega_max;
      if (fb_test_verbose())
        fprintf(stderr, "  %-8s omega %s %+.12f (dyads %+.12f) rad/s\n", names[b],
                sense > 0 ? "min" : "max", got, want);
      worst = fmax(worst, rel(got, want));
    }
  }
  report_residual("six-bar omega peaks, core vs dyads (rel)", worst, SIXBAR_OMEGA_REL);
  assert_true(worst <= SIXBAR_OMEGA_REL);
  fb_test_planar_free(&t);
}

/* a loop that opens within the revolution stops the path with the angle */
static void test_follow_locks(void **state) {
  (void)state;
  fb_case c = fb_test_paper_once();
  /* a crank longer than the rest allows: non-Grashof, it rocks */
  const fb_linkage lk = {{0.2, 0.15, 0.12, 0.25}};
  fb_planar *m;
  fb_diag d;
  assert_int_equal(fb_planar_fourbar(&m, &lk, FB_BRANCH_OPEN, c.link, 0.0, &d), FB_OK);
  fb_planar_kin *k;
  assert_int_equal(fb_planar_kin_new(&k, m, &d), FB_OK);
  double q[9], reached;
  fb_path_end end;
  fb_planar_assembly(m, q);
  assert_int_equal(fb_planar_follow(k, q, 0.0, 2.0 * M_PI, &reached, &end, &d), FB_ERR_ASSEMBLY);
  assert_int_equal(end, FB_PATH_LOCKED);
  /* the crank range's end by the closed form: |BD| = coupler + follower */
  double lo, hi;
  int full;
  assert_int_equal(fb_linkage_crank_range(&lk, &lo, &hi, &full, &d), FB_OK);
  if (fb_test_verbose()) fprintf(stderr, "  locked at %.9f rad, closed form %.9f\n", reached, hi);
  assert_near(reached, hi, 1e-6);
  assert_non_null(strstr(d.msg, "locks at"));
  fb_planar_kin_free(k);
  fb_planar_free(m);
}

/* A mechanism that turns fully is followed over its revolution in a run's
 * sample intervals, whatever the step: the drive angle of sample i is
 * omega (i h), as the planar run computes it, so that an interval is a
 * few whole continuation steps and a remainder of rounding (4e-16 rad at
 * h = 5e-4 s, 1000 rpm: three steps of 1 degree short of 3 degrees),
 * which the path once took as a step of its own and called a lock at
 * -117 degrees. Every step from 1e-5 to 2e-3 s in steps of 1e-5 s (200
 * runs of intervals from 0.06 to 12 degrees), at the paper's 1000 rpm,
 * clockwise as cases/templates/planar_fourbar.ini. */
static void test_follow_in_sample_steps(void **state) {
  (void)state;
  fb_case c = fb_test_paper_once();
  c.crank_angle0 = 0.0; /* the template's assembly: the crank along +x */
  fb_test_planar t = fb_test_planar_paper(&c, &c.nominal);
  const double omega = -1000.0 * 2.0 * M_PI / 60.0;
  double q[9], q0[9];
  fb_planar_assembly(t.m, q0);
  fb_diag d;
  memcpy(q, q0, sizeof q);
  assert_int_equal(fb_planar_position(t.k, q, 0.0, NULL, &d), FB_OK);
  memcpy(q0, q, sizeof q);
  int runs = 0;
  for (int k = 1; k <= 200; k++) {
    const double h = 1e-5 * k;
    memcpy(q, q0, sizeof q);
    double from = 0.0;
    for (long i = 1; omega * (double)i * h >= -2.0 * M_PI; i++) {
      const double to = omega * ((double)i * h);
      fb_path_end end;
      if (fb_planar_follow(t.k, q, from, to, NULL, &end, &d) != FB_OK)
        fail_msg("h = %g s, sample %ld (%.6f to %.6f rad): %s", h, i, from, to, d.msg);
      from = to;
    }
    runs++;
  }
  assert_int_equal(runs, 200);
  fb_test_planar_free(&t);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_fourbar_peaks),
      cmocka_unit_test(test_slider_crank_peaks),
      cmocka_unit_test(test_sixbar_against_dyads),
      cmocka_unit_test(test_follow_locks),
      cmocka_unit_test(test_follow_in_sample_steps),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
