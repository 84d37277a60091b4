/* The exact pin-in-hole contact of the ODE world (ode_world.h, "Clearance
 * joints"): the eccentricity from the two bodies, the penetration and its
 * rate, the law mapped to one soft contact row (ode_contact.h) at the
 * effective mass along the normal, the drift correction of the
 * matched-static row, the contact joint on the hole wall; and what the other
 * colliders (ode_colliders.c) are handed: the step's effective mass and
 * law. Also the mechanism's configuration for the effective mass and the
 * ODE probe of it. */
#include <math.h>
#include <string.h>

#include "contact_mass.h"
#include "ode_contact.h"
#include "ode_world_internal.h"

/* the effective mass of clearance joint j along unit n (pin minus hole
 * direction) [kg], from this step's inverse-mass tensor (effective_mass.h),
 * computed at the step's first call; the law's mass if that fails */
double ode_step_effective_mass(fb_ode_world *s, int j, const double n[2]) {
  if (!s->w_valid) {
    fb_mechanism m;
    fb_ode_world_mechanism(s, &m);
    if (fb_effective_mass_tensor(s->w_inv, &m, NULL) != FB_OK) return s->def.law[j].mass;
    s->w_valid = 1;
  }
  const double me = fb_effective_mass_along(s->w_inv[j], n);
  return isfinite(me) && me > 0.0 ? me : s->def.law[j].mass;
}

/* the joint's law at this step: the restitution law's damper acts on the
 * effective mass along the normal (c = 2 zeta sqrt(p m_eff)), so the
 * achieved restitution is the one asked */
fb_contact_law ode_step_law(const fb_contact_law *law, double m_eff) {
  return fb_contact_law_on_mass(law, m_eff); /* contact_mass.h's rule */
}

/* eccentricity, penetration rate and hole-wall point of clearance joint c */
void ode_clearance_geometry(const ode_clearance *c, double e[2], double *ddot_num, double ev[2]) {
  dVector3 p, q, vp, vq = {0, 0, 0, 0};
  dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], p);
  dBodyGetRelPointVel(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], vp);
  if (c->hole) {
    dBodyGetRelPointPos(c->hole, c->hole_local[0], c->hole_local[1], c->hole_local[2], q);
    dBodyGetRelPointVel(c->hole, c->hole_local[0], c->hole_local[1], c->hole_local[2], vq);
  } else {
    q[0] = c->hole_local[0];
    q[1] = c->hole_local[1];
  }
  e[0] = p[0] - q[0];
  e[1] = p[1] - q[1];
  ev[0] = vp[0] - vq[0];
  ev[1] = vp[1] - vq[1];
  *ddot_num = e[0] * ev[0] + e[1] * ev[1]; /* |e| times the rate of |e| */
}

/* what ODE's position update adds to a body point's displacement over a
 * step beyond the linear h (v + w x r) a contact row's Jacobian sees: ODE
 * turns the body by theta = 2 atan(h w / 2) (its quaternion update,
 * normalised), so the point at r from the centre of mass moves by
 * (cos theta - 1) r + (sin theta - h w) z x r more [m] (w taken at the
 * start of the step) */
static void point_drift(dBodyID b, const double local[3], double h, double out[2]) {
  out[0] = out[1] = 0.0;
  if (!b) return; /* the ground */
  dVector3 p;
  dBodyGetRelPointPos(b, local[0], local[1], local[2], p);
  const dReal *x = dBodyGetPosition(b);
  const double r[2] = {p[0] - x[0], p[1] - x[1]};
  const double w = dBodyGetAngularVel(b)[2];
  const double th = 2.0 * atan(0.5 * h * w);
  const double cm1 = -2.0 * sin(0.5 * th) * sin(0.5 * th), sw = sin(th) - h * w;
  out[0] = cm1 * r[0] - sw * r[1];
  out[1] = cm1 * r[1] + sw * r[0];
}

/* The change of the penetration |e| - c over the coming step that a contact
 * row on the normal n does not see [m]: a row constrains the normal rate
 * n . de/dt at the start of the step (J v_{n+1}), while the penetration
 * also moves by the rotation's second-order terms of both bodies' points
 * (point_drift) and by the curvature of the circle |e| = const under the
 * tangential rate, h^2 |de/dt_t|^2 / (2 |e|). In continuous contact the
 * row then holds a steady rate u = -drift / h, and its damper b turns that
 * into a force error b drift / h: on the paper case at 1000 rpm with the
 * heavily damped restitution law (cr 0.14, zeta 0.99) that is +10 % of the
 * persistent-contact penetration with a statically exact row. */
