/* One step of the MuJoCo scene (mujoco_scene.h, "Stepping and sampling"):
 * MuJoCo's integrator with the project's hook, the forward pass at the new
 * state and the clearance joints' bookkeeping; and the adaptive step
 * ([solver] h_s = adaptive, step_control.h): its size from the contacts,
 * the samples inside a step. */
#include <math.h>

#include "contact_mass.h"
#include "kit_record.h"
#include "mujoco_common.h"
#include "mujoco_scene_internal.h"
#include "step_control.h"

/* one MuJoCo step of the model's timestep from the state now */
static void step_once(fb_mujoco_scene *s) {
  mujoco_hook_on(s);
  /* integrate with the accelerations of the last forward pass (this state) */
  fb_mujoco_integrate(s->m, s->d, s->integrator);
  mj_forward(s->m, s->d);
  mujoco_hook_off();
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    mj_clearance *c = &s->cl[j];
    if (s->def.native) {
      mujoco_native_force(s, j);
      mujoco_native_solref_update(s, j);
    }
    fb_episode_update(&c->ep, c->delta > 0.0, c->ddot, s->def.impact_velocity_min);
    if (c->delta > 0.0) {
      /* one solve serves the provenance and the next adaptive step */
      const double me = mujoco_joint_effective_mass(s, s->m, s->d, j);
      s->ad.m_eff_now[j] = me;
      mujoco_note_contact(s, j, me);
    }
  }
  s->ad.m_eff_fresh = 1;
  mujoco_reactions_now(s);
}

/* the next adaptive step as grid steps: the shortest any clearance joint's
 * contact asks for (step_control.h; persistence from the contact phase, as
 * ODE's matched-static row counts it), ramped */
static int adapt_multiple(fb_mujoco_scene *s) {
  const double hg = s->def.h;
  double h = s->def.h_max;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const mj_clearance *c = &s->cl[j];
    if (c->delta > 0.0) {
      const double me =
          s->ad.m_eff_fresh ? s->ad.m_eff_now[j] : mujoco_joint_effective_mass(s, s->m, s->d, j);
      if (me > 0.0) s->ad.m_eff[j] = me;
    }
    fb_step_joint sj = {.rule = FB_PERSIST_DEPTH_CHANGE};
    sj.delta = c->delta;
    sj.ddot = c->ddot;
    sj.m_eff = s->ad.m_eff[j];
    sj.dddot = s->ad.stats.steps > 0 ? (c->ddot - s->ad.ddot_prev[j]) / s->ad.h_prev : 0.0;
    s->ad.ddot_prev[j] = c->ddot;
    sj.persistence = c->delta > 0.0 ? fb_contact_persistence(s->ad.phase[j]) : 0.0;
    const fb_contact_law law = fb_contact_law_on_mass(&s->def.law[j], sj.m_eff);
    h = fmin(h, fb_step_adaptive(&law, &sj, s->def.accuracy, hg, s->def.h_max));
  }
  const int want = (int)floor(h / hg * (1.0 + 1e-9));
  return fb_step_ramp(want < 1 ? 1 : want, s->ad.m_prev, s->ad.m_max);
}

fb_status fb_mujoco_scene_step(fb_mujoco_scene *s, fb_diag *diag) {
  (void)diag;
  if (!s->def.adaptive) {
    step_once(s);
    s->steps++;
    return FB_OK;
  }
  if (s->ad.k < s->ad.mc) { /* a sample inside the last step */
    s->ad.k++;
    s->steps++;
    return FB_OK;
  }
  const int mult = adapt_multiple(s);
  const double h = mult * s->def.h;
  mujoco_sample_now(s, &s->ad.x0);
  s->m->opt.timestep = h;
  step_once(s);
  mujoco_sample_now(s, &s->ad.x1);
  /* the contact phase (contact.h): h omega_c at each joint in contact */
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const mj_clearance *c = &s->cl[j];
    if (!(c->delta > 0.0)) {
      s->ad.phase[j] = 0.0;
      continue;
    }
    double kp, kd, depth;
    fb_contact_linearize(&s->def.law[j], FB_MAPPING_TANGENT, c->delta, c->ddot, c->ep.v0, &kp,
                         &kd, &depth);
    s->ad.phase[j] += fb_contact_h_omega(h, kp, s->ad.m_eff[j]);
  }
  fb_kit_stats_add(&s->ad.stats, h);
  s->ad.m_prev = mult;
  s->ad.h_prev = h;
  s->ad.mc = mult;
  s->ad.k = 1;
  s->steps++;
  return FB_OK;
}

void fb_mujoco_scene_step_stats(const fb_mujoco_scene *s, fb_step_stats *out) {
  if (s->def.adaptive) {
    *out = s->ad.stats;
    return;
  }
  fb_kit_stats_fixed(out, s->steps, s->def.h);
}
