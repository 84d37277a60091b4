/* The single impact through an engine's kit binding (see kit_impact.h). */
#include <math.h>
#include <string.h>

#include "clock.h"
#include "kit_impact.h"

/* the sphere whose moment of inertia the body carries [m] */
#define KIT_IMPACT_BODY_RADIUS_M 0.01

/* one impact's world in the binding and the contact's running state */
typedef struct {
  const fb_kit_binding *b;
  void *w;
  fb_solver solver;
  fb_contact_law law; /* d's, its damper on the body's mass */
  const fb_impact_def *d;
  double v0;          /* the contact's onset rate, -1 before it [m/s] */
  double phase;       /* the contact's phase so far [rad] (contact.h) */
} kit_impact;

/* the binding's world of d (mass, step, stepper) with the one body at
 * height y0 [m] above the wall, at rest or moving in at speed [m/s]; the
 * contact rows' speed limit speed_max [m/s] (0: the engine's own) */
static fb_status impact_open(kit_impact *x, const fb_kit_binding *b, const fb_impact_def *d,
                             double y0, double speed, double speed_max, const fb_case *c,
                             fb_diag *diag) {
  memset(x, 0, sizeof *x);
  x->b = b;
  x->d = d;
  x->v0 = -1.0;
  x->solver = (fb_solver){.h = d->h, .h_mode = FB_STEP_FIXED, .stepper = d->stepper,
                          .quick_iterations = d->quick_iterations, .world_erp = 0.2,
                          .world_cfm = 1e-5, .seed = 1};
  const fb_kit_world o = {.gravity = 0.0, .h = d->h, .solver = &x->solver, .nbodies = 1,
                          .njoints = 0, .c = c, .drive = -1, .contact_speed_max = speed_max};
  fb_status st = b->world_new(&x->w, &o, diag);
  if (st != FB_OK) return st;
  const double r = KIT_IMPACT_BODY_RADIUS_M;
  const fb_kit_body body = {.mass = d->mass, .inertia = 0.4 * d->mass * r * r,
                            .pos = {0.0, y0, 0.0}, .vel = {0.0, -speed, 0.0}};
  if ((st = b->add_body(x->w, &body, diag)) != FB_OK) return st;
  return b->add_drive(x->w, -1, 0.0, diag); /* the walk's end: no drive */
}

/* d's law on its body's mass, prepared once (zeta solved once, not on
 * every step) */
static void impact_law(kit_impact *x) {
  x->law = x->d->law;
  x->law.mass = x->d->mass;
  fb_contact_law_prepare(&x->law, NULL);
}

/* the wall's contact at the body's state pos, vel, depth -y: the fields a
 * clearance joint's contact has, no row yet */
static fb_kit_contact wall_contact(const kit_impact *x, const double pos[3],
                                   const double vel[3], int onset) {
  const fb_impact_def *d = x->d;
  return (fb_kit_contact){.pin = 0, .hole = FB_KIT_GROUND, .point = {pos[0], pos[1]},
                          .normal = {0.0, -1.0}, .depth = -pos[1], .rate = -vel[1],
                          .v0 = x->v0, .onset = onset, .m_eff = d->mass, .law = x->law,
                          .mapping = d->mapping, .h = d->h, .m_alone = d->mass,
                          .persistence = fb_contact_persistence(x->phase), .wall = 1,
                          .centre = {{pos[0], pos[1]}, {pos[0], 0.0}},
                          .ecc_rate = {0.0, vel[1]}};
}

/* the wall's contact for the coming step at the body's state pos, vel (the
 * body at depth delta = -y > 0): its soft row, as the kit's pipeline hands
 * a clearance joint's; *made 1 when the law gave a row */
static fb_status impact_contact(kit_impact *x, const double pos[3], const double vel[3],
                                int *made, fb_diag *diag) {
  const fb_impact_def *d = x->d;
  const double delta = -pos[1], ddot = -vel[1];
  const int onset = x->v0 < 0.0;
  if (onset) x->v0 = fmax(ddot, 1e-300);
  fb_kit_contact ct = wall_contact(x, pos, vel, onset);
  *made = 0;
  if (fb_contact_row_step(&ct.row, &x->law, d->mapping, d->h, d->mass, 1, delta, ddot, x->v0,
                          onset, ct.persistence) != FB_OK)
    return FB_OK; /* no row at this state (contact.h) */
  *made = 1;
  ct.has_row = x->b->contact_rows;
  x->phase += fb_contact_h_omega(d->h, ct.row.kp, d->mass);
  return x->b->add_contact(x->w, 0, &ct, diag);
}

