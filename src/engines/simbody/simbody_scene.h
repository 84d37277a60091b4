/* The Simbody scene: one simbody-* model as a Simbody MultibodySystem,
 * integrated by one of Simbody's error-controlled integrators. The only
 * header of the Simbody engine the C side sees; the implementation (the
 * C++ files simbody_internal.h lists) is the only code that includes
 * Simbody.
 *
 * The mechanism (SI, planar in x-y, every mobilizer a Pin about +z):
 *
 *        B_pin (crank)  B_hole (coupler)       C
 *            o . . . . . o======================o
 *           /   clearance: Force::Custom       ||  Pin (coupler on follower)
 *  crank   /    ideal: Constraint::Ball        ||  follower
 *  Pin +  /     (the loop closure)             ||
 *  Motion (angle)                              ||
 *        A (origin)                            D (ground, +x)  Pin
 *
 * The tree is cut at the crank-coupler joint B: ground -> crank (Pin, speed
 * prescribed as theta0 + omega2 t by a position-level Motion), ground -> follower (Pin at D), follower ->
 * coupler (Pin at C). The ideal models close the loop with a
 * Constraint::Ball at B (its out-of-plane row is redundant; Simbody's
 * constraint solver tolerates redundant rows); the clearance models leave
 * B free (two degrees of freedom, the reference's theta3, theta4) and apply
 * the project's contact law (contact.h, fb_contact_force) as a
 * Force::Custom at the exact pin-in-hole eccentricity, with the restitution
 * law's damper on the mechanism's effective mass along the normal
 * (effective_mass.h), as ODE's world, MuJoCo's and the reference do.
 *
 * The slider-crank (fb_mech_slider_crank, a case's [linkage] type =
 * slider-crank):
 *
 *                  B  Pin (rod on crank)
 *                 / \
 *          crank /   \ rod (coupler)
 *     Pin +     /     \
 *     Motion   A       P o H [slider]  Slider mobilizer along +x
 *                 - - - - - - - - - -  guide y = offset
 *
 * ground -> crank (Pin at A, the same Motion), crank -> rod (Pin at B),
 * ground -> slider (a Slider mobilizer along +x on the guide line y =
 * offset, the slider's frame and centre of mass at its hole centre H). A
 * loop needs one joint as a constraint whatever the tree; it is cut at the
 * piston pin, the one joint that may carry clearance, as the four-bar is
 * cut at B: the guide stays a mobilizer (exact: the slider never leaves its
 * line or turns, and its x, v, a are the Slider's own q, u, udot), the
 * ideal models close the loop with a Constraint::Ball between the rod's pin
 * centre P and H, and the clearance models drop it for the contact law
 * between the pin P (on the rod) and the hole H (on the slider), the rod
 * and the slider then free (the reference's theta3 and x). The effective
 * mass is the piston pin's (fb_effective_mass_tensor with the guide
 * prismatic, prismatic_mask = 1 << 3). The other cut, a Pin tree through
 * the piston pin (ground -> crank -> rod -> slider) with the guide as a
 * Constraint::PointInPlane (and a ConstantAngle for the slider's turn), is
 * as accurate (measured on cases/slider_crank_flores.ini, reports at every
 * 2 us, rkmerson 1e-6: both within 1.3e-6 of the analytic peaks of the
 * rod's omega and alpha and the slider's v and a; the slider off its line
 * by 1.4e-7 m there, the pin open by 1.7e-7 m here) but cannot carry the
 * piston pin's clearance, and its slider x is no mobility the grid's
 * Hermite interpolant could take.
 *
 * Sampling (simbody_scene.cpp says how): the integrator runs on its own
 * error-controlled steps to the run's end, returning after each; the output
 * grid k h is filled between its steps by Simbody's cubic Hermite
 * interpolant (accelerations its derivative), and the samples around a
 * peak of a velocity, acceleration or load are realized exactly, as Simbody
 * realizes an interpolated report. Contact episodes (episode.h) are updated
 * at every step end, and the sample at k h holds the extremes of the contact
 * force, penetration and angular accelerations over the step ends of
 * ((k-1) h, k h] in intervals with contact, so peaks and impacts between
 * samples are kept. */
#ifndef FB_SIMBODY_SCENE_H
#define FB_SIMBODY_SCENE_H

#include <stddef.h>

#include "engine.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_simbody_scene fb_simbody_scene;

/* Builds model sm's system at t = 0 (the four-bar or the slider-crank, by
 * the case's mechanism) and initialises the integrator (sm->simbody:
 * integrator and accuracy). Errors: those of fb_scene_check and
 * fb_model_scene_start; FB_ERR_ARG for clearance at a joint other than the
 * four-bar's crank-coupler or the slider-crank's coupler-slider (the tree is
 * cut there only);
 * FB_ERR_NUMERIC when Simbody refuses the multibody system, with its message;
 * FB_ERR_NOMEM. */
fb_status fb_simbody_scene_create(fb_simbody_scene **out, const fb_model_scene *sm,
                                  fb_diag *diag);

/* Advances to the next sample time (the integrator runs ahead of it by a
 * few of its steps, to find the peaks). Errors: FB_ERR_NUMERIC when the
 * integrator fails or spends its step budget (fb_simbody_scene_stopped says
 * which), reported at the first sample it could not reach. */
fb_status fb_simbody_scene_step(fb_simbody_scene *s, fb_diag *diag);

/* Why the last step failed (FB_STOP_NONE when it did not). */
void fb_simbody_scene_stopped(const fb_simbody_scene *s, fb_stop *out);

/* The state at the last sample time (see the header comment for peaks). */
void fb_simbody_scene_sample(const fb_simbody_scene *s, fb_sample *x);

/* Penetration at the clearance joint now [m] (the four-bar's crank-coupler,
 * the slider-crank's coupler-slider) and impacts so far. */
void fb_simbody_scene_contact(const fb_simbody_scene *s, fb_engine_contact *out);

/* Effective mass range over the contact evaluations so far (NAN for the
 * mapping figures Simbody has none of: ERP, CFM, h omega). */
void fb_simbody_scene_provenance(const fb_simbody_scene *s, int joint, fb_contact_provenance *out);

/* Joint reactions (invdyn.h's convention: on the second-named body; the
 * slider-crank's slider_crank_invdyn.h, its guide's the force on the ground
 * from the slider, (0, -N)) and the drive torque on the crank about +z
 * [N m], at the last sample. */
void fb_simbody_scene_reactions(const fb_simbody_scene *s, double force[4][2],
                                double *drive_torque);

/* Distance between the cut joint's two points [m] for the ideal models (the
 * Ball constraint's violation: the four-bar's crank and coupler B points,
 * the slider-crank's rod pin and slider hole); 0 for the clearance models. */
double fb_simbody_scene_drift(const fb_simbody_scene *s);

/* The integrator's accepted steps so far. */
size_t fb_simbody_scene_steps(const fb_simbody_scene *s);

/* Wall time so far in the integrator's own steps (Integrator::stepTo) [s]:
 * the engine's stepping, apart from filling the output grid (the
 * interpolation and the exact samples). */
double fb_simbody_scene_stepping_s(const fb_simbody_scene *s);

/* Samples so far that were realized exactly (next to a local extreme of an
 * acceleration or a load, and the run's first and last) instead of
 * interpolated between the integrator's steps. */
size_t fb_simbody_scene_exact_samples(const fb_simbody_scene *s);

/* Frees s (NULL is ignored). */
void fb_simbody_scene_destroy(fb_simbody_scene *s);

#ifdef __cplusplus
}
#endif

#endif
