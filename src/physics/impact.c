#include "clock.h"
#include "impact.h"
#include "units.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_sf_gamma.h>
#include <math.h>
#include <string.h>

static int is_linear(fb_law_kind k) { return k == FB_LAW_LINEAR || k == FB_LAW_RESTITUTION; }

const fb_impact_names fb_impact_flag_names = {"--stiffness", "--restitution", "--damping-n-s-m",
                                               "--mass-kg", "--speed-m-s", "--h-s"};

/* the word naming input w (a flag, a key) or the plain word */
#define NAME(w, plain) (d->names && d->names->w ? d->names->w : (plain))

/* the law's own rules, each naming its input */
static fb_status law_check(const fb_impact_def *d, fb_diag *diag) {
  const fb_contact_law *l = &d->law;
  if (!(l->stiffness > 0.0) || !isfinite(l->stiffness))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the stiffness must be positive and finite",
                       NAME(stiffness, "stiffness ="), l->stiffness);
  if (!(l->restitution > 0.0 && l->restitution <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: a coefficient of restitution lies in (0, 1]",
                       NAME(restitution, "restitution ="), l->restitution);
  if ((l->kind == FB_LAW_FLORES || l->kind == FB_LAW_GONTHIER) &&
      l->restitution < FB_IMPACT_CR_MIN_DIVERGENT)
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g with the %s law: its damping factor (%s) grows "
                       "as 1 / cr, and below cr = %g the impact no longer ends within the 100 "
                       "contact durations it is followed for: give %s >= %g", NAME(restitution,
                       "restitution ="), l->restitution, fb_law_name(l->kind),
                       l->kind == FB_LAW_FLORES ? "8 (1 - cr) / (5 cr)" : "(1 - cr^2) / cr",
                       FB_IMPACT_CR_MIN_DIVERGENT, NAME(restitution, "cr"),
                       FB_IMPACT_CR_MIN_DIVERGENT);
  if (!(l->damping >= 0.0) || !isfinite(l->damping))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the damping must be >= 0 and finite (N s/m)",
                       NAME(damping, "damping ="), l->damping);
  if ((l->kind == FB_LAW_LINEAR || l->kind == FB_LAW_IMPACT) && l->damping > 0.0) {
    /* the damper against the spring it acts with: the linear law's k, the
     * IMPACT law's tangent stiffness n K d^(n-1) at d_max, where c_max acts */
    const double k = l->kind == FB_LAW_LINEAR
                         ? l->stiffness
                         : l->exponent * l->stiffness * pow(l->damping_depth, l->exponent - 1.0);
    const double c_max = FB_IMPACT_DAMPING_RATIO_MAX * 2.0 * sqrt(k * d->mass);
    if (l->damping > c_max)
      return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the damping ratio c / (2 sqrt(k m)) = %.3g "
                         "(k = %.4g N/m, m = %g kg) passes %g: the damper would stop the body "
                         "within m / c = %.3g s, under a thousandth of the spring's 1 / omega_c, "
                         "where no step follows the contact: give %s <= %.4g N s/m",
                         NAME(damping, "damping ="), l->damping,
                         l->damping / (2.0 * sqrt(k * d->mass)), k, d->mass,
                         FB_IMPACT_DAMPING_RATIO_MAX, d->mass / l->damping, NAME(damping, "c"),
                         c_max);
  }
  return FB_OK;
}

fb_status fb_impact_check(const fb_impact_def *d, fb_diag *diag) {
  if (!(d->mass >= FB_MASS_MIN_KG && d->mass <= FB_MASS_MAX_KG))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the mass must be positive, from %g kg to %g kg",
                       NAME(mass, "mass ="), d->mass, FB_MASS_MIN_KG, FB_MASS_MAX_KG);
  fb_status st = law_check(d, diag);
  if (st == FB_OK) st = fb_contact_law_check(&d->law, diag); /* the rest, unnamed */
  if (st != FB_OK) return st;
  if (!(d->speed > 0.0) || !isfinite(d->speed))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the impact speed must be positive (m/s)",
                       NAME(speed, "speed ="), d->speed);
  if (!(d->speed <= FB_IMPACT_SPEED_MAX_M_S))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the impact speed must be at most %g m/s "
                       "(an elastic contact law does not hold beyond)", NAME(speed, "speed ="),
                       d->speed, FB_IMPACT_SPEED_MAX_M_S);
  if (!(d->h > 0.0) || !isfinite(d->h))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the step size must be positive (s)",
                       NAME(h, "h ="), d->h);
  /* the contact the inputs make must be one a double can follow: a duration
   * and penetration that are finite and not vanishingly small */
  const double T = fb_impact_duration_estimate(d);
  if (!(T >= FB_IMPACT_DURATION_MIN_S && T <= FB_IMPACT_DURATION_MAX_S))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g, %s %g kg, %s %g m/s give a contact lasting %g "
                       "s, outside %g s to %g s: the contact law cannot be integrated there; bring "
                       "stiffness, mass or speed nearer to a mechanism's",
                       NAME(stiffness, "stiffness ="), d->law.stiffness, NAME(mass, "mass ="),
                       d->mass, NAME(speed, "speed ="), d->speed, T, FB_IMPACT_DURATION_MIN_S,
                       FB_IMPACT_DURATION_MAX_S);
  /* the ODE impact runs for up to about the contact duration in steps of h */
  if (T / d->h > FB_IMPACT_MAX_STEPS)
    return fb_diag_set(diag, FB_ERR_RANGE, "%s %g: the contact lasts about %.3g s, so the impact "
                       "would take about %.3g steps of h, more than %.0e: give %s >= %.2g s",
                       NAME(h, "h ="), d->h, T, T / d->h, FB_IMPACT_MAX_STEPS, NAME(h, "h"),
                       T / FB_IMPACT_MAX_STEPS);
  if (d->quick_iterations < 1)
    return fb_diag_set(diag, FB_ERR_RANGE, "quick iterations = %d: must be >= 1",
                       d->quick_iterations);
  return FB_OK;
}
#undef NAME