/* a binding that can run the impact, else FB_ERR_ARG naming it */
static fb_status impact_binding(const fb_kit_binding *b, int wrench, fb_diag *diag) {
  if (!b->add_contact || !b->contact_force || b->applied_force)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "the %s kit applies no soft contact row: no single impact through it",
                       b->engine);
  if (wrench && !b->apply_wrench)
    return fb_diag_set(diag, FB_ERR_ARG, "the %s kit applies no load: no static load through it",
                       b->engine);
  return FB_OK;
}

fb_status fb_kit_impact(fb_impact_result *out, const fb_kit_binding *b, const fb_impact_def *d,
                        const fb_case *c, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  fb_status st = fb_impact_check(d, diag);
  if (st == FB_OK) st = impact_binding(b, 0, diag);
  if (st != FB_OK) return st;
  const double t_wall = fb_clock_s();
  const size_t max_steps = (size_t)ceil(100.0 * fb_impact_duration_estimate(d) / d->h) + 10;
  kit_impact x;
  st = impact_open(&x, b, d, 0.0, d->speed, 0.0, c, diag); /* touching: depth 0 */
  impact_law(&x);
  fb_impact_tally tally = {0, 0, 0.0, 0.0};
  double pos[3], vel[3];
  size_t k = 0;
  if (st == FB_OK) b->body_state(x.w, 0, pos, vel);
  for (; st == FB_OK && k < max_steps && !tally.done; k++) {
    int made = 0;
    if (-pos[1] > 0.0 && (st = impact_contact(&x, pos, vel, &made, diag)) != FB_OK) break;
    if ((st = b->step(x.w, diag)) != FB_OK) break;
    const double force = made ? b->contact_force(x.w, 0) : 0.0;
    b->body_state(x.w, 0, pos, vel);
    const double t1 = (double)(k + 1) * d->h;
    if (!isfinite(pos[1]) || !isfinite(force)) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "%s impact: non-finite state at t = %g s",
                       b->engine, t1);
      break;
    }
    fb_impact_tally_force(&tally, out, t1, d->h, -pos[1], force, vel[1]);
  }
  out->steps = k;
  out->contact_duration = tally.t_end;
  if (st == FB_OK) out->restitution = vel[1] / d->speed;
  if (x.w) b->world_free(x.w);
  if (st == FB_OK && !tally.done)
    st = fb_diag_set(diag, FB_ERR_NUMERIC,
                     "%s impact: the body has not left the contact after %zu steps (%g s)",
                     b->engine, k, (double)k * d->h);
  out->wall_s = fb_clock_s() - t_wall;
  return st;
}

fb_status fb_kit_impact_static(double *penetration, const fb_kit_binding *b,
                               const fb_impact_def *d, double load, double duration,
                               const fb_case *c, fb_diag *diag) {
  *penetration = NAN;
  fb_status st = fb_impact_check(d, diag);
  if (st != FB_OK) return st;
  if (!(load > 0.0) || !isfinite(load) || !(duration > 0.0) || !isfinite(duration))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "static load %g N over %g s: need a positive, finite load and duration",
                       load, duration);
  if ((st = impact_binding(b, 1, diag)) != FB_OK) return st;
  const size_t steps = (size_t)ceil(duration / d->h);
  kit_impact x;
  st = impact_open(&x, b, d, 0.0, 0.0, 0.0, c, diag); /* at rest: the load is sudden */
  impact_law(&x);
  double pos[3], vel[3];
  if (st == FB_OK) b->body_state(x.w, 0, pos, vel);
  const double wrench[3] = {0.0, -load, 0.0};
  for (size_t k = 0; st == FB_OK && k < steps; k++) {
    int made = 0;
    if (-pos[1] > 0.0) st = impact_contact(&x, pos, vel, &made, diag);
    else x.v0 = -1.0, x.phase = 0.0; /* left the contact: the next one is a new contact */
    if (st != FB_OK) break;
    b->apply_wrench(x.w, 0, wrench);
    if ((st = b->step(x.w, diag)) != FB_OK) break;
    b->body_state(x.w, 0, pos, vel);
    if (!isfinite(pos[1]))
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "%s static load: non-finite state at step %zu",
                       b->engine, k + 1);
  }
  if (st == FB_OK) *penetration = -pos[1];
  if (x.w) b->world_free(x.w);
  return st;
}

