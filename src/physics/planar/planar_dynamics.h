/* The clearance dynamics of a planar description in absolute coordinates:
 * any of its revolute joints (clearance[j] = 1) is taken out of the
 * constraint set and becomes a pin in a hole, whose contact law
 * (contact.h) acts along the eccentricity; the other joints and the drive
 * hold. The model (fb_planar_dyn_model) of the engine-free yardstick of a
 * clearance model for any mechanism, as reference.h is for the four-bar's
 * crank-coupler joint and slider_crank_dynamics.h for the slider-crank's
 * piston pin. The reference integrates it in relative coordinates
 * (planar_relative.h); this absolute form is that one's cross-check (an
 * independent path, a Schur complement in every body's coordinates, to
 * the same equations) and its steady start.
 *
 * State y = (q, q') in absolute coordinates (2 nq). At each evaluation:
 *   contact   at each clearance joint j (pin on body[0], hole on body[1],
 *             Flores and Ambrosio's geometry, docs/contact.md):
 *             e = p_pin - p_hole, delta = |e| - c, n = e / |e|,
 *             delta' = n . (v_pin - v_hole), F = law(delta, delta', v0) >= 0
 *             (the restitution law's damper on the effective mass along n,
 *             planar_mass.h, by contact_mass.h's rule); +F n on the hole's
 *             body, -F n on the pin's,
 *             as generalised forces (f, (p - r) x f) of each body;
 *   motion    the index-1 DAE M q'' + G^T lambda = Q, G q'' = gamma (G the
 *             joints left and the drive at phi(t) = omega t), solved by the
 *             Schur complement of planar_mass.h.
 * The constraints hold at the acceleration level only, so positions and
 * velocities integrated from it drift from them at the integrator's
 * error; its contact geometry, p_pin - p_hole, carries the rounding of
 * coordinates of the mechanism's size (~1e-17 m), which the contact's
 * stiffness turns into force noise (planar_relative.h has neither). */
#ifndef FB_PLANAR_DYNAMICS_H
#define FB_PLANAR_DYNAMICS_H

#include "contact.h"
#include "planar_guide.h"
#include "planar_mass.h"

/* The model. */
typedef struct {
  const fb_planar *mech;           /* the description (outlives the model) */
  const unsigned char *clearance;  /* (njoints) 1: a revolute clearance joint */
  fb_contact_law law;              /* normal-force law at every clearance joint (prepared:
                                      fb_contact_law_prepare) unless joint_law gives each its
                                      own; not read, nor checked, when no joint has
                                      clearance (the ideal mechanism) */
  double radial_clearance;         /* c = R_hole - R_pin [m] >= 0 */
  double impact_velocity;          /* v0 of the hysteresis laws [m/s] > 0 (fixed, as reference.c) */
  double gravity;                  /* along -y [m/s^2] */
  double omega;                    /* the drive's constant speed, signed [rad/s]: phi(t) = omega t */
  const fb_planar_guide *guide;    /* (njoints) a prismatic clearance joint's slider in its
                                      guide (planar_guide.h); NULL when none is one */
  const double *omega0;            /* an undriven description's initial angular velocities
                                      (nbodies) [rad/s] (planar_start.h); NULL: all 0 */
  const fb_contact_law *joint_law; /* (njoints) each clearance joint's own law (prepared; read
                                      at the clearance joints only), so that several joints
                                      each take theirs (their working forces and masses
                                      differ); NULL: law at every one */
} fb_planar_dyn_model;

/* The law at clearance joint j of model (its joint_law[j], else law). */
static inline const fb_contact_law *fb_planar_dyn_law(const fb_planar_dyn_model *model, int j) {
  return model->joint_law ? &model->joint_law[j] : &model->law;
}

/* One clearance joint's contact at an evaluation (a slider in its guide:
 * the deepest corner's, force the corners' sum, ecc the slider's offset
 * across the slide and its tilt [m, rad]). */
typedef struct {
  double ecc[2];         /* e = p_pin - p_hole [m] (x, y) */
  double penetration;    /* max(|e| - c, 0) [m] */
  double rate;           /* delta' [m/s] (0 at e = 0) */
  double force;          /* F >= 0 [N] */
  double effective_mass; /* 1 / (n^T W n) along n [kg] where the law's damper needs it
                            (contact_mass.h: the restitution law in contact); else 0 */
} fb_planar_contact;

/* The right-hand side's workspace. */
typedef struct fb_planar_dyn fb_planar_dyn;

/* A workspace for model (copied; its mech and clearance must outlive it).
 * An undriven description (m->drive < 0) runs free from omega0. A
 * prismatic clearance joint is a slider in its guide (guide[j]).
 * Errors: FB_ERR_ARG when a clearance joint is prismatic without its
 * guide; those of fb_planar_guide_check; FB_ERR_RANGE for a negative clearance or
 * gravity, a non-positive v0; those of fb_contact_law_check; FB_ERR_NOMEM. */
fb_status fb_planar_dyn_new(fb_planar_dyn **out, const fb_planar_dyn_model *model,
                            fb_diag *diag);

void fb_planar_dyn_free(fb_planar_dyn *d);

/* Coordinates (nq); the state has 2 nq. */
int fb_planar_dyn_nq(const fb_planar_dyn *d);

/* The model held. */
const fb_planar_dyn_model *fb_planar_dyn_model_of(const fb_planar_dyn *d);

/* The constraint set's workspace (the joints left and the drive), for the
 * projection of a state (fb_planar_cmass_project). */
fb_planar_cmass *fb_planar_dyn_cmass(fb_planar_dyn *d);

/* dydt (2 nq) = (q', q'') at time t [s] and state y (2 nq); contact[j]
 * (njoints; may be NULL) receives each clearance joint's contact, other
 * entries untouched. Errors: FB_ERR_NUMERIC when the constraint set is
 * singular at q. */
fb_status fb_planar_dyn_eval(fb_planar_dyn *d, double t, const double *y, double *dydt,
                             fb_planar_contact *contact);

/* fb_planar_dyn_eval in the form of GSL's gsl_odeiv2_system function
 * (params: an fb_planar_dyn *): GSL_SUCCESS, or GSL_EBADFUNC when the set
 * is singular. */
int fb_planar_dyn_rhs(double t, const double y[], double dydt[], void *params);

/* The steady start: every joint (the clearance joints too, pins centred)
 * and the drive on the ideal motion at t = 0, the assembly configuration,
 * into y0 (2 nq); an undriven description's free start from omega0
 * (planar_start.h). Errors: those of planar_kinematics.h and
 * fb_planar_free_start. */
fb_status fb_planar_dyn_steady(double *y0, const fb_planar_dyn *d, fb_diag *diag);

#endif
