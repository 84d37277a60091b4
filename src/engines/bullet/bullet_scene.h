/* The four-bar and the slider-crank in Bullet 3.24 (double precision, bullet-float64): the same
 * scene definition as the ODE world (ode_world.h: lengths, masses, inertias,
 * gravity, drive, start state, clearance joints and their contact laws),
 * built as three btRigidBody links in a btDiscreteDynamicsWorld. The only
 * folder that includes Bullet headers, and the only C++ in the project:
 * bullet_scene.cpp implements these functions with C linkage; this header
 * includes no Bullet header, so every caller is C11 (FB_HAVE_BULLET in
 * fb_config.h says whether these functions exist).
 *
 * Bodies: each link a btRigidBody (btEmptyShape, no collision pairs) with
 *   the definition's mass and principal moments (long, transverse, hinge)
 *   on its (x, y, z), x along the link; linear factor (1, 1, 0) and angular
 *   factor (0, 0, 1) keep it in the plane exactly (Bullet zeroes the other
 *   freedoms' impulses), so no out-of-plane rows are needed. Gyroscopic
 *   flags off (planar rotation about a principal axis has none), no damping,
 *   no sleeping.
 *
 * Ideal joints: a planar pin constraint (btTypedConstraint subclass, two
 *   rows x and y at the joint point, velocity-level with ERP
 *   [solver] world_erp on the position error, CFM 0). Four pins and the
 *   drive give 9 rows on 9 freedoms: no redundant row, so the direct MLCP
 *   is regular (btHingeConstraint's 5 rows per joint would over-constrain
 *   the planar loop by 3 rows per joint, as ODE's hinges do; its angular
 *   rows would also meet zeroed freedoms). docs/engines.md, "Bullet".
 *
 * Drive: one angular velocity row on the crank about +z (target omega2,
 *   impulse limited to [solver] drive_torque_max_n_m h), as ODE's hinge
 *   velocity motor: crank speed exact to the solver's tolerance.
 *
 * Clearance joints: no pin constraint; each step, from the exact pin-in-hole
 *   eccentricity (as ODE's exact collider), one unilateral soft row (a
 *   btTypedConstraint whose getInfo2 sets m_constraintError = ERP depth / h,
 *   cfm, limits [0, inf), like an ODE contact joint) carrying the ERP/CFM of
 *   the law's row for this step (fb_contact_row_step: the same mapping code
 *   as ODE's contact, matched on the true effective mass along the normal,
 *   effective_mass.h). Bullet's joint rows do not include their CFM in the
 *   row's diagonal (convertJoint), so the solvers are subclassed to treat
 *   these rows as Bullet treats its own contacts' CFM (diagonal + CFM / h,
 *   btSequentialImpulseConstraintSolver::setupContactConstraint; for the
 *   MLCP the diagonal of A): the row then solves
 *   J v_{n+1} = ERP depth / h - CFM lambda, ODE's contact row, with lambda
 *   the row's force.
 *
 * The slider-crank (the case's [linkage] type = slider-crank,
 *   fb_mech_slider_crank): crank and connecting rod as the four-bar's crank
 *   and coupler (planar bodies, pin rows at A and B, the same drive row);
 *   the slider a btRigidBody free in 3-D (linear and angular factors 1)
 *   with its centre of mass at its hole centre H = (x, offset), held on its
 *   guide by a btSliderConstraint to the world along +x (Bullet's prismatic
 *   joint: rows y, z and the rotations about y and z; about x only once it
 *   turns, which nothing in the plane makes it do), its ERP set to
 *   [solver] world_erp (setParam BT_CONSTRAINT_STOP_ERP), CFM 0. A
 *   btSliderConstraint on a planar-factored body would leave rows on zeroed
 *   freedoms (a zero diagonal in the MLCP); the 3-D slider has none. The
 *   piston pin (joint C) is a pin row pair, or the clearance contact with
 *   the pin on the rod and the hole on the slider, as any clearance joint.
 *   Samples: the slider's x, v and a = (v_{n+1} - v_n) / h in the second
 *   output body's slots; its effective mass (matched mapping, restitution
 *   damper) with the guide as effective_mass.h's prismatic joint D at the
 *   slider's centre; its reaction at slider-ground is the force on the
 *   ground, minus the guide's on the slider (btJointFeedback).
 *
 * Stepping and sampling: stepSimulation(h, 0) (one step of exactly h;
 *   semi-implicit Euler, rotations by the exponential map), then samples as
 *   ODE's: angles and angular velocities at t = steps h, angular
 *   accelerations (omega_now - omega_before) / h and the contact force of the
 *   step (step_values_lag). */
