/* A fixed contact row's single impact in ODE (impact_ode.c): one free body
 * meets the ground plane, no gravity, in a world of its own, with the ERP
 * and CFM a user pastes into ODE. Reached from above the engines through
 * the ODE engine table's impact op (engine.h, fb_engine_impact: row is
 * fb_impact_ode_row; law is the kit binding's, kit_impact.h); the tests
 * call it directly. */
#ifndef FB_IMPACT_ODE_H
#define FB_IMPACT_ODE_H

#include "impact.h"

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
