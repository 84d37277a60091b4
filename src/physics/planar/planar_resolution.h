/* How well a step resolves a planar case's clearance contacts, before any
 * run: the four-bar's estimate (resolution.h) on a planar description, and
 * the automatic step of a planar case (`[solver] h_s = auto`, or no h_s
 * with clearance joints) from it, by the one rule of resolution.h.
 *
 * Per revolute clearance joint and law: the effective mass along every
 * direction at the pin (fb_planar_effective_mass_tensor, the clearance
 * joints out of the set, the drive held) over FB_RESOLUTION_SAMPLES drive
 * angles of a revolution; the expected force FB_IMPACT_LOAD_FACTOR x the
 * joint's largest ideal reaction; the contact's rates at that force on the
 * smallest mass (fb_contact_rates_at: omega_c, the damper's c / m_eff, the
 * impact law's ramp v_n / d_max, reported); h_resolving =
 * FB_H_OMEGA_C_BOUND over the rate the step keeps. */
#ifndef FB_PLANAR_RESOLUTION_H
#define FB_PLANAR_RESOLUTION_H

#include "case.h"
#include "contact.h"
#include "planar.h"
#include "resolution.h"

/* One clearance pin's contact under one law. */
typedef struct {
  int joint;                 /* index in the description */
  int impact;                /* 1: the impact law (*-clearance-impact), 0: the restitution law */
  fb_contact_law law;        /* the law a run's models of that kind take (joint_law.h) */
  double m_eff_min, m_eff_max; /* [kg] */
  double reaction_max;       /* the joint's largest ideal reaction over a revolution [N] */
  double force_expected;     /* [N] */
  double stiffness_tangent;  /* [N/m] */
  double omega_c;            /* [rad/s] */
  fb_contact_rates rates;    /* every rate at m_eff_min [1/s] */
  double h_resolving;        /* FB_H_OMEGA_C_BOUND / rates.rate [s] */
} fb_planar_contact_estimate;

/* The estimates of every revolute clearance joint of case c (description
 * m) under both laws, impact first (out: 2 m->njoints; *n receives their
 * number; a prismatic clearance joint has none). A driven case only.
 * Errors: those of the laws (joint_law.h), the kinematics, the inverse
 * dynamics and the effective mass. */
fb_status fb_planar_contact_estimates(fb_planar_contact_estimate *out, int *n, const fb_case *c,
                                      const fb_planar *m, fb_diag *diag);

/* The automatic step [s] of planar case c (description m): the smallest
 * h_resolving of its estimates, at most one revolution /
 * FB_H_AUTO_STEPS_PER_REV (that alone without revolute clearance joints;
 * NAN when undriven: no revolution to count, the caller's rule). Errors:
 * those of fb_planar_contact_estimates. */
fb_status fb_planar_step_auto(double *h, const fb_case *c, const fb_planar *m,
                              fb_diag *diag);

#endif
