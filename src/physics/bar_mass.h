/* Mass properties of a link modelled as a solid rectangular bar: length L
 * from joint centre to joint centre, width w in the mechanism plane across
 * the link, thickness t out of the plane, uniform density rho. The bosses and
 * rounded ends of a real link are not modelled (docs/keys.md, "Masses and
 * inertias": the paper's links carry 1.1 to 1.5 times the bar's moment).
 *
 * Closed form of a homogeneous rectangular cuboid with edges a, b, c about
 * an axis through its centre parallel to c: m (a^2 + b^2) / 12 (e.g.
 * Meriam and Kraige, Engineering Mechanics: Dynamics, Table D/4). Pure
 * functions, SI units, no allocation. */
#ifndef FB_BAR_MASS_H
#define FB_BAR_MASS_H

#include "case.h"
#include "status.h"

/* The bar's geometry and material. */
typedef struct {
  double length;    /* joint centre to joint centre L [m] > 0 */
  double width;     /* in the mechanism plane, across the link w [m] > 0 */
  double thickness; /* out of the plane t [m] > 0 */
  double density;   /* rho [kg/m^3] > 0 */
} fb_bar;

/* A 100 mm steel bar, 20 mm wide, 6.5 mm thick, 7800 kg/m^3 (the defaults
 * of the case keys; docs/keys.md). */
fb_bar fb_bar_default(void);

/* Checks every field is positive and finite; names the field, value and
 * rule in diag. Errors: FB_ERR_RANGE. */
fb_status fb_bar_check(const fb_bar *b, fb_diag *diag);

/* Mass [kg] of the bar: rho w t L. */
double fb_bar_mass(const fb_bar *b);

/* Fills out with the bar's mass properties scaled to mass m [kg] (pass
 * fb_bar_mass(b) for the bar itself, or a mass the case gives):
 *   inertia            = m (L^2 + w^2) / 12  about the hinge (out-of-plane) axis,
 *   inertia_long       = m (w^2 + t^2) / 12  about the long axis,
 *   inertia_transverse = m (L^2 + t^2) / 12  about the in-plane axis across,
 * all through the centre of mass, which lies at com_fraction 0.5. All in kg
 * m^2. Errors: FB_ERR_RANGE (b fails fb_bar_check, or m is not positive). */
fb_status fb_bar_fill(fb_link_mass *out, const fb_bar *b, double m, fb_diag *diag);

#endif
