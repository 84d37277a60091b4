#include "resolution.h"

#include <math.h>
#include <string.h>

#include "joint_law.h"
#include "mech_kinematics.h"

/* crank angles per revolution for the largest joint reaction (joint_law.c's) */
#define REACTION_SAMPLES 3600

double fb_contact_tangent_at_force(const fb_contact_law *law, double force) {
  if (law->kind == FB_LAW_LINEAR || law->kind == FB_LAW_RESTITUTION) return law->stiffness;
  const double n = law->exponent;
  return n * pow(law->stiffness, 1.0 / n) * pow(force, (n - 1.0) / n);
}

void fb_contact_rates_at(fb_contact_rates *out, const fb_contact_law *law, double m_eff,
                         double force) {
  memset(out, 0, sizeof *out);
  const double n = law->kind == FB_LAW_LINEAR || law->kind == FB_LAW_RESTITUTION ? 1.0
                                                                                  : law->exponent;
  out->stiffness_tangent = fb_contact_tangent_at_force(law, force);
  out->omega_c = sqrt(out->stiffness_tangent / m_eff);
  out->depth = pow(force / law->stiffness, 1.0 / n);
  out->approach_speed = sqrt(2.0 * force * out->depth / ((n + 1.0) * m_eff));
  fb_contact_law on = *law; /* the restitution damper is put on the effective mass */
  on.mass = m_eff;
  out->damper_rate = fb_contact_damping_at(&on, out->depth, out->approach_speed) / m_eff;
  if (law->kind == FB_LAW_IMPACT && law->damping > 0.0)
    out->ramp_rate = out->approach_speed / law->damping_depth;
  out->rate = out->omega_c;
  out->by_damper = out->damper_rate > out->rate;
  if (out->by_damper) out->rate = out->damper_rate;
  out->limit = out->by_damper ? "damper" : "stiffness";
}

fb_status fb_contact_estimates(fb_contact_estimate est[4], const fb_case *c,
                               const fb_contact_law law[4], fb_diag *diag) {
  memset(est, 0, 4 * sizeof est[0]);
  const int mask = c->clearance.mask;
  if (!mask) return FB_OK;
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  const double omega2 = fb_case_omega2(c);
  double reaction[4];
  fb_status st = fb_mech_reaction_peaks(reaction, c->mechanism, &su, c->branch, c->link,
                                        c->gravity, omega2, REACTION_SAMPLES, diag);
  if (st != FB_OK) return st;
  for (int j = 0; j < 4; j++) {
    est[j].m_eff_min = INFINITY;
    est[j].m_eff_max = 0.0;
  }
  for (int k = 0; k < FB_RESOLUTION_SAMPLES; k++) {
    const double th = c->crank_angle0 + 2.0 * M_PI * k / FB_RESOLUTION_SAMPLES;
    fb_mechanism m;
    st = fb_mech_mechanism_at(&m, c->mechanism, &su, c->branch, c->link, th, mask, diag);
    if (st != FB_OK) return st;
    double w[4][2][2];
    st = fb_effective_mass_tensor(w, &m, diag);
    if (st != FB_OK) return st;
    for (int j = 0; j < 4; j++) {
      if (!(mask & (1 << j))) continue;
      double lo, hi;
      fb_effective_mass_range(w[j], &lo, &hi);
      est[j].m_eff_min = fmin(est[j].m_eff_min, lo);
      est[j].m_eff_max = fmax(est[j].m_eff_max, hi);
    }
  }
  for (int j = 0; j < 4; j++) {
    if (!(mask & (1 << j))) {
      memset(&est[j], 0, sizeof est[j]);
      continue;
    }
    est[j].force_expected = FB_IMPACT_LOAD_FACTOR * reaction[j];
    fb_contact_rates_at(&est[j].rates, &law[j], est[j].m_eff_min, est[j].force_expected);
    est[j].stiffness_tangent = est[j].rates.stiffness_tangent;
    est[j].omega_c = est[j].rates.omega_c;
  }
  return FB_OK;
}

fb_status fb_step_auto(double *h, double *omega_c_max, const fb_case *c, fb_diag *diag) {
  double hv = 2.0 * M_PI / (c->crank_speed * FB_H_AUTO_STEPS_PER_REV);
  double wmax = 0.0;
  if (c->clearance.mask) {
    fb_contact_law laws[2][4];
    fb_status st = fb_joint_laws(laws[0], laws[1], c, diag);
    for (int model = 0; model < 2 && st == FB_OK; model++) {
      fb_contact_estimate est[4];
      st = fb_contact_estimates(est, c, laws[model], diag);
      if (st != FB_OK) break;
      for (int j = 0; j < 4; j++)
        if (c->clearance.mask & (1 << j)) wmax = fmax(wmax, est[j].rates.rate);
    }
    if (st != FB_OK) return st;
    if (wmax > 0.0) hv = fmin(hv, FB_H_OMEGA_C_BOUND / wmax);
  }
  *h = hv;
  if (omega_c_max) *omega_c_max = wmax;
  return FB_OK;
}

fb_status fb_case_resolve_step(fb_case *c, fb_diag *diag) {
  const int automatic =
      c->solver.h_mode == FB_STEP_AUTO || (c->solver.h_mode == FB_STEP_DEFAULT && c->clearance.mask);
  if (c->solver.h_mode == FB_STEP_ADAPTIVE) {
    if (!(c->solver.h_max >= c->solver.h_min))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[solver] h_max_s = %g: the longest adaptive step must not be below "
                         "h_min_s = %g",
                         c->solver.h_max, c->solver.h_min);
    c->solver.h = c->solver.h_min; /* the output grid */
    return FB_OK;
  }
  if (!automatic) return FB_OK;
  return fb_step_auto(&c->solver.h, NULL, c, diag);
}

fb_status fb_case_contact_of(fb_case_contact *out, const fb_case *c, int j, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (j < 0 || j > 3 || !(c->clearance.mask & (1 << j))) {
    char names[128] = "";
    for (int i = 0; i < 4; i++)
      if (c->clearance.mask & (1 << i)) {
        if (names[0]) strcat(names, ", ");
        strcat(names, fb_case_joint_name(c, i));
      }
    return fb_diag_set(diag, FB_ERR_ARG,
                       "joint '%s' is not a clearance joint of this case (its [clearance] joints: "
                       "%s)", j >= 0 && j <= 3 ? fb_case_joint_name(c, j) : "?",
                       names[0] ? names : "none");
  }
  fb_contact_law imp[4], res[4];
  fb_status st = fb_joint_laws(imp, res, c, diag);
  if (st != FB_OK) return st;
  out->impact = imp[j];
  out->restitution = res[j];
  fb_contact_estimate est[4];
  st = fb_contact_estimates(est, c, res, diag);
  if (st != FB_OK) return st;
  out->est = est[j];
  fb_case step = *c;
  st = fb_case_resolve_step(&step, diag);
  if (st != FB_OK) return st;
  out->h = step.solver.h;
  return FB_OK;
}
