/* The closed-form kinematics of a case's mechanism, chosen by its type
 * (mechanism.h fb_mech_type): what the analytic model, the peaks and the
 * errors against the analytic solution call, so that they serve the
 * four-bar (linkage.h, analytic.h) and the slider-crank (slider_crank.h)
 * alike. Each function is its mechanism's table entry (closed_form.h:
 * closed_form_fourbar.c, closed_form_slider_crank.c). Lengths are fb_linkage's in the description's order (a
 * slider-crank's crank, coupler and guide offset at FB_LENGTH_OFFSET);
 * SI units throughout. */
#ifndef FB_MECH_KINEMATICS_H
#define FB_MECH_KINEMATICS_H

#include <stddef.h>

#include "analytic.h"
#include "effective_mass.h"
#include "mechanism.h"

/* The output bodies' positions, velocities and accelerations at one crank
 * angle: out[b][FB_Q_*], b in the description's output order (the
 * four-bar's coupler and follower angles [rad], [rad/s], [rad/s^2]; the
 * slider-crank's coupler the same and the slider's x [m], v [m/s],
 * a [m/s^2]).
 * Errors: those of fb_linkage_solve or fb_slider_crank_solve (the loop does
 * not close; invalid lengths). */
fb_status fb_mech_solve(double out[FB_MECH_MAX_OUTPUTS][3], fb_mech_type t, const fb_linkage *lk,
                        fb_branch branch, double theta2, double omega2, double alpha2,
                        fb_diag *diag);

/* FB_OK when the lengths make a mechanism of type t whose crank turns
 * fully: the four-bar's fb_linkage_check (its drivability is the case's
 * check, case.c); the slider-crank's fb_slider_crank_require_full_turn.
 * Errors: FB_ERR_RANGE, FB_ERR_ASSEMBLY naming the rule. */
fb_status fb_mech_check_lengths(fb_mech_type t, const fb_linkage *lk, fb_diag *diag);

/* Peaks over one crank revolution at constant crank speed omega2 [rad/s]:
 * the four-bar's fb_analytic_peaks; the slider-crank's coupler angular
 * velocity and acceleration and slider velocity and acceleration extremes
 * bracketed on FB_ANALYTIC_PEAK_SAMPLES crank angles and refined with GSL's
 * Brent minimiser to 1e-12 rad in crank angle, and the slider's position
 * extremes, the dead centres in closed form (fb_slider_crank_limit_positions).
 * pos_max/pos_min are filled for the slider-crank's bodies only (the
 * four-bar's are NAN).
 * Errors: those of fb_analytic_peaks or fb_slider_crank_require_full_turn. */
fb_status fb_mech_peaks(fb_peaks *out, fb_mech_type t, const fb_linkage *lk, fb_branch branch,
                        double omega2, fb_diag *diag);

/* As fb_mech_peaks, and also the crank angle [rad] of each extreme in
 * `where` (may be NULL), as fb_analytic_peaks_where: the first output
 * body's omega max, min, alpha max, min, then the same for the second (the
 * slider-crank's slider: v max, min, a max, min). The tolerance stack-up's
 * sensitivities of a peak are taken there (the envelope theorem).
 * The slider-crank's search is one pass over FB_ANALYTIC_PEAK_SAMPLES crank
 * angles for every extreme, then Brent for each.
 * Errors: those of fb_mech_peaks. */
fb_status fb_mech_peaks_where(fb_peaks *out, double where[8], fb_mech_type t,
                              const fb_linkage *lk, fb_branch branch, double omega2,
                              fb_diag *diag);

/* Samples the exact solution at t = k h, k = 0 .. n - 1, crank angle
 * theta0 + omega2 t, into a fresh series *out of the mechanism's columns
 * (free with fb_series_free): fb_analytic_sample for the four-bar.
 * Errors: those of fb_mech_solve; FB_ERR_NOMEM. */
fb_status fb_mech_sample(fb_series *out, fb_mech_type t, const fb_linkage *lk, fb_branch branch,
                         double theta0, double omega2, double h, size_t n, fb_diag *diag);

/* Largest joint reaction magnitude over one revolution at constant crank
 * speed omega2 [rad/s], gravity [m/s^2] along -y, n >= 1 crank angles
 * 2 pi k / n, per joint of the description into force_max[j] [N]: the
 * four-bar's fb_invdyn_peaks (lengths lk, branch, link[3]); the
 * slider-crank's pin forces (fb_slider_crank_invdyn_peaks) and at the
 * guide, slider-ground, the largest |N|. The last four sets of inputs'
 * results are kept (per thread), and the same inputs return them: a
 * case's setup asks for its peaks from several stages (the automatic
 * step, the contact estimates, the joint laws, the scene, the preflight),
 * each of the case's lengths (nominal, stack-up) computed once.
 * Errors: those of fb_invdyn_peaks or fb_slider_crank_invdyn_peaks. */
fb_status fb_mech_reaction_peaks(double force_max[4], fb_mech_type t, const fb_linkage *lk,
                                 fb_branch branch, const fb_link_mass link[3], double gravity,
                                 double omega2, int n, fb_diag *diag);

/* How many times this thread has computed reaction peaks (not returned
 * them from the kept results): a count for tests. */
long fb_mech_reaction_peaks_computed(void);

/* The mechanism of type t at crank angle theta2 [rad] (its exact solution),
 * as effective_mass.h takes it: fb_mechanism_from_state for the four-bar,
 * fb_mechanism_from_slider_crank for the slider-crank; the crank driven,
 * clearance_mask the clearance joints.
 * Errors: those of fb_linkage_solve or fb_slider_crank_solve. */
fb_status fb_mech_mechanism_at(fb_mechanism *out, fb_mech_type t, const fb_linkage *lk,
                               fb_branch branch, const fb_link_mass link[3], double theta2,
                               int clearance_mask, fb_diag *diag);

#endif
