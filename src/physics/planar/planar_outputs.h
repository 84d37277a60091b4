/* What a designer reads off a planar mechanism besides its bodies' angles:
 * the motion of its output points ([point.NAME], planar.h fb_planar_mark)
 * and of every prismatic joint's slide, at one configuration of the core's
 * coordinates (planar.h: q = x, y, theta per moving body).
 *
 * A point s of body b (in b's frame) at r + A(theta) s moves with
 *   v = r' + omega perp(A s),  a = r'' + alpha perp(A s) - omega^2 A s,
 * perp(x, y) = (-y, x) (rigid-body kinematics; Uicker, Pennock and
 * Shigley, Theory of Machines and Mechanisms, sec. 3.6 and 4.5).
 *
 * A prismatic joint's slide is the position of its slider's point along
 * its axis, measured from a datum of its guide: the guide is the ground
 * when either body is (the datum the world's origin, so that a slider on a
 * ground guide through the origin reads its abscissa, as the slider-crank's
 * slider_x_m), else the joint's first body, whose datum is its first joint
 * point (its joint with the ground first, then in the description's
 * order: a slotted lever's pivot). With u the axis, d the datum and p the
 * slider's joint point, both turning at the guide's omega, alpha:
 *   s = (p - d).u
 *   s' = (p' - d').u + omega (p - d).perp(u)
 *   s'' = (p'' - d'').u + 2 omega (p' - d').perp(u) + (p - d).(alpha perp(u) - omega^2 u)
 * The slide is positive along the axis the case gave (axis_deg). */
#ifndef FB_PLANAR_OUTPUTS_H
#define FB_PLANAR_OUTPUTS_H

#include "planar.h"

/* Quantities per output point and per slide, in fb_planar_outputs' order. */
#define FB_PLANAR_POINT_QUANTITIES 6 /* x, y [m], v_x, v_y [m/s], a_x, a_y [m/s^2] */
#define FB_PLANAR_SLIDE_QUANTITIES 3 /* slide [m], its rate [m/s] and acceleration [m/s^2] */

/* Prismatic joints of m (each one slide). */
int fb_planar_slide_count(const fb_planar *m);

/* Values fb_planar_outputs writes: 6 per point, 3 per slide; 0 when m has
 * neither (its runs keep no output columns). */
int fb_planar_output_count(const fb_planar *m);

/* The motion of every output point, then every prismatic joint's slide
 * (in joint order), at the coordinates q, their rates qd and accelerations
 * qdd (each fb_planar_nq(m)) into out (fb_planar_output_count(m)): point k's
 * x, y, v_x, v_y, a_x, a_y at out[6 k ..], slide s's position, rate and
 * acceleration at out[6 npoints + 3 s ..], SI (above). */
void fb_planar_outputs(double *out, const fb_planar *m, const double *q, const double *qd,
                       const double *qdd);

/* Prismatic joint j's slide rate [m/s] at the coordinates q and their
 * rates qd (each fb_planar_nq(m)): s' above, the sign that tells an
 * outstroke (positive) from a return. */
double fb_planar_slide_rate(const fb_planar *m, int j, const double *q, const double *qd);

/* Prismatic joint j's guide (0 or 1, an index into its body[]) and datum
 * in the guide's frame [m] (2) (above). */
int fb_planar_slide_guide(const fb_planar *m, int j, double datum[2]);

/* 1 when moving body b of m turns as the mechanism moves; 0 when a
 * chain of prismatic joints holds its angle to the ground's (a ram on its
 * guide): its angle, omega and alpha are zero throughout. */
int fb_planar_body_turns(const fb_planar *m, int b);

#endif
