#include "reference.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "closed_form.h"
#include "contact_mass.h"
#include "linkage.h"
#include "planar_turn.h"
#include "slider_crank_dynamics.h"
#include "stop_text.h"
#include "start.h"

typedef struct {
  const fb_case *c;
  const fb_contact_law *law;
  int ideal;
  double a, b, cf, g;         /* crank, coupler, follower, ground lengths [m] */
  double m3, m4, i3, i4, f3, f4;
  double theta0, omega2, grav, clear;
  double open;                /* the assembly branch: +1 open, -1 crossed */
  double bb_cc, inv_2b, inv_cf; /* b^2 - c^2 [m^2], 1 / (2 b), 1 / c [1/m]: fourbar_origin_at */
  double v0;                  /* hysteresis laws' impact velocity (unused by the models) */
  int sc;                     /* 1: the closed form's own model (closed_form.h reference_model:
                                 the slider-crank's, slider_crank_dynamics.h), q = (theta3, x) */
  fb_sc_dyn_model scm;        /* its model */
  int cj;                     /* the clearance joint (the description's reference_joint) */
  /* the crank's clock: the right-hand side's time is local, counted from
   * t_base (a sample's time), where the crank's direction is (c_base, s_base) */
  double t_base, c_base, s_base;
  /* last evaluation, for sampling */
  double force, pen, ex, ey, acc[2];
} ref_ctx;

/* Starts the local clock at the absolute time t [s]. The crank's angle
 * theta0 + omega2 t is formed once here; inside a sample interval the
 * right-hand side turns the crank from there by omega2 tl, tl <= a few
 * output steps, so its direction carries the rounding of a small angle
 * rather than of omega2 t (which grows with the run: 1.4e-14 rad at 16
 * revolutions of the paper's case, enough for the stiff contact law to
 * drive the step controller down as t grows). */
static void clock_start(ref_ctx *r, double t) {
  const double th2 = r->theta0 + r->omega2 * t;
  r->t_base = t;
  r->c_base = cos(th2);
  r->s_base = sin(th2);
}

/* the crank's direction (cos theta2, sin theta2) at the local time tl [s] */
static void crank_dir(const ref_ctx *r, double tl, double *c2, double *s2) {
  const double d = r->omega2 * tl, cd = cos(d), sd = sin(d);
  *c2 = r->c_base * cd - r->s_base * sd;
  *s2 = r->s_base * cd + r->c_base * sd;
}

/* The ideal four-bar (no clearance) at the crank direction (c2, s2): the
 * coupler's and follower's directions and angular velocities, the origin of
 * the deviation state. fb_linkage_solve's position and velocity
 * (linkage.h), formed from directions: C on circle(B, b) and circle(D, c),
 * theta3 = angle(B->D) +- phi (open: +), cos phi = (b^2 + f^2 - c^2) /
 * (2 b f), f = |BD|. */
typedef struct {
  double u3[2], u4[2]; /* (cos, sin) of theta3, theta4 [-] */
  double w3, w4;       /* [rad/s] */
} fourbar_origin;

static void fourbar_origin_at(fourbar_origin *o, const ref_ctx *r, double c2, double s2) {
  const double b = r->b, cl = r->cf;
  const double bx = r->a * c2, by = r->a * s2;
  const double dx = r->g - bx, dy = -by; /* B->D */
  const double f2 = dx * dx + dy * dy, inv_f = 1.0 / sqrt(f2);
  const double cphi = (r->bb_cc + f2) * inv_f * r->inv_2b;
  const double sphi = r->open * sqrt(fmax(0.0, (1.0 - cphi) * (1.0 + cphi)));
  const double ux = dx * inv_f, uy = dy * inv_f;
  o->u3[0] = ux * cphi - uy * sphi;
  o->u3[1] = ux * sphi + uy * cphi;
  o->u4[0] = (bx + b * o->u3[0] - r->g) * r->inv_cf;
  o->u4[1] = (by + b * o->u3[1]) * r->inv_cf;
  /* -b s3 w3 + c s4 w4 = a s2 w2,  b c3 w3 - c c4 w4 = -a c2 w2 */
  const double c3 = o->u3[0], s3 = o->u3[1], c4 = o->u4[0], s4 = o->u4[1];
  const double inv_det = 1.0 / (b * cl * (s3 * c4 - c3 * s4));
  const double r1 = r->a * s2 * r->omega2, r2 = -r->a * c2 * r->omega2;
  o->w3 = (r1 * (-cl * c4) - cl * s4 * r2) * inv_det;
  o->w4 = ((-b * s3) * r2 - b * c3 * r1) * inv_det;
}

