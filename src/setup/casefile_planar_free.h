/* Two parts of a planar case beyond its mechanism (docs/planar.md),
 * checked as a whole once the case is read (casefile_planar.c calls them;
 * internal to the reader):
 *
 *   a free start   [drive] joint = none: no drive; each body's
 *                  [body.NAME] initial_omega_rad_s (ccw, default 0), the
 *                  linear rates from the joints (physics/planar/
 *                  planar_start.h); [run] duration_s required (no
 *                  revolution to count), [run] start refused (it is the
 *                  driven start's key), initial_omega_rad_s refused in a
 *                  driven case
 *   a slider in    a prismatic joint [clearance] joints names: its
 *   its guide      [joint.NAME] slider_half_length_mm and
 *                  slider_half_height_mm and [clearance] guide_clearance_mm
 *                  required (physics/planar/planar_guide.h); the slider
 *                  keys refused on any other joint, guide_clearance_mm
 *                  without such a joint
 * Each error names the file and line of the entry concerned (the case's
 * path when the entry is missing), the key, the value and the rule. */
#ifndef FB_CASEFILE_PLANAR_FREE_H
#define FB_CASEFILE_PLANAR_FREE_H

#include "casefile_internal.h"

/* The free start's rules above for case c (entries e[0 .. n-1], the file
 * path). Errors: FB_ERR_PARSE. */
fb_status fb_casefile_planar_free(const fb_case *c, const entry *e, int n, const char *path,
                                  fb_diag *diag);

/* The slider-in-its-guide rules above. Errors: FB_ERR_PARSE. */
fb_status fb_casefile_planar_guides(const fb_case *c, const entry *e, int n, const char *path,
                                    fb_diag *diag);

#endif
