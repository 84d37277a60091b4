/* The single impact in MuJoCo (impact_mujoco.c; only in builds with MuJoCo,
 * FB_HAVE_MUJOCO). Reached from above the engines through the MuJoCo engine
 * table's impact op (engine.h, fb_engine_impact: row is fb_impact_mujoco);
 * the tests call it directly. */
#ifndef FB_IMPACT_MUJOCO_H
#define FB_IMPACT_MUJOCO_H

#include "impact.h"

/* The same impact in MuJoCo (builds with it; src/engines/mujoco/impact_mujoco.c):
 * a sphere of mass [kg] on a vertical slide joint meets a plane, both geoms
 * with the given solref and solimp (condim 1: frictionless), Euler
 * integrator, step h [s], no gravity.
 * onset_phase as for fb_kit_impact_row (kit_impact.h). Errors:
 * FB_ERR_RANGE (bad parameter or onset_phase), FB_ERR_NUMERIC, FB_ERR_NOMEM. */
fb_status fb_impact_mujoco(fb_impact_result *out, double mass, double speed, double h,
                           const double solref[2], const double solimp[5], double t_max,
                           double onset_phase, fb_diag *diag);

#endif
