#include "penalty.h"

#include <math.h>

#include "analytic.h"
#include "contact.h"
#include "closed_form.h"
#include "mech_kinematics.h"

/* the recipe's constants (docs/paper.md), in its own units: N, mm */
#define PAPER_K_KG_M 8.783456e-5   /* F / max|alpha| [kg m] */
#define PAPER_C_MM 0.042           /* stated maximum clearance [mm] */
#define PAPER_R_MM (20.0 / 3.0)    /* contact radius of Table III [mm] */
#define PAPER_UNROUNDED_RPM 100.0  /* the one speed whose force is not rounded */
#define PAPER_ROUNDED_JOINT 1      /* the pin joint whose force is rounded (coupler-follower) */

/* samples per revolution for the physical joint reaction peak: 0.1 deg */
#define PHYSICAL_SAMPLES 3600

int fb_penalty_joint(const fb_mech_desc *m, fb_pin_joint j) {
  for (int i = 0, k = 0; i < m->njoints; i++) {
    const int *b = m->joint[i].body;
    const int grounded = m->body[b[0]].motion == FB_MOTION_FIXED ||
                         m->body[b[1]].motion == FB_MOTION_FIXED;
    if (grounded) continue;
    if (k++ == j) return i;
  }
  return -1;
}

const char *fb_pin_joint_name(fb_pin_joint j) {
  return fb_mech_joint_name(&fb_mech_fourbar, fb_penalty_joint(&fb_mech_fourbar, j));
}

const char *fb_penalty_paper_refusal(const fb_case *c) {
  return fb_closed_form_of(c->mechanism)->paper_refusal;
}

static fb_status paper_rows(fb_penalty_row out[FB_PENALTY_PIN_JOINTS], const fb_case *c,
                            double omega, fb_diag *diag) {
  fb_peaks p;
  fb_status st = fb_analytic_peaks(&p, &c->nominal, c->branch, omega, diag);
  if (st != FB_OK) return st;
  const double e_star_nmm2 = c->youngs_modulus * 1e-6 /
                             (2.0 * (1.0 - c->poisson_ratio * c->poisson_ratio));
  const double rpm = omega * 60.0 / (2.0 * M_PI);
  /* pin joint j's force from output body j's alpha (Table I: the coupler's
   * for crank-coupler, the follower's for coupler-follower) */
  for (int j = 0; j < FB_PENALTY_PIN_JOINTS; j++) {
    const double alpha = fmax(fabs(p.body[j].alpha_max), fabs(p.body[j].alpha_min));
    double f = PAPER_K_KG_M * alpha;
    double f_used = f;
    if (j == PAPER_ROUNDED_JOINT && fabs(rpm - PAPER_UNROUNDED_RPM) > 1e-9)
      f_used = round(f * 100.0) / 100.0;
    const double a_mm = sqrt(f_used / (100.0 * PAPER_C_MM));
    const double kc_nmm = 2.0 * a_mm * e_star_nmm2;
    const double delta_mm =
        cbrt(9.0 * f_used * f_used / (16.0 * PAPER_R_MM * e_star_nmm2 * e_star_nmm2));
    out[j].speed = omega;
    out[j].joint = (fb_pin_joint)j;
    out[j].force = f;
    out[j].stiffness = kc_nmm * 1e3;
    out[j].penalty = kc_nmm * pow(PAPER_C_MM, 1.5);
    out[j].approach = delta_mm * 1e-3;
  }
  return FB_OK;
}

static fb_status physical_rows(fb_penalty_row out[FB_PENALTY_PIN_JOINTS], const fb_case *c,
                               double omega, fb_diag *diag) {
  double fmax_joint[FB_MECH_MAX_JOINTS];
  /* the mechanism's inverse dynamics (its closed form, mech_kinematics.h) */
  fb_status st = fb_mech_reaction_peaks(fmax_joint, c->mechanism, &c->nominal, c->branch, c->link,
                                        c->gravity, c->direction * omega, PHYSICAL_SAMPLES, diag);
  if (st != FB_OK) return st;
  const double e_star = fb_contact_modulus(c->youngs_modulus, c->poisson_ratio,
                                           c->youngs_modulus, c->poisson_ratio);
  const fb_mech_desc *mech = fb_case_mech(c);
  for (int j = 0; j < FB_PENALTY_PIN_JOINTS; j++) {
    const int ji = fb_penalty_joint(mech, j);
    if (ji < 0)
      return fb_diag_set(diag, FB_ERR_ARG, "the %s has no joint %d between two moving bodies",
                         mech->type, j + 1);
    const double f = fmax_joint[ji];
    double kc = fb_contact_johnson_stiffness(f, c->pin_length, e_star, c->radial_clearance);
    double d = fb_contact_johnson_approach(f, c->pin_length, e_star, c->radial_clearance);
    if (!isfinite(kc) || !isfinite(d))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s joint at %g rpm: force %g N is beyond Johnson's pin-in-hole "
                         "relation for L = %g m, c = %g m (needs F < 4 pi L E* c / e^2)",
                         fb_case_joint_name(c, ji),
                         omega * 60 / (2 * M_PI), f, c->pin_length, c->radial_clearance);
    out[j].speed = omega;
    out[j].joint = (fb_pin_joint)j;
    out[j].force = f;
    out[j].stiffness = kc;
    out[j].penalty = kc * pow(c->radial_clearance, 1.5);
    out[j].approach = d;
  }
  return FB_OK;
}

fb_status fb_penalty_rows(fb_penalty_row out[FB_PENALTY_PIN_JOINTS], const fb_case *c,
                          fb_penalty_mode mode, double omega, fb_diag *diag) {
  if (!(omega > 0.0) || !isfinite(omega))
    return fb_diag_set(diag, FB_ERR_RANGE, "crank speed %g rad/s: must be positive", omega);
  if (mode == FB_PENALTY_PAPER && fb_penalty_paper_refusal(c))
    return fb_diag_set(diag, FB_ERR_ARG, "paper mode: %s", fb_penalty_paper_refusal(c));
  return mode == FB_PENALTY_PAPER ? paper_rows(out, c, omega, diag)
                                  : physical_rows(out, c, omega, diag);
}
