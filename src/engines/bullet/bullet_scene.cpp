/* The four-bar and the slider-crank in Bullet (bullet_scene.h). */
#include "bullet_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <new>

#include "bt_world.h"
extern "C" {
#include "contact_mass.h"
#include "effective_mass.h"
#include "episode.h"
#include "kit_record.h"
}

namespace {

/* one clearance joint */
struct Clearance {
  btRigidBody *pin = nullptr, *hole = nullptr; /* hole nullptr: ground */
  btVector3 pin_local, hole_local;             /* centre in the body's frame (world for ground) */
  FbRows *row = nullptr;                       /* its soft row (nrows 0 when free) */
  fb_episode ep;
  double force = 0.0;                          /* contact force of the last step [N] */
  double force_pin[2] = {0, 0};                /* on the pin [N] */
  double share = 1.0;                          /* step share of the last row (contact.h) */
  fb_contact_provenance prov;
  double phase = 0.0;                          /* contact phase so far [rad] (matched-static) */
  double step_wdh = 0.0, step_hw = 0.0;
};

}  // namespace

struct fb_bullet_scene {
  fb_model_scene def;
  FbBtWorld *w = nullptr;
  btRigidBody *body[3] = {nullptr, nullptr, nullptr};
  FbRows *pin[4] = {nullptr, nullptr, nullptr, nullptr};  /* ideal joints: 2 rows */
  btVector3 pin_local[4][2];                              /* joint point on body 1 and 2 */
  btRigidBody *b1[4] = {nullptr, nullptr, nullptr, nullptr}, *b2[4] = {nullptr, nullptr, nullptr,
                                                                        nullptr};
  btJointFeedback feedback[4];
  btSliderConstraint *guide = nullptr; /* the slider-crank's slider-ground joint */
  double guide_y = 0.0, guide_z = 0.0; /* its line: y = offset, z = 0 [m] */
  FbRows *drive = nullptr;
  Clearance cl[4];
  size_t steps = 0;
  double angle[3] = {0, 0, 0};
  double omega_prev[3] = {0, 0, 0};
  double alpha[3] = {0, 0, 0};
  double drive_torque = 0.0;
  double w_inv[4][2][2];
  int w_valid = 0;
  fb_stop stop;
  int slider_crank = 0; /* 1: body 2 is the slider, joint 3 the guide */
};

/* a link body between joint points p and q, centre of mass at com_fraction */
static btRigidBody *make_link(FbBtWorld *w, const fb_link_mass *lm, const double p[2],
                              const double q[2], double omega, const double vp[2]) {
  const double dx = q[0] - p[0], dy = q[1] - p[1];
  const double phi = atan2(dy, dx);
  const double rx = lm->com_fraction * dx, ry = lm->com_fraction * dy;
  btRigidBody *b =
      w->body(lm->mass, btVector3(lm->inertia_long, lm->inertia_transverse, lm->inertia));
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(p[0] + rx, p[1] + ry, 0));
  t.setRotation(btQuaternion(btVector3(0, 0, 1), phi));
  b->setCenterOfMassTransform(t);
  b->setLinearVelocity(btVector3(vp[0] - omega * ry, vp[1] + omega * rx, 0));
  b->setAngularVelocity(btVector3(0, 0, omega));
  return b;
}

/* the slider-crank's slider: a body free in 3-D whose centre of mass is its
 * hole centre h, moving at v along +x, its principal moments on its (x, y,
 * z); the guide (btSliderConstraint) holds all of it but x */
static btRigidBody *make_slider(FbBtWorld *w, const fb_link_mass *lm, const double h[2], double v) {
  btRigidBody *b =
      w->body(lm->mass, btVector3(lm->inertia_long, lm->inertia_transverse, lm->inertia), false);
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(h[0], h[1], 0));
  b->setCenterOfMassTransform(t);
  b->setLinearVelocity(btVector3(v, 0, 0));
  b->setAngularVelocity(btVector3(0, 0, 0));
  return b;
}

extern "C" int fb_bullet_version(void) { return btGetVersion(); }

