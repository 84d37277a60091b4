/* One step of the ODE world (ode_world.h): each clearance joint's contact
 * rows from its collider, the aliasing stop, dWorldStep or dWorldQuickStep
 * under ODE's fatal-error escape (ode_env.h), the contact forces the step
 * left and the bodies' angles and accelerations; and the adaptive step
 * ([solver] h_s = adaptive, step_control.h): its size, the velocities
 * carried across a change of step, the samples inside a step. */
#include <math.h>
#include <stdio.h>

#include "kit_record.h"
#include "ode_env.h"
#include "ode_world_internal.h"
#include "step_control.h"

/* the hand-built world's effective mass and row record for a generic
 * collider's rows (ode_colliders.h): clearance joint j of world s */
typedef struct {
  fb_ode_world *s;
  int j;
} generic_user;

static double generic_mass(void *user, const double n[2]) {
  const generic_user *u = user;
  return ode_step_effective_mass(u->s, u->j, n);
}

static void generic_note(void *user, const fb_contact_row *row, double share, double mass) {
  const generic_user *u = user;
  ode_clearance *c = &u->s->cl[u->j];
  ode_note_row(&c->prov, &c->step_hw, &c->step_wdh, row, share, mass, u->s->def.solver.h);
}

/* the faceted or libccd collider's contact rows of clearance joint j for
 * this step: its hits, the episode they make (the lead hit's rate), the
 * rows on the episode's onset rate */
static void generic_contacts(fb_ode_world *s, int j) {
  ode_clearance *c = &s->cl[j];
  const fb_model_scene *d = &s->def;
  const int n = ode_collider_hits(&c->gen);
  fb_episode_update(&c->ep, n > 0, n > 0 ? c->gen.hit[c->gen.lead].rate : 0.0,
                    d->impact_velocity_min);
  if (n == 0) return;
  generic_user u = {s, j};
  const ode_collider_step x = {.world = s->world, .group = s->contacts, .mass = generic_mass,
                               .note = generic_note, .user = &u, .law = &d->law[j],
                               .mapping = d->mapping, .h = d->solver.h, .friction = d->friction,
                               .persistence = c->persistence, .v0 = c->ep.v0,
                               .split = d->ccd_split};
  ode_collider_rows(&c->gen, &x);
}

/* one ODE step of size h from the state now (the step's contact rows,
 * dWorldStep or dWorldQuickStep, the forces and accelerations it left) */