fb_status fb_kit_impact_row(fb_impact_result *out, const fb_kit_binding *b, double mass,
                            double speed, double h, double erp, double cfm, double speed_max,
                            double t_max, double onset_phase, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(mass > 0.0) || !(speed > 0.0) || !(h > 0.0) || !(cfm > 0.0) || !(erp >= 0.0) ||
      !(speed_max > 0.0) || !(t_max > h) || !isfinite(mass) || !isfinite(speed) ||
      !isfinite(erp))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "%s row impact: mass %g kg, speed %g m/s, h %g s, ERP %g, CFM %g, "
                       "max_vel %g m/s, t_max %g s: need positive, finite values, ERP >= 0",
                       b->engine, mass, speed, h, erp, cfm, speed_max, t_max);
  if (!(onset_phase >= 0.0 && onset_phase < 1.0))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s row impact: onset phase %g: must lie in [0, 1)",
                       b->engine, onset_phase);
  if (!b->add_contact || !b->contact_force || !b->contact_rows)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "the %s kit takes no soft contact row (ERP, CFM): no fixed row through it",
                       b->engine);
  if (isfinite(speed_max) && !b->contact_speed_limit)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "the %s kit has no contact correcting speed limit: max_vel %g m/s cannot "
                       "be set", b->engine, speed_max);
  /* touching (phase 0), or a free step short of the crossing: the first
   * step that sees the contact then sees the depth phase h v */
  const double t_free = onset_phase > 0.0 ? (1.0 - onset_phase) * h : 0.0;
  const double steps_max = ceil((t_max + t_free) / h);
  if (steps_max > FB_IMPACT_MAX_STEPS)
    return fb_diag_set(diag, FB_ERR_RANGE, "%s row impact: %g steps of %g s: more than %g",
                       b->engine, steps_max, h, FB_IMPACT_MAX_STEPS);
  const double t_wall = fb_clock_s();
  const fb_impact_def d = {.mass = mass, .speed = speed, .h = h, .stepper = FB_STEPPER_WORLD,
                           .quick_iterations = 20};
  kit_impact x;
  fb_status st = impact_open(&x, b, &d, t_free * speed, speed,
                             isfinite(speed_max) ? speed_max : 0.0, NULL, diag);
  const fb_contact_row row = {.erp = erp, .cfm = cfm, .step_share = 1.0};
  fb_impact_tally tally = {0, 0, 0.0, 0.0};
  double pos[3], vel[3];
  size_t k = 0;
  if (st == FB_OK) b->body_state(x.w, 0, pos, vel);
  for (; st == FB_OK && (double)k < steps_max && !tally.done; k++) {
    const int made = -pos[1] >= 0.0; /* touching counts, as the engines' colliders report it */
    if (made) {
      fb_kit_contact ct = wall_contact(&x, pos, vel, 0);
      ct.has_row = 1;
      ct.row = row;
      ct.row.depth = -pos[1];
      if ((st = b->add_contact(x.w, 0, &ct, diag)) != FB_OK) break;
    }
    if ((st = b->step(x.w, diag)) != FB_OK) break;
    const double force = made ? b->contact_force(x.w, 0) : 0.0;
    b->body_state(x.w, 0, pos, vel);
    const double t1 = (double)(k + 1) * h - t_free; /* from the crossing */
    if (!isfinite(pos[1]) || !isfinite(force)) {
      st = fb_diag_set(diag, FB_ERR_NUMERIC, "%s row impact: non-finite state at t = %g s",
                       b->engine, t1);
      break;
    }
    fb_impact_tally_depth(&tally, out, t1, h, -pos[1], force);
  }
  out->steps = k;
  out->contact_duration = tally.t_end;
  if (st == FB_OK) out->restitution = vel[1] / speed;
  if (x.w) b->world_free(x.w);
  if (st == FB_OK && !tally.done)
    st = fb_diag_set(diag, FB_ERR_NUMERIC,
                     "%s row impact: the body has not left the contact after %zu steps (%g s)",
                     b->engine, k, (double)k * h);
  out->wall_s = fb_clock_s() - t_wall;
  return st;
}
