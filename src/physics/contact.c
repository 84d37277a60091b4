#include "contact.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <string.h>

double fb_contact_modulus(double e1, double nu1, double e2, double nu2) {
  return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
}

double fb_contact_hertz_sphere(double e_star, double r1, double r2) {
  double inv = 1.0 / r1 + 1.0 / r2;
  if (!(inv > 0.0)) return NAN;
  return 4.0 / 3.0 * e_star * sqrt(1.0 / inv);
}

double fb_contact_goldsmith(double e1, double nu1, double e2, double nu2, double r_pin,
                            double r_hole) {
  if (!(r_hole > r_pin)) return NAN;
  double s1 = (1.0 - nu1 * nu1) / e1, s2 = (1.0 - nu2 * nu2) / e2;
  return 4.0 / (3.0 * (s1 + s2)) * sqrt(r_pin * r_hole / (r_hole - r_pin));
}

double fb_contact_line_halfwidth(double force, double length, double e_star, double r_star) {
  return sqrt(4.0 * force * r_star / (M_PI * length * e_star));
}

double fb_contact_johnson_approach(double force, double length, double e_star, double dr) {
  double s = M_PI * length * e_star;
  double arg = 4.0 * s * dr / force;
  if (!(arg > M_E)) return NAN;
  return force / s * (log(arg) - 1.0);
}

double fb_contact_johnson_stiffness(double force, double length, double e_star, double dr) {
  double s = M_PI * length * e_star;
  double arg = 4.0 * s * dr / force;
  if (!(arg > M_E * M_E)) return NAN;
  return s / (log(arg) - 2.0);
}

typedef struct {
  double delta, length, e_star, dr;
} johnson_ctx;

static double johnson_residual(double f, void *p) {
  const johnson_ctx *c = p;
  return fb_contact_johnson_approach(f, c->length, c->e_star, c->dr) - c->delta;
}

fb_status fb_contact_johnson_force(double *force, double delta, double length, double e_star,
                                   double dr, fb_diag *diag) {
  /* delta(F) rises while ln(arg) > 2, i.e. up to F_top = 4 pi L E* dR / e^2 */
  const double f_top = 4.0 * M_PI * length * e_star * dr / (M_E * M_E);
  const double d_top = fb_contact_johnson_approach(f_top, length, e_star, dr);
  if (!(delta > 0.0) || !(delta < d_top))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "approach %g m: Johnson's pin-in-hole relation is monotone only for "
                       "0 < delta < %g m (F < %g N)",
                       delta, d_top, f_top);
  johnson_ctx c = {delta, length, e_star, dr};
  gsl_function F = {johnson_residual, &c};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  double lo = f_top * 1e-15, hi = f_top; /* delta(lo) ~ 0: residual < 0 */
  int st = s ? gsl_root_fsolver_set(s, &F, lo, hi) : GSL_ENOMEM;
  for (int it = 0; st == GSL_SUCCESS && it < 200; it++) {
    st = gsl_root_fsolver_iterate(s);
    lo = gsl_root_fsolver_x_lower(s);
    hi = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(lo, hi, 0.0, 1e-15) == GSL_SUCCESS) break;
  }
  double root = s ? gsl_root_fsolver_root(s) : NAN;
  if (s) gsl_root_fsolver_free(s);
  gsl_set_error_handler(old);
  if (st != GSL_SUCCESS)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "approach %g m: root solve failed (%s)", delta,
                       gsl_strerror(st));
  *force = root;
  return FB_OK;
}

/* ---- laws ------------------------------------------------------------------ */

static const char *const law_names[FB_LAW_COUNT] = {
    "hertz", "lankarani-nikravesh", "hunt-crossley", "flores", "gonthier", "linear", "impact",
    "restitution"};

const char *fb_law_name(fb_law_kind k) {
  return (k >= 0 && k < FB_LAW_COUNT) ? law_names[k] : "?";
}

fb_law_kind fb_law_parse(const char *name) {
  for (int i = 0; i < FB_LAW_COUNT; i++)
    if (strcmp(name, law_names[i]) == 0) return (fb_law_kind)i;
  return FB_LAW_COUNT;
}

fb_contact_law fb_contact_law_default(void) {
  fb_contact_law l = {FB_LAW_HERTZ, 1e10, 1.5, 0.9, 0.0, 1e-5, 1.0, 0.0, 0.0};
  return l;
}

