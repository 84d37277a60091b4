/* The ODE engine behind the engine interface (engine.h): thin wrappers over
 * the ODE world (ode_world.h). */
#include "engine.h"
#include "ode_world.h"

static fb_status ode_create(void **self, const fb_scene_model *sm, fb_diag *diag) {
  fb_ode_world *s = NULL;
  fb_status st = fb_ode_world_create(&s, sm, diag);
  if (st == FB_OK) *self = s;
  return st;
}

static fb_status ode_step(void *self, fb_diag *diag) { return fb_ode_world_step(self, diag); }

static void ode_stopped(const void *self, fb_stop *out) { fb_ode_world_stopped(self, out); }

static void ode_sample(const void *self, fb_sample *x) { fb_ode_world_sample(self, x); }

static void ode_contact(const void *self, fb_engine_contact *out) {
  out->penetration = fb_ode_world_penetration(self, &out->joint);
  for (int j = 0; j < 4; j++) out->impacts[j] = fb_ode_world_impacts(self, j);
}

static void ode_provenance(const void *self, int joint, fb_contact_provenance *out) {
  fb_ode_world_provenance(self, joint, out);
}

static void ode_reactions(const void *self, double force[4][2], double *drive_torque) {
  fb_ode_world_reactions(self, force, drive_torque);
}

static double ode_drift(const void *self) { return fb_ode_world_joint_drift(self); }

static size_t ode_steps(const void *self) { return fb_ode_world_steps(self); }

static void ode_destroy(void *self) { fb_ode_world_destroy(self); }

static void ode_step_stats(const void *self, fb_step_stats *out) {
  fb_ode_world_step_stats(self, out);
}

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
};
