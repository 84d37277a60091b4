/* A planar case's sections in the case-file reader ([linkage] type =
 * planar): one [joint.NAME] section per joint, an optional [body.NAME]
 * per moving body, [drive] joint, and [clearance] joints by joint name.
 * Internal to the reader (casefile.c calls it; not a public header).
 *
 *   [joint.NAME]  bodies = A, B           two bodies (ground: the fixed one)
 *                 at_mm = x, y            its position in the assembly configuration
 *                 kind = revolute         or prismatic (default revolute)
 *                 axis_deg = a            prismatic: the slide's direction, ccw from +x
 *                 slider_half_length_mm,  a prismatic clearance joint's slider
 *                 slider_half_height_mm   (casefile_planar_free.h)
 *   [body.NAME]   mass_kg, inertia_kg_mm2 (about its centre), centre_mm = x, y,
 *                 width_mm, thickness_mm  (the bar section when masses are derived),
 *                 initial_omega_rad_s     (an undriven case's start)
 *   [drive]       joint = NAME            the driven (revolute) joint; speed_rpm and
 *                                         direction as for every case; none: undriven
 *   [clearance]   joints = NAME, ...      revolute joints modelled as a pin in a hole,
 *                                         prismatic ones as a slider in its guide
 *
 * Values are checked as they are read (file, line, key, value, rule), the
 * sections as a whole when the file is read (casefile_planar_finish), and
 * the description they make by the planar core's checks
 * (physics/planar/planar_check.h): each error names the file and line of
 * the joint's or body's section. docs/planar.md is the user's page. */
#ifndef FB_CASEFILE_PLANAR_H
#define FB_CASEFILE_PLANAR_H

#include "casefile_internal.h"

/* 1 when e is [linkage] type = planar. */
int fb_casefile_planar_type(const entry *e);

/* 1 when the planar reader takes entry e of case c: a [joint.*] or
 * [body.*] section's key, [drive] joint, and in a planar case (c->planar.on)
 * [linkage] type, [clearance] joints and the four-bar's geometry and mass
 * keys ([linkage], [mass], [tolerance] *_plus_minus_mm), which it refuses. */
int fb_casefile_planar_claims(const fb_case *c, const entry *e);

/* Takes entry e (claimed) into c->planar. Errors: FB_ERR_PARSE naming
 * e->origin, the section, key, value and rule (a value of the wrong form,
 * an unknown key, a planar section in a four-bar or slider-crank case, a
 * four-bar key in a planar case); FB_ERR_RANGE (a value out of range). */
fb_status fb_casefile_planar_take(fb_case *c, const entry *e, fb_diag *diag);

/* The sections as a whole, once every entry of a planar case (entries
 * e[0 .. n-1], in the order given) is taken: each joint has its bodies and
 * position (a prismatic joint its axis), each [body.NAME] a joint, the
 * drive and the clearance joints name joints; then the description is
 * compiled (masses derived as bars) and checked by the planar core.
 * A case without [run] models runs the four-bar's default rule on its
 * description (casefile_planar.c default_models).
 * run: 1 for a caller that computes on a planar case
 * (fb_casefile_load_planar: fourbar run), 0 for the commands that do not
 * run one yet, which then refuse it after the checks pass.
 * Errors: FB_ERR_PARSE, FB_ERR_ARG, FB_ERR_ASSEMBLY, FB_ERR_RANGE with the
 * file and line of the section concerned; FB_ERR_NOMEM. */
fb_status fb_casefile_planar_finish(fb_case *c, const entry *e, int n, const char *path, int run,
                                    fb_diag *diag);

#endif
