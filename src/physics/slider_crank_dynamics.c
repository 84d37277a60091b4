#include "slider_crank_dynamics.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <string.h>

#include "contact_mass.h"
#include "planar_turn.h"

/* tolerance bounds: the four-bar reference's (reference.h), for the same
 * reasons (rk8pd's error estimate is lost in round-off below 1e-13) */
#define SC_DYN_TOL_MIN 1e-13
#define SC_DYN_TOL_MAX 1e-3

fb_status fb_sc_dyn_check(const fb_sc_dyn_model *m, fb_diag *diag) {
  fb_status st = fb_slider_crank_require_full_turn(&m->geometry, diag);
  if (st != FB_OK) return st;
  st = fb_slider_crank_mass_check(&m->mass, diag);
  if (st != FB_OK) return st;
  const double fb = m->mass.coupler_com_fraction * m->geometry.coupler;
  const double i_b = m->mass.coupler_mass * fb * fb + m->mass.coupler_inertia;
  if (!(i_b > 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "coupler inertia about the crank pin = %g kg m^2: the rod needs mass or "
                       "inertia to have dynamics",
                       i_b);
  if (!(m->mass.slider_mass > 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "slider mass = %g kg: a free slider needs a positive mass",
                       m->mass.slider_mass);
  if (!(isfinite(m->gravity) && m->gravity >= 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "gravity = %g m/s^2: must be finite and >= 0",
                       m->gravity);
  if (!(isfinite(m->clearance) && m->clearance >= 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "radial clearance = %g m: must be finite and not negative", m->clearance);
  if (!(isfinite(m->impact_velocity) && m->impact_velocity > 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "impact velocity = %g m/s: must be positive",
                       m->impact_velocity);
  if (!isfinite(m->theta0) || !isfinite(m->omega2))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "crank angle %g rad, speed %g rad/s: the drive must be finite", m->theta0,
                       m->omega2);
  return fb_contact_law_check(&m->law, diag);
}

/* the law's elastic exponent: the linear and restitution laws force 1 */
static double elastic_exponent(const fb_contact_law *l) {
  return (l->kind == FB_LAW_LINEAR || l->kind == FB_LAW_RESTITUTION) ? 1.0 : l->exponent;
}

/* the equations of motion from the crank's direction (c2, s2), the rod's
 * (c3, s3), the eccentricity e = P - H and the speeds w3 = theta3', v = x' */
static void eval_core(fb_sc_dyn_eval *out, const fb_sc_dyn_model *m, double c2, double s2,
                      double c3, double s3, const double e[2], double w3, double v) {
  const double a = m->geometry.crank, b = m->geometry.coupler;
  const double w2 = m->omega2;
  const double m3 = m->mass.coupler_mass, m4 = m->mass.slider_mass, g = m->gravity;
  const double f3 = m->mass.coupler_com_fraction;
  /* the crank pin B and its motion (prescribed) */
  const double B[2] = {a * c2, a * s2};
  const double dB[2] = {-a * w2 * s2, a * w2 * c2};
  const double ddB[2] = {-w2 * w2 * B[0], -w2 * w2 * B[1]};
  const double up[2] = {-s3, c3}; /* d u / d theta3 */
  const double de[2] = {dB[0] + b * w3 * up[0] - v, dB[1] + b * w3 * up[1]};
  const double ecc = hypot(e[0], e[1]);
  const double M11 = m3 * f3 * b * f3 * b + m->mass.coupler_inertia, M22 = m4;
  double n[2] = {0.0, 0.0}, F = 0.0, Fel = 0.0, rate = 0.0, meff = INFINITY;
  if (ecc > 0.0) {
    n[0] = e[0] / ecc;
    n[1] = e[1] / ecc;
    rate = n[0] * de[0] + n[1] * de[1];
    /* w = J_e^T n with J_e = [b u', -(1, 0)] */
    const double wt = b * (up[0] * n[0] + up[1] * n[1]), wx = -n[0];
    const double inv = wt * wt / M11 + wx * wx / M22;
    meff = inv > 0.0 ? 1.0 / inv : INFINITY;
  }
  const double delta = ecc - m->clearance;
  if (delta > 0.0) {
    const fb_contact_law l = fb_contact_law_on_mass(&m->law, meff); /* contact_mass.h */
    F = fb_contact_force(&l, delta, rate, m->impact_velocity);
    Fel = fb_contact_force(&l, delta, 0.0, m->impact_velocity);
  }
  /* rod: (m3 (f3 b)^2 + I3) theta3'' = -m3 f3 b u'.(B'' + g y) - F b u'.n */
  const double q3 = -m3 * f3 * b * (up[0] * ddB[0] + up[1] * (ddB[1] + g)) -
                    F * b * (up[0] * n[0] + up[1] * n[1]);
  const double a3 = q3 / M11;
  const double ax = F * n[0] / M22;
  out->dydt[0] = w3;
  out->dydt[1] = v;
  out->dydt[2] = a3;
  out->dydt[3] = ax;
  out->ecc[0] = e[0];
  out->ecc[1] = e[1];
  out->penetration = delta > 0.0 ? delta : 0.0;
  out->penetration_rate = rate;
  out->force = F;
  out->elastic_force = Fel;
  out->effective_mass = meff;
  out->guide_force = m4 * g - F * n[1];
  /* the rod's Newton equation gives the force on it from the crank:
   * m3 a_G3 = F_B - F n - m3 g y, a_G3 = B'' + f3 b (a3 u' - w3^2 u) */
  const double aG3[2] = {ddB[0] + f3 * b * (a3 * up[0] - w3 * w3 * c3),
                         ddB[1] + f3 * b * (a3 * up[1] - w3 * w3 * s3)};
  const double FB[2] = {m3 * aG3[0] + F * n[0], m3 * (aG3[1] + g) + F * n[1]};
  out->crank_force[0] = FB[0];
  out->crank_force[1] = FB[1];
  /* crank at constant speed, about A: T - B x F_B - m2 g G2_x = 0 */
  out->drive_torque = (B[0] * FB[1] - B[1] * FB[0]) +
                      m->mass.crank_mass * g * m->mass.crank_com_fraction * B[0];
  out->power_in = FB[0] * dB[0] + FB[1] * dB[1];
  out->power_damping = (F - Fel) * rate;
}

void fb_sc_dyn_eval_at(fb_sc_dyn_eval *out, const fb_sc_dyn_model *m, double t, const double y[]) {
  const double a = m->geometry.crank, b = m->geometry.coupler, off = m->geometry.offset;
  const double th2 = m->theta0 + m->omega2 * t;
  const double c2 = cos(th2), s2 = sin(th2), c3 = cos(y[0]), s3 = sin(y[0]);
  /* eccentricity: rod pin P minus slider hole H */
  const double e[2] = {a * c2 + b * c3 - y[1], a * s2 + b * s3 - off};
  eval_core(out, m, c2, s2, c3, s3, e, y[2], y[3]);
}

void fb_sc_dyn_origin_at(fb_sc_dyn_origin *o, const fb_sc_dyn_model *m, double c2, double s2) {
  const double a = m->geometry.crank, b = m->geometry.coupler, w2 = m->omega2;
  /* fb_slider_crank_solve's position and velocity (slider_crank.h), from
   * the crank's direction: u = b sin theta3, w = b cos theta3 > 0 */
  const double u = m->geometry.offset - a * s2, w = sqrt((b - u) * (b + u));
  o->u3[0] = w / b;
  o->u3[1] = u / b;
  o->x = a * c2 + w;
  o->w3 = -a * c2 * w2 / w;
  o->v = -a * s2 * w2 - u * o->w3;
}

void fb_sc_dyn_eval_dev(fb_sc_dyn_eval *out, const fb_sc_dyn_model *m, double c2, double s2,
                        const double yd[]) {
  fb_sc_dyn_origin o;
  fb_sc_dyn_origin_at(&o, m, c2, s2);
  const double b = m->geometry.coupler;
  /* P - H = b (u(theta3) - u(theta3 ideal)) - (x - x ideal, 0): the ideal
   * loop closes, B + b u(theta3 ideal) = H ideal, so only small terms remain */
  double turn[2];
  fb_turn_change(turn, o.u3, yd[0]);
  const double e[2] = {b * turn[0] - yd[1], b * turn[1]};
  eval_core(out, m, c2, s2, o.u3[0] + turn[0], o.u3[1] + turn[1], e, yd[2], yd[3]);
  out->dydt[0] = yd[2] - o.w3;
  out->dydt[1] = yd[3] - o.v;
}

int fb_sc_dyn_rhs(double t, const double y[], double dydt[], void *params) {
  fb_sc_dyn_eval ev;
  fb_sc_dyn_eval_at(&ev, params, t, y);
  for (int i = 0; i < FB_SC_DYN_DIM; i++) dydt[i] = ev.dydt[i];
  return GSL_SUCCESS;
}

void fb_sc_dyn_energy_at(fb_sc_dyn_energy *out, const fb_sc_dyn_model *m, double t,
                         const double y[]) {
  const double a = m->geometry.crank, b = m->geometry.coupler, off = m->geometry.offset;
  const double w2 = m->omega2, th2 = m->theta0 + w2 * t;
  const double m3 = m->mass.coupler_mass, m4 = m->mass.slider_mass;
  const double f3 = m->mass.coupler_com_fraction;
  const double th3 = y[0], x = y[1], w3 = y[2], v = y[3];
  const double c3 = cos(th3), s3 = sin(th3);
  const double vG3[2] = {-a * w2 * sin(th2) - f3 * b * w3 * s3, a * w2 * cos(th2) + f3 * b * w3 * c3};
  out->kinetic = 0.5 * m3 * (vG3[0] * vG3[0] + vG3[1] * vG3[1]) +
                 0.5 * m->mass.coupler_inertia * w3 * w3 + 0.5 * m4 * v * v;
  out->gravity = m3 * m->gravity * (a * sin(th2) + f3 * b * s3);
  const double e[2] = {a * cos(th2) + b * c3 - x, a * sin(th2) + b * s3 - off};
  const double delta = hypot(e[0], e[1]) - m->clearance;
  out->elastic = 0.0;
  if (delta > 0.0) {
    const double fel = fb_contact_force(&m->law, delta, 0.0, m->impact_velocity);
    out->elastic = fel * delta / (elastic_exponent(&m->law) + 1.0);
  }
  out->total = out->kinetic + out->gravity + out->elastic;
}

fb_status fb_sc_dyn_start(double y0[FB_SC_DYN_DIM], const fb_sc_dyn_model *m,
                          const double ecc0[2], fb_diag *diag) {
  if (!(hypot(ecc0[0], ecc0[1]) <= m->clearance))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "start eccentricity (%g, %g) m: its length %g m exceeds the radial "
                       "clearance %g m (the pin would start inside the hole's wall)",
                       ecc0[0], ecc0[1], hypot(ecc0[0], ecc0[1]), m->clearance);
  /* the rod's pin P lies on the guide of an ideal slider-crank offset by ecc0_y */
  fb_slider_crank shifted = m->geometry;
  shifted.offset += ecc0[1];
  fb_slider_crank_state s;
  fb_status st = fb_slider_crank_solve(&s, &shifted, m->theta0, m->omega2, 0.0, diag);
  if (st != FB_OK) return st;
  y0[0] = s.coupler_angle;
  y0[1] = s.slider_x - ecc0[0];
  y0[2] = s.coupler_omega;
  y0[3] = s.slider_v;
  return FB_OK;
}

/* the state and the two works: y[4] = W_in, y[5] = W_damp */
static int rhs_with_work(double t, const double y[], double dydt[], void *params) {
  fb_sc_dyn_eval ev;
  fb_sc_dyn_eval_at(&ev, params, t, y);
  for (int i = 0; i < FB_SC_DYN_DIM; i++) dydt[i] = ev.dydt[i];
  dydt[4] = ev.power_in;
  dydt[5] = ev.power_damping;
  return GSL_SUCCESS;
}

static void sample_at(fb_sc_dyn_sample *s, const fb_sc_dyn_model *m, double t, const double y[]) {
  fb_sc_dyn_eval ev;
  fb_sc_dyn_eval_at(&ev, m, t, y);
  fb_sc_dyn_energy en;
  fb_sc_dyn_energy_at(&en, m, t, y);
  s->t = t;
  s->crank_angle = m->theta0 + m->omega2 * t;
  s->coupler_angle = y[0];
  s->slider_x = y[1];
  s->coupler_omega = y[2];
  s->slider_v = y[3];
  s->coupler_alpha = ev.dydt[2];
  s->slider_a = ev.dydt[3];
  s->force = ev.force;
  s->penetration = ev.penetration;
  s->ecc[0] = ev.ecc[0];
  s->ecc[1] = ev.ecc[1];
  s->guide_force = ev.guide_force;
  s->drive_torque = ev.drive_torque;
  s->energy = en.total;
  s->work_in = y[4];
  s->work_damping = y[5];
}

fb_status fb_sc_dyn_run(fb_sc_dyn_sample *out, size_t n, double h, const double y0[FB_SC_DYN_DIM],
                        const fb_sc_dyn_model *m, double tol, size_t max_steps, size_t *steps,
                        size_t *done, fb_diag *diag) {
  if (done) *done = 0;
  if (steps) *steps = 0;
  if (!(tol >= SC_DYN_TOL_MIN && tol <= SC_DYN_TOL_MAX))
    return fb_diag_set(diag, FB_ERR_RANGE, "tolerance %g: must lie in [%g, %g]", tol,
                       SC_DYN_TOL_MIN, SC_DYN_TOL_MAX);
  if (!(h > 0.0 && isfinite(h)) || n < 1)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "output step %g s and %zu samples: need a positive step and a sample", h,
                       n);
  fb_status st = fb_sc_dyn_check(m, diag);
  if (st != FB_OK) return st;
  fb_sc_dyn_model mp = *m; /* a prepared copy of the law */
  st = fb_contact_law_prepare(&mp.law, diag);
  if (st != FB_OK) return st;
  const size_t budget = max_steps ? max_steps : n * FB_SC_DYN_STEPS_PER_SAMPLE;
  double y[FB_SC_DYN_DIM + 2];
  for (int i = 0; i < FB_SC_DYN_DIM; i++) y[i] = y0[i];
  y[4] = y[5] = 0.0;
  gsl_odeiv2_system sys = {rhs_with_work, NULL, FB_SC_DYN_DIM + 2, &mp};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h * 1e-3, tol, tol);
  if (!drv) {
    gsl_set_error_handler(old);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the slider-crank integrator");
  }
  double t = 0.0;
  size_t taken = 0;
  fb_status status = FB_OK;
  for (size_t k = 0; k < n; k++) {
    const double tk = (double)k * h;
    if (k > 0) {
      gsl_odeiv2_driver_set_nmax(drv, budget > taken ? budget - taken : 1);
      const int g = gsl_odeiv2_driver_apply(drv, &t, tk, y);
      taken += (size_t)drv->n;
      if (g == GSL_EMAXITER || (g == GSL_SUCCESS && taken >= budget && k + 1 < n)) {
        status = fb_diag_set(diag, FB_ERR_NUMERIC,
                             "slider-crank dynamics stopped at t = %.9g s: step budget of %zu "
                             "accepted steps used up",
                             t, budget);
        break;
      }
      if (g != GSL_SUCCESS) {
        status = fb_diag_set(diag, FB_ERR_NUMERIC,
                             "slider-crank dynamics stopped at t = %.9g s: %s", t, gsl_strerror(g));
        break;
      }
    }
    int finite = 1;
    for (int i = 0; i < FB_SC_DYN_DIM + 2; i++) finite = finite && isfinite(y[i]);
    if (!finite) {
      status = fb_diag_set(diag, FB_ERR_NUMERIC,
                           "slider-crank dynamics stopped at t = %.9g s: the state is not finite",
                           tk);
      break;
    }
    sample_at(&out[k], &mp, tk, y);
    if (done) *done = k + 1;
  }
  if (steps) *steps = taken;
  gsl_odeiv2_driver_free(drv);
  gsl_set_error_handler(old);
  return status;
}
