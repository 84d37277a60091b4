/* The slider-crank (RRRP): exact kinematics and inverse dynamics, each
 * against an oracle computed here by an independent route.
 *
 *                  B
 *                 / \          A = (0, 0), B = crank u(theta2)
 *          crank /   \ coupler C = (x, offset), the piston pin
 *               /     \
 *              A       \            guide y = offset
 *                  - - -[ C ]- - - - - - -> x
 *
 * Oracles: the slider's position as an explicit function of the crank
 * angle, x(t) = a cos t + sqrt(b^2 - (a sin t - e)^2), and the rod's,
 * theta3(t) = asin((e - a sin t) / b), differentiated here by hand (the
 * library solves the loop's derivative equations instead); central
 * differences; brute-force scans; statics; Newton-Euler residuals and the
 * power balance of the inverse dynamics with accelerations from those
 * explicit derivatives. */
#include <string.h>

#include "fb_test.h"
#include "slider_crank.h"
#include "slider_crank_invdyn.h"

/* ---- tolerances ----------------------------------------------------------- */

/* The bound for slider velocity and acceleration against an
 * independent closed form, relative to a |omega2| and a omega2^2 (+ a |alpha2|).
 * Both sides are a few dozen flops of O(1) terms: round-off ~1e-15. */
#define KIN_REL_TOL 1e-9
/* Five-point central differences of the exact position in crank angle, step
 * FD_STEP_V for the first derivative (truncation h^4/30 |x^(5)| ~ 1e-14 a,
 * round-off 1.5 eps |x| / h ~ 6e-14 m) and FD_STEP_A for the second
 * (truncation h^4/90 |x^(6)| ~ 1e-12 a, round-off 5.3 eps |x| / h^2 ~ 2e-11
 * m): 1e-8 of a covers both by a factor 20. */
#define FD_STEP_V 1e-3
#define FD_STEP_A 3e-3
#define FD_REL_TOL 1e-8
/* Loop closure: lengths ~0.1 m, a handful of roundings each ~1e-17 m. */
#define LOOP_TOL_M 1e-15
/* Brute-force scan of the slider's extremes on SCAN_N crank angles: the
 * nearest sample lies within pi / SCAN_N of the dead centre, so the scan
 * falls short by at most |x''| (pi / SCAN_N)^2 / 2 (computed per case);
 * SCAN_ROUND_M covers the round-off of the comparison itself. */
#define SCAN_N 200000
#define SCAN_ROUND_M 1e-15
/* The slider's speed at a dead centre: zero but for round-off of a few
 * terms of size a |omega2|. */
#define DEAD_CENTRE_V_REL 1e-12
/* Sensitivities against five-point central differences in each length with
 * step SENS_STEP_REL of the coupler (round-off eps |f| / step ~ 1e-12 of
 * each row's scale; truncation step^4 |f^(5)| / 30 far below): 1e-8 of the
 * row's scale leaves a factor of 1000 for the rows' own round-off. */
#define SENS_STEP_REL 1e-4
#define SENS_REL_TOL 1e-8
/* Inverse dynamics: closed-form sums of a few products of forces ~10^3 N:
 * round-off ~1e-13 of the largest force or torque. */
#define INVDYN_REL_TOL 1e-10
/* Over one revolution at constant speed the drive's work is zero (every
 * energy is periodic); the trapezoid rule on a periodic integrand is exact
 * to round-off, ~1e-13 of max |T| 2 pi. */
#define CYCLE_WORK_REL_TOL 1e-10

/* ---- fixtures ------------------------------------------------------------- */

/* two proportions: rod/crank 2.4 (a benchmark-like short rod) and 3.5 */
static const double CRANKS[2] = {0.05, 0.1}, COUPLERS[2] = {0.12, 0.35};
/* offsets -20 % .. +20 % of the crank in steps of 5 % */
#define N_OFFSETS 9
static double offset_of(int k, double crank) { return (k - 4) * 0.05 * crank; }
static const double OMEGA = 5000.0 * 2.0 * M_PI / 60.0; /* 5000 rpm [rad/s] */
static const double ALPHA = 2000.0;                     /* a crank acceleration too [rad/s^2] */
#define N_ANGLES 720

