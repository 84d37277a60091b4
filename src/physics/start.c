#include "start.h"

#include <math.h>
#include <string.h>

#include "closed_form.h"
#include "series.h"

const char *fb_start_name(fb_start s) { return s == FB_START_REST ? "rest" : "steady"; }

const char *fb_pin_start_name(fb_pin_start p) {
  return p == FB_PIN_RESTING ? "resting" : (p == FB_PIN_ANGLE ? "angle" : "centred");
}

/* each joint's force on its second body with the crank held at theta0 under
 * gravity alone (inverse dynamics at zero speed, the mechanism's closed
 * form); a slider-crank's guide (slider-ground) carries no pin */
static fb_status static_load(double force[4][2], const fb_case *c, const fb_linkage *lk,
                             fb_diag *diag) {
  memset(force, 0, 4 * sizeof force[0]);
  return fb_closed_form_of(c->mechanism)->reactions(force, NULL, lk, c->branch, c->link,
                                                    c->gravity, c->crank_angle0, 0.0, diag);
}

/* eccentricity of every clearance joint from the case's pin_start */
static fb_status eccentricities(double ecc[4][2], const fb_case *c, const fb_linkage *lk,
                                int mask, fb_diag *diag) {
  memset(ecc, 0, 4 * sizeof ecc[0]);
  /* an ensemble member's perturbation (ensemble.h), on top of the pin start */
  for (int j = 0; j < 4; j++)
    if (mask & (1 << j)) ecc[j][0] = c->pin_start_offset[0], ecc[j][1] = c->pin_start_offset[1];
  if (!mask || c->pin_start == FB_PIN_CENTRED) return FB_OK;
  double dir[4][2];
  if (c->pin_start == FB_PIN_ANGLE) {
    for (int j = 0; j < 4; j++) dir[j][0] = cos(c->pin_start_angle), dir[j][1] = sin(c->pin_start_angle);
  } else {
    /* static load at zero speed; fb_reactions gives each force on the
     * joint's second body. The contact pushes the hole body along +e and
     * the pin body along -e: at B and C the second body holds the hole
     * (e along the force), at A and D it holds the pin (e against it). */
    double force[4][2];
    fb_status st = static_load(force, c, lk, diag);
    if (st != FB_OK) return st;
    const double sign[4] = {-1.0, 1.0, 1.0, -1.0};
    for (int j = 0; j < 4; j++) {
      const double f = hypot(force[j][0], force[j][1]);
      /* no load (zero gravity): the wall below the hole, an arbitrary choice */
      dir[j][0] = f > 0.0 ? sign[j] * force[j][0] / f : 0.0;
      dir[j][1] = f > 0.0 ? sign[j] * force[j][1] / f : -1.0;
    }
  }
  for (int j = 0; j < 4; j++)
    if (mask & (1 << j)) {
      ecc[j][0] += c->radial_clearance * dir[j][0];
      ecc[j][1] += c->radial_clearance * dir[j][1];
    }
  return FB_OK;
}

fb_status fb_start_resolve(fb_start_state *out, const fb_case *c, const fb_linkage *lk,
                           int clearance_mask, fb_diag *diag) {
  double ecc[4][2];
  fb_status st = eccentricities(ecc, c, lk, clearance_mask, diag);
  if (st != FB_OK) return st;
  return fb_closed_form_of(c->mechanism)->start_resolve(out, c, lk, (const double(*)[2])ecc,
                                                        clearance_mask, diag);
}

fb_status fb_start_steady(fb_start_state *out, fb_mech_type t, const fb_linkage *lk,
                          fb_branch branch, double theta0, double omega2, fb_diag *diag) {
  return fb_closed_form_of(t)->start_steady(out, lk, branch, theta0, omega2, diag);
}
