/* Single-impact fidelity: one body of mass m meets one contact at speed v0
 * (no gravity) and the normal-force law acts until it lets go. Three answers
 * to the same question: ODE with the law mapped into ERP/CFM every step
 * (impact_ode.c), an adaptive high-accuracy integration of the same law
 * (GSL rk8pd), and closed forms where they exist (undamped Hertz-type power
 * law; linear spring-dashpot and the restitution law). */
#ifndef FB_IMPACT_H
#define FB_IMPACT_H

#include <stddef.h>

#include "case.h"
#include "contact.h"

/* Highest impact speed [m/s]: pins in mechanisms hit at well under 10 m/s;
 * far beyond, the elastic laws here stop describing the contact (plastic
 * flow), and the duration estimate leaves double range sooner. */
#define FB_IMPACT_SPEED_MAX_M_S 100.0
/* Range of the estimated contact duration [s] an impact may have: below 1e-12
 * s the penetration is a few ulps of the position; above 1e3 s the "impact"
 * is a quasi-static load, not an impact. */
#define FB_IMPACT_DURATION_MIN_S 1e-12
#define FB_IMPACT_DURATION_MAX_S 1e3
/* Most ODE steps one impact may take: about 10 s at ODE's 1 us per step, the
 * same order as [run] max_wall_s's default for a run. */
#define FB_IMPACT_MAX_STEPS 1e7

typedef struct {
  fb_contact_law law;  /* normal-force law (law.mass is set to mass) */
  double mass;         /* body mass m [kg] */
  double speed;        /* impact speed v0 [m/s] > 0 */
  double h;            /* ODE step size [s] */
  fb_stepper stepper;  /* dWorldStep or dWorldQuickStep */
  int quick_iterations;
  fb_mapping mapping;  /* per-step linearisation of the law */
} fb_impact_def;

/* What one impact produced. */
typedef struct {
  double penetration_max;  /* [m] */
  double contact_duration; /* time with a positive contact force [s] */
  double force_max;        /* [N] */
  double restitution;      /* exit speed / impact speed [-] */
  size_t steps;            /* ODE steps or integrator output steps */
  double wall_s;           /* [s] */
} fb_impact_result;

/* Checks the definition: the law, mass, speed (<= FB_IMPACT_SPEED_MAX_M_S),
 * h, the estimated contact duration (FB_IMPACT_DURATION_MIN_S to _MAX_S) and
 * the step count it gives (<= FB_IMPACT_MAX_STEPS). Errors: FB_ERR_RANGE
 * naming the parameter and the rule. */
fb_status fb_impact_check(const fb_impact_def *d, fb_diag *diag);

/* Closed form where one exists: returns 1 and fills out for undamped Hertz
 * (any exponent n: delta_max = ((n + 1) m v0^2 / (2 K))^(1/(n+1)),
 * T = 2 delta_max / v0 * sqrt(pi) Gamma(1 + 1/(n+1)) / Gamma(1/2 + 1/(n+1)),
 * so T = 2.943 delta_max / v0 for n = 1.5; Goldsmith 1960 / Johnson 1985
 * sec. 11.4) and for the linear and restitution laws (damped oscillator that
 * separates where k delta + c ddot = 0); returns 0 otherwise. */
int fb_impact_closed_form(fb_impact_result *out, const fb_impact_def *d);

/* Reference: m delta'' = -F(delta, delta', v0) integrated with GSL's rk8pd
 * (relative tolerance 1e-12), sampled 4000 times per estimated contact
 * duration, the end of contact located by bisection to 1e-13 of it, and
 * peaks refined by a parabola through the three samples around each.
 * Errors: FB_ERR_NUMERIC if the integrator fails. */
fb_status fb_impact_reference(fb_impact_result *out, const fb_impact_def *d, fb_diag *diag);

/* ODE: a free body meets the ground plane; every step in contact creates one
 * contact joint with soft ERP/CFM from fb_contact_linearize and
 * fb_contact_erp_cfm (dContactSoftERP | dContactSoftCFM, no bounce,
 * frictionless; contact max-correcting velocity and surface layer left at
 * their defaults, infinite and 0). Force from dJointGetFeedback.
 * Errors: FB_ERR_NUMERIC on a non-finite state or when the body has not left
 * the contact after 100 estimated contact durations. */
fb_status fb_impact_ode(fb_impact_result *out, const fb_impact_def *d, fb_diag *diag);

/* Bullet (src/engines/bullet/impact_bullet.cpp; only in builds with Bullet,
 * FB_HAVE_BULLET): one free body of mass d->mass
 * meets the ground through the same soft row as the clearance joints
 * (one row per step in contact, ERP/CFM of fb_contact_row_step with
 * d->mapping on the body's mass), solved by bt->solver with bt->iterations.
 * d->mapping = FB_MAPPING_SECANT (or tangent) on a linear or restitution law
 * is exactly Bullet's own conversion of a contact stiffness k and damping c
 * (btSequentialImpulseConstraintSolver::setupContactConstraint with
 * BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING: erp = h k / (h k + c),
 * cfm = 1 / (h k + c)); FB_MAPPING_MATCHED the project's matched row.
 * d->stepper and d->quick_iterations are not used. Errors: those of
 * fb_impact_check; FB_ERR_NUMERIC on a non-finite state or when the body has
 * not left the contact after 100 estimated contact durations. */
