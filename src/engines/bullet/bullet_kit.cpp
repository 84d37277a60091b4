/* Bullet as a binding of the engine kit (kit.h, bullet_kit.h): any planar
 * description in Bullet as the four-bar's scene (bullet_scene.h) builds its
 * own, with the same pieces (bt_world.h). A body is a btRigidBody with an
 * empty shape (no collision pairs), linear factor (1, 1, 0) and angular
 * factor (0, 0, 1): planar exactly (its in-plane moments half its +z one,
 * a thin plate's, which nothing planar excites). A revolute joint is the
 * four-bar's planar pin, two rows (x, y at the joint point, ERP [solver]
 * world_erp on the position error, CFM 0; a btHingeConstraint's five rows
 * would over-constrain a planar loop by three per joint): the loops close
 * through the pins themselves, with no redundant row, so the direct MLCP
 * is regular. A prismatic joint is the slider-crank's guide: a
 * btSliderConstraint along the joint's axis, its ERP world_erp, CFM 0, on
 * a body then free in 3-D (factors 1), which the guide holds out of the
 * plane (a slider row on a planar-factored body would meet zeroed
 * freedoms). The drive is the four-bar's: one angular velocity row of the
 * driven pin's body[1] relative to its body[0], impulse limited to
 * [solver] drive_torque_max_n_m h. The solver is the case's [bullet]
 * solver (btMLCPSolver with btDantzigSolver, or sequential impulse) and
 * iterations; one stepSimulation(h, 0, h) a step; a Dantzig solve that
 * falls back to sequential impulse stops the model, as the four-bar's.
 * A clearance joint's contact (kit.h's pipeline computes it) is the
 * four-bar's clearance row: the law's row of the step at the effective
 * mass (fb_contact_row_step, the mapping ODE's contact uses), one
 * unilateral soft row on the hole wall along the normal into the pin
 * (bt_rows.h: solved as ODE's soft row, J v = ERP depth / h - CFM / h
 * lambda), its force the row's impulse times its step share over h.
 * Reactions: every pin's, guide's and the drive's row keeps Bullet's joint
 * feedback (btJointFeedback: the force and the torque about the centre of
 * mass the rows applied over the step), turned to kit.h's convention. */
#include <math.h>
#include <stdio.h>

#include <new>

#include "bt_world.h"
#include "bullet_kit.h"
extern "C" {
#include "contact.h"
#include "planar_spec.h"
}

