/* The kit's adaptive step (kit_adaptive.h). */
#include "kit_adaptive.h"

#include <math.h>
#include <string.h>

#include "contact_mass.h"

int fb_kit_adapt_m_max(const fb_kit_world *o) {
  const fb_solver *sv = o->solver;
  if (!sv || sv->h_mode != FB_STEP_ADAPTIVE) return 1;
  const int m = (int)floor(sv->h_max / o->h * (1.0 + 1e-9));
  return m < 1 ? 1 : m;
}

fb_status fb_kit_adapt_open(fb_kit_adapt *a, fb_kit_pipe *p, const fb_kit_binding *b,
                            const fb_planar *m, const fb_kit_world *o,
                            const fb_kit_clearance *cl, fb_diag *diag) {
  memset(a, 0, sizeof *a);
  const fb_solver *sv = o->solver;
  if (!sv || sv->h_mode != FB_STEP_ADAPTIVE) return FB_OK;
  const unsigned mask = cl ? cl->mask : 0u;
  if (mask && cl->collider.kind == FB_COLLIDER_NATIVE)
    return fb_diag_set(diag, FB_ERR_ARG, "[solver] h_s = adaptive follows the project's contact "
                       "law at the exact pin; the %s engine's native contact is its own: give a "
                       "fixed step or auto", b->engine);
  if (!b->step_by)
    return fb_diag_set(diag, FB_ERR_ARG, "[solver] h_s = adaptive: the %s engine's binding steps "
                       "at a fixed h; give a fixed step or auto", b->engine);
  if (mask && (cl->collider.kind == FB_COLLIDER_FACETED || cl->collider.kind == FB_COLLIDER_CCD))
    return fb_diag_set(diag, FB_ERR_ARG, "[solver] h_s = adaptive follows the exact pin in its "
                       "hole; the %s collider's contacts are not followed: give a fixed step or "
                       "auto", fb_collider_name(cl->collider.kind));
  for (int j = 0; j < m->njoints; j++)
    if ((mask & (1u << j)) && m->joint[j].kind != FB_KIND_REVOLUTE)
      return fb_diag_set(diag, FB_ERR_ARG, "[solver] h_s = adaptive follows a pin in its hole; "
                         "the clearance joint '%s' is a slider in its guide: give a fixed step "
                         "or auto", m->joint[j].name);
  if (mask && b->persistent_rule == FB_PERSIST_LOAD_SCHEDULE && !cl->load)
    return fb_diag_set(diag, FB_ERR_ARG, "[solver] h_s = adaptive: the %s engine's step in "
                       "persistent contact follows the ideal joint loads ahead, and this run has "
                       "no load schedule (a drive at constant speed); give a fixed step or auto",
                       b->engine);
  a->on = 1;
  a->h_grid = o->h;
  a->h_max = sv->h_max;
  a->accuracy = sv->accuracy;
  a->m_max = fb_kit_adapt_m_max(o);
  a->m_prev = 1;
  a->rocking_h_omega = mask ? sv->rocking_h_omega : 0.0;
  p->rocking = a->rocking_h_omega > 0.0;
  return FB_OK;
}

fb_status fb_kit_adapt_multiple(int *mult, fb_kit_adapt *a, fb_kit_pipe *p,
                                const fb_kit_binding *b, const fb_planar *m,
                                const fb_kit_clearance *cl, fb_diag *diag) {
  double h = a->h_max;
  int impulsive = 0; /* a joint penetrating with its matched row (step_control.h) */
  for (int j = 0; cl && j < m->njoints; j++) {
    if (!(cl->mask & (1u << j))) continue;
    fb_step_joint sj;
    fb_status st = fb_kit_pipe_step_joint(&sj, &impulsive, p, b, m, cl, j, diag);
    if (st != FB_OK) return st;
    if (sj.rule == FB_PERSIST_DEPTH_CHANGE) { /* the rate's change over the last step */
      sj.dddot = a->h_prev > 0.0 ? (sj.ddot - a->ddot_prev[j]) / a->h_prev : 0.0;
      a->ddot_prev[j] = sj.ddot;
    }
    sj.rocking_h_omega = a->rocking_h_omega;
    const fb_contact_law law = fb_contact_law_on_mass(&cl->joint[j].law, sj.m_eff);
    h = fmin(h, fb_step_adaptive(&law, &sj, a->accuracy, a->h_grid, a->h_max));
  }
  int want = (int)floor(h / a->h_grid * (1.0 + 1e-9));
  want = fb_step_hold_in_impact(want < 1 ? 1 : want, a->m_prev, impulsive);
  *mult = fb_step_ramp(want, a->m_prev, a->m_max);
  a->m_prev = *mult;
  a->h_prev = *mult * a->h_grid;
  return FB_OK;
}