fb_status fb_impact_bullet(fb_impact_result *out, const fb_impact_def *d,
                           const fb_bullet_opts *bt, fb_diag *diag);

/* The same impact through Bullet's own contact (builds with Bullet,
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

/* ODE under a sustained load: the body of d (mass, law, step, stepper,
 * mapping; d->speed is not used) rests touching the contact at t = 0 and a
 * constant force load [N] presses it in from then on, for duration [s]
 * (ceil(duration / h) steps). *penetration receives the depth at the end
 * [m]: the law's static penetration F^-1(load) once the motion has died
 * out, for a row whose sustained-load stiffness is the law's (secant,
 * tangent, matched-static), and load / a for a matched row
 * (fb_contact_row_static). Errors: FB_ERR_RANGE for a bad d, load or
 * duration; FB_ERR_NUMERIC on a non-finite state or an ODE fatal check. */
fb_status fb_impact_ode_static(double *penetration, const fb_impact_def *d, double load,
                               double duration, fb_diag *diag);

/* One body of mass [kg] meets the ground plane at speed [m/s] (no gravity)
 * with one FIXED contact row, as a user pastes it into an engine: ODE with
 * soft ERP erp and CFM cfm [m/(N s)] (dContactSoftERP | dContactSoftCFM,
 * frictionless, no bounce), world contact_max_correcting_vel max_vel [m/s]
 * (INFINITY: ODE's default) and surface layer 0, step h [s]; a row is
 * created whenever the depth is >= 0 (touching counts, as ODE's colliders
 * report it). Runs until the body leaves or t_max [s].
 * onset_phase as for fb_impact_bullet_contact. Errors:
 * FB_ERR_RANGE (bad parameter or onset_phase), FB_ERR_NUMERIC (non-finite
 * state, ODE fatal check, still in contact at
 * t_max), FB_ERR_NOMEM. */
fb_status fb_impact_ode_row(fb_impact_result *out, double mass, double speed, double h, double erp,
                            double cfm, double max_vel, double t_max, double onset_phase,
                            fb_diag *diag);

/* The same impact in MuJoCo (builds with it; src/engines/mujoco/impact_mujoco.c):
 * a sphere of mass [kg] on a vertical slide joint meets a plane, both geoms
 * with the given solref and solimp (condim 1: frictionless), Euler
 * integrator, step h [s], no gravity.
 * onset_phase as for fb_impact_bullet_contact. Errors:
 * FB_ERR_RANGE (bad parameter or onset_phase), FB_ERR_ARG in a build without
 * MuJoCo (how to enable it in the message), FB_ERR_NUMERIC, FB_ERR_NOMEM. */
fb_status fb_impact_mujoco(fb_impact_result *out, double mass, double speed, double h,
                           const double solref[2], const double solimp[5], double t_max,
                           double onset_phase, fb_diag *diag);

/* The bookkeeping every engine's single impact shares, step by step: peak
 * penetration and force into an fb_impact_result, the contact's end, and
 * when the body has left. Zero-initialise, then call one of the two rules
 * after each step with the state at its end. */
typedef struct {
  int in_contact;    /* the contact has begun */
  int done;          /* the body has left: stop stepping */
  double t_end;      /* end of the contact [s] (the result's contact_duration) */
  double prev_depth; /* depth after the step before [m] */
} fb_impact_tally;

/* Force rule (engines whose contact force is known per step: ODE's world
 * impact, Bullet's): a step whose force [N] > 0 is in contact, and the
 * contact ends with it, or where the depth [m] crosses zero inside it
 * (linear interpolation); the body has left once the force is gone, or the
 * depth is <= 0, while it moves out (v_out [m/s] > 0). t1 [s] is the time
 * at the step's end, h [s] its length. */
void fb_impact_tally_force(fb_impact_tally *t, fb_impact_result *out, double t1, double h,
                           double depth, double force, double v_out);

/* Depth rule (a fixed row created whenever the depth >= 0, MuJoCo's
 * contacts): in contact once the depth [m] > 0; the contact ends, and the
 * body has left, where the depth crosses below zero (interpolated). force
 * [N] only enters the peak. */
void fb_impact_tally_depth(fb_impact_tally *t, fb_impact_result *out, double t1, double h,
                           double depth, double force);

/* Estimated contact duration [s] used for sampling and default steps: the
 * undamped closed form of the law's elastic part. */
double fb_impact_duration_estimate(const fb_impact_def *d);

#endif
