/* The four-bar in ODE: crank, coupler and follower as rigid bodies joined by
 * four ideal hinges (axis +z), gravity along -y in the mechanism plane, the
 * crank driven at constant speed by a hinge velocity motor. It owns the
 * world and its joints; engine_ode.c puts it behind the engine interface
 * (engine.h), and nothing outside src/engines/ode includes this header.
 * ode_world_internal.h lists the files the world is made of (building,
 * the exact contact, the generic colliders, the step, the outputs).
 *
 * The world is built from the case's mechanism description (mechanism.h),
 * joint by joint in its order: a revolute joint is a hinge, or with
 * clearance the pin-in-hole contact below; a prismatic joint is ODE's slider
 * joint (dJointCreateSlider, axis +x, to the ground). The slider-crank:
 *
 *                  B            crank A-B hinged to the ground at A (driven),
 *                 / \           the connecting rod (the coupler body) hinged
 *          crank /   \ rod      to the crank at B, the slider a body at the
 *               /     \         piston pin's hole centre H = (x, offset)
 *              A      [H]--->x  held by the slider joint (its y and its
 *                               rotation: 5 rows), and at the piston pin C
 *   a hinge (ideal models) or the clearance contact (pin on the rod, hole on
 *   the slider; body 2 plays the follower's part). The slider's centre of
 *   mass is at H; its inertias are the case's but do not enter (the slider
 *   joint holds its rotation). Its samples are x, v and a along +x
 *   (fb_sample body[1]), its acceleration (v_now - v_before) / h like the
 *   angular ones. Loop: 3 hinges and the slider joint give 20 rows for 18
 *   freedoms + 1 mobility, the same 3 redundant rows as the four-bar's.
 *
 * Crank drive: the ground hinge's motor (dParamVel = omega2, dParamFMax =
 * drive_torque_max) is a velocity constraint row solved with the others each
 * step, so the crank speed is exact to the solver's tolerance and its angle
 * integrates exactly as theta0 + omega2 t (semi-implicit Euler on a constant
 * velocity). The drive torque it needs is available through joint feedback.
 * A kinematic crank body would also be exact but hides the drive torque and
 * the crank's inertia from the equations, so the motor is used.
 *
 * The planar loop of four 3-D hinges is over-constrained (20 rows for 18
 * body freedoms + 1 mobility: 3 redundant out-of-plane rows); ODE copes
 * through the world CFM > 0, and tests check the joint drift stays small.
 *
 * Clearance joints: a joint in clearance_mask gets no hinge. The pin is fixed
 * to the joint's first body (ground-crank: crank; crank-coupler: crank;
 * coupler-follower: coupler; follower-ground: follower) and the hole to the
 * second (ground for A and D). Every step, the eccentricity e = pin centre -
 * hole centre is computed exactly from the two bodies (Flores and Ambrosio's
 * formulation, docs/contact.md); when |e| exceeds the radial clearance c, one
 * contact joint is created directly (no ODE geometry: the pin-in-hole pair is
 * concave and its exact penetration, normal and point are known in closed
 * form, so a collider would only add cost and error) with soft ERP/CFM from
 * the joint's law mapped at the current penetration (contact.h), normal along
 * -e/|e| into the pin, point on the hole wall, no bounce; contact max-correcting
 * velocity and surface layer stay at ODE's defaults (infinite, 0), which the
 * exact mapping needs. A clearance ground-crank joint keeps the drive through
 * an angular motor (dJointCreateAMotor, z axis) at the crank speed. A body left
 * with no hinge at all is kept in the plane by dJointCreatePlane2D.
 *
 * Faceted variant (FB_COLLIDER_FACETED, faceted_n > 0), ODE's generic path for comparison: the hole
 * is a ring of n boxes (2 mm thick, inner faces tangent to the hole circle) and
 * the pin an ODE cylinder, collided by dCollide (box-cylinder); every contact
 * ODE reports gets the law's spring-damper at its own depth divided by the
 * number of contacts of the step (n contact rows on one penetration act as
 * parallel springs). Contact point and normal come from the collider.
 *
 * libccd variant (FB_COLLIDER_CCD, ccd_segments > 0), the generic collider (collide_ccd.h):
 * the bore a ring of ccd_segments convex segments tangent to the hole circle
 * (or to an ellipse, bore_ovality > 0), the pin a convex cylinder, contacts
 * from ccdMPRPenetration in the hole body's frame, at most FB_CCD_CONTACTS
 * per joint and step (the deepest). The law is evaluated once per step at the
 * deepest contact (depth delta*, rate ddot*), as the exact model evaluates it
 * at the one penetration, and its spring-damper is split over the contacts in
 * proportion to their depths (w_i = delta_i / sum delta_j: every row gets
 * the one row's ERP and depth and CFM / w_i, since scaling a row's spring and
 * damper, or the matched mapping's a and b, by w scales 1/CFM by w and leaves
 * ERP = h a / b alone): the rows together push with the
 * law's force along the depth-weighted normal, so the split cannot change the
 * force when a shallow contact appears or goes. ccd_split = 1 selects the
 * faceted model's rule instead (each contact at its own depth, divided by
 * their number), kept to measure the difference. The penetration the world
 * reports is the pin's depth into the faceted bore (fb_ccd_bore_depth). */
#ifndef FB_ODE_WORLD_H
#define FB_ODE_WORLD_H

#include "effective_mass.h"
#include "engine.h"
#include "scene.h"
#include "series.h"
#include "start.h"

