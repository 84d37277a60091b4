/* The motion of a planar description over its drive's revolution: the
 * positions followed from one drive angle to the next (continuation:
 * a second-order predictor along the velocity, then Newton), and the
 * extremes of every body's angular velocity and acceleration at constant
 * drive speed (the analytic model's peaks of a planar case).
 *
 * A step is accepted when Newton converges, its correction to the
 * predictor stays within FB_PLANAR_JUMP of the step's own motion plus a
 * solution's own rounding, FB_PLANAR_CLOSE_TOL (no jump to another
 * assembly branch), and the sign of det Phi_q is the step's start's (no
 * singular position passed). Otherwise the step is halved, down to
 * FB_PLANAR_STEP_MIN: a path that cannot go on there is locked (a toggle
 * or dead position: no solution beyond it), or passes a singular position
 * (a change point), at that angle. The last step of a path takes the rest
 * of it, a remainder shorter than FB_PLANAR_STEP_MIN included. */
#ifndef FB_PLANAR_PATH_H
#define FB_PLANAR_PATH_H

#include "planar_kinematics.h"

/* Longest continuation step [rad] of the drive: 1 degree. The predictor's
 * error is of the third order in the step (1e-6 of the motion per step at
 * 1 degree), so Newton needs 1 to 3 steps. */
#define FB_PLANAR_STEP_MAX (3.14159265358979323846 / 180.0)

/* Shortest step [rad] before a path is declared locked: a position is
 * then known to 1e-7 rad (6e-6 degrees) of drive angle, more than the
 * message's digits. */
#define FB_PLANAR_STEP_MIN 1e-7

/* Largest Newton correction to the predictor, relative to the scaled
 * motion of the step (|q'| times the step): a correction larger than a
 * tenth of the step's own motion is a jump to another solution, not a
 * correction of the predictor's O(step^3) error. */
#define FB_PLANAR_JUMP 0.1

/* Drive angles per revolution sampled for the peaks (0.1 degree): the
 * extremes of a rigid mechanism's motion away from a locked position are
 * wider than a few tenths of a degree of drive angle; each sampled extreme
 * is then refined with GSL's Brent minimiser (gsl_min_fminimizer_brent)
 * to FB_PLANAR_PEAK_ANGLE_TOL in drive angle. */
#define FB_PLANAR_PEAK_SAMPLES 3600

/* Brent's stopping width [rad] in drive angle around an extreme: at the
 * extreme the value's error is quadratic in it (1e-18 of its curvature,
 * far below double precision). */
#define FB_PLANAR_PEAK_ANGLE_TOL 1e-9

/* Why a path stopped (fb_planar_follow). */
typedef enum {
  FB_PATH_OK = 0,      /* reached the end */
  FB_PATH_LOCKED = 1,  /* no solution beyond *reached: a locked (toggle) position */
  FB_PATH_SINGULAR = 2 /* det Phi_q changes sign at *reached: a singular (change-point)
                          position is passed */
} fb_path_end;

/* Follows the solved position q (at drive angle from [rad]) to drive angle
 * to, in steps of at most FB_PLANAR_STEP_MAX, halved as above; q receives
 * the position at *reached (to, or where the path stopped), *end why.
 * Errors: FB_ERR_ASSEMBLY when it stopped (the message gives the angle),
 * FB_ERR_NUMERIC for a non-finite state. */
fb_status fb_planar_follow(fb_planar_kin *k, double *q, double from, double to, double *reached,
                           fb_path_end *end, fb_diag *diag);

/* Extremes of one body's angular velocity and acceleration over a
 * revolution of the drive at constant speed. */
typedef struct {
  double omega_max, omega_min; /* [rad/s] */
  double alpha_max, alpha_min; /* [rad/s^2] */
  double where[4];             /* the drive's angle from the assembly configuration of
                                  omega_max, omega_min, alpha_max, alpha_min [rad] in [0, 2 pi) */
} fb_planar_peaks;

/* Peaks of every body (out[b], b < m->nbodies; the ground's are zero) over
 * one revolution of the drive at constant signed speed omega [rad/s] from
 * the assembly configuration: FB_PLANAR_PEAK_SAMPLES angles followed with
 * fb_planar_follow, then each extreme refined by Brent.
 * Errors: those of fb_planar_follow (the drive cannot turn fully);
 * FB_ERR_NOMEM. */
fb_status fb_planar_peaks_of(fb_planar_peaks *out, fb_planar_kin *k, double omega,
                             fb_diag *diag);

/* A quantity of the motion at constant drive speed: index i of a family,
 * at the position q, rates qd and accelerations qdd of description m
 * (fb_planar_nq each), w1 = dq/d(drive angle); NaN where it is undefined
 * there. */
typedef double (*fb_planar_quantity)(const fb_planar *m, const double *q, const double *qd,
                                     const double *qdd, const double *w1, int i, void *ctx);

/* One quantity's extremes over a revolution. */
typedef struct {
  double max, min;       /* in the quantity's unit; NaN when it is undefined throughout */
  double at_max, at_min; /* the drive's angle of each from the assembly configuration [rad]
                            in [0, 2 pi) */
} fb_planar_extreme;

/* The extremes of quantities f(.., i, ctx), i < nf, into out[i] over one
 * revolution of the drive at constant signed speed omega [rad/s], as
 * fb_planar_peaks_of finds a body's: the FB_PLANAR_PEAK_SAMPLES angles,
 * then each sampled extreme refined by Brent (samples where f is NaN
 * left out). Errors: those of fb_planar_follow; FB_ERR_NOMEM. */
fb_status fb_planar_extremes_of(fb_planar_extreme *out, int nf, fb_planar_quantity f, void *ctx,
                                fb_planar_kin *k, double omega, fb_diag *diag);

#endif
