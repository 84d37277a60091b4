/* fourbar penalty below the command: contact stiffness Kc (paper Eq. 7),
 * penalty parameter P and mutual approach of the crank-coupler and
 * coupler-follower joints per crank speed (penalty.h; a slider-crank's
 * crank-coupler and coupler-slider, physical mode only), and the contact a
 * fourbar run of the case uses, through the run's own scene stage (its
 * laws per joint, effective-mass range, expected impact force, contact
 * frequency and the automatic step; scene.h, resolution.h). */
#ifndef FB_PENALTY_STUDY_H
#define FB_PENALTY_STUDY_H

#include "case.h"
#include "contact.h"
#include "linkage.h"
#include "penalty.h"
#include "resolution.h"
#include "status.h"

/* Most crank speeds of one table. */
#define FB_PENALTY_SPEEDS_MAX 1000

typedef struct {
  fb_mech_type mech;                       /* the case's mechanism (joint names: its pin joints,
                                              penalty.h fb_penalty_joint) */
  const char *rows_skipped;                /* NULL, or why the table does not apply (paper mode on
                                              a slider-crank: fb_penalty_paper_refusal) */
  fb_penalty_mode mode;
  int n;                                   /* speeds asked */
  double rpm[FB_PENALTY_SPEEDS_MAX];       /* crank speeds [rpm] */
  fb_penalty_row rows[FB_PENALTY_SPEEDS_MAX][FB_PENALTY_PIN_JOINTS]; /* per speed: both pin joints */
  int n_ok;                                /* speeds whose rows were computed: [0, n_ok) */
  fb_status rows_status;                   /* FB_OK, or why speed n_ok failed (rows_msg) */
  char rows_msg[FB_DIAG_SIZE];
  /* the contact a run of the case uses (only for a case with clearance joints) */
  int has_contact;                         /* the case has clearance joints */
  fb_status contact_status;                /* FB_OK, or why it could not be found (contact_msg) */
  char contact_msg[FB_DIAG_SIZE];
  fb_case run_case;                        /* the case as the run's scene stage resolved it */
  fb_contact_law laws[2][4];               /* [0] clearance-impact, [1] clearance-restitution,
                                              per joint */
  fb_contact_estimate est[2][4];           /* their estimates per joint */
  double h_auto;                           /* [solver] h_s = auto's step [s] */
  double omega_c;                          /* its fastest contact's rate (resolution.h's
                                              fb_contact_rates: omega_c or c / m_eff) [1/s] */
  fb_linkage stackup;                      /* the stack-up corner's lengths [m] */
  char corner[FB_LINK_COUNT + 1];          /* the corner as '-', '0', '+' per length of the
                                              mechanism's description */
  const char *contact_models[2];           /* the models whose laws the contact block shows
                                              (fb_penalty_contact_models_of) */
  fb_mapping mapping;                      /* the case's [clearance] mapping */
} fb_penalty_study;

/* The two models whose laws the contact block shows for mechanism t (the
 * impact and the restitution law, clearance models that build t): its
 * description's contact_models (mechanism.h), the four-bar's ODE rows, the
 * slider-crank's reference rows. */
const char *const *fb_penalty_contact_models_of(fb_mech_type t);

/* Fills s for case c in mode at the n speeds rpm [rpm]. Never fails as a
 * whole: the rows stop at the first speed fb_penalty_rows refuses
 * (rows_status), or are skipped whole where the mode does not apply to the
 * mechanism (rows_skipped, rows_status FB_OK, n_ok 0), and the contact
 * records its own error (contact_status), so the command reports each
 * where its output reaches it. */
void fb_penalty_study_run(fb_penalty_study *s, const fb_case *c, fb_penalty_mode mode,
                          const double *rpm, int n);

#endif