fb_status fb_contact_law_check(const fb_contact_law *l, fb_diag *diag) {
  if (l->kind < 0 || l->kind >= FB_LAW_COUNT)
    return fb_diag_set(diag, FB_ERR_RANGE, "unknown contact law %d", (int)l->kind);
  if (!(l->stiffness > 0.0) || !isfinite(l->stiffness))
    return fb_diag_set(diag, FB_ERR_RANGE, "stiffness = %g: must be positive and finite",
                       l->stiffness);
  if (!(l->exponent >= 1.0 && l->exponent <= 3.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "exponent = %g: must lie in [1, 3]", l->exponent);
  if (!(l->restitution > 0.0 && l->restitution <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "restitution = %g: a coefficient of restitution lies in (0, 1]",
                       l->restitution);
  if (l->kind == FB_LAW_RESTITUTION && !(l->restitution > FB_RESTITUTION_MIN))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "restitution = %g: the restitution law (a spring-dashpot that cannot "
                       "pull) reaches at most critical damping, where cr = e^-2 = %.4f; "
                       "choose cr above that",
                       l->restitution, FB_RESTITUTION_MIN);
  if (!(l->damping >= 0.0) || !isfinite(l->damping))
    return fb_diag_set(diag, FB_ERR_RANGE, "damping = %g N s/m: must be >= 0", l->damping);
  if (!(l->damping_depth > 0.0) || !isfinite(l->damping_depth))
    return fb_diag_set(diag, FB_ERR_RANGE, "damping depth = %g m: must be positive",
                       l->damping_depth);
  if (!(l->mass > 0.0) || !isfinite(l->mass))
    return fb_diag_set(diag, FB_ERR_RANGE, "mass = %g kg: must be positive", l->mass);
  return FB_OK;
}

/* restitution of the clamped linear spring-dashpot with damping ratio z */
static double clamped_restitution(double z, void *p) {
  const double target = p ? *(const double *)p : 0.0;
  const double s = sqrt(1.0 - z * z);
  const double phi = M_PI - atan2(2.0 * z * s, 1.0 - 2.0 * z * z);
  return exp(-z * phi / s) * fabs(cos(phi) - z / s * sin(phi)) - target;
}

double fb_contact_restitution_zeta(double cr) {
  if (cr >= 1.0) return 0.0;
  if (!(cr > FB_RESTITUTION_MIN)) return NAN;
  double target = cr;
  gsl_function F = {clamped_restitution, &target};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  double lo = 0.0, hi = 0.999999;
  double root = NAN;
  if (s && gsl_root_fsolver_set(s, &F, lo, hi) == GSL_SUCCESS) {
    for (int it = 0; it < 200; it++) {
      if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
      lo = gsl_root_fsolver_x_lower(s);
      hi = gsl_root_fsolver_x_upper(s);
      if (gsl_root_test_interval(lo, hi, 1e-15, 0.0) == GSL_SUCCESS) break;
    }
    root = gsl_root_fsolver_root(s);
  }
  if (s) gsl_root_fsolver_free(s);
  gsl_set_error_handler(old);
  return root;
}

fb_status fb_contact_law_prepare(fb_contact_law *l, fb_diag *diag) {
  fb_status st = fb_contact_law_check(l, diag);
  if (st != FB_OK) return st;
  l->zeta = fb_contact_restitution_zeta(l->restitution);
  l->zeta_cr = l->restitution;
  return FB_OK;
}

double fb_contact_law_zeta(const fb_contact_law *l) {
  return l->zeta_cr == l->restitution && l->zeta_cr > 0.0 ? l->zeta
                                                           : fb_contact_restitution_zeta(l->restitution);
}

void fb_contact_law_scale(fb_contact_law *l, double stiffness_scale, double damping_scale,
                          int damping_given) {
  l->stiffness *= stiffness_scale;
  if (l->kind == FB_LAW_IMPACT || l->kind == FB_LAW_LINEAR) l->damping *= damping_scale;
  if (l->kind != FB_LAW_RESTITUTION || !damping_given) return;
  l->zeta = fb_contact_law_zeta(l) * damping_scale / sqrt(stiffness_scale);
  l->zeta_cr = l->restitution;
}

static double step3(double x, double x0, double h0, double x1, double h1) {
  double z = (x - x0) / (x1 - x0);
  z = z < 0.0 ? 0.0 : (z > 1.0 ? 1.0 : z);
  return h0 + (h1 - h0) * z * z * (3.0 - 2.0 * z);
}

/* hysteresis factor chi of the laws K delta^n (1 + chi ddot / v0) */
static double chi(const fb_contact_law *l) {
  const double e = l->restitution;
  switch (l->kind) {
    case FB_LAW_LANKARANI_NIKRAVESH: return 3.0 * (1.0 - e * e) / 4.0;
    case FB_LAW_HUNT_CROSSLEY: return 3.0 * (1.0 - e) / 2.0;
    case FB_LAW_FLORES: return 8.0 * (1.0 - e) / (5.0 * e);
    case FB_LAW_GONTHIER: return (1.0 - e * e) / e;
    default: return 0.0;
  }
}

/* delta^n [m^n] for delta > 0: the Hertz exponent 1.5 as delta sqrt(delta)
 * and 1 as delta, without pow; other exponents through pow. pow was 17-22 %
 * of a reference run's cycles (perf record, paper case, 8 revolutions,
 * issue 54); without it the reference alone runs 7-17 % faster (task-clock
 * 1.62-1.66 s against 1.73-2.00 s). delta sqrt(delta) is within 2 ulp of
 * pow's value: results that amplify rounding (a chaotic impact sequence)
 * move as under any other rounding change. */
static double law_power(double delta, double n) {
  if (n == 1.5) return delta * sqrt(delta);
  if (n == 1.0) return delta;
  return pow(delta, n);
}

/* elastic force, its slope (slope may be NULL: not wanted), and the
 * coefficient of ddot, at delta > 0; the slope n K delta^(n - 1) of
 * K delta^n is n fel / delta */
static void law_parts(const fb_contact_law *l, double delta, double v0, double *fel,
                      double *slope, double *cdamp) {
  double k = l->stiffness; /* the slope of the linear laws */
  switch (l->kind) {
    case FB_LAW_LINEAR:
      *fel = k * delta;
      *cdamp = l->damping;
      break;
    case FB_LAW_RESTITUTION:
      *fel = k * delta;
      *cdamp = 2.0 * fb_contact_law_zeta(l) * sqrt(l->stiffness * l->mass);
      break;
    case FB_LAW_IMPACT:
      *fel = l->stiffness * law_power(delta, l->exponent);
      *cdamp = step3(delta, 0.0, 0.0, l->damping_depth, l->damping);
      k = l->exponent * *fel / delta;
      break;
    default:
      *fel = l->stiffness * law_power(delta, l->exponent);
      *cdamp = v0 > 0.0 ? *fel * chi(l) / v0 : 0.0;
      k = l->exponent * *fel / delta;
      break;
  }
  if (slope) *slope = k;
}

double fb_contact_damping_at(const fb_contact_law *l, double delta, double v0) {
  if (!(delta > 0.0)) return 0.0;
  double fel, c;
  law_parts(l, delta, v0, &fel, NULL, &c);
  return c;
}

double fb_contact_force(const fb_contact_law *l, double delta, double ddot, double v0) {
  if (!(delta > 0.0)) return 0.0;
  double fel, c;
  law_parts(l, delta, v0, &fel, NULL, &c);
  double f = fel + c * ddot;
  return f > 0.0 ? f : 0.0;
}

/* ---- ODE mapping ------------------------------------------------------------ */

fb_status fb_contact_erp_cfm(double h, double kp, double kd, double *erp, double *cfm,
                             fb_diag *diag) {
  double d = h * kp + kd;
  if (!(d > 0.0) || !(h > 0.0) || kp < 0.0 || kd < 0.0)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "h = %g s, kp = %g N/m, kd = %g N s/m: need h > 0, kp, kd >= 0 and "
                       "h kp + kd > 0",
                       h, kp, kd);
  *erp = h * kp / d;
  *cfm = 1.0 / d;
  return FB_OK;
}

