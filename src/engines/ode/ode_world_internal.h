/* The ODE world's insides, shared by the files that make it up (private to
 * src/engines/ode: it includes ODE's header). ode_world.h says what the
 * world is; the files are:
 *   ode_world.c      building the world (bodies, hinges, drive, the clearance
 *                    joints' pins and holes) and freeing it
 *   ode_clearance.c  the exact pin-in-hole contact (eccentricity, penetration,
 *                    the law mapped to one soft row), the effective mass, the
 *                    probe
 *   ode_colliders.c  the faceted and libccd colliders, ODE's generic path
 *                    (ode_colliders.h, shared with the engine kit's binding)
 *   ode_step.c       one step: each joint's contact rows, ODE's stepper, the
 *                    contact forces it left, the adaptive step
 *   ode_sample.c     what a step leaves: samples, penetration, drift, joint
 *                    reactions, counts and stops
 * Calls run one way: step -> world, sample, colliders, clearance; world ->
 * colliders; sample -> clearance, colliders; clearance -> colliders. */
#ifndef FB_ODE_WORLD_INTERNAL_H
#define FB_ODE_WORLD_INTERNAL_H

#include <ode/ode.h>

#include "episode.h"
#include "load_scale.h"
#include "ode_colliders.h"
#include "ode_world.h"

/* one clearance joint */
typedef struct {
  dBodyID pin, hole;    /* hole 0: ground */
  double pin_local[3];  /* joint centre in the pin body's frame */
  double hole_local[3]; /* in the hole body's frame, or world point for ground */
  fb_episode ep;        /* contact episodes: state during the last step, impacts, v0 */
  dJointID cj;          /* contact joint of the last step, or 0 */
  dJointFeedback fb;
  ode_collider gen;     /* faceted or libccd: the generic collider (its pin, hole and centres
                           these); unused by the exact one */
  double force;         /* contact force magnitude of the last step [N] */
  double force_pin[2];  /* contact force on the pin in the last step, x, y [N] */
  fb_contact_provenance prov; /* what its contact rows received */
  double step_share;    /* share of the last row's impulse that is its step's force (contact.h) */
  double step_wdh;      /* largest omega_d h of this step's rows [-] (contact.h) */
  double step_hw;       /* largest h omega of this step's rows (all rows together) [-] */
  double phase;         /* contact phase so far, sum of step_hw over the contact [rad] */
  double persistence;   /* matched-static: weight of the static row this step (contact.h) */
  double f_mean;        /* [solver] rocking_h_omega: the contact's mean force (contact.h,
                           fb_contact_mean_force_step) [N]; 0 out of contact */
  double omega_c;       /* the last row's contact frequency sqrt(k_t / m_eff) [rad/s] */
} ode_clearance;