static fb_slider_crank_mass fixture_mass(void) {
  fb_slider_crank_mass m = {.crank_mass = 0.30,
                            .crank_inertia = 1e-4,
                            .crank_com_fraction = 0.5,
                            .coupler_mass = 0.21,
                            .coupler_inertia = 2.5e-4,
                            .coupler_com_fraction = 0.5,
                            .slider_mass = 0.14};
  return m;
}

/* The oracle: x, dx/dt, d2x/dt2, theta3, dtheta3/dt, d2theta3/dt2 of the
 * explicit position functions, differentiated by hand in crank angle t
 * (g = a sin t - e, r = sqrt(b^2 - g^2) = b cos theta3):
 *   x   = a cos t + r,          x'  = -a sin t - g g' / r,
 *   x'' = -a cos t - (g'^2 + g g'') / r - g^2 g'^2 / r^3,
 *   th3 = asin(-g / b),         th3' = -g' / r,
 *   th3'' = -g'' / r - g g'^2 / r^3,      g' = a cos t, g'' = -a sin t,
 * then d/dt = omega d/dt2 and d2/dt2 = omega^2 d2/dt2^2 + alpha d/dt2. */
static void oracle(double out[6], double a, double b, double e, double t, double w, double al) {
  const double g = a * sin(t) - e, g1 = a * cos(t), g2 = -a * sin(t);
  const double r = sqrt(b * b - g * g);
  const double x1 = -a * sin(t) - g * g1 / r;
  const double x2 = -a * cos(t) - (g1 * g1 + g * g2) / r - g * g * g1 * g1 / (r * r * r);
  const double t1 = -g1 / r, t2 = -g2 / r - g * g1 * g1 / (r * r * r);
  out[0] = a * cos(t) + r;
  out[1] = x1 * w;
  out[2] = x2 * w * w + x1 * al;
  out[3] = asin(-g / b);
  out[4] = t1 * w;
  out[5] = t2 * w * w + t1 * al;
}

static double x_of(double a, double b, double e, double t) {
  const double g = a * sin(t) - e;
  return a * cos(t) + sqrt(b * b - g * g);
}

static fb_slider_crank geom(int gi, int k) {
  fb_slider_crank sc = {CRANKS[gi], COUPLERS[gi], offset_of(k, CRANKS[gi])};
  return sc;
}

/* ---- kinematics ----------------------------------------------------------- */

static void test_velocity_acceleration_vs_independent_closed_form(void **state) {
  (void)state;
  double worst[4] = {0};
  int n = 0;
  for (int gi = 0; gi < 2; gi++)
    for (int k = 0; k < N_OFFSETS; k++)
      for (int ai = 0; ai < 2; ai++)
        for (int i = 0; i < N_ANGLES; i++) {
          const fb_slider_crank sc = geom(gi, k);
          const double a = sc.crank, b = sc.coupler;
          const double al = ai ? ALPHA : 0.0, w = ai ? -OMEGA : OMEGA;
          const double t = 2.0 * M_PI * (i + 0.37) / N_ANGLES;
          fb_slider_crank_state s;
          assert_int_equal(fb_slider_crank_solve(&s, &sc, t, w, al, NULL), FB_OK);
          double o[6];
          oracle(o, a, b, sc.offset, t, w, al);
          const double ev = fabs(s.slider_v - o[1]) / (a * OMEGA);
          const double ea = fabs(s.slider_a - o[2]) / (a * (OMEGA * OMEGA + al));
          const double ew = fabs(s.coupler_omega - o[4]) / OMEGA;
          const double eal = fabs(s.coupler_alpha - o[5]) / (OMEGA * OMEGA + al);
          const double e[4] = {ev, ea, ew, eal};
          for (int q = 0; q < 4; q++) {
            worst[q] = fmax(worst[q], e[q]);
            if (!(e[q] < KIN_REL_TOL))
              fail_msg("geometry %d offset %g m angle %g rad alpha %g: quantity %d error %.3e", gi,
                       sc.offset, t, al, q, e[q]);
          }
          assert_near(s.slider_x, o[0], LOOP_TOL_M * 10);
          assert_near(s.coupler_angle, o[3], 1e-14);
          n++;
        }
  assert_int_equal(n, 2 * N_OFFSETS * 2 * N_ANGLES);
  report_residual("slider v vs explicit derivative (rel a w)", worst[0], KIN_REL_TOL);
  report_residual("slider a vs explicit derivative (rel a w^2)", worst[1], KIN_REL_TOL);
  report_residual("rod omega vs explicit derivative (rel w)", worst[2], KIN_REL_TOL);
  report_residual("rod alpha vs explicit derivative (rel w^2)", worst[3], KIN_REL_TOL);
}

