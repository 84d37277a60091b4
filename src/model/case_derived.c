/* The case's names and the quantities derived from its fields alone (the
 * model floor: data and what follows from it, no checks, no physics beyond
 * unit-free arithmetic): joint and value-source names, the crank's signed
 * speed, the generic colliders' ring and bore, the stack-up corner's lengths, the run's duration, the
 * penetration limit and the peak window (each engine's option names are
 * its opts_<name>.c). Declared in case.h;
 * the case's defaults and checks are setup/case.c. */
#include "case.h"

#include <math.h>

const char *fb_joint_name(int j) { return fb_mech_joint_name(&fb_mech_fourbar, j); }

const fb_mech_desc *fb_case_mech(const fb_case *c) { return fb_mech_of(c->mechanism); }

const char *fb_case_joint_name(const fb_case *c, int j) {
  return fb_mech_joint_name(fb_case_mech(c), j);
}

const char *fb_value_source_name(int s) {
  static const char *const names[3] = {"case", "derived", "default"};
  return (s >= 0 && s < 3) ? names[s] : "?";
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

int fb_case_clearance_count(const fb_case *c) {
  int n = 0;
  for (unsigned m = (unsigned)c->clearance.mask; m; m &= m - 1) n++;
  return n;
}

int fb_case_compared_joint(const fb_case *c) {
  const int cj = fb_case_mech(c)->reference_joint;
  if (c->clearance.mask & (1 << cj)) return cj;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
    if (c->clearance.mask & (1 << j)) return j;
  return -1;
}

int fb_case_faceted_n(const fb_case *c) {
  return c->clearance.segments_given ? c->clearance.segments : c->clearance.faceted_n;
}

double fb_case_bore_ovality(const fb_case *c) {
  return c->clearance.bore == FB_CASE_BORE_ELLIPSE ? c->clearance.ovality : 0.0;
}

void fb_case_stackup_lengths(const fb_case *c, fb_linkage *out) {
  for (int i = 0; i < FB_LINK_COUNT; i++)
    out->length[i] = c->nominal.length[i] + c->stackup.corner[i] * c->plus_minus[i];
}

double fb_case_duration(const fb_case *c) {
  if (c->duration_s > 0.0) return c->duration_s;
  return c->revolutions * 2.0 * M_PI / c->crank_speed;
}