/* undamped power law: delta_max and duration */
static void power_law_undamped(double k, double n, double m, double v0, double *dmax,
                               double *t) {
  *dmax = pow((n + 1.0) * m * v0 * v0 / (2.0 * k), 1.0 / (n + 1.0));
  double q = 1.0 / (n + 1.0);
  *t = 2.0 * *dmax / v0 * sqrt(M_PI) * gsl_sf_gamma(1.0 + q) / gsl_sf_gamma(0.5 + q);
}

double fb_impact_duration_estimate(const fb_impact_def *d) {
  double n = is_linear(d->law.kind) ? 1.0 : d->law.exponent;
  double dmax, t;
  power_law_undamped(d->law.stiffness, n, d->mass, d->speed, &dmax, &t);
  return t;
}

int fb_impact_closed_form(fb_impact_result *out, const fb_impact_def *d) {
  memset(out, 0, sizeof *out);
  const fb_contact_law *l = &d->law;
  const double m = d->mass, v0 = d->speed;
  if (l->kind == FB_LAW_HERTZ || (l->kind == FB_LAW_IMPACT && l->damping == 0.0) ||
      (l->kind == FB_LAW_LINEAR && l->damping == 0.0)) {
    double n = l->kind == FB_LAW_LINEAR ? 1.0 : l->exponent;
    power_law_undamped(l->stiffness, n, m, v0, &out->penetration_max, &out->contact_duration);
    out->force_max = l->stiffness * pow(out->penetration_max, n);
    out->restitution = 1.0;
    return 1;
  }
  if (!is_linear(l->kind)) return 0;
  /* damped oscillator delta = (v0/wd) e^{-a t} sin(wd t), a = zeta wn */
  const double k = l->stiffness;
  const double c = l->kind == FB_LAW_LINEAR
                       ? l->damping
                       : 2.0 * fb_contact_law_zeta(l) * sqrt(k * m);
  const double wn = sqrt(k / m), z = c / (2.0 * sqrt(k * m));
  if (!(z < 1.0)) return 0;
  const double s = sqrt(1.0 - z * z), wd = wn * s, a = z * wn;
  /* derivatives: delta^(j) = (v0/wd) wn^j e^{-a t} sin(wd t + j psi) */
  const double psi = atan2(wd, -a);
  const double amp = v0 / wd;
  const double t_sep = (M_PI - atan2(2.0 * z * s, 1.0 - 2.0 * z * z)) / wd;
  const double t_max = (M_PI - psi) / wd; /* first zero of delta' */
  out->penetration_max = amp * exp(-a * t_max) * sin(wd * t_max);
  out->contact_duration = t_sep;
  out->restitution = amp * wn * exp(-a * t_sep) * fabs(sin(wd * t_sep + psi)) / v0;
  /* force -m delta'' is extreme where delta''' = 0: wd t = j pi - 3 psi */
  double fmax = c * v0; /* t = 0 */
  for (int j = -3; j <= 6; j++) {
    double t = (j * M_PI - 3.0 * psi) / wd;
    if (t <= 0.0 || t >= t_sep) continue;
    double f = -m * amp * wn * wn * exp(-a * t) * sin(wd * t + 2.0 * psi);
    if (f > fmax) fmax = f;
  }
  out->force_max = fmax;
  return 1;
}

/* ---- reference integration ---------------------------------------------------- */

typedef struct {
  const fb_contact_law *law;
  double m, v0;
} ref_ctx;

static int rhs(double t, const double y[], double dydt[], void *p) {
  (void)t;
  const ref_ctx *c = p;
  dydt[0] = y[1];
  dydt[1] = -fb_contact_force(c->law, y[0], y[1], c->v0) / c->m;
  return GSL_SUCCESS;
}

/* parabola through (x-1, x0, x+1) at equal spacing: vertex value */
static double vertex(double ym, double y0, double yp) {
  double den = ym - 2.0 * y0 + yp;
  if (den >= 0.0) return y0;
  return y0 - 0.125 * (yp - ym) * (yp - ym) / den;
}