static void scene_free(fb_bullet_scene *s) {
  if (!s) return;
  if (s->w) {
    for (int j = 0; j < 4; j++) {
      if (s->pin[j]) s->w->world.removeConstraint(s->pin[j]), delete s->pin[j];
      if (s->cl[j].row) s->w->world.removeConstraint(s->cl[j].row), delete s->cl[j].row;
    }
    if (s->drive) s->w->world.removeConstraint(s->drive), delete s->drive;
    if (s->guide) s->w->world.removeConstraint(s->guide), delete s->guide;
    for (int i = 0; i < 3; i++)
      if (s->body[i]) s->w->world.removeRigidBody(s->body[i]), delete s->body[i];
    delete s->w;
  }
  delete s;
}

extern "C" fb_status fb_bullet_scene_create(fb_bullet_scene **out, const fb_model_scene *sm,
                                            fb_diag *diag) {
  fb_status rc = fb_scene_check(sm->def, diag);
  if (rc != FB_OK) return rc;
  if (sm->clearance_mask && sm->collider != FB_COLLIDER_EXACT)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': the Bullet engine has no such collider",
                       sm->model->name);
  fb_start_state st;
  rc = fb_model_scene_start(&st, sm, diag);
  if (rc != FB_OK) return rc;
  fb_bullet_scene *s = new (std::nothrow) fb_bullet_scene();
  if (!s) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Bullet scene");
  try {
    s->def = *sm;
    memset(&s->stop, 0, sizeof s->stop);
    for (int j = 0; j < 4; j++) memset(&s->cl[j].ep, 0, sizeof s->cl[j].ep);
    for (int j = 0; j < 4; j++) memset(&s->cl[j].prov, 0, sizeof s->cl[j].prov);
    s->w = new FbBtWorld(sm->bullet.solver, sm->bullet.iterations, sm->gravity);
    const double zero[2] = {0, 0};
    s->body[FB_CRANK] = make_link(s->w, &sm->link[FB_CRANK], st.pin[FB_JOINT_A],
                                  st.pin[FB_JOINT_B], st.crank_omega, zero);
    s->body[FB_COUPLER] = make_link(s->w, &sm->link[FB_COUPLER], st.hole[FB_JOINT_B],
                                    st.pin[FB_JOINT_C], st.coupler_omega, st.coupler_b_vel);
    s->slider_crank = sm->def->source.mechanism == FB_MECH_SLIDER_CRANK;
    s->body[2] = s->slider_crank
                     ? make_slider(s->w, &sm->link[2], st.hole[FB_JOINT_C], st.body[1][FB_Q_VEL])
                     : make_link(s->w, &sm->link[FB_FOLLOWER], st.pin[FB_JOINT_D],
                                 st.hole[FB_JOINT_C], st.follower_omega, zero);
    btRigidBody *const first[4] = {s->body[FB_CRANK], s->body[FB_CRANK], s->body[FB_COUPLER],
                                   s->body[2]};
    btRigidBody *const second[4] = {nullptr, s->body[FB_COUPLER], s->body[2], nullptr};
    for (int j = 0; j < 4; j++) {
      if (s->slider_crank && j == FB_JOINT_D) {
        /* the guide: btSliderConstraint to the world along +x through the
         * slider's centre (y = offset, z = 0); its rows hold y, z and the
         * rotations about y and z (and about x once it turns), hard (CFM
         * 0) with the pins' ERP [solver] world_erp */
        s->b1[j] = s->body[2];
        btTransform frame;
        frame.setIdentity();
        s->guide = fb_bt_slider(nullptr, frame, *s->body[2], frame, sm->solver.world_erp);
        s->guide->setJointFeedback(&s->feedback[j]);
        s->guide->enableFeedback(true);
        s->guide_y = st.hole[FB_JOINT_C][1];
        s->w->add(s->guide);
        continue;
      }
      s->b1[j] = first[j];
      s->b2[j] = second[j];
      const btVector3 pw(st.pin[j][0], st.pin[j][1], 0), hw(st.hole[j][0], st.hole[j][1], 0);
      if (sm->clearance_mask & (1 << j)) {
        Clearance *c = &s->cl[j];
        c->pin = first[j];
        c->hole = second[j];
        c->pin_local = c->pin->getCenterOfMassTransform().inverse() * pw;
        c->hole_local = c->hole ? c->hole->getCenterOfMassTransform().inverse() * hw : hw;
        c->row = c->hole ? new FbRows(*c->pin, *c->hole) : new FbRows(*c->pin);
        c->row->enableFeedback(true);
        s->w->add(c->row);
        continue;
      }
      /* the joint point on each body (the start's pin position) */
      s->pin_local[j][0] = first[j]->getCenterOfMassTransform().inverse() * pw;
      s->pin_local[j][1] = second[j] ? second[j]->getCenterOfMassTransform().inverse() * pw : pw;
      s->pin[j] = second[j] ? new FbRows(*first[j], *second[j]) : new FbRows(*first[j]);
      s->pin[j]->nrows = 2;
      s->pin[j]->setJointFeedback(&s->feedback[j]);
      s->pin[j]->enableFeedback(true);
      s->w->add(s->pin[j]);
    }
    /* the drive: the crank's angular velocity about +z held at omega2 */
    s->drive = new FbRows(*s->body[FB_CRANK]);
    s->drive->nrows = 1;
    s->w->add(s->drive);
  } catch (const std::bad_alloc &) {
    scene_free(s);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Bullet scene");
  }
  for (int i = 0; i < 3; i++) {
    s->angle[i] = fb_bt_body_angle(s->body[i]);
    s->omega_prev[i] = s->body[i]->getAngularVelocity()[2];
  }
  if (s->slider_crank) { /* the slider's x and v along the guide */
    s->angle[2] = s->body[2]->getCenterOfMassPosition()[0];
    s->omega_prev[2] = s->body[2]->getLinearVelocity()[0];
  }
  *out = s;
  return FB_OK;
}

