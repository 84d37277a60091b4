/* What a step leaves in the harness's records (kit_record.h). */
#include "kit_record.h"

#include <math.h>

#include "case.h"
#include "contact.h"
#include "links.h"

void fb_kit_stats_add(fb_step_stats *t, double h) {
  const double r = FB_KIT_SAME_STEP_REL;
  if (t->steps == 0 || h < t->h_min * (1.0 - r)) t->h_min = h, t->n_h_min = 0;
  if (t->steps == 0 || h > t->h_max * (1.0 + r)) t->h_max = h, t->n_h_max = 0;
  t->n_h_min += fabs(h - t->h_min) <= r * h;
  t->n_h_max += fabs(h - t->h_max) <= r * h;
  t->steps++;
}

void fb_kit_stats_fixed(fb_step_stats *out, size_t steps, double h) {
  out->steps = steps;
  out->h_min = out->h_max = h;
  out->n_h_min = out->n_h_max = steps;
}

fb_status fb_kit_alias_diag(fb_diag *diag, double wdh, const char *joint, double h) {
  return fb_diag_set(diag, FB_ERR_NUMERIC, "aliased: omega_d h = %.3g at the %s joint (bound "
                     "%.3g); largest usable step %.3g s", wdh, joint, FB_MATCHED_ALIAS_BOUND,
                     h * FB_MATCHED_ALIAS_BOUND / wdh);
}

int fb_kit_aliased(fb_mapping mapping, double wdh) {
  return fb_mapping_is_matched(mapping) && wdh > FB_MATCHED_ALIAS_BOUND;
}

fb_status fb_kit_alias_stop(fb_stop *stop, int joint, double wdh, double h, size_t steps,
                            fb_diag *diag) {
  stop->kind = FB_STOP_ALIASED;
  stop->t = (double)steps * h;
  stop->step = steps + 1;
  stop->joint = joint;
  stop->value = wdh;
  stop->limit = FB_MATCHED_ALIAS_BOUND;
  stop->h_max = h * FB_MATCHED_ALIAS_BOUND / wdh;
  return fb_kit_alias_diag(diag, wdh, fb_joint_name(joint), h);
}

void fb_kit_sample_bodies(fb_sample *x, double t, const double angle[3], const double omega[3],
                          const double alpha[3]) {
  x->t = t;
  x->crank_angle = angle[FB_CRANK];
  x->coupler_angle = angle[FB_COUPLER];
  x->coupler_omega = omega[FB_COUPLER];
  x->coupler_alpha = alpha[FB_COUPLER];
  x->follower_angle = angle[FB_FOLLOWER];
  x->follower_omega = omega[FB_FOLLOWER];
  x->follower_alpha = alpha[FB_FOLLOWER];
}

void fb_kit_sample_contact(double col[FB_CONTACT_COLS], double force, double pen, double ex,
                           double ey, const fb_episode *ep) {
  col[FB_C_FORCE] = force;
  col[FB_C_PEN] = pen;
  col[FB_C_EX] = ex;
  col[FB_C_EY] = ey;
  col[FB_C_STATE] = force > 0.0 ? (double)ep->state : (double)FB_STATE_FREE;
}