static fb_status world_step(fb_ode_world *s, double h, fb_diag *diag) {
  s->h_now = h;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    ode_clearance *c = &s->cl[j];
    c->step_wdh = c->step_hw = 0.0;
    c->persistence = s->def.mapping == FB_MAPPING_MATCHED_STATIC && !s->ad.rocking
                         ? fb_contact_persistence(c->phase)
                         : 0.0;
    /* the joint's contact rows for this step, from its collider */
    if (c->gen.bore || c->gen.ring)
      generic_contacts(s, j);
    else
      ode_exact_contact(s, j);
    /* the contact's phase: a step without a row ends the contact */
    c->phase = c->step_hw > 0.0 ? c->phase + c->step_hw : 0.0;
  }
  /* a matched row past the aliasing bound has lost its spring's meaning:
   * stop, naming the largest usable step (contact.h) */
  for (int j = 0; j < 4; j++) {
    if (!fb_kit_aliased(s->def.mapping, s->cl[j].step_wdh)) continue;
    dJointGroupEmpty(s->contacts);
    for (int q = 0; q < 4; q++) s->cl[q].cj = 0, s->cl[q].gen.nfb = 0;
    return fb_kit_alias_stop(&s->stop, j, s->cl[j].step_wdh, h, s->steps, diag);
  }
  const dReal *g1 = dBodyGetPosition(s->body[FB_CRANK]);
  s->crank_com_before[0] = g1[0];
  s->crank_com_before[1] = g1[1];
  /* an ODE fatal error (a failed internal check) stops this world with its
   * message instead of aborting the process (ode_env.h); the caller then
   * only destroys the world */
  jmp_buf escape;
  if (setjmp(escape) != 0) {
    s->broken = 1;
    s->stop.kind = FB_STOP_SOLVER;
    s->stop.t = (double)s->steps * s->def.solver.h;
    s->stop.step = s->steps + 1;
    snprintf(s->stop.detail, sizeof s->stop.detail, "%s", fb_ode_last_error());
    return fb_diag_set(diag, FB_ERR_NUMERIC, "ode-error: %s at t = %.6g s (step %zu)",
                       fb_ode_last_error(), (double)s->steps * s->def.solver.h, s->steps + 1);
  }
  fb_ode_escape = &escape;
  int ok = s->def.solver.stepper == FB_STEPPER_WORLD ? dWorldStep(s->world, h)
                                                     : dWorldQuickStep(s->world, h);
  fb_ode_escape = NULL;
  s->w_valid = 0; /* the bodies moved: the next step's tensors are its own */
  for (int j = 0; j < 4; j++) {
    ode_clearance *c = &s->cl[j];
    if (c->gen.bore || c->gen.ring) {
      /* force on the pin (body 1: dCollide(pin, box) keeps that order),
       * summed over the step's contacts */
      double f[2];
      const int rows = ode_collider_force(&c->gen, f);
      c->force = rows ? hypot(f[0], f[1]) : 0.0;
      c->force_pin[0] = rows ? f[0] : 0.0;
      c->force_pin[1] = rows ? f[1] : 0.0;
    } else {
      /* an onset row's impulse also covers the contact before the step (contact.h) */
      const double share = c->cj ? c->step_share : 0.0;
      c->force = share * hypot(c->fb.f1[0], c->fb.f1[1]);
      c->f_mean = c->cj && s->ad.rocking
                      ? fb_contact_mean_force_step(c->f_mean, c->force, h, c->omega_c)
                      : 0.0;
      c->force_pin[0] = share * c->fb.f1[0]; /* body 1 is the pin */
      c->force_pin[1] = share * c->fb.f1[1];
    }
    c->cj = 0;
  }
  dJointGroupEmpty(s->contacts);
  if (!ok) {
    s->stop.kind = FB_STOP_ALLOCATION;
    s->stop.t = (double)s->steps * s->def.solver.h;
    s->stop.step = s->steps + 1;
    return fb_diag_set(diag, FB_ERR_NOMEM, "ODE could not allocate memory for step %zu",
                       s->steps + 1);
  }
  for (int i = 0; i < 3; i++) {
    double w = ode_body_rate(s, i);
    s->alpha[i] = (w - s->omega_prev[i]) / h;
    s->omega_prev[i] = w;
    double a = ode_body_coord(s, i);
    if (i == s->translating) { /* the slider's x: nothing to unwrap */
      s->angle[i] = a;
      continue;
    }
    double prev = s->angle[i];
    double d = remainder(a - prev, 2.0 * M_PI);
    s->angle[i] = prev + d;
  }
  return FB_OK;
}

/* penetration (0 when free) and eccentricity of every clearance joint now */
static void adapt_geometry(const fb_ode_world *s, double pen[4], double ex[4], double ey[4]) {
  for (int j = 0; j < 4; j++) {
    pen[j] = ex[j] = ey[j] = 0.0;
    if (!(s->def.clearance_mask & (1 << j))) continue;
    double e[2], ev[2], num;
    ode_clearance_geometry(&s->cl[j], e, &num, ev);
    pen[j] = ode_clearance_penetration(s, &s->cl[j]);
    ex[j] = e[0];
    ey[j] = e[1];
  }
}

/* the next adaptive step as grid steps: the shortest any clearance joint's
 * contact asks for (step_control.h), ramped */
static int adapt_multiple(fb_ode_world *s) {
  const fb_model_scene *d = &s->def;
  const double hg = d->solver.h;
  double h = d->solver.h_max;
  int impulsive = 0; /* a joint penetrating with the matched row (step_control.h) */
  for (int j = 0; j < 4; j++) {
    if (!(d->clearance_mask & (1 << j))) continue;
    const ode_clearance *c = &s->cl[j];
    double e[2], ev[2], num;
    ode_clearance_geometry(c, e, &num, ev);
    const double ecc = hypot(e[0], e[1]);
    const double n[2] = {ecc > 0.0 ? e[0] / ecc : 1.0, ecc > 0.0 ? e[1] / ecc : 0.0};
    fb_step_joint sj = {.rule = FB_PERSIST_LOAD_SCHEDULE};
    fb_load_scale_at(&s->ad.load, j, s->angle[FB_CRANK], &sj.tau_load, &sj.load_force);
    sj.delta = ecc - d->radial_clearance;
    sj.ddot = ecc > 0.0 ? num / ecc : 0.0;
    sj.m_eff = ode_step_effective_mass(s, j, n);
    if (d->mapping == FB_MAPPING_MATCHED_STATIC && sj.delta > 0.0) {
      sj.persistence = fb_contact_persistence(c->phase);
      if (sj.persistence < 1.0) impulsive = 1;
    }
    if (s->ad.rocking) {
      /* the rocking along the wall: the effective mass along the tangent */
      const double t[2] = {-n[1], n[0]};
      sj.rocking_h_omega = d->solver.rocking_h_omega;
      sj.m_t = ode_step_effective_mass(s, j, t);
      sj.ecc = ecc;
    }
    const fb_contact_law law = ode_step_law(&d->law[j], sj.m_eff);
    h = fmin(h, fb_step_adaptive(&law, &sj, d->solver.accuracy, hg, d->solver.h_max));
  }
  int want = (int)floor(h / hg * (1.0 + 1e-9));
  want = fb_step_hold_in_impact(want < 1 ? 1 : want, s->ad.m_prev, impulsive);
  return fb_step_ramp(want, s->ad.m_prev, s->ad.m_max);
}

