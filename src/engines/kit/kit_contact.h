/* The kit's clearance pipeline (kit.h), private to src/engines/kit: each
 * clearance joint's contact computed once for every engine (the
 * eccentricity from the bodies' states, the penetration and its rate, the
 * episode, the effective mass from the planar core, the law's damper on
 * it) and handed to the binding. */
#ifndef FB_KIT_CONTACT_H
#define FB_KIT_CONTACT_H

#include "episode.h"
#include "kit.h"
#include "planar_mass.h"
#include "planar_spec.h"
#include "step_control.h"

/* What the pipeline keeps between steps. */
typedef struct {
  fb_episode ep[FB_KIT_SLOTS];                /* per contact slot (kit.h, fb_kit_slot) */
  double force[FB_KIT_SLOTS];                 /* the law's force handed this step [N] */
  double phase[FB_KIT_SLOTS];                 /* contact phase: the sum of the slot's rows'
                                                 h omega_c since its onset (a binding that
                                                 applies the law's force: of its tangent
                                                 stiffness) [rad] (contact.h) */
  double normal[FB_KIT_SLOTS][2];             /* the normal of the contact handed this step
                                                 (fb_kit_contact.normal) [-] */
  double point[FB_KIT_SLOTS][2];              /* its point on the hole's wall [m] */
  double pen[FB_PLANAR_SPEC_MAX_JOINTS];      /* penetration at the step's start [m] */
  unsigned char off[FB_PLANAR_SPEC_MAX_JOINTS]; /* 1: a clearance joint (no ideal joint) */
  double *q, *qd;                             /* the core's coordinates and rates (nq each) */
  double cs[FB_PLANAR_SPEC_MAX_BODIES + 1][2]; /* body b's cos, sin at the state last read
                                                 (fb_planar_rotation), formed at its first use
                                                 since the read (bit b of rotated): the pins'
                                                 points and the closed form's joints placed
                                                 without a sin/cos of their own */
  unsigned long long rotated;                 /* bit b: cs[b] is the state last read's */
  double rate[FB_PLANAR_SPEC_MAX_JOINTS];     /* penetration rate at the state last read [m/s] */
  double rate_before[FB_PLANAR_SPEC_MAX_JOINTS]; /* the one read before it [m/s] */
  double ecc[FB_PLANAR_SPEC_MAX_JOINTS][2];   /* eccentricity pin - hole at the last read [m]
                                                 (a slider: its centre across the slide [m],
                                                 its tilt [rad]) */
  fb_planar_cmass *cm;                        /* the joints but the clearance ones, for every
                                                 contact's effective mass (NULL: no clearance
                                                 joint) */
  int factored;                               /* 1: cm is factorised at the state last read */
  int closed;                                 /* 1: w4 holds the closed form at that state */
  double w4[4][2][2];                         /* the closed form's tensors at that state
                                                 (fb_kit_clearance.mass_tensors) [1/kg] */
  int rocking;                                /* 1: the adaptive step's rocking bound is on:
                                                 every row matched with the mean-force
                                                 correction (fb_kit_contact.mean_force) */
  double f_mean[FB_KIT_SLOTS];                /* rocking: each slot's mean force
                                                 (contact.h fb_contact_mean_force_step) [N] */
  double omega_c[FB_KIT_SLOTS];               /* rocking: the frequency of the slot's row this
                                                 step, sqrt(kp / m_eff) (0: no row) [rad/s] */
  fb_kit_contact read[FB_PLANAR_SPEC_MAX_JOINTS]; /* a pin's contact at the state last read,
                                                 its geometry only (fb_kit_pipe_read), which
                                                 the coming step's contacts start from */
  unsigned char read_off_centre[FB_PLANAR_SPEC_MAX_JOINTS]; /* 1: that pin is off its hole's
                                                 centre (read[j] has a normal) */
} fb_kit_pipe;

/* Sets p up for m's clearance joints cl->mask in b's engine. Errors:
 * FB_ERR_ARG (cl->friction not 0 with a binding whose add_contact applies
 * no friction, kit.h's friction member; a generic collider, a ring or a
 * bore (cl->collider), with a binding without collide, or at a prismatic
 * joint, a slider in its guide; a joint out of range, a revolute joint that
 * may not carry clearance, a prismatic one without cl->guide), those of
 * fb_planar_guide_check, FB_ERR_NOMEM (a binding's add_clearance, called
 * before, refuses what it cannot build). Free with fb_kit_pipe_free. */
fb_status fb_kit_pipe_new(fb_kit_pipe *p, const fb_kit_binding *b, const fb_planar *m,
                          const fb_kit_clearance *cl, fb_diag *diag);
void fb_kit_pipe_free(fb_kit_pipe *p);

/* Body b's (0: the ground, 1 ..: the description's) cos and sin at the
 * state last read, p->q (fb_kit_pipe.cs): formed at its first use since
 * the state was read (fb_kit_pipe_rotations), by the planar core's
 * fb_planar_rotation, then kept. */
