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
#include "series.h"

int fb_kit_slot(int joint, int corner) {
  return corner == 0 ? joint : FB_PLANAR_SPEC_MAX_JOINTS + (FB_PLANAR_GUIDE_CORNERS - 1) * joint +
                                   corner - 1;
}

/* 1: joint j of m is a slider in its guide (a prismatic clearance joint) */
static int is_guide(const fb_planar *m, int j) { return m->joint[j].kind == FB_KIND_PRISMATIC; }

/* the contact slots of clearance joint j */
static int slots(const fb_planar *m, int j) { return is_guide(m, j) ? FB_PLANAR_GUIDE_CORNERS : 1; }

/* 1: cl's pins are found by a generic collider, not the exact pin in its
 * hole (kit.h's fb_kit_collider) */
static int generic(const fb_kit_clearance *cl) {
  return cl->collider.kind == FB_COLLIDER_FACETED || cl->collider.kind == FB_COLLIDER_CCD;
}

/* 1: clearance joint j's contact is the binding's own collider's (kit.h
 * collide): a pin in its hole, a generic collider */
static int own_collider(const fb_kit_binding *b, const fb_planar *m, const fb_kit_clearance *cl,
                        int j) {
  return b->collide && generic(cl) && !is_guide(m, j);
}

/* prismatic clearance joint j: its guide's size (a binding that builds
 * its own clearance, add_clearance, refuses there what it cannot build) */
static fb_status guide_ok(const fb_planar *m, const fb_kit_clearance *cl, int j, fb_diag *diag) {
  if (!cl->guide)
    return fb_diag_set(diag, FB_ERR_ARG, "clearance at prismatic joint '%s': the engine kit needs "
                       "the slider's size in its guide (fb_kit_clearance.guide)", m->joint[j].name);
  return fb_planar_guide_check(&cl->guide[j], diag);
}

fb_status fb_kit_pipe_new(fb_kit_pipe *p, const fb_kit_binding *b, const fb_planar *m,
                          const fb_kit_clearance *cl, fb_diag *diag) {
  memset(p, 0, sizeof *p);
  if (cl->mask && cl->friction != 0.0 && b->add_contact && !b->friction)
    return fb_diag_set(diag, FB_ERR_ARG, "[clearance] friction = %g: the %s engine's clearance "
                       "contact is a normal law only, frictionless (ODE's applies friction); "
                       "give friction = 0", cl->friction, b->engine);
  if (cl->mask && generic(cl) && !(b->collide && b->collided))
    return fb_diag_set(diag, FB_ERR_ARG, "[clearance] collider = %s: the %s engine's binding "
                       "finds a pin in its hole as the exact one only (it builds no collider of "
                       "its own); give collider = exact",
                       fb_collider_name(cl->collider.kind), b->engine);
  int guides = 0;
  for (int j = 0; j < m->njoints; j++) {
    if (!(cl->mask & (1u << j))) continue;
    if (j >= FB_PLANAR_SPEC_MAX_JOINTS || (!m->joint[j].clearance_ok && !is_guide(m, j)))
      return fb_diag_set(diag, FB_ERR_ARG, "clearance at joint '%s': the engine kit takes a pin "
                         "in a hole at a revolute joint, or a slider in its guide at a prismatic "
                         "one", m->joint[j].name);
    if (is_guide(m, j) && generic(cl))
      return fb_diag_set(diag, FB_ERR_ARG, "clearance at prismatic joint '%s' with [clearance] "
                         "collider = %s: a slider in its guide is its four corners against the "
                         "guide's flat walls, the kit's own contact; a ring of facets or a bore "
                         "of segments is a pin's hole; a slider takes the exact collider",
                         m->joint[j].name,
                         fb_collider_name(cl->collider.kind));
    if (is_guide(m, j)) {
      fb_status st = guide_ok(m, cl, j, diag);
      if (st != FB_OK) return st;
      guides++;
    }
    p->off[j] = 1;
  }
  const int nq = fb_planar_nq(m);
  p->q = calloc(2 * (size_t)nq, sizeof *p->q);
  if (!p->q) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  p->qd = p->q + nq;
  (void)guides;
  /* the constraint set without the clearance joints, factorised at most
   * once a step (fb_kit_pipe_contacts), for every joint's effective mass */
  return cl->mask ? fb_planar_cmass_new(&p->cm, m, p->off, diag) : FB_OK;
}

