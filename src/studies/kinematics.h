/* fourbar kinematics below the command: a four-bar's Grashof class, the
 * exact peaks of coupler and follower over one crank revolution at
 * constant speed (analytic.h) and its transmission angle range
 * (linkage.h); a slider-crank's class (coupler against crank + |offset|),
 * dead centres, stroke, quick-return ratio, transmission angle range and
 * the exact peaks of rod and slider (slider_crank.h, mech_kinematics.h). */
#ifndef FB_KINEMATICS_H
#define FB_KINEMATICS_H

#include "analytic.h"
#include "linkage.h"
#include "mechanism.h"
#include "slider_crank.h"
#include "status.h"

typedef struct {
  /* in: */
  fb_mech_type mech;      /* the four-bar or the slider-crank */
  fb_linkage lk;          /* lengths [m]: the four-bar's links; a slider-crank's crank, coupler
                             and guide offset (FB_LENGTH_OFFSET), the fourth 0 */
  double mm[FB_LINK_COUNT]; /* the same as given [mm] (for messages and text) */
  double rpm;             /* crank speed as given [rpm] */
  int dir;                /* -1 cw, +1 ccw, seen from +z */
  fb_branch branch;       /* assembly branch (the four-bar's) */
  const char *case_path;  /* the case the values came from, "" for none */
  /* out: */
  double omega2;          /* crank angular velocity [rad/s] (dir rpm) */
  fb_grashof g;           /* Grashof class (four-bar) */
  char grashof[512];      /* its line (fb_linkage_grashof_text); the slider-crank's class line */
  double sl, pq;          /* s + l and p + q [m] (four-bar) */
  fb_peaks p;             /* peaks of coupler and follower (slider-crank: rod and slider, the
                             slider's position extremes included) */
  double mu_min, mu_max;  /* transmission angle range [rad] */
  /* out, the slider-crank's: */
  fb_sc_class sc_class;   /* full-turn, change-point or rocker */
  double sc_margin;       /* coupler - (crank + |offset|) [m]: > 0 for a full-turning crank */
  fb_slider_crank_limits lim; /* dead centres, stroke, smallest transmission angle */
  double outstroke_angle; /* crank angle turned in the drive's direction while the slider goes
                             from the inner to the outer dead centre (+x) [rad] */
  double return_angle;    /* 2 pi - outstroke_angle: from the outer back to the inner [rad] */
  double outstroke_time;  /* outstroke_angle / |omega2| [s] */
  double return_time;     /* return_angle / |omega2| [s] */
  double quick_return;    /* the slower stroke's time over the faster's (>= 1; 1 at offset 0) */
} fb_kinematics;

/* Fills k's outputs from its inputs. Errors: FB_ERR_RANGE for a
 * change-point four-bar (it folds flat: no exact peaks) and those of
 * fb_linkage_transmission_range and fb_analytic_peaks (the message then
 * opens with the Grashof line); for a slider-crank FB_ERR_ASSEMBLY when its
 * crank cannot turn fully (change point or rocker: the message opens with
 * its class line) and those of fb_mech_peaks. */
fb_status fb_kinematics_run(fb_kinematics *k, fb_diag *diag);

#endif
