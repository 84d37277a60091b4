/* How well a step resolves a case's clearance contacts, before any run:
 * the effective mass along the contact normal over a revolution, the force
 * to expect, the contact frequency that follows, and the automatic step
 * (`[solver] h_s = auto`) that keeps h omega_c below a stated bound.
 *
 *   m_eff range: fb_effective_mass_tensor on the ideal stack-up linkage at
 *     FB_RESOLUTION_SAMPLES crank angles, every direction (the smallest and
 *     largest eigen-masses); the contact's normal turns freely, so its
 *     worst direction is the one to resolve.
 *   expected force: FB_IMPACT_LOAD_FACTOR times the joint's largest ideal
 *     reaction over a revolution (inverse dynamics, gravity included): the
 *     pin leaves the wall and strikes it again under the load it carried; a
 *     suddenly applied load on a spring peaks at twice its static value
 *     (dynamic load factor 2, e.g. Timoshenko, Vibration Problems in
 *     Engineering). Measured on the paper case at 1000 rpm: 2 x 1505 N
 *     against a largest contact force of 2490 N (reference).
 *   omega_c = sqrt(k_t / m_eff_min), k_t the tangent stiffness of the law's
 *     elastic part at the expected force (n K^(1/n) F^((n-1)/n); p for the
 *     restitution law).
 *   the contact's rate at that impact (fb_contact_rates_at): the larger of
 *     omega_c and the damper's own rate c / m_eff_min (a velocity decays as
 *     exp(-c t / m) on a damper alone), c the law's damper at the expected
 *     impact's depth and approach speed (the impact law's c_max STEP(delta),
 *     so that a damper deeper than the impact's depth counts as far as the
 *     impact reaches it; the restitution law's 2 zeta omega_c, below
 *     omega_c for cr above 0.29). The impact law's
 *     damper also ramps in, from 0 to c_max v_n over its full-damping depth
 *     d_max, at rate v_n / d_max (v_n the expected approach speed); that
 *     rate is reported, not kept: the paper case's models are within
 *     0.13 % of the reference at the automatic step, where h v_n / d_max
 *     is 0.79 (v_n 0.24 m/s estimated, 0.165 m/s at its first impact), and
 *     keeping it would take that step from 3.32e-6 to 2.09e-6 s and
 *     slider_crank_flores's from 2e-6 to 4.4e-7 s.
 *   h auto = min(FB_H_OMEGA_C_BOUND / that rate over the clearance joints
 *     and both clearance laws, one revolution / FB_H_AUTO_STEPS_PER_REV). */
#ifndef FB_RESOLUTION_H
#define FB_RESOLUTION_H

#include "case.h"
#include "contact.h"

/* The bound on h omega_c that `auto` keeps and beyond which a run is
 * flagged `under-resolved` (an accuracy bound, not a stability one).
 * Measured on the paper case with the matched mapping (h omega_c as the run
 * reports it, h sqrt(k_t / m_eff) over its contact steps): both clearance
 * models ran at h = 3e-5 s (h omega_c 4.1 and 3.8) and left the hole at
 * 4e-5 s (5.1 and 5.0) before such steps were refused as aliasing
 * (contact.h, FB_MATCHED_ALIAS_BOUND); accuracy goes much earlier: at 1e-5 s (1.1) the
 * coupler spike is 19 % low, at 5e-6 s (0.54) force, penetration and spike
 * are within 0.4 % of the reference, and `auto` (3.3e-6 s, 0.36) within
 * 0.13 %. A single impact loses 40 % of its penetration's accuracy at
 * h omega_c = 1.5 (pi / contact duration), where the contact lasts two steps. */
#define FB_H_OMEGA_C_BOUND 0.5

/* The ideal model's accuracy cap of the automatic step: steps per crank
 * revolution (1e-5 s at 1000 rpm, where the ideal stack-up model's omega
 * peaks are within 1e-3 of the exact ones). */
#define FB_H_AUTO_STEPS_PER_REV 6000.0

/* Crank angles sampled over a revolution for the effective-mass range. */
#define FB_RESOLUTION_SAMPLES 720

/* Dynamic load factor of an impact against the joint's largest reaction. */
#define FB_IMPACT_LOAD_FACTOR 2.0