/* the mechanism now, for the effective mass (effective_mass.h) */
static void mechanism(const fb_bullet_scene *s, fb_mechanism *m) {
  memset(m, 0, sizeof *m);
  for (int i = 0; i < 3; i++) {
    const btVector3 p = s->body[i]->getCenterOfMassPosition();
    m->mass[i] = s->def.link[i].mass;
    m->inertia[i] = s->def.link[i].inertia;
    m->com[i][0] = p[0];
    m->com[i][1] = p[1];
  }
  for (int j = 0; j < 4; j++) {
    const btVector3 q = (s->def.clearance_mask & (1 << j))
                            ? fb_bt_world_point(s->cl[j].pin, s->cl[j].pin_local)
                            : fb_bt_world_point(s->b1[j], s->pin_local[j][0]);
    m->joint[j][0] = q[0];
    m->joint[j][1] = q[1];
  }
  if (s->slider_crank) { /* the guide at the slider's point (its centre, the hole's) */
    m->joint[FB_JOINT_D][0] = m->com[2][0];
    m->joint[FB_JOINT_D][1] = m->com[2][1];
    m->prismatic_mask = 1 << FB_JOINT_D;
  }
  m->clearance_mask = s->def.clearance_mask;
  m->crank_driven = 1;
}

static double step_effective_mass(fb_bullet_scene *s, int j, const double n[2]) {
  if (!s->w_valid) {
    fb_mechanism m;
    mechanism(s, &m);
    if (fb_effective_mass_tensor(s->w_inv, &m, NULL) != FB_OK) return s->def.law[j].mass;
    s->w_valid = 1;
  }
  const double me = fb_effective_mass_along(s->w_inv[j], n);
  return isfinite(me) && me > 0.0 ? me : s->def.law[j].mass;
}

/* eccentricity e = pin centre - hole centre [m] and its rate [m/s] */
static void geometry(const Clearance *c, btVector3 *p, btVector3 *q, btVector3 *ev) {
  *p = fb_bt_world_point(c->pin, c->pin_local);
  *q = fb_bt_world_point(c->hole, c->hole_local);
  *ev = fb_bt_point_velocity(c->pin, *p) - fb_bt_point_velocity(c->hole, *q);
}