static void test_velocity_acceleration_vs_central_differences(void **state) {
  (void)state;
  double worst_v = 0, worst_a = 0;
  for (int gi = 0; gi < 2; gi++)
    for (int k = 0; k < N_OFFSETS; k++)
      for (int i = 0; i < 360; i++) {
        const fb_slider_crank sc = geom(gi, k);
        const double a = sc.crank, b = sc.coupler, e = sc.offset;
        const double t = 2.0 * M_PI * (i + 0.5) / 360.0;
        fb_slider_crank_state s;
        assert_int_equal(fb_slider_crank_solve(&s, &sc, t, OMEGA, 0.0, NULL), FB_OK);
        const double h = FD_STEP_V, H = FD_STEP_A;
        const double d1 = (-x_of(a, b, e, t + 2 * h) + 8 * x_of(a, b, e, t + h) -
                           8 * x_of(a, b, e, t - h) + x_of(a, b, e, t - 2 * h)) /
                          (12 * h);
        const double d2 = (-x_of(a, b, e, t + 2 * H) + 16 * x_of(a, b, e, t + H) -
                           30 * x_of(a, b, e, t) + 16 * x_of(a, b, e, t - H) -
                           x_of(a, b, e, t - 2 * H)) /
                          (12 * H * H);
        const double ev = fabs(s.slider_v / OMEGA - d1) / a;
        const double ea = fabs(s.slider_a / (OMEGA * OMEGA) - d2) / a;
        worst_v = fmax(worst_v, ev);
        worst_a = fmax(worst_a, ea);
        assert_true(ev < FD_REL_TOL);
        assert_true(ea < FD_REL_TOL);
      }
  report_residual("slider v vs 5-point difference (rel a w)", worst_v, FD_REL_TOL);
  report_residual("slider a vs 5-point difference (rel a w^2)", worst_a, FD_REL_TOL);
}

static void test_loop_closure_and_branch(void **state) {
  (void)state;
  double worst = 0;
  for (int gi = 0; gi < 2; gi++)
    for (int k = 0; k < N_OFFSETS; k++)
      for (int i = 0; i < 3600; i++) {
        const fb_slider_crank sc = geom(gi, k);
        fb_slider_crank_state s;
        const double t = 2.0 * M_PI * i / 3600.0;
        assert_int_equal(fb_slider_crank_solve(&s, &sc, t, 1.0, 0.0, NULL), FB_OK);
        const double rod = hypot(s.c[0] - s.b[0], s.c[1] - s.b[1]);
        worst = fmax(worst, fabs(rod - sc.coupler));
        assert_near(rod, sc.coupler, LOOP_TOL_M);
        assert_true(s.c[1] == sc.offset); /* C on the guide, exactly */
        assert_near(s.b[0], sc.crank * cos(t), 0.0);
        assert_true(s.slider_x > 0.0 && s.c[0] == s.slider_x); /* the +x branch */
        assert_true(cos(s.coupler_angle) > 0.0);
        assert_near(s.transmission_angle, M_PI / 2 - fabs(s.coupler_angle), 1e-15);
        /* C is B plus the rod along theta3 */
        assert_near(s.b[0] + sc.coupler * cos(s.coupler_angle), s.c[0], LOOP_TOL_M);
        assert_near(s.b[1] + sc.coupler * sin(s.coupler_angle), s.c[1], LOOP_TOL_M);
      }
  report_residual("loop closure |BC| - coupler [m]", worst, LOOP_TOL_M);
}

