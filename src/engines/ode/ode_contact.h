/* The one place an ODE soft contact is filled from a contact law: used by the
 * exact and the faceted clearance colliders (ode_clearance.c, ode_colliders.c)
 * and by the kit binding (ode_kit.c), whose world the single impact uses
 * too (kit_impact.h). Private to src/engines/ode
 * (includes ODE's header). */
#ifndef FB_ODE_CONTACT_H
#define FB_ODE_CONTACT_H

#include <ode/ode.h>

#include "contact.h"

/* Maps law at penetration delta [m], penetration rate ddot [m/s] and onset
 * rate v0 [m/s] to one of n_rows parallel contact rows at step h [s] with
 * effective mass m_eff [kg] along the normal (fb_contact_map: secant,
 * tangent or matched mapping), and fills ct->surface (soft ERP and CFM,
 * Coulomb friction mu = friction with ODE's friction pyramid when > 0) and
 * ct->geom.depth. onset = 1 at the first step of a contact episode: a single
 * matched row of a linear law gets fb_contact_row_onset. A matched-static
 * row with persistence w > 0 (fb_contact_persistence of its contact's
 * phase) gets fb_contact_row_static with that weight instead. The caller zeroes ct first and sets the geometry (point,
 * normal, geoms). *row (if not NULL) receives what the row got.
 * Returns 1 when filled, 0 when the law gives no row at this state. */
int fb_ode_soft_contact(dContact *ct, const fb_contact_law *law, fb_mapping mapping, double h,
                        double m_eff, int n_rows, double delta, double ddot, double v0,
                        int onset, double persistence, double friction,
                        fb_contact_row *row);

/* Fills ct->surface and ct->geom.depth from a row already mapped
 * (fb_contact_map), with Coulomb friction mu = friction (friction pyramid
 * when > 0): the one place a soft contact's surface is written. */
void fb_ode_soft_fill(dContact *ct, const fb_contact_row *row, double friction);

#endif
