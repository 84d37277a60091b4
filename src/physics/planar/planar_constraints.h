/* The constraint equations of a planar description (model/mech/planar.h)
 * in absolute coordinates q = (x, y, theta) per moving body: their values
 * Phi(q, t), their Jacobian Phi_q and the right-hand side gamma of the
 * acceleration equation Phi_q q'' = gamma, for any subset of the joints
 * and with or without the drive's row. Pure functions, no allocation.
 *
 * Rows, in joint order, two per joint left in the set, the drive's last:
 *   revolute j (bodies i = body[0], k = body[1], points s_i, s_k in their
 *   frames, A(theta) the rotation, p = r + A s):
 *     Phi = p_i - p_k                                          (2 rows)
 *     gamma = A_i s_i w_i^2 - A_k s_k w_k^2
 *   prismatic j (slide direction u fixed in body i, n = A_i perp(u) its
 *   normal, d = p_k - p_i):
 *     Phi_1 = theta_k - theta_i - (theta_k0 - theta_i0)        (no turning)
 *     Phi_2 = n . d                                            (on the line)
 *     gamma_1 = 0,
 *     gamma_2 = (n . d) w_i^2 - 2 w_i perp(n) . d' + n . (A_k s_k w_k^2 - A_i s_i w_i^2)
 *   the drive (from, to: fb_planar_drive_bodies; phi(t) its angle from
 *   the assembly configuration):
 *     Phi = theta_to - theta_from - (theta_to0 - theta_from0) - phi(t)
 *     gamma = phi''(t); the velocity equation's right side is phi'(t)
 * where perp(v) = (-v_y, v_x), w = theta'. gamma is -(Phi_q q')_q q' - Phi_tt
 * (Haug, Computer-Aided Kinematics and Dynamics of Mechanical Systems, 1989,
 * ch. 3, Table 3.3, written here in 2-D; Nikravesh, Computer-Aided Analysis
 * of Mechanical Systems, 1988, ch. 5). The ground's coordinates are fixed
 * (r = 0, theta = 0) and have no columns. tests/test_planar_constraints.c
 * checks Phi_q and gamma against finite differences of Phi. */
#ifndef FB_PLANAR_CONSTRAINTS_H
#define FB_PLANAR_CONSTRAINTS_H

#include "planar.h"

/* The drive's prescribed motion: its angle from the assembly
 * configuration [rad], rate [rad/s] and acceleration [rad/s^2]. */
typedef struct {
  double angle;
  double omega;
  double alpha;
} fb_planar_drive;

/* Rows of the set: 2 per joint with off[j] == 0 (off may be NULL: every
 * joint), plus 1 when with_drive. */
int fb_planar_rows(const fb_planar *m, const unsigned char *off, int with_drive);

/* Evaluates the set (joints with off[j] == 0, off NULL for all; the drive's
 * row when drive is not NULL) at q (fb_planar_nq) and qd (needed for gamma
 * only): phi (rows), jac (rows x nq, row-major; zeroed here) and gamma
 * (rows); any output may be NULL. The drive's angle enters phi, its
 * acceleration gamma. */
void fb_planar_constraints(double *phi, double *jac, double *gamma, const fb_planar *m,
                           const unsigned char *off, const fb_planar_drive *drive,
                           const double *q, const double *qd);

/* A(theta) s: s (2) rotated by theta [rad] into out (2), A(theta) =
 * [cos -sin; sin cos] the rotation of a body's frame (the same A as the
 * constraint equations above). */
void fb_planar_rotate(double out[2], double theta, const double s[2]);

/* Body b's angle at q [rad] (q: 3 per moving body, x, y, theta); the
 * ground's (b = 0) is 0. */
double fb_planar_angle(const double *q, int b);

/* World position of point s (2, in body b's frame) [m] at q into out (2);
 * the ground's frame is the world's. */
void fb_planar_point(double out[2], const fb_planar *m, const double *q, int b,
                     const double s[2]);

/* World position x [m] and velocity v [m/s] (2 each) of point s of body b
 * at q, qd: fb_planar_point and fb_planar_point_velocity in one (the
 * body's rotation formed once). */
void fb_planar_point_motion(double x[2], double v[2], const fb_planar *m, const double *q,
                            const double *qd, int b, const double s[2]);

/* Body b's rotation at q: cs (2) = (cos, sin) of its angle [-] (the
 * ground's (1, 0)). A caller that places several points of a body at one
 * q forms its rotation once and hands it to the _at functions below,
 * which give fb_planar_point's and fb_planar_point_motion's numbers to the
 * last bit. */
void fb_planar_rotation(double cs[2], const double *q, int b);

/* fb_planar_point with body b's rotation cs (2: its cos, sin at q). */
void fb_planar_point_at(double out[2], const double *q, int b, const double s[2],
                        const double cs[2]);

/* fb_planar_point_motion with body b's rotation cs (2: its cos, sin at q). */
void fb_planar_point_motion_at(double x[2], double v[2], const double *q, const double *qd,
                               int b, const double s[2], const double cs[2]);

/* World velocity of point s of body b at q, qd [m/s] into out (2). */
void fb_planar_point_velocity(double out[2], const fb_planar *m, const double *q,
                              const double *qd, int b, const double s[2]);

/* Adds sign times the Jacobian of point s of body b's world position to rows
 * (2 x nq, row-major): d p / d q = [I, perp(A s)] in body b's columns;
 * nothing for the ground. */
void fb_planar_point_jacobian(double *rows, const fb_planar *m, const double *q, int b,
                              const double s[2], double sign);

/* Adds point force f (2) [N] acting at world point p (2) [m] on body b to
 * the generalised forces force (nq): (f_x, f_y, (p - r_b) x f) in body b's
 * columns; nothing for the ground. */
void fb_planar_add_force(double *force, const double *q, int b, const double p[2],
                         const double f[2]);

#endif
