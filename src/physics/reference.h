/* Reference dynamics of the four-bar with a clearance crank-coupler joint, in
 * minimal coordinates, integrated by an adaptive high-accuracy integrator: the
 * yardstick for ODE's clearance models, where no analytic answer exists.
 *
 * Crank prescribed (theta2 = theta0 + omega2 t). The coupler hangs from the
 * follower at the ideal joint C, the follower turns about D: generalised
 * coordinates q = (theta3, theta4). The pin (on the crank) moves freely inside
 * the hole at the coupler's B end; e = B_pin(t) - B_hole(q), penetration
 * |e| - c, and the contact law's force (contact.h) acts on the coupler along
 * e/|e|, mapped by J_hole^T. Kane's equations in closed form:
 *   M(q) q'' + h(q, q') = J_G^T m g + J_hole^T F n,
 *   M = [[m3 ((1 - f3) b)^2 + I3, -m3 c (1 - f3) b cos(theta4 - theta3)],
 *        [sym, m3 c^2 + m4 (f4 c)^2 + I4]],
 * with f the centre-of-mass fractions. Integrated with GSL's rk8pd, relative
 * and absolute tolerances FB_REFERENCE_TOL, sampled on the case's time grid;
 * accelerations come from the equations of motion, not from differences.
 * Contact onset is not located as an event: the impact law's force is
 * continuous in the penetration and the adaptive step shrinks to resolve the
 * restitution law's jump of c delta' at contact onset (error control, not
 * event location); both models used here need no impact velocity.
 *
 * Start: the case's [run] start and pin_start resolved by fb_start_resolve
 * (start.h) for the stack-up lengths with clearance at B, the state ODE's
 * scene starts from. The penetration limit (fb_case_penetration_limit)
 * applies as to ODE's models: a sample beyond it ends the run with the
 * status "unstable: penetration ..." (FB_ERR_NUMERIC, samples so far kept).
 *
 * Ideal limit (ideal = 1): the B joint closes (no clearance); the loop's
 * velocity constraint J(q) q' = r(t) is integrated from the assembled state,
 * which must reproduce the analytic solution (tested to 1e-8). */
#ifndef FB_REFERENCE_H
#define FB_REFERENCE_H

#include "case.h"
#include "contact.h"
#include "outcome.h"
#include "series.h"

/* rk8pd error control, relative and absolute. 1e-12 is where revolution 2
 * of the paper's restitution case converges: its impact count (run.revolutions
 * = 2, models reference-restitution, output step 1e-5, 5e-6, 2e-6, 1e-6 s)
 * is 15, 12, 14, 14 at 1e-10; 12, 14, 13, 14 at 1e-11; 14 at every step at
 * 1e-12 and 1e-13 (FOURBAR_REFERENCE_TOL=T fourbar run --set solver.h_s=H
 * --set run.revolutions=2 --set run.models=reference-restitution). Cost on
 * the paper case at the automatic step (3 revolutions): accepted steps
 * 54596 -> 74950 (impact law), 55793 -> 93961 (restitution) against 1e-10.
 * Revolution 3 converges at no tolerance (near-grazing separations grow a
 * difference 300-fold per rattling phase): its impact counts are noise, as
 * summary.json's error_estimate shows. */
#define FB_REFERENCE_TOL 1e-12

/* FOURBAR_REFERENCE_TOL (convergence studies) may move the tolerance within
 * [MIN, MAX]: below 1e-13 rk8pd's error estimate is lost in round-off and the
 * step shrinks without end; above 1e-3 the reference is no yardstick */
#define FB_REFERENCE_TOL_MIN 1e-13
#define FB_REFERENCE_TOL_MAX 1e-3

/* Step budget: at most this many accepted steps per output sample, on
 * average over the run. The paper's case needed 1.07 per sample at 1e-10
 * and 17 at 1e-13; a run that needs more has lost the
 * solution (a step collapsing at a singular position) and stops with the
 * named reason "step budget" instead of running on without end. */
#define FB_REFERENCE_STEPS_PER_SAMPLE 200

/* Peak refinement. Sampled at t = k h, a spike lasting a few samples is
 * missed by up to ~20 % (the coupler's acceleration spike at h = 1e-5 s:
 * 17.5 %). Every sample that is a local extreme of the contact force, the
 * penetration or either output body's acceleration, and at least
 * FB_REFERENCE_REFINE_FRACTION of that quantity's largest magnitude in its
 * part of the run (the start-up revolution, or the peak window from
 * fb_case_peak_window_from: a window's spike is refined even where the
 * start-up's first impact is five times harder), is re-integrated from the sample before it over two sample
 * intervals at FB_REFERENCE_REFINE evaluations per interval, and holds the
 * extreme found there instead of its instantaneous value: peak metrics then
 * see the true spike. The extreme of a smooth pulse of duration T sampled at
 * T / (2 FB_REFERENCE_REFINE x (T / h)) is within (pi h / (T N))^2 / 8 of the
 * truth: 3e-5 for the shortest contacts (T ~ 5 h) at N = 64. */
#define FB_REFERENCE_REFINE 64
#define FB_REFERENCE_REFINE_FRACTION 0.2

/* Integrates the case's stack-up linkage with law at the crank-coupler joint
 * (or ideal) and samples it at t = k h over the case's duration into *out
 * (initialised here; contact columns of the crank-coupler joint unless ideal).
 * *steps receives the integrator's accepted steps.
 * *stop (if not NULL) receives why the integration stopped early
 * (FB_STOP_NONE when it reached the end): step budget, solver failure,
 * non-finite state, penetration beyond the case's limit; the samples before
 * the stop are kept in *out.
 * Samples at spikes hold the refined extreme (FB_REFERENCE_REFINE).
 * Errors: FB_ERR_ARG when the case has clearance at a joint other than
 * crank-coupler (no reference for it yet); FB_ERR_ASSEMBLY; FB_ERR_NUMERIC
 * when the integrator fails or the penetration passes the case's limit
 * (message names the time). */
fb_status fb_reference_run(fb_series *out, size_t *steps, const fb_case *c,
                           const fb_contact_law *law, int ideal, fb_stop *stop, fb_diag *diag);

/* fb_reference_run at relative and absolute tolerance tol, in
 * [FB_REFERENCE_TOL_MIN, FB_REFERENCE_TOL_MAX] (FB_ERR_RANGE outside). */
fb_status fb_reference_run_tol(fb_series *out, size_t *steps, const fb_case *c,
                               const fb_contact_law *law, int ideal, double tol, fb_stop *stop,
                               fb_diag *diag);

/* The tolerance fb_reference_run uses: FB_REFERENCE_TOL, or
 * FOURBAR_REFERENCE_TOL from the environment (convergence studies).
 * Errors: FB_ERR_RANGE when that is not a number in [MIN, MAX]. */
fb_status fb_reference_tolerance(double *tol, fb_diag *diag);

/* The reference's own error estimate: a second integration at
 * tol / FB_REFERENCE_CHECK_FACTOR (at most down to FB_REFERENCE_TOL_MIN)
 * compared with the first like a model with its reference
 * (fb_metrics_vs_reference): summary.json's error_estimate. At the
 * default 1e-12 the check runs at 1e-13 (the floor), a tenth. */
#define FB_REFERENCE_CHECK_FACTOR 100.0

#endif
