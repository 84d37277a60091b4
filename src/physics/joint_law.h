/* The contact law of each clearance joint for the two clearance models,
 * resolved from the case's penalty source.
 *
 * ode-clearance-impact uses the impact law F = K delta^n + STEP(...) ddot;
 * ode-clearance-restitution the restitution law F = p delta + c ddot with c
 * giving restitution cr for the joint's effective mass (reduced mass of the
 * two bodies, or the moving body's mass at a ground joint).
 *   physical: F_j = largest inverse-dynamics reaction at joint j over a
 *     revolution (stack-up lengths, gravity included), delta_j = Johnson's
 *     approach at F_j for the pin length and radial clearance;
 *     K = F_j / delta_j^n (secant through Johnson's curve at the working
 *     force), p = Johnson's tangent stiffness at F_j.
 *   paper: the paper's Kc (Eq. 7, Table II recipe) read as N/mm^1.5 for the
 *     impact law (K = Kc[N/mm] * 1000^1.5 N/m^1.5, n = 1.5) and its P read as
 *     N/mm for the restitution law (p = P * 1000 N/m), as a multibody code
 *     in mm-N units would; crank-coupler values for the ground-crank and
 *     crank-coupler joints, coupler-follower values for the other two.
 *   explicit: the case's stiffness keys.
 *   goldsmith: paper Eq. (3)-(5), Goldsmith's equivalent stiffness of the
 *     internal contact of the pin (radius R_pin = [pin] diameter / 2) in its
 *     hole (R_hole = R_pin + radial clearance c), both of the case's
 *     material: K = 4 / (3 (s1 + s2)) sqrt(R_pin R_hole / (R_hole - R_pin))
 *     [N/m^1.5], s_i = (1 - nu_i^2) / E_i (the paper writes
 *     s_i = (1 - nu_i^2)/(pi E_i) and 4 / (3 pi (s1 + s2)): the two pi
 *     cancel; fb_contact_goldsmith). The impact law gets K with n = 1.5 (the
 *     law Eq. 3 is the stiffness of); the restitution law its tangent
 *     p = 1.5 K^(2/3) F_j^(1/3) at the joint's largest inverse-dynamics
 *     reaction F_j (the working force, as for physical).
 * Every source's stiffness is then multiplied by [clearance] stiffness_scale. */
#ifndef FB_JOINT_LAW_H
#define FB_JOINT_LAW_H

#include "case.h"
#include "contact.h"

/* Fills impact[j] and restitution[j] for every clearance joint j of the
 * case (others untouched); either array may be NULL when not wanted. The
 * inverse-dynamics reactions (or the paper's rows) are solved once for both.
 * Errors: those of the penalty estimates (FB_ERR_RANGE when Johnson's
 * relation does not hold at the force). */
fb_status fb_joint_laws(fb_contact_law impact[4], fb_contact_law restitution[4],
                        const fb_case *c, fb_diag *diag);

/* The law of one clearance joint of any mechanism (a planar case's): the
 * impact law (impact = 1) or the restitution law of the case's [clearance]
 * keys at working force fmax [N] (the joint's largest ideal reaction:
 * physical, goldsmith), the joint named name in messages, the law's
 * starting mass [kg] > 0 (its damper is put on the effective mass at each
 * step, contact_mass.h). Errors: as fb_joint_laws; FB_ERR_ARG for
 * [clearance] penalty = paper, whose recipe is the four-bar's. */
fb_status fb_joint_law_at(fb_contact_law *out, const fb_case *c, int impact, double fmax,
                          const char *name, double mass, fb_diag *diag);

#endif
