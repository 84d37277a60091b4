/* The free start of an undriven description (m->drive < 0, [drive] joint
 * = none, docs/planar.md): every body at its assembly configuration with
 * the angular velocity the case gives it ([body.NAME]
 * initial_omega_rad_s), the bodies' linear velocities derived from the
 * joints that hold (all but the clearance joints).
 *
 * The choice: the case gives the angular rates, the joints' velocity
 * equations G q' = 0 (planar_constraints.h) then fix the linear ones,
 * G_v v = -G_w w (G_v the columns of the x and y rates, G_w those of the
 * angles), solved by least squares (GSL's SVD, the minimum-norm solution
 * where the joints leave a linear rate free: it is then 0). Rates the
 * joints cannot hold are refused with the residual, not projected: a
 * projection would silently start a different motion from the one the
 * case asked for. A four-bar's three angular rates, for example, are tied
 * by its one degree of freedom; a slider with clearance in its guide
 * leaves the crank's, the rod's and the slider's free. */
#ifndef FB_PLANAR_START_H
#define FB_PLANAR_START_H

#include "planar.h"

/* Largest residual of the joints' velocity equations allowed at the
 * start, relative to the description's size times the largest given
 * angular rate: 1e-9, about 1e6 times the rounding of the least-squares
 * solve (rows of O(1) entries, a few dozen of them), far below any rate a
 * case gives to 4 significant digits that the joints cannot hold. */
#define FB_PLANAR_START_TOL 1e-9

/* y0 (2 nq) = (q, q') at the assembly with body b's angular rate
 * omega0[b] (nbodies; [0], the ground's, ignored) [rad/s] and the linear
 * rates from the joints not flagged in off (njoints; NULL: all joints).
 * Errors: FB_ERR_ARG when the joints cannot hold the rates (the message
 * names the joint with the largest residual and the residual in m/s or
 * rad/s); FB_ERR_RANGE for a non-finite rate; FB_ERR_NOMEM. */
fb_status fb_planar_free_start(double *y0, const fb_planar *m, const unsigned char *off,
                               const double *omega0, fb_diag *diag);

#endif