static int integrate_to(gsl_odeiv2_driver *drv, double *t, double t1, double y[2]) {
  return gsl_odeiv2_driver_apply(drv, t, t1, y);
}

fb_status fb_impact_reference(fb_impact_result *out, const fb_impact_def *d, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  double t_wall = fb_clock_s();
  fb_contact_law law = d->law;
  law.mass = d->mass;
  fb_contact_law_prepare(&law, NULL); /* zeta solved once, not on every step */
  ref_ctx c = {&law, d->mass, d->speed};
  const double T = fb_impact_duration_estimate(d);
  const double dt = T / 4000.0;
  gsl_odeiv2_system sys = {rhs, NULL, 2, &c};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, dt * 1e-3, 1e-14 * d->speed * T, 1e-12);
  if (!drv) {
    gsl_set_error_handler(old);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the reference integrator");
  }
  double t = 0.0, y[2] = {0.0, d->speed};
  double prev_d[2] = {0, 0}, prev_f[2] = {0, 0}; /* two samples back, one back */
  double dmax = 0.0, fmax = 0.0;
  fb_status st = FB_OK;
  size_t k = 0;
  for (;; k++) {
    double ys[2] = {y[0], y[1]}, ts = t;
    int rc = integrate_to(drv, &t, ts + dt, y);
    if (rc != GSL_SUCCESS) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "reference integration failed at t = %g s: %s", t,
                       gsl_strerror(rc));
      break;
    }
    double f = fb_contact_force(&law, y[0], y[1], d->speed);
    /* peaks: parabola through the three samples around a local maximum */
    if (k >= 1 && prev_d[1] >= prev_d[0] && prev_d[1] > y[0] && prev_d[1] >= dmax)
      dmax = vertex(prev_d[0], prev_d[1], y[0]);
    if (k >= 1 && prev_f[1] >= prev_f[0] && prev_f[1] > f && prev_f[1] >= fmax)
      fmax = vertex(prev_f[0], prev_f[1], f);
    if (y[0] > dmax && y[1] > 0) dmax = y[0];
    if (f > fmax) fmax = f;
    if (f <= 0.0 && k > 0) {
      /* contact ended in (ts, t]: bisect on the force from the saved state */
      double lo = ts, hi = t, ylo[2] = {ys[0], ys[1]};
      while (hi - lo > 1e-13 * T) {
        double mid = 0.5 * (lo + hi), tm = lo, ym[2] = {ylo[0], ylo[1]};
        gsl_odeiv2_driver_reset(drv);
        if (integrate_to(drv, &tm, mid, ym) != GSL_SUCCESS) break;
        if (fb_contact_force(&law, ym[0], ym[1], d->speed) > 0.0) {
          lo = mid;
          ylo[0] = ym[0];
          ylo[1] = ym[1];
        } else {
          hi = mid;
        }
      }
      out->contact_duration = 0.5 * (lo + hi);
      out->restitution = fabs(ylo[1]) / d->speed;
      break;
    }
    prev_d[0] = prev_d[1];
    prev_d[1] = y[0];
    prev_f[0] = prev_f[1];
    prev_f[1] = f;
    if (t > 100.0 * T) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC,
                       "reference: the body has not left the contact after %g s", t);
      break;
    }
  }
  gsl_odeiv2_driver_free(drv);
  gsl_set_error_handler(old);
  out->penetration_max = dmax;
  out->force_max = fmax;
  out->steps = k;
  out->wall_s = fb_clock_s() - t_wall;
  return st;
}

void fb_impact_tally_force(fb_impact_tally *t, fb_impact_result *out, double t1, double h,
                           double depth, double force, double v_out) {
  if (depth > out->penetration_max) out->penetration_max = depth;
  if (force > out->force_max) out->force_max = force;
  if (force > 0.0) {
    t->in_contact = 1;
    t->t_end = t1;
    /* the body leaves during this step: end where the depth crosses zero */
    if (depth <= 0.0 && t->prev_depth > 0.0)
      t->t_end = t1 - h + h * t->prev_depth / (t->prev_depth - depth);
  } else if (t->in_contact && v_out > 0.0) {
    t->done = 1; /* force gone and moving out: free flight from here */
  }
  t->prev_depth = depth;
  if (t->in_contact && depth <= 0.0 && v_out > 0.0) t->done = 1;
}

void fb_impact_tally_depth(fb_impact_tally *t, fb_impact_result *out, double t1, double h,
                           double depth, double force) {
  if (depth > out->penetration_max) out->penetration_max = depth;
  if (force > out->force_max) out->force_max = force;
  if (depth > 0.0) t->in_contact = 1;
  if (t->in_contact && depth < 0.0) {
    t->t_end = t1 - h + h * t->prev_depth / (t->prev_depth - depth);
    t->done = 1;
  }
  t->prev_depth = depth;
}
