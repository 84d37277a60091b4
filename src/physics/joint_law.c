#include "joint_law.h"

#include <math.h>
#include <string.h>

#include "mech_kinematics.h"
#include "penalty.h"

typedef enum { FB_CLEARANCE_RESTITUTION = 0, FB_CLEARANCE_IMPACT = 1 } fb_clearance_model;

/* crank angles per revolution for the largest joint reaction: 0.1 deg */
#define REACTION_SAMPLES 3600

/* masses on either side of each joint; 0 is ground */
static double effective_mass(const fb_case *c, int j) {
  const double crank = c->link[FB_CRANK].mass, coupler = c->link[FB_COUPLER].mass;
  const double follower = c->link[FB_FOLLOWER].mass;
  switch (j) {
    case FB_JOINT_A: return crank;
    case FB_JOINT_B: return crank * coupler / (crank + coupler);
    case FB_JOINT_C: return coupler * follower / (coupler + follower);
    default: return follower;
  }
}

/* the law of one clearance joint named name for one model: its working
 * force fmax (physical, goldsmith), its paper row (paper; NULL where the
 * paper's recipe does not apply), the mass its law starts from */
static fb_status law_of(fb_contact_law *out, const fb_case *c, fb_clearance_model model,
                        double fmax, const fb_penalty_row *paper, const char *name, double mass,
                        fb_diag *diag) {
  const fb_clearance *cl = &c->clearance;
  const double e_star = fb_contact_modulus(c->youngs_modulus, c->poisson_ratio,
                                           c->youngs_modulus, c->poisson_ratio);
  fb_contact_law l = fb_contact_law_default();
  l.kind = model == FB_CLEARANCE_IMPACT ? FB_LAW_IMPACT : FB_LAW_RESTITUTION;
  l.exponent = model == FB_CLEARANCE_IMPACT ? cl->exponent : 1.0;
  l.restitution = cl->restitution;
  l.damping = cl->damping;
  l.damping_depth = cl->damping_depth;
  l.mass = mass;
  if (cl->penalty == FB_PENALTY_SOURCE_EXPLICIT) {
    l.stiffness = model == FB_CLEARANCE_IMPACT ? cl->stiffness_impact : cl->stiffness_linear;
  } else if (cl->penalty == FB_PENALTY_SOURCE_PAPER) {
    if (!paper)
      return fb_diag_set(diag, FB_ERR_ARG, "[clearance] penalty = paper: the paper's recipe is "
                         "its four-bar's; the %s joint needs physical, goldsmith or explicit", name);
    if (model == FB_CLEARANCE_IMPACT) {
      l.stiffness = paper->stiffness * 1e-3 * pow(1e3, 1.5); /* N/mm read as N/mm^1.5 */
      l.exponent = 1.5;
    } else {
      l.stiffness = paper->penalty * 1e3; /* P read as N/mm */
    }
  } else if (cl->penalty == FB_PENALTY_SOURCE_GOLDSMITH) {
    const double r_pin = 0.5 * c->pin_diameter;
    const double k = fb_contact_goldsmith(c->youngs_modulus, c->poisson_ratio, c->youngs_modulus,
                                          c->poisson_ratio, r_pin, r_pin + c->radial_clearance);
    if (!isfinite(k) || !(k > 0.0) || !(fmax > 0.0))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[clearance] penalty = goldsmith: no stiffness for the %s joint "
                         "(K = %g N/m^1.5 from [pin] diameter_mm = %g and radial clearance "
                         "%g um, peak reaction %g N): both must be positive",
                         name, k, c->pin_diameter * 1e3, c->radial_clearance * 1e6, fmax);
    if (model == FB_CLEARANCE_IMPACT) {
      l.stiffness = k;
      l.exponent = 1.5;
    } else {
      l.stiffness = 1.5 * pow(k, 2.0 / 3.0) * cbrt(fmax); /* dF/d delta of K delta^1.5 */
    }
  } else {
    const double d = fb_contact_johnson_approach(fmax, c->pin_length, e_star, c->radial_clearance);
    const double kt = fb_contact_johnson_stiffness(fmax, c->pin_length, e_star,
                                                   c->radial_clearance);
    if (!isfinite(d) || !isfinite(kt) || !(d > 0.0))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[clearance] penalty = physical: the %s joint's peak reaction %g N "
                         "(inverse dynamics at [drive] speed_rpm = %g with the [mass] keys) is "
                         "outside Johnson's pin-in-hole relation for [pin] length_mm = %g and "
                         "radial_clearance_um = %g (or [pin] fit): use penalty = paper or "
                         "explicit, a longer pin or a smaller clearance",
                         name, fmax, c->crank_speed * 60.0 / (2.0 * M_PI), c->pin_length * 1e3,
                         c->radial_clearance * 1e6);
    l.stiffness = model == FB_CLEARANCE_IMPACT ? fmax / pow(d, l.exponent) : kt;
  }
  l.stiffness *= cl->stiffness_scale;
  fb_status st = fb_contact_law_prepare(&l, diag); /* checked, and zeta solved once */
  if (st == FB_OK) *out = l;
  return st;
}

/* fills law[j] for one model from the reactions or paper rows resolved once */
static fb_status laws_of(fb_contact_law law[4], const fb_case *c, fb_clearance_model model,
                         const double fmax[4], const fb_penalty_row paper[2], fb_diag *diag) {
  for (int j = 0; j < 4; j++) {
    if (!(c->clearance.mask & (1 << j))) continue;
    const fb_penalty_row *row = &paper[(j == FB_JOINT_A || j == FB_JOINT_B) ? 0 : 1];
    const fb_status st = law_of(&law[j], c, model, fmax[j], row, fb_case_joint_name(c, j),
                                effective_mass(c, j), diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

fb_status fb_joint_law_at(fb_contact_law *out, const fb_case *c, int impact, double fmax,
                          const char *name, double mass, fb_diag *diag) {
  return law_of(out, c, impact ? FB_CLEARANCE_IMPACT : FB_CLEARANCE_RESTITUTION, fmax, NULL, name,
                mass, diag);
}

fb_status fb_joint_laws(fb_contact_law impact[4], fb_contact_law restitution[4],
                        const fb_case *c, fb_diag *diag) {
  const fb_clearance *cl = &c->clearance;
  double fmax[4] = {0, 0, 0, 0};
  fb_penalty_row paper[2];
  memset(paper, 0, sizeof paper);
  fb_status st = FB_OK;
  if (cl->penalty == FB_PENALTY_SOURCE_PHYSICAL || cl->penalty == FB_PENALTY_SOURCE_GOLDSMITH) {
    fb_linkage su;
    fb_case_stackup_lengths(c, &su);
    st = fb_mech_reaction_peaks(fmax, c->mechanism, &su, c->branch, c->link, c->gravity,
                                fb_case_omega2(c), REACTION_SAMPLES, diag);
  } else if (cl->penalty == FB_PENALTY_SOURCE_PAPER) {
    st = fb_penalty_rows(paper, c, FB_PENALTY_PAPER, c->crank_speed, diag);
  }
  if (st != FB_OK) return st;
  if (impact) st = laws_of(impact, c, FB_CLEARANCE_IMPACT, fmax, paper, diag);
  if (st == FB_OK && restitution)
    st = laws_of(restitution, c, FB_CLEARANCE_RESTITUTION, fmax, paper, diag);
  return st;
}