static double step_drift(const ode_clearance *c, const double n[2], const double ev[2], double ecc,
                         double h) {
  double dp[2], dq[2];
  point_drift(c->pin, c->pin_local, h, dp);
  point_drift(c->hole, c->hole_local, h, dq);
  return fb_contact_step_drift(n, dp, dq, ev, ecc, h);
}

/* penetration of clearance joint c now [m]: into the faceted bore for the
 * libccd collider, |e| - c otherwise; 0 when free */
double ode_clearance_penetration(const fb_ode_world *s, const ode_clearance *c) {
  if (c->gen.bore) {
    double p[2];
    ode_collider_pin_in_hole(&c->gen, p);
    return fb_ccd_bore_depth(c->gen.bore, p);
  }
  double e[2], ev[2], num;
  ode_clearance_geometry(c, e, &num, ev);
  const double pen = hypot(e[0], e[1]) - s->def.radial_clearance;
  return pen > 0.0 ? pen : 0.0;
}

/* exact collider: creates the contact joint of clearance joint j for this
 * step, if in contact */
void ode_exact_contact(fb_ode_world *s, int j) {
  ode_clearance *c = &s->cl[j];
  const fb_model_scene *d = &s->def;
  double e[2], ev[2], num;
  ode_clearance_geometry(c, e, &num, ev);
  const double ecc = hypot(e[0], e[1]);
  const double delta = ecc - d->radial_clearance;
  c->cj = 0;
  if (!(delta > 0.0) || ecc == 0.0) {
    fb_episode_update(&c->ep, 0, 0.0, d->impact_velocity_min);
    return;
  }
  const double n[2] = {e[0] / ecc, e[1] / ecc};
  const double ddot = num / ecc;
  const int onset = !c->ep.in_contact;
  fb_episode_update(&c->ep, 1, ddot, d->impact_velocity_min);
  const double m_eff = ode_step_effective_mass(s, j, n);
  const fb_contact_law law = ode_step_law(&d->law[j], m_eff);
  dContact ct;
  memset(&ct, 0, sizeof ct);
  fb_contact_row used;
  if (!fb_ode_soft_contact(&ct, &law, d->mapping, s->h_now, m_eff, 1, delta, ddot, c->ep.v0,
                           onset, c->persistence, d->friction, &used))
    return;
  c->omega_c = sqrt(used.kp / m_eff);
  if (s->ad.rocking) {
    /* the matched row throughout, its static depth the law's (contact.h) */
    fb_contact_row_mean_force(&used, s->h_now, c->f_mean);
    ct.geom.depth = used.depth;
  } else if (d->mapping == FB_MAPPING_MATCHED_STATIC && used.erp > 0.0) {
    /* the row's lambda = a d_n + b u: handing it d_n + drift / ERP makes its
     * b act on the penetration's true rate u + drift / h (contact.h) */
    used.depth += step_drift(c, n, ev, ecc, s->h_now) / used.erp;
    ct.geom.depth = used.depth;
  }
  c->step_share = used.step_share;
  ode_note_row(&c->prov, &c->step_hw, &c->step_wdh, &used, 1.0, m_eff, s->h_now);
  /* hole centre + R_hole n, on the hole wall */
  const double r_hole = d->pin_radius + d->radial_clearance;
  dVector3 q;
  if (c->hole)
    dBodyGetRelPointPos(c->hole, c->hole_local[0], c->hole_local[1], c->hole_local[2], q);
  else
    q[0] = c->hole_local[0], q[1] = c->hole_local[1];
  ct.geom.pos[0] = q[0] + r_hole * n[0];
  ct.geom.pos[1] = q[1] + r_hole * n[1];
  ct.geom.pos[2] = 0.0;
  ct.geom.normal[0] = -n[0]; /* into the pin: moving it along -n removes the depth */
  ct.geom.normal[1] = -n[1];
  ct.geom.normal[2] = 0.0;
  c->cj = dJointCreateContact(s->world, s->contacts, &ct);
  dJointAttach(c->cj, c->pin, c->hole);
  dJointSetFeedback(c->cj, &c->fb);
}

