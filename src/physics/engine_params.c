/* Contact parameters for the engines users run (see engine_params.h). */
#include "engine_params.h"

#include <math.h>

#include "contact.h"

fb_status fb_linear_contact_check(const fb_linear_contact *lc, fb_diag *diag) {
  if (!(lc->k > 0.0) || !isfinite(lc->k))
    return fb_diag_set(diag, FB_ERR_RANGE, "stiffness %g N/m: must be positive and finite", lc->k);
  if (!(lc->c >= 0.0) || !isfinite(lc->c))
    return fb_diag_set(diag, FB_ERR_RANGE, "damping %g N s/m: must be >= 0 and finite", lc->c);
  if (!(lc->m > 0.0) || !isfinite(lc->m))
    return fb_diag_set(diag, FB_ERR_RANGE, "effective mass %g kg: must be positive and finite",
                       lc->m);
  if (!(lc->h > 0.0) || !isfinite(lc->h))
    return fb_diag_set(diag, FB_ERR_RANGE, "step size h = %g s: must be positive and finite",
                       lc->h);
  return FB_OK;
}

double fb_params_damper_for_restitution(double k, double m, double cr) {
  return 2.0 * fb_contact_restitution_zeta(cr) * sqrt(k * m);
}

double fb_params_peak_factor(double zeta) {
  if (!(zeta >= 0.0 && zeta < 1.0)) return NAN;
  const double s = sqrt(1.0 - zeta * zeta);
  return exp(-zeta / s * atan2(s, zeta));
}

fb_status fb_params_linear_equivalent(double cr, double delta, double m, double v, double *k,
                                      double *c, fb_diag *diag) {
  *k = *c = NAN;
  if (!(cr > FB_RESTITUTION_MIN && cr <= 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "restitution %g: a linear spring-damper reaches only "
                       "(%.4g, 1]", cr, FB_RESTITUTION_MIN);
  if (!(delta > 0.0) || !isfinite(delta) || !(m > 0.0) || !isfinite(m) || !(v > 0.0) ||
      !isfinite(v))
    return fb_diag_set(diag, FB_ERR_RANGE, "penetration %g m, mass %g kg, speed %g m/s: must be "
                       "positive and finite", delta, m, v);
  const double zeta = fb_contact_restitution_zeta(cr);
  const double omega = fb_params_peak_factor(zeta) * v / delta;
  *k = m * omega * omega;
  *c = 2.0 * zeta * sqrt(*k * m);
  return FB_OK;
}

fb_status fb_params_ode_matched(const fb_linear_contact *lc, fb_ode_row *out, fb_diag *diag) {
  fb_status st = fb_linear_contact_check(lc, diag);
  if (st != FB_OK) return st;
  return fb_contact_matched(lc->h, lc->k, lc->c, lc->m, &out->erp, &out->cfm, diag);
}

fb_status fb_params_ode_standard(const fb_linear_contact *lc, fb_ode_row *out, fb_diag *diag) {
  fb_status st = fb_linear_contact_check(lc, diag);
  if (st != FB_OK) return st;
  return fb_contact_erp_cfm(lc->h, lc->k, lc->c, &out->erp, &out->cfm, diag);
}

double fb_params_correcting_velocity(const fb_ode_row *row, double h, double depth) {
  return row->erp * depth / h;
}

void fb_params_spring_damper_of_row(const fb_ode_row *row, double h, fb_spring_damper *out) {
  out->kp = row->erp / (h * row->cfm);
  out->kd = (1.0 - row->erp) / row->cfm;
}

fb_status fb_params_row_of_spring_damper(const fb_spring_damper *sd, double h, fb_ode_row *out,
                                         fb_diag *diag) {
  const double den = h * sd->kp + sd->kd;
  if (!(den > 0.0) || !isfinite(den))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "kp = %g N/m, kd = %g N s/m at h = %g s: h kp + kd must be positive",
                       sd->kp, sd->kd, h);
  out->erp = h * sd->kp / den;
  out->cfm = 1.0 / den;
  return FB_OK;
}

static void mujoco_fill(fb_mujoco_params *out, double kappa, double beta) {
  const double d = FB_MUJOCO_IMPEDANCE;
  out->kappa = kappa;
  out->beta = beta;
  /* d K = kappa with K = s0 / d^2: s0 = d kappa; d B = beta with B = s1 / d: s1 = beta */
  out->solref[0] = -d * kappa;
  out->solref[1] = -beta;
  out->solimp[0] = d;
  out->solimp[1] = d;
  out->solimp[2] = 0.001;
  out->solimp[3] = 0.5;
  out->solimp[4] = 2.0;
}

void fb_params_mujoco_direct_matched(const fb_linear_contact *lc, fb_mujoco_params *out) {
  const double x = lc->c * lc->h / lc->m;
  const double beta = -expm1(-x) / lc->h;
  const double kappa = fb_contact_pole_gap(lc->h, lc->k, lc->c, lc->m) / (lc->h * lc->h);
  mujoco_fill(out, kappa, beta);
}

void fb_params_mujoco_direct_continuous(const fb_linear_contact *lc, fb_mujoco_params *out) {
  mujoco_fill(out, lc->k / lc->m, lc->c / lc->m);
}

fb_status fb_params_mujoco_standard(const fb_linear_contact *lc, fb_mujoco_params *out,
                                    fb_diag *diag) {
  fb_params_mujoco_direct_matched(lc, out);
  if (!(out->beta > 0.0))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "MuJoCo standard form: the contact has no damper (c = 0), which "
                       "(timeconst, dampratio) cannot express; use the direct form");
  const double d = FB_MUJOCO_IMPEDANCE;
  const double tc = 2.0 / out->beta;
  if (tc < 2.0 * lc->h)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "MuJoCo standard form: timeconst 2 / (c/m) = %.3g s is below 2 h = %.3g "
                       "s, and MuJoCo 2.2 raises it to 2 h (less damping than asked); use the "
                       "direct form, or a step h <= %.3g s",
                       tc, 2.0 * lc->h, 0.5 * tc);
  out->solref[0] = tc;
  out->solref[1] = 1.0 / (tc * sqrt(d * out->kappa));
  return FB_OK;
}
