/* The single impact in ODE (impact_ode.c): one free body meets the ground
 * plane, no gravity, in a world of its own. Reached from above the engines
 * through the ODE engine table's impact op (engine.h, fb_engine_impact: law
 * is fb_impact_ode, row is fb_impact_ode_row); the tests call these
 * directly. */
#ifndef FB_IMPACT_ODE_H
#define FB_IMPACT_ODE_H

#include "impact.h"

/* ODE: a free body meets the ground plane; every step in contact creates one
 * contact joint with soft ERP/CFM from fb_contact_linearize and
 * fb_contact_erp_cfm (dContactSoftERP | dContactSoftCFM, no bounce,
 * frictionless; contact max-correcting velocity and surface layer left at
 * their defaults, infinite and 0). Force from dJointGetFeedback.
 * Errors: FB_ERR_NUMERIC on a non-finite state or when the body has not left
 * the contact after 100 estimated contact durations. */
fb_status fb_impact_ode(fb_impact_result *out, const fb_impact_def *d, fb_diag *diag);

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
 * onset_phase in [0, 1): where inside a step the contact begins; 0: the body
 * touches at t = 0; p > 0: it starts (1 - p) h of free flight short of the
 * crossing, so the first step that sees the contact sees the depth p h v
 * (times and depths are reported from the crossing). Errors:
 * FB_ERR_RANGE (bad parameter or onset_phase), FB_ERR_NUMERIC (non-finite
 * state, ODE fatal check, still in contact at
 * t_max), FB_ERR_NOMEM. */
fb_status fb_impact_ode_row(fb_impact_result *out, double mass, double speed, double h, double erp,
                            double cfm, double max_vel, double t_max, double onset_phase,
                            fb_diag *diag);

#endif
