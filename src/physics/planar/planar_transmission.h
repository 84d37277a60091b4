/* The transmission angle of a planar description wherever a binary link (a
 * two-force member: a moving body with two revolute joints and no other)
 * drives another moving body. The force such a link passes on acts along
 * its line; at the joint J where it meets the driven body D, the pressure
 * angle is the angle between that line and the velocity of J as a point
 * of D, and the transmission angle mu = 90 deg - |pressure angle|, in
 * [0, 90] deg (Uicker, Pennock and Shigley, Theory of Machines and
 * Mechanisms, sec. 1.11 and 3.16; Norton, Design of Machinery, sec. 4.10).
 * D's point moves about D's pivot when D turns about the ground (the
 * direction perpendicular to the pivot-to-J line, defined at rest too),
 * along its guide when D slides on the ground, else with D's instantaneous
 * motion. So mu is the four-bar's angle BCD (linkage.h) where that is at
 * most 90 deg (180 deg - BCD beyond: the same quality of transmission)
 * and the slider-crank's 90 deg - |theta3| (slider_crank.h). The link
 * drives the end farther from the drive (more joints between it and the
 * driven body, the ground not counted); the end towards the drive drives
 * the link. Elsewhere (a body with a prismatic joint, three joints, the
 * driven body itself) no transmission angle is defined. */
#ifndef FB_PLANAR_TRANSMISSION_H
#define FB_PLANAR_TRANSMISSION_H

#include "planar.h"

/* One place a binary link drives a moving body. */
typedef struct {
  int link;   /* the binary link (a body index) */
  int joint;  /* the joint where it drives */
  int driven; /* the body it drives there */
  int from;   /* the link's other joint */
} fb_planar_transmission;

/* The places of m (a driven description) where a binary link drives a
 * moving body, in joint order, into out (at most max); returns how many
 * (0 on an undriven description). */
int fb_planar_transmissions(fb_planar_transmission *out, int max, const fb_planar *m);

/* The transmission angle [rad] in [0, pi/2] at t of m at the position q
 * with the coordinates' rates qd (any nonzero multiple of the motion, used
 * only where D moves freely); NaN where the direction of J's motion is
 * undefined (D at rest there). */
double fb_planar_transmission_angle(const fb_planar *m, const fb_planar_transmission *t,
                                    const double *q, const double *qd);

#endif
