/* The closed forms of the four-bar family as one table per mechanism
 * (physics floor): what a member with exact kinematics provides to the
 * harness (its position, velocity and acceleration solution, peaks, joint
 * reactions, start states, tolerance outputs, the checks a case of it
 * needs), each with one shape for every member, and its data (the
 * tolerance outputs' names, the Monte Carlo cost per sample, whether the
 * paper's Tables I to III recipe and the ideal reference apply).
 *
 * The files that serve any mechanism (mech_kinematics.c, start.c,
 * tolerance.c, load_scale.c, penalty.c, reference.c, and the consumers
 * above the physics floor) call through the table and never name a
 * mechanism type: a third closed-form member costs a description
 * (mechanism.h) and one table (its closed_form_<name>.c), registered in
 * closed_form.c, the one place that maps a type to its table.
 *
 * Units SI throughout. Lengths are fb_linkage's in the description's order
 * (a slider-crank's crank, coupler and guide offset at FB_LENGTH_OFFSET);
 * link[3] the case's per-link mass properties in body order. */
#ifndef FB_CLOSED_FORM_H
#define FB_CLOSED_FORM_H

#include <stddef.h>

#include "analytic.h"
#include "effective_mass.h"
#include "mechanism.h"
#include "planar_case.h"
#include "slider_crank_dynamics.h"
#include "start.h"
#include "tolerance.h"

