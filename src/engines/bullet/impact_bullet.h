/* The single impact through Bullet's own contact (impact_bullet.cpp; only
 * in builds with Bullet, FB_HAVE_BULLET): one body meets the ground, no
 * gravity. Reached from above the engines through the Bullet engine
 * table's impact op (engine.h, fb_engine_impact: row is
 * fb_impact_bullet_contact; law is the kit binding's, kit_impact.h); the
 * tests call it directly. */
#ifndef FB_IMPACT_BULLET_H
#define FB_IMPACT_BULLET_H

/* the project's headers are C: C linkage for them and for these functions */
#ifdef __cplusplus
extern "C" {
#endif

#include "impact.h"

/* One body's impact through Bullet's own contact (builds with Bullet,
 * FB_HAVE_BULLET; src/engines/bullet/impact_bullet.cpp): a sphere of mass [kg] meets
 * a static plane at speed [m/s] (no gravity, frictionless, restitution 0),
 * the sphere's btCollisionObject::setContactStiffnessAndDamping(stiffness
 * [N/m], damping [N s/m]) and the plane's (BT_LARGE_FLOAT, 0), split impulse
 * off, linear slop 0, SOR 1, step h [s]; Bullet turns them into erp =
 * h k / (h k + c), cfm = 1 / (h k + c) (btSequentialImpulseConstraintSolver::
 * setupContactConstraint); the sphere's contact processing threshold 0 (no
 * speculative points). Runs until the body leaves or t_max [s].
 * onset_phase in [0, 1): where inside a step the contact begins; 0: the body
 * touches at t = 0; p > 0: it starts (1 - p) h of free flight short of the
 * crossing, so the first step that sees the contact sees the depth p h v
 * (times and depths are reported from the crossing). Errors: FB_ERR_RANGE (a parameter
 * not positive, h k + c <= 0, onset_phase outside [0, 1), more than
 * FB_IMPACT_MAX_STEPS steps),
 * FB_ERR_NUMERIC (non-finite state, still in contact at t_max). */
fb_status fb_impact_bullet_contact(fb_impact_result *out, double mass, double speed, double h,
                                   double stiffness, double damping, double t_max,
                                   double onset_phase, fb_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
