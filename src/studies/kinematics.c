/* fourbar kinematics below the command (kinematics.h): the run common to
 * every kind and the kinds' run entries. */
#include "kinematics.h"

#include <math.h>
#include <stdio.h>

#include "mech_kinematics.h"
#include "units.h"

fb_status fb_kinematics_fourbar_run(fb_kinematics *k, fb_diag *diag) {
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
  const fb_status st = fb_linkage_transmission_range(&k->lk, &k->mu_min, &k->mu_max, &dg);
  if (st != FB_OK) return fb_diag_set(diag, st, "%s; %s", k->grashof, dg.msg);
  return FB_OK;
}

fb_status fb_kinematics_slider_crank_run(fb_kinematics *k, fb_diag *diag) {
  const fb_slider_crank sc = fb_slider_crank_of(&k->lk);
  const double sum = sc.crank + fabs(sc.offset);
  k->sc_class = fb_slider_crank_class(&sc);
  k->sc_margin = sc.coupler - sum;
  snprintf(k->grashof, sizeof k->grashof,
           "slider-crank, %s: coupler %.6g mm against crank + |offset| = %.6g mm (margin %.4g "
           "mm); the crank turns fully when the coupler is longer",
           fb_sc_class_name(k->sc_class), sc.coupler * 1e3, sum * 1e3, k->sc_margin * 1e3);
  fb_diag dg;
  const fb_status st = fb_slider_crank_limit_positions(&k->lim, &sc, &dg);
  if (st != FB_OK) return fb_diag_set(diag, st, "%s; %s", k->grashof, dg.msg);
  /* mu = pi/2 - |theta3|, sin theta3 = (offset - crank sin theta2) / coupler
   * spans [(offset - crank), (offset + crank)] / coupler: |theta3| is
   * smallest at 0 when |offset| <= crank, else at asin((|offset| - crank) /
   * coupler) */
  k->mu_min = k->lim.transmission_min;
  k->mu_max = 0.5 * M_PI - asin(fmax(0.0, fabs(sc.offset) - sc.crank) / sc.coupler);
  /* the outstroke (inner to outer dead centre) is outstroke_angle
   * counter-clockwise: a ccw crank turns that, a cw crank the rest */
  k->outstroke_angle = k->dir > 0 ? k->lim.outstroke_angle : 2.0 * M_PI - k->lim.outstroke_angle;
  k->return_angle = 2.0 * M_PI - k->outstroke_angle;
  k->outstroke_time = k->outstroke_angle / fabs(k->omega2);
  k->return_time = k->return_angle / fabs(k->omega2);
  k->quick_return = fmax(k->outstroke_angle, k->return_angle) /
                    fmin(k->outstroke_angle, k->return_angle);
  return FB_OK;
}

fb_status fb_kinematics_run(fb_kinematics *k, fb_diag *diag) {
  if (!k->kind || !k->kind->run)
    return fb_diag_set(diag, FB_ERR_ARG, "kinematics of the %s: no kind given (set k->kind to "
                       "fb_report_kinematics_kind(mech))", fb_mech_of(k->mech)->type);
  k->omega2 = k->dir * k->rpm * FB_RAD_S_PER_RPM;
  fb_status st = k->kind->run(k, diag);
  if (st != FB_OK) return st;
  fb_diag dg;
  if ((st = fb_mech_peaks(&k->p, k->mech, &k->lk, k->branch, k->omega2, &dg)) != FB_OK)
    return fb_diag_set(diag, st, "%s; %s", k->grashof, dg.msg);
  return FB_OK;
}