void fb_kit_pipe_free(fb_kit_pipe *p) {
  free(p->q);
  p->q = p->qd = NULL;
  fb_planar_cmass_free(p->cm);
  p->cm = NULL;
}

_Static_assert(FB_PLANAR_SPEC_MAX_BODIES + 1 <= 64, "fb_kit_pipe.rotated has a bit per body");

const double *fb_kit_pipe_rotation(fb_kit_pipe *p, int b) {
  if (!(p->rotated & (1ull << b))) {
    fb_planar_rotation(p->cs[b], p->q, b);
    p->rotated |= 1ull << b;
  }
  return p->cs[b];
}

void fb_kit_pipe_rotations(fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                           const fb_planar *m) {
  p->rotated = 0;
  if (!b->body_rotation) return;
  for (int k = 1; k < m->nbodies; k++) b->body_rotation(w, k - 1, p->cs[k]);
  p->rotated = ((1ull << m->nbodies) - 1) & ~1ull; /* the ground's: at first use */
}

/* joint j's penetration, rate and eccentricity at the state read, and its
 * contact into *c (depth <= 0: free flight) when the pin is off the
 * hole's centre (returns 1; 0: on it, no normal) */
static int geometry(fb_kit_contact *c, fb_kit_pipe *p, const fb_planar *m,
                    const fb_kit_clearance *cl, int j) {
  const fb_planar_joint *pj = &m->joint[j];
  double xp[2], vp[2], xh[2], vh[2];
  fb_planar_point_motion_at(xp, vp, p->q, p->qd, pj->body[0], pj->point[0],
                            fb_kit_pipe_rotation(p, pj->body[0]));
  fb_planar_point_motion_at(xh, vh, p->q, p->qd, pj->body[1], pj->point[1],
                            fb_kit_pipe_rotation(p, pj->body[1]));
  const double e[2] = {xp[0] - xh[0], xp[1] - xh[1]}, ecc = hypot(e[0], e[1]);
  const double delta = ecc - cl->radial_clearance;
  if (ecc > 0.0) p->rate[j] = (e[0] * (vp[0] - vh[0]) + e[1] * (vp[1] - vh[1])) / ecc;
  p->pen[j] = delta > 0.0 ? delta : 0.0;
  p->ecc[j][0] = e[0];
  p->ecc[j][1] = e[1];
  if (ecc == 0.0) return 0;
  const double n[2] = {e[0] / ecc, e[1] / ecc}, r = cl->pin_radius + cl->radial_clearance;
  *c = (fb_kit_contact){.pin = pj->body[0] - 1, .hole = pj->body[1] - 1,
                        .point = {xh[0] + r * n[0], xh[1] + r * n[1]}, .normal = {n[0], n[1]},
                        .depth = delta, .rate = n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]),
                        .mapping = cl->mapping, .centre = {{xp[0], xp[1]}, {xh[0], xh[1]}},
                        .ecc_rate = {vp[0] - vh[0], vp[1] - vh[1]}};
  if (pj->body[1] == FB_PLANAR_GROUND) c->hole = FB_KIT_GROUND;
  return 1;
}

/* slider joint j's corners at the state read (planar_guide.h); its
 * penetration the deepest corner's, its rate that corner's, its ecc the
 * slider's centre across the slide and its tilt (the reference's columns,
 * planar_dynamics.c) */
static void corners(fb_planar_guide_corner c[FB_PLANAR_GUIDE_CORNERS], fb_kit_pipe *p,
                    const fb_planar *m, const fb_kit_clearance *cl, int j) {
  double tilt;
  fb_planar_guide_corners(c, &tilt, m, j, &cl->guide[j], p->q, p->qd);
  int deep = 0;
  for (int r = 1; r < FB_PLANAR_GUIDE_CORNERS; r++)
    if (c[r].gap < c[deep].gap) deep = r;
  p->pen[j] = c[deep].gap < 0.0 ? -c[deep].gap : 0.0;
  p->rate[j] = c[deep].rate;
  p->ecc[j][0] = 0.25 * (c[2].gap + c[3].gap - c[0].gap - c[1].gap);
  p->ecc[j][1] = tilt;
}