namespace {

/* one joint the walk added: rows between body A and body B (B nullptr:
 * the ground) */
struct Joint {
  FbRows *pin = nullptr;               /* a revolute joint's two rows */
  btSliderConstraint *guide = nullptr; /* a prismatic joint's guide */
  btRigidBody *a = nullptr, *b = nullptr;
  btVector3 la, lb; /* the pin's point on A and on B (the world's for the ground) [m] */
  int b0 = 0, b1 = 0; /* the kit's handles of the joint's bodies */
  btJointFeedback fb;  /* what its rows applied over the last step */
  btVector3 ls;        /* a guide's point on its slider, in the slider's frame [m] */
  double lever[2] = {0.0, 0.0}; /* a guide's slider: centre of mass minus that point at the
                                   last step's start [m] */
};

/* one clearance joint's soft row */
struct Contact {
  FbRows *row = nullptr; /* nrows 1 for a step with a contact, else 0 */
  double share = 1.0;    /* the step's share of its impulse (contact.h) */
  double force = 0.0;    /* its normal force in the last step [N] */
};

struct Kit {
  FbBtWorld *w = nullptr;
  double h = 0.0, erp = 0.0, fmax = 0.0; /* step [s], pins' ERP [-], drive torque limit [N m] */
  btRigidBody *body[FB_PLANAR_SPEC_MAX_BODIES] = {};
  int nbodies = 0;
  Joint joint[FB_PLANAR_SPEC_MAX_JOINTS];
  int njoints = 0;
  FbRows *drive = nullptr;
  btJointFeedback drive_fb; /* the drive row's feedback */
  int drive_joint = -1;     /* the driven joint (its place among the joints added) */
  Contact contact[FB_KIT_SLOTS]; /* by the kit's contact slot (a pin's, a slider's corner's) */
  int used[FB_KIT_SLOTS];        /* the slots whose row exists, in the order made */
  int nused = 0;
  size_t steps = 0;
};

/* Bullet's body of a kit handle (nullptr: the ground) */
btRigidBody *bt_body(const Kit *k, int b) { return b == FB_KIT_GROUND ? nullptr : k->body[b]; }

/* rows between handles b0 and b1, the moving one as A when one is the
 * ground */
FbRows *rows_between(const Kit *k, int b0, int b1) {
  btRigidBody *a = bt_body(k, b0), *b = bt_body(k, b1);
  if (!a) return new FbRows(*b);
  return b ? new FbRows(*a, *b) : new FbRows(*a);
}

/* what the coming step's position update adds to the motion of the point
 * at x [m] of body handle b beyond the linear h (v + w x r) a row sees:
 * Bullet turns the body by exactly h w (btTransformUtil::integrateTransform,
 * exponential map), so the point at r moves (cos(h w) - 1) r +
 * (sin(h w) - h w) z x r more [m]; 0 for the ground */
void point_drift(const Kit *k, int b, const double x[2], double h, double out[2]) {
  out[0] = out[1] = 0.0;
  const btRigidBody *body = bt_body(k, b);
  if (!body) return;
  const btVector3 o = body->getCenterOfMassPosition();
  const double r[2] = {x[0] - o[0], x[1] - o[1]};
  const double th = h * body->getAngularVelocity()[2];
  const double cm1 = cos(th) - 1.0, sw = sin(th) - th;
  out[0] = cm1 * r[0] - sw * r[1];
  out[1] = cm1 * r[1] + sw * r[0];
}

/* the frame at world point at [m] turned to the axis, seen from body b
 * (the world's for the ground) */
btTransform frame_in(const btRigidBody *b, const double at[2], const double axis[2]) {
  btTransform f;
  f.setIdentity();
  f.setOrigin(btVector3(at[0], at[1], 0));
  f.setRotation(btQuaternion(btVector3(0, 0, 1), atan2(axis[1], axis[0])));
  return b ? b->getCenterOfMassTransform().inverse() * f : f;
}


fb_status world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  if (o->nbodies > FB_PLANAR_SPEC_MAX_BODIES || o->njoints > FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_ARG, "the Bullet kit builds at most %d bodies and %d joints",
                       FB_PLANAR_SPEC_MAX_BODIES, FB_PLANAR_SPEC_MAX_JOINTS);
  const fb_bullet_opts bo = o->c ? o->c->bullet : fb_bullet_opts_default();
  const fb_status st = fb_bullet_opts_check(&bo, diag);
  if (st != FB_OK) return st;
  Kit *k = new (std::nothrow) Kit();
  if (!k) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Bullet world");
  try {
    k->w = new FbBtWorld(bo.solver, bo.iterations, o->gravity);
  } catch (const std::bad_alloc &) {
    delete k;
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Bullet world");
  }
  k->h = o->h;
  k->erp = o->solver->world_erp;
  k->fmax = o->solver->drive_torque_max;
  *out = k;
  return FB_OK;
}

fb_status add_body(void *w, const fb_kit_body *b, fb_diag *diag) {
  (void)diag;
  Kit *k = static_cast<Kit *>(w);
  btRigidBody *r = k->w->body(b->mass, btVector3(0.5 * b->inertia, 0.5 * b->inertia, b->inertia));
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(b->pos[0], b->pos[1], 0));
  t.setRotation(btQuaternion(btVector3(0, 0, 1), b->pos[2]));
  r->setCenterOfMassTransform(t);
  r->setLinearVelocity(btVector3(b->vel[0], b->vel[1], 0));
  r->setAngularVelocity(btVector3(0, 0, b->vel[2]));
  k->body[k->nbodies++] = r;
  return FB_OK;
}

