/* Inverse dynamics of the ideal slider-crank in closed form: the joint
 * reactions, the guide's normal force and the crank drive torque that make
 * rigid links follow the exact kinematics (slider_crank.h), gravity
 * included.
 *
 *                  B           F_A: ground on crank (ground-crank)
 *                 / \          F_B: crank on coupler (crank-coupler)
 *          crank /   \ coupler F_C: coupler on slider (coupler-slider, the piston pin)
 *               /     \        N:   ground on slider along +y (slider-ground, the guide)
 *              A       [ C ]   T:   drive torque on the crank from ground, about +z
 *
 * Planar Newton-Euler, solved body by body from the slider back to the
 * crank (no linear system):
 *   slider   m4 a_C = F_C + N y - m4 g y, a_C = (a, 0):
 *              F_Cx = m4 a,  N = m4 g - F_Cy;
 *   coupler  m3 a_G3 = F_B - F_C - m3 g y,
 *            (B - G3) x F_B - (C - G3) x F_C = I3 alpha3; eliminating F_B,
 *              F_Cy = [I3 alpha3 - (B - G3) x m3 (a_G3 + g y) + (B - C)_y F_Cx] / (B - C)_x,
 *              F_B = m3 (a_G3 + g y) + F_C, with (B - C)_x = -coupler cos theta3 != 0;
 *   crank    F_A = m2 (a_G2 + g y) + F_B,
 *            T = I2 alpha2 - (A - G2) x F_A + (B - G2) x F_B.
 * The guide is frictionless; its reaction is the normal force N through the
 * piston pin C plus a couple that is zero here, since every force on the
 * slider passes through C (its centre of mass is at the pin: the slider's
 * inertia never enters). Gravity acts along -y. Same sign conventions as
 * invdyn.h (force on the second-named body from the first).
 * Source: the Newton-Euler equations of each body, as in Norton, Design of
 * Machinery, ch. 11 (force analysis of the slider-crank); the elimination
 * order above is ours. */
#ifndef FB_SLIDER_CRANK_INVDYN_H
#define FB_SLIDER_CRANK_INVDYN_H

#include "case.h"
#include "slider_crank.h"

/* Mass properties of the slider-crank's moving bodies. Each link's centre of
 * mass lies on the line between its joints at com_fraction of the way from
 * its first joint (crank: A->B, coupler: B->C); the slider's is at the
 * piston pin C. */
typedef struct {
  double crank_mass;            /* m2 [kg] */
  double crank_inertia;         /* I2 about +z through the crank's centre of mass [kg m^2] */
  double crank_com_fraction;    /* f2 along A->B [-] in [0, 1] */
  double coupler_mass;          /* m3 [kg] */
  double coupler_inertia;       /* I3 about +z through the rod's centre of mass [kg m^2] */
  double coupler_com_fraction;  /* f3 along B->C [-] in [0, 1] */
  double slider_mass;           /* m4 [kg] */
} fb_slider_crank_mass;

/* The mass properties of a case's links (case.h fb_link_mass: crank,
 * coupler, slider, each centre of mass at com_fraction along its link; the
 * slider's inertia and centre do not enter: it is at the piston pin). */
fb_slider_crank_mass fb_slider_crank_mass_of(const fb_link_mass link[3]);

/* Joints of the slider-crank, in the order of the reactions' arrays; the
 * prismatic slider-ground joint comes last (its reaction is the scalar N). */
typedef enum {
  FB_SC_JOINT_GROUND_CRANK = 0,   /* A */
  FB_SC_JOINT_CRANK_COUPLER = 1,  /* B */
  FB_SC_JOINT_COUPLER_SLIDER = 2, /* C, the piston pin */
  FB_SC_JOINT_SLIDER_GROUND = 3,  /* the guide (prismatic) */
  FB_SC_JOINT_COUNT = 4
} fb_sc_joint;

/* Number of revolute joints (A, B, C): the rows of the force arrays. */
#define FB_SC_PIN_COUNT 3

/* "ground-crank", "crank-coupler", "coupler-slider", "slider-ground". */
const char *fb_sc_joint_name(fb_sc_joint j);

/* Checks masses and inertias (finite, >= 0) and centre-of-mass fractions
 * (in [0, 1]). Errors: FB_ERR_RANGE naming the field and its value. */
fb_status fb_slider_crank_mass_check(const fb_slider_crank_mass *m, fb_diag *diag);

/* Joint reactions at one crank angle, SI. */
typedef struct {
  double force[FB_SC_PIN_COUNT][2]; /* A on crank from ground, B on coupler from crank,
                                       C on slider from coupler (x, y) [N] (3 x 2) */
  double guide_force;               /* N: on the slider from the guide, along +y [N] */
  double drive_torque;              /* on the crank from ground, about +z [N m] */
  /* components of each pin force in the frame of a link at the joint: A and B
   * in the crank frame, C in the coupler frame; radial along the link (from
   * its first joint to its second), tangential perpendicular to it (+90 deg) */
  double radial[FB_SC_PIN_COUNT];     /* [N] (3) */
  double tangential[FB_SC_PIN_COUNT]; /* [N] (3) */
} fb_slider_crank_reactions;

/* Inputs: geometry, mass properties, gravity magnitude along -y [m/s^2],
 * crank angle [rad], crank speed [rad/s] and crank angular acceleration
 * [rad/s^2]. Errors: those of fb_slider_crank_solve and
 * fb_slider_crank_mass_check. out is left untouched on error. */
fb_status fb_slider_crank_invdyn(fb_slider_crank_reactions *out, const fb_slider_crank *sc,
                                 const fb_slider_crank_mass *m, double gravity, double theta2,
                                 double omega2, double alpha2, fb_diag *diag);

/* Largest magnitudes over one crank revolution at constant speed omega2
 * [rad/s], sampled at n >= 1 crank angles 2 pi k / n: each pin force
 * (force_max, 3) [N], the guide's normal force |N| [N] and the drive torque
 * |T| [N m]. Any output pointer may be NULL.
 * Errors: FB_ERR_ARG for n < 1; those of fb_slider_crank_require_full_turn
 * and fb_slider_crank_invdyn. */
fb_status fb_slider_crank_invdyn_peaks(double force_max[FB_SC_PIN_COUNT], double *guide_max,
                                       double *torque_max, const fb_slider_crank *sc,
                                       const fb_slider_crank_mass *m, double gravity,
                                       double omega2, int n, fb_diag *diag);

#endif
