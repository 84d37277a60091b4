/* fourbar kinematics below the command (kinematics.h). */
#include "kinematics.h"

#include <stdio.h>

#include "units.h"

fb_status fb_kinematics_run(fb_kinematics *k, fb_diag *diag) {
  k->omega2 = k->dir * k->rpm * FB_RAD_S_PER_RPM;
  k->g = fb_linkage_grashof(&k->lk);
  fb_linkage_grashof_text(k->grashof, sizeof k->grashof, &k->lk);
  fb_linkage_grashof_sums(&k->lk, &k->sl, &k->pq, NULL, NULL);
  /* a change-point linkage folds flat on its way round: no peaks to give */
  if (k->g == FB_GRASHOF_CHANGE_POINT)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "crank %g, coupler %g, follower %g, ground %g mm: %s; a crank driven "
                       "through a fold has no exact peaks: make s + l differ from p + q (s + l < "
                       "p + q for a crank-rocker)",
                       k->mm[0], k->mm[1], k->mm[2], k->mm[3], k->grashof);
  fb_diag dg;
  fb_status st = fb_linkage_transmission_range(&k->lk, &k->mu_min, &k->mu_max, &dg);
  if (st == FB_OK) st = fb_analytic_peaks(&k->p, &k->lk, k->branch, k->omega2, &dg);
  if (st != FB_OK) return fb_diag_set(diag, st, "%s; %s", k->grashof, dg.msg);
  return FB_OK;
}