void fb_kit_pipe_read(fb_kit_pipe *p, const fb_kit_binding *b, const void *w, const fb_planar *m,
                      const fb_kit_clearance *cl) {
  p->factored = p->closed = 0; /* the state is read anew */
  fb_kit_pipe_rotations(p, b, w, m);
  fb_planar_guide_corner gc[FB_PLANAR_GUIDE_CORNERS];
  for (int j = 0; j < m->njoints; j++) {
    if (p->off[j] && is_guide(m, j)) {
      corners(gc, p, m, cl, j);
    } else if (p->off[j]) { /* kept for the coming step's contacts: the same state */
      p->read[j] = (fb_kit_contact){0};
      p->read_off_centre[j] = (unsigned char)geometry(&p->read[j], p, m, cl, j);
    }
    /* a pin in the hole its binding's collider builds: its depth there */
    if (p->off[j] && b->penetration && own_collider(b, m, cl, j)) p->pen[j] = b->penetration(w, j);
  }
}

/* the row the law and mapping hand the engine (contact.h), kept in c for
 * the binding: its h omega_c noted (joint j's and cl's h_omega_max) and
 * added to the slot's contact phase *phase (a step without a row sets it
 * to 0); the matched mapping's aliasing
 * stop: a row whose damped frequency passes FB_MATCHED_ALIAS_BOUND per
 * step has lost its spring's meaning; FB_ERR_NUMERIC naming the largest
 * usable step, its omega_d h in cl->aliased_omega_d_h */
static fb_status note_row(fb_kit_contact *c, const char *joint, fb_kit_clearance *cl, int j,
                          double *phase, fb_diag *diag) {
  fb_contact_row row;
  c->has_row = 0;
  if (fb_contact_row_step(&row, &c->law, c->mapping, c->h, c->m_eff, 1, c->depth, c->rate, c->v0,
                          c->onset, c->persistence) != FB_OK) {
    *phase = 0.0; /* a step without a row ends the contact's phase */
    return FB_OK;
  }
  c->row = row; /* the binding's, so it maps the law once */
  c->has_row = 1;
  const double hw = fb_contact_h_omega(c->h, row.kp, c->m_eff);
  *phase += hw;
  fb_kit_joint_record *r = &cl->joint[j];
  cl->h_omega_max = fmax(cl->h_omega_max, hw);
  r->h_omega_max = fmax(r->h_omega_max, hw);
  if (r->contact_steps == 0 || row.erp > r->erp_max) r->erp_max = row.erp;
  if (r->contact_steps == 0 || row.cfm < r->cfm_min) r->cfm_min = row.cfm;
  if (!fb_mapping_is_matched(c->mapping)) return FB_OK;
  const double wdh = fb_contact_omega_d_h(c->h, row.kp, row.kd, c->m_eff);
  if (!fb_kit_aliased(c->mapping, wdh)) return FB_OK;
  cl->aliased_omega_d_h = wdh;
  cl->aliased_joint = j;
  return fb_kit_alias_diag(diag, wdh, joint, c->h);
}

/* a law the engine integrates explicitly (kit.h's explicit_law): h omega_c
 * with its secant stiffness at this depth on the contact's effective mass
 * noted (joint j's and cl's h_omega_max) */
static void note_secant(const fb_kit_contact *c, fb_kit_clearance *cl, int j) {
  double kp, kd, depth;
  fb_contact_linearize(&c->law, FB_MAPPING_SECANT, c->depth, c->rate, c->v0, &kp, &kd, &depth);
  const double hw = fb_contact_h_omega(c->h, kp, c->m_eff);
  cl->h_omega_max = fmax(cl->h_omega_max, hw);
  cl->joint[j].h_omega_max = fmax(cl->joint[j].h_omega_max, hw);
}

/* joint j of an engine's own relation (add_clearance): its episode from
 * the force of the step just taken, at onset the rate before that step */
static void native_episode(fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                           fb_kit_clearance *cl, int j) {
  const int in = b->contact_force(w, j) > 0.0, before = p->ep[j].impacts;
  const double rate = in && !p->ep[j].in_contact ? p->rate_before[j] : p->rate[j];
  fb_episode_update(&p->ep[j], in, rate, cl->impact_velocity_min);
  cl->impacts += p->ep[j].impacts - before;
  cl->joint[j].impacts += p->ep[j].impacts - before;
  cl->contact_steps += (size_t)in;
  cl->joint[j].contact_steps += (size_t)in;
  p->rate_before[j] = p->rate[j];
}

