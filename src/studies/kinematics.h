/* fourbar kinematics below the command: the exact peaks of a mechanism's
 * output bodies over one crank revolution at constant speed
 * (mech_kinematics.h fb_mech_peaks) and its kind's own part: a four-bar's
 * Grashof class and transmission angle range (linkage.h); a slider-crank's
 * class (coupler against crank + |offset|), dead centres, stroke,
 * quick-return ratio and transmission angle range (slider_crank.h). The
 * kinds are one table (fb_kinematics_kind), indexed by the mechanism's type
 * in one place (kinematics_kinds.h fb_report_kinematics_kind), where the
 * writers' entries meet the study's. */
#ifndef FB_KINEMATICS_H
#define FB_KINEMATICS_H

#include <stdio.h>

#include "analytic.h"
#include "linkage.h"
#include "mechanism.h"
#include "slider_crank.h"
#include "status.h"

typedef struct json_t json_t;
typedef struct fb_kinematics fb_kinematics;

/* One kind of mechanism as fourbar kinematics sees it: what its command
 * line takes beyond the description's lengths, and its part of the study
 * and of the output, each entry of one shape for every kind. */
typedef struct {
  int branch;         /* 1: it assembles on two branches (--branch, [linkage] branch) */
  int offset_length;  /* index into the description's lengths of an offset, not a link: 0 or
                         either sign, 0 unless given, no plausibility warning (-1: none) */
  int json_names_mechanism; /* 1: its JSON opens with "mechanism" (the description's type) */
  /* fills the kind's outputs of k (its class line into k->grashof, then its
   * own quantities) before the peaks; errors name the rule broken */
  fb_status (*run)(fb_kinematics *k, fb_diag *diag);
  /* its text after the case line, on f */
  void (*text)(FILE *f, const fb_kinematics *k);
  /* its own keys into the JSON object o, after "direction" */
  void (*json)(json_t *o, const fb_kinematics *k);
} fb_kinematics_kind;

struct fb_kinematics {
  /* in: */
  fb_mech_type mech;      /* the mechanism: its description names lengths and bodies */
  const fb_kinematics_kind *kind; /* its kind (fb_report_kinematics_kind(mech)) */
  fb_linkage lk;          /* lengths [m] in the description's order (a slider-crank's crank,
                             coupler and guide offset, FB_LENGTH_OFFSET), the rest 0 */
  double mm[FB_LINK_COUNT]; /* the same as given [mm] (for messages and text) */
  double rpm;             /* crank speed as given [rpm] */
  int dir;                /* -1 cw, +1 ccw, seen from +z */
  fb_branch branch;       /* assembly branch (a kind with branches) */
  const char *case_path;  /* the case the values came from, "" for none */
  /* out: */
  double omega2;          /* crank angular velocity [rad/s] (dir rpm) */
  fb_grashof g;           /* Grashof class (four-bar) */
  char grashof[512];      /* the class line: fb_linkage_grashof_text, the slider-crank's */
  double sl, pq;          /* s + l and p + q [m] (four-bar) */
  fb_peaks p;             /* peaks of the output bodies (slider-crank: rod and slider, the
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
};

/* Fills k's outputs from its inputs: the crank's omega2, the kind's part
 * (k->kind->run), then the peaks (fb_mech_peaks). Errors: FB_ERR_ARG
 * without a kind; the kind's; those of fb_mech_peaks, the message then
 * opening with the class line. */
fb_status fb_kinematics_run(fb_kinematics *k, fb_diag *diag);

/* The four-bar kind's run entry: Grashof class, its sums and transmission
 * angle range. Errors: FB_ERR_RANGE for a change-point four-bar (it folds
 * flat: no exact peaks) and those of fb_linkage_transmission_range (the
 * message then opening with the Grashof line). */
fb_status fb_kinematics_fourbar_run(fb_kinematics *k, fb_diag *diag);

/* The slider-crank kind's run entry: class and margin, dead centres,
 * stroke, transmission angle range, each stroke's crank angle and time and
 * the quick-return ratio. Errors: FB_ERR_ASSEMBLY when its crank cannot
 * turn fully (change point or rocker: the message opens with its class
 * line). */
fb_status fb_kinematics_slider_crank_run(fb_kinematics *k, fb_diag *diag);

#endif