/* the ideal motion's positions at the local time tl: both angles (four-bar),
 * the rod's angle and the slider's x (slider-crank) */
static void origin_positions(const ref_ctx *r, double tl, double q[2]) {
  double c2, s2;
  crank_dir(r, tl, &c2, &s2);
  if (r->sc) {
    fb_sc_dyn_origin o;
    fb_sc_dyn_origin_at(&o, &r->scm, c2, s2);
    q[0] = atan2(o.u3[1], o.u3[0]);
    q[1] = o.x;
    return;
  }
  fourbar_origin o;
  fourbar_origin_at(&o, r, c2, s2);
  q[0] = atan2(o.u3[1], o.u3[0]);
  q[1] = atan2(o.u4[1], o.u4[0]);
}

/* Absolute positions to deviations (y[0..1] in place) at the local time tl,
 * angles reduced to (-pi, pi]; the ideal reference (ideal = 1) integrates
 * absolute positions. */
static void to_deviation(const ref_ctx *r, double tl, double y[4]) {
  if (r->ideal) return;
  double q[2];
  origin_positions(r, tl, q);
  y[0] = remainder(y[0] - q[0], 2.0 * M_PI);
  y[1] = r->sc ? y[1] - q[1] : remainder(y[1] - q[1], 2.0 * M_PI);
}

/* Deviations back to absolute positions at the local time tl; an angle is
 * continued from the previous sample's (prev, same units) so that it does not
 * jump by 2 pi where the ideal angle wraps. */
static void to_absolute(const ref_ctx *r, double tl, const double y[4], const double prev[2],
                        double q[2]) {
  if (r->ideal) {
    q[0] = y[0], q[1] = y[1];
    return;
  }
  origin_positions(r, tl, q);
  q[0] = prev[0] + remainder(q[0] + y[0] - prev[0], 2.0 * M_PI);
  q[1] = r->sc ? q[1] + y[1] : prev[1] + remainder(q[1] + y[1] - prev[1], 2.0 * M_PI);
}

/* the slider-crank's equations of motion in deviation form
 * (fb_sc_dyn_eval_dev), with the contact of the evaluation kept for sampling */
static int eom_sc(double tl, const double y[], double dydt[], ref_ctx *r) {
  double c2, s2;
  crank_dir(r, tl, &c2, &s2);
  fb_sc_dyn_eval ev;
  fb_sc_dyn_eval_dev(&ev, &r->scm, c2, s2, y);
  for (int i = 0; i < FB_SC_DYN_DIM; i++) dydt[i] = ev.dydt[i];
  r->force = ev.force;
  r->pen = ev.penetration;
  r->ex = ev.ecc[0];
  r->ey = ev.ecc[1];
  r->acc[0] = ev.dydt[2];
  r->acc[1] = ev.dydt[3];
  return GSL_SUCCESS;
}

/* the ideal limit (ideal = 1): the closed loop's velocity constraint on the
 * absolute angles (fb_linkage_solve's 2x2 system):
 *  -b s3 w3 + c s4 w4 = a s2 w2,  b c3 w3 - c c4 w4 = -a c2 w2 */
