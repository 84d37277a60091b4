/* Position, velocity and acceleration analysis of a planar description
 * with one degree of freedom and its drive (the `analytic` model of a
 * planar case: not a closed form, but Newton on the loop equations
 * converged to machine precision).
 *
 * With the drive's row the Jacobian Phi_q is square (n = 3 (bodies - 1)
 * rows and columns) and, away from a locked or singular position,
 * invertible:
 *   position      Phi(q, phi) = 0        Newton: Phi_q dq = -Phi, q += dq
 *   velocity      Phi_q q'  = (0, .., 0, phi')
 *   acceleration  Phi_q q'' = gamma(q, q') (planar_constraints.h)
 * each solved by the sparse LU of the square set (planar_sparse.h,
 * planar_lu.h), refactorised in its pivot order. Newton stops one step after its
 * correction falls below FB_PLANAR_NEWTON_STOP (scaled: lengths by the
 * description's size, fb_planar_size, angles in radians), which leaves the residual at the
 * rounding level of the equations (quadratic convergence: the step after a
 * 1e-10 correction is ~1e-20). Haug (1989) ch. 3 and Nikravesh (1988)
 * ch. 5 give the method; the closed forms of the four-bar (linkage.h) and
 * the slider-crank (slider_crank.h) are its fast paths, tested against it
 * (tests/test_planar_kinematics.c). */
#ifndef FB_PLANAR_KINEMATICS_H
#define FB_PLANAR_KINEMATICS_H

#include "planar_constraints.h"

/* A scaled Newton correction below this ends the iteration after one more
 * step: from 1e-10 the next step's error is ~1e-20 (quadratic
 * convergence), below the rounding of Phi itself (~1e-16 of the size). */
#define FB_PLANAR_NEWTON_STOP 1e-10

/* Newton steps allowed from a guess; a good guess (the previous angle's
 * solution moved along its velocity) needs 2 to 4. */
#define FB_PLANAR_NEWTON_MAX 40

/* Largest scaled residual |Phi| a solution may keep: 1e-12 of the
 * description's size, a thousand times the rounding of Phi for
 * mechanisms of up to ~30 bodies (measured: below 1e-15 on the four-bar,
 * slider-crank and six-bar). */
#define FB_PLANAR_CLOSE_TOL 1e-12

/* The workspace of one description's kinematics (its Jacobian, LU and
 * vectors, sized once). */
typedef struct fb_planar_kin fb_planar_kin;

/* A workspace for m, which must have a drive and fb_planar_gruebler(m) == 1
 * (so that the Jacobian with the drive's row is square); m must outlive
 * it. Errors: FB_ERR_ARG (no drive, or not one degree of freedom: the count
 * is in the message), FB_ERR_NOMEM. */
fb_status fb_planar_kin_new(fb_planar_kin **out, const fb_planar *m, fb_diag *diag);

void fb_planar_kin_free(fb_planar_kin *k);

/* The description k works on. */
const fb_planar *fb_planar_kin_mech(const fb_planar_kin *k);

/* Newton on Phi(q, angle) = 0 from the guess in q (fb_planar_nq), the
 * drive at angle [rad] from the assembly configuration; q receives the
 * solution. *iterations (may be NULL) the steps taken.
 * Errors: FB_ERR_ASSEMBLY when Newton does not converge within
 * FB_PLANAR_NEWTON_MAX steps, diverges, meets a singular Jacobian or ends
 * with a residual above FB_PLANAR_CLOSE_TOL (the message names the joint
 * with the largest residual and its size in mm); q then holds the last
 * iterate. */
fb_status fb_planar_position(fb_planar_kin *k, double *q, double angle, int *iterations,
                             fb_diag *diag);

/* Velocities qd and accelerations qdd (either may be NULL) at a solved
 * position q for the drive's rate and acceleration in d (its angle is not
 * used), from one LU of Phi_q(q). *sign (may be NULL) receives the sign of
 * det Phi_q (+1, -1): it changes where a path passes a singular position.
 * Errors: FB_ERR_ASSEMBLY when Phi_q is singular at q. */
fb_status fb_planar_motion(fb_planar_kin *k, double *qd, double *qdd, const double *q,
                           const fb_planar_drive *d, int *sign, fb_diag *diag);

/* x = Phi_q^-T rhs (fb_planar_nq each) with the factorisation of Phi_q(q)
 * that the last successful fb_planar_motion(k, ..., q, ...) left in k
 * (planar_lu.h's transposed solve), no second factorisation: the Lagrange
 * multipliers of planar_invdyn.h's fb_planar_invdyn_kin. */
void fb_planar_kin_solve_transposed(fb_planar_kin *k, const double *rhs, double *x);

/* Room for 5 fb_planar_nq values that k owns (planar_path.c's predictor
 * and trial motion, so that following a path allocates nothing). */
double *fb_planar_kin_scratch(fb_planar_kin *k);

/* The Jacobian Phi_q of the last factorisation (fb_planar_motion's q),
 * the square set of planar_sparse.h: its values (returned), each entry's
 * column (*col) and each row's first entry (*rowptr, n + 1: row r's
 * entries are rowptr[r] .. rowptr[r + 1] - 1); *mult (may be NULL): room
 * for 2 n values k owns (planar_invdyn.c's right-hand side and
 * multipliers). */
const double *fb_planar_kin_jacobian(fb_planar_kin *k, const int **col, const int **rowptr,
                                     double **mult);

/* The joint whose rows hold the largest scaled residual of Phi at q and
 * that residual [m] (lengths) or [rad]; -1 for the drive's row. */
int fb_planar_worst_joint(fb_planar_kin *k, const double *q, double angle, double *residual);

#endif