#ifndef FB_BULLET_SCENE_H
#define FB_BULLET_SCENE_H

#include <stddef.h>

/* the project's headers are C: C linkage for them and for these functions */
#ifdef __cplusplus
extern "C" {
#endif

#include "engine.h"
#include "impact.h"
#include "scene.h"
#include "series.h"

typedef struct fb_bullet_scene fb_bullet_scene;

/* Builds the world of model sm at t = 0 from its start (fb_model_scene_start).
 * Uses the model's lengths, start, clearance joints and laws, the mapping,
 * solver.h, world_erp, drive_torque_max, radial clearance,
 * impact_velocity_min and the bullet options; ignores ODE's stepper and
 * world_cfm, friction and the MuJoCo options. Errors: those of
 * fb_scene_check; FB_ERR_ARG for a collider other than the exact one;
 * FB_ERR_NOMEM. */
fb_status fb_bullet_scene_create(fb_bullet_scene **out, const fb_model_scene *sm, fb_diag *diag);

/* Advances one step h. Errors: FB_ERR_NUMERIC when a matched row passes the
 * aliasing bound (stopped() says FB_STOP_ALIASED, as ODE's scene), and when
 * btMLCPSolver's Dantzig solve fails and Bullet falls back to sequential
 * impulse (FB_STOP_SOLVER: the step is not the direct solver's; measured:
 * no fallback on the paper case at h = auto and 1e-5 s). */
fb_status fb_bullet_scene_step(fb_bullet_scene *s, fb_diag *diag);

/* Why the last step failed (FB_STOP_NONE while none did). */
void fb_bullet_scene_stopped(const fb_bullet_scene *s, fb_stop *out);

/* Current state as a sample at t = steps h (see the header comment; a
 * slider-crank's body[1] holds the slider's x [m], v [m/s], a [m/s^2]). */
void fb_bullet_scene_sample(const fb_bullet_scene *s, fb_sample *x);

/* Largest distance between the two bodies' points of an ideal joint, or of
 * the slider's centre from its guide line [m]. */
double fb_bullet_scene_joint_drift(const fb_bullet_scene *s);

/* Largest penetration over the clearance joints now [m] and its joint (-1
 * without clearance joints). */
double fb_bullet_scene_penetration(const fb_bullet_scene *s, int *joint);

/* What the contact rows of clearance joint j received so far (engine.h). */
void fb_bullet_scene_provenance(const fb_bullet_scene *s, int j, fb_contact_provenance *out);

/* Joint reactions of the last step with fb_ode_world_reactions' convention
 * (ode_world.h) [N] (a slider-crank's slider-ground: the force on the ground
 * from the slider, (0, -N) with N the guide's normal force on the slider
 * along +y, as the analytic engine's), and the drive row's torque on the
 * crank about +z [N m]. */
void fb_bullet_scene_reactions(const fb_bullet_scene *s, double force[4][2], double *drive_torque);

/* Impact episodes counted so far at joint j. */
int fb_bullet_scene_impacts(const fb_bullet_scene *s, int j);

/* Steps taken. */
size_t fb_bullet_scene_steps(const fb_bullet_scene *s);

/* Frees the world (NULL is ignored). */
void fb_bullet_scene_destroy(fb_bullet_scene *s);

/* Bullet's version number (btGetVersion(): 324 for 3.24). */
int fb_bullet_version(void);

/* The single impact in Bullet is the kit binding's (kit_impact.h); through
 * Bullet's own contact, impact_bullet.h. */

#ifdef __cplusplus
}
#endif

#endif