static int eom_ideal(double tl, const double y[], double dydt[], const ref_ctx *r) {
  double c2, s2;
  crank_dir(r, tl, &c2, &s2);
  const double s3 = sin(y[0]), c3 = cos(y[0]), s4 = sin(y[1]), c4 = cos(y[1]);
  const double det = r->b * r->cf * sin(y[0] - y[1]);
  const double r1 = r->a * s2 * r->omega2, r2 = -r->a * c2 * r->omega2;
  dydt[0] = (r1 * (-r->cf * c4) - r->cf * s4 * r2) / det;
  dydt[1] = ((-r->b * s3) * r2 - r->b * c3 * r1) / det;
  dydt[2] = dydt[3] = 0.0;
  return GSL_SUCCESS;
}

/* The four-bar's equations of motion at the local time tl (contact geometry
 * and generalised forces; fills acc[]). The state is y = (theta3 - theta3i,
 * theta4 - theta4i, theta3', theta4'): the angles as deviations from the
 * ideal four-bar's (fourbar_origin_at), so that the eccentricity
 *   e = B_pin - B_hole = b (u(theta3) - u(theta3i)) - c (u(theta4) - u(theta4i))
 * (the ideal loop closes: B_pin = D + c u(theta4i) - b u(theta3i)) is formed
 * from small terms (planar_turn.h) and carries no rounding of the links'
 * lengths. The slider-crank's likewise (eom_sc). */
static int eom(double tl, const double y[], double dydt[], void *p) {
  ref_ctx *r = p;
  if (r->sc) return eom_sc(tl, y, dydt, r);
  if (r->ideal) return eom_ideal(tl, y, dydt, r);
  double c2, s2;
  crank_dir(r, tl, &c2, &s2);
  fourbar_origin o;
  fourbar_origin_at(&o, r, c2, s2);
  double t3[2], t4[2];
  fb_turn_change(t3, o.u3, y[0]);
  fb_turn_change(t4, o.u4, y[1]);
  const double w3 = y[2], w4 = y[3];
  const double c3 = o.u3[0] + t3[0], s3 = o.u3[1] + t3[1];
  const double c4 = o.u4[0] + t4[0], s4 = o.u4[1] + t4[1];
  const double b = r->b, cl = r->cf, f3 = r->f3, f4 = r->f4;
  /* e3p = d e3 / d theta3 = (-s3, c3), likewise e4p */
  const double e3[2] = {c3, s3}, e3p[2] = {-s3, c3}, e4[2] = {c4, s4}, e4p[2] = {-s4, c4};
  /* Jacobian columns (theta3, theta4) of the coupler COM G3, follower COM G4, hole B */
  const double JG3[2][2] = {{-(1 - f3) * b * e3p[0], cl * e4p[0]}, {-(1 - f3) * b * e3p[1], cl * e4p[1]}};
  const double JG4_4[2] = {f4 * cl * e4p[0], f4 * cl * e4p[1]};
  const double JB[2][2] = {{-b * e3p[0], cl * e4p[0]}, {-b * e3p[1], cl * e4p[1]}};
  /* mass matrix; cos(theta4 - theta3) = c4 c3 + s4 s3 */
  const double M11 = r->m3 * (1 - f3) * (1 - f3) * b * b + r->i3;
  const double M12 = -r->m3 * cl * (1 - f3) * b * (c4 * c3 + s4 * s3);
  const double M22 = r->m3 * cl * cl + r->m4 * f4 * f4 * cl * cl + r->i4;
  /* quadratic velocity terms of G3: -c w4^2 e4 + (1 - f3) b w3^2 e3 */
  const double gam[2] = {-cl * w4 * w4 * e4[0] + (1 - f3) * b * w3 * w3 * e3[0],
                         -cl * w4 * w4 * e4[1] + (1 - f3) * b * w3 * w3 * e3[1]};
  double Q[2];
  for (int k = 0; k < 2; k++)
    Q[k] = -r->m3 * (JG3[0][k] * gam[0] + JG3[1][k] * gam[1]) /* -J^T m gamma */
           + r->m3 * (-r->grav) * JG3[1][k];                     /* gravity on the coupler */
  Q[1] += r->m4 * (-r->grav) * JG4_4[1];
  /* contact */
  const double e[2] = {b * t3[0] - cl * t4[0], b * t3[1] - cl * t4[1]};
  const double ecc = sqrt(e[0] * e[0] + e[1] * e[1]); /* |e| ~ the clearance: no overflow */
  const double delta = ecc - r->clear;
  double fn = 0.0;
  if (delta > 0.0 && ecc > 0.0) {
    const double n[2] = {e[0] / ecc, e[1] / ecc};
    const double vp[2] = {-r->a * s2 * r->omega2, r->a * c2 * r->omega2};
    const double vh[2] = {JB[0][0] * w3 + JB[0][1] * w4, JB[1][0] * w3 + JB[1][1] * w4};
    const double ddot = n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]);
    fb_contact_law l = *r->law;
    if (fb_contact_law_wants_mass(&l)) {
      /* the damper's mass: the mechanism's effective mass along n,
       * 1 / (w^T M^-1 w), w = J_hole^T n (the pin's crank is driven) */
      const double w[2] = {JB[0][0] * n[0] + JB[1][0] * n[1], JB[0][1] * n[0] + JB[1][1] * n[1]};
      const double dm = M11 * M22 - M12 * M12;
      l = fb_contact_law_on_mass(
          &l, dm / (w[0] * (M22 * w[0] - M12 * w[1]) + w[1] * (M11 * w[1] - M12 * w[0])));
    }
    fn = fb_contact_force(&l, delta, ddot, r->v0);
    /* the pin pushes the hole (coupler) along +n */
    for (int k = 0; k < 2; k++) Q[k] += fn * (JB[0][k] * n[0] + JB[1][k] * n[1]);
  }
  const double det = M11 * M22 - M12 * M12;
  const double a3 = (Q[0] * M22 - M12 * Q[1]) / det;
  const double a4 = (M11 * Q[1] - M12 * Q[0]) / det;
  dydt[0] = w3 - o.w3; /* the deviations' rates */
  dydt[1] = w4 - o.w4;
  dydt[2] = a3;
  dydt[3] = a4;
  r->force = fn;
  r->pen = delta > 0.0 ? delta : 0.0;
  r->ex = e[0];
  r->ey = e[1];
  r->acc[0] = a3;
  r->acc[1] = a4;
  return GSL_SUCCESS;
}

