/* The MuJoCo engine behind the engine interface (engine.h): thin wrappers
 * over the MuJoCo scene (mujoco_scene.h). */
#include <stdio.h>

#include "engine.h"
#include "impact_mujoco.h"
#include "mujoco_kit.h"
#include "mujoco_scene.h"

static fb_status mujoco_create(void **self, const fb_model_scene *sm, fb_diag *diag) {
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

/* Time per sample [s] (engine.h: CPU time, timing.json models[].cpu_s over
 * its samples; issue 54): 1.8 to 2.3 us ideal, 8.05 us clearance (engines
 * and engines_restitution), 10.1 us native (paper case, 2 revolutions);
 * each rounded up. */
#define MUJOCO_COST_S 2.6e-6
#define MUJOCO_COST_CLEARANCE_S 9.5e-6
#define MUJOCO_COST_NATIVE_S 12e-6

static double mujoco_cost_per_sample(const fb_model *m, const fb_case *c) {
  (void)c;
  return m->joints != FB_JOINTS_CLEARANCE ? MUJOCO_COST_S
         : m->collider == FB_COLLIDER_NATIVE ? MUJOCO_COST_NATIVE_S
                                             : MUJOCO_COST_CLEARANCE_S;
}

/* MuJoCo's settings for its peer (tests/peers/peer_mujoco.c) */
static void mujoco_peer_args(const fb_model_scene *sm, double h, fb_engine_put_arg put, void *a) {
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

static const fb_engine_impact mujoco_impact = {
    .law = NULL, .row = mujoco_impact_row, .version = fb_mujoco_version};

/* MuJoCo's own choices as a model used them (0 in the case: 1/h^2, 1/h) */
static int mujoco_settings(fb_engine_setting *out, const fb_case *c, int clearance_mask,
                           fb_collider collider, double h) {
  const fb_mujoco_opts *mj = &c->mujoco;
  int n = 0;
  out[n++] = (fb_engine_setting){.key = "integrator", .kind = FB_SETTING_TEXT,
                                 .text = fb_mujoco_integrator_name(
                                     fb_mujoco_integrator_resolve(mj, clearance_mask))};
  out[n++] = (fb_engine_setting){.key = "loop_stiffness_1_s2", .kind = FB_SETTING_NUMBER,
                                 .number = mj->loop_stiffness > 0.0 ? mj->loop_stiffness
                                                                    : 1.0 / (h * h)};
  out[n++] = (fb_engine_setting){.key = "loop_damping_1_s", .kind = FB_SETTING_NUMBER,
                                 .number = mj->loop_damping > 0.0 ? mj->loop_damping : 1.0 / h};
  out[n++] = (fb_engine_setting){.key = "loop_impedance", .kind = FB_SETTING_NUMBER,
                                 .number = mj->loop_impedance};
  out[n++] = (fb_engine_setting){.key = "drive_armature_kg_m2", .kind = FB_SETTING_NUMBER,
                                 .number = mj->drive_armature};
  if (collider == FB_COLLIDER_NATIVE)
    out[n++] = (fb_engine_setting){.key = "native_bore", .kind = FB_SETTING_TEXT,
                                   .text = fb_mujoco_bore_name(mj->native_bore)};
  return n;
}

/* the run's table: MuJoCo's integrator(s) and loop closure, its native bore */
static void mujoco_settings_lines(const fb_case *c, const fb_engine_models_used *u,
                                  fb_engine_put_line put, void *a) {
  char line[512];
  snprintf(line, sizeof line,
           "MuJoCo models: integrator %s%s%s%s%s; loop closure solref (-k, -b) with k = %g "
           "1/s^2, b = %g 1/s, solimp %g",
           u->ideal ? fb_mujoco_integrator_name(fb_mujoco_integrator_resolve(&c->mujoco, 0)) : "",
           u->ideal ? " (ideal models)" : "", u->ideal && u->clearance ? ", " : "",
           u->clearance ? fb_mujoco_integrator_name(fb_mujoco_integrator_resolve(&c->mujoco, 1))
                        : "",
           u->clearance ? " (clearance models)" : "",
           c->mujoco.loop_stiffness > 0 ? c->mujoco.loop_stiffness
                                        : 1.0 / (c->solver.h * c->solver.h),
           c->mujoco.loop_damping > 0 ? c->mujoco.loop_damping : 1.0 / c->solver.h,
           c->mujoco.loop_impedance);
  put(a, line);
  if (u->native) {
    snprintf(line, sizeof line, "mujoco-clearance-native: bore %s ([mujoco] native_bore; %s)",
             fb_mujoco_bore_name(c->mujoco.native_bore),
             c->mujoco.native_bore == FB_MUJOCO_BORE_FACETS
                 ? "a sphere pin in a ring of boxes, MuJoCo's contacts"
                 : "a tendon limited to the radial clearance, MuJoCo's limit row along the "
                   "eccentricity");
    put(a, line);
  }
}

/* the clearance contact: MuJoCo's own, or the project's law as an applied force */
static const char *mujoco_mapping_text(fb_collider collider) {
  return collider == FB_COLLIDER_NATIVE ? "none (MuJoCo contact)" : "none (applied force)";
}

/* ---- MuJoCo's rows of fourbar bench (engine_bench.h): the case's loop
 * closure and drive throughout ---- */

/* [solver] h_s = adaptive at FB_BENCH_ADAPTIVE_ACCURACY(i) with the case's
 * integrator */
static void mujoco_adaptive(int i, fb_case *k, fb_bench_point *p) {
  fb_bench_adaptive_step(k, FB_BENCH_ADAPTIVE_ACCURACY(i));
  snprintf(p->stepper, sizeof p->stepper, "%s-a%g", fb_mujoco_integrator_name(k->mujoco.integrator),
           FB_BENCH_ADAPTIVE_ACCURACY(i));
}

static int mujoco_bench_point(fb_bench_set s, int i, const fb_case *c, fb_case *k,
                              fb_bench_point *p) {
  (void)c;
  switch (s) {
    case FB_BENCH_SET_DEFAULT: /* the case's integrator at 1e-5 s, 3e-6 s and adaptive 0.3 */
      if (i >= 3) return 0;
      fb_bench_fixed_step(k, i == 0 ? 1e-5 : i == 1 ? 3e-6 : 0.0);
      if (i == 2) fb_bench_adaptive_step(k, 0.3);
      snprintf(p->stepper, sizeof p->stepper, "%s%s",
               fb_mujoco_integrator_name(k->mujoco.integrator), i == 2 ? "-a0.3" : "");
      return 1;
    case FB_BENCH_SET_SOLVERS: { /* the adaptive rows, then integrator x step */
      if (i < FB_BENCH_ADAPTIVE) {
        mujoco_adaptive(i, k, p);
        return 1;
      }
      i -= FB_BENCH_ADAPTIVE;
      if (i >= 3 * FB_BENCH_MUJOCO_STEPS) return 0;
      const double mh[FB_BENCH_MUJOCO_STEPS] = {1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6};
      const int integ[3] = {FB_MUJOCO_EULER, FB_MUJOCO_IMPLICIT, FB_MUJOCO_RK4};
      fb_bench_fixed_step(k, mh[i % FB_BENCH_MUJOCO_STEPS]);
      k->mujoco.integrator = integ[i / FB_BENCH_MUJOCO_STEPS];
      snprintf(p->stepper, sizeof p->stepper, "%s", fb_mujoco_integrator_name(k->mujoco.integrator));
      return 1;
    }
    case FB_BENCH_SET_FRONTIER: /* the case's integrator at the frontier's fixed steps */
      if (i >= FB_BENCH_FRONTIER_STEPS - 1) return 0;
      fb_bench_fixed_step(k, FB_BENCH_FRONTIER_H(i));
      snprintf(p->stepper, sizeof p->stepper, "%s", fb_mujoco_integrator_name(k->mujoco.integrator));
      return 1;
    case FB_BENCH_SET_FRONTIER_LAST:
      if (i >= FB_BENCH_ADAPTIVE) return 0;
      mujoco_adaptive(i, k, p);
      return 1;
    default: return 0;
  }
}

static const fb_engine_bench mujoco_bench = {.point = mujoco_bench_point};

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
    .settings = mujoco_settings,
    .settings_lines = mujoco_settings_lines,
    .mapping_text = mujoco_mapping_text,
    .bench = &mujoco_bench,
    .kit = &fb_mujoco_kit,
    .kit_native = &fb_mujoco_kit_native,
    /* the kit builds MuJoCo's clearance models by default (its native contact
     * through kit_native): their binding has every feature of the scene's
     * (friction, which the scene ignored, it refuses), is nearer the
     * reference and costs about half a step on the four-bar, whose scene
     * closes its loop by a soft connect (the slider-crank's tree 1.16x);
     * the ideal models keep the scene, where the kit's sampling costs more
     * (callgrind 1.17x on the paper case; docs/architecture.md) */
    .kit_default = FB_KIT_DEFAULT_CLEARANCE,
};