const double *fb_kit_pipe_rotation(fb_kit_pipe *p, int b);

/* The state in p->q is read anew from world w: every moving body's cos
 * and sin taken from binding b's body_rotation when it has one, else
 * formed at first use (fb_kit_pipe_rotation). fb_kit_pipe_read calls it. */
void fb_kit_pipe_rotations(fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                           const fb_planar *m);

/* Every clearance joint's penetration and eccentricity (p->pen, p->ecc)
 * at the bodies' states the caller put in p->q and p->qd (the engine's, as
 * the kit's sample read them); a pin in the hole of b's own collider (kit.h
 * collide) its depth there when b reports it (penetration, from world w). */
void fb_kit_pipe_read(fb_kit_pipe *p, const fb_kit_binding *b, const void *w, const fb_planar *m,
                      const fb_kit_clearance *cl);

/* Every clearance joint's contact at the state last read (the effective
 * masses of the state fb_kit_pipe_read read last), handed to b's
 * add_contact for the coming step of h [s] (a binding with contact_always:
 * every revolute one off its hole's centre, in free flight too, with its
 * effective mass); counts contact steps and impact episodes into cl. A pin
 * whose contacts b's own collider finds (kit.h collide, cl->collider) is
 * handed where its exact penetration is positive and the collider found
 * contacts, its episode theirs, its record the rows they made (collided:
 * contact steps count rows). A binding with its own clearance relation
 * (add_clearance) gets no contact: a step with a contact force
 * (contact_force > 0) is a contact step, an episode's onset rate the one
 * read before that step. Errors: FB_ERR_NUMERIC when a matched row
 * would alias (contact.h, FB_MATCHED_ALIAS_BOUND: "aliased: ..." with
 * the largest usable step, the hand-built ODE world's stop; not for a
 * binding whose applied_force is 1); those of
 * add_contact and of the effective mass (planar_mass.h). */
fb_status fb_kit_pipe_contacts(fb_kit_pipe *p, const fb_kit_binding *b, void *w,
                               const fb_planar *m, fb_kit_clearance *cl, double h,
                               fb_diag *diag);

/* After a step of h [s]: each slot's mean force under the rocking bound
 * (p->rocking; contact.h fb_contact_mean_force_step from the force the
 * binding reports, 0 for a slot without a row). */
void fb_kit_pipe_stepped(fb_kit_pipe *p, const fb_kit_binding *b, const void *w, double h);

/* Revolute clearance joint j's contact state at the state last read, as
 * the adaptive step takes it (step_control.h): penetration |e| - c (a gap
 * below 0), its rate, the effective mass along e (along +x at e = 0),
 * the persistence of its contact (contact.h, of its slot's phase; 0 out of
 * contact), with p->rocking the effective mass along the wall and |e|;
 * the rule b->persistent_rule and, for FB_PERSIST_LOAD_SCHEDULE, the
 * load ahead from cl->load at the drive's angle theta_to - theta_from
 * (load_scale.h). sj->dddot and sj->rocking_h_omega are left 0 for the
 * caller. *impulsive is set to 1 (else left) when the joint penetrates
 * with a matched-static row not yet persistent (a binding that takes
 * rows: step_control.h fb_step_hold_in_impact). Errors: those of the
 * effective mass (planar_mass.h). */
fb_status fb_kit_pipe_step_joint(fb_step_joint *sj, int *impulsive, fb_kit_pipe *p,
                                 const fb_kit_binding *b, const fb_planar *m,
                                 const fb_kit_clearance *cl, int j, fb_diag *diag);

/* The force of clearance joint j of m in the step just taken [N], over
 * its slots (a slider's four corners summed): the engine's
 * (contact_force) when the binding reports it, else the law's. */
double fb_kit_pipe_force(const fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                         const fb_planar *m, int j);

/* Clearance joint j's reaction over the step just taken, out (3): the
 * force on the joint's body[1] from its body[0] (x, y) [N] and, for a
 * slider in its guide, the moment on body[1] about +z at the joint's point
 * on it [N m] (kit.h's fb_kit_series.reaction), from each slot's force
 * (the binding's vector, contact_force_vec, else the normal force along
 * the slot's normal) at the state last read (the step's start); an engine
 * that builds its own relation (add_clearance without add_contact) gives
 * it whole (clearance_reaction, which fb_kit_open requires then). */
void fb_kit_pipe_reaction(const fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                          const fb_planar *m, int j, double out[3]);

/* The contact state (series.h FB_STATE_*) of clearance joint j of m's
 * episode: a revolute joint's; a slider's impact when a corner in contact
 * is in an impact episode, else continuous when one is in contact, else
 * free. */
int fb_kit_pipe_state(const fb_kit_pipe *p, const fb_planar *m, int j);

#endif
