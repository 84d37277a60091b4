/* The kit's clearance pipeline (kit_contact.h). */
#include "kit_contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_mass.h"
#include "effective_mass.h"
#include "kit_record.h"
#include "planar_constraints.h"
#include "planar_mass.h"

fb_status fb_kit_pipe_new(fb_kit_pipe *p, const fb_planar *m, const fb_kit_clearance *cl,
                          fb_diag *diag) {
  memset(p, 0, sizeof *p);
  for (int j = 0; j < m->njoints; j++) {
    if (!(cl->mask & (1u << j))) continue;
    const int guided = m->joint[j].kind == FB_KIND_PRISMATIC && cl->guide; /* its corners */
    if (j >= FB_PLANAR_SPEC_MAX_JOINTS || !(m->joint[j].clearance_ok || guided))
      return fb_diag_set(diag, FB_ERR_ARG, "clearance at joint '%s': the engine kit takes a pin "
                         "in a hole at a revolute joint only", m->joint[j].name);
    p->off[j] = 1;
  }
  const int nq = fb_planar_nq(m);
  p->q = calloc(3 * (size_t)nq, sizeof *p->q); /* q, qd, a guide's scratch forces */
  if (!p->q) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  p->qd = p->q + nq;
  return FB_OK;
}

void fb_kit_pipe_free(fb_kit_pipe *p) {
  free(p->q);
  p->q = p->qd = NULL;
}

/* the coordinates now, from the engine */
static void read_state(fb_kit_pipe *p, const fb_kit_binding *b, const void *w, const fb_planar *m) {
  for (int k = 0; k < m->nbodies - 1; k++) b->body_state(w, k, p->q + 3 * k, p->qd + 3 * k);
}

/* prismatic joint j's slider in its guide (an engine's own relation): the
 * deepest corner's penetration and its rate (planar_guide.h's corners; no
 * contact handed: returns 0) */
static int guide_geometry(fb_kit_pipe *p, const fb_planar *m, const fb_kit_clearance *cl, int j) {
  const fb_contact_law none = {.kind = FB_LAW_LINEAR, .exponent = 1.0}; /* no force: geometry */
  fb_planar_guide_state g;
  fb_planar_guide_contact(p->qd + fb_planar_nq(m), &g, NULL, m, j, &cl->guide[j], &none, 0.0,
                          p->q, p->qd);
  int deep = 0;
  for (int c = 1; c < FB_PLANAR_GUIDE_CORNERS; c++)
    if (g.gap[c] < g.gap[deep]) deep = c;
  p->pen[j] = g.gap[deep] < 0.0 ? -g.gap[deep] : 0.0;
  p->rate[j] = g.rate[deep];
  p->ecc[j][0] = p->ecc[j][1] = 0.0;
  return 0;
}

/* joint j's contact into *c when its pin presses into the hole (returns 1) */
static int geometry(fb_kit_contact *c, fb_kit_pipe *p, const fb_planar *m,
                    const fb_kit_clearance *cl, int j) {
  const fb_planar_joint *pj = &m->joint[j];
  if (pj->kind == FB_KIND_PRISMATIC) return guide_geometry(p, m, cl, j);
  double xp[2], vp[2], xh[2], vh[2];
  fb_planar_point(xp, m, p->q, pj->body[0], pj->point[0]);
  fb_planar_point_velocity(vp, m, p->q, p->qd, pj->body[0], pj->point[0]);
  fb_planar_point(xh, m, p->q, pj->body[1], pj->point[1]);
  fb_planar_point_velocity(vh, m, p->q, p->qd, pj->body[1], pj->point[1]);
  const double e[2] = {xp[0] - xh[0], xp[1] - xh[1]}, ecc = hypot(e[0], e[1]);
  const double delta = ecc - cl->radial_clearance;
  if (ecc > 0.0) p->rate[j] = (e[0] * (vp[0] - vh[0]) + e[1] * (vp[1] - vh[1])) / ecc;
  p->pen[j] = delta > 0.0 ? delta : 0.0;
  p->ecc[j][0] = e[0];
  p->ecc[j][1] = e[1];
  if (!(delta > 0.0) || ecc == 0.0) return 0;
  const double n[2] = {e[0] / ecc, e[1] / ecc}, r = cl->pin_radius + cl->radial_clearance;
  *c = (fb_kit_contact){.pin = pj->body[0] - 1, .hole = pj->body[1] - 1,
                        .point = {xh[0] + r * n[0], xh[1] + r * n[1]}, .normal = {n[0], n[1]},
                        .depth = delta, .rate = n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]),
                        .mapping = cl->mapping};
  if (pj->body[1] == FB_PLANAR_GROUND) c->hole = FB_KIT_GROUND;
  return 1;
}

