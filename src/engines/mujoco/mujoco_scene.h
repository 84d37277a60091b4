/* The four-bar and the slider-crank in MuJoCo 2.2.2: the same scene definition as the ODE world
 * (ode_world.h: lengths, masses, inertias, gravity, drive, initial state from the
 * analytic solver, clearance joints and their contact laws), generated as
 * MJCF text and loaded from memory through MuJoCo's virtual file system. The
 * only folder that includes MuJoCo headers; this header includes none, so a
 * build without MuJoCo compiles every caller (FB_HAVE_MUJOCO in fb_config.h
 * says whether these functions exist). mujoco_scene_internal.h lists the
 * files the scene is made of (building, the MJCF text, loading, the
 * contact, the step, the outputs).
 *
 * Model (generalised coordinates, a kinematic tree):
 *   world -> crank (hinge A at the origin) -> coupler (hinge B at the crank
 *   pin); world -> follower (hinge D at (ground, 0)). Every hinge axis is +z,
 *   so the motion stays in the plane by construction. The loop is closed at C
 *   by a `connect` equality (coupler to follower) in MuJoCo's direct soft form:
 *   solref = (-k, -b), solimp = (d, d, 0.001, 0.5, 2); with k = 1/h^2, b = 1/h
 *   and d -> 1, one semi-implicit Euler step removes a violation entirely.
 *   Gravity along -y. Body frames: x along the link (crank A->B, coupler
 *   B->C, follower D->C), the centre of mass at com_fraction along x, the
 *   principal moments (long, transverse, hinge) on (x, y, z).
 *
 * The slider-crank (the case's [linkage] type = slider-crank; mechanism.h
 *   fb_mech_slider_crank): world -> crank (hinge A) -> coupler, the
 *   connecting rod (hinge B), as above; world -> slider, a body at the
 *   piston pin's hole centre H = (x0, offset) on a slide joint along +x (the
 *   guide: the tree holds the slider's y and angle exactly), its centre of
 *   mass at H. Ideal: the loop closed at the piston pin C by the same
 *   `connect` equality (rod to slider). Clearance at the piston pin (the only
 *   joint a slider-crank lets carry it): no equality, the project's law
 *   between the rod's pin site and the slider's hole site through
 *   mjcb_passive, or mujoco-clearance-native's bore tendon, as at any
 *   four-bar joint. The effective mass along the normal is 1 / (w^T M^-1 w)
 *   from the sites' Jacobians, the slide in M (no loop rows: the clearance
 *   opens the only loop). Samples: the slider's x, v, a from the slide's
 *   qpos (+ x0), qvel and qacc into body[1] (the follower's names alias
 *   them); reactions: at the guide the force on the ground from the slider,
 *   (0, -N) as the analytic engine writes it.
 *
 * Drive (exact to the flywheel's inertia): the crank hinge has an armature of
 *   fb_mujoco_opts.drive_armature (1e6 kg m^2 by default) and starts at the
 *   crank speed; with no motor, the reaction torques (~100 N m) change its
 *   speed by ~1e-4 rad/s^2, so the crank angle stays within ~1e-9 rad of
 *   theta0 + omega2 t over three revolutions; the run reports the crank-angle
 *   error (error_vs_analytic.crank_angle_err_max_rad) like ODE's. A velocity
 *   actuator was measured to diverge with euler and to leave 0.1-0.9 rad/s of
 *   speed error with implicit, so it is not used.
 *
 * Clearance joints (clearance_mask): the joint gets no hinge and no equality;
 *   the body that carries the hole (or the pin, for the ground joints) gets
 *   planar freedom instead (slide x, slide y, hinge z; the crank's drive
 *   armature sits on its hinge z). A site marks the pin centre on the pin
 *   body and one the hole centre on the hole body (ground: the world), as in
 *   the ODE world (pin on the joint's first body). MuJoCo's contact solver is
 *   not involved: the project's law (contact.h, fb_contact_force with the
 *   joint's fb_contact_law, exactly as the ODE world and the reference
 *   evaluate it) gives the normal force F(delta, ddot) from the site
 *   positions and velocities, and MuJoCo's passive-force hook (mjcb_passive)
 *   adds it as generalised forces -F J^T n, J = J_pin - J_hole from
 *   mj_jacSite, n = e/|e|. This is MuJoCo's integrator with the project's
 *   contact law, evaluated at every integrator stage (4 per rk4 step).
 *
 * MuJoCo's own constraint solver (mujoco-clearance-native; the model row's
 *   collider FB_COLLIDER_NATIVE), [mujoco] native_bore:
 *   - tendon (default): a spatial tendon from the hole's site to the pin's
 *     (length |e|) limited to [0, c]; MuJoCo adds one limit row along e when
 *     |e| > c. Its solref is the law's spring and damper in the force form,
 *     per unit of MuJoCo's diagonal approximation of the row's inverse mass
 *     at impedance 1e-4 (mujoco_contact.c, mujoco_native_solref_update), so the row's
 *     force is k delta + c ddot whatever else acts along e;
 *   - facets: the pin a sphere and the hole a ring of faceted_n boxes,
 *     collided by MuJoCo (filterparent disabled), with the direct form per
 *     unit of the effective mass at impedance 0.9999 (the study before the
 *     tendon; docs/engines.md).
 *   The passive-force hook then only measures (e, delta, ddot, J^T n for the
 *   effective mass); the contact force is read from MuJoCo's constraint
 *   forces.
 *
 * Stepping and sampling: a step integrates with the state's accelerations
 * (mj_Euler, mj_RungeKutta(4), or mj_step2 for implicit) and then runs
 * mj_forward at the new state, so every sample is instantaneous at
 * t = steps h: angles and angular velocities from the hinge coordinates,
 * angular accelerations from qacc (not differences of omega), the contact
 * force evaluated at the sample's state. Numerical trouble is not caught by
 * MuJoCo (mj_checkPos/Vel/Acc would silently reset the state): a NaN reaches
 * the sample and the caller stops the run. MuJoCo's fatal errors (mju_error)
 * print "fourbar: MuJoCo error: ..." and end the process with status 1. */
