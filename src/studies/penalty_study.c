/* fourbar penalty below the command (penalty_study.h). */
#include "penalty_study.h"

#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "units.h"

const char *const *fb_penalty_contact_models_of(fb_mech_type t) {
  return fb_mech_of(t)->contact_models;
}

/* the contact a run of case in uses, through the run's own law resolution */
static fb_status contact_used(fb_penalty_study *s, const fb_case *in, fb_diag *d) {
  /* the scene stage a run goes through, with both clearance laws asked for */
  static fb_case c;
  static fb_scene def;
  c = *in;
  c.model_count = 2;
  for (int m = 0; m < 2; m++) snprintf(c.models[m], FB_NAME_SIZE, "%s", s->contact_models[m]);
  fb_status st = fb_scene_from_case(&def, &c, d);
  if (st != FB_OK) return st;
  s->run_case = def.source;
  memcpy(s->laws[0], def.law[FB_MODEL_LAW_IMPACT], sizeof s->laws[0]);
  memcpy(s->laws[1], def.law[FB_MODEL_LAW_RESTITUTION], sizeof s->laws[1]);
  for (int m = 0; m < 2; m++)
    if ((st = fb_contact_estimates(s->est[m], &s->run_case, s->laws[m], d)) != FB_OK) return st;
  if ((st = fb_step_auto(&s->h_auto, &s->omega_c, &s->run_case, d)) != FB_OK) return st;
  s->stackup = def.lengths[FB_LENGTHS_STACKUP];
  const int nl = fb_case_mech(&s->run_case)->nlengths;
  for (int k = 0; k < nl; k++) s->corner[k] = "-0+"[s->run_case.stackup.corner[k] + 1];
  s->corner[nl] = '\0';
  s->mapping = (fb_mapping)s->run_case.clearance.mapping;
  return FB_OK;
}

void fb_penalty_study_run(fb_penalty_study *s, const fb_case *c, fb_penalty_mode mode,
                          const double *rpm, int n) {
  s->mech = c->mechanism;
  s->contact_models[0] = fb_penalty_contact_models_of(c->mechanism)[0];
  s->contact_models[1] = fb_penalty_contact_models_of(c->mechanism)[1];
  s->mode = mode;
  s->n = n;
  s->n_ok = 0;
  s->rows_status = FB_OK;
  s->rows_skipped = mode == FB_PENALTY_PAPER ? fb_penalty_paper_refusal(c) : NULL;
  for (int i = 0; i < n && !s->rows_skipped; i++) {
    s->rpm[i] = rpm[i];
    fb_diag d;
    s->rows_status = fb_penalty_rows(s->rows[i], c, mode, rpm[i] * FB_RAD_S_PER_RPM, &d);
    if (s->rows_status != FB_OK) {
      snprintf(s->rows_msg, sizeof s->rows_msg, "%s", d.msg);
      return;
    }
    s->n_ok = i + 1;
  }
  s->has_contact = c->clearance.mask != 0;
  s->contact_status = FB_OK;
  if (s->has_contact) {
    fb_diag d;
    s->contact_status = contact_used(s, c, &d);
    if (s->contact_status != FB_OK) snprintf(s->contact_msg, sizeof s->contact_msg, "%s", d.msg);
  }
}
