/* The single impact through an engine's kit binding (kit_impact.c): one
 * body meets a flat wall, no gravity, in a world the binding builds as it
 * builds a mechanism's (kit.h: world_new, add_body, add_drive, add_contact,
 * step, body_state, contact_force). fourbar impact and contact-params
 * verify an engine's contact this way (engine.h's fb_engine_impact law):
 * the wall's row is the one the engine's clearance joints get, made by the
 * same binding call. SI throughout. */
#ifndef FB_KIT_IMPACT_H
#define FB_KIT_IMPACT_H

#include "impact.h"
#include "kit.h"

/* One body of mass d->mass [kg] (a sphere's moment of inertia, radius
 * 0.01 m, which a row through its centre never uses) starts touching the
 * wall y = 0 and moves into it at d->speed [m/s]; every step in contact
 * (depth -y > 0) hands the binding the contact of a flat wall
 * (fb_kit_contact with wall = 1: the body the pin, the ground the hole,
 * normal (0, -1), the point at the body's centre, effective mass d->mass),
 * the law d->law (its damper on d->mass) mapped to the step's soft row by
 * d->mapping (contact.h fb_contact_row_step: the matched-static row's
 * persistence from the contact's phase so far) for a binding that takes
 * rows. The world: gravity 0, step d->h, [solver] settings d->stepper,
 * d->quick_iterations, seed 1, the ideal joints' ERP 0.2 and CFM 1e-5
 * (none is built); c (optional, NULL: defaults) gives the engine's own
 * options (kit.h fb_kit_world.c). The force is the binding's
 * contact_force, the bookkeeping fb_impact_tally_force's.
 * b needs add_contact and contact_force, and no applied_force (the law is
 * handed as a row or a force the binding maps itself).
 * Errors: those of fb_impact_check; FB_ERR_ARG for a binding without them;
 * the binding's (FB_ERR_NUMERIC for an engine error, FB_ERR_NOMEM);
 * FB_ERR_NUMERIC on a non-finite state or when the body has not left the
 * contact after 100 estimated contact durations
 * (fb_impact_duration_estimate). */
fb_status fb_kit_impact(fb_impact_result *out, const fb_kit_binding *b, const fb_impact_def *d,
                        const fb_case *c, fb_diag *diag);

/* The body of d (mass, law, step, stepper, mapping; d->speed is not used)
 * at rest touching the wall at t = 0, a constant force load [N] pressing it
 * in from then on (the binding's apply_wrench, required), for duration [s]
 * (ceil(duration / h) steps); a step out of contact (depth <= 0) ends it,
 * and the next contact is a new one. *penetration receives the
 * depth at the end [m]: the law's static penetration F^-1(load) once the
 * motion has died out, for a row whose sustained-load stiffness is the
 * law's (secant, tangent, matched-static), and load / a for the matched row
 * (contact.h fb_contact_row_static). Errors: FB_ERR_RANGE for a bad d,
 * load or duration; FB_ERR_ARG for a binding without apply_wrench; the
 * binding's; FB_ERR_NUMERIC on a non-finite state. */
fb_status fb_kit_impact_static(double *penetration, const fb_kit_binding *b,
                               const fb_impact_def *d, double load, double duration,
                               const fb_case *c, fb_diag *diag);

/* One body of mass [kg] meets the wall at speed [m/s] (no gravity) with one
 * FIXED soft contact row, as a user pastes it into an engine: ERP erp [-]
 * and CFM cfm [m/(N s)] handed to the binding as the row (fb_kit_contact
 * has_row, depth the body's, frictionless), the world's contact correcting
 * speed limit speed_max [m/s] (ODE's contact_max_correcting_vel; INFINITY:
 * the engine's own, unlimited), step h [s] (ODE: dWorldStep); a row is
 * made whenever the depth is >= 0 (touching counts, as ODE's colliders
 * report it), and the bookkeeping is fb_impact_tally_depth's. Runs until
 * the body leaves or t_max [s]. onset_phase in [0, 1): where inside a step
 * the contact begins; 0: the body touches at t = 0; p > 0: it starts
 * (1 - p) h of free flight short of the crossing, so the first step that
 * sees the contact sees the depth p h v (times and depths are reported
 * from the crossing). b needs add_contact, contact_force and contact_rows,
 * and contact_speed_limit for a finite speed_max. Errors: FB_ERR_RANGE
 * (bad parameter or onset_phase, more than FB_IMPACT_MAX_STEPS steps),
 * FB_ERR_ARG (a binding without those), the binding's (FB_ERR_NUMERIC for
 * an engine error), FB_ERR_NUMERIC (non-finite state, still in contact at
 * t_max), FB_ERR_NOMEM. */
fb_status fb_kit_impact_row(fb_impact_result *out, const fb_kit_binding *b, double mass,
                            double speed, double h, double erp, double cfm, double speed_max,
                            double t_max, double onset_phase, fb_diag *diag);

#endif