/* the masses [m_lo, m_hi] noted in the range [lo, hi] (count: the contact
 * steps before them) */
static void note_mass(double *lo, double *hi, size_t count, double m_lo, double m_hi) {
  if (count == 0 || m_lo < *lo) *lo = m_lo;
  if (count == 0 || m_hi > *hi) *hi = m_hi;
}

/* what the binding's own collider made of clearance joint j's contact
 * (slot k) in its add_contact: its rows noted as the kit notes its own
 * (note_row), the contact's phase, the matched mapping's aliasing stop */
static fb_status note_collided(fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                               const fb_planar *m, fb_kit_clearance *cl, int j, int k, double h,
                               fb_diag *diag) {
  fb_kit_rows o;
  b->collided(w, k, &o);
  fb_kit_joint_record *r = &cl->joint[j];
  p->phase[k] = o.h_omega_max > 0.0 ? p->phase[k] + o.h_omega_max : 0.0;
  if (o.rows == 0) return FB_OK;
  note_mass(&cl->m_eff_min, &cl->m_eff_max, cl->contact_steps, o.m_eff_min, o.m_eff_max);
  note_mass(&r->m_eff_min, &r->m_eff_max, r->contact_steps, o.m_eff_min, o.m_eff_max);
  if (r->contact_steps == 0 || o.erp_max > r->erp_max) r->erp_max = o.erp_max;
  if (r->contact_steps == 0 || o.cfm_min < r->cfm_min) r->cfm_min = o.cfm_min;
  cl->h_omega_max = fmax(cl->h_omega_max, o.h_omega_max);
  r->h_omega_max = fmax(r->h_omega_max, o.h_omega_max);
  cl->contact_steps += o.rows;
  r->contact_steps += o.rows;
  if (!fb_kit_aliased(cl->mapping, o.omega_d_h_max)) return FB_OK;
  cl->aliased_omega_d_h = o.omega_d_h_max;
  cl->aliased_joint = j;
  return fb_kit_alias_diag(diag, o.omega_d_h_max, m->joint[j].name, h);
}

/* a contact step of clearance joint record r (of cl) on effective mass
 * m_eff [kg]: counted, its mass in the ranges */
static void count_step(fb_kit_clearance *cl, fb_kit_joint_record *r, double m_eff) {
  note_mass(&cl->m_eff_min, &cl->m_eff_max, cl->contact_steps, m_eff, m_eff);
  note_mass(&r->m_eff_min, &r->m_eff_max, r->contact_steps, m_eff, m_eff);
  cl->contact_steps++;
  r->contact_steps++;
}

/* contact *c for the coming step of h: the effective mass me along its
 * normal (else the law's own mass), clearance joint j's law on it, the
 * episode's onset rate; its normal and point kept for slot k's reaction */
static void on_mass(fb_kit_pipe *p, const fb_kit_clearance *cl, int j, int k, fb_kit_contact *c,
                    double me, double h) {
  c->m_eff = isfinite(me) && me > 0.0 ? me : cl->joint[j].law.mass;
  if (!(c->m_alone > 0.0 && c->m_alone < c->m_eff)) c->m_alone = c->m_eff; /* a pin's */
  c->law = fb_contact_law_on_mass(&cl->joint[j].law, c->m_eff);
  c->v0 = p->ep[k].v0;
  c->h = h;
  c->friction = cl->friction;
  p->normal[k][0] = c->normal[0], p->normal[k][1] = c->normal[1];
  p->point[k][0] = c->point[0], p->point[k][1] = c->point[1];
}

/* contact slot k's episode (in: it presses), and when in, its contact
 * *c (its geometry filled; the effective mass me along its normal, else
 * the law's own mass) with clearance joint j's law on that mass, noted
 * and handed to b; the binding's own collider's contact (own) noted from
 * the rows it made; in free flight, to a binding that takes every step's
 * (kit.h's contact_always), a pin's contact off its hole's centre with
 * its effective mass (me > 0), neither noted nor counted */