static void test_limit_positions_vs_scan(void **state) {
  (void)state;
  double worst_short = 0;
  for (int gi = 0; gi < 2; gi++)
    for (int k = 0; k < N_OFFSETS; k++) {
      const fb_slider_crank sc = geom(gi, k);
      const double a = sc.crank, b = sc.coupler, e = sc.offset;
      fb_slider_crank_limits L;
      assert_int_equal(fb_slider_crank_limit_positions(&L, &sc, NULL), FB_OK);
      double xmax = -1, xmin = 1e9, tmax = 0, tmin = 0, mumin = 10, curv = 0;
      for (int i = 0; i < SCAN_N; i++) {
        const double t = 2.0 * M_PI * i / SCAN_N;
        const double x = x_of(a, b, e, t);
        if (x > xmax) xmax = x, tmax = t;
        if (x < xmin) xmin = x, tmin = t;
        mumin = fmin(mumin, acos(fabs((e - a * sin(t)) / b)));
        double o[6];
        oracle(o, a, b, e, t, 1.0, 0.0);
        curv = fmax(curv, fabs(o[2]));
      }
      const double d = M_PI / SCAN_N;
      const double shortfall = 0.5 * curv * d * d + SCAN_ROUND_M;
      /* the closed form is never beaten by a sample, and the scan comes as
       * close as its spacing allows */
      assert_true(L.x_max >= xmax - SCAN_ROUND_M);
      assert_true(L.x_max - xmax <= shortfall);
      assert_true(L.x_min <= xmin + SCAN_ROUND_M);
      assert_true(xmin - L.x_min <= shortfall);
      worst_short = fmax(worst_short, fmax(L.x_max - xmax, xmin - L.x_min) / shortfall);
      assert_near(L.stroke, L.x_max - L.x_min, 0.0);
      assert_near(L.stroke, xmax - xmin, 2 * shortfall);
      /* the scan's extreme sample is one of the two neighbours of the dead centre */
      assert_true(fabs(remainder(tmax - L.theta_outer, 2 * M_PI)) <= 2 * d);
      assert_true(fabs(remainder(tmin - L.theta_inner, 2 * M_PI)) <= 2 * d);
      assert_true(L.transmission_min <= mumin + 1e-15);
      assert_true(mumin - L.transmission_min <= 1e-6); /* acos near its kink: ~d */
      /* zero offset: the textbook stroke 2 crank, dead centres at 0 and pi */
      if (k == 4) {
        assert_near(L.stroke, 2.0 * a, 1e-15);
        assert_near(L.outstroke_angle, M_PI, 1e-15);
      }
      /* the outstroke angle is the counter-clockwise turn inner -> outer */
      double turn = fmod(L.theta_outer - L.theta_inner, 2 * M_PI);
      if (turn < 0) turn += 2 * M_PI;
      assert_near(L.outstroke_angle, turn, 1e-14);
      /* the slider stops at both dead centres */
      fb_slider_crank_state s;
      assert_int_equal(fb_slider_crank_solve(&s, &sc, L.theta_outer, OMEGA, 0, NULL), FB_OK);
      assert_near(s.slider_v, 0.0, DEAD_CENTRE_V_REL * a * OMEGA);
      assert_near(s.slider_x, L.x_max, 1e-15);
      assert_int_equal(fb_slider_crank_solve(&s, &sc, L.theta_inner, OMEGA, 0, NULL), FB_OK);
      assert_near(s.slider_v, 0.0, DEAD_CENTRE_V_REL * a * OMEGA);
      assert_near(s.slider_x, L.x_min, 1e-15);
    }
  report_residual("dead centres: scan shortfall / its bound", worst_short, 1.0);
}

