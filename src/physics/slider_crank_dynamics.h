/* Dynamics of the slider-crank with a revolute clearance joint at the
 * piston pin (coupler-slider), in minimal coordinates: the engine-free
 * reference for the slider-crank's clearance models, as reference.h is for
 * the four-bar's crank-coupler joint.
 *
 *                  B                 P = B + coupler u(theta3): the rod's pin centre
 *                 / \                H = (x, offset): the slider's hole centre
 *          crank /   \ coupler       e = P - H, |e| <= c in free flight
 *               /     \
 *              A      (P)H  ---- guide y = offset ---->
 *
 * The crank is driven at constant speed, theta2(t) = theta0 + omega2 t, so
 * B(t) = crank u(theta2(t)) is prescribed. The crank-coupler joint and the
 * slider's guide are ideal; the piston pin has radial clearance c. The rod
 * turns about the moving B and the slider slides freely along the guide, so
 * the generalised coordinates are q = (theta3, x): the rod angle (direction
 * B->P) and the slider's position. With u = (cos theta3, sin theta3),
 * u' = (-sin theta3, cos theta3), f3 the rod's centre-of-mass fraction:
 *   G3 = B + f3 b u,  P = B + b u,  H = (x, offset),
 * and Kane's equations (partial velocities f3 b u' of G3, b u' of P, (1, 0)
 * of H) are, without coupling between the two coordinates:
 *   (m3 (f3 b)^2 + I3) theta3'' = -m3 f3 b u'.(B'' + g y) - F b u'.n,
 *   m4 x''                      = F n_x,
 * with B'' = -crank omega2^2 u(theta2), n = e / |e|, penetration
 * delta = |e| - c and the contact law's normal force F (contact.h) acting on
 * the slider along +n and on the rod along -n (the pin pushes the hole
 * outward). The penetration rate is delta' = n . (P' - H'),
 * P' = B' + b theta3' u', H' = (x', 0). Gravity (along -y) loads the rod
 * and, through the guide, the slider (N = m4 g - F n_y, not a coordinate).
 * Derivation ours (Kane's method, as reference.h for the four-bar; the
 * clearance geometry of Flores and Ambrosio, docs/contact.md);
 * tests/test_slider_crank.c checks it against an independent formulation
 * in absolute coordinates with Lagrange multipliers, against the ideal
 * kinematics in the zero-clearance limit, and by its energy balance.
 *
 * Energy. The crank feeds the rod at B with the power F_B . B', F_B the
 * force on the rod from the crank; the law's damping removes
 * (F - F_el) delta' (F_el its elastic part, fb_contact_force at zero rate).
 * So E = T_rod + T_slider + m3 g G3_y + V_el(delta) obeys
 * E(t) - E(0) = W_in(t) - W_damp(t); fb_sc_dyn_run integrates both works
 * with the state so that the balance can be checked. V_el = F_el delta /
 * (n + 1) for the laws' elastic part F_el = K delta^n (n = 1 for the linear
 * and restitution laws).
 *
 * Hysteresis laws (Lankarani-Nikravesh, Hunt-Crossley, Flores, Gonthier)
 * scale their damping by 1 / v0, v0 the impact velocity at contact onset;
 * this right-hand side takes v0 as a fixed parameter (impact_velocity) and
 * does not track each impact's onset: exact for the Hertz, linear, impact
 * and restitution laws, which need no v0. */
#ifndef FB_SLIDER_CRANK_DYNAMICS_H
#define FB_SLIDER_CRANK_DYNAMICS_H

#include <stddef.h>

#include "contact.h"
#include "slider_crank_invdyn.h"

/* The model: a slider-crank, its masses, the drive and the clearance joint. */
typedef struct {
  fb_slider_crank geometry;   /* crank, coupler, offset [m] */
  fb_slider_crank_mass mass;  /* the crank's entries enter only the drive torque */
  double gravity;             /* along -y [m/s^2], >= 0 */
  double clearance;           /* radial clearance c at the piston pin [m], >= 0 */
  fb_contact_law law;         /* normal-force law at the piston pin (contact.h) */
  double impact_velocity;     /* v0 of the hysteresis laws [m/s], > 0 (see above) */
  double theta0;              /* crank angle at t = 0 [rad] */
  double omega2;              /* constant crank speed [rad/s] (signed) */
} fb_sc_dyn_model;

