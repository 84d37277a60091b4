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
 *
 * Kept at full precision over long runs (issue 54). The integrated state
 * holds the angles as deviations from the ideal four-bar's at the same
 * crank angle (theta3 - theta3i(t), theta4 - theta4i(t); the velocities
 * absolute), and the eccentricity is formed from those small deviations
 * (planar_turn.h) rather than as the difference of two coordinates of the
 * mechanism's size; the crank turns on a clock restarted at each sample,
 * so that its angle carries the rounding of one sample interval's turn,
 * not of omega2 t. In the absolute form the ~1e-17 m rounding of e and the
 * growing rounding of omega2 t, through the contact's stiffness, reached
 * the tolerance: the step controller shrank the step on noise, the more
 * the longer the run (paper case, steps per revolution 22.7k at 1
 * revolution, 47.9k at 16; the check integration's 101k and 372k). Now:
 * 18.2k to 18.5k for both, at 1 to 16 revolutions (docs/performance.md).
 * The slider-crank's state likewise (fb_sc_dyn_eval_dev).
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
#include "peak_refine.h"
#include "series.h"

/* rk8pd error control, relative and absolute. 1e-12 is where revolution 2
 * of the paper's restitution case converges: its impact count (run.revolutions
 * = 2, models reference-restitution, output step 1e-5, 5e-6, 2e-6, 1e-6 s)
 * is 16, 13, 13, 14 at 1e-10; 12, 14, 14, 14 at 1e-11; 14 at every step at
 * 1e-12 and 1e-13 (FOURBAR_REFERENCE_TOL=T fourbar run --set solver.h_s=H
 * --set run.revolutions=2 --set run.models=reference-restitution; before
 * issue 54's full-precision state: 15, 12, 14, 14 and 12, 14, 13, 14).
 * Cost of that run at h = 1e-5 s: accepted steps 13428 (1e-10), 18154
 * (1e-12), 24021 (1e-13); at the paper case's automatic step (3.3e-6 s)
 * nearly one step per output sample at any of them. Revolution 3 converges
 * at no tolerance (near-grazing separations grow a difference 300-fold per
 * rattling phase): its impact counts are noise, as summary.json's
 * error_estimate shows. */
#define FB_REFERENCE_TOL 1e-12

/* FOURBAR_REFERENCE_TOL (convergence studies) may move the tolerance within
 * [MIN, MAX]: above 1e-3 the reference is no yardstick. MIN is where the
 * absolute form's error estimate was lost in round-off (the step shrank
 * without end below it); the full-precision state moved that floor to
 * about 1e-15 (paper case, 2 revolutions: 18.5k steps per revolution at
 * 1e-13 and 1e-14, 19.4k at 1e-15, 35.8k at 1e-16), which a lower MIN
 * could use (the check integration would then run at tol / 100) */
#define FB_REFERENCE_TOL_MIN 1e-13
#define FB_REFERENCE_TOL_MAX 1e-3

/* Step budget: at most this many accepted steps per output sample, on
 * average over the run. The paper's case needs 1.01 per sample at 1e-12
 * and 1e-13 (17 at 1e-13 in the absolute form); a run that needs more has
 * lost the solution (a step collapsing at a singular position) and stops
 * with the named reason "step budget" instead of running on without end. */
#define FB_REFERENCE_STEPS_PER_SAMPLE 200

/* Peak refinement: samples at spikes hold the extreme between their
 * neighbours (peak_refine.h, FB_REFERENCE_REFINE). */

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
 * crank-coupler (fb_reference_run_joints takes those); FB_ERR_ASSEMBLY; FB_ERR_NUMERIC
 * when the integrator fails or the penetration passes the case's limit
 * (message names the time). */
fb_status fb_reference_run(fb_series *out, size_t *steps, const fb_case *c,
                           const fb_contact_law *law, int ideal, fb_stop *stop, fb_diag *diag);

/* fb_reference_run at relative and absolute tolerance tol, in
 * [FB_REFERENCE_TOL_MIN, FB_REFERENCE_TOL_MAX] (FB_ERR_RANGE outside). */
fb_status fb_reference_run_tol(fb_series *out, size_t *steps, const fb_case *c,
                               const fb_contact_law *law, int ideal, double tol, fb_stop *stop,
                               fb_diag *diag);

/* The reference of a case with clearance at any of its mechanism's pins
 * ([clearance] joints: one or several revolute joints), at relative and
 * absolute tolerance tol (as fb_reference_run_tol), each clearance joint j
 * with its own law law[j] (FB_MECH_MAX_JOINTS, indexed by the mechanism's
 * joints; read at the clearance joints), into *out with the contact
 * columns of every clearance joint. Clearance at the reference joint alone
 * (the description's reference_joint): the closed form above
 * (fb_reference_run_tol). Several: the mechanism's description at the
 * stack-up lengths (planar_case.h fb_planar_of_case) integrated on the
 * planar core in relative coordinates (planar_reference.h: rk8pd at tol,
 * each pin's eccentricity in the state, every joint's law its own), from
 * the steady start with every pin centred, the state the engines' scenes
 * start from at [run] start = steady and pin_start = centred (an ensemble
 * member's pins moved by its pin_start_offset, as the scenes' are:
 * planar_relative.h fb_planar_rel_steady_offset); each sample's
 * output bodies' motion and each joint's force, penetration, eccentricity
 * (pin centre - hole centre) and state (fb_reference_contact_state), the
 * spikes refined by the same rule (planar_reference.h
 * fb_planar_ref_refine); the penetration limit stops it as above (the
 * samples before kept). tests/test_reference_joints.c holds it to the
 * closed form at one joint.
 * Errors: FB_ERR_ARG for several clearance joints with [run] start =
 * rest or a pin_start other than centred, or a prismatic clearance joint
 * (the message names the key); those of fb_reference_run_tol, of
 * fb_planar_of_case and of the planar core; FB_ERR_NUMERIC as above. */
fb_status fb_reference_run_joints(fb_series *out, size_t *steps, const fb_case *c,
                                  const fb_contact_law law[FB_MECH_MAX_JOINTS], double tol,
                                  fb_stop *stop, fb_diag *diag);

/* What fb_reference_run_joints' planar path refuses, for case c's
 * [clearance] joints (the reference joint alone, none, or a planar case,
 * whose references the run floor integrates: FB_OK).
 * Errors: FB_ERR_ARG as fb_reference_run_joints. */
fb_status fb_reference_joints_check(const fb_case *c, fb_diag *diag);

/* fb_reference_run_joints' planar path at any clearance joints, the
 * reference joint alone too (its tests hold it to the closed form there).
 * Errors: as fb_reference_run_joints. */
fb_status fb_reference_run_planar(fb_series *out, size_t *steps, const fb_case *c,
                                  const fb_contact_law law[FB_MECH_MAX_JOINTS], double tol,
                                  fb_stop *stop, fb_diag *diag);

/* The phase of one joint's contact across a reference's samples. */
typedef struct {
  int state;       /* the last sample's FB_STATE_* */
  int restituting; /* 1: the force has fallen since the impact began */
} fb_contact_phase;

/* A reference's contact state at a sample of contact force force [N], the
 * previous sample's force_prev [N] (read while in contact): free at zero
 * force; an impact from the first sample in contact; continuous contact
 * when the force rises again after it fell within the impact (the
 * impact's phase from the force trend between samples, rising:
 * compression, falling: restitution, as the ODE scene classifies it from
 * the rate). Updates *p (start: {FB_STATE_FREE, 0}). */
int fb_reference_contact_state(fb_contact_phase *p, double force, double force_prev);

/* The tolerance fb_reference_run uses: FB_REFERENCE_TOL, or
 * FOURBAR_REFERENCE_TOL from the environment (convergence studies).
 * Errors: FB_ERR_RANGE when that is not a number in [MIN, MAX]. */
fb_status fb_reference_tolerance(double *tol, fb_diag *diag);

/* The reference's own error estimate: a second integration at
 * tol / FB_REFERENCE_CHECK_FACTOR (at most down to FB_REFERENCE_TOL_MIN)
 * compared with the first like a model with its reference
 * (fb_metrics_vs_reference): summary.json's error_estimate. At the
 * default 1e-12 the check runs at 1e-13 (the floor), a tenth, and costs
 * what the reference does (paper case: 18.3k against 18.2k steps per
 * revolution; docs/performance.md has the accuracy argument). */
#define FB_REFERENCE_CHECK_FACTOR 100.0

#endif