/* The time scales of one contact at its expected impact, each a rate. */
typedef struct {
  double stiffness_tangent; /* k_t of the law's elastic part at the expected force [N/m] */
  double omega_c;           /* sqrt(k_t / m_eff) [rad/s] */
  double depth;             /* delta = (F / K)^(1/n): the elastic depth at the expected force [m] */
  double approach_speed;    /* v_n [m/s]: the approach speed of the undamped impact that peaks
                               at the expected force, 1/2 m_eff v_n^2 = F delta / (n + 1) */
  double damper_rate;       /* c / m_eff [1/s], c the law's damper at that depth and speed
                               (fb_contact_damping_at): the impact law's c_max STEP(delta), the
                               restitution law's 2 zeta sqrt(p m_eff) (its damper is put on the
                               effective mass, contact_mass.h); 0 without a damper */
  double ramp_rate;         /* v_n / d_max [1/s] of the impact law's damper (0 for others):
                               reported, not kept (above) */
  double rate;              /* the larger of omega_c and damper_rate: the step's [1/s] */
  int by_damper;            /* 1: the damper's rate is the larger (rate = damper_rate) */
  const char *limit;        /* which one in words, for the outputs: "stiffness" or "damper" */
} fb_contact_rates;

/* The rates of law on effective mass m_eff [kg] > 0 at the expected impact
 * force force [N] > 0 (resolution.h's comment: the rule of the automatic
 * step, for every mechanism). */
void fb_contact_rates_at(fb_contact_rates *out, const fb_contact_law *law, double m_eff,
                         double force);

/* Resolution estimate of one clearance joint under one law. */
typedef struct {
  double m_eff_min;         /* smallest effective mass over a revolution and directions [kg] */
  double m_eff_max;         /* largest [kg] */
  double force_expected;    /* FB_IMPACT_LOAD_FACTOR x the largest ideal reaction [N] */
  double stiffness_tangent; /* k_t of the law's elastic part at force_expected [N/m] */
  double omega_c;           /* sqrt(k_t / m_eff_min) [rad/s] */
  fb_contact_rates rates;   /* every time scale at m_eff_min; rates.rate the one the step keeps */
} fb_contact_estimate;

/* Tangent stiffness dF_el/d delta [N/m] of law's elastic part where it
 * carries force [N] > 0: n K^(1/n) F^((n-1)/n); k for the linear and
 * restitution laws. */
double fb_contact_tangent_at_force(const fb_contact_law *law, double force);

/* Estimates for every clearance joint j of case c (law[j] its law; others
 * zeroed). Errors: those of fb_linkage_solve, fb_invdyn_peaks and
 * fb_effective_mass_tensor. */
fb_status fb_contact_estimates(fb_contact_estimate est[4], const fb_case *c,
                               const fb_contact_law law[4], fb_diag *diag);

/* The automatic step [s] of case c: the rule in this header's comment over
 * both clearance laws of the case's clearance joints (one revolution /
 * FB_H_AUTO_STEPS_PER_REV alone without clearance joints). *omega_c_max
 * (may be NULL) receives the largest contact rate [1/s] (fb_contact_rates'
 * rate; 0 without clearance).
 * Errors: those of fb_joint_laws and fb_contact_estimates. */
fb_status fb_step_auto(double *h, double *omega_c_max, const fb_case *c, fb_diag *diag);

/* One clearance joint of a case as a contact on its own (`fourbar
 * contact-params --case`): the laws of its two clearance models, its
 * effective-mass range over a revolution and every direction, the force to
 * expect, and the step the run would take. */
typedef struct {
  fb_contact_law impact;      /* the *-clearance-impact model's law */
  fb_contact_law restitution; /* the *-clearance-restitution model's law */
  fb_contact_estimate est;    /* m_eff range [kg], expected force [N], omega_c [rad/s] */
  double h;                   /* the run's step [s] (fb_case_resolve_step; h_min_s if adaptive) */
} fb_case_contact;

/* Fills out for joint j (FB_JOINT_A..D) of case c. Errors: FB_ERR_ARG when
 * j is not one of the case's clearance joints (the message names those);
 * those of fb_joint_laws, fb_contact_estimates and fb_case_resolve_step. */
fb_status fb_case_contact_of(fb_case_contact *out, const fb_case *c, int j, fb_diag *diag);

/* Sets c->solver.h from fb_step_auto when h_mode is FB_STEP_AUTO, or
 * FB_STEP_DEFAULT with clearance joints (h_mode is left as it was, so a
 * later change of the case can resolve it again). Errors: those of
 * fb_step_auto. */
fb_status fb_case_resolve_step(fb_case *c, fb_diag *diag);

#endif
