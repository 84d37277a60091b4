/* The reference's right-hand side in the relative coordinates of its
 * clearance joints: the state is what the contact law reads, so the
 * contact geometry carries no rounding of the mechanism's size.
 *
 * A clearance joint j's two constraint values r_j = Phi_j(q) are its
 * coordinates (planar_constraints.h's rows: a revolute joint's
 * eccentricity e = p_pin - p_hole; a prismatic joint's tilt psi and the
 * slider's offset y across its slide); with the drive at phi(t) = omega t
 * (or, undriven, one revolute joint's relative angle as a coordinate of
 * its own), the mechanism's positions q follow from r by the square set
 * of planar_sparse.h:
 *   Phi_i(q) = 0 (joints that hold),  Phi_j(q) = r_j,  Phi_a(q) = phi,
 * solved by Newton from a predictor along the last evaluation's motion
 * (one step at the reference's step sizes) and factorised by planar_lu.h.
 * Then, with G = Phi_q and E the columns of the identity at r's rows,
 *   V = G^-1 E (nq x nr),  q' = V r' + q_t (q_t = G^-1 omega e_drive),
 *   q'' = q''_0 + V r'',   q''_0 = G^-1 gamma(q, q')   (planar_sparse.h),
 * and the equations of motion projected on the free coordinates
 * (Lagrange's, the virtual displacements dq = V dr):
 *   (V^T M V) r'' = V^T (Q - M q''_0) + F_r,
 * F_r the contact forces' generalised forces in r: -F n for a pin (the
 * force F >= 0 on the hole along n = e / |e|, minus it on the pin); for a
 * slider's corner c (planar_guide.h, y_c = y + sigma a sin psi +
 * tau b cos psi its offset across the slide, its gap
 * g_c = c - tau y - tau sigma a sin psi + 2 b sin^2(psi / 2)) its force
 * times d g_c / d r. The restitution law's damper sits on the effective
 * mass from W = (V^T M V)^-1 (the pin's block: 1 / (n^T W n); a corner's:
 * its face's share 1 / (D_cc + D_cc'), D = J W J^T, J = d delta / d r),
 * the same masses as planar_mass.h's P = V W V^T gives. This is
 * coordinate partitioning with the contact's own coordinates independent
 * (Wehage and Haug 1982; Haug 1989, ch. 6), the form reference.c writes
 * in closed form for the four-bar (its state the angles' deviations from
 * the ideal motion): no drift, no projection, and no cancellation between
 * coordinates of the mechanism's size in e (planar_dynamics.h forms e as
 * p_pin - p_hole, whose ~1e-17 m of rounding times the contact's
 * stiffness is noise the step control of a check at 1e-13 sees).
 *
 * tests/test_planar_relative.c checks it against planar_dynamics.h's
 * absolute form and the closed forms (reference.h,
 * slider_crank_dynamics.h). */
#ifndef FB_PLANAR_RELATIVE_H
#define FB_PLANAR_RELATIVE_H

#include "planar_dynamics.h"

/* A Newton correction below this (scaled: lengths by the description's
 * size, angles in radians) leaves an error of ~its square, 1e-18: the
 * position is then taken without another step. The predictor's error at
 * a reference's steps is ~1e-10. */
#define FB_PLANAR_REL_NEWTON_QUAD 1e-9

/* A guess whose Newton correction is below this (scaled as above) is
 * taken as the position with its factorisation, no step: the position's
 * error, ~1e-14 of the mechanism's size, enters only the smooth terms
 * (masses, velocity products; not the contact, whose geometry is the
 * state), as noise ~1e-14 of them, a thousandth of what the absolute
 * form's contact geometry put into its forces (planar_dynamics.h). */
#define FB_PLANAR_REL_TAKE 1e-14

/* Newton steps allowed from a predictor before starting again from the
 * last solved position (a large jump of the state, such as a refinement's
 * restart at an earlier sample). */
#define FB_PLANAR_REL_NEWTON_MAX 12

/* Largest relative coordinate a state may hold, in its unit (a length:
 * this fraction of the description's size; a tilt: radians): a pin a
 * hundredth of the mechanism's size off its hole is far outside any
 * clearance (micrometres) and any law's range; such a state is a trial
 * stage of too long a step, which the integrator retries shorter
 * (fb_planar_rel_rhs). */
#define FB_PLANAR_REL_WILD 1e-2

/* The right-hand side's workspace. */
typedef struct fb_planar_rel fb_planar_rel;

/* What the evaluations did (for tests and measurements). */
typedef struct {
  long evals;       /* evaluations */
  long newton;      /* Newton steps */
  long restarts;    /* Newton restarted from the last solved position */
} fb_planar_rel_stats;