struct fb_ode_world {
  fb_model_scene def;
  int broken;        /* 1 after an ODE fatal error left its world mid-step: never touched again */
  fb_stop stop;      /* why the last step failed (FB_STOP_NONE while none did) */
  dWorldID world;
  dBodyID body[3];   /* crank, coupler, follower (a slider-crank's slider) */
  dJointID hinge[4]; /* A (ground-crank, driven), B, C, D; 0 for clearance and prismatic joints */
  dJointID slider;   /* a slider-crank's guide (its prismatic joint, slider_joint): ODE's slider
                        joint along +x from the slider to the ground; 0 for the four-bar */
  int slider_joint;  /* the description's prismatic joint (slider-ground), or -1 */
  int translating;   /* the body that slides along the guide (a slider-crank's slider, 2), or
                        -1: its angle[], omega_prev[] and alpha[] are its x [m], v [m/s] and
                        a [m/s^2] along +x */
  double guide_y;    /* the guide line's y at the start [m] (the slider's drift is measured
                        from it) */
  dJointID amotor;   /* the drive when A is a clearance joint */
  dJointGroupID contacts;
  ode_clearance cl[4];
  dJointFeedback feedback[4];
  double crank_com_before[2]; /* crank centre of mass at the start of the last step */
  size_t steps;
  double angle[3];     /* unwrapped angles [rad]; the translating body's x [m] */
  double omega_prev[3]; /* [rad/s]; the translating body's v [m/s] */
  double alpha[3];      /* [rad/s^2]; the translating body's a [m/s^2] */
  double w_inv[4][2][2]; /* inverse-mass tensors of the clearance joints this step [1/kg] */
  int w_valid;           /* w_inv holds the configuration now (the next step's start); reset
                            when a step moves the bodies, so the adaptive step and the contact
                            rows share one computation */
  double h_now;          /* step of the ODE step being taken [s]: solver.h, or the adaptive one */
  /* [solver] h_s = adaptive (step_control.h): each ODE step spans mc grid
   * steps of solver.h (= h_min); the samples inside it are interpolated */
  struct {
    int on;               /* 1: adaptive */
    int m_max;            /* h_max / h_min, rounded down [-] */
    int m_prev;           /* grid steps of the last ODE step [-] */
    int mc, k;            /* the last ODE step spans mc samples; sample k of them is reported */
    double ang0[3], ang1[3], w0[3], w1[3]; /* angles [rad] and omega [rad/s] at its ends */
    double pen0[4], pen1[4], ex0[4], ex1[4], ey0[4], ey1[4]; /* penetration, eccentricity [m] */
    fb_step_stats stats;  /* steps taken, shortest and longest h and their counts */
    double pen_end;       /* largest penetration at the last ODE step's end [m] */
    int pen_joint_end;    /* its joint */
    double drift_end;     /* hinge drift at the last ODE step's end [m] */
    fb_load_scale load;   /* the clearance joints' ideal load time scale (load_scale.h) */
    int rocking;          /* 1: [solver] rocking_h_omega > 0 (step_control.h) */
    double h_last;        /* the last ODE step [s]; 0 before the first */
    double v_start[3][3]; /* each body's linear velocity at the last ODE step's start [m/s] */
    double w_start[3][3]; /* and its angular velocity [rad/s] */
  } ad;
};

/* ---- ode_world.c ---- */

/* the body's angle about +z from its rotation matrix [rad], in (-pi, pi] */
double ode_body_angle(dBodyID b);

/* body i's coordinate now: its angle about +z [rad] in (-pi, pi] (to be
 * unwrapped), or for the translating body its x [m]; and its rate [rad/s or
 * m/s] */
double ode_body_coord(const fb_ode_world *s, int i);
double ode_body_rate(const fb_ode_world *s, int i);

/* ---- ode_clearance.c: the exact contact and what every collider shares ---- */

/* the effective mass of clearance joint j along unit n [kg] (this step's
 * inverse-mass tensor, or the law's mass if it cannot be formed) */
double ode_step_effective_mass(fb_ode_world *s, int j, const double n[2]);

/* the joint's law at this step: a restitution law's damper on m_eff [kg] */
fb_contact_law ode_step_law(const fb_contact_law *law, double m_eff);

/* eccentricity e = pin - hole [m], |e| times its rate [m^2/s] and the
 * relative velocity ev [m/s] of clearance joint c now */
void ode_clearance_geometry(const ode_clearance *c, double e[2], double *ddot_num, double ev[2]);

/* penetration of clearance joint c now [m], 0 when free */
double ode_clearance_penetration(const fb_ode_world *s, const ode_clearance *c);

/* exact collider: the contact joint of clearance joint j for this step */
void ode_exact_contact(fb_ode_world *s, int j);

/* ---- ode_sample.c ---- */

/* largest penetration over the clearance joints now [m] and its joint (-1:
 * none); largest hinge anchor distance now [m] */
double ode_penetration_now(const fb_ode_world *s, int *joint);
double ode_joint_drift_now(const fb_ode_world *s);

#endif
