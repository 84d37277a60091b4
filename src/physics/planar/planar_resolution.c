/* the contact estimate and automatic step of a planar case (planar_resolution.h) */
#include "planar_resolution.h"

#include <math.h>
#include <stdlib.h>

#include "effective_mass.h"
#include "joint_law.h"
#include "planar_invdyn.h"
#include "planar_kinematics.h"
#include "planar_mass.h"
#include "planar_path.h"

/* the effective-mass range of clearance joint j over a revolution and
 * every direction: lo, hi [kg] */
static fb_status m_eff_range(double *lo, double *hi, const fb_case *c, const fb_planar *m, int j,
                             fb_diag *diag) {
  const int nq = fb_planar_nq(m);
  double *q = malloc((size_t)nq * sizeof *q);
  unsigned char *off = calloc((size_t)m->njoints, 1);
  fb_planar_kin *k = NULL;
  fb_status st = q && off ? fb_planar_kin_new(&k, m, diag)
                          : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int i = 0; i < m->njoints && off; i++)
    off[i] = ((unsigned)c->clearance.mask >> i) & 1u;
  *lo = INFINITY;
  *hi = 0.0;
  if (st == FB_OK) {
    fb_planar_assembly(m, q);
    st = fb_planar_position(k, q, 0.0, NULL, diag);
  }
  double from = 0.0;
  for (int s = 0; s < FB_RESOLUTION_SAMPLES && st == FB_OK; s++) {
    const double to = c->direction * 2.0 * M_PI * s / FB_RESOLUTION_SAMPLES;
    fb_path_end end;
    if (s > 0) st = fb_planar_follow(k, q, from, to, NULL, &end, diag);
    from = to;
    double w[2][2], a, b;
    if (st == FB_OK) st = fb_planar_effective_mass_tensor(w, m, q, off, j, diag);
    if (st != FB_OK) break;
    fb_effective_mass_range(w, &a, &b);
    *lo = fmin(*lo, a);
    *hi = fmax(*hi, b);
  }
  fb_planar_kin_free(k);
  free(q);
  free(off);
  return st;
}

fb_status fb_planar_contact_estimates(fb_planar_contact_estimate *out, int *n, const fb_case *c,
                                      const fb_planar *m, fb_diag *diag) {
  *n = 0;
  if (!c->clearance.mask || c->planar.undriven) return FB_OK;
  double *most = malloc((size_t)m->njoints * sizeof *most);
  if (!most) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  fb_status st = fb_planar_reaction_max(most, m, c->direction * c->crank_speed, c->gravity, diag);
  for (int j = 0; j < m->njoints && st == FB_OK; j++) {
    if (!(((unsigned)c->clearance.mask >> j) & 1u) || m->joint[j].kind != FB_KIND_REVOLUTE) continue;
    double lo, hi;
    st = m_eff_range(&lo, &hi, c, m, j, diag);
    const double mass = fb_planar_joint_law_mass(m, j);
    for (int impact = 1; impact >= 0 && st == FB_OK; impact--) {
      fb_planar_contact_estimate *e = &out[(*n)];
      *e = (fb_planar_contact_estimate){.joint = j, .impact = impact, .m_eff_min = lo,
                                        .m_eff_max = hi, .reaction_max = most[j]};
      st = fb_joint_law_at(&e->law, c, impact, most[j], m->joint[j].name, mass, diag);
      if (st != FB_OK) break;
      e->force_expected = FB_IMPACT_LOAD_FACTOR * most[j];
      fb_contact_rates_at(&e->rates, &e->law, lo, e->force_expected);
      e->stiffness_tangent = e->rates.stiffness_tangent;
      e->omega_c = e->rates.omega_c;
      e->h_resolving = FB_H_OMEGA_C_BOUND / e->rates.rate;
      (*n)++;
    }
  }
  free(most);
  return st;
}


fb_status fb_planar_step_auto(double *h, const fb_case *c, const fb_planar *m, fb_diag *diag) {
  *h = c->planar.undriven ? NAN : 2.0 * M_PI / (c->crank_speed * FB_H_AUTO_STEPS_PER_REV);
  if (c->planar.undriven || !c->clearance.mask) return FB_OK;
  fb_planar_contact_estimate *est = malloc(2 * (size_t)m->njoints * sizeof *est);
  if (!est) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  int n = 0;
  fb_status st = fb_planar_contact_estimates(est, &n, c, m, diag);
  for (int k = 0; k < n && st == FB_OK; k++) *h = fmin(*h, est[k].h_resolving);
  free(est);
  return st;
}