static void test_change_point_and_rocker_refused(void **state) {
  (void)state;
  fb_diag d;
  /* change point: coupler = crank + |offset| (binary-exact lengths, so that the
   * perpendicular position is hit exactly) */
  const fb_slider_crank cp = {0.25, 0.375, 0.125}, cn = {0.25, 0.375, -0.125};
  assert_int_equal(fb_slider_crank_class(&cp), FB_SC_CHANGE_POINT);
  assert_int_equal(fb_slider_crank_require_full_turn(&cp, &d), FB_ERR_ASSEMBLY);
  if (!strstr(d.msg, "coupler = crank + |offset|") || !strstr(d.msg, "-90 deg"))
    fail_msg("change point message: %s", d.msg);
  assert_int_equal(fb_slider_crank_require_full_turn(&cn, &d), FB_ERR_ASSEMBLY);
  assert_non_null(strstr(d.msg, "90 deg"));
  fb_slider_crank_limits L;
  assert_int_equal(fb_slider_crank_limit_positions(&L, &cp, &d), FB_ERR_ASSEMBLY);
  /* at the perpendicular position itself the solve refuses, leaving out alone */
  fb_slider_crank_state s;
  memset(&s, 0, sizeof s);
  assert_int_equal(fb_slider_crank_solve(&s, &cp, -M_PI / 2, 1.0, 0.0, &d), FB_ERR_ASSEMBLY);
  assert_non_null(strstr(d.msg, "perpendicular"));
  assert_true(s.slider_x == 0.0);
  /* a hair longer turns fully; a hair shorter only rocks */
  const fb_slider_crank ok = {0.25, 0.375 * (1 + 1e-9), 0.125}, rock = {0.25, 0.37, 0.125};
  assert_int_equal(fb_slider_crank_class(&ok), FB_SC_FULL_TURN);
  assert_int_equal(fb_slider_crank_require_full_turn(&ok, NULL), FB_OK);
  assert_int_equal(fb_slider_crank_class(&rock), FB_SC_ROCKER);
  assert_int_equal(fb_slider_crank_require_full_turn(&rock, &d), FB_ERR_ASSEMBLY);
  assert_non_null(strstr(d.msg, "cannot turn fully"));
  /* where the loop opens: an error, no NaN */
  assert_int_equal(fb_slider_crank_solve(&s, &rock, -M_PI / 2, 1.0, 0.0, &d), FB_ERR_ASSEMBLY);
  assert_non_null(strstr(d.msg, "cannot be assembled"));
  assert_true(s.slider_x == 0.0);
  assert_int_equal(fb_slider_crank_solve(&s, &rock, M_PI / 2, 1.0, 0.0, &d), FB_OK);
  assert_string_equal(fb_sc_class_name(FB_SC_CHANGE_POINT), "change-point");
  /* bad lengths */
  const fb_slider_crank neg = {-0.05, 0.2, 0.0}, inf = {0.05, 0.2, INFINITY};
  assert_int_equal(fb_slider_crank_solve(&s, &neg, 0, 1, 0, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "crank length"));
  assert_int_equal(fb_slider_crank_check(&inf, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "offset"));
}

/* f(length) of one output row at a perturbed geometry */
static double row_at(const fb_slider_crank *base, int param, double dl, int row, double t) {
  fb_slider_crank sc = *base;
  if (param == FB_SC_PARAM_CRANK) sc.crank += dl;
  if (param == FB_SC_PARAM_COUPLER) sc.coupler += dl;
  if (param == FB_SC_PARAM_OFFSET) sc.offset += dl;
  fb_slider_crank_state s;
  if (fb_slider_crank_solve(&s, &sc, t, OMEGA, ALPHA, NULL) != FB_OK) fail_msg("solve failed");
  const double v[FB_SC_SENS_COUNT] = {s.slider_x,      s.slider_v,      s.slider_a,
                                      s.coupler_angle, s.coupler_omega, s.coupler_alpha};
  return v[row];
}

static void test_sensitivity_vs_finite_differences(void **state) {
  (void)state;
  double worst = 0;
  for (int gi = 0; gi < 2; gi++)
    for (int k = 0; k < N_OFFSETS; k += 2)
      for (int i = 0; i < 72; i++) {
        const fb_slider_crank sc = geom(gi, k);
        const double t = 2.0 * M_PI * (i + 0.3) / 72;
        double S[FB_SC_SENS_COUNT][FB_SC_PARAM_COUNT];
        assert_int_equal(fb_slider_crank_sensitivity(S, &sc, t, OMEGA, ALPHA, NULL), FB_OK);
        const double b = sc.coupler, W = OMEGA * OMEGA + ALPHA;
        /* each row's scale per metre */
        const double scale[FB_SC_SENS_COUNT] = {1.0, OMEGA, W, 1.0 / b, OMEGA / b, W / b};
        const double h = SENS_STEP_REL * b;
        for (int p = 0; p < FB_SC_PARAM_COUNT; p++)
          for (int r = 0; r < FB_SC_SENS_COUNT; r++) {
            const double fd = (-row_at(&sc, p, 2 * h, r, t) + 8 * row_at(&sc, p, h, r, t) -
                               8 * row_at(&sc, p, -h, r, t) + row_at(&sc, p, -2 * h, r, t)) /
                              (12 * h);
            const double err = fabs(S[r][p] - fd) / scale[r];
            worst = fmax(worst, err);
            if (!(err < SENS_REL_TOL))
              fail_msg("d(row %d)/d(%s) at %g rad: %.9g vs difference %.9g (err %.3e)", r,
                       fb_sc_param_name(p), t, S[r][p], fd, err);
          }
      }
  report_residual("sensitivities vs 5-point differences (rel)", worst, SENS_REL_TOL);
}