static fb_status hand(fb_kit_pipe *p, const fb_kit_binding *b, void *w, const fb_planar *m,
                      fb_kit_clearance *cl, int j, int k, fb_kit_contact *c, int in, double me,
                      double h, int own, fb_diag *diag) {
  fb_kit_joint_record *r = &cl->joint[j];
  p->force[k] = p->omega_c[k] = 0.0;
  const int onset = in && !p->ep[k].in_contact, before = p->ep[k].impacts;
  fb_episode_update(&p->ep[k], in, in ? c->rate : 0.0, cl->impact_velocity_min);
  cl->impacts += p->ep[k].impacts - before;
  r->impacts += p->ep[k].impacts - before;
  if (!in) {
    p->phase[k] = 0.0;
    if (!(b->contact_always && isfinite(me) && me > 0.0 && !c->wall)) return FB_OK;
    on_mass(p, cl, j, k, c, me, h);
    c->onset = 0;
    c->persistence = 0.0;
    return b->add_contact(w, k, c, diag);
  }
  on_mass(p, cl, j, k, c, me, h);
  c->onset = onset;
  c->persistence = c->mapping == FB_MAPPING_MATCHED_STATIC && !p->rocking
                       ? fb_contact_persistence(p->phase[k])
                       : 0.0;
  c->mean_force = p->rocking;
  if (!b->contact_force) /* the law's force is the kit's figure for a binding without one */
    p->force[k] = fb_contact_force(&c->law, c->depth, c->rate, c->v0);
  fb_status st = FB_OK;
  if (own) { /* the rows are the collider's: noted from what it made */
    if ((st = b->add_contact(w, k, c, diag)) != FB_OK) return st;
    return note_collided(p, b, w, m, cl, j, k, h, diag);
  }
  if (!b->applied_force && (st = note_row(c, m->joint[j].name, cl, j, &p->phase[k], diag)) != FB_OK) {
    count_step(cl, r, c->m_eff); /* the refused row's step is in the stop's provenance, as its
                                    h omega_c is (run.c's under-resolved warning reads both) */
    return st;
  }
  if (p->rocking && c->has_row) { /* the matched row about the contact's mean force */
    p->omega_c[k] = sqrt(c->row.kp / c->m_eff);
    fb_contact_row_mean_force(&c->row, h, p->f_mean[k]);
  }
  if (b->applied_force && b->explicit_law) note_secant(c, cl, j);
  if (b->applied_force) { /* the contact's phase from the law's tangent stiffness (contact.h) */
    double kp, kd, depth;
    fb_contact_linearize(&c->law, FB_MAPPING_TANGENT, c->depth, c->rate, c->v0, &kp, &kd, &depth);
    p->phase[k] += fb_contact_h_omega(h, kp, c->m_eff);
  }
  if ((st = b->add_contact(w, k, c, diag)) != FB_OK) return st;
  count_step(cl, r, c->m_eff);
  return FB_OK;
}

/* the constraint set factorised at the state last read, once a step */
static fb_status factored(fb_kit_pipe *p, fb_diag *diag) {
  if (p->factored) return FB_OK;
  fb_status st = fb_planar_cmass_factor(p->cm, p->q, FB_EFFECTIVE_MASS_REG, diag);
  p->factored = st == FB_OK;
  return st;
}

/* clearance joint j's inverse-mass tensor w [1/kg] at the state last read:
 * the mechanism's closed form when the run has one (all four joints' at
 * once, once a step), else the factorised constraint set's */
static fb_status tensor(double w[2][2], fb_kit_pipe *p, const fb_planar *m,
                        const fb_kit_clearance *cl, int j, fb_diag *diag) {
  if (cl->mass_tensors && j < 4) {
    if (!p->closed) {
      for (int b = 0; b < m->nbodies; b++) fb_kit_pipe_rotation(p, b);
      fb_status st = cl->mass_tensors(p->w4, m, p->q, (const double(*)[2])p->cs, cl->mask, diag);
      if (st != FB_OK) return st;
      p->closed = 1;
    }
    memcpy(w, p->w4[j], sizeof p->w4[j]);
    return FB_OK;
  }
  fb_status st = factored(p, diag);
  if (st == FB_OK) fb_planar_cmass_tensor(p->cm, w, j, p->q);
  return st;
}

