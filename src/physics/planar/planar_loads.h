/* The forces applied to a planar mechanism besides its joints' and the
 * drive's: gravity, springs and loads (planar.h fb_planar_spring,
 * fb_planar_load), as generalised forces on the core's coordinates
 * (planar.h: q = x, y, theta per moving body).
 *
 * A force F at world point p of body b (centre r) adds F to b's x, y
 * rows and (p - r) x F to its theta row; a torque adds to theta alone
 * (virtual work; Haug, Computer-Aided Kinematics and Dynamics of
 * Mechanical Systems, sec. 6.1; Nikravesh, Computer-Aided Analysis of
 * Mechanical Systems, sec. 5.3). Gravity acts along -y on every moving
 * body's centre. A spring of ends a (on body[0]) and b (on body[1]), of
 * length l = |b - a| and unit direction u = (b - a) / l, has the tension
 * f = k (l - l0) + c l', l' = u . (v_b - v_a): -f u acts at b, +f u at a.
 * A torque drive (planar.h torque_joint) puts +T on its joint's body[1]
 * and -T on its body[0]. A load on one stroke acts while its prismatic joint's slide rate
 * (planar_outputs.h) has the stroke's sign (outstroke: positive, return:
 * negative), and not at all at a dead centre, where the rate is zero. */
#ifndef FB_PLANAR_LOADS_H
#define FB_PLANAR_LOADS_H

#include "planar.h"

/* 1 when m has springs, loads or a torque drive (gravity aside). */
int fb_planar_has_loads(const fb_planar *m);

/* The generalised applied forces of gravity [m/s^2, >= 0, along -y],
 * m's springs, its loads and its torque drive at the coordinates q and their rates qd
 * (each fb_planar_nq(m)) into Q (fb_planar_nq(m)): N on the x, y rows,
 * N m on the theta rows. */
void fb_planar_applied(double *Q, const fb_planar *m, const double *q, const double *qd,
                       double gravity);

/* The quantities fb_planar_spring_state gives per spring. */
#define FB_PLANAR_SPRING_QUANTITIES 3

/* Spring s of m at q, qd: its length [m], length rate [m/s] and tension
 * [N] (positive pulls its ends together) into out
 * (FB_PLANAR_SPRING_QUANTITIES). */
void fb_planar_spring_state(double out[3], const fb_planar *m, int s, const double *q,
                            const double *qd);

/* 1 when load l of m acts at q, qd (its stroke's sign, above). */
int fb_planar_load_acts(const fb_planar *m, int l, const double *q, const double *qd);

#endif
