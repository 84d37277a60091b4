/* What the MuJoCo scene and the kit's binding share (mujoco_common.h). */
#include "mujoco_common.h"

/* the hook of the model being stepped on this thread */
static _Thread_local struct {
  const mjModel *m;
  fb_mujoco_passive_fn fn;
  void *ctx;
} hook;

static void passive(const mjModel *m, mjData *d) {
  if (hook.fn && hook.m == m) hook.fn(hook.ctx, m, d);
}

void fb_mujoco_passive_on(const mjModel *m, fb_mujoco_passive_fn fn, void *ctx) {
  hook.m = m;
  hook.fn = fn;
  hook.ctx = ctx;
  mjcb_passive = passive;
}

void fb_mujoco_passive_off(void) { hook.fn = NULL; }

void fb_mujoco_integrate(const mjModel *m, mjData *d, int integrator) {
  switch (integrator) {
    case FB_MUJOCO_RK4: mj_RungeKutta(m, d, 4); break;
    case FB_MUJOCO_IMPLICIT: mj_step2(m, d); break; /* redoes the acceleration stage */
    default: mj_Euler(m, d); break;
  }
}

const char *fb_mujoco_integrator_xml(int integrator) {
  static const char *const names[3] = {"Euler", "implicit", "RK4"};
  return integrator >= 0 && integrator < 3 ? names[integrator] : "Euler";
}

void fb_mujoco_loop_solref(const fb_mujoco_opts *o, double h, double sr[2]) {
  sr[0] = -(o->loop_stiffness > 0.0 ? o->loop_stiffness : 1.0 / (h * h));
  sr[1] = -(o->loop_damping > 0.0 ? o->loop_damping : 1.0 / h);
}

int fb_mujoco_export_integrator(const fb_mujoco_opts *o) {
  return o->integrator == FB_MUJOCO_AUTO ? FB_MUJOCO_RK4 : o->integrator;
}

void fb_mujoco_export_loop_solref(const fb_mujoco_opts *o, int integrator, double h,
                                  double sr[2]) {
  fb_mujoco_loop_solref(o, h, sr);
  if (o->loop_stiffness > 0.0 || o->loop_damping > 0.0) return;
  sr[0] = 2.0 * h;
  sr[1] = integrator == FB_MUJOCO_RK4 ? FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_RK4
                                      : FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_EULER;
}