double fb_kit_pipe_read(fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                        const fb_planar *m, const fb_kit_clearance *cl) {
  read_state(p, b, w, m);
  fb_kit_contact c;
  for (int j = 0; j < m->njoints; j++)
    if (p->off[j]) geometry(&c, p, m, cl, j);
  return p->pen[cl->joint];
}

/* the row the law and mapping hand the engine (contact.h): its h omega_c
 * noted (cl->h_omega_max); the matched mapping's aliasing stop: a row
 * whose damped frequency passes FB_MATCHED_ALIAS_BOUND per step has lost
 * its spring's meaning; FB_ERR_NUMERIC naming the largest usable step,
 * its omega_d h in cl->aliased_omega_d_h */
static fb_status note_row(const fb_kit_contact *c, const char *joint, fb_kit_clearance *cl,
                          fb_diag *diag) {
  fb_contact_row row;
  if (fb_contact_row_step(&row, &c->law, c->mapping, c->h, c->m_eff, 1, c->depth, c->rate, c->v0,
                          c->onset, 0.0) != FB_OK)
    return FB_OK;
  cl->h_omega_max = fmax(cl->h_omega_max, fb_contact_h_omega(c->h, row.kp, c->m_eff));
  if (!fb_mapping_is_matched(c->mapping)) return FB_OK;
  const double wdh = fb_contact_omega_d_h(c->h, row.kp, row.kd, c->m_eff);
  if (!fb_kit_aliased(c->mapping, wdh)) return FB_OK;
  cl->aliased_omega_d_h = wdh;
  return fb_kit_alias_diag(diag, wdh, joint, c->h);
}

/* joint j of an engine's own relation (add_clearance): its episode from
 * the force of the step just taken, at onset the rate before that step */
static void native_episode(fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                           fb_kit_clearance *cl, int j) {
  const int in = b->contact_force(w, j) > 0.0, before = p->ep[j].impacts;
  const double rate = in && !p->ep[j].in_contact ? p->rate_before[j] : p->rate[j];
  fb_episode_update(&p->ep[j], in, rate, cl->impact_velocity_min);
  cl->impacts += p->ep[j].impacts - before;
  cl->contact_steps += (size_t)in;
  p->rate_before[j] = p->rate[j];
}

fb_status fb_kit_pipe_contacts(fb_kit_pipe *p, const fb_kit_binding *b, void *w,
                               const fb_planar *m, fb_kit_clearance *cl, double h,
                               fb_diag *diag) {
  for (int j = 0; j < m->njoints; j++) {
    if (!p->off[j]) continue;
    if (b->add_clearance && !b->add_contact) { /* the engine's own relation */
      native_episode(p, b, w, cl, j);
      continue;
    }
    fb_kit_contact c;
    p->force[j] = 0.0;
    const int in = geometry(&c, p, m, cl, j);
    const int onset = in && !p->ep[j].in_contact, before = p->ep[j].impacts;
    fb_episode_update(&p->ep[j], in, in ? c.rate : 0.0, cl->impact_velocity_min);
    cl->impacts += p->ep[j].impacts - before;
    if (!in) continue;
    double wi[2][2];
    fb_status st = fb_planar_effective_mass_tensor(wi, m, p->q, p->off, j, diag);
    if (st != FB_OK) return st;
    const double me = fb_effective_mass_along(wi, c.normal);
    c.m_eff = isfinite(me) && me > 0.0 ? me : cl->law.mass;
    c.law = fb_contact_law_on_mass(&cl->law, c.m_eff);
    c.v0 = p->ep[j].v0;
    c.onset = onset;
    c.h = h;
    p->force[j] = fb_contact_force(&c.law, c.depth, c.rate, c.v0);
    if (!b->applied_force && (st = note_row(&c, m->joint[j].name, cl, diag)) != FB_OK) return st;
    if ((st = b->add_contact(w, j, &c, diag)) != FB_OK) return st;
    if (cl->contact_steps == 0 || c.m_eff < cl->m_eff_min) cl->m_eff_min = c.m_eff;
    if (cl->contact_steps == 0 || c.m_eff > cl->m_eff_max) cl->m_eff_max = c.m_eff;
    cl->contact_steps++;
  }
  return FB_OK;
}

double fb_kit_pipe_force(const fb_kit_pipe *p, const fb_kit_binding *b, const void *w, int k) {
  return b->contact_force ? b->contact_force(w, k) : p->force[k];
}