/* what the coming step's position update adds to a body point's motion
 * beyond the linear h (v + w x r) a row sees: Bullet turns the body by
 * exactly h w (btTransformUtil::integrateTransform, exponential map), so the
 * point at r moves (cos(h w) - 1) r + (sin(h w) - h w) z x r more [m] (the
 * Bullet counterpart of ode_clearance.c's point_drift) */
static btVector3 point_drift(const btRigidBody *b, const btVector3 &p, double h) {
  if (!b) return btVector3(0, 0, 0);
  const btVector3 r = p - b->getCenterOfMassPosition();
  const double th = h * b->getAngularVelocity()[2];
  const double cm1 = cos(th) - 1.0, sw = sin(th) - th;
  return btVector3(cm1 * r[0] - sw * r[1], cm1 * r[1] + sw * r[0], 0);
}

static void note_row(Clearance *c, const fb_contact_row *u, double mass, double h) {
  fb_contact_provenance *p = &c->prov;
  if (p->contact_steps == 0 || u->erp > p->erp_max) p->erp_max = u->erp;
  if (p->contact_steps == 0 || u->cfm < p->cfm_min) p->cfm_min = u->cfm;
  const double hw = fb_contact_h_omega(h, u->kp, mass);
  if (p->contact_steps == 0 || hw > p->h_omega_max) p->h_omega_max = hw;
  if (hw > c->step_hw) c->step_hw = hw;
  if (p->contact_steps == 0 || mass < p->mass_eff_min) p->mass_eff_min = mass;
  if (p->contact_steps == 0 || mass > p->mass_eff_max) p->mass_eff_max = mass;
  p->contact_steps++;
  const double wdh = fb_contact_omega_d_h(h, u->kp, u->kd, mass);
  if (wdh > c->step_wdh) c->step_wdh = wdh;
}

/* the soft row of clearance joint j for this step, or none when free */
static void clearance_row(fb_bullet_scene *s, int j) {
  Clearance *c = &s->cl[j];
  const fb_model_scene *d = &s->def;
  const double h = d->solver.h;
  c->row->nrows = 0;
  c->share = 1.0;
  btVector3 p, q, ev;
  geometry(c, &p, &q, &ev);
  const double ex = p[0] - q[0], ey = p[1] - q[1];
  const double ecc = hypot(ex, ey);
  const double delta = ecc - d->radial_clearance;
  if (!(delta > 0.0) || ecc == 0.0) {
    fb_episode_update(&c->ep, 0, 0.0, d->impact_velocity_min);
    return;
  }
  const double n[2] = {ex / ecc, ey / ecc};
  const double ddot = n[0] * ev[0] + n[1] * ev[1];
  const int onset = !c->ep.in_contact;
  fb_episode_update(&c->ep, 1, ddot, d->impact_velocity_min);
  const double m_eff = step_effective_mass(s, j, n);
  const fb_contact_law law = fb_contact_law_on_mass(&d->law[j], m_eff); /* contact_mass.h */
  const double persistence =
      d->mapping == FB_MAPPING_MATCHED_STATIC ? fb_contact_persistence(c->phase) : 0.0;
  fb_contact_row u;
  if (fb_contact_row_step(&u, &law, d->mapping, h, m_eff, 1, delta, ddot, c->ep.v0, onset,
                          persistence) != FB_OK)
    return;
  /* the contact point on the hole wall, normal N = -n into the pin */
  const double r_hole = d->pin_radius + d->radial_clearance;
  const btVector3 pt(q[0] + r_hole * n[0], q[1] + r_hole * n[1], 0);
  if (d->mapping == FB_MAPPING_MATCHED_STATIC && u.erp > 0.0) {
    /* as ODE's scene: the penetration's drift over the step the row cannot
     * see (rotation of both points, curvature of the circle) */
    const btVector3 bp = point_drift(c->pin, p, h), bq = point_drift(c->hole, q, h);
    const double dp[2] = {bp[0], bp[1]}, dq[2] = {bq[0], bq[1]}, e_rate[2] = {ev[0], ev[1]};
    u.depth += fb_contact_step_drift(n, dp, dq, e_rate, ecc, h) / u.erp;
  }
  c->share = u.step_share;
  note_row(c, &u, m_eff, h);
  fb_bt_contact_row(c->row, btVector3(-n[0], -n[1], 0), pt, u.erp, u.depth, u.cfm, h);
}