void fb_ode_world_mechanism(const fb_ode_world *s, fb_mechanism *out) {
  memset(out, 0, sizeof *out);
  for (int i = 0; i < 3; i++) {
    const dReal *p = dBodyGetPosition(s->body[i]);
    out->mass[i] = s->def.link[i].mass;
    out->inertia[i] = s->def.link[i].inertia;
    out->com[i][0] = p[0];
    out->com[i][1] = p[1];
  }
  for (int j = 0; j < 4; j++) {
    dVector3 q;
    if (s->hinge[j]) {
      dJointGetHingeAnchor(s->hinge[j], q);
    } else if (j == s->slider_joint) {
      /* the guide: the slider's point on it, its centre of mass (the hole centre) */
      const dReal *p = dBodyGetPosition(s->body[FB_FOLLOWER]);
      q[0] = p[0];
      q[1] = p[1];
      out->prismatic_mask |= 1 << j;
    } else {
      const ode_clearance *c = &s->cl[j];
      dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], q);
    }
    out->joint[j][0] = q[0];
    out->joint[j][1] = q[1];
  }
  out->clearance_mask = s->def.clearance_mask;
  out->crank_driven = 1;
}

/* penetration rate n . (v_pin - v_hole) at the pin centre of clearance joint c */
static double probe_rate(const ode_clearance *c, const double n[2]) {
  dVector3 p, vp, vh = {0, 0, 0, 0};
  dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], p);
  dBodyGetRelPointVel(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], vp);
  if (c->hole) dBodyGetPointVel(c->hole, p[0], p[1], p[2], vh);
  return n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]);
}

fb_status fb_ode_world_probe_inverse_mass(fb_ode_world *s, int j, const double n[2], double force,
                                      double *inv_mass, fb_diag *diag) {
  if (j < 0 || j > 3 || !(s->def.clearance_mask & (1 << j)) || !(force > 0.0))
    return fb_diag_set(diag, FB_ERR_ARG,
                       "probe: joint %d must be a clearance joint and force %g N positive", j,
                       force);
  const ode_clearance *c = &s->cl[j];
  dReal pos[3][3], quat[3][4], lin[3][3], ang[3][3];
  for (int i = 0; i < 3; i++) {
    memcpy(pos[i], dBodyGetPosition(s->body[i]), sizeof pos[i]);
    memcpy(quat[i], dBodyGetQuaternion(s->body[i]), sizeof quat[i]);
    memcpy(lin[i], dBodyGetLinearVel(s->body[i]), sizeof lin[i]);
    memcpy(ang[i], dBodyGetAngularVel(s->body[i]), sizeof ang[i]);
  }
  double rate[2];
  int ok = 1;
  for (int trial = 0; trial < 2 && ok; trial++) {
    for (int i = 0; i < 3; i++) {
      dBodySetPosition(s->body[i], pos[i][0], pos[i][1], pos[i][2]);
      dBodySetQuaternion(s->body[i], quat[i]);
      dBodySetLinearVel(s->body[i], lin[i][0], lin[i][1], lin[i][2]);
      dBodySetAngularVel(s->body[i], ang[i][0], ang[i][1], ang[i][2]);
    }
    if (trial == 1) {
      dVector3 p;
      dBodyGetRelPointPos(c->pin, c->pin_local[0], c->pin_local[1], c->pin_local[2], p);
      dBodyAddForceAtPos(c->pin, -force * n[0], -force * n[1], 0.0, p[0], p[1], p[2]);
      if (c->hole) dBodyAddForceAtPos(c->hole, force * n[0], force * n[1], 0.0, p[0], p[1], p[2]);
    }
    ok = dWorldStep(s->world, s->def.solver.h);
    rate[trial] = probe_rate(c, n);
  }
  for (int i = 0; i < 3; i++) {
    dBodySetPosition(s->body[i], pos[i][0], pos[i][1], pos[i][2]);
    dBodySetQuaternion(s->body[i], quat[i]);
    dBodySetLinearVel(s->body[i], lin[i][0], lin[i][1], lin[i][2]);
    dBodySetAngularVel(s->body[i], ang[i][0], ang[i][1], ang[i][2]);
  }
  if (!ok) return fb_diag_set(diag, FB_ERR_NOMEM, "probe: ODE could not step");
  *inv_mass = (rate[0] - rate[1]) / (s->def.solver.h * force);
  return FB_OK;
}
