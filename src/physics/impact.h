/* Single-impact fidelity: one body of mass m meets one contact at speed v0
 * (no gravity) and the normal-force law acts until it lets go. The
 * engine-free answers to the question: an adaptive high-accuracy
 * integration of the law (GSL rk8pd) and closed forms where they exist
 * (undamped Hertz-type power law; linear spring-dashpot and the restitution
 * law); the definition and result types every engine's single impact uses,
 * and the bookkeeping they share. Each engine's own single impact (ODE with
 * the law mapped into ERP/CFM every step, ...) is in its folder, reached
 * through its engine table's impact op (engine.h, fb_engine_impact). */
#ifndef FB_IMPACT_H
#define FB_IMPACT_H

#include <stddef.h>

#include "case.h"
#include "contact.h"

/* Highest impact speed [m/s]: pins in mechanisms hit at well under 10 m/s;
 * far beyond, the elastic laws here stop describing the contact (plastic
 * flow), and the duration estimate leaves double range sooner. */
#define FB_IMPACT_SPEED_MAX_M_S 100.0

/* A faithful single impact of an engine's contact (issue 39's acceptance,
 * docs/contact-params.md): its restitution within 1 % and its peak
 * penetration within 2 % of the continuous law's. `fourbar contact-params`
 * verifies a step with them (FB_CP_*), and a verdict holds a model's first
 * impact in a run, a single impact of the same law before any chaos, to the
 * penetration's (verdict_stats.h) [-]. */
#define FB_FAITHFUL_RESTITUTION_TOL 0.01
#define FB_FAITHFUL_PENETRATION_TOL 0.02
/* Range of the estimated contact duration [s] an impact may have: below 1e-12
 * s the penetration is a few ulps of the position; above 1e3 s the "impact"
 * is a quasi-static load, not an impact. */
#define FB_IMPACT_DURATION_MIN_S 1e-12
#define FB_IMPACT_DURATION_MAX_S 1e3
/* Most engine steps one impact may take: about 10 s at ODE's 1 us per step, the
 * same order as [run] max_wall_s's default for a run. */
#define FB_IMPACT_MAX_STEPS 1e7

/* Smallest coefficient of restitution of the Flores and Gonthier laws, whose
 * damping factor grows as 1/cr (8 (1 - cr) / (5 cr), (1 - cr^2) / cr): at
 * cr = 1e-3 the impact lasts about 38 undamped contact durations (measured:
 * 0.0121 s against 3.2e-4 s at K = 1e10 N/m^1.5, 1 kg, 1 m/s), within the
 * 100 the reference follows; at 1e-4 it does not end there, and at 1e-300
 * the factor leaves double range. */
#define FB_IMPACT_CR_MIN_DIVERGENT 1e-3
/* Largest damping ratio c / (2 sqrt(k m)) of a linear damper (the linear
 * law's c, the IMPACT law's c_max with the tangent stiffness at d_max): the
 * damper then stops the body within m / c = 1 / (1000 omega_c), a thousandth
 * of the spring's time, as fine as the smallest step contact-params tries
 * (h omega_c = 0.001); beyond, no step follows the contact and the
 * engines' ERP/CFM arithmetic leaves double range (c = 1e300: inf, nan). */
#define FB_IMPACT_DAMPING_RATIO_MAX 500.0

/* The words naming each input in fb_impact_check's messages: the flags of
 * the command that took them (fb_impact_flag_names: --stiffness, ...), or
 * a case's keys; NULL members read "stiffness", "mass", ... */
typedef struct {
  const char *stiffness, *restitution, *damping, *mass, *speed, *h;
} fb_impact_names;

/* fourbar impact's and contact-params' flags */
extern const fb_impact_names fb_impact_flag_names;

typedef struct {
  const fb_impact_names *names; /* what names each input in messages (NULL: plain words) */
  fb_contact_law law;  /* normal-force law (law.mass is set to mass) */
  double mass;         /* body mass m [kg] */
  double speed;        /* impact speed v0 [m/s] > 0 */
  double h;            /* the engine's step size [s] */
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
  size_t steps;            /* engine steps or integrator output steps */
  double wall_s;           /* [s] */
} fb_impact_result;

/* Checks the definition: the law (Flores and Gonthier: cr >=
 * FB_IMPACT_CR_MIN_DIVERGENT; a linear damper's ratio <=
 * FB_IMPACT_DAMPING_RATIO_MAX), mass, speed (<= FB_IMPACT_SPEED_MAX_M_S),
 * h, the estimated contact duration (FB_IMPACT_DURATION_MIN_S to _MAX_S) and
 * the step count it gives (<= FB_IMPACT_MAX_STEPS). Errors: FB_ERR_RANGE
 * naming the parameter (by d->names) and the rule. */
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