fb_status fb_contact_kp_kd(double h, double erp, double cfm, double *kp, double *kd,
                           fb_diag *diag) {
  if (!(cfm > 0.0) || !(h > 0.0) || !(erp >= 0.0 && erp <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "h = %g s, ERP = %g, CFM = %g: need h > 0, ERP in [0, 1], CFM > 0", h, erp,
                       cfm);
  *kp = erp / (h * cfm);
  *kd = (1.0 - erp) / cfm;
  return FB_OK;
}

double fb_contact_h_omega(double h, double k, double m) { return h * sqrt(k / m); }

static const char *const mapping_names[FB_MAPPING_COUNT] = {"secant", "tangent", "matched",
                                                            "matched-static"};

int fb_mapping_is_matched(fb_mapping m) {
  return m == FB_MAPPING_MATCHED || m == FB_MAPPING_MATCHED_STATIC;
}

double fb_contact_persistence(double phase) {
  const double z = (phase - FB_PERSISTENT_PHASE_RAD) / FB_PERSISTENT_RAMP_RAD;
  if (!(z > 0.0)) return 0.0;
  if (z >= 1.0) return 1.0;
  return z * z * (3.0 - 2.0 * z);
}

void fb_contact_row_mean_force(fb_contact_row *row, double h, double f_mean) {
  if (!(row->kp > 0.0) || !(row->erp > 0.0) || !(row->cfm > 0.0) || !(h > 0.0)) return;
  const double a = row->erp / (h * row->cfm);
  row->depth -= (1.0 / row->kp - 1.0 / a) * f_mean;
}

double fb_contact_mean_force_step(double f_mean, double force, double h, double omega_c) {
  if (!(omega_c > 0.0) || !(h > 0.0)) return 0.0;
  const double tau = FB_MEAN_FORCE_PERIODS * 2.0 * M_PI / omega_c;
  return f_mean + h / (tau + h) * (force - f_mean);
}

void fb_contact_row_static(fb_contact_row *row, double h, double m, double w) {
  if (!(w > 0.0)) return;
  if (w > 1.0) w = 1.0;
  const double a_m = row->erp / (h * row->cfm), b_m = 1.0 / row->cfm; /* the matched row */
  const double k = row->kp, sigma = 0.5 * row->kd / m, disc = sigma * sigma - k / m;
  const double w2h2 = k * h * h / m; /* (h omega)^2 */
  /* log of the modulus of the law's slowest pole, times h */
  const double lr = disc < 0.0 ? -sigma * h : -(k / m) / (sigma + sqrt(disc)) * h;
  double det = exp(2.0 * lr);
  double one_minus = -expm1(2.0 * lr); /* 1 - det without cancellation */
  const double tr = 1.0 + det * (1.0 - w2h2);
  const double r = exp(lr), omr = -expm1(lr), x = sqrt(w2h2);
  if (omr > x * r) {
    /* r < 1 / (1 + h omega): faster than a row with a = k can decay; the
     * double root 1 / (1 + h omega) is the fastest it can */
    det = 1.0 / ((1.0 + x) * (1.0 + x));
    one_minus = x * (2.0 + x) * det;
  } else if (tr * tr >= 4.0 * det) { /* real roots: the larger one is r */
    det = r * omr / (omr + w2h2 * r);
    one_minus = (omr * omr + w2h2 * r) / (omr + w2h2 * r);
  }
  double b = det > 0.0 ? m * one_minus / (det * h) : INFINITY;
  if (!(b > FB_MATCHED_B_MIN_REL * m / h)) b = FB_MATCHED_B_MIN_REL * m / h;
  /* blend a and b from the matched row to the static one */
  const double a_w = a_m + w * (k - a_m), b_w = b_m + w * (b - b_m);
  row->cfm = 1.0 / b_w;
  row->erp = h * a_w / b_w;
}

const char *fb_mapping_name(fb_mapping m) {
  return (m >= 0 && m < FB_MAPPING_COUNT) ? mapping_names[m] : "?";
}

fb_mapping fb_mapping_parse(const char *name) {
  for (int i = 0; i < FB_MAPPING_COUNT; i++)
    if (strcmp(name, mapping_names[i]) == 0) return (fb_mapping)i;
  return FB_MAPPING_COUNT;
}

/* (1 - e^{s1 h})(1 - e^{s2 h}) for the poles s of m s^2 + c s + k = 0,
 * without cancellation at small h: |expm1(s h)|^2 for a complex pair, the
 * product of two expm1 for real poles (the smaller root from k / (m s_big)
 * so k -> 0 keeps its digits). */
double fb_contact_pole_gap(double h, double k, double c, double m) {
  const double sigma = -0.5 * c / m;            /* real part of both poles [1/s] */
  const double disc = sigma * sigma - k / m;    /* (s - sigma)^2 [1/s^2] */
  if (disc < 0.0) {
    const double wd = sqrt(-disc) * h;
    const double em = expm1(sigma * h);
    const double s2 = sin(0.5 * wd);
    const double re = em * cos(wd) - 2.0 * s2 * s2; /* e^{sigma h} cos(wd h) - 1 */
    const double im = exp(sigma * h) * sin(wd);
    return re * re + im * im;
  }
  const double big = sigma - sqrt(disc);              /* the more negative root */
  const double small = big != 0.0 ? (k / m) / big : 0.0; /* s1 s2 = k / m */
  return expm1(big * h) * expm1(small * h);
}

double fb_contact_omega_d_h(double h, double k, double c, double m) {
  const double sigma = 0.5 * c / m;
  const double wd2 = k / m - sigma * sigma;
  return wd2 > 0.0 ? h * sqrt(wd2) : 0.0;
}

fb_status fb_contact_matched(double h, double k, double c, double m, double *erp, double *cfm,
                             fb_diag *diag) {
  if (!(h > 0.0) || !(m > 0.0) || !isfinite(h) || !isfinite(m) || !(k >= 0.0) || !(c >= 0.0) ||
      !isfinite(k) || !isfinite(c))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "h = %g s, k = %g N/m, c = %g N s/m, m = %g kg: need h, m > 0 and "
                       "k, c >= 0, all finite",
                       h, k, c, m);
  if (k == 0.0 && c == 0.0)
    return fb_diag_set(diag, FB_ERR_RANGE, "k = c = 0: no contact force, no row (0/0)");
  const double x = c * h / m;
  const double gap = fb_contact_pole_gap(h, k, c, m);
  if (expm1(x) > FB_MATCHED_B_MIN_REL) {
    /* ERP = h a / b = gap / (1 - beta), CFM = 1 / b = h / (m (e^x - 1)): no
     * overflow when c h / m is large (a rigid, fully inelastic row) */
    *erp = gap / -expm1(-x);
    *cfm = h / (m * expm1(x));
  } else {
    const double b = FB_MATCHED_B_MIN_REL * m / h;
    *erp = h * (m * gap / (exp(-x) * h * h)) / b;
    *cfm = 1.0 / b;
  }
  return FB_OK;
}

