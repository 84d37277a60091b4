/* A planar mechanism in DART 6.12 (dartsim): the only header of the DART
 * engine the C side sees; dart_world.cpp, its implementation, is the only
 * code that includes DART. The kit's binding (dart_kit.c) calls it.
 *
 * How DART's experts build a mechanism with loops: a Skeleton is a set of
 * trees of BodyNodes, each joined to its parent (or to the world) by a
 * Joint with its own coordinates (RevoluteJoint about +z, PrismaticJoint
 * along an in-plane axis, PlanarJoint x, y, theta for a body no joint
 * holds); a loop is closed by a constraint of DART's constraint solver
 * (BallJointConstraint at the pin, as examples/rigid_loop closes its
 * chain). fb_dart_build takes the tree its caller chose (the kit's
 * fb_kit_tree), each joint out of it becoming a loop constraint (which
 * must therefore be a revolute joint). The world steps by semi-implicit Euler with velocity-level
 * impulses (World::step); the drive is a SERVO actuator, a velocity
 * motor the constraint solver keeps at its command within the force limit.
 * SI throughout; bodies and joints are numbered in the order added, the
 * ground is -1. Functions returning int give 0 on success, else -1 with a
 * message in err (size bytes). */
#ifndef FB_DART_WORLD_H
#define FB_DART_WORLD_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_dart_world fb_dart_world;

/* PGS run to convergence (fb_dart_world_new; the bare peer program
 * tests/peers/peer_dart.cpp is handed the same): at most this many sweeps,
 * stopping when no impulse changes by more than 1e-12 N s or by 1e-10 of
 * itself; measured on the Watt six-bar at h = 1e-5 s, the largest change of
 * any sample's alpha from DART's default (30 sweeps, 1e-6, 1e-3) is 123
 * rad/s^2, and none beyond 200 sweeps, 1e-12 and 1e-10 (1000, 1e-14, 1e-12
 * give the same samples) */
#define FB_DART_PGS_SWEEPS 200
#define FB_DART_PGS_DX 1e-12
#define FB_DART_PGS_REL_DX 1e-10

/* A world with gravity g [m/s^2] along -y, step h [s], the ideal joints'
 * ERP [-] (DART's global DynamicJointConstraint ERP), the drive's torque
 * limit [N m]; its constraint solver PGS run to convergence (Dantzig, DART's
 * default, fails on a planar loop's redundant out-of-plane row: dart_world.cpp);
 * NULL when out of memory. */
fb_dart_world *fb_dart_world_new(double g, double h, double erp, double drive_torque_max);

/* A body: mass [kg], moment about +z through the centre of mass [kg m^2]
 * (in-plane moments half of it each, a thin plate's), pose (centre x, y
 * [m], frame angle [rad]) and velocity (centre [m/s], omega [rad/s]). */
int fb_dart_add_body(fb_dart_world *w, double mass, double inertia, const double pos[3],
                     const double vel[3], char *err, size_t size);

/* A joint between bodies b0 and b1 (-1: the ground) at world point at [m];
 * prismatic: along the unit world axis (else a revolute joint about +z). */
int fb_dart_add_joint(fb_dart_world *w, int prismatic, int b0, int b1, const double at[2],
                      const double axis[2], char *err, size_t size);

/* Builds the skeleton from the bodies and joints added: tree[j] 1 for a
 * joint of the tree, 0 for one that closes a loop (its constraint); the
 * tree's joints' start velocities. Errors: a loop closed at a prismatic
 * joint; DART's exceptions. */
int fb_dart_build(fb_dart_world *w, const unsigned char *tree, char *err, size_t size);

/* Drives joint j (its index among those added) at rate [rad/s] of body b1
 * relative to body b0. Errors: j not a revolute joint of the tree. */
int fb_dart_drive(fb_dart_world *w, int j, double rate, char *err, size_t size);

/* Adds for the coming step force f [N] on body pin and -f on body hole
 * (-1: the ground, nothing), both at world point p [m] (DART's external
 * force, BodyNode::addExtForce). */
void fb_dart_add_force(fb_dart_world *w, int pin, int hole, const double p[2], const double f[2]);

/* A force (f[0], f[1]) [N] at body b's centre of mass and a torque f[2]
 * about +z [N m] for the coming World::step (fb_dart_step clears every
 * external force after it). */
void fb_dart_add_wrench(fb_dart_world *w, int b, const double f[3]);

/* Sets the step of the coming World::step calls to h [s] (World::setTimeStep:
 * the skeleton's and the constraint solver's). */
void fb_dart_set_step(fb_dart_world *w, double h);

/* One step of h (World::step); the external forces are cleared after it;
 * each joint's reaction over it is added to those fb_dart_reaction
 * averages. Errors: DART's exceptions, a non-finite state. */
int fb_dart_step(fb_dart_world *w, char *err, size_t size);

/* Starts the steps fb_dart_reaction averages anew. */
void fb_dart_reactions_clear(fb_dart_world *w);

/* Joint j's (its index among those added) reaction, the mean over the
 * steps since fb_dart_reactions_clear (0 before one), each step's taken at
 * the poses it started from: the force on its body b1 from its body b0
 * (x, y) [N] and the moment about +z at its point on b1 (on b0 when b1 is
 * the ground) [N m]. A joint of the tree gives the wrench its child's
 * BodyNode holds from its parent after the step (BodyNode::getBodyForce,
 * which Joint::getWrenchToChildBodyNode turns to the joint's frame: the
 * forward dynamics' transmitted force plus the constraint impulses over
 * the step, the servo's included); a revolute joint's moment is so its
 * coordinate's force, the drive's torque or 0. A loop's pin gives its
 * BallJointConstraint's impulse over the step, no moment. */
void fb_dart_reaction(const fb_dart_world *w, int j, double out[3]);

/* Body b's pose (centre of mass x, y [m], angle [rad]) and velocity. */
void fb_dart_body_state(const fb_dart_world *w, int b, double pos[3], double vel[3]);

/* The loop constraints fb_dart_build made (BallJointConstraint). */
int fb_dart_loops(const fb_dart_world *w);

void fb_dart_world_free(fb_dart_world *w);

#ifdef __cplusplus
}
#endif

#endif
