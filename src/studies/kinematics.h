/* fourbar kinematics below the command: a linkage's Grashof class, the
 * exact peaks of coupler and follower over one crank revolution at
 * constant speed (analytic.h) and its transmission angle range
 * (linkage.h). */
#ifndef FB_KINEMATICS_H
#define FB_KINEMATICS_H

#include "analytic.h"
#include "linkage.h"
#include "status.h"

typedef struct {
  /* in: */
  fb_linkage lk;          /* link lengths [m] */
  double mm[FB_LINK_COUNT]; /* the same as given [mm] (for messages and text) */
  double rpm;             /* crank speed as given [rpm] */
  int dir;                /* -1 cw, +1 ccw, seen from +z */
  fb_branch branch;       /* assembly branch */
  const char *case_path;  /* the case the values came from, "" for none */
  /* out: */
  double omega2;          /* crank angular velocity [rad/s] (dir rpm) */
  fb_grashof g;           /* Grashof class */
  char grashof[512];      /* its line (fb_linkage_grashof_text) */
  double sl, pq;          /* s + l and p + q [m] */
  fb_peaks p;             /* peaks of coupler and follower */
  double mu_min, mu_max;  /* transmission angle range [rad] */
} fb_kinematics;

/* Fills k's outputs from its inputs. Errors: FB_ERR_RANGE for a
 * change-point linkage (it folds flat: no exact peaks) and those of
 * fb_linkage_transmission_range and fb_analytic_peaks (the message then
 * opens with the Grashof line). */
fb_status fb_kinematics_run(fb_kinematics *k, fb_diag *diag);

#endif
