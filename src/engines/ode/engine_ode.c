/* The ODE engine behind the engine interface (engine.h): thin wrappers over
 * the scene (scene.h). */
#include "engine.h"
#include "impact_ode.h"
#include "scene.h"

static fb_status ode_create(void **self, const fb_scene_model *sm, fb_diag *diag) {
  fb_scene *s = NULL;
  fb_status st = fb_scene_create(&s, sm, diag);
  if (st == FB_OK) *self = s;
  return st;
}

static fb_status ode_step(void *self, fb_diag *diag) { return fb_scene_step(self, diag); }

static void ode_stopped(const void *self, fb_stop *out) { fb_scene_stopped(self, out); }

static void ode_sample(const void *self, fb_sample *x) { fb_scene_sample(self, x); }

static void ode_contact(const void *self, fb_engine_contact *out) {
  out->penetration = fb_scene_penetration(self, &out->joint);
  for (int j = 0; j < 4; j++) out->impacts[j] = fb_scene_impacts(self, j);
}

static void ode_provenance(const void *self, int joint, fb_contact_provenance *out) {
  fb_scene_provenance(self, joint, out);
}

static void ode_reactions(const void *self, double force[4][2], double *drive_torque) {
  fb_scene_reactions(self, force, drive_torque);
}

static double ode_drift(const void *self) { return fb_scene_joint_drift(self); }

static size_t ode_steps(const void *self) { return fb_scene_steps(self); }

static void ode_destroy(void *self) { fb_scene_destroy(self); }

static void ode_step_stats(const void *self, fb_step_stats *out) {
  fb_scene_step_stats(self, out);
}

/* the single impact (impact_ode.h) */
static fb_status ode_impact_law(fb_impact_result *out, const fb_impact_def *d,
                                const fb_impact_opts *o, fb_diag *diag) {
  (void)o;
  return fb_impact_ode(out, d, diag);
}

static fb_status ode_impact_row(fb_impact_result *out, const fb_impact_row *r, fb_diag *diag) {
  return fb_impact_ode_row(out, r->mass, r->speed, r->h, r->ode.erp, r->ode.cfm, r->max_vel,
                           r->t_max, r->onset_phase, diag);
}

static const fb_engine_impact ode_impact = {.law = ode_impact_law, .row = ode_impact_row};

const fb_engine fb_engine_ode = {
    .name = "ode",
    .guarded = 1,
    .step_values_lag = 1,
    .refine_peaks = 1,
    .create = ode_create,
    .step = ode_step,
    .stopped = ode_stopped,
    .sample = ode_sample,
    .contact = ode_contact,
    .provenance = ode_provenance,
    .reactions = ode_reactions,
    .drift = ode_drift,
    .steps = ode_steps,
    .destroy = ode_destroy,
    .step_stats = ode_step_stats,
    .impact = &ode_impact,
};