/* the two rows of ideal joint j: the bodies' joint points coincide */
static void pin_rows(fb_bullet_scene *s, int j) {
  const double h = s->def.solver.h, erp = s->def.solver.world_erp;
  fb_bt_pin_rows(s->pin[j], fb_bt_world_point(s->b1[j], s->pin_local[j][0]),
                 fb_bt_world_point(s->b2[j], s->pin_local[j][1]), erp, h);
}

extern "C" fb_status fb_bullet_scene_step(fb_bullet_scene *s, fb_diag *diag) {
  const double h = s->def.solver.h;
  s->w_valid = 0;
  for (int j = 0; j < 4; j++) {
    if (s->pin[j]) pin_rows(s, j);
    if (!(s->def.clearance_mask & (1 << j))) continue;
    Clearance *c = &s->cl[j];
    c->step_wdh = c->step_hw = 0.0;
    clearance_row(s, j);
    c->phase = c->step_hw > 0.0 ? c->phase + c->step_hw : 0.0;
  }
  for (int j = 0; j < 4; j++) {
    if (fb_kit_aliased(s->def.mapping, s->cl[j].step_wdh))
      return fb_kit_alias_stop(&s->stop, j, s->cl[j].step_wdh, h, s->steps, diag);
  }
  fb_bt_drive_row(s->drive, s->def.omega2, s->def.solver.drive_torque_max, h);
  if (s->w->step(h)) {
    /* btMLCPSolver falls back to sequential impulse when the Dantzig solve
     * fails; that step is no longer the direct solver's: stop, say so */
    s->stop.kind = FB_STOP_SOLVER;
    s->stop.t = (double)s->steps * h;
    s->stop.step = s->steps + 1;
    snprintf(s->stop.detail, sizeof s->stop.detail,
             "btDantzigSolver failed (btMLCPSolver fell back to sequential impulse)");
    return fb_diag_set(diag, FB_ERR_NUMERIC,
                       "bullet: the Dantzig MLCP solve failed at t = %.6g s (step %zu); "
                       "[bullet] solver = sequential-impulse runs the iterative solver on purpose",
                       s->stop.t, s->stop.step);
  }
  s->steps++;
  s->drive_torque = s->drive->getAppliedImpulse() / h;
  for (int j = 0; j < 4; j++) {
    Clearance *c = &s->cl[j];
    if (!c->row) continue;
    const double imp = c->row->nrows ? c->row->getAppliedImpulse() : 0.0;
    const FbRow &r = c->row->row[0];
    c->force = c->row->nrows ? c->share * imp / h : 0.0;
    c->force_pin[0] = c->row->nrows ? c->force * r.n[0] : 0.0; /* N pushes the pin */
    c->force_pin[1] = c->row->nrows ? c->force * r.n[1] : 0.0;
  }
  for (int i = 0; i < 3; i++) {
    if (s->slider_crank && i == 2) { /* the slider: x, v, a along the guide */
      const double v = s->body[i]->getLinearVelocity()[0];
      s->alpha[i] = (v - s->omega_prev[i]) / h;
      s->omega_prev[i] = v;
      s->angle[i] = s->body[i]->getCenterOfMassPosition()[0];
      continue;
    }
    const double w = s->body[i]->getAngularVelocity()[2];
    s->alpha[i] = (w - s->omega_prev[i]) / h;
    s->omega_prev[i] = w;
    const double a = fb_bt_body_angle(s->body[i]);
    s->angle[i] += remainder(a - s->angle[i], 2.0 * M_PI);
  }
  return FB_OK;
}

extern "C" void fb_bullet_scene_stopped(const fb_bullet_scene *s, fb_stop *out) {
  *out = s->stop;
  out->engine = "bullet";
  if (out->kind != FB_STOP_ALIASED) out->joint = -1;
}

