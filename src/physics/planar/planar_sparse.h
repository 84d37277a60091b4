/* The square constraint set of a planar description of one degree of
 * freedom in sparse form: every joint's two rows (joint j: rows 2 j and
 * 2 j + 1, planar_constraints.h's equations) and one angle row last, the
 * relative angle of joint aj's bodies (the drive's joint: the drive's row;
 * another revolute joint: the free coordinate of an undriven description).
 * n = fb_planar_nq rows and columns; each row holds only its bodies'
 * entries (2 to 6), so that the Jacobian costs what its entries do and
 * factorises by planar_lu.h in the chain's length, not its square.
 *
 * Every function takes the bodies' cosines and sines once
 * (fb_planar_sq_trig), not one rotation per joint point: the same values
 * as planar_constraints.c's to the rounding of a product. Pure functions,
 * no allocation. tests/test_planar_sparse.c checks them against
 * planar_constraints.h's dense forms. */
#ifndef FB_PLANAR_SPARSE_H
#define FB_PLANAR_SPARSE_H

#include "planar.h"

/* The bodies of joint aj's angle row: *from (the ground when the joint
 * touches it, else body[0]) and *to (the other), as fb_planar_drive_bodies
 * takes the drive's; the row is theta_to - theta_from - (its assembly
 * value). */
void fb_planar_sq_angle_bodies(const fb_planar *m, int aj, int *from, int *to);

/* Entries of the set's Jacobian (the pattern's size). */
int fb_planar_sq_nnz(const fb_planar *m, int aj);

/* The pattern: entry e at (row[e], col[e]) (fb_planar_sq_nnz each). */
void fb_planar_sq_pattern(const fb_planar *m, int aj, int *row, int *col);

/* Every body's cosine and sine at q into cs (2 nbodies: cs[2 b], cs[2 b
 * + 1]; the ground's 1, 0). */
void fb_planar_sq_trig(double *cs, const fb_planar *m, const double *q);

/* The Jacobian's values at q (cs its trig) in the pattern's order. */
void fb_planar_sq_values(double *val, const fb_planar *m, int aj, const double *q,
                         const double *cs);

/* Phi (n) at q: the joints' rows, and the angle row without the drive's
 * angle (the caller subtracts its target). */
void fb_planar_sq_phi(double *phi, const fb_planar *m, int aj, const double *q, const double *cs);

/* gamma (n) at q, qd: -(Phi_q qd)_q qd of every row (the angle row's 0:
 * the caller adds the drive's acceleration). */
void fb_planar_sq_gamma(double *gamma, const fb_planar *m, int aj, const double *q,
                        const double *qd, const double *cs);

/* Joint j's two rows alone (its rows of the above): Phi_j at q, Phi_j,q x
 * for any x (nq; the rows' Jacobian applied to it) and gamma_j at q, qd. */
void fb_planar_sq_joint_phi(double out[2], const fb_planar *m, int j, const double *q,
                            const double *cs);
void fb_planar_sq_joint_apply(double out[2], const fb_planar *m, int j, const double *q,
                              const double *cs, const double *x);
void fb_planar_sq_joint_gamma(double out[2], const fb_planar *m, int j, const double *q,
                              const double *qd, const double *cs);

#endif
