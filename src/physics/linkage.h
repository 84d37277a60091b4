/* Exact kinematics of the planar four-bar linkage (closed form, loop closure).
 *
 *            C
 *           / \
 *  coupler /   \ follower
 *         B     \
 *  crank /       \
 *       A ------- D        A = (0, 0), D = (ground, 0)
 *          ground
 *
 * Angles are measured counter-clockwise from +x: the crank angle theta2 is the
 * direction A->B, the coupler angle theta3 the direction B->C, the follower
 * angle theta4 the direction D->C. Loop closure (vector form):
 *   crank e^{i theta2} + coupler e^{i theta3} - follower e^{i theta4} - ground = 0.
 * Velocities and accelerations solve the first and second time derivatives of
 * that equation exactly (R. L. Norton, Design of Machinery, 5th ed., sec. 4.5,
 * 6.7 and 7.3); no finite differences are involved.
 *
 * Branches: on the open branch, C lies to the left of the directed line B->D
 * (the quadrilateral ABCD does not cross itself for a crank-rocker); on the
 * crossed branch, to the right. All lengths are in metres.
 */
#ifndef FB_LINKAGE_H
#define FB_LINKAGE_H

#include <stddef.h>

#include "links.h"
#include "status.h"

/* Lower-case name of a link ("crank", "coupler", "follower", "ground"). */
const char *fb_link_name(fb_link link);

/* Grashof class (Norton, Design of Machinery, sec. 2.12). s, l, p, q are the
 * shortest, longest and the two other link lengths. */
typedef enum {
  FB_GRASHOF_CRANK_ROCKER,   /* s + l < p + q, shortest is the crank */
  FB_GRASHOF_DOUBLE_CRANK,   /* s + l < p + q, shortest is the ground */
  FB_GRASHOF_DOUBLE_ROCKER,  /* s + l < p + q, shortest is the coupler */
  FB_GRASHOF_ROCKER_CRANK,   /* s + l < p + q, shortest is the follower */
  FB_GRASHOF_CHANGE_POINT,   /* s + l = p + q (to FB_GRASHOF_REL_TOL) */
  FB_GRASHOF_NON_GRASHOF     /* s + l > p + q: triple rocker */
} fb_grashof;

/* Relative tolerance on s + l = p + q for the change-point class: lengths are
 * manufactured to microns, so equality closer than 1e-12 relative is equality
 * to double precision and nothing looser would be safe to call singular. */
#define FB_GRASHOF_REL_TOL 1e-12

/* Name of a Grashof class ("crank-rocker", "double-crank", "double-rocker",
 * "rocker-crank", "change-point", "non-Grashof"). */
const char *fb_grashof_name(fb_grashof g);

/* Full kinematic state at one crank angle. */
typedef struct {
  double crank_angle;        /* theta2 [rad] */
  double crank_omega;        /* d theta2 / dt [rad/s] */
  double crank_alpha;        /* d^2 theta2 / dt^2 [rad/s^2] */
  double coupler_angle;      /* theta3, direction B->C [rad] in (-pi, pi] */
  double coupler_omega;      /* [rad/s] */
  double coupler_alpha;      /* [rad/s^2] */
  double follower_angle;     /* theta4, direction D->C [rad] in (-pi, pi] */
  double follower_omega;     /* [rad/s] */
  double follower_alpha;     /* [rad/s^2] */
  double transmission_angle; /* mu, angle BCD between coupler and follower [rad] in [0, pi] */
  double b[2];               /* coupler pin B (crank-coupler joint) [m] (x, y) */
  double c[2];               /* C (coupler-follower joint) [m] (x, y) */
} fb_linkage_state;

/* Checks that every length is finite and positive.
 * Errors: FB_ERR_RANGE naming the link and its value. */
fb_status fb_linkage_check(const fb_linkage *lk, fb_diag *diag);

/* Grashof class of a linkage with valid lengths. */
fb_grashof fb_linkage_grashof(const fb_linkage *lk);