#ifndef FB_MUJOCO_SCENE_H
#define FB_MUJOCO_SCENE_H

#include <stddef.h>

#include "case.h"
#include "engine.h"
#include "scene.h"
#include "series.h"

typedef struct fb_mujoco_scene fb_mujoco_scene;

/* Writes the MJCF text of model sm (the scene definition with the model's
 * row applied) into buf (size bytes, NUL terminated): numbers printed with
 * 17 significant digits, so the compiled model holds the definition's
 * doubles. Errors: those of fb_scene_check; FB_ERR_RANGE when buf is too
 * small. */
fb_status fb_mujoco_mjcf(char *buf, size_t size, const fb_model_scene *sm, fb_diag *diag);


/* Checks the definition (fb_scene_check), compiles the model
 * (mj_loadXML from a VFS holding the MJCF text) and sets the state at t = 0
 * from the definition's assembled start (loop closed, velocities compatible,
 * pins centred in their holes). Uses the model's lengths, start and
 * clearance joints and laws, and the definition's crank speed, gravity,
 * masses, solver.h, radial clearance, impact_velocity_min and mujoco
 * options; ignores ODE's stepper, ERP/CFM, mapping and friction, and
 * faceted_n except for mujoco-clearance-native with native_bore = facets.
 * Errors: those of fb_scene_check; FB_ERR_ARG when MuJoCo rejects the
 * model (its message quoted); FB_ERR_NOMEM. */
fb_status fb_mujoco_scene_create(fb_mujoco_scene **out, const fb_model_scene *sm,
                                 fb_diag *diag);

/* Advances one step h. Errors: none today (FB_OK); NaN is reported through
 * the sample. */
fb_status fb_mujoco_scene_step(fb_mujoco_scene *s, fb_diag *diag);

/* Current state as a sample at t = steps h (see the header comment), with
 * the contact columns of the clearance joints: force [N] at this state,
 * penetration [m], eccentricity (x, y) [m], state (series.h). */
void fb_mujoco_scene_sample(const fb_mujoco_scene *s, fb_sample *x);

/* Loop-closure violation now: distance between the coupler's and the
 * follower's C points [m] (0 when C is a clearance joint). */
double fb_mujoco_scene_joint_drift(const fb_mujoco_scene *s);

/* Largest penetration over the clearance joints now [m] and its joint (-1
 * when there is no clearance joint). */
double fb_mujoco_scene_penetration(const fb_mujoco_scene *s, int *joint);

/* What the engine did at clearance joint j over the contact steps so far:
 * effective mass along the normal [kg] (range), h omega_c [-] (largest, with
 * the law's secant stiffness), contact steps; ERP and CFM are NaN (no
 * constraint row); NaN everywhere before the first contact. */
void fb_mujoco_scene_provenance(const fb_mujoco_scene *s, int j, fb_contact_provenance *out);

/* Joint reactions at the current state (instantaneous, like the sample),
 * with invdyn.h's convention: force[j] on the second-named body from the
 * first at joint A, B, C, D (x, y) [N] (at a clearance joint the contact
 * force), and the drive torque the flywheel gives the crank about +z,
 * -armature * crank alpha [N m]. From MuJoCo's mj_rnePostConstraint and the
 * connect equality's force. */
void fb_mujoco_scene_reactions(const fb_mujoco_scene *s, double force[4][2],
                               double *drive_torque);

/* Impact episodes counted so far at joint j. */
int fb_mujoco_scene_impacts(const fb_mujoco_scene *s, int j);

/* Steps taken. */
size_t fb_mujoco_scene_steps(const fb_mujoco_scene *s);

/* The MuJoCo steps taken: with [solver] h_s = adaptive their count,
 * shortest and longest size and how many of each; else every step h. */
void fb_mujoco_scene_step_stats(const fb_mujoco_scene *s, fb_step_stats *out);

/* The MJCF a user loads (fourbar export, docs/commands.md; the engine
 * table's export_model): model sm's
 * mechanism with bodies crank, coupler, follower (a slider-crank's: slider,
 * on a slide joint slider-ground along +x) (ground the world), joints
 * named after their joints (ground-crank, crank-coupler, follower-ground),
 * sites <joint>_pin and <joint>_hole at each joint's pin and hole centre
 * (crank-coupler_pin), the loop closed by an equality connect, each
 * clearance joint as mujoco-clearance-native's bore tendon (limited to the
 * radial clearance, solreflimit in the force form with MuJoCo's own
 * tendon_invweight0 and the damper of the law's restitution on its design
 * mass), the crank's flywheel armature and a velocity servo "drive" that
 * holds the case's speed at ctrl 0, a keyframe "start" (qvel), and a
 * comment at the top giving the start and the steps the file holds (the
 * loop's solref in the time-constant form that follows a user's timestep
 * up to 2 ms; mujoco_mjcf.c). Errors: those of
 * fb_scene_check; FB_ERR_ARG for a clearance model other than
 * mujoco-clearance-native or a text MuJoCo rejects; FB_ERR_RANGE when buf
 * is too small. */
fb_status fb_mujoco_export(char *buf, size_t size, const fb_model_scene *sm, fb_diag *diag);

/* MuJoCo's library version string ("2.2.2"). */
const char *fb_mujoco_version(void);

/* Frees the model and data (NULL is ignored). */
void fb_mujoco_scene_destroy(fb_mujoco_scene *s);

#endif