/* Size of the state y: theta3 [rad], x [m], theta3' [rad/s], x' [m/s]. */
#define FB_SC_DYN_DIM 4

/* Checks geometry (a full-turning crank), masses, the rod's inertia about B
 * and the slider's mass (both > 0: the equations divide by them), gravity,
 * clearance, impact velocity and the law (fb_contact_law_check).
 * Errors: FB_ERR_RANGE or FB_ERR_ASSEMBLY naming the field, value and rule. */
fb_status fb_sc_dyn_check(const fb_sc_dyn_model *m, fb_diag *diag);

/* Everything the equations of motion compute at one state. */
typedef struct {
  double dydt[FB_SC_DYN_DIM]; /* theta3', x', theta3'', x'' (SI) */
  double ecc[2];              /* eccentricity e = P - H [m] (x, y) */
  double penetration;         /* max(|e| - c, 0) [m] */
  double penetration_rate;    /* delta' = n . e' [m/s] (also out of contact) */
  double force;               /* contact force magnitude F >= 0 [N] */
  double elastic_force;       /* the law's elastic part at delta (zero rate) [N] */
  double effective_mass;      /* 1 / (w^T M^-1 w) along n, w = J_e^T n [kg]; +inf at e = 0 */
  double guide_force;         /* N on the slider from the guide, along +y [N] */
  double crank_force[2];      /* F_B on the rod from the crank (x, y) [N] */
  double drive_torque;        /* on the crank from ground, about +z [N m] */
  double power_in;            /* F_B . B' [W] */
  double power_damping;       /* (F - F_el) delta' [W] (>= 0 while the law damps) */
} fb_sc_dyn_eval;

/* Evaluates the equations of motion at time t [s] and state y (4); for the
 * restitution law the damper's mass is the effective mass along n, as in
 * reference.c. Pure: no allocation, no state. m must have passed
 * fb_sc_dyn_check and its law should be prepared (fb_contact_law_prepare)
 * so that the restitution law's damping ratio is not solved at every call. */
void fb_sc_dyn_eval_at(fb_sc_dyn_eval *out, const fb_sc_dyn_model *m, double t, const double y[]);

/* The ideal slider-crank (no clearance) at the crank direction
 * (cos theta2, sin theta2): the origin of the deviation state below. */
typedef struct {
  double u3[2]; /* the rod's direction (cos theta3, sin theta3) [-] (2) */
  double x;     /* the slider's position [m] */
  double w3;    /* the rod's angular velocity [rad/s] */
  double v;     /* the slider's velocity [m/s] */
} fb_sc_dyn_origin;

/* fb_slider_crank_solve's position and velocity (slider_crank.h) from the
 * crank's direction instead of its angle; m must have passed fb_sc_dyn_check. */
void fb_sc_dyn_origin_at(fb_sc_dyn_origin *o, const fb_sc_dyn_model *m, double c2, double s2);

/* fb_sc_dyn_eval_at in deviation form, for long integrations at tolerances
 * near round-off (reference.c): the crank given by its direction (c2, s2)
 * = (cos theta2, sin theta2) and the state yd = (theta3 - theta3i, x - xi,
 * theta3', x'), the positions as deviations from the ideal motion's
 * (fb_sc_dyn_origin_at) and the speeds absolute. The eccentricity is then
 * b (u(theta3) - u(theta3i)) - (x - xi, 0) (planar_turn.h), free of the
 * cancellation of P - H between coordinates of the mechanism's size, which
 * in the absolute form leaves ~1e-17 m of rounding noise that the contact's
 * stiffness turns into noise in the accelerations. out->dydt[0..1] are the
 * deviations' rates (theta3' - theta3i', x' - xi'); the rest as
 * fb_sc_dyn_eval_at's at the same instant. */
