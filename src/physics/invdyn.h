/* Inverse dynamics of the ideal four-bar: the joint reactions and the crank
 * drive torque that make the rigid links follow the exact kinematics at
 * constant crank speed, gravity included. Planar Newton-Euler for the three
 * moving links gives 9 linear equations in 9 unknowns (two force components
 * at each of the four joints, and the drive torque), solved by LU
 * decomposition (GSL gsl_linalg_LU). Reference: Norton, Design of Machinery,
 * sec. 11.5 (four-bar force analysis). */
#ifndef FB_INVDYN_H
#define FB_INVDYN_H

#include "case.h"
#include "linkage.h"

/* Joint reactions at one crank angle, SI. Sign convention: the force at a
 * joint acts on the second-named body from the first: A on the crank from
 * ground, B on the coupler from the crank, C on the follower from the
 * coupler, D on the follower from ground. */
typedef struct {
  double force[4][2];  /* A, B, C, D (x, y) [N] (4 x 2) */
  double drive_torque; /* on the crank from ground, about +z [N m] */
  /* components of each joint force in the frame of the link that carries the
   * joint's pin: A and B in the crank frame, C and D in the follower frame;
   * radial along the link (from its first joint to its second), tangential
   * perpendicular to it (+90 deg) */
  double radial[4];     /* [N] (4) */
  double tangential[4]; /* [N] (4) */
} fb_reactions;

/* Inputs: link lengths, branch, the three moving links' mass properties,
 * gravity magnitude along -y [m/s^2], crank angle [rad] and signed crank
 * speed [rad/s] (constant). Errors: those of fb_linkage_solve; FB_ERR_NUMERIC
 * if the system is singular. */
fb_status fb_invdyn_solve(fb_reactions *out, const fb_linkage *lk, fb_branch branch,
                          const fb_link_mass link[3], double gravity, double theta2,
                          double omega2, fb_diag *diag);

/* Largest magnitude of each joint's reaction and of its tangential component
 * over one crank revolution sampled at n crank angles. Outputs (4) [N] each;
 * either pointer may be NULL. */
fb_status fb_invdyn_peaks(double force_max[4], double tangential_max[4], const fb_linkage *lk,
                          fb_branch branch, const fb_link_mass link[3], double gravity,
                          double omega2, int n, fb_diag *diag);

#endif
