/* The ideal joint load's time scale: how soon the reaction a joint carries
 * in the ideal linkage changes by its own size, in magnitude or direction,
 *
 *   tau(theta) = |F(theta)| / |dF/dt|,   dF/dt = omega2 dF/dtheta,
 *
 * F the joint's reaction from inverse dynamics (invdyn.h) at crank angle
 * theta, the crank at constant speed omega2. A clearance joint's pin rests
 * on the wall while its load is large and turns slowly against the contact's
 * period; where tau is short the pin slides round the hole after a turning
 * load, leaves the wall and strikes it again. On the paper case at 1000 rpm
 * this happens once per revolution: the ideal reaction at B falls to 60 N
 * and turns by 150 degrees in 1 ms (tau 0.16 ms, against 1.7 ms or more
 * over the rest of the revolution), the pin lags it by up to 72 degrees and
 * leaves the wall 0.6 ms after the smallest load (reference model,
 * docs/step-size.md).
 *
 * The adaptive step (step_control.h) uses it to shorten the step in
 * continuous contact ahead of such an event, from the crank angle alone:
 * an exogenous schedule that does not follow the contact's own ringing.
 * Pure tables over one revolution of the drive; SI units. */
#ifndef FB_LOAD_SCALE_H
#define FB_LOAD_SCALE_H

#include "case.h"
#include "linkage.h"
#include "planar.h"

/* Crank angles per revolution of the table: 7200 (0.05 degree; 8.3 us
 * apart at the paper's 1000 rpm, against the 160 us of its shortest
 * tau). */
#define FB_LOAD_SCALE_SAMPLES 7200

/* Joints a table can hold: a planar description's (planar_spec.h). */
#define FB_LOAD_SCALE_JOINTS FB_PLANAR_SPEC_MAX_JOINTS

/* tau ahead of each drive angle for each joint of a mask. */
typedef struct {
  int n;               /* drive angles in the table [-] (FB_LOAD_SCALE_SAMPLES) */
  double angle0;       /* the drive angle of entry 0 [rad]: entry k is at angle0 + 2 pi k / n
                          (0 for the closed forms' crank angle; a description's drive angle
                          at its assembly for fb_load_scale_build_planar) */
  double *ahead[FB_LOAD_SCALE_JOINTS]; /* per joint: the smallest tau [s] over the drive
                          angles the drive sweeps in the next lookahead seconds, at entry k
                          (n); NULL for joints outside the mask */
  double *force[FB_LOAD_SCALE_JOINTS]; /* per joint: the largest |F| [N] over the same
                          angles (n); NULL for joints outside the mask */
} fb_load_scale;

/* Builds the table for the joints in joint_mask (bit j: joint j, fb_joint)
 * of the ideal linkage lk (branch, masses link, gravity along -y [m/s^2]) at
 * crank speed omega2 [rad/s], each entry the smallest tau over the next
 * lookahead_s >= 0 seconds. A crank at rest (omega2 = 0) or a load that does
 * not change gives tau = INFINITY. Errors: those of fb_invdyn_solve;
 * FB_ERR_NOMEM. On error *out is left empty (fb_load_scale_free is safe).
 * The four-bar's (its closed form's reactions, closed_form.h). */
fb_status fb_load_scale_build(fb_load_scale *out, const fb_linkage *lk, fb_branch branch,
                              const fb_link_mass link[3], double gravity, double omega2,
                              int joint_mask, double lookahead_s, fb_diag *diag);

/* The same for a mechanism of type t (mechanism.h), joints in its
 * description's order: the four-bar's reactions from fb_invdyn_solve; the
 * slider-crank's (lk's crank, coupler and offset at FB_LENGTH_OFFSET, link
 * crank, coupler, slider; branch unused) from fb_slider_crank_invdyn, the
 * pins' forces at joints 0..2 and the guide's (0, -N) at slider-ground, as
 * the analytic model reports them. Errors: those of fb_invdyn_solve or
 * fb_slider_crank_invdyn; FB_ERR_NOMEM. */
fb_status fb_load_scale_build_mech(fb_load_scale *out, fb_mech_type t, const fb_linkage *lk,
                                   fb_branch branch, const fb_link_mass link[3], double gravity,
                                   double omega2, int joint_mask, double lookahead_s,
                                   fb_diag *diag);

/* The same for any planar description m with a speed drive, from the
 * planar core: its joints' reactions (planar_invdyn.h, gravity [m/s^2]
 * along -y, springs and loads included) at FB_LOAD_SCALE_SAMPLES drive
 * angles over a revolution followed from the assembly (planar_path.h),
 * the drive at constant signed speed omega2 [rad/s]; the joints of mask
 * (bit j: m's joint j, below FB_LOAD_SCALE_JOINTS); entry 0 at the
 * assembly (angle0 the drive's angle there, theta_to0 - theta_from0,
 * planar_constraints.h). For the four-bar's and slider-crank's
 * descriptions the same table as fb_load_scale_build_mech's to the
 * finite differences' truncation (tests/test_load_scale.c). Errors:
 * FB_ERR_ARG (no speed drive, a joint of mask out of range), those of
 * planar_path.h and fb_planar_invdyn (a drive that cannot turn a whole
 * revolution); FB_ERR_NOMEM. */
fb_status fb_load_scale_build_planar(fb_load_scale *out, const fb_planar *m, double gravity,
                                     double omega2, unsigned mask, double lookahead_s,
                                     fb_diag *diag);

/* The table's tau ahead [s] and largest load ahead [N] of joint j at drive
 * angle theta [rad] (any value: theta - angle0 taken modulo 2 pi); INFINITY
 * and 0 for a joint outside the mask. Either pointer may be NULL. */
void fb_load_scale_at(const fb_load_scale *ls, int j, double theta, double *tau, double *force);

void fb_load_scale_free(fb_load_scale *ls);

#endif
