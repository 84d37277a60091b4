/* The analytic model: exact four-bar kinematics at constant crank speed,
 * sampled on a time grid, and its exact peaks over a crank revolution.
 * Built on linkage.h; this is the reference every dynamic result is judged
 * against. */
#ifndef FB_ANALYTIC_H
#define FB_ANALYTIC_H

#include "linkage.h"
#include "series.h"

/* Extremes of one body's velocity and acceleration (angular for a rotating
 * or planar body [rad/s, rad/s^2], linear for a translating one, such as a
 * slider [m/s, m/s^2]) and of its position. */
typedef struct {
  double omega_max; /* [rad/s] */
  double omega_min; /* [rad/s] */
  double alpha_max; /* [rad/s^2] */
  double alpha_min; /* [rad/s^2] */
  double pos_max;   /* largest position: a slider's x [m], a rod's angle [rad]; NAN where
                       not taken (the four-bar's analytic peaks) */
  double pos_min;   /* smallest position [m] or [rad] */
} fb_body_peaks;

/* Extremes of each output body (mechanism.h; the four-bar's coupler and
 * follower). */
typedef struct {
  FB_MECH_OUTPUT_MEMBERS(fb_body_peaks);
} fb_peaks;

/* Crank angles per revolution of the dense-grid search fb_analytic_peaks_grid
 * (the method before the series search): 0.1 deg spacing brackets every
 * extreme of a non-degenerate crank-rocker. */
#define FB_ANALYTIC_PEAK_SAMPLES 3600

/* Exact extremes of coupler and follower angular velocity and acceleration
 * over one full crank revolution at constant crank speed omega2 [rad/s]
 * (sign gives the direction: negative is clockwise).
 * Method: exact Taylor series of theta3, theta4 in crank angle (order 9, from
 * the loop closure order by order) on nodes spaced by a third of the distance
 * to the nearest complex singularity of the position problem (|BD| = |b - c|,
 * b + c or 0), so the grid is denser near a change point or a folding
 * linkage; every root of d omega / d theta2 and of the jerk is excluded or
 * isolated on each interval by series bounds (halving where undecided) and
 * refined by Newton steps on the series to 1e-12 rad in crank angle. All
 * eight extremes share every evaluation (about 30-60 per call). The comment
 * in analytic.c gives the derivation.
 * Errors: FB_ERR_ASSEMBLY when the crank cannot turn fully (message names the
 * reachable range); FB_ERR_RANGE for invalid lengths. */
fb_status fb_analytic_peaks(fb_peaks *out, const fb_linkage *lk, fb_branch branch,
                            double omega2, fb_diag *diag);

/* As fb_analytic_peaks, and also the crank angle [rad] of each extreme in
 * `where` (may be NULL): coupler omega max, min, alpha max, min, then the
 * same for the follower (8). */
fb_status fb_analytic_peaks_where(fb_peaks *out, double where[8], const fb_linkage *lk,
                                  fb_branch branch, double omega2, fb_diag *diag);

/* The reference search: each extreme bracketed on a uniform grid of n crank
 * angles (n >= 3; FB_ANALYTIC_PEAK_SAMPLES was the default) and refined with
 * GSL's Brent minimiser (gsl_min_fminimizer_brent) to 1e-12 rad in crank
 * angle inside +- one grid step. Costs about n + 200 solves: for tests and
 * benchmarks. Output as fb_analytic_peaks_where.
 * Errors: those of fb_analytic_peaks; FB_ERR_ARG for n < 3. */
fb_status fb_analytic_peaks_grid(fb_peaks *out, double where[8], const fb_linkage *lk,
                                 fb_branch branch, double omega2, int n, fb_diag *diag);

/* Samples the analytic solution at t = t0 + k h, k = 0 .. n - 1, for the crank
 * angle theta2(t) = theta0 + omega2 t, into a fresh series *out (initialised
 * here; free with fb_series_free).
 * Errors: FB_ERR_ASSEMBLY, FB_ERR_RANGE as fb_linkage_solve; FB_ERR_NOMEM. */
fb_status fb_analytic_sample(fb_series *out, const fb_linkage *lk, fb_branch branch,
                             double theta0, double omega2, double h, size_t n,
                             fb_diag *diag);

#endif
