/* A planar case's free start and sliders in their guides
 * (casefile_planar_free.h). */
#include "casefile_planar_free.h"

#include <stdio.h>
#include <string.h>

/* the entry [section] key (key NULL: the section's first), or NULL */
static const entry *find(const entry *e, int n, const char *section, const char *key) {
  for (int i = 0; i < n; i++)
    if (strcmp(e[i].section, section) == 0 && (!key || strcmp(e[i].key, key) == 0)) return &e[i];
  return NULL;
}

fb_status fb_casefile_planar_free(const fb_case *c, const entry *e, int n, const char *path,
                                  fb_diag *diag) {
  const fb_planar_spec *s = &c->planar;
  const char *file = path ? path : "case";
  if (!s->undriven) {
    for (int b = 1; b < s->nbodies; b++) {
      char sec[sizeof e->section];
      snprintf(sec, sizeof sec, "body.%s", s->body[b].name);
      const entry *w = find(e, n, sec, "initial_omega_rad_s");
      if (w)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] initial_omega_rad_s = %s: initial "
                           "angular velocities are for an undriven case ([drive] joint = none); "
                           "a driven case starts on its drive's motion ([run] start)",
                           w->origin, w->section, w->value);
    }
    return FB_OK;
  }
  const int torque = s->torque_joint >= 0; /* a torque drive: undriven, with a torque */
  const char *what = torque ? "a torque-driven case ([drive] torque_n_m)"
                            : "an undriven case ([drive] joint = none)";
  const entry *st = find(e, n, "run", "start");
  if (st)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [run] start = %s: %s starts from %s; remove "
                       "[run] start (the speed drive's start key)", st->origin, st->value, what,
                       torque ? "[drive] speed0_rpm" : "its bodies' [body.NAME] "
                                                       "initial_omega_rad_s");
  if (!find(e, n, "run", "duration_s"))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: %s needs [run] duration_s, the simulated time "
                       "in s (its speed follows from the dynamics: no revolution to count)",
                       file, what);
  return FB_OK;
}

fb_status fb_casefile_planar_guides(const fb_case *c, const entry *e, int n, const char *path,
                                    fb_diag *diag) {
  const fb_planar_spec *s = &c->planar;
  int guides = 0;
  for (int j = 0; j < s->njoints; j++) {
    const fb_planar_spec_joint *sj = &s->joint[j];
    const int guide = sj->kind == FB_KIND_PRISMATIC && (c->clearance.mask & (1 << j));
    char sec[sizeof e->section];
    snprintf(sec, sizeof sec, "joint.%s", sj->name);
    const entry *at = find(e, n, sec, NULL);
    const int given = sj->given & (FB_SPEC_JOINT_HALF_LENGTH | FB_SPEC_JOINT_HALF_HEIGHT);
    guides += guide;
    if (!guide && given) {
      const entry *k = find(e, n, sec, sj->given & FB_SPEC_JOINT_HALF_LENGTH
                                           ? "slider_half_length_mm" : "slider_half_height_mm");
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = %s: a slider's size belongs to a "
                         "prismatic joint with clearance ([clearance] joints naming it), and "
                         "joint '%s' is %s", k->origin, k->section, k->key, k->value, sj->name,
                         sj->kind == FB_KIND_PRISMATIC ? "not in [clearance] joints" : "revolute");
    }
    if (guide && given != (FB_SPEC_JOINT_HALF_LENGTH | FB_SPEC_JOINT_HALF_HEIGHT))
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] has no %s: a prismatic joint with "
                         "clearance is a slider in its guide and needs the slider's "
                         "slider_half_length_mm (along the slide) and slider_half_height_mm "
                         "(across it)", at->origin, at->section,
                         given & FB_SPEC_JOINT_HALF_LENGTH ? "slider_half_height_mm"
                                                           : "slider_half_length_mm");
  }
  const entry *gc = find(e, n, "clearance", "guide_clearance_mm");
  if (guides && !gc)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [clearance] joints names a prismatic joint: give "
                       "[clearance] guide_clearance_mm, the gap on each side between the centred "
                       "slider's face and its guide's wall", path ? path : "case");
  if (!guides && gc)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [clearance] guide_clearance_mm = %s: no "
                       "prismatic joint is in [clearance] joints (the key is a slider's gap in "
                       "its guide)", gc->origin, gc->value);
  return FB_OK;
}
