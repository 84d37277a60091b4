/* A planar description of one degree of freedom as a spanning tree and its
 * loop closures: the positions, velocities and accelerations of every body
 * from one coordinate per moving body and the clearance joints' relative
 * coordinates, by recursion from the ground, and the closure equations
 * that tie the coordinates together (planar_relative.h's kinematics).
 *
 * The tree: a breadth-first search from the ground over the joints; each
 * moving body b hangs from its parent by its tree joint, and its
 * coordinate u_b is its absolute angle (a revolute tree joint) or its
 * slide along the joint's axis (a prismatic one, the slide measured from
 * the assembly: d = p_slider - p_guide = s A_guide axis). A clearance
 * joint in the tree carries its relative coordinates into the recursion
 * (a pin's eccentricity e = p_pin - p_hole; a slider's tilt psi and offset
 * y across its slide); every other joint (a cut joint) closes a loop with
 * its two equations (planar_constraints.h's rows), which equal its
 * relative coordinates when it is a clearance joint and zero otherwise.
 * With one angle row (the drive's joint's relative angle = omega t, or an
 * undriven description's free coordinate), the closure F(u, r, t) has
 * nu = (bodies - 1) equations in the nu coordinates: Gruebler's count of
 * one degree of freedom with every joint.
 *
 * The recursions are the standard ones for a tree in absolute angles
 * (Nikravesh 1988, ch. 7; Wittenburg, Dynamics of Multibody Systems,
 * 2008, ch. 5): a revolute child's joint point is its parent's (plus or
 * minus e), its centre r_b = P - A_b s_b; velocities and accelerations by
 * differentiating that, linear in the coordinates' rates. A breadth-first
 * tree keeps each loop short (a chain of four-bar loops closes each loop
 * through its own three bodies), so the closure's Jacobian is banded and
 * planar_lu.h factorises it in the chain's length. */
#ifndef FB_PLANAR_TREE_H
#define FB_PLANAR_TREE_H

#include "planar.h"

/* Largest turn [rad] of a body from its trig's anchor (the angle of its
 * last cosine and sine by libm) for which fb_planar_tree_poses rotates the
 * anchor by the turn's series (cos d and sin d to the fifth order, error
 * below 1.4e-21: a few products, not a libm call). Beyond it libm
 * anchors the body again. */
#define FB_PLANAR_TREE_TURN_MAX 1e-3

/* The tree's workspace. */
typedef struct fb_planar_tree fb_planar_tree;

/* The tree of m with the clearance joints flagged in clearance (njoints)
 * and the angle row of revolute joint aj (the drive's; or, with free = 1,
 * an undriven description's free coordinate, the last relative
 * coordinate). Relative coordinates r: 2 per clearance joint in joint
 * order (its rows 2 j, 2 j + 1 of planar_constraints.h), then the free
 * coordinate. Errors: FB_ERR_ARG when m is not joined to the ground or not
 * of one degree of freedom with every joint; FB_ERR_NOMEM. */
fb_status fb_planar_tree_new(fb_planar_tree **out, const fb_planar *m,
                             const unsigned char *clearance, int aj, int free, fb_diag *diag);

void fb_planar_tree_free(fb_planar_tree *t);

/* Coordinates u (= closure rows), fb_planar_nq / 3. */
int fb_planar_tree_nu(const fb_planar_tree *t);

/* Relative coordinates r. */
int fb_planar_tree_nr(const fb_planar_tree *t);

/* 1 when body b's coordinate is a slide [m] (its tree joint is
 * prismatic), 0 when it is its angle [rad]. */
int fb_planar_tree_is_slide(const fb_planar_tree *t, int b);

/* The closure Jacobian's pattern: entry e at (row[e], col[e]) (its size:
 * fb_planar_tree_nnz); rows and columns nu. */
int fb_planar_tree_nnz(const fb_planar_tree *t);
void fb_planar_tree_pattern(const fb_planar_tree *t, int *row, int *col);

/* The coordinates u (nu) and relative coordinates r (nr; may be NULL) of
 * the positions q (nq); an undriven description's free coordinate is the
 * angle row's value. */
void fb_planar_tree_coords(const fb_planar_tree *t, double *u, double *r, const double *q);

/* The positions q (nq) and every body's cosine and sine cs (2 nbodies) at
 * coordinates u, r. */
void fb_planar_tree_poses(fb_planar_tree *t, double *q, double *cs, const double *u,
                          const double *r);

/* The closure's residual res (nu) at the last pose q (fb_planar_tree_poses)
 * for r and the drive's angle phi [rad] (driven; the free coordinate is
 * r's last otherwise). */
void fb_planar_tree_residual(const fb_planar_tree *t, double *res, const double *q,
                             const double *r, double phi);

/* The closure's Jacobian C_u at the last pose into val (the pattern's
 * order) and its columns along the relative coordinates, C_r (nu x nr,
 * column i at cr + i nu; may be NULL). */
void fb_planar_tree_jacobian(fb_planar_tree *t, double *val, double *cr);

/* C_r alone at the last pose (as fb_planar_tree_jacobian's). */
void fb_planar_tree_jacobian_r(fb_planar_tree *t, double *cr);

/* The velocities qd (nq) at the last pose for coordinate rates ud (nu)
 * and relative rates rd (nr; may be NULL: zero): linear in both. */
void fb_planar_tree_rates(const fb_planar_tree *t, double *qd, const double *ud, const double *rd);

/* The same for ncol columns at once (ud: nu x ncol, rd: nr x ncol, qd: nq
 * x ncol, column-major), the pose's geometry read once per body. */
void fb_planar_tree_rates_many(const fb_planar_tree *t, double *qd, const double *ud,
                               const double *rd, int ncol);

/* The accelerations at the last pose and the velocities qd (the rates of
 * coordinate rates ud, relative rates rd; may be NULL) with no second
 * derivative of any coordinate (the velocities' products) into qdd (nq);
 * the closure's right-hand side for u'' into rhs (nu): C_u u'' = rhs -
 * C_r r'' (plus the drive's acceleration, zero at constant speed, on the
 * angle row). q'' is then qdd + fb_planar_tree_rates(u'', r''). */
void fb_planar_tree_bias(const fb_planar_tree *t, double *qdd, double *rhs, const double *qd,
                         const double *ud, const double *rd);

#endif
