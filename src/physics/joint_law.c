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

/* fills law[j] for one model from the reactions or paper rows resolved once */
static fb_status laws_of(fb_contact_law law[4], const fb_case *c, fb_clearance_model model,
                         const double fmax[4], const fb_penalty_row paper[2], fb_diag *diag) {
  const fb_clearance *cl = &c->clearance;
  fb_status st = FB_OK;
  const double e_star = fb_contact_modulus(c->youngs_modulus, c->poisson_ratio,
                                           c->youngs_modulus, c->poisson_ratio);
  for (int j = 0; j < 4; j++) {
    if (!(cl->mask & (1 << j))) continue;
    fb_contact_law l = fb_contact_law_default();
    l.kind = model == FB_CLEARANCE_IMPACT ? FB_LAW_IMPACT : FB_LAW_RESTITUTION;
    l.exponent = model == FB_CLEARANCE_IMPACT ? cl->exponent : 1.0;
    l.restitution = cl->restitution;
    l.damping = cl->damping;
    l.damping_depth = cl->damping_depth;
    l.mass = effective_mass(c, j);
    if (cl->penalty == FB_PENALTY_SOURCE_EXPLICIT) {
      l.stiffness = model == FB_CLEARANCE_IMPACT ? cl->stiffness_impact : cl->stiffness_linear;
    } else if (cl->penalty == FB_PENALTY_SOURCE_PAPER) {
      const fb_penalty_row *r = &paper[(j == FB_JOINT_A || j == FB_JOINT_B) ? 0 : 1];
      if (model == FB_CLEARANCE_IMPACT) {
        l.stiffness = r->stiffness * 1e-3 * pow(1e3, 1.5); /* N/mm read as N/mm^1.5 */
        l.exponent = 1.5;
      } else {
        l.stiffness = r->penalty * 1e3; /* P read as N/mm */
      }
    } else if (cl->penalty == FB_PENALTY_SOURCE_GOLDSMITH) {
      const double r_pin = 0.5 * c->pin_diameter;
      const double k = fb_contact_goldsmith(c->youngs_modulus, c->poisson_ratio, c->youngs_modulus,
                                            c->poisson_ratio, r_pin, r_pin + c->radial_clearance);
      if (!isfinite(k) || !(k > 0.0) || !(fmax[j] > 0.0))
        return fb_diag_set(diag, FB_ERR_RANGE,
                           "[clearance] penalty = goldsmith: no stiffness for the %s joint "
                           "(K = %g N/m^1.5 from [pin] diameter_mm = %g and radial clearance "
                           "%g um, peak reaction %g N): both must be positive",
                           fb_case_joint_name(c, j), k, c->pin_diameter * 1e3, c->radial_clearance * 1e6,
                           fmax[j]);
      if (model == FB_CLEARANCE_IMPACT) {
        l.stiffness = k;
        l.exponent = 1.5;
      } else {
        l.stiffness = 1.5 * pow(k, 2.0 / 3.0) * cbrt(fmax[j]); /* dF/d delta of K delta^1.5 */
      }
    } else {
      const double d = fb_contact_johnson_approach(fmax[j], c->pin_length, e_star,
                                                   c->radial_clearance);
      const double kt = fb_contact_johnson_stiffness(fmax[j], c->pin_length, e_star,
                                                     c->radial_clearance);
      if (!isfinite(d) || !isfinite(kt) || !(d > 0.0))
        return fb_diag_set(diag, FB_ERR_RANGE,
                           "[clearance] penalty = physical: the %s joint's peak reaction %g N "
                           "(inverse dynamics at [drive] speed_rpm = %g with the [mass] keys) is "
                           "outside Johnson's pin-in-hole relation for [pin] length_mm = %g and "
                           "radial_clearance_um = %g (or [pin] fit): use penalty = paper or "
                           "explicit, a longer pin or a smaller clearance",
                           fb_case_joint_name(c, j), fmax[j], c->crank_speed * 60.0 / (2.0 * M_PI),
                           c->pin_length * 1e3, c->radial_clearance * 1e6);
      l.stiffness = model == FB_CLEARANCE_IMPACT ? fmax[j] / pow(d, l.exponent) : kt;
    }
    l.stiffness *= cl->stiffness_scale;
    st = fb_contact_law_prepare(&l, diag); /* checked, and zeta solved once */
    if (st != FB_OK) return st;
    law[j] = l;
  }
  return FB_OK;
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