fb_status fb_contact_matched_inverse(double h, double m, double erp, double cfm, double *k,
                                     double *c, fb_diag *diag) {
  if (!(cfm > 0.0) || !(erp >= 0.0) || !(h > 0.0) || !(m > 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "h = %g s, m = %g kg, ERP = %g, CFM = %g: need h, m, CFM > 0, ERP >= 0",
                       h, m, erp, cfm);
  const double b = 1.0 / cfm, a = erp * b / h;
  const double beta = m / (m + h * b);       /* det of the update */
  const double tr = 1.0 + beta - a * beta * h * h / m;
  const double sigma = 0.5 * log(beta) / h;  /* real part of the poles */
  const double q = tr / (2.0 * sqrt(beta));  /* cos or cosh of the pole spread times h */
  double spread2;                            /* (s - sigma)^2 [1/s^2] */
  if (q >= -1.0 && q <= 1.0) {
    const double wd = acos(q) / h;
    spread2 = -wd * wd;
  } else if (q > 1.0) {
    const double g = acosh(q) / h;
    spread2 = g * g;
  } else {
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "ERP = %g, CFM = %g: the row's update has a negative real pole; no "
                       "continuous spring-damper maps to it",
                       erp, cfm);
  }
  *c = -2.0 * m * sigma;
  *k = m * (sigma * sigma - spread2);
  return FB_OK;
}