/* A workspace for model (planar_dynamics.h's; copied, its mech, clearance
 * and guide must outlive it). An undriven description takes as its own
 * coordinate the relative angle of the revolute joint (not a clearance
 * joint) at which the square set is best conditioned at the assembly.
 * Errors: those of fb_planar_dyn_new's checks (the same model rules);
 * FB_ERR_ARG when the description is not of one degree of freedom with
 * every joint, or (undriven) no revolute joint can take the free
 * coordinate; FB_ERR_NOMEM. */
fb_status fb_planar_rel_new(fb_planar_rel **out, const fb_planar_dyn_model *model,
                            fb_diag *diag);

void fb_planar_rel_free(fb_planar_rel *d);

/* The state's size, 2 nr: r (nr: 2 per clearance joint, then the free
 * coordinate when undriven), then r', in the mechanism's units: a length
 * over the description's size (fb_planar_size), an angle in radians, a
 * rate times fb_planar_rel_time_unit. The reference's tolerance is then
 * relative to the mechanism's scale, as reference.c's on angles and
 * angular rates is (its steps and its check's measured in
 * docs/performance.md). */
int fb_planar_rel_dim(const fb_planar_rel *d);

/* The state's unit of time [s]: 1 / |omega| of the drive; undriven, 1 / the
 * largest initial angular rate, else sqrt(size / gravity), else 1 s. */
double fb_planar_rel_time_unit(const fb_planar_dyn_model *model);

/* The description's coordinates (fb_planar_nq). */
int fb_planar_rel_nq(const fb_planar_rel *d);

/* The model held. */
const fb_planar_dyn_model *fb_planar_rel_model_of(const fb_planar_rel *d);

/* dzdt (dim) = (r', r'') at time t [s] and state z (dim); contact[j]
 * (njoints; may be NULL) receives each clearance joint's contact
 * (planar_dynamics.h's struct), other entries untouched. Errors:
 * FB_ERR_NUMERIC when the positions cannot be solved or the square set is
 * singular there. */
fb_status fb_planar_rel_eval(fb_planar_rel *d, double t, const double *z, double *dzdt,
                             fb_planar_contact *contact);

/* fb_planar_rel_eval in the form of GSL's gsl_odeiv2_system function
 * (params: an fb_planar_rel *): GSL_SUCCESS, or GSL_FAILURE when the
 * positions cannot be solved at the state, so that gsl_odeiv2_evolve_apply
 * tries the step again at half its size (a trial stage of too long a step
 * may put a pin where the mechanism does not assemble). */
int fb_planar_rel_rhs(double t, const double z[], double dzdt[], void *params);

/* The absolute motion of the last evaluation: q, q', q'' (nq each; any may
 * be NULL). */
void fb_planar_rel_motion(const fb_planar_rel *d, double *q, double *qd, double *qdd);

/* The largest |Phi| of the joints that hold at the last evaluation's
 * position, their length rows only [m]: the rounding the positions keep
 * them to. */
double fb_planar_rel_closure(fb_planar_rel *d);

/* The steady start (planar_dynamics.h's fb_planar_dyn_steady: every joint
 * and the drive on the ideal motion at t = 0, pins centred; an undriven
 * description's free start) as a state z0 (dim), the positions solved
 * there. Errors: those of the kinematics and the free start. */
fb_status fb_planar_rel_steady(double *z0, fb_planar_rel *d, fb_diag *diag);

/* fb_planar_rel_steady with every revolute clearance joint's pin moved off
 * its hole's centre by offset [m] (x, y in the world: an ensemble member's
 * perturbation, start.h's rule for every clearance joint), its relative
 * rate zero. Errors: those of fb_planar_rel_steady. */
fb_status fb_planar_rel_steady_offset(double *z0, fb_planar_rel *d, const double offset[2],
                                      fb_diag *diag);

/* The state z (dim) of an absolute motion q, qd (nq each) that keeps the
 * joints that hold: r = Phi_r(q), r' = G_r qd; the positions' guess for
 * the next evaluation set to q. */
void fb_planar_rel_state_of(double *z, fb_planar_rel *d, const double *q, const double *qd);

/* The next evaluation's positions start from q (nq), not from the last
 * evaluation's motion: a state far from the last one (a refinement's
 * restart at an earlier sample) needs its own guess, as Newton from a
 * distant position may find another assembly of the mechanism. */
void fb_planar_rel_guess(fb_planar_rel *d, const double *q);

/* The evaluations' counts so far. */
fb_planar_rel_stats fb_planar_rel_stats_of(const fb_planar_rel *d);

#endif