static double penetration_of(const fb_bullet_scene *s, const Clearance *c) {
  btVector3 p, q, ev;
  geometry(c, &p, &q, &ev);
  const double pen = hypot(p[0] - q[0], p[1] - q[1]) - s->def.radial_clearance;
  return pen > 0.0 ? pen : 0.0;
}

extern "C" void fb_bullet_scene_sample(const fb_bullet_scene *s, fb_sample *x) {
  fb_kit_sample_bodies(x, (double)s->steps * s->def.solver.h, s->angle, s->omega_prev, s->alpha);
  for (int j = 0; j < 4; j++) {
    for (int k = 0; k < FB_CONTACT_COLS; k++) x->contact[j][k] = 0.0;
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const Clearance *c = &s->cl[j];
    btVector3 p, q, ev;
    geometry(c, &p, &q, &ev);
    fb_kit_sample_contact(x->contact[j], c->force, penetration_of(s, c), p[0] - q[0], p[1] - q[1],
                          &c->ep);
  }
}

extern "C" double fb_bullet_scene_joint_drift(const fb_bullet_scene *s) {
  double worst = 0.0;
  for (int j = 0; j < 4; j++) {
    if (!s->pin[j]) continue;
    const btVector3 d =
        fb_bt_world_point(s->b1[j], s->pin_local[j][0]) - fb_bt_world_point(s->b2[j], s->pin_local[j][1]);
    if (d.length() > worst) worst = d.length();
  }
  if (s->guide) { /* the slider's centre off its guide line */
    const btVector3 p = s->body[2]->getCenterOfMassPosition();
    const double d = hypot(p[1] - s->guide_y, p[2] - s->guide_z);
    if (d > worst) worst = d;
  }
  return worst;
}

extern "C" double fb_bullet_scene_penetration(const fb_bullet_scene *s, int *joint) {
  double worst = 0.0;
  *joint = -1;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const double pen = penetration_of(s, &s->cl[j]);
    if (*joint < 0 || pen > worst) worst = pen, *joint = j;
  }
  return worst;
}

extern "C" void fb_bullet_scene_provenance(const fb_bullet_scene *s, int j,
                                           fb_contact_provenance *out) {
  *out = s->cl[j].prov;
  if (out->contact_steps == 0)
    out->mass_eff_min = out->mass_eff_max = out->erp_max = out->cfm_min = out->h_omega_max = NAN;
}

extern "C" void fb_bullet_scene_reactions(const fb_bullet_scene *s, double force[4][2],
                                          double *drive_torque) {
  const int on_body2[4] = {0, 1, 1, 0};
  for (int j = 0; j < 4; j++) {
    if (j == FB_JOINT_D && s->guide) {
      /* the force on the ground from the slider: minus the guide's on the
       * slider (its body B) */
      const btVector3 &f = s->feedback[j].m_appliedForceBodyB;
      force[j][0] = s->steps ? -f[0] : 0.0;
      force[j][1] = s->steps ? -f[1] : 0.0;
      continue;
    }
    if (!s->pin[j]) {
      const double sign = on_body2[j] ? -1.0 : 1.0;
      force[j][0] = sign * s->cl[j].force_pin[0];
      force[j][1] = sign * s->cl[j].force_pin[1];
      continue;
    }
    const btVector3 &f = on_body2[j] ? s->feedback[j].m_appliedForceBodyB
                                     : s->feedback[j].m_appliedForceBodyA;
    force[j][0] = s->steps ? f[0] : 0.0;
    force[j][1] = s->steps ? f[1] : 0.0;
  }
  *drive_torque = s->steps ? s->drive_torque : 0.0;
}

extern "C" int fb_bullet_scene_impacts(const fb_bullet_scene *s, int j) {
  return s->cl[j].ep.impacts;
}

extern "C" size_t fb_bullet_scene_steps(const fb_bullet_scene *s) { return s->steps; }

extern "C" void fb_bullet_scene_destroy(fb_bullet_scene *s) { scene_free(s); }