typedef struct fb_ode_world fb_ode_world;

/* Builds the world of model sm->model at t = 0 from sm->start (start.h:
 * pins and holes placed, the case's start velocities) or, when the start was
 * moved (start_given 0), with positions and velocities from the analytic
 * solver (loop closed, velocities compatible, pins centred). Checks
 * the definition first (fb_scene_check). The model's collider picks the
 * clearance contact: FB_COLLIDER_EXACT (eccentricity), FB_COLLIDER_FACETED
 * (ring of faceted_n boxes) or FB_COLLIDER_CCD (libccd ring of ccd_segments). Errors: those of fb_scene_check;
 * FB_ERR_ARG for a collider this engine lacks; FB_ERR_NOMEM. */
fb_status fb_ode_world_create(fb_ode_world **out, const fb_model_scene *sm, fb_diag *diag);

/* Advances one step h with the configured stepper. Errors: FB_ERR_NOMEM if
 * ODE could not allocate its step memory. */
fb_status fb_ode_world_step(fb_ode_world *s, fb_diag *diag);

/* Current state as a sample at time t = steps * h (contact columns of the
 * clearance joints included): unwrapped angles, angular
 * velocities, and angular accelerations as (omega_now - omega_before) / h,
 * the acceleration the last step applied (a slider-crank's slider: x [m],
 * v [m/s] and (v_now - v_before) / h [m/s^2] in body[1]). Before the first
 * step the accelerations are 0. */
void fb_ode_world_sample(const fb_ode_world *s, fb_sample *x);

/* Largest distance between the two bodies' anchor points over the hinges
 * now [m], and the slider's distance from the guide line it started on: the
 * loop-closure drift of the constrained system. */
double fb_ode_world_joint_drift(const fb_ode_world *s);

/* Joint reactions applied during the last step, from dJointGetFeedback, with
 * fb_reactions' sign convention (invdyn.h): force[j] on the second-named body
 * at joint A, B, C, D (x, y) [N], and the drive torque on the crank about +z
 * [N m]. They belong to the configuration at the start of that step. Zero
 * before the first step. At a clearance joint the force is the contact force
 * of the last step (zero in free flight); the drive torque is reported only
 * when the ground-crank joint is a hinge (0 otherwise). A slider-crank's
 * slider-ground joint reports the force on the ground from the slider, minus
 * the slider joint's force on the slider: (0, -N), N the guide's normal
 * force along +y, as slider_crank_invdyn.h and the analytic model. */
void fb_ode_world_reactions(const fb_ode_world *s, double force[4][2], double *drive_torque);

/* Largest penetration over the clearance joints now [m] and the joint it is
 * at (-1 when there is no clearance joint). */
double fb_ode_world_penetration(const fb_ode_world *s, int *joint);

/* Impact episodes counted so far at joint j (contact onsets whose penetration
 * rate was at least impact_velocity_min). */
int fb_ode_world_impacts(const fb_ode_world *s, int j);

/* Calls of ccdMPRPenetration made by the libccd collider of every clearance
 * joint so far, and the contacts they returned (both 0 on the other paths). */
void fb_ode_world_ccd_calls(const fb_ode_world *s, unsigned long *calls, unsigned long *contacts);

/* Most contacts the libccd collider hands to ODE per joint and step. */
#define FB_CCD_CONTACTS 2

/* Why the last step failed: FB_STOP_SOLVER (ODE's internal check, its
 * message as detail) or FB_STOP_ALLOCATION; FB_STOP_NONE while none did. */
void fb_ode_world_stopped(const fb_ode_world *s, fb_stop *out);

/* What the contact rows of clearance joint j received so far (engine.h). */
void fb_ode_world_provenance(const fb_ode_world *s, int j, fb_contact_provenance *out);

/* Steps taken. */
size_t fb_ode_world_steps(const fb_ode_world *s);

/* The ODE steps taken: with [solver] h_s = adaptive their count, shortest
 * and longest size and how many of each (a grid sample inside a step is not
 * a step); else every step h. */
void fb_ode_world_step_stats(const fb_ode_world *s, fb_step_stats *out);

/* The mechanism's configuration now, for fb_effective_mass_tensor: body
 * masses and inertias from the definition, centres of mass from ODE, joint
 * centres from the hinge anchors and, for clearance joints, the pin centre;
 * a slider-crank's guide (slider-ground) is prismatic (prismatic_mask bit
 * 3) at the slider's position, its centre of mass and hole centre; the
 * crank counts as driven (its motor is a velocity constraint). */
void fb_ode_world_mechanism(const fb_ode_world *s, fb_mechanism *out);

/* ODE test-force probe of the inverse effective mass [1/kg] of clearance
 * joint j along unit normal n (pin centre minus hole centre direction): from
 * the current state, one dWorldStep with a force pair force [N] (-force n on
 * the pin, +force n on the hole, at the pin centre) and one without; the
 * change of the penetration rate n . (v_pin - v_hole) at the pin centre is
 * -h force / m_eff. The state is restored afterwards and no step is counted.
 * Errors: FB_ERR_ARG when j is not a clearance joint or force is not
 * positive; FB_ERR_NOMEM when ODE cannot step. */
fb_status fb_ode_world_probe_inverse_mass(fb_ode_world *s, int j, const double n[2], double force,
                                      double *inv_mass, fb_diag *diag);

/* Frees the world and everything in it (NULL is ignored). */
void fb_ode_world_destroy(fb_ode_world *s);

#endif
