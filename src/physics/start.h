/* The initial state of a run ([run] start and [run] pin_start), resolved
 * once for every model so that ODE and the reference dynamics integrate the
 * same start.
 *
 * Joint points. Each joint j has a pin centre (on its first body: the crank
 * for ground-crank and crank-coupler, the coupler for coupler-follower, the
 * follower for follower-ground) and a hole centre (on its second body;
 * ground for A and D). For an ideal joint they coincide; for a clearance
 * joint the eccentricity e_j = pin_j - hole_j is set by pin_start:
 *   centred  e_j = 0;
 *   resting  |e_j| = c along the static load the joint carries under gravity
 *            alone with the crank held at theta0 (fb_invdyn_solve at zero
 *            speed): the pin touches the wall on the side its body leans on,
 *            with zero penetration (the static approach, ~0.3 um in the
 *            paper's case, is left out);
 *   angle    |e_j| = c at the given angle, counter-clockwise from +x.
 * The loop then closes through the offsets (Flores and Ambrosio's clearance-joint
 * geometry):
 *   A_hole = 0, A_pin = A_hole + e_A, B_pin = A_pin + a u(theta2),
 *   B_hole = B_pin - e_B, C_pin = B_hole + b u(theta3), C_hole = C_pin - e_C,
 *   D_pin = C_hole - f u(theta4), D_hole = D_pin - e_D = (g, 0),
 * so theta3 and theta4 are those of a four-bar whose crank tip is the point
 * B_hole - e_C - e_D: the same circle intersection as fb_linkage_solve, on
 * the case's branch.
 *
 * Velocities. steady: the ideal motion with every offset held fixed (the
 * pins move with their holes): the loop's velocity equations with the
 * displaced crank tip; with all offsets zero this is fb_linkage_solve
 * exactly. rest: the crank turns at omega2 about A_pin from t = 0; the
 * coupler and the follower are at rest when a clearance joint leaves them
 * free of the crank (the Adams start the paper's model had). A model
 * without clearance joints has no such freedom: its coupler and follower
 * get the velocities the ideal joints impose at t = 0, the same as steady
 * (ODE given bodies at rest would itself project them onto the joints in
 * the first step, with an impulse of about I omega and an acceleration
 * spike of about omega / h; the consistent start removes that artefact). */
#ifndef FB_START_H
#define FB_START_H

#include "case.h"

/* Positions and velocities of the three moving bodies at t = 0 (SI). The
 * output bodies' position and velocity are body[output][FB_Q_POS / FB_Q_VEL]
 * (series.h) in the description's output order; over the same storage, the
 * four-bar's names for them. A slider-crank's body[1] is the slider: its
 * hole centre's x along the guide [m] and its velocity along +x [m/s]. */
typedef struct {
  double crank_angle;       /* theta2 [rad] */
  double crank_omega;       /* signed crank speed [rad/s] */
  union {
    double body[2][2];      /* per output body: position [rad or m], velocity [rad/s or m/s] */
    __extension__ struct {
      double coupler_angle;  /* theta3, direction B_hole -> C_pin [rad] */
      double coupler_omega;  /* [rad/s] */
      double follower_angle; /* theta4, direction D_pin -> C_hole [rad] */
      double follower_omega; /* [rad/s] */
    };
  };
  double pin[4][2];         /* pin centre of each joint of the description [m] (4 x 2); a
                               slider-crank's slider-ground: the slider's point on the guide */
  double hole[4][2];        /* hole centre of each joint [m] (4 x 2); = pin when ideal */
  double ecc[4][2];         /* pin - hole [m] (4 x 2); 0 for ideal joints */
  double coupler_b_vel[2];  /* velocity of the coupler's point at hole[B] [m/s] (2) */
} fb_start_state;

/* "steady"/"rest" and "centred"/"resting"/"angle". */
const char *fb_start_name(fb_start s);
const char *fb_pin_start_name(fb_pin_start p);

/* Resolves the case's start for a model with link lengths lk whose
 * clearance joints are clearance_mask (0 for an ideal model), at the case's
 * crank angle theta0, signed speed and branch, for the case's mechanism.
 * The slider-crank (its clearance joint the piston pin C, coupler-slider):
 *   the rod's pin P = B + coupler u(theta3) and the slider's hole
 *   H = (x, offset) with P - H = e_C (pin_start as above; resting along
 *   the static load at C, slider_crank_invdyn.h), so the rod is that of an
 *   ideal slider-crank whose guide is offset by e_C,y and x = P_x - e_C,x
 *   (slider_crank_dynamics.h fb_sc_dyn_start); steady: that mechanism's
 *   velocities; rest: the slider, which the clearance leaves free of the
 *   rod, at rest, the rod on its ideal motion (it hangs from the crank at
 *   the ideal joint B).
 * Errors: FB_ERR_ASSEMBLY when the loop does not close at theta0 (with the
 * offsets) or sits at a toggle; those of fb_invdyn_solve (or
 * fb_slider_crank_invdyn) for resting. */
fb_status fb_start_resolve(fb_start_state *out, const fb_case *c, const fb_linkage *lk,
                           int clearance_mask, fb_diag *diag);

/* The steady start of mechanism t with every pin centred, from its exact
 * solver at crank angle theta0 [rad] and signed speed omega2 [rad/s] (tests
 * that move the start: scene.h fb_scene_set_start). The four-bar's joint
 * centres A = 0, B, C, D = (ground, 0); the slider-crank's A = 0, B, C and
 * the slider's point C on the guide.
 * Errors: those of fb_linkage_solve or fb_slider_crank_solve. */
fb_status fb_start_steady(fb_start_state *out, fb_mech_type t, const fb_linkage *lk,
                          fb_branch branch, double theta0, double omega2, fb_diag *diag);

#endif
