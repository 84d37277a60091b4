/* The MuJoCo engine behind the engine interface (engine.h): thin wrappers
 * over the MuJoCo scene (mujoco_scene.h). */
#include "engine.h"
#include "impact_mujoco.h"
#include "mujoco_scene.h"

static fb_status mujoco_create(void **self, const fb_scene_model *sm, fb_diag *diag) {
  fb_mujoco_scene *s = NULL;
  fb_status st = fb_mujoco_scene_create(&s, sm, diag);
  if (st == FB_OK) *self = s;
  return st;
}

static fb_status mujoco_step(void *self, fb_diag *diag) { return fb_mujoco_scene_step(self, diag); }

static void mujoco_sample(const void *self, fb_sample *x) { fb_mujoco_scene_sample(self, x); }

static void mujoco_contact(const void *self, fb_engine_contact *out) {
  out->penetration = fb_mujoco_scene_penetration(self, &out->joint);
  for (int j = 0; j < 4; j++) out->impacts[j] = fb_mujoco_scene_impacts(self, j);
}

static void mujoco_provenance(const void *self, int joint, fb_contact_provenance *out) {
  fb_mujoco_scene_provenance(self, joint, out);
}

static void mujoco_reactions(const void *self, double force[4][2], double *drive_torque) {
  fb_mujoco_scene_reactions(self, force, drive_torque);
}

static double mujoco_drift(const void *self) { return fb_mujoco_scene_joint_drift(self); }

static size_t mujoco_steps(const void *self) { return fb_mujoco_scene_steps(self); }

static void mujoco_destroy(void *self) { fb_mujoco_scene_destroy(self); }

static void mujoco_step_stats(const void *self, fb_step_stats *out) {
  fb_mujoco_scene_step_stats(self, out);
}

/* Wall time per sample on an idle 2-core machine [s] (engine.h): measured on
 * the paper's case, 3.5 to 4.2 us ideal, 15.5 to 17.5 us clearance, 23 us
 * native; each rounded up. */
#define MUJOCO_COST_S 5e-6
#define MUJOCO_COST_CLEARANCE_S 18e-6
#define MUJOCO_COST_NATIVE_S 25e-6

static double mujoco_cost_per_sample(const fb_model *m, const fb_case *c) {
  (void)c;
  return m->joints != FB_JOINTS_CLEARANCE ? MUJOCO_COST_S
         : m->collider == FB_COLLIDER_NATIVE ? MUJOCO_COST_NATIVE_S
                                             : MUJOCO_COST_CLEARANCE_S;
}

/* MuJoCo's settings for its peer (tests/peers/peer_mujoco.c) */
static void mujoco_peer_args(const fb_scene_model *sm, double h, fb_engine_put_arg put, void *a) {
  const fb_mujoco_opts *o = &sm->mujoco;
  put(a, "integrator", fb_mujoco_integrator_name(fb_mujoco_integrator_resolve(o, 0)));
  fb_engine_put_number(put, a, "loop_k", o->loop_stiffness > 0.0 ? o->loop_stiffness : 1.0 / (h * h));
  fb_engine_put_number(put, a, "loop_b", o->loop_damping > 0.0 ? o->loop_damping : 1.0 / h);
  fb_engine_put_number(put, a, "loop_imp", o->loop_impedance);
  fb_engine_put_number(put, a, "armature", o->drive_armature);
}
/* the single impact (impact_mujoco.h): a fixed row only */
static fb_status mujoco_impact_row(fb_impact_result *out, const fb_impact_row *r,
                                   fb_diag *diag) {
  return fb_impact_mujoco(out, r->mass, r->speed, r->h, r->mujoco.solref, r->mujoco.solimp,
                          r->t_max, r->onset_phase, diag);
}

static const fb_engine_impact mujoco_impact = {.law = NULL, .row = mujoco_impact_row};

const fb_engine fb_engine_mujoco = {
    .name = "mujoco",
    .guarded = 1,
    .create = mujoco_create,
    .step = mujoco_step,
    .sample = mujoco_sample,
    .contact = mujoco_contact,
    .provenance = mujoco_provenance,
    .reactions = mujoco_reactions,
    .drift = mujoco_drift,
    .steps = mujoco_steps,
    .destroy = mujoco_destroy,
    .step_stats = mujoco_step_stats,
    .cost_per_sample = mujoco_cost_per_sample,
    .drive_key = "[mujoco] drive_armature_kg_m2",
    .peer_args = mujoco_peer_args,
    .model_format = "mjcf",
    .export_model = fb_mujoco_export,
    .impact = &mujoco_impact,
};
