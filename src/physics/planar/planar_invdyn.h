/* Inverse dynamics of a planar description: the joint reactions and the
 * drive torque that make its rigid bodies follow a motion (q, q', q''),
 * gravity, springs and loads included, from the Lagrange multipliers of
 * its constraints.
 *
 * With the drive's row the Jacobian Phi_q is square, so the equations of
 * motion M q'' + Phi_q^T lambda = Q (Q: gravity, (0, -m g, 0) per body,
 * with the springs' and loads' generalised forces, planar_loads.h)
 * give the multipliers alone: Phi_q^T lambda = Q - M q'', solved with the
 * transpose of the kinematics' sparse LU of Phi_q (planar_lu.h). A joint's rows' -Phi_q^T lambda in one body's columns are
 * the force and moment (about its centre) the joint puts on that body
 * (Haug 1989, sec. 6.6: reaction forces from Lagrange multipliers;
 * Nikravesh 1988, sec. 6.4). The force on a joint's body[1] from its
 * body[0], for every joint (invdyn.h's D, follower-ground, is the other way:
 * on the follower from the ground); the drive torque on the driven body
 * from the drive, about +z. tests/test_planar_invdyn.c checks the
 * four-bar's against invdyn.h and the slider-crank's against
 * slider_crank_invdyn.h. */
#ifndef FB_PLANAR_INVDYN_H
#define FB_PLANAR_INVDYN_H

#include "planar_kinematics.h"

/* One joint's reaction. */
typedef struct {
  double force[2]; /* on body[1] from body[0] (x, y) [N]: a prismatic joint's is normal to its
                      slide */
  double moment;   /* about +z at the joint's point on body[1] (on body[0] when body[1] is the
                      ground), on body[1] from body[0] [N m]: zero for a revolute joint (a
                      pin carries no moment); a prismatic joint's couple */
} fb_planar_reaction;

/* Reactions of every joint (out, njoints) and the drive torque [N m] for
 * the motion q, qd, qdd (fb_planar_nq each) of m under gravity [m/s^2]
 * along -y. Errors: FB_ERR_ASSEMBLY when Phi_q is singular at q (a locked
 * position: the reactions are not determined); FB_ERR_ARG when m has no
 * drive or is not of one degree of freedom; FB_ERR_NOMEM. */
fb_status fb_planar_invdyn(fb_planar_reaction *out, double *drive_torque, const fb_planar *m,
                           const double *q, const double *qd, const double *qdd, double gravity,
                           fb_diag *diag);

/* fb_planar_invdyn's reactions and drive torque at the motion q, qd, qdd, with
 * the LU of Phi_q(q) that the last successful fb_planar_motion(k, ..., q,
 * ...) left in k (fb_planar_kin_solve_transposed): no factorisation of its
 * own. The same multipliers to the rounding level (the two solves' roundings
 * differ). Errors: FB_ERR_ASSEMBLY when a multiplier is not finite;
 * FB_ERR_NOMEM. */
fb_status fb_planar_invdyn_kin(fb_planar_reaction *out, double *drive_torque, fb_planar_kin *k,
                               const double *q, const double *qd, const double *qdd,
                               double gravity, fb_diag *diag);

/* Every joint's reaction over a revolution of the drive at constant signed
 * speed omega [rad/s] from the assembly configuration (gravity [m/s^2]
 * along -y): out (n x njoints) row i the reactions at drive angle
 * 2 pi i / n, the positions followed from one angle to the next
 * (planar_path.h). Errors: those of planar_path.h and fb_planar_invdyn;
 * FB_ERR_NOMEM. */
fb_status fb_planar_reactions_over(fb_planar_reaction *out, int n, const fb_planar *m,
                                   double omega, double gravity, fb_diag *diag);

/* Every joint's largest reaction magnitude |force| over a revolution of
 * the drive at constant signed speed omega [rad/s] from the assembly
 * configuration (FB_PLANAR_PEAK_SAMPLES drive angles followed by
 * planar_path.h, gravity [m/s^2] along -y) into most (njoints) [N]: the
 * working force of a joint's contact law (joint_law.h) and of fourbar
 * penalty. Errors: those of planar_path.h and fb_planar_invdyn. */
fb_status fb_planar_reaction_max(double *most, const fb_planar *m, double omega, double gravity,
                                 fb_diag *diag);

#endif