/* the six quantities the refinement ranks (peak_refine.h), each as a
 * maximum: force, penetration, theta'' max and -min of both output bodies */
#define REFINE_QUANTITIES 6

/* the series refined (peak_refine.h's start reads it) */
typedef struct {
  ref_ctx *r;
  const fb_series *s;
} refine_src;

static int refine_rhs(double tl, const double y[], double dydt[], void *p) {
  return eom(tl, y, dydt, ((refine_src *)p)->r);
}

/* peak_refine.h's eval: the six quantities and the rates at local time tl */
static void refine_eval(double *q, double *dy, double tl, const double *y, void *p) {
  ref_ctx *r = ((refine_src *)p)->r;
  eom(tl, y, dy, r);
  const double v[REFINE_QUANTITIES] = {r->force, r->pen, dy[2], -dy[2], dy[3], -dy[3]};
  memcpy(q, v, sizeof v);
}

/* peak_refine.h's start: sample k's state as deviations, local time 0 there */
static double refine_start(double *y, size_t k, void *p) {
  const refine_src *src = p;
  const fb_series *s = src->s;
  y[0] = s->body[0][FB_Q_POS][k];
  y[1] = s->body[1][FB_Q_POS][k];
  y[2] = s->body[0][FB_Q_VEL][k];
  y[3] = s->body[1][FB_Q_VEL][k];
  clock_start(src->r, s->t[k]);
  to_deviation(src->r, 0.0, y);
  return 0.0;
}

