/* What the ODE world (ode_world.h) gives after a step: the sample (angles,
 * velocities, accelerations and the contact columns, interpolated inside an
 * adaptive step), the penetration and the hinge drift, the joint reactions
 * from ODE's joint feedback, the impact and collider counts, the stop and
 * the contact provenance. */
#include <math.h>

#include "kit_record.h"
#include "ode_world_internal.h"

void fb_ode_world_sample(const fb_ode_world *s, fb_sample *x) {
  fb_kit_sample_bodies(x, (double)s->steps * s->def.solver.h, s->angle, s->omega_prev, s->alpha);
  if (s->ad.on && s->ad.k < s->ad.mc) {
    /* inside an ODE step: angles and omega linear, alpha the step's */
    const double f = (double)s->ad.k / (double)s->ad.mc;
    double *ang[3] = {&x->crank_angle, &x->coupler_angle, &x->follower_angle};
    for (int i = 0; i < 3; i++) *ang[i] = s->ad.ang0[i] + f * (s->ad.ang1[i] - s->ad.ang0[i]);
    x->coupler_omega = s->ad.w0[FB_COUPLER] + f * (s->ad.w1[FB_COUPLER] - s->ad.w0[FB_COUPLER]);
    x->follower_omega =
        s->ad.w0[FB_FOLLOWER] + f * (s->ad.w1[FB_FOLLOWER] - s->ad.w0[FB_FOLLOWER]);
  }
  for (int j = 0; j < 4; j++) {
    for (int q = 0; q < FB_CONTACT_COLS; q++) x->contact[j][q] = 0.0;
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const ode_clearance *c = &s->cl[j];
    if (s->ad.on && s->ad.k < s->ad.mc) { /* inside an ODE step: interpolated */
      const double f = (double)s->ad.k / (double)s->ad.mc;
      fb_kit_sample_contact(x->contact[j], c->force,
                            s->ad.pen0[j] + f * (s->ad.pen1[j] - s->ad.pen0[j]),
                            s->ad.ex0[j] + f * (s->ad.ex1[j] - s->ad.ex0[j]),
                            s->ad.ey0[j] + f * (s->ad.ey1[j] - s->ad.ey0[j]), &c->ep);
      continue;
    }
    double e[2], ev[2], num;
    ode_clearance_geometry(c, e, &num, ev);
    fb_kit_sample_contact(x->contact[j], c->force, ode_clearance_penetration(s, c), e[0], e[1],
                          &c->ep);
  }
}

double ode_penetration_now(const fb_ode_world *s, int *joint) {
  double worst = 0.0;
  *joint = -1;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const double pen = ode_clearance_penetration(s, &s->cl[j]);
    if (*joint < 0 || pen > worst) {
      worst = pen;
      *joint = j;
    }
  }
  return worst;
}

void fb_ode_world_ccd_calls(const fb_ode_world *s, unsigned long *calls, unsigned long *contacts) {
  *calls = *contacts = 0;
  for (int j = 0; j < 4; j++) {
    const fb_ccd_bore *b = s->cl[j].gen.bore;
    if (!b) continue;
    *calls += fb_ccd_bore_calls(b);
    *contacts += fb_ccd_bore_contacts(b);
  }
}

int fb_ode_world_impacts(const fb_ode_world *s, int j) { return s->cl[j].ep.impacts; }

void fb_ode_world_stopped(const fb_ode_world *s, fb_stop *out) {
  *out = s->stop;
  out->engine = "ode";
  if (out->kind != FB_STOP_ALIASED) out->joint = -1;
}

void fb_ode_world_provenance(const fb_ode_world *s, int j, fb_contact_provenance *out) {
  *out = s->cl[j].prov;
  if (out->contact_steps == 0)
    out->mass_eff_min = out->mass_eff_max = out->erp_max = out->cfm_min = out->h_omega_max = NAN;
}

double ode_joint_drift_now(const fb_ode_world *s) {
  double worst = 0.0;
  for (int j = 0; j < 4; j++) {
    if (!s->hinge[j]) continue;
    dVector3 p1, p2;
    dJointGetHingeAnchor(s->hinge[j], p1);
    dJointGetHingeAnchor2(s->hinge[j], p2);
    double d = sqrt((p1[0] - p2[0]) * (p1[0] - p2[0]) + (p1[1] - p2[1]) * (p1[1] - p2[1]) +
                    (p1[2] - p2[2]) * (p1[2] - p2[2]));
    if (d > worst) worst = d;
  }
  if (s->slider) {
    /* the guide: the slider's distance from the line it started on */
    const dReal *p = dBodyGetPosition(s->body[FB_FOLLOWER]);
    const double d = hypot(p[1] - s->guide_y, p[2]);
    if (d > worst) worst = d;
  }
  return worst;
}

/* inside an adaptive ODE step the bodies rest at its end: the values of
 * its end, kept when it was taken */
double fb_ode_world_joint_drift(const fb_ode_world *s) {
  return s->ad.on ? s->ad.drift_end : ode_joint_drift_now(s);
}

double fb_ode_world_penetration(const fb_ode_world *s, int *joint) {
  if (!s->ad.on) return ode_penetration_now(s, joint);
  *joint = s->ad.pen_joint_end;
  return s->ad.pen_end;
}

void fb_ode_world_reactions(const fb_ode_world *s, double force[4][2], double *drive_torque) {
  if (s->steps == 0) {
    for (int j = 0; j < 4; j++) force[j][0] = force[j][1] = 0.0;
    *drive_torque = 0.0;
    return;
  }
  /* A: on the crank (body 1); B: on the coupler (body 2); C: on the follower
   * (body 2); D: on the follower (body 1) */
  const int on_body2[4] = {0, 1, 1, 0};
  for (int j = 0; j < 4; j++) {
    if (j == s->slider_joint) {
      /* the guide (slider_crank_invdyn.h): the force on the ground from the
       * slider, minus the slider joint's force on the slider (body 1),
       * (0, -N) with N the guide's normal force along +y */
      force[j][0] = -s->feedback[j].f1[0];
      force[j][1] = -s->feedback[j].f1[1];
      continue;
    }
    if (!s->hinge[j]) {
      /* a clearance joint: the contact force; its pin is on body 1 (the
       * crank at A and B, the coupler at C, the follower at D) */
      const double sign = on_body2[j] ? -1.0 : 1.0;
      force[j][0] = sign * s->cl[j].force_pin[0];
      force[j][1] = sign * s->cl[j].force_pin[1];
      continue;
    }
    const dReal *f = on_body2[j] ? s->feedback[j].f2 : s->feedback[j].f1;
    force[j][0] = f[0];
    force[j][1] = f[1];
  }
  /* ODE's torque is about the crank's centre of mass; move it to the pivot */
  const double r[2] = {-s->crank_com_before[0], -s->crank_com_before[1]}; /* A - G */
  *drive_torque = s->hinge[0] ? s->feedback[0].t1[2] - (r[0] * force[0][1] - r[1] * force[0][0])
                              : 0.0;
}

size_t fb_ode_world_steps(const fb_ode_world *s) { return s->steps; }
