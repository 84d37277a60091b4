/* A unit vector turned by a small angle, at the small angle's own precision.
 *
 * The reference integrations (reference.c, slider_crank_dynamics.c) keep a
 * body's angle as its deviation d from the ideal mechanism's angle and need
 * the change of the body's direction, u(theta + d) - u(theta). Written as
 * cos(theta + d) - cos(theta) it cancels to rounding of order 1e-16 of the
 * body's length; written as
 *   u(theta + d) - u(theta) = u (cos d - 1) + u_perp sin d,
 *   cos d - 1 = -2 sin^2(d / 2),  u_perp = (-u_y, u_x),
 * its error is 1e-16 of |d| (a trigonometric identity, no approximation). */
#ifndef FB_PLANAR_TURN_H
#define FB_PLANAR_TURN_H

#include <math.h>

/* out = u(theta + d) - u(theta) for the unit vector u = u(theta) (x, y),
 * d [rad]; out [-] (2) */
static inline void fb_turn_change(double out[2], const double u[2], double d) {
  const double h = sin(0.5 * d), cm = -2.0 * h * h, s = sin(d);
  out[0] = u[0] * cm - u[1] * s;
  out[1] = u[1] * cm + u[0] * s;
}

#endif