fb_status add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag) {
  (void)diag;
  Kit *k = static_cast<Kit *>(w);
  Joint &j = k->joint[k->njoints++];
  j.b0 = b0;
  j.b1 = b1;
  const int a = b0 == FB_KIT_GROUND ? b1 : b0; /* the moving body is A */
  j.a = bt_body(k, a);
  j.b = bt_body(k, a == b0 ? b1 : b0);
  const btVector3 p(at[0], at[1], 0);
  j.la = j.a->getCenterOfMassTransform().inverse() * p;
  j.lb = j.b ? j.b->getCenterOfMassTransform().inverse() * p : p;
  j.pin = rows_between(k, a, a == b0 ? b1 : b0);
  j.pin->nrows = 2;
  j.pin->setJointFeedback(&j.fb);
  j.pin->enableFeedback(true);
  k->w->add(j.pin);
  return FB_OK;
}

fb_status add_prismatic(void *w, int b0, int b1, const double at[2], const double axis[2],
                        fb_diag *diag) {
  (void)diag;
  Kit *k = static_cast<Kit *>(w);
  Joint &j = k->joint[k->njoints++];
  j.b0 = b0;
  j.b1 = b1;
  /* the slider (body[1], or body[0] on a ground slide) is free in 3-D, its
   * guide on the other body (or the world) */
  const int s = b1 == FB_KIT_GROUND ? b0 : b1, g = s == b1 ? b0 : b1;
  btRigidBody *slider = bt_body(k, s), *on = bt_body(k, g);
  slider->setLinearFactor(btVector3(1, 1, 1));
  slider->setAngularFactor(btVector3(1, 1, 1));
  const btTransform fs = frame_in(slider, at, axis);
  j.guide = fb_bt_slider(on, frame_in(on, at, axis), *slider, fs, k->erp);
  j.ls = fs.getOrigin();
  j.guide->setJointFeedback(&j.fb);
  j.guide->enableFeedback(true);
  k->w->add(j.guide);
  return FB_OK;
}

fb_status add_drive(void *w, int joint, double rate, fb_diag *diag) {
  Kit *k = static_cast<Kit *>(w);
  if (joint < 0) return FB_OK; /* undriven (kit.h): nothing to drive */
  const Joint &j = k->joint[joint];
  if (!j.pin) return fb_diag_set(diag, FB_ERR_ARG, "the Bullet kit drives a revolute joint only");
  /* body[1]'s rate relative to body[0]'s; the ground's body[1] is body[0]'s
   * at -rate */
  k->drive = j.b1 == FB_KIT_GROUND ? rows_between(k, j.b0, j.b1) : rows_between(k, j.b1, j.b0);
  fb_bt_drive_row(k->drive, j.b1 == FB_KIT_GROUND ? -rate : rate, k->fmax, k->h);
  k->drive->setJointFeedback(&k->drive_fb);
  k->drive->enableFeedback(true);
  k->drive_joint = joint;
  k->w->add(k->drive);
  return FB_OK;
}

/* contact slot j's row between the pin's and the hole's bodies (the hole
 * is A when the pin is the ground's), made once and kept in the world */
void make_row(Kit *k, int j, int pin, int hole) {
  Contact &ct = k->contact[j];
  if (ct.row) return;
  ct.row = pin == FB_KIT_GROUND ? rows_between(k, hole, pin) : rows_between(k, pin, hole);
  ct.row->nrows = 0;
  k->w->add(ct.row);
  k->used[k->nused++] = j;
}

/* a revolute clearance joint's row made in the joint's place among the
 * constraints, as the hand-built four-bar's (bullet_scene.cpp): Bullet's
 * solver takes its rows in that order (a slider's corners get theirs at
 * their first contact) */
fb_status add_clearance(void *w, int j, const fb_kit_clearance_joint *c, fb_diag *diag) {
  (void)diag;
  if (c->kind == FB_KIND_REVOLUTE) make_row(static_cast<Kit *>(w), j, c->pin, c->hole);
  return FB_OK;
}

/* the four-bar's clearance row (bullet_scene.cpp): the law's row of the
 * step at the effective mass, on the hole wall, along -n into the pin (the
 * hole is A, along +n, when the pin is the ground's) */
