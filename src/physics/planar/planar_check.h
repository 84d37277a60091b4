/* Checks a planar description before anything runs on it, with errors that
 * name the joint or body:
 *   connected    every moving body is joined to the ground through joints;
 *   one degree   the Gruebler-Kutzbach count 3 (n - 1) - 2 j is 1, which the
 *     of freedom drive takes (n bodies with the ground, j joints, each
 *                revolute or prismatic joint removing two);
 *   rank         the Jacobian with the drive's row, Phi_q, is of full rank
 *                at the assembly configuration (its smallest singular
 *                value, GSL's SVD of the scaled matrix, above
 *                FB_PLANAR_RANK_TOL of its largest): the count alone
 *                passes a mechanism with a redundant joint and a body left
 *                free, or one assembled at a toggle;
 *   closes       Newton on the loop equations from the assembly
 *                configuration converges (planar_kinematics.h);
 *   turns        the drive turns a full revolution without locking or
 *                passing a singular position (planar_path.h) and brings
 *                the mechanism back to its assembly configuration (no
 *                branch switched on the way).
 * Lengths are scaled by the description's size (fb_planar_size) and angle
 * rows and columns by it too, so that the singular values compare lengths
 * with lengths. */
#ifndef FB_PLANAR_CHECK_H
#define FB_PLANAR_CHECK_H

#include "planar.h"
#include "planar_case.h"

/* Smallest singular value of the scaled Phi_q, relative to its largest,
 * that counts as full rank: 1e-8. At a toggle the value falls to the
 * rounding level (~1e-16); near one it falls as the square root of the
 * drive angle still to go (a fold: the positions move as that root), so a
 * mechanism 0.1 degree from a toggle keeps ~1e-2 (measured 3e-5 to 7e-5
 * at 1e-7 rad from one, tests/test_planar_check.c): the threshold sits
 * far from both. */
#define FB_PLANAR_RANK_TOL 1e-8

/* After one revolution every body's position is its start's to this,
 * relative to the size (angles to this in radians, modulo 2 pi): both
 * come from Newton solutions at machine precision. */
#define FB_PLANAR_RETURN_TOL 1e-9

/* Runs every check in the order above; *where (may be NULL) receives the
 * joint or body the first failure is about. Errors: FB_ERR_ARG
 * (connectivity, the count, the rank, no drive), FB_ERR_ASSEMBLY (does not
 * close, locks, passes a singular position, does not come back),
 * FB_ERR_NOMEM; one sentence in diag naming the joint or body and the
 * rule. */
fb_status fb_planar_check(const fb_planar *m, fb_planar_where *where, fb_diag *diag);

/* The first two checks alone (connected, one degree of freedom), which
 * need no mass: fb_planar_compile runs them before it refuses a body whose
 * mass no bar gives, so that a joint missing is said as such. Errors:
 * FB_ERR_ARG, as fb_planar_check's. */
fb_status fb_planar_check_structure(const fb_planar *m, fb_planar_where *where, fb_diag *diag);

#endif