/* ODE's step moves positions as leapfrog does, its velocities acting as
 * the half-step ones: v_{n+1} = v_n + h_n a_n. When the step changes from
 * h_{n-1} to h_n, leapfrog's half-step velocity takes (h_{n-1} + h_n) / 2 of
 * the acceleration, ODE's h_n: a first-order error at every change, which
 * on the paper case spoiled the rocking's phase wherever the step follows
 * the load (docs/step-size.md). Before a step of h that follows one of
 * h_last, the moving links' velocities get (h_last - h) / 2 times the last
 * step's acceleration, (v now - v at its start) / h_last; the driven crank
 * keeps its speed. */
static void carry_velocities(fb_ode_world *s, double h) {
  const double hl = s->ad.h_last;
  if (hl > 0.0 && fabs(h - hl) > 1e-9 * hl) {
    const double g = 0.5 * (hl - h) / hl;
    for (int i = FB_COUPLER; i <= FB_FOLLOWER; i++) {
      const dReal *v = dBodyGetLinearVel(s->body[i]), *w = dBodyGetAngularVel(s->body[i]);
      dBodySetLinearVel(s->body[i], v[0] + g * (v[0] - s->ad.v_start[i][0]),
                        v[1] + g * (v[1] - s->ad.v_start[i][1]), v[2]);
      dBodySetAngularVel(s->body[i], w[0], w[1], w[2] + g * (w[2] - s->ad.w_start[i][2]));
    }
  }
  for (int i = 0; i < 3; i++) {
    const dReal *v = dBodyGetLinearVel(s->body[i]), *w = dBodyGetAngularVel(s->body[i]);
    for (int q = 0; q < 3; q++) s->ad.v_start[i][q] = v[q], s->ad.w_start[i][q] = w[q];
  }
  s->ad.h_last = h;
}

fb_status fb_ode_world_step(fb_ode_world *s, fb_diag *diag) {
  if (!s->ad.on) {
    fb_status st = world_step(s, s->def.solver.h, diag);
    if (st == FB_OK) s->steps++;
    return st;
  }
  if (s->ad.k < s->ad.mc) { /* a sample inside the last ODE step */
    s->ad.k++;
    s->steps++;
    return FB_OK;
  }
  const int m = adapt_multiple(s);
  if (s->ad.rocking) carry_velocities(s, m * s->def.solver.h);
  for (int i = 0; i < 3; i++) s->ad.ang0[i] = s->angle[i], s->ad.w0[i] = s->omega_prev[i];
  adapt_geometry(s, s->ad.pen0, s->ad.ex0, s->ad.ey0);
  const double h = m * s->def.solver.h;
  fb_status st = world_step(s, h, diag);
  if (st != FB_OK) return st;
  for (int i = 0; i < 3; i++) s->ad.ang1[i] = s->angle[i], s->ad.w1[i] = s->omega_prev[i];
  adapt_geometry(s, s->ad.pen1, s->ad.ex1, s->ad.ey1);
  s->ad.pen_end = ode_penetration_now(s, &s->ad.pen_joint_end);
  s->ad.drift_end = ode_joint_drift_now(s);
  fb_kit_stats_add(&s->ad.stats, h);
  s->ad.m_prev = m;
  s->ad.mc = m;
  s->ad.k = 1;
  s->steps++;
  return FB_OK;
}

void fb_ode_world_step_stats(const fb_ode_world *s, fb_step_stats *out) {
  if (s->ad.on) {
    *out = s->ad.stats;
    return;
  }
  fb_kit_stats_fixed(out, s->steps, s->def.solver.h);
}
