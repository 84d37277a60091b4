/* The constrained inverse mass of a planar description: the accelerations
 * forces give a mechanism whose joints (all, or all but its clearance
 * joints) and drive hold, and the effective mass at any joint along any
 * direction.
 *
 * With M = diag(m, m, I) per moving body (centre-of-mass frames, so M is
 * constant and diagonal), G the Jacobian of the joints left in the set
 * and the drive's row (planar_constraints.h), and S = G M^-1 G^T
 * (positive definite when G has full row rank), the equations of motion
 *   M q'' + G^T lambda = Q,   G q'' = gamma
 * (an index-1 DAE: the constraints at the acceleration level) are solved
 * by the Schur complement
 *   S lambda = G M^-1 Q - gamma,   q'' = M^-1 (Q - G^T lambda),
 * S factorised once per configuration with GSL's Cholesky
 * (gsl_linalg_cholesky_decomp1). lambda are the Lagrange multipliers:
 * -G^T lambda is the joints' and the drive's force on the bodies.
 *
 * The effective mass at joint j along unit n: with J the Jacobian of the
 * joint's point on body[0] (the pin) minus its point on body[1] (the
 * hole), W = J P J^T, P = M^-1 - M^-1 G^T S^-1 G M^-1 (the inverse mass in
 * the coordinates the constraints leave free; the drive held, as a
 * velocity motor is infinitely heavy), m_eff = 1 / (n^T W n): the
 * Gauss/KKT form of the operational-space inertia (Featherstone, Rigid
 * Body Dynamics Algorithms, 2008, sec. 8.2; Khatib 1987), the form of
 * effective_mass.h written for any description. */
#ifndef FB_PLANAR_MASS_H
#define FB_PLANAR_MASS_H

#include "planar_constraints.h"

/* The workspace of one constraint set (sized once). */
typedef struct fb_planar_cmass fb_planar_cmass;

/* A workspace for m with the joints flagged in off (njoints; NULL: none)
 * left out of the set and the drive's row in it (none when m is undriven,
 * m->drive < 0: then the drive arguments below are ignored). Every moving body needs a
 * positive mass and inertia (fb_planar_add_body checks it).
 * Errors: FB_ERR_NOMEM. */
fb_status fb_planar_cmass_new(fb_planar_cmass **out, const fb_planar *m,
                              const unsigned char *off, fb_diag *diag);

void fb_planar_cmass_free(fb_planar_cmass *c);

/* Rows of the set (fb_planar_rows). */
int fb_planar_cmass_rows(const fb_planar_cmass *c);

/* Evaluates G at q and factorises S = G M^-1 G^T + reg max(diag S) I
 * (reg >= 0: 0 for the dynamics; FB_EFFECTIVE_MASS_REG, effective_mass.h,
 * for an effective mass that must exist at a dead point of the chain).
 * Errors: FB_ERR_NUMERIC when S is not positive definite (the set is
 * redundant or singular at q). */
fb_status fb_planar_cmass_factor(fb_planar_cmass *c, const double *q, double reg,
                                 fb_diag *diag);

/* q'' (nq) and lambda (rows; may be NULL) for generalised forces force
 * (nq: per body f_x, f_y [N], moment about its centre [N m]) and the
 * acceleration equation's gamma (rows), at the configuration last
 * factorised. */
void fb_planar_cmass_accel(fb_planar_cmass *c, double *qdd, double *lambda, const double *force,
                           const double *gamma);

/* The inverse-mass tensor W (2 x 2, [1/kg]) of joint j's relative motion
 * (its point on body[0] minus its point on body[1]) at q, the
 * configuration last factorised. */
void fb_planar_cmass_tensor(fb_planar_cmass *c, double w[2][2], int j, const double *q);

/* Most contacts fb_planar_cmass_delassus takes. */
#define FB_PLANAR_CMASS_MAX_CONTACTS 4

/* The Delassus matrix d (k x k, row-major) [1/kg] of k <= 
 * FB_PLANAR_CMASS_MAX_CONTACTS contacts at q (the configuration last
 * factorised): contact r's normal velocity n_r . (v(b0_r, s0_r) -
 * v(b1_r, s1_r)) (points s in their bodies' frames [m], n_r unit (2)),
 * d = J P J^T with J (k x nq) those rows and P the constrained inverse
 * mass above (Moreau's and Siconos's W = H^T M^-1 H in the joints' free
 * coordinates); d[r][r] = 1 / m_eff of contact r alone. */
void fb_planar_cmass_delassus(fb_planar_cmass *c, double *d, int k, const int *b0,
                              const double (*s0)[2], const int *b1, const double (*s1)[2],
                              const double (*n)[2], const double *q);

/* The same for any two points: the relative motion of point s0 (2, body
 * b0's frame) minus point s1 (2, body b1's frame) [m] (a slider's corner
 * against its guide, planar_guide.h). */
void fb_planar_cmass_tensor_points(fb_planar_cmass *c, double w[2][2], int b0, const double s0[2],
                                   int b1, const double s1[2], const double *q);

/* q (in, out) moved to the closest position of the set (mass-weighted
 * least squares: dq = -M^-1 G^T S^-1 Phi, repeated until the correction is
 * below FB_PLANAR_NEWTON_STOP, at most 4 times) with the drive at angle,
 * and qd to the closest velocities (dqd = -M^-1 G^T S^-1 (G qd - nu), nu
 * the drive's rate omega in its row); leaves the configuration factorised
 * at the new q. *dq_max and *dv_max (may be NULL) receive the largest
 * residual before the projection: |Phi| [m] of the joints' rows and
 * |G qd - nu| [m/s].
 * Errors: those of fb_planar_cmass_factor. */
fb_status fb_planar_cmass_project(fb_planar_cmass *c, double *q, double *qd,
                                  const fb_planar_drive *d, double *dq_max, double *dv_max,
                                  fb_diag *diag);

/* Effective mass tensor W at joint j (one of those flagged in off) of m at
 * q, with the flagged joints out of the set and the drive held; S
 * regularised by FB_EFFECTIVE_MASS_REG (effective_mass.h) as
 * fb_effective_mass_tensor_kkt does, so that the two agree; m_eff along n
 * is fb_effective_mass_along(w, n). Errors: FB_ERR_ARG when j is not
 * flagged in off; FB_ERR_NOMEM; FB_ERR_NUMERIC. */
fb_status fb_planar_effective_mass_tensor(double w[2][2], const fb_planar *m, const double *q,
                                          const unsigned char *off, int j, fb_diag *diag);

/* The mass a clearance joint j's law starts from [kg]: its two bodies'
 * reduced mass m_a m_b / (m_a + m_b), the moving body's mass at a ground
 * joint (joint_law.h's rule); the damper then sits on the effective mass
 * at each evaluation (contact_mass.h). */
double fb_planar_joint_law_mass(const fb_planar *m, int j);

#endif