typedef struct fb_closed_form {
  /* ---- kinematics (mech_kinematics.h has each one's contract) ---- */
  /* the output bodies' q, q', q'' at crank angle theta2 (fb_mech_solve) */
  fb_status (*solve)(double out[FB_MECH_MAX_OUTPUTS][3], const fb_linkage *lk, fb_branch branch,
                     double theta2, double omega2, double alpha2, fb_diag *diag);
  /* FB_OK when the lengths make a mechanism whose crank turns fully
   * (fb_mech_check_lengths) */
  fb_status (*check_lengths)(const fb_linkage *lk, fb_diag *diag);
  /* peaks over one revolution, where (8, may be NULL) their crank angles
   * (fb_mech_peaks_where; fb_mech_peaks with where NULL) */
  fb_status (*peaks_where)(fb_peaks *out, double where[8], const fb_linkage *lk,
                           fb_branch branch, double omega2, fb_diag *diag);
  /* the exact series at t = k h (fb_mech_sample); NULL: the description's
   * columns filled from solve, sample by sample */
  fb_status (*sample)(fb_series *out, const fb_linkage *lk, fb_branch branch, double theta0,
                      double omega2, double h, size_t n, fb_diag *diag);
  /* each joint's force on its second body [N] (4 x 2, the description's
   * joint order; a prismatic guide's normal force as (0, -N)) and the drive
   * torque [N m] at crank angle theta2 and constant speed omega2, gravity
   * [m/s^2] along -y: inverse dynamics of the ideal mechanism */
  fb_status (*reactions)(double force[4][2], double *drive_torque, const fb_linkage *lk,
                         fb_branch branch, const fb_link_mass link[3], double gravity,
                         double theta2, double omega2, fb_diag *diag);
  /* largest |reaction| per joint over n crank angles (fb_mech_reaction_peaks) */
  fb_status (*reaction_peaks)(double force_max[4], const fb_linkage *lk, fb_branch branch,
                              const fb_link_mass link[3], double gravity, double omega2, int n,
                              fb_diag *diag);
  /* the mechanism at crank angle theta2 for effective_mass.h
   * (fb_mech_mechanism_at) */
  fb_status (*mechanism_at)(fb_mechanism *out, const fb_linkage *lk, fb_branch branch,
                            const fb_link_mass link[3], double theta2, int clearance_mask,
                            fb_diag *diag);
  /* ---- start states (start.h) ---- */
  /* the steady start with every pin centred (fb_start_steady) */
  fb_status (*start_steady)(fb_start_state *out, const fb_linkage *lk, fb_branch branch,
                            double theta0, double omega2, fb_diag *diag);
  /* case c's start with the clearance joints' eccentricities ecc [m] (4 x 2,
   * already resolved from [run] pin_start by start.c) (fb_start_resolve) */
  fb_status (*start_resolve)(fb_start_state *out, const fb_case *c, const fb_linkage *lk,
                             const double ecc[4][2], int clearance_mask, fb_diag *diag);
  /* ---- tolerance stack-up (tolerance.h) ---- */
  const char *const *tol_names;  /* the FB_TOL_NOUT outputs' names, units in the suffix */
  /* the FB_TOL_NOUT outputs (fb_tol_outputs_of) */
  fb_status (*tol_outputs)(double out[FB_TOL_NOUT], const fb_linkage *lk, fb_branch branch,
                           double omega2, fb_diag *diag);
  /* their exact sensitivities to each length [unit/m] (fb_tol_sensitivities_of) */
  fb_status (*tol_sensitivities)(double out[FB_TOL_NOUT][FB_LINK_COUNT], const fb_linkage *lk,
                                 fb_branch branch, double omega2, fb_diag *diag);
  /* ---- contact and reference ---- */
  const char *paper_refusal;     /* NULL: the paper's Tables I to III recipe applies
                                    (penalty.h); else why it does not, for the user */
  int ideal_reference;           /* 1: the engine-free reference integrates the ideal
                                    mechanism too (reference.h) */
  /* NULL: the reference integrates the four-bar's two-angle minimal
   * coordinates; else fills the minimal-coordinate model (rod angle, slider
   * x) it integrates instead, for case c with lengths lk, law and the
   * hysteresis laws' impact velocity [m/s] (slider_crank_dynamics.h) */
  fb_status (*reference_model)(fb_sc_dyn_model *out, const fb_case *c, const fb_linkage *lk,
                               const fb_contact_law *law, double impact_velocity, fb_diag *diag);
  /* the description of case c's mechanism at lengths lengths (planar_case.h
   * fb_planar_of_case) */
  fb_status (*planar)(fb_planar **out, const fb_linkage *lk, fb_branch branch,
                      const fb_link_mass link[3], double theta0, fb_diag *diag);
  /* ---- case checks (setup/case.c fb_case_check) ---- */
  /* the line that classifies case c's nominal lengths (fb_case_grashof_text) */
  void (*class_text)(const fb_case *c, char *out, size_t size);
  /* the lengths, tolerances and options case c must have, before its masses
   * are checked; FB_ERR_* with the key to fix */
  fb_status (*check_case)(const fb_case *c, fb_diag *diag);
  int tolerances_checked;        /* lengths 0 .. n - 1 need 0 <= tolerance < length
                                    ([tolerance] <name>_plus_minus_mm), checked next */
  /* then the options case c's mechanism refuses or restricts ([clearance]
   * joints, penalty, [tolerance] stackup); NULL: none */
  fb_status (*check_options)(const fb_case *c, fb_diag *diag);
  /* after the masses and the pin: can a crank driven at constant speed turn
   * the nominal and the stack-up mechanism fully */
  fb_status (*check_drivable)(const fb_case *c, fb_diag *diag);
} fb_closed_form;

/* The tables, one per mechanism, each defined next to its closed forms. */
extern const fb_closed_form fb_closed_form_fourbar;      /* closed_form_fourbar.c */
extern const fb_closed_form fb_closed_form_slider_crank; /* closed_form_slider_crank.c */

/* The table of mechanism type t; the four-bar's for a value out of range
 * (as mechanism.h fb_mech_of). Never NULL. */
const fb_closed_form *fb_closed_form_of(fb_mech_type t);

/* The table of description m (found by its type name, mechanism.h
 * fb_mech_find); the four-bar's for NULL or a description without a
 * closed form (a planar case's). Never NULL. */
const fb_closed_form *fb_closed_form_of_desc(const fb_mech_desc *m);

#endif