void fb_sc_dyn_eval_dev(fb_sc_dyn_eval *out, const fb_sc_dyn_model *m, double c2, double s2,
                        const double yd[]);

/* The right-hand side in the form of GSL's gsl_odeiv2_system function
 * (params: a const fb_sc_dyn_model *); returns 0 (GSL_SUCCESS). */
int fb_sc_dyn_rhs(double t, const double y[], double dydt[], void *params);

/* Mechanical energy at (t, y) [J]: the rod's and slider's kinetic energy,
 * the rod's potential in gravity (zero at y = 0; the slider's height is
 * fixed) and the law's elastic energy V_el (see above). */
typedef struct {
  double kinetic;   /* [J] */
  double gravity;   /* [J] */
  double elastic;   /* [J] */
  double total;     /* sum [J] */
} fb_sc_dyn_energy;

void fb_sc_dyn_energy_at(fb_sc_dyn_energy *out, const fb_sc_dyn_model *m, double t,
                         const double y[]);

/* The start with the pin held at eccentricity ecc0 (pin minus hole, |ecc0|
 * <= c) in the ideal motion ("steady": the pin moves with its hole): the
 * rod and slider of the ideal slider-crank whose guide is offset by ecc0_y,
 * at theta0 and omega2 (fb_slider_crank_solve), with x = its C_x - ecc0_x.
 * ecc0 = (0, 0) starts on the ideal kinematics. y0 receives (4).
 * Errors: FB_ERR_RANGE when |ecc0| > c; those of fb_slider_crank_solve. */
fb_status fb_sc_dyn_start(double y0[FB_SC_DYN_DIM], const fb_sc_dyn_model *m,
                          const double ecc0[2], fb_diag *diag);

/* One sample of a run. */
typedef struct {
  double t;                /* [s] */
  double crank_angle;      /* theta2 [rad] */
  double coupler_angle;    /* theta3 [rad] */
  double coupler_omega;    /* [rad/s] */
  double coupler_alpha;    /* [rad/s^2] */
  double slider_x;         /* [m] */
  double slider_v;         /* [m/s] */
  double slider_a;         /* [m/s^2] */
  double force;            /* contact force at the piston pin [N] */
  double penetration;      /* [m] */
  double ecc[2];           /* eccentricity [m] (x, y) */
  double guide_force;      /* [N] */
  double drive_torque;     /* [N m] */
  double energy;           /* fb_sc_dyn_energy total [J] */
  double work_in;          /* integral of power_in from t = 0 [J] */
  double work_damping;     /* integral of power_damping from t = 0 [J] */
} fb_sc_dyn_sample;

/* Accepted integrator steps allowed per output sample, on average over the
 * run, when fb_sc_dyn_run is given max_steps = 0: the four-bar reference's
 * budget (FB_REFERENCE_STEPS_PER_SAMPLE) for output steps near the
 * contact's own time scale. */
#define FB_SC_DYN_STEPS_PER_SAMPLE 200

/* Integrates from y0 at t = 0 with GSL's rk8pd (gsl_odeiv2_step_rk8pd),
 * relative and absolute tolerance tol in [1e-13, 1e-3] (as the four-bar
 * reference), with the works W_in and W_damp as two more states, and
 * samples at t = k h, k = 0 .. n - 1, into out (n samples, caller-owned).
 * *steps (may be NULL) receives the accepted steps. max_steps bounds them
 * (0: n FB_SC_DYN_STEPS_PER_SAMPLE).
 * Errors: FB_ERR_RANGE for tol, h or n out of range; those of
 * fb_sc_dyn_check and fb_contact_law_prepare; FB_ERR_NUMERIC when the
 * integrator fails, the step budget runs out or the state stops being
 * finite (message names the time; the samples before it are filled and
 * *done, if not NULL, says how many). */
fb_status fb_sc_dyn_run(fb_sc_dyn_sample *out, size_t n, double h, const double y0[FB_SC_DYN_DIM],
                        const fb_sc_dyn_model *m, double tol, size_t max_steps, size_t *steps,
                        size_t *done, fb_diag *diag);

#endif