/* delta(t) = u (e^{s1 t} - e^{s2 t}) / (s1 - s2) of m d'' + c d' + k d = 0
 * from d(0) = 0, d'(0) = u */
static double linear_from_zero(double t, double k, double c, double m, double u) {
  const double sigma = -0.5 * c / m, disc = sigma * sigma - k / m;
  if (disc < 0.0) {
    const double wd = sqrt(-disc);
    return u * exp(sigma * t) * sin(wd * t) / wd;
  }
  if (disc == 0.0) return u * t * exp(sigma * t);
  const double g = sqrt(disc);
  return u * exp(sigma * t) * sinh(g * t) / g;
}

double fb_contact_matched_onset_depth(double h, double k, double c, double m, double d_n,
                                      double u_n, double erp, double cfm) {
  const double b = 1.0 / cfm, a = erp * b / h;
  if (!(u_n > 0.0) || !(a > 0.0) || !(d_n > 0.0)) return d_n;
  /* the time tau after the crossing at which the exact motion has depth d_n
   * (Newton from d_n / u_n: the unbraked depth runs a little ahead) */
  double tau = fmin(d_n / u_n, h);
  for (int it = 0; it < 8; it++) {
    const double f = linear_from_zero(tau, k, c, m, u_n) - d_n;
    const double dt = 1e-6 * tau;
    const double df = (linear_from_zero(tau + dt, k, c, m, u_n) - linear_from_zero(tau - dt, k, c, m, u_n)) / (2.0 * dt);
    if (!(df > 0.0)) break;
    tau -= f / df;
    if (!(tau > 0.0)) return d_n;
  }
  const double target = linear_from_zero(tau + h, k, c, m, u_n);
  const double u_next = (target - d_n) / h;
  return (m * u_n - (m + h * b) * u_next) / (h * a);
}