/* replaces the samples at the spikes of out with their refined extremes */
static void refine_peaks(fb_series *out, ref_ctx *r, double h, double tol, double t_split) {
  refine_src src = {r, out};
  const fb_peak_refine_ode ode = {4, REFINE_QUANTITIES, refine_rhs, refine_eval, refine_start,
                                  &src, h, tol, 0};
  fb_peak_refine_column cols[4] = {{out->contact[r->cj][FB_C_FORCE], 0, -1, 1},
                                   {out->contact[r->cj][FB_C_PEN], 1, -1, 1},
                                   {out->body[0][FB_Q_ACC], 2, 3, 0},
                                   {out->body[1][FB_Q_ACC], 4, 5, 0}};
  fb_peak_refine(cols, 4, out->t, out->n, t_split, &ode);
}

fb_status fb_reference_tolerance(double *tol, fb_diag *diag) {
  const char *tol_env = getenv("FOURBAR_REFERENCE_TOL"); /* convergence studies only */
  *tol = FB_REFERENCE_TOL;
  if (!tol_env) return FB_OK;
  char *end;
  const double t = strtod(tol_env, &end);
  /* decimal only: strtod also reads 0x1p-30, inf and nan */
  const int decimal = strspn(tol_env, "0123456789+-.eE") == strlen(tol_env);
  if (!decimal || end == tol_env || *end || !(t >= FB_REFERENCE_TOL_MIN && t <= FB_REFERENCE_TOL_MAX))
    return fb_diag_set(diag, FB_ERR_RANGE, "FOURBAR_REFERENCE_TOL = '%s' (environment): the "
                       "reference tolerance must be a decimal number from %g to %g", tol_env,
                       FB_REFERENCE_TOL_MIN, FB_REFERENCE_TOL_MAX);
  *tol = t;
  return FB_OK;
}

int fb_reference_contact_state(fb_contact_phase *p, double force, double force_prev) {
  int state = FB_STATE_FREE;
  if (force > 0.0) {
    if (p->state == FB_STATE_FREE) {
      state = FB_STATE_IMPACT;
      p->restituting = 0;
    } else {
      state = p->state;
      if (force - force_prev < 0.0) p->restituting = 1;
      else if (p->restituting && state == FB_STATE_IMPACT) state = FB_STATE_CONTINUOUS;
    }
  }
  p->state = state;
  return state;
}

fb_status fb_reference_run(fb_series *out, size_t *steps, const fb_case *c,
                           const fb_contact_law *law, int ideal, fb_stop *stop, fb_diag *diag) {
  double tol;
  fb_status st = fb_reference_tolerance(&tol, diag);
  if (st != FB_OK) return st;
  return fb_reference_run_tol(out, steps, c, law, ideal, tol, stop, diag);
}