fb_status add_contact(void *w, int j, const fb_kit_contact *c, fb_diag *diag) {
  (void)diag;
  Kit *k = static_cast<Kit *>(w);
  Contact &ct = k->contact[j];
  const int ground_pin = c->pin == FB_KIT_GROUND;
  make_row(k, j, c->pin, c->hole);
  fb_contact_row u = c->row; /* the kit's, when it mapped the law already */
  if (!c->has_row && fb_contact_row_step(&u, &c->law, c->mapping, c->h, c->m_eff, 1, c->depth,
                                         c->rate, c->v0, c->onset, c->persistence) != FB_OK)
    return FB_OK; /* no row at this state (contact.h) */
  if (c->mapping == FB_MAPPING_MATCHED_STATIC && u.erp > 0.0 && !c->wall) {
    /* the penetration's drift over the step the row cannot see (rotation of
     * both points, curvature of the circle; contact.h), as ODE's binding */
    double dp[2], dq[2];
    point_drift(k, c->pin, c->centre[0], c->h, dp);
    point_drift(k, c->hole, c->centre[1], c->h, dq);
    const double e[2] = {c->centre[0][0] - c->centre[1][0], c->centre[0][1] - c->centre[1][1]};
    u.depth += fb_contact_step_drift(c->normal, dp, dq, c->ecc_rate, hypot(e[0], e[1]), c->h) /
               u.erp;
  }
  const double s = ground_pin ? 1.0 : -1.0;
  ct.share = u.step_share;
  fb_bt_contact_row(ct.row, btVector3(s * c->normal[0], s * c->normal[1], 0),
                    btVector3(c->point[0], c->point[1], 0), u.erp, u.depth, u.cfm, c->h);
  return FB_OK;
}

double contact_force(const void *w, int j) {
  return static_cast<const Kit *>(w)->contact[j].force;
}

fb_status step(void *w, fb_diag *diag) {
  Kit *k = static_cast<Kit *>(w);
  for (int i = 0; i < k->njoints; i++) {
    Joint &j = k->joint[i];
    if (j.pin)
      fb_bt_pin_rows(j.pin, fb_bt_world_point(j.a, j.la), fb_bt_world_point(j.b, j.lb), k->erp,
                     k->h);
    if (j.guide) { /* the lever the guide's feedback torque is about, at the step's start */
      const btRigidBody *r = bt_body(k, j.b1 == FB_KIT_GROUND ? j.b0 : j.b1);
      const btVector3 g = r->getCenterOfMassPosition(), p = fb_bt_world_point(r, j.ls);
      j.lever[0] = g[0] - p[0];
      j.lever[1] = g[1] - p[1];
    }
  }
  if (k->w->step(k->h))
    return fb_diag_set(diag, FB_ERR_NUMERIC, "bullet: the Dantzig MLCP solve failed at t = %.6g s "
                       "(step %zu); [bullet] solver = sequential-impulse runs the iterative "
                       "solver on purpose", (double)k->steps * k->h, k->steps + 1);
  k->steps++;
  for (int u = 0; u < k->nused; u++) {
    Contact &ct = k->contact[k->used[u]];
    ct.force = ct.row->nrows ? ct.share * ct.row->getAppliedImpulse() / k->h : 0.0;
    ct.row->nrows = 0; /* until the kit hands the next step's contact */
  }
  return FB_OK;
}

/* ideal joint i's reaction over the last step (kit.h): the force on its
 * body[1] from its body[0], and the moment about the joint's point on
 * body[1] (body[0]'s when body[1] is the ground). A pin's rows act at the
 * pin: its moment is the drive's torque on the driven joint, else 0. A
 * guide's feedback on its slider (B) is a force and a torque about the
 * slider's centre G: about the point P, T + (G - P) x F. Each taken with
 * the sign of the side asked. */