/* ---- inverse dynamics ----------------------------------------------------- */

static double cross2(const double p[2], const double q[2]) { return p[0] * q[1] - p[1] * q[0]; }

static void test_statics_balance(void **state) {
  (void)state;
  const fb_slider_crank_mass m = fixture_mass();
  const double g = 9.81, W = (m.crank_mass + m.coupler_mass + m.slider_mass) * g;
  for (int k = 0; k < N_OFFSETS; k++)
    for (int i = 0; i < 72; i++) {
      const fb_slider_crank sc = geom(0, k);
      const double t = 2.0 * M_PI * i / 72;
      fb_slider_crank_reactions r;
      assert_int_equal(fb_slider_crank_invdyn(&r, &sc, &m, g, t, 0.0, 0.0, NULL), FB_OK);
      /* external loads on the whole mechanism: ground at A, the guide, gravity */
      assert_near(r.force[0][0], 0.0, INVDYN_REL_TOL * W);
      assert_near(r.force[0][1] + r.guide_force, W, INVDYN_REL_TOL * W);
      fb_slider_crank_state s;
      fb_slider_crank_solve(&s, &sc, t, 0, 0, NULL);
      const double x2 = 0.5 * s.b[0], x3 = 0.5 * (s.b[0] + s.c[0]), x4 = s.c[0];
      const double mom = r.drive_torque + x4 * r.guide_force -
                         g * (m.crank_mass * x2 + m.coupler_mass * x3 + m.slider_mass * x4);
      assert_near(mom, 0.0, INVDYN_REL_TOL * W * (sc.crank + sc.coupler)); /* W x lever */
    }
}

/* positions, velocities and accelerations of every centre of mass from the
 * oracle (explicit derivatives), independent of fb_slider_crank_solve */
typedef struct {
  double G[3][2], v[3][2], acc[3][2]; /* crank, coupler, slider centres of mass */
  double w[3], al[3];                 /* angular velocity and acceleration (slider 0) */
  double B[2], C[2];
} motion;

static void motion_of(motion *q, const fb_slider_crank *sc, const fb_slider_crank_mass *m,
                      double t, double w, double al) {
  const double a = sc->crank;
  double o[6];
  oracle(o, a, sc->coupler, sc->offset, t, w, al);
  const double B[2] = {a * cos(t), a * sin(t)};
  const double vB[2] = {-a * w * sin(t), a * w * cos(t)};
  const double aB[2] = {-a * al * sin(t) - a * w * w * cos(t), a * al * cos(t) - a * w * w * sin(t)};
  const double C[2] = {o[0], sc->offset}, vC[2] = {o[1], 0}, aC[2] = {o[2], 0};
  const double f2 = m->crank_com_fraction, f3 = m->coupler_com_fraction;
  for (int i = 0; i < 2; i++) {
    q->G[0][i] = f2 * B[i];
    q->v[0][i] = f2 * vB[i];
    q->acc[0][i] = f2 * aB[i];
    /* G3 = (1 - f3) B + f3 C on the rigid rod */
    q->G[1][i] = (1 - f3) * B[i] + f3 * C[i];
    q->v[1][i] = (1 - f3) * vB[i] + f3 * vC[i];
    q->acc[1][i] = (1 - f3) * aB[i] + f3 * aC[i];
    q->G[2][i] = C[i];
    q->v[2][i] = vC[i];
    q->acc[2][i] = aC[i];
    q->B[i] = B[i];
    q->C[i] = C[i];
  }
  q->w[0] = w;
  q->al[0] = al;
  q->w[1] = o[4];
  q->al[1] = o[5];
  q->w[2] = q->al[2] = 0.0;
}