fb_status fb_reference_run_tol(fb_series *out, size_t *steps, const fb_case *c,
                               const fb_contact_law *law, int ideal, double tol, fb_stop *stop,
                               fb_diag *diag) {
  if (!(tol >= FB_REFERENCE_TOL_MIN && tol <= FB_REFERENCE_TOL_MAX))
    return fb_diag_set(diag, FB_ERR_RANGE, "reference tolerance %g: must lie in [%g, %g]", tol,
                       FB_REFERENCE_TOL_MIN, FB_REFERENCE_TOL_MAX);
  fb_stop why;
  memset(&why, 0, sizeof why);
  why.engine = "reference";
  why.joint = -1;
  if (!stop) stop = &why;
  *stop = why;
  const int cj = fb_case_mech(c)->reference_joint;
  const char *cjn = fb_case_joint_name(c, cj);
  if (!ideal && c->clearance.mask != (1 << cj))
    return fb_diag_set(diag, FB_ERR_ARG,
                       "the closed-form reference covers clearance at the %s joint alone "
                       "(fb_reference_run_joints takes the others)", cjn);
  const fb_closed_form *cf = fb_closed_form_of(c->mechanism);
  if (ideal && !cf->ideal_reference)
    return fb_diag_set(diag, FB_ERR_ARG, "the ideal reference integrates the four-bar only");
  fb_linkage lk;
  fb_case_stackup_lengths(c, &lk);
  const double omega2 = fb_case_omega2(c);
  /* the case's start ([run] start, pin_start), the same state ODE starts from */
  fb_start_state st;
  fb_status rc = fb_start_resolve(&st, c, &lk, ideal ? 0 : 1 << cj, diag);
  if (rc != FB_OK) return rc;
  const double pen_limit = fb_case_penetration_limit(c);
  ref_ctx r;
  memset(&r, 0, sizeof r);
  r.c = c;
  r.law = law;
  r.ideal = ideal;
  r.a = lk.length[FB_CRANK];
  r.b = lk.length[FB_COUPLER];
  r.cf = lk.length[FB_FOLLOWER];
  r.g = lk.length[FB_GROUND];
  r.m3 = c->link[FB_COUPLER].mass;
  r.m4 = c->link[FB_FOLLOWER].mass;
  r.i3 = c->link[FB_COUPLER].inertia;
  r.i4 = c->link[FB_FOLLOWER].inertia;
  r.f3 = c->link[FB_COUPLER].com_fraction;
  r.f4 = c->link[FB_FOLLOWER].com_fraction;
  r.theta0 = c->crank_angle0;
  r.omega2 = omega2;
  r.grav = c->gravity;
  r.clear = c->radial_clearance;
  r.v0 = 1e-3;
  r.cj = cj;
  r.open = c->branch == FB_BRANCH_CROSSED ? -1.0 : 1.0;
  r.bb_cc = r.b * r.b - r.cf * r.cf;
  r.inv_2b = 0.5 / r.b;
  r.inv_cf = 1.0 / r.cf;
  clock_start(&r, 0.0);
  if (cf->reference_model) { /* the closed form's own minimal coordinates */
    r.sc = 1;
    rc = cf->reference_model(&r.scm, c, &lk, law, r.v0, diag);
    if (rc != FB_OK) return rc;
  }
  double y[4] = {st.body[0][FB_Q_POS], st.body[1][FB_Q_POS], st.body[0][FB_Q_VEL],
                 st.body[1][FB_Q_VEL]};
  double q[2] = {y[0], y[1]}; /* the absolute positions at the last sample */
  to_deviation(&r, 0.0, y);
  gsl_odeiv2_system sys = {eom, NULL, 4, &r};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_odeiv2_driver *drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, c->solver.h * 1e-3,
                                                         tol, tol);
  if (!drv) {
    gsl_set_error_handler(old);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the reference integrator");
  }
  gsl_odeiv2_driver_set_nmax(drv, 0);
  const size_t n = (size_t)llround(fb_case_duration(c) / c->solver.h);
  fb_status status = FB_OK;
  if (fb_series_init_mech(out, n + 1, fb_case_mech(c)) != FB_OK ||
      (!ideal && fb_series_enable_contact(out, 1 << cj) != FB_OK)) {
    gsl_odeiv2_driver_free(drv);
    gsl_set_error_handler(old);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n + 1);
  }
  double t = 0.0; /* local time since the clock's start, the previous sample (clock_start) */
  size_t taken = 0;
  const size_t budget = (n + 1) * FB_REFERENCE_STEPS_PER_SAMPLE;
  fb_contact_phase phase = {FB_STATE_FREE, 0};
  for (size_t k = 0; k <= n; k++) {
    const double tk = (double)k * c->solver.h;
    /* the run's wall-time deadline ([run] max_wall_s, case.h) holds here too */
    if (k > 0 && c->wall_deadline > 0.0 && k % 16 == 0 && fb_clock_s() > c->wall_deadline) {
      stop->kind = FB_STOP_WALL_TIME;
      stop->t = r.t_base + t;
      stop->limit = c->max_wall_s;
      stop->t_end = fb_case_duration(c);
      break;
    }
    if (k > 0) {
      gsl_odeiv2_driver_set_nmax(drv, budget - taken); /* the rest of the budget */
      clock_start(&r, (double)(k - 1) * c->solver.h);
      t = 0.0;
      int g = gsl_odeiv2_driver_apply(drv, &t, c->solver.h, y);
      taken += (size_t)drv->n; /* the driver counts per call */
      if (g == GSL_EMAXITER || (g == GSL_SUCCESS && taken >= budget && k < n)) {
        stop->kind = FB_STOP_STEP_BUDGET;
        stop->t = r.t_base + t;
        stop->value = (double)budget;
        stop->limit = FB_REFERENCE_STEPS_PER_SAMPLE;
        stop->t_end = fb_case_duration(c);
        break;
      }
      if (g != GSL_SUCCESS) {
        stop->kind = FB_STOP_SOLVER;
        stop->t = r.t_base + t;
        snprintf(stop->detail, sizeof stop->detail, "%s", gsl_strerror(g));
        break;
      }
    }
    double dy[4];
    eom(t, y, dy, &r); /* accelerations and contact at the sample */
    to_absolute(&r, t, y, q, q);
    double a3 = dy[2], a4 = dy[3];
    if (ideal) {
      /* accelerations: the second time derivative of the loop constraint along
       * the integrated state (the same 2x2 matrix with the state's angles) */
      double c2_, s2_;
      crank_dir(&r, t, &c2_, &s2_);
      const double s3 = sin(y[0]), c3 = cos(y[0]);
      const double s4 = sin(y[1]), c4 = cos(y[1]);
      const double w3 = dy[0], w4 = dy[1];
      const double q1 = r.a * c2_ * omega2 * omega2 + r.b * c3 * w3 * w3 - r.cf * c4 * w4 * w4;
      const double q2 = r.a * s2_ * omega2 * omega2 + r.b * s3 * w3 * w3 - r.cf * s4 * w4 * w4;
      const double det = r.b * r.cf * sin(y[0] - y[1]);
      a3 = (q1 * (-r.cf * c4) - r.cf * s4 * q2) / det;
      a4 = ((-r.b * s3) * q2 - r.b * c3 * q1) / det;
    }
    fb_sample x;
    memset(&x, 0, sizeof x);
    x.t = tk;
    x.crank_angle = r.theta0 + omega2 * tk;
    x.body[0][FB_Q_POS] = q[0];
    x.body[1][FB_Q_POS] = q[1];
    x.body[0][FB_Q_VEL] = ideal ? dy[0] : y[2];
    x.body[1][FB_Q_VEL] = ideal ? dy[1] : y[3];
    x.body[0][FB_Q_ACC] = a3;
    x.body[1][FB_Q_ACC] = a4;
    if (!ideal) {
      const int state = fb_reference_contact_state(
          &phase, r.force, out->n ? out->contact[cj][FB_C_FORCE][out->n - 1] : 0.0);
      x.contact[cj][FB_C_FORCE] = r.force;
      x.contact[cj][FB_C_PEN] = r.pen;
      x.contact[cj][FB_C_EX] = r.ex;
      x.contact[cj][FB_C_EY] = r.ey;
      x.contact[cj][FB_C_STATE] = state;
    }
    if (!(isfinite(q[0]) && isfinite(q[1]) && isfinite(x.body[0][FB_Q_VEL]) && isfinite(a3))) {
      stop->kind = FB_STOP_NONFINITE;
      stop->t = tk;
      break;
    }
    if (!ideal && r.pen > pen_limit) {
      stop->kind = FB_STOP_PENETRATION;
      stop->t = tk;
      stop->joint = cj;
      stop->joint_name = cjn;
      stop->value = r.pen;
      stop->limit = pen_limit;
      break;
    }
    fb_series_push(out, &x);
  }
  if (!ideal && status == FB_OK) refine_peaks(out, &r, c->solver.h, tol, fb_case_peak_window_from(c));
  *steps = taken;
  gsl_odeiv2_driver_free(drv);
  gsl_set_error_handler(old);
  if (status == FB_OK && stop->kind != FB_STOP_NONE) {
    char text[256];
    status = fb_diag_set(diag, FB_ERR_NUMERIC, "%s", fb_stop_text(text, sizeof text, stop));
  }
  return status;
}
