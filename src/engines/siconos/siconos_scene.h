/* The Siconos scene: one siconos-* model as a Siconos nonsmooth dynamical
 * system: a LagrangianDS with Lagrangian relations, integrated by
 * Moreau-Jean's event-capturing time stepping. The only header of the
 * Siconos engine the C side sees; the implementation (siconos_scene.cpp) is
 * the only translation unit that includes Siconos.
 *
 * Coordinates: q = (theta3, theta4), the coupler's and the follower's
 * absolute angles, the reference's minimal coordinates (reference.h). The
 * follower turns about D, the coupler hangs from it at the ideal joint C:
 *
 *   C = D + c u(theta4),  B_hole = C - b u(theta3)  (u(x) = (cos x, sin x))
 *
 * The crank is prescribed, theta2(t) = theta0 + omega2 t, exactly: it is no
 * coordinate, and enters only through the relations at the crank-coupler
 * joint B, whose pin centre B_pin(t) = a u(theta2(t)) moves with time. So
 * those relations are rheonomous (LagrangianRheonomousR: h(q, t), its
 * Jacobian dh/dq and its time derivative dh/dt):
 *
 *   ideal models:    h(q, t) = B_hole(q) - B_pin(t) = 0    (2 rows,
 *                    EqualityConditionNSL: the loop closed by a bilateral
 *                    constraint, solved as an Equality problem)
 *   clearance model: g(q, t) = c - |e|,  e = B_pin(t) - B_hole(q),  g >= 0
 *                    (NewtonImpactNSL with e_N = [clearance] restitution,
 *                    an LCP; with [clearance] friction > 0 a second row, the
 *                    sliding velocity of the pin's surface on the hole's at
 *                    the contact point, and NewtonImpactFrictionNSL with
 *                    Coulomb's mu, a 2-D FrictionContact problem)
 *
 * The Lagrangian dynamics M(q) q'' + F(q, q') = p (the reference's
 * mass matrix, quadratic velocity terms and gravity, with their Jacobians for
 * Moreau-Jean's Newton iteration) are integrated by MoreauJeanOSI(theta),
 * theta = [siconos] theta, at the fixed step h = [solver] h_s, by
 * TimeStepping with its Newton loop. The impulse lambda of a step is a
 * percussion: the contact force reported is lambda / h (the step's mean
 * force), and an impact is one step whose velocity jump obeys Newton's law
 * g'(t+) = -e_N g'(t-).
 *
 * With [siconos] scheme = combined-projection the integrator is
 * MoreauJeanCombinedProjectionOSI(theta) and the simulation
 * TimeSteppingCombinedProjection (Acary, CMAME 256, 2013; Siconos's
 * slider-crank example's scheme): a step that ends with a relation closed
 * (g <= 0) is redone with it in the velocity problem, then the positions of
 * every relation the step closed (and the ideal models' loop closure) are
 * projected onto the constraints by MLCPProjectOnConstraints, to 1e-10 m;
 * the friction problem, when there is one, is the same 2-D FrictionContact.
 * A projection that does not converge stops the model (FB_STOP_SOLVER).
 *
 * Sampling: one sample per step. The angular accelerations are
 * (omega_{k+1} - omega_k) / h and the contact force and state those of the
 * step from t_k: the engine reports them one step late (step_values_lag), as
 * ODE. Clearance at a joint other than crank-coupler is refused.
 *
 * The slider-crank (a case with [linkage] type = slider-crank) is built the
 * same way on the reference's coordinates q = (theta3, x)
 * (slider_crank_dynamics.h): the rod's angle about the driven crank pin
 * B(t) = a u(theta2(t)) and the slider's hole centre's x along the guide,
 * H = (x, offset) (the guide is in the coordinates: the slider neither
 * leaves it nor turns), M = diag(m3 (f3 b)^2 + I3, m4), and the crank pin's
 * acceleration and gravity on the rod as F(t, q). The relation is written
 * at the piston pin, the rod's pin P = B(t) + b u(theta3) in the slider's
 * hole H:
 *
 *   ideal models:    h(q, t) = P(q, t) - H(q) = 0   (2 rows, EqualityConditionNSL)
 *   clearance model: g(q, t) = c - |e|, e = P - H, g >= 0 (NewtonImpactNSL,
 *                    e_N = [clearance] restitution; with friction a second
 *                    row, NewtonImpactFrictionNSL, as above)
 *
 * and its Newton loop also checks Newton's law at the step's end (the
 * relation's residual, siconos_scene.cpp LawCheckedMoreauJeanOSI). Samples:
 * the rod's angle, omega and alpha in body[0], the slider's x, v and a in
 * body[1] (accelerations as above), the contact columns at the piston pin
 * (joint 2, coupler-slider). Clearance at another joint is refused (the
 * case refuses it first). */
#ifndef FB_SICONOS_SCENE_H
#define FB_SICONOS_SCENE_H

#include <stddef.h>

#include "engine.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_siconos_scene fb_siconos_scene;

/* Builds model sm's nonsmooth dynamical system at t = 0 (sm->siconos:
 * theta), the four-bar's or the slider-crank's (the case's mechanism).
 * Errors: those of fb_scene_check and fb_model_scene_start; FB_ERR_ARG for
 * clearance at a joint other than crank-coupler (four-bar) or
 * coupler-slider (slider-crank), or another mechanism;
 * FB_ERR_NUMERIC when Siconos refuses the system, with its message;
 * FB_ERR_NOMEM. */
fb_status fb_siconos_scene_create(fb_siconos_scene **out, const fb_model_scene *sm, fb_diag *diag);

/* Advances one step h. Errors: FB_ERR_NUMERIC when Siconos throws, its
 * Newton loop does not converge or its one-step problem fails
 * (fb_siconos_scene_stopped says which). */
fb_status fb_siconos_scene_step(fb_siconos_scene *s, fb_diag *diag);

/* Why the last step failed (FB_STOP_NONE when it did not). */
void fb_siconos_scene_stopped(const fb_siconos_scene *s, fb_stop *out);

/* The state at the last step's end (see the header comment for the values
 * that belong to the step). */
void fb_siconos_scene_sample(const fb_siconos_scene *s, fb_sample *x);

/* Penetration at the clearance joint now (crank-coupler, or the
 * slider-crank's coupler-slider), max(0, |e| - c) [m], and impacts so far. */
void fb_siconos_scene_contact(const fb_siconos_scene *s, fb_engine_contact *out);

/* The effective mass along the normal, 1 / (w^T M^-1 w) with w = J_hole^T n,
 * over the steps with a contact impulse (NAN for ERP, CFM and h omega_c: a
 * rigid contact has none). */
void fb_siconos_scene_provenance(const fb_siconos_scene *s, int joint, fb_contact_provenance *out);

/* Distance between the crank's and the coupler's B points [m] for the ideal
 * models (the bilateral constraint's violation; the slider-crank's: between
 * the rod's pin and the slider's hole); 0 for the clearance model. */
double fb_siconos_scene_drift(const fb_siconos_scene *s);

/* Steps taken. */
size_t fb_siconos_scene_steps(const fb_siconos_scene *s);

/* Frees s (NULL is ignored). */
void fb_siconos_scene_destroy(fb_siconos_scene *s);

#ifdef __cplusplus
}
#endif

#endif
