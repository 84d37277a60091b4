/* What a planar reference needs beyond a driven pin in a hole (run floor,
 * planar_ref_model.c calls it): an undriven case's initial angular
 * velocities and a prismatic clearance joint's slider in its guide, from
 * the case (docs/planar.md), and the rule on their contact law.
 *
 * The rule: the penalty sources physical and goldsmith take a pin's
 * radius and its largest ideal reaction over a revolution; a slider's
 * corner against a flat wall has no pin radius, and an undriven case no
 * revolution to take a reaction over. There the case gives its law's
 * stiffness ([clearance] penalty = explicit with stiffness_impact_n_m1_5
 * or penalty_n_m), and the law's working force is reported as 0. */
#ifndef FB_PLANAR_FREE_H
#define FB_PLANAR_FREE_H

#include "case.h"
#include "planar.h"
#include "planar_guide.h"

/* What run needs for the clearance joints clear (njoints; 1 at each) of m,
 * described by case c: *guide (njoints, each prismatic clearance joint's
 * entry filled; NULL unless one is prismatic) and *omega0 (nbodies
 * [rad/s]; NULL unless m is undriven), owned by the caller (free());
 * *needs_explicit 1 when the law must be explicit (above: a prismatic one
 * among them, or m undriven).
 * Errors: FB_ERR_ARG when the law must be explicit and the case's penalty
 * is another (the message names the key and the rule); FB_ERR_NOMEM. */
fb_status fb_planar_free_parts(fb_planar_guide **guide, double **omega0, int *needs_explicit,
                               const fb_case *c, const fb_planar *m, const unsigned char *clear,
                               fb_diag *diag);

/* *omega0 (nbodies [rad/s], the ground's 0; owned by the caller, free())
 * = each body's [body.NAME] initial_omega_rad_s of case c, by m's body
 * names, or with a torque drive (planar.h torque_joint) each body's rate
 * in the motion that turns the drive's joint at [drive] speed0_rpm from
 * the assembly (the kinematics, planar_kinematics.h; their errors): an undriven case's free start (planar_start.h), whatever its
 * joints. Errors: FB_ERR_NOMEM. */
fb_status fb_planar_free_omega0(double **omega0, const fb_case *c, const fb_planar *m,
                                fb_diag *diag);

#endif