static void test_newton_euler_residuals(void **state) {
  (void)state;
  const fb_slider_crank_mass m = fixture_mass();
  const double g = 9.81;
  double worst = 0;
  for (int gi = 0; gi < 2; gi++)
    for (int k = 0; k < N_OFFSETS; k++)
      for (int ai = 0; ai < 2; ai++)
        for (int i = 0; i < 360; i++) {
          const fb_slider_crank sc = geom(gi, k);
          const double t = 2.0 * M_PI * (i + 0.25) / 360, al = ai ? ALPHA : 0.0;
          fb_slider_crank_reactions r;
          assert_int_equal(fb_slider_crank_invdyn(&r, &sc, &m, g, t, OMEGA, al, NULL), FB_OK);
          motion q;
          motion_of(&q, &sc, &m, t, OMEGA, al);
          const double *FA = r.force[0], *FB = r.force[1], *FC = r.force[2];
          double big = 0;
          for (int j = 0; j < 3; j++) big = fmax(big, hypot(r.force[j][0], r.force[j][1]));
          /* slider: F_C + N y - m4 g y = m4 a_C */
          const double res_s[2] = {FC[0] - m.slider_mass * q.acc[2][0],
                                   FC[1] + r.guide_force - m.slider_mass * (g + q.acc[2][1])};
          /* rod: F_B - F_C - m3 g y = m3 a_G3, moments about G3 */
          const double res_r[2] = {FB[0] - FC[0] - m.coupler_mass * q.acc[1][0],
                                   FB[1] - FC[1] - m.coupler_mass * (g + q.acc[1][1])};
          const double BG[2] = {q.B[0] - q.G[1][0], q.B[1] - q.G[1][1]};
          const double CG[2] = {q.C[0] - q.G[1][0], q.C[1] - q.G[1][1]};
          const double res_rm = cross2(BG, FB) - cross2(CG, FC) - m.coupler_inertia * q.al[1];
          /* crank: F_A - F_B - m2 g y = m2 a_G2, moments about G2 */
          const double res_c[2] = {FA[0] - FB[0] - m.crank_mass * q.acc[0][0],
                                   FA[1] - FB[1] - m.crank_mass * (g + q.acc[0][1])};
          const double AG[2] = {-q.G[0][0], -q.G[0][1]};
          const double BG2[2] = {q.B[0] - q.G[0][0], q.B[1] - q.G[0][1]};
          const double res_cm =
              r.drive_torque + cross2(AG, FA) - cross2(BG2, FB) - m.crank_inertia * q.al[0];
          const double lever = sc.crank + sc.coupler;
          const double res[8] = {res_s[0], res_s[1], res_r[0], res_r[1],
                                 res_rm / lever, res_c[0], res_c[1], res_cm / lever};
          for (int e = 0; e < 8; e++) {
            worst = fmax(worst, fabs(res[e]) / big);
            if (!(fabs(res[e]) <= INVDYN_REL_TOL * big))
              fail_msg("residual %d = %.3e N at %g rad (largest force %g N)", e, res[e], t, big);
          }
          /* frames: radial and tangential recombine to the force */
          const double u3[2] = {(q.C[0] - q.B[0]) / sc.coupler, (q.C[1] - q.B[1]) / sc.coupler};
          assert_near(r.radial[2], FC[0] * u3[0] + FC[1] * u3[1], INVDYN_REL_TOL * big);
          assert_near(hypot(r.radial[0], r.tangential[0]), hypot(FA[0], FA[1]),
                      INVDYN_REL_TOL * big);
        }
  report_residual("Newton-Euler residuals (rel largest force)", worst, INVDYN_REL_TOL);
}

