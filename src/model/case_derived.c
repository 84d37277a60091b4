/* The case's names and the quantities derived from its fields alone (the
 * model floor: data and what follows from it, no checks, no physics beyond
 * unit-free arithmetic): joint and value-source names, each engine option's
 * name, the crank's signed speed, the stack-up corner's lengths, the run's
 * duration, the penetration limit and the peak window. Declared in case.h;
 * the case's defaults and checks are setup/case.c. */
#include "case.h"

#include <math.h>

const char *fb_joint_name(int j) { return fb_mech_joint_name(&fb_mech_fourbar, j); }

const fb_mech_desc *fb_case_mech(const fb_case *c) {
  (void)c;
  return &fb_mech_fourbar;
}

const char *fb_value_source_name(int s) {
  static const char *const names[3] = {"case", "derived", "default"};
  return (s >= 0 && s < 3) ? names[s] : "?";
}

const char *fb_bullet_solver_name(int k) {
  static const char *const names[] = {"sequential-impulse", "mlcp-dantzig"};
  return k >= 0 && k <= FB_BULLET_MLCP_DANTZIG ? names[k] : "?";
}

const char *fb_simbody_integrator_name(int k) {
  static const char *const names[FB_SIMBODY_INTEGRATOR_COUNT] = {"rkmerson", "rkfeldberg", "rk3",
                                                                 "cpodes", "verlet"};
  return k >= 0 && k < FB_SIMBODY_INTEGRATOR_COUNT ? names[k] : "?";
}

int fb_mujoco_integrator_resolve(const fb_mujoco_opts *o, int clearance_mask) {
  if (o->integrator != FB_MUJOCO_AUTO) return o->integrator;
  return clearance_mask ? FB_MUJOCO_RK4 : FB_MUJOCO_EULER;
}

const char *fb_mujoco_bore_name(int k) {
  static const char *const names[] = {"tendon", "facets"};
  return k >= 0 && k <= FB_MUJOCO_BORE_FACETS ? names[k] : "?";
}

const char *fb_mujoco_integrator_name(int k) {
  static const char *const names[] = {"euler", "implicit", "rk4", "auto"};
  return k >= 0 && k <= FB_MUJOCO_AUTO ? names[k] : "?";
}


double fb_case_penetration_limit(const fb_case *c) {
  if (c->clearance.penetration_unlimited) return INFINITY;
  return c->clearance.penetration_limit > 0.0 ? c->clearance.penetration_limit
                                              : c->radial_clearance;
}

double fb_case_peak_window_from(const fb_case *c) {
  if (c->peaks == FB_PEAKS_ALL) return 0.0;
  return 2.0 * M_PI / c->crank_speed - 0.5 * c->solver.h;
}

double fb_case_omega2(const fb_case *c) { return c->direction * c->crank_speed; }

void fb_case_stackup_lengths(const fb_case *c, fb_linkage *out) {
  for (int i = 0; i < FB_LINK_COUNT; i++)
    out->length[i] = c->nominal.length[i] + c->stackup.corner[i] * c->plus_minus[i];
}

double fb_case_duration(const fb_case *c) {
  return c->revolutions * 2.0 * M_PI / c->crank_speed;
}
