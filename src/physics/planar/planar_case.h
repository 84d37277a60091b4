/* The planar description (model/mech/planar.h) of a case's mechanism:
 * the four-bar and the slider-crank from today's keys as two instances of
 * it, and a planar case's own sections ([linkage] type = planar,
 * model/mech/planar_spec.h) compiled into it, their masses derived as bars
 * where the case gives none.
 *
 * Four-bar (bodies ground, crank, coupler, follower; joints ground-crank at
 * A, crank-coupler at B, coupler-follower at C, follower-ground at D, the
 * names of model/mechanism.c's fb_mech_fourbar), assembled at the case's
 * crank angle by the closed form (linkage.h) on the case's branch: every
 * body's frame at its centre of mass (com_fraction along its link, crank
 * A->B, coupler B->C, follower D->C) with its x axis along its link in the
 * closed form's sense, so that the core's body angles are theta2, theta3,
 * theta4. Slider-crank (ground, crank, coupler, slider; joints ground-crank,
 * crank-coupler, coupler-slider and the prismatic slider-ground along +x at
 * the piston pin), assembled by its closed form (slider_crank.h), the
 * slider's centre at the pin. The drive is ground-crank. The drive's angle
 * 0 is the case's crank_angle0.
 *
 * Bars (a planar case's body without mass_kg, inertia_kg_mm2 or centre_mm):
 * the body is the bars between every pair of its distinct joint points
 * (one bar for a binary link, the triangle's three for a ternary one), each
 * of width w and thickness t ([body.NAME] width_mm, thickness_mm; else the
 * default bar's, bar_mass.h) and the case's density rho: bar i of length
 * L_i weighs m_i = rho w t L_i, centre at its midpoint, moment
 * m_i (L_i^2 + w^2) / 12 (bar_mass.h); the body's mass is the sum, its
 * centre the mass-weighted midpoint, its moment the sum of each bar's about
 * the body's centre (parallel axes). A given mass scales the bars' moment
 * in proportion (as fb_bar_fill does); a given centre moves the derived
 * moment to it (parallel axes). A body with one distinct joint point (a
 * slider) has no bar: it needs mass_kg and inertia_kg_mm2, and its centre
 * defaults to that point. A body that guides a prismatic joint (carries
 * its slot) counts, instead of the slider's point in the assembly, the two
 * ends of the slider's travel along the slot over a drive revolution
 * (fb_planar_compile compiles once, finds the travel with
 * planar_path.h's fb_planar_extremes_of, and compiles again), so that a
 * derived mass does not depend on the assembly pose; an undriven
 * description keeps the assembly's point. A body's frame angle is the direction from its
 * first joint point to its second (its joint with the ground first, then
 * in file order; 0 with one point), so a binary link's angle is the
 * four-bar's link angle. */
#ifndef FB_PLANAR_CASE_H
#define FB_PLANAR_CASE_H

#include "case.h"
#include "planar.h"
#include "planar_spec.h"

/* Where a problem is: a joint or body index of the description (and of
 * the spec it was compiled from, the same order), -1 for none. */
typedef struct {
  int joint;
  int body;
} fb_planar_where;

/* The four-bar of lengths lk on branch at crank angle theta0 [rad] with
 * the mass properties link[3] (crank, coupler, follower), driven at
 * ground-crank, into *out (free with fb_planar_free).
 * Errors: those of fb_linkage_solve (the loop does not close at theta0);
 * FB_ERR_RANGE for a mass or inertia that is not positive; FB_ERR_NOMEM. */
fb_status fb_planar_fourbar(fb_planar **out, const fb_linkage *lk, fb_branch branch,
                            const fb_link_mass link[3], double theta0, fb_diag *diag);

/* The slider-crank of lengths lk (crank, coupler, offset at
 * FB_LENGTH_OFFSET) at crank angle theta0 with link[3] (crank, coupler,
 * slider; the slider's centre at the piston pin).
 * Errors: those of fb_slider_crank_solve; as fb_planar_fourbar. */
fb_status fb_planar_slider_crank(fb_planar **out, const fb_linkage *lk,
                                 const fb_link_mass link[3], double theta0, fb_diag *diag);

/* A planar case's spec compiled: its bodies (masses derived as bars where
 * not given, density [kg/m^3] the case's), joints, output points and drive. *where names
 * the body or joint a failure is about (may be NULL).
 * Errors: FB_ERR_ARG (a body without a bar and without mass_kg or
 * inertia_kg_mm2; no drive), FB_ERR_RANGE (a derived mass outside the
 * key's range), FB_ERR_NOMEM; the message names the body or joint. */
fb_status fb_planar_compile(fb_planar **out, const fb_planar_spec *s, double density,
                            fb_planar_where *where, fb_diag *diag);

/* The two of n points pts [m] (n x 2) farthest apart: their indices into
 * *a < *b (0 and 1, or 0 and 0 for one point, when none is farther) and
 * their distance [m] (0 for fewer than two distinct points). A body's
 * points lie on one bar when each is within half the bar's width of the
 * line through these two (planar.h on_one_bar). */
double fb_planar_farthest_pair(const double (*pts)[2], int n, int *a, int *b);

/* The description of case c's mechanism with link lengths lengths (the
 * nominal or a stack-up corner's; ignored for a planar case, whose
 * geometry is its joints'): fb_planar_compile for a planar case,
 * fb_planar_fourbar or fb_planar_slider_crank at the case's crank angle
 * otherwise. Errors: theirs. */
fb_status fb_planar_of_case(fb_planar **out, const fb_case *c, const fb_linkage *lengths,
                            fb_diag *diag);

/* The four-bar's or slider-crank's inverse-mass tensor at each of its four
 * joints (w, 4 x 2 x 2 [1/kg]) with the drive held, at the pose q
 * (fb_planar_nq) of its instance m (fb_planar_fourbar or
 * fb_planar_slider_crank: bodies crank, coupler, follower or slider; joints
 * in fb_mech_desc's order), the joints of clearance_mask (bit j) left out:
 * effective_mass.h's closed form (fb_effective_mass_tensor) on the bodies'
 * centres and each joint's point on its first moving body (a clearance
 * joint's pin) placed with the bodies' rotations cs (m->nbodies x 2: cos,
 * sin at q, planar_constraints.h fb_planar_rotation; NULL: formed here),
 * the prismatic joint a guide along x. Errors: FB_ERR_ARG
 * when m is not such an instance (3 moving bodies, 4 joints); those of
 * fb_effective_mass_tensor. */
fb_status fb_planar_instance_mass(double w[4][2][2], const fb_planar *m, const double *q,
                                  const double (*cs)[2], unsigned clearance_mask, fb_diag *diag);

#endif