static void test_power_balance(void **state) {
  (void)state;
  const fb_slider_crank_mass m = fixture_mass();
  const double g = 9.81;
  const double I[3] = {m.crank_inertia, m.coupler_inertia, 0.0};
  const double M[3] = {m.crank_mass, m.coupler_mass, m.slider_mass};
  double worst = 0, worst_cycle = 0;
  for (int gi = 0; gi < 2; gi++)
    for (int k = 0; k < N_OFFSETS; k++) {
      const fb_slider_crank sc = geom(gi, k);
      double work = 0, tmax = 0;
      const int n = 3600;
      for (int ai = 0; ai < 2; ai++)
        for (int i = 0; i < n; i++) {
          const double t = 2.0 * M_PI * i / n, al = ai ? ALPHA : 0.0;
          fb_slider_crank_reactions r;
          assert_int_equal(fb_slider_crank_invdyn(&r, &sc, &m, g, t, OMEGA, al, NULL), FB_OK);
          motion q;
          motion_of(&q, &sc, &m, t, OMEGA, al);
          /* dE/dt = sum m v.(a + g y) + I w alpha: the drive's power */
          double dE = 0, scale = 0;
          for (int b = 0; b < 3; b++) {
            const double p = M[b] * (q.v[b][0] * q.acc[b][0] + q.v[b][1] * (q.acc[b][1] + g)) +
                             I[b] * q.w[b] * q.al[b];
            dE += p;
            scale += fabs(p);
          }
          const double err = fabs(r.drive_torque * OMEGA - dE) / scale;
          worst = fmax(worst, err);
          assert_true(err < INVDYN_REL_TOL);
          if (!ai) {
            work += r.drive_torque * (2 * M_PI / n); /* periodic trapezoid */
            tmax = fmax(tmax, fabs(r.drive_torque));
          }
        }
      const double rel = fabs(work) / (tmax * 2 * M_PI);
      worst_cycle = fmax(worst_cycle, rel);
      assert_true(rel < CYCLE_WORK_REL_TOL);
    }
  report_residual("drive power vs dE/dt (rel sum |terms|)", worst, INVDYN_REL_TOL);
  report_residual("drive work over a revolution (rel)", worst_cycle, CYCLE_WORK_REL_TOL);
}

static void test_invdyn_peaks_and_refusals(void **state) {
  (void)state;
  const fb_slider_crank_mass m = fixture_mass();
  const fb_slider_crank sc = geom(0, 6);
  double fm[3], nmax, tmax;
  assert_int_equal(
      fb_slider_crank_invdyn_peaks(fm, &nmax, &tmax, &sc, &m, 9.81, OMEGA, 720, NULL), FB_OK);
  /* the peaks are the samples' largest: recompute two of them by hand */
  double fc = 0, tq = 0;
  for (int i = 0; i < 720; i++) {
    fb_slider_crank_reactions r;
    fb_slider_crank_invdyn(&r, &sc, &m, 9.81, 2 * M_PI * i / 720, OMEGA, 0, NULL);
    fc = fmax(fc, hypot(r.force[2][0], r.force[2][1]));
    tq = fmax(tq, fabs(r.drive_torque));
  }
  assert_near(fm[2], fc, 0.0);
  assert_near(tmax, tq, 0.0);
  /* the piston pin carries about the slider's inertia force m4 a_max at the
   * outer dead centre: a omega^2 (1 + a/b) for zero offset, more here */
  assert_true(fm[2] > m.slider_mass * sc.crank * OMEGA * OMEGA);
  fb_diag d;
  fb_slider_crank_mass bad = m;
  bad.coupler_com_fraction = 1.5;
  fb_slider_crank_reactions r;
  assert_int_equal(fb_slider_crank_invdyn(&r, &sc, &bad, 9.81, 0, 1, 0, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "coupler centre-of-mass fraction"));
  bad = m;
  bad.slider_mass = -1;
  assert_int_equal(fb_slider_crank_invdyn(&r, &sc, &bad, 9.81, 0, 1, 0, &d), FB_ERR_RANGE);
  assert_non_null(strstr(d.msg, "slider mass"));
  assert_int_equal(fb_slider_crank_invdyn_peaks(fm, NULL, NULL, &sc, &m, 9.81, 1, 0, &d),
                   FB_ERR_ARG);
  assert_string_equal(fb_sc_joint_name(FB_SC_JOINT_COUPLER_SLIDER), "coupler-slider");
  assert_string_equal(fb_sc_joint_name(FB_SC_JOINT_SLIDER_GROUND), "slider-ground");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_velocity_acceleration_vs_independent_closed_form),
      cmocka_unit_test(test_velocity_acceleration_vs_central_differences),
      cmocka_unit_test(test_loop_closure_and_branch),
      cmocka_unit_test(test_limit_positions_vs_scan),
      cmocka_unit_test(test_change_point_and_rocker_refused),
      cmocka_unit_test(test_sensitivity_vs_finite_differences),
      cmocka_unit_test(test_statics_balance),
      cmocka_unit_test(test_newton_euler_residuals),
      cmocka_unit_test(test_power_balance),
      cmocka_unit_test(test_invdyn_peaks_and_refusals),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