/* slider joint j's four corners, each a contact of its own slot: the
 * slider the pin, the guide the hole, the point on the wall under the
 * corner, the face's share of the effective mass (planar_guide.h) */
static fb_status guide_contacts(fb_kit_pipe *p, const fb_kit_binding *b, void *w,
                                const fb_planar *m, fb_kit_clearance *cl, int j, double h,
                                fb_diag *diag) {
  const fb_planar_joint *pj = &m->joint[j];
  fb_planar_guide_corner gc[FB_PLANAR_GUIDE_CORNERS];
  double mass[FB_PLANAR_GUIDE_CORNERS] = {0.0}, alone[FB_PLANAR_GUIDE_CORNERS] = {0.0};
  corners(gc, p, m, cl, j);
  if (p->pen[j] > 0.0) {
    fb_status st = factored(p, diag);
    if (st != FB_OK) return st;
    fb_planar_guide_masses(mass, alone, p->cm, m, j, gc, p->q);
  }
  for (int r = 0; r < FB_PLANAR_GUIDE_CORNERS; r++) {
    const double d = -gc[r].gap, *n = gc[r].normal;
    const double wall[2] = {gc[r].point[0] - d * n[0], gc[r].point[1] - d * n[1]};
    fb_kit_contact c = {.pin = pj->body[1] - 1, .hole = pj->body[0] - 1,
                        .point = {wall[0], wall[1]}, .normal = {n[0], n[1]}, .depth = d,
                        .rate = gc[r].rate, .mapping = cl->mapping, .m_alone = alone[r],
                        .wall = 1, .centre = {{gc[r].point[0], gc[r].point[1]}, {wall[0], wall[1]}},
                        .ecc_rate = {gc[r].rate * n[0], gc[r].rate * n[1]}};
    if (pj->body[0] == FB_PLANAR_GROUND) c.hole = FB_KIT_GROUND;
    fb_status st = hand(p, b, w, m, cl, j, fb_kit_slot(j, r), &c, d > 0.0, mass[r], h, 0, diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
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
    fb_status st = FB_OK;
    if (is_guide(m, j)) {
      if ((st = guide_contacts(p, b, w, m, cl, j, h, diag)) != FB_OK) return st;
      continue;
    }
    /* the pin's geometry at the state last read (fb_kit_pipe_read), which
     * no step has moved since */
    fb_kit_contact c = p->read[j];
    const int off_centre = p->read_off_centre[j];
    int in = off_centre && c.depth > 0.0;
    double me = 0.0; /* in free flight too for a binding that takes every step's */
    if (in || (off_centre && b->contact_always)) {
      if ((st = tensor(c.w_inv, p, m, cl, j, diag)) != FB_OK) return st;
      me = fb_effective_mass_along(c.w_inv, c.normal);
    }
    /* the binding's own collider: its contacts make the episode, and it
     * has one only where the exact penetration is positive (kit.h's
     * collide: the ring or bore lies outside the hole's circle) */
    const int own = own_collider(b, m, cl, j);
    if (in && own) in = b->collide(w, j, &c.rate) > 0;
    if ((st = hand(p, b, w, m, cl, j, j, &c, in, me, h, own, diag)) != FB_OK) return st;
  }
  return FB_OK;
}

void fb_kit_pipe_stepped(fb_kit_pipe *p, const fb_kit_binding *b, const void *w, double h) {
  if (!p->rocking) return;
  for (int k = 0; k < FB_KIT_SLOTS; k++) {
    const double f = b->contact_force ? b->contact_force(w, k) : p->force[k];
    p->f_mean[k] = p->omega_c[k] > 0.0 ? fb_contact_mean_force_step(p->f_mean[k], f, h,
                                                                     p->omega_c[k])
                                       : 0.0;
  }
}

fb_status fb_kit_pipe_step_joint(fb_step_joint *sj, int *impulsive, fb_kit_pipe *p,
                                 const fb_kit_binding *b, const fb_planar *m,
                                 const fb_kit_clearance *cl, int j, fb_diag *diag) {
  const double *e = p->ecc[j], ecc = hypot(e[0], e[1]);
  const double n[2] = {ecc > 0.0 ? e[0] / ecc : 1.0, ecc > 0.0 ? e[1] / ecc : 0.0};
  *sj = (fb_step_joint){.rule = (fb_persistent_rule)b->persistent_rule, .tau_load = INFINITY,
                        .delta = ecc - cl->radial_clearance, .ddot = ecc > 0.0 ? p->rate[j] : 0.0};
  double w[2][2];
  fb_status st = tensor(w, p, m, cl, j, diag);
  if (st != FB_OK) return st;
  const double me = fb_effective_mass_along(w, n);
  sj->m_eff = isfinite(me) && me > 0.0 ? me : cl->joint[j].law.mass;
  if (sj->delta > 0.0) {
    sj->persistence = fb_contact_persistence(p->phase[j]);
    if (b->contact_rows && cl->mapping == FB_MAPPING_MATCHED_STATIC && sj->persistence < 1.0)
      *impulsive = 1;
  }
  if (p->rocking) { /* the rocking along the wall: the effective mass along the tangent */
    const double t[2] = {-n[1], n[0]}, mt = fb_effective_mass_along(w, t);
    sj->m_t = isfinite(mt) && mt > 0.0 ? mt : cl->joint[j].law.mass;
    sj->ecc = ecc;
  }
  if (sj->rule == FB_PERSIST_LOAD_SCHEDULE && cl->load && m->drive >= 0) {
    int from, to;
    fb_planar_drive_bodies(m, &from, &to);
    fb_load_scale_at(cl->load, j, fb_planar_angle(p->q, to) - fb_planar_angle(p->q, from),
                     &sj->tau_load, &sj->load_force);
  }
  return FB_OK;
}

double fb_kit_pipe_force(const fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                         const fb_planar *m, int j) {
  double f = 0.0;
  /* an engine's own relation (add_clearance, no add_contact) reports its
   * joint's whole force at the joint's index */
  const int n = b->add_clearance && !b->add_contact ? 1 : slots(m, j);
  for (int r = 0; r < n; r++) {
    const int k = fb_kit_slot(j, r);
    f += b->contact_force ? b->contact_force(w, k) : p->force[k];
  }
  return f;
}

void fb_kit_pipe_reaction(const fb_kit_pipe *p, const fb_kit_binding *b, const void *w,
                          const fb_planar *m, int j, double out[3]) {
  if (b->add_clearance && !b->add_contact) { /* the engine's own relation: its reaction */
    out[0] = out[1] = out[2] = 0.0;
    b->clearance_reaction(w, j, out);
    return;
  }
  const fb_planar_joint *pj = &m->joint[j];
  /* a revolute joint's pin is on body[0], its hole on body[1]: the force on
   * body[1] is minus the pin's; a guide's corners push the slider, its
   * body[1], as the pin (kit.h) */
  const int guide = is_guide(m, j), n = guide ? FB_PLANAR_GUIDE_CORNERS : 1;
  const double sign = guide ? 1.0 : -1.0;
  double at[2] = {0.0, 0.0};
  if (guide) fb_planar_point(at, m, p->q, pj->body[1] == FB_PLANAR_GROUND ? pj->body[0] : pj->body[1],
                             pj->point[pj->body[1] == FB_PLANAR_GROUND ? 0 : 1]);
  out[0] = out[1] = out[2] = 0.0;
  for (int r = 0; r < n; r++) {
    const int k = fb_kit_slot(j, r);
    double f[2]; /* on the pin's body */
    if (b->contact_force_vec) {
      b->contact_force_vec(w, k, f);
    } else {
      const double fn = b->contact_force ? b->contact_force(w, k) : p->force[k];
      f[0] = -fn * p->normal[k][0], f[1] = -fn * p->normal[k][1];
    }
    out[0] += sign * f[0];
    out[1] += sign * f[1];
    if (guide) /* at the wall's point under the corner */
      out[2] += (p->point[k][0] - at[0]) * f[1] - (p->point[k][1] - at[1]) * f[0];
  }
}

int fb_kit_pipe_state(const fb_kit_pipe *p, const fb_planar *m, int j) {
  if (!is_guide(m, j)) return p->ep[j].state;
  int state = FB_STATE_FREE;
  for (int r = 0; r < FB_PLANAR_GUIDE_CORNERS; r++) {
    const fb_episode *e = &p->ep[fb_kit_slot(j, r)];
    if (e->in_contact && (state == FB_STATE_FREE || e->state == FB_STATE_IMPACT)) state = e->state;
  }
  return state;
}