void reactions(const void *w, int i, double out[3]) {
  const Kit *k = static_cast<const Kit *>(w);
  const Joint &j = k->joint[i];
  out[0] = out[1] = out[2] = 0.0;
  if (j.pin) {
    /* the rows' A is the moving body: body[0] unless it is the ground */
    const double s = j.b0 == FB_KIT_GROUND ? 1.0 : -1.0;
    out[0] = s * j.fb.m_appliedForceBodyA[0];
    out[1] = s * j.fb.m_appliedForceBodyA[1];
    if (i == k->drive_joint) /* the drive row's A: body[1], or body[0] on the ground */
      out[2] = (j.b1 == FB_KIT_GROUND ? -1.0 : 1.0) * k->drive_fb.m_appliedTorqueBodyA[2];
    return;
  }
  const btVector3 &f = j.fb.m_appliedForceBodyB, &t = j.fb.m_appliedTorqueBodyB;
  const double s = j.b1 == FB_KIT_GROUND ? -1.0 : 1.0; /* the slider is body[1] unless ground */
  out[0] = s * f[0];
  out[1] = s * f[1];
  out[2] = s * (t[2] + j.lever[0] * f[1] - j.lever[1] * f[0]);
}

void body_state(const void *w, int b, double pos[3], double vel[3]) {
  const btRigidBody *r = static_cast<const Kit *>(w)->body[b];
  const btVector3 &p = r->getCenterOfMassPosition(), &v = r->getLinearVelocity();
  pos[0] = p[0];
  pos[1] = p[1];
  pos[2] = fb_bt_body_angle(r);
  vel[0] = v[0];
  vel[1] = v[1];
  vel[2] = r->getAngularVelocity()[2];
}

/* cos and sin of the body's angle as Bullet holds it: its basis's first
 * column, the atan2 body_state takes (fb_bt_body_angle) */
void body_rotation(const void *w, int b, double cs[2]) {
  const btMatrix3x3 &R = static_cast<const Kit *>(w)->body[b]->getCenterOfMassTransform().getBasis();
  cs[0] = R[0][0];
  cs[1] = R[1][0];
}

// the force at the body's centre of mass and the torque for the coming
// step: stepSimulation clears both after it (clearForces)
void apply_wrench(void *w, int b, const double f[3]) {
  btRigidBody *r = static_cast<Kit *>(w)->body[b];
  r->applyCentralForce(btVector3(f[0], f[1], 0.0));
  r->applyTorque(btVector3(0.0, 0.0, f[2]));
}

void world_free(void *w) {
  Kit *k = static_cast<Kit *>(w);
  btDiscreteDynamicsWorld &world = k->w->world;
  btTypedConstraint *c[FB_PLANAR_SPEC_MAX_JOINTS + FB_KIT_SLOTS + 1];
  int n = 0;
  for (int i = 0; i < k->njoints; i++)
    c[n++] = k->joint[i].pin ? static_cast<btTypedConstraint *>(k->joint[i].pin)
                             : k->joint[i].guide;
  for (int i = 0; i < FB_KIT_SLOTS; i++)
    if (k->contact[i].row) c[n++] = k->contact[i].row;
  if (k->drive) c[n++] = k->drive;
  for (int i = 0; i < n; i++) world.removeConstraint(c[i]), delete c[i];
  for (int i = 0; i < k->nbodies; i++) world.removeRigidBody(k->body[i]), delete k->body[i];
  delete k->w;
  delete k;
}

/* the binding (kit.h): every body planar by Bullet's factors (no
 * hold_in_plane), the loops closed by the pins' rows (no close_loop); a
 * member kit.h adds later stays NULL */
constexpr fb_kit_binding binding() {
  fb_kit_binding b = {};
  b.engine = "bullet";
  b.world_new = world_new;
  b.add_body = add_body;
  b.add_revolute = add_revolute;
  b.add_prismatic = add_prismatic;
  b.add_drive = add_drive;
  b.add_contact = add_contact;
  b.add_clearance = add_clearance;
  b.contact_force = contact_force;
  b.step = step;
  b.body_state = body_state;
  b.world_free = world_free;
  b.contact_rows = 1;
  b.apply_wrench = apply_wrench;
  b.reactions = reactions;
  b.body_rotation = body_rotation;
  return b;
}

}  // namespace

extern "C" const fb_kit_binding fb_bullet_kit = binding();