/* The sums the Grashof class compares, for a linkage with valid lengths:
 * *sl = s + l (shortest plus longest link) and *pq = p + q (the other two)
 * [m]; *shortest and *longest receive the links' indices (fb_link; may be
 * NULL). s + l < p + q: the shortest link turns fully (Grashof); equal:
 * change-point; greater: no link turns fully (Norton, Design of Machinery,
 * sec. 2.12). */
void fb_linkage_grashof_sums(const fb_linkage *lk, double *sl, double *pq, int *shortest,
                             int *longest);

/* One sentence on the Grashof class of a linkage with valid lengths into
 * out (size bytes): the class, the sums it compares in mm with the margin
 * p + q - (s + l), and what turns fully; for a change-point linkage, the
 * crank angles where it folds flat (fb_linkage_fold_angles). E.g.
 * "Grashof crank-rocker: s + l = 45 + 170 = 215 mm < p + q = 270 mm (margin
 * 55 mm): the crank, the shortest link, turns fully; the follower rocks". */
void fb_linkage_grashof_text(char *out, size_t size, const fb_linkage *lk);

/* Crank angles theta2 [rad] (0 and/or pi) at which all four pivots lie on
 * one line: the folded positions a change-point linkage passes through,
 * where its assembly branch may switch and the velocity problem is singular
 * (|BD| equals |coupler - follower| or coupler + follower with B on the
 * ground line; to FB_GRASHOF_REL_TOL of the length sum). Writes up to 2
 * angles to out and returns how many. */
int fb_linkage_fold_angles(const fb_linkage *lk, double out[2]);

/* Solves positions, velocities and accelerations at crank angle theta2 [rad]
 * with crank speed omega2 [rad/s] and crank angular acceleration alpha2
 * [rad/s^2] on the given branch.
 * Errors: FB_ERR_ASSEMBLY when the linkage cannot be assembled at theta2
 * (|coupler - follower| > |BD| or |BD| > coupler + follower), or when it sits
 * exactly at a toggle position where the velocity problem is singular;
 * FB_ERR_RANGE for invalid lengths. out is left untouched on error. */
fb_status fb_linkage_solve(fb_linkage_state *out, const fb_linkage *lk,
                           fb_branch branch, double theta2, double omega2,
                           double alpha2, fb_diag *diag);

/* Partial derivatives of coupler and follower angular velocity and
 * acceleration with respect to each link length, at fixed crank angle theta2,
 * crank speed omega2 and zero crank acceleration, by implicit differentiation
 * of the loop-closure equations and their first two time derivatives (exact,
 * no finite differences). Rows: omega3, omega4, alpha3, alpha4; columns:
 * crank, coupler, follower, ground. Units [rad/s/m] and [rad/s^2/m].
 * Errors: those of fb_linkage_solve. */
fb_status fb_linkage_sensitivity(double out[4][FB_LINK_COUNT], const fb_linkage *lk,
                                 fb_branch branch, double theta2, double omega2, fb_diag *diag);

/* Crank angles at which the linkage can be assembled. The assemblable set is
 * symmetric about the ground line: |theta2| in [lo, hi] (wrapped to [0, pi]).
 * Full rotation means lo == 0 and hi == pi with no toggle of coupler and
 * follower on the way, which is the strict condition
 *   coupler + follower > crank + ground and |coupler - follower| < |ground - crank|.
 * Derivation: |BD|^2 = crank^2 + ground^2 - 2 crank ground cos theta2 must lie
 * in [(coupler - follower)^2, (coupler + follower)^2].
 * Returns FB_OK with *lo, *hi [rad] and *full (1 when the crank can turn a full
 * revolution), or FB_ERR_ASSEMBLY when no crank angle assembles. */
fb_status fb_linkage_crank_range(const fb_linkage *lk, double *lo, double *hi,
                                 int *full, fb_diag *diag);

/* Transmission angle extremes over the crank angles that assemble [rad]:
 * mu = acos((coupler^2 + follower^2 - |BD|^2) / (2 coupler follower)), with
 * |BD| extremal at the ends of the crank range (theta2 = lo and hi).
 * Errors as fb_linkage_crank_range. */
fb_status fb_linkage_transmission_range(const fb_linkage *lk, double *mu_min,
                                        double *mu_max, fb_diag *diag);

#endif