fb_status fb_contact_map(fb_contact_row *row, const fb_contact_law *law, fb_mapping mapping,
                         double h, double m_eff, int n_rows, double delta, double ddot, double v0,
                         fb_diag *diag) {
  const double n = n_rows > 0 ? (double)n_rows : 1.0;
  const fb_mapping lin = fb_mapping_is_matched(mapping) ? FB_MAPPING_TANGENT : mapping;
  row->step_share = 1.0;
  fb_contact_linearize(law, lin, delta, ddot, v0, &row->kp, &row->kd, &row->depth);
  row->kp /= n;
  row->kd /= n;
  if (fb_mapping_is_matched(mapping))
    return fb_contact_matched(h, row->kp, row->kd, m_eff / n, &row->erp, &row->cfm, diag);
  return fb_contact_erp_cfm(h, row->kp, row->kd, &row->erp, &row->cfm, diag);
}

void fb_contact_linearize(const fb_contact_law *l, fb_mapping mapping, double delta,
                          double ddot, double v0, double *kp, double *kd, double *depth) {
  (void)ddot;
  double fel, slope, c;
  if (!(delta > 0.0)) {
    *kp = 0.0;
    *kd = 0.0;
    *depth = 0.0;
    return;
  }
  law_parts(l, delta, v0, &fel, &slope, &c);
  *kd = c;
  if (mapping == FB_MAPPING_TANGENT && slope > 0.0) {
    *kp = slope;
    *depth = fel / slope;
  } else {
    *kp = fel / delta;
    *depth = delta;
  }
}

void fb_contact_row_onset(fb_contact_row *row, const fb_contact_law *law, fb_mapping mapping,
                          double h, double m_eff, double delta, double ddot) {
  if (!fb_mapping_is_matched(mapping) ||
      !(law->kind == FB_LAW_LINEAR || law->kind == FB_LAW_RESTITUTION))
    return;
  row->depth = fb_contact_matched_onset_depth(h, row->kp, row->kd, m_eff, delta, ddot, row->erp,
                                              row->cfm);
  if (ddot > 0.0) row->step_share = h / (h + fmin(delta / ddot, h));
}

double fb_contact_step_drift(const double n[2], const double dp[2], const double dq[2],
                             const double ev[2], double ecc, double h) {
  const double en = ev[0] * n[0] + ev[1] * n[1];
  const double et[2] = {ev[0] - en * n[0], ev[1] - en * n[1]};
  return n[0] * (dp[0] - dq[0]) + n[1] * (dp[1] - dq[1]) +
         h * h * (et[0] * et[0] + et[1] * et[1]) / (2.0 * ecc);
}

fb_status fb_contact_row_step(fb_contact_row *row, const fb_contact_law *law, fb_mapping mapping,
                              double h, double m_eff, int n_rows, double delta, double ddot,
                              double v0, int onset, double persistence) {
  fb_status st = fb_contact_map(row, law, mapping, h, m_eff, n_rows, delta, ddot, v0, NULL);
  if (st != FB_OK) return st;
  if (persistence > 0.0 && mapping == FB_MAPPING_MATCHED_STATIC)
    fb_contact_row_static(row, h, m_eff / (n_rows > 0 ? n_rows : 1), persistence);
  else if (onset && n_rows == 1)
    fb_contact_row_onset(row, law, mapping, h, m_eff, delta, ddot);
  return FB_OK;
}
