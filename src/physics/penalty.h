/* Penalty-parameter estimation per crank speed and clearance joint, two ways.
 *
 * Paper mode reproduces the paper's Tables I to III with the recipe recovered
 * in docs/paper.md ("What reproduces the printed Tables I to III"): it is offered
 * for line-by-line comparison with the paper, not as physics.
 *   Table I:   F = k max|alpha| over a revolution (coupler for the
 *              crank-coupler joint, follower for the coupler-follower joint),
 *              nominal lengths, k = 8.783456e-5 kg m;
 *   Table II:  P = Kc C^1.5 (paper Eq. 9), Kc = 2 a E* (Eq. 7),
 *              E* = E / (2 (1 - nu^2)), C = 0.042 mm, a = sqrt(F / (100 C)) mm;
 *   Table III: delta = (9 F^2 / (16 R E*^2))^(1/3), R = 20/3 mm;
 *   the coupler-follower column uses F rounded to 0.01 N except at 100 rpm.
 * Physical mode uses the inverse-dynamics joint reaction (largest magnitude
 * over a revolution, gravity included), the case's radial clearance c and
 * pin length L, and Johnson's pin-in-hole line contact: approach
 * delta(F) = F/(pi L E*) [ln(4 pi L E* c / F) - 1], stiffness Kc = dF/d delta,
 * penalty P = Kc c^1.5 (Eq. 9 evaluated in SI). */
#ifndef FB_PENALTY_H
#define FB_PENALTY_H

#include "case.h"

typedef enum { FB_PENALTY_PAPER = 0, FB_PENALTY_PHYSICAL = 1 } fb_penalty_mode;

/* The clearance joints the paper tabulates, as pin joint j = 0 ..
 * FB_PENALTY_PIN_JOINTS - 1: the mechanism's joints between two moving
 * bodies, in the description's joint order (fb_penalty_joint; the
 * four-bar's crank-coupler and coupler-follower, the slider-crank's
 * crank-coupler and coupler-slider). */
enum { FB_PENALTY_PIN_JOINTS = 2 };
typedef int fb_pin_joint;

/* The description's index of pin joint j of mechanism m (mechanism.h), -1
 * when m has no such joint. */
int fb_penalty_joint(const fb_mech_desc *m, fb_pin_joint j);

/* The four-bar's names of pin joint j: "crank-coupler" or
 * "coupler-follower" (fb_mech_joint_name of fb_penalty_joint). */
const char *fb_pin_joint_name(fb_pin_joint j);

/* NULL when paper mode applies to case c (a four-bar), else why it does not
 * (the slider-crank: the paper's recipe is its four-bar's), one sentence. */
const char *fb_penalty_paper_refusal(const fb_case *c);

/* One row: one speed, one joint. */
typedef struct {
  double speed;     /* crank speed [rad/s] */
  fb_pin_joint joint;
  double force;     /* force used [N] */
  double stiffness; /* contact stiffness Kc [N/m] */
  double penalty;   /* P = Kc C^1.5: paper units (N mm^0.5) in paper mode, N m^0.5 in physical */
  double approach;  /* mutual approach delta [m] */
} fb_penalty_row;

/* Rows for both pin joints at crank speed omega [rad/s] > 0 for case c: the
 * four-bar's in either mode, a slider-crank's (its crank-coupler and
 * coupler-slider joints, reactions from fb_mech_reaction_peaks) in physical
 * mode. Errors: those of fb_analytic_peaks / fb_invdyn_peaks /
 * fb_mech_reaction_peaks; FB_ERR_RANGE when Johnson's relation is outside
 * its valid range (force too large for the clearance); FB_ERR_ARG for paper
 * mode on a slider-crank (fb_penalty_paper_refusal). */
fb_status fb_penalty_rows(fb_penalty_row out[FB_PENALTY_PIN_JOINTS], const fb_case *c,
                          fb_penalty_mode mode, double omega, fb_diag *diag);

#endif
