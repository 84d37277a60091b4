/* The four-bar in ODE: crank, coupler and follower as rigid bodies joined by
 * four ideal hinges (axis +z), gravity along -y in the mechanism plane, the
 * crank driven at constant speed by a hinge velocity motor. The only module
 * that includes ODE headers; it owns the world and its joints.
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
 * through the world CFM > 0, and tests check the joint drift stays small. */
#ifndef FB_SCENE_H
#define FB_SCENE_H

#include "case.h"
#include "series.h"

typedef struct fb_scene fb_scene;

/* Everything a scene needs, in SI units. */
typedef struct {
  fb_linkage lengths;   /* link lengths [m] */
  fb_branch branch;     /* assembly branch of the initial configuration */
  double crank_angle0;  /* crank angle at t = 0 [rad] */
  double omega2;        /* signed crank speed [rad/s] */
  double gravity;       /* along -y [m/s^2] */
  fb_link_mass link[3]; /* crank, coupler, follower */
  fb_solver solver;     /* step size, stepper, ERP/CFM, drive torque, seed */
} fb_scene_def;

/* Builds the world at t = 0 with positions and velocities from the analytic
 * solver, so the run starts consistent (loop closed, velocities compatible).
 * Errors: FB_ERR_ASSEMBLY when the initial configuration does not exist;
 * FB_ERR_NOMEM. */
fb_status fb_scene_create(fb_scene **out, const fb_scene_def *def, fb_diag *diag);

/* Advances one step h with the configured stepper. Errors: FB_ERR_NOMEM if
 * ODE could not allocate its step memory. */
fb_status fb_scene_step(fb_scene *s, fb_diag *diag);

/* Current state as a sample at time t = steps * h: unwrapped angles, angular
 * velocities, and angular accelerations as (omega_now - omega_before) / h,
 * the acceleration the last step applied. Before the first step the
 * accelerations are 0. */
void fb_scene_sample(const fb_scene *s, fb_sample *x);

/* Largest distance between the two bodies' anchor points over the four hinges
 * now [m]: the loop-closure drift of the constrained system. */
double fb_scene_joint_drift(const fb_scene *s);

/* Joint reactions applied during the last step, from dJointGetFeedback, with
 * fb_reactions' sign convention (invdyn.h): force[j] on the second-named body
 * at joint A, B, C, D (x, y) [N], and the drive torque on the crank about +z
 * [N m]. They belong to the configuration at the start of that step. Zero
 * before the first step. */
void fb_scene_reactions(const fb_scene *s, double force[4][2], double *drive_torque);

/* Steps taken. */
size_t fb_scene_steps(const fb_scene *s);

/* Frees the world and everything in it (NULL is ignored). */
void fb_scene_destroy(fb_scene *s);

#endif
