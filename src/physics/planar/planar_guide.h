/* A slider in its guide with clearance: a prismatic joint of the
 * description taken out of the constraint set, its slider (the joint's
 * body[1]) a rectangle of half-length a along the slide and half-height b
 * across it, between the two walls of its guide (the joint's body[0]) at
 * (b + c) on each side of the slide's line (c the clearance, the gap on
 * each side of the centred slider). Translational clearance after Flores,
 * Leine and Glocker (Multibody Syst Dyn 23:165, 2010), the four corners as
 * Siconos's SliderCrank example writes them (docs/models.md):
 *
 *        wall  +(b + c) ______________________________
 *                          1 +-----------------+ 2        tau = +1
 *        slide line  o - - - | - - - p - - - - | - - ->  u (axis_deg)
 *                          3 +-----------------+ 4        tau = -1
 *        wall  -(b + c) ------------------------------
 *                         sigma = -1       sigma = +1
 *
 * Corner (sigma, tau) in the slider's frame: s = s_k + sigma a u_k +
 * tau b n_k (s_k the joint's point on the slider, u_k the slide direction
 * carried into the slider's frame at the assembly, n_k = perp(u_k)). In
 * the world, with o the joint's point on the guide and n = A_i perp(u)
 * the slide's normal, y = n . (p - o) and the gap g = (b + c) - tau y;
 * penetration delta = -g > 0 in contact, its rate delta' = tau n .
 * (p' - v_guide(p)) (the guide's material point under the corner). The
 * contact law (contact.h) gives F = law(delta, delta', v0) >= 0, pushed
 * along -tau n on the slider at the corner and +tau n on the guide there;
 * the restitution law's damper sits on the effective mass of the corner
 * (contact_mass.h) taken as its face's share 1 / (D_cc + D_cc'), c' the
 * other corner of its face, D the corners' Delassus matrix in the joints'
 * free coordinates (planar_mass.h): exact when a face strikes flat (equal
 * forces at its two corners; this case's every strike), and continuous in
 * q. A lone corner of a tilting slider gets the same mass, above its own
 * 1 / D_cc, so its damper rebounds it below cr. With each corner's own
 * 1 / D_cc instead, a flat strike of this slider (whose tilt inertia
 * makes one corner's mass about a tenth of the face's share) would
 * rebound far above cr.
 * Frictionless: the harness's laws are normal laws only (the example has
 * Coulomb friction mu = 0.01; docs/models.md says what that moves). */
#ifndef FB_PLANAR_GUIDE_H
#define FB_PLANAR_GUIDE_H

#include "contact.h"
#include "planar_mass.h"

/* Corners of a slider. */
#define FB_PLANAR_GUIDE_CORNERS 4

/* The slider's geometry in its guide. */
typedef struct {
  double half_length; /* a, along the slide [m] > 0 */
  double half_height; /* b, across the slide [m] > 0 */
  double clearance;   /* c, the gap on each side of the centred slider [m] > 0 */
} fb_planar_guide;

/* The four corners at an evaluation (order 1, 2, 3, 4 as sketched). */
typedef struct {
  double gap[FB_PLANAR_GUIDE_CORNERS];   /* g = (b + c) - tau y [m] (< 0: penetration) */
  double rate[FB_PLANAR_GUIDE_CORNERS];  /* delta' = -g' [m/s] (> 0 approaching the wall) */
  double force[FB_PLANAR_GUIDE_CORNERS]; /* F >= 0 [N] */
  double mass[FB_PLANAR_GUIDE_CORNERS];  /* the damper's effective mass [kg] (above) when
                                            the law wants one and the corner is in contact;
                                            else 0 */
  double tilt;                           /* the slider's angle to the slide [rad] */
} fb_planar_guide_state;

/* One corner of the slider at a state (fb_planar_guide_corners): where it
 * is, which way its wall lies, how far, how fast it closes. */
typedef struct {
  double slider[2]; /* s: the corner in the slider's frame [m] */
  double guide[2];  /* sg: the guide's material point under the corner, in the guide's
                       frame [m] */
  double point[2];  /* p: the corner in the world [m] */
  double normal[2]; /* tau n: unit, from the slide's line towards the corner's own wall,
                       the way the corner penetrates it (the wall pushes the slider along
                       -normal, the guide along +normal) [-] */
  double gap;       /* g = (b + c) - tau y [m] (< 0: penetration) */
  double rate;      /* delta' = tau n . (p' - v_guide(p)) [m/s] (> 0 approaching the wall) */
} fb_planar_guide_corner;

/* Checks g: a, b, c positive and finite. Errors: FB_ERR_RANGE naming the
 * value and the rule. */
fb_status fb_planar_guide_check(const fb_planar_guide *g, fb_diag *diag);

/* The four corners of prismatic joint j of m (its body[0] the guide, its
 * body[1] the slider) with geometry g at state q, qd (nq each) into c
 * (order 1, 2, 3, 4 as sketched: sigma = -1, +1; tau = +1, +1, -1, -1);
 * the slider's tilt to the slide into *tilt [rad] (may be NULL). The one
 * geometry of a corner: the reference (fb_planar_guide_contact) and the
 * engine kit's corner contacts (kit_contact.c) both take it. */
void fb_planar_guide_corners(fb_planar_guide_corner c[FB_PLANAR_GUIDE_CORNERS], double *tilt,
                             const fb_planar *m, int j, const fb_planar_guide *g,
                             const double *q, const double *qd);

/* Corner r (0 .. 3: the sketch's 1 .. 4) of a centred slider in guide g
 * whose slide passes through at [m] along the unit axis u [-]: the
 * corner's point [m], its wall's point on the slide's normal through at
 * [m] and the wall's unit normal, towards the wall (the way the corner
 * penetrates it) [-], in the frame at and u are given in. The layout
 * fb_planar_guide_corners moves with the bodies, for an engine that
 * evaluates the corners itself (MuJoCo's hook, Simbody's force element). */
void fb_planar_guide_layout(double corner[2], double wall[2], double normal[2],
                            const double at[2], const double u[2], const fb_planar_guide *g,
                            int r);

/* The restitution damper's effective mass [kg] of every corner of c in
 * contact (gap < 0) into mass (others 0): its face's share
 * 1 / (D_cc + D_cc') (the sketch's rule above), D the four corners'
 * Delassus matrix (planar_mass.h) at q, the configuration cm last
 * factorised, with prismatic joint j of m out of its set; alone (may be
 * NULL) the same corners' own 1 / D_cc [kg] (the corner alone: lighter,
 * the slider's tilt). */
void fb_planar_guide_masses(double mass[FB_PLANAR_GUIDE_CORNERS],
                            double alone[FB_PLANAR_GUIDE_CORNERS], fb_planar_cmass *cm,
                            const fb_planar *m, int j,
                            const fb_planar_guide_corner c[FB_PLANAR_GUIDE_CORNERS],
                            const double *q);

/* The corners of prismatic joint j of m with geometry g at state q, qd
 * (nq each) into *out (may be NULL); each corner's force is added to
 * force (nq, generalised forces, planar_constraints.h) with law (prepared)
 * and impact velocity v0 [m/s]. cm: the constraint set the dynamics
 * factorised at q (for the effective mass; used only when the law wants
 * one). */
void fb_planar_guide_contact(double *force, fb_planar_guide_state *out, fb_planar_cmass *cm,
                             const fb_planar *m, int j, const fb_planar_guide *g,
                             const fb_contact_law *law, double v0, const double *q,
                             const double *qd);

#endif
