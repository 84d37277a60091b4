/* The rule that puts a contact law's damper on the mechanism's effective
 * mass along the contact normal: the restitution law's damper is
 * c = 2 zeta sqrt(p m) (contact.h, fb_contact_force), exact for one
 * degree of freedom of mass m, so in a mechanism m is the effective mass
 * 1 / (n^T W n) of the joint's relative motion along the normal n (the
 * drive held; effective_mass.h, physics/planar/planar_mass.h). Every other
 * law ignores the mass. Written once here: the planar core, reference.c,
 * slider_crank_dynamics.c and the engines (ODE, MuJoCo, Bullet, Simbody)
 * all put the damper on the mass through it. */
#ifndef FB_CONTACT_MASS_H
#define FB_CONTACT_MASS_H

#include "contact.h"

/* 1 when law's force depends on the effective mass (the restitution law),
 * so that a caller computes the mass only then. */
int fb_contact_law_wants_mass(const fb_contact_law *law);

/* law with its damper on mass m_eff [kg] (> 0, +infinity allowed: no
 * motion along the normal) when it wants one, else law unchanged. */
fb_contact_law fb_contact_law_on_mass(const fb_contact_law *law, double m_eff);

#endif
