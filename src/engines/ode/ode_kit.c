/* ODE as a binding of the engine kit (kit.h): any planar description in
 * ODE as the four-bar world (ode_world.c) builds its own. A body is an ODE
 * rigid body (its moment about +z the description's; about its in-plane
 * axes half of it each, a thin plate's, which no planar motion excites);
 * a revolute joint is a hinge about +z (dJointCreateHinge), a prismatic
 * one a slider joint along its axis (dJointCreateSlider); the loops close
 * through the joints themselves (3-D hinges over-constrain a planar loop
 * by three rows each; the world CFM absorbs them, as in the four-bar); the
 * drive is the driven hinge's velocity motor (dParamVel, dParamFMax =
 * [solver] drive_torque_max_n_m). A clearance joint (kit.h's pipeline
 * computes its contact) is ODE's soft contact row as the exact collider
 * makes it (ode_clearance.c): the law mapped at the effective mass to ERP
 * and CFM (ode_contact.h), the matched-static row's drift correction, on
 * the hole wall, Coulomb friction at [clearance] friction, its force read
 * back from the row's feedback. The world's ERP,
 * CFM, stepper (dWorldStep or dWorldQuickStep with its iterations) and
 * seed are the case's [solver] keys, gravity along -y; each step runs
 * under ODE's fatal-error escape (ode_env.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ode/ode.h>

#include "kit.h"
#include "ode_contact.h"
#include "ode_env.h"
#include "ode_kit.h"
#include "planar_spec.h"

typedef struct {
  dWorldID world;
  dBodyID *body;   /* (nbodies) */
  dJointID *joint; /* (njoints) */
  int nbodies, njoints;
  double h;
  fb_stepper stepper;
  double fmax;     /* drive torque limit [N m] */
  size_t steps;
  int broken;      /* an ODE error left the world mid-step */
  /* contacts by the kit's slot (kit.h: a pin's, or a slider's corner's):
   * this step's contact joint, its feedback, the share of its impulse that
   * is this step's (contact.h), the normal force of the last step [N] */
  dJointGroupID contacts;
  dJointID cj[FB_KIT_SLOTS];
  dJointFeedback fb[FB_KIT_SLOTS];
  double share[FB_KIT_SLOTS];
  double force[FB_KIT_SLOTS];
} ode_kit;

static fb_status kit_world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  ode_kit *k = calloc(1, sizeof *k);
  if (k) k->body = calloc((size_t)o->nbodies + 1, sizeof *k->body);
  if (k && k->body) k->joint = calloc((size_t)o->njoints + 1, sizeof *k->joint);
  if (!k || !k->body || !k->joint) {
    if (k) free(k->body);
    free(k);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the ODE world");
  }
  fb_ode_acquire();
  k->world = dWorldCreate();
  k->contacts = dJointGroupCreate(0);
  dWorldSetGravity(k->world, 0, -o->gravity, 0);
  dWorldSetERP(k->world, o->solver->world_erp);
  dWorldSetCFM(k->world, o->solver->world_cfm);
  dWorldSetQuickStepNumIterations(k->world, o->solver->quick_iterations);
  dRandSetSeed(o->solver->seed);
  k->h = o->h;
  k->stepper = o->solver->stepper;
  k->fmax = o->solver->drive_torque_max;
  *out = k;
  return FB_OK;
}

static fb_status kit_add_body(void *w, const fb_kit_body *b, fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dBodyID id = dBodyCreate(k->world);
  dMass m;
  dMassSetParameters(&m, b->mass, 0, 0, 0, 0.5 * b->inertia, 0.5 * b->inertia, b->inertia, 0, 0,
                     0);
  dBodySetMass(id, &m);
  dBodySetPosition(id, b->pos[0], b->pos[1], 0.0);
  dMatrix3 R;
  dRFromAxisAndAngle(R, 0, 0, 1, b->pos[2]);
  dBodySetRotation(id, R);
  dBodySetLinearVel(id, b->vel[0], b->vel[1], 0.0);
  dBodySetAngularVel(id, 0, 0, b->vel[2]);
  k->body[k->nbodies++] = id;
  return FB_OK;
}

/* ODE's body of a kit handle (0: the static environment) */
static dBodyID ode_body(const ode_kit *k, int b) { return b == FB_KIT_GROUND ? 0 : k->body[b]; }

/* attaches joint j: ODE wants the moving body first when one is the ground */
static void attach(ode_kit *k, dJointID j, int b0, int b1) {
  if (b1 == FB_KIT_GROUND) dJointAttach(j, ode_body(k, b0), 0);
  else dJointAttach(j, ode_body(k, b1), ode_body(k, b0));
  k->joint[k->njoints++] = j;
}

static fb_status kit_add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dJointID j = dJointCreateHinge(k->world, 0);
  attach(k, j, b0, b1);
  dJointSetHingeAnchor(j, at[0], at[1], 0.0);
  dJointSetHingeAxis(j, 0, 0, b1 == FB_KIT_GROUND ? -1 : 1);
  return FB_OK;
}

static fb_status kit_add_prismatic(void *w, int b0, int b1, const double at[2],
                                   const double axis[2], fb_diag *diag) {
  (void)at;
  (void)diag;
  ode_kit *k = w;
  dJointID j = dJointCreateSlider(k->world, 0);
  attach(k, j, b0, b1);
  const double s = b1 == FB_KIT_GROUND ? -1.0 : 1.0;
  dJointSetSliderAxis(j, s * axis[0], s * axis[1], 0.0);
  return FB_OK;
}

static fb_status kit_add_drive(void *w, int joint, double rate, fb_diag *diag) {
  ode_kit *k = w;
  if (joint < 0) return FB_OK; /* undriven (kit.h): nothing to drive */
  dJointID j = k->joint[joint];
  if (dJointGetType(j) != dJointTypeHinge)
    return fb_diag_set(diag, FB_ERR_ARG, "the ODE kit drives a revolute joint only");
  dJointSetHingeParam(j, dParamVel, rate);
  dJointSetHingeParam(j, dParamFMax, k->fmax);
  return FB_OK;
}

/* a body that only a clearance joint holds stays in the plane */
static fb_status kit_hold_in_plane(void *w, int b, fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dJointAttach(dJointCreatePlane2D(k->world, 0), k->body[b], 0);
  return FB_OK;
}

/* what ODE's position update adds to the displacement of the point at x
 * [m] of body handle b over a step of h [s] beyond the linear h (v + w x r)
 * a contact row sees: ODE turns the body by theta = 2 atan(h w / 2) (its
 * quaternion update, normalised), so the point at r from the centre of
 * mass moves by (cos theta - 1) r + (sin theta - h w) z x r more [m]
 * (w taken at the start of the step); 0 for the ground */
static void point_drift(const ode_kit *k, int b, const double x[2], double h, double out[2]) {
  out[0] = out[1] = 0.0;
  if (b == FB_KIT_GROUND) return;
  const dReal *o = dBodyGetPosition(k->body[b]);
  const double r[2] = {x[0] - o[0], x[1] - o[1]};
  const double w = dBodyGetAngularVel(k->body[b])[2];
  const double th = 2.0 * atan(0.5 * h * w);
  const double cm1 = -2.0 * sin(0.5 * th) * sin(0.5 * th), sw = sin(th) - h * w;
  out[0] = cm1 * r[0] - sw * r[1];
  out[1] = cm1 * r[1] + sw * r[0];
}

/* the exact collider's row as ode_clearance.c makes it: the law mapped to
 * one soft contact row (ode_contact.h) at the effective mass (the
 * matched-static row blended by the contact's persistence, its depth
 * carrying the step's drift that the row cannot see, contact.h's
 * fb_contact_step_drift), on the hole wall, its normal into the pin,
 * Coulomb friction mu with ODE's friction pyramid */
static fb_status kit_add_contact(void *w, int j, const fb_kit_contact *c, fb_diag *diag) {
  (void)diag;
  ode_kit *k = w;
  dContact ct;
  memset(&ct, 0, sizeof ct);
  fb_contact_row used;
  if (!fb_ode_soft_contact(&ct, &c->law, c->mapping, c->h, c->m_eff, 1, c->depth, c->rate, c->v0,
                           c->onset, c->persistence, c->friction, &used))
    return FB_OK;
  if (c->mapping == FB_MAPPING_MATCHED_STATIC && used.erp > 0.0 && !c->wall) {
    /* the row's lambda = a d_n + b u: handing it d_n + drift / ERP makes its
     * b act on the penetration's true rate u + drift / h (contact.h) */
    double dp[2], dq[2];
    point_drift(k, c->pin, c->centre[0], c->h, dp);
    point_drift(k, c->hole, c->centre[1], c->h, dq);
    const double e[2] = {c->centre[0][0] - c->centre[1][0], c->centre[0][1] - c->centre[1][1]};
    ct.geom.depth = used.depth +
                    fb_contact_step_drift(c->normal, dp, dq, c->ecc_rate, hypot(e[0], e[1]), c->h) /
                        used.erp;
  }
  ct.geom.pos[0] = c->point[0];
  ct.geom.pos[1] = c->point[1];
  ct.geom.normal[0] = -c->normal[0];
  ct.geom.normal[1] = -c->normal[1];
  k->cj[j] = dJointCreateContact(k->world, k->contacts, &ct);
  dJointAttach(k->cj[j], ode_body(k, c->pin), ode_body(k, c->hole));
  dJointSetFeedback(k->cj[j], &k->fb[j]);
  k->share[j] = used.step_share;
  return FB_OK;
}

static double kit_contact_force(const void *w, int j) { return ((const ode_kit *)w)->force[j]; }

/* the contact forces the step left (on the pin, body 1 of each row) */
static void contact_forces(ode_kit *k) {
  for (int j = 0; j < FB_KIT_SLOTS; j++) {
    k->force[j] = k->cj[j] ? k->share[j] * hypot(k->fb[j].f1[0], k->fb[j].f1[1]) : 0.0;
    k->cj[j] = 0;
  }
  dJointGroupEmpty(k->contacts);
}

static fb_status kit_step(void *w, fb_diag *diag) {
  ode_kit *k = w;
  jmp_buf escape;
  if (setjmp(escape) != 0) {
    k->broken = 1;
    return fb_diag_set(diag, FB_ERR_NUMERIC, "ode-error: %s at t = %.6g s (step %zu)",
                       fb_ode_last_error(), (double)k->steps * k->h, k->steps + 1);
  }
  fb_ode_escape = &escape;
  const int ok = k->stepper == FB_STEPPER_WORLD ? dWorldStep(k->world, k->h)
                                                : dWorldQuickStep(k->world, k->h);
  fb_ode_escape = NULL;
  contact_forces(k);
  if (!ok)
    return fb_diag_set(diag, FB_ERR_NOMEM, "ODE could not allocate memory for step %zu",
                       k->steps + 1);
  k->steps++;
  return FB_OK;
}

static void kit_body_state(const void *w, int b, double pos[3], double vel[3]) {
  const ode_kit *k = w;
  const dReal *p = dBodyGetPosition(k->body[b]), *R = dBodyGetRotation(k->body[b]);
  const dReal *v = dBodyGetLinearVel(k->body[b]), *om = dBodyGetAngularVel(k->body[b]);
  pos[0] = p[0];
  pos[1] = p[1];
  pos[2] = atan2(R[4], R[0]);
  vel[0] = v[0];
  vel[1] = v[1];
  vel[2] = om[2];
}

static void kit_world_free(void *w) {
  ode_kit *k = w;
  if (k->broken) {
    fb_ode_quarantine(k->world); /* left mid-step: never touched again (ode_env.h) */
    fb_ode_quarantine(k->contacts);
  } else {
    dJointGroupDestroy(k->contacts);
    dWorldDestroy(k->world);
    fb_ode_release();
  }
  free(k->body);
  free(k->joint);
  free(k);
}

const fb_kit_binding fb_ode_kit = {
    .engine = "ode",
    .world_new = kit_world_new,
    .add_body = kit_add_body,
    .add_revolute = kit_add_revolute,
    .add_prismatic = kit_add_prismatic,
    .add_drive = kit_add_drive,
    .hold_in_plane = kit_hold_in_plane,
    .add_contact = kit_add_contact,
    .contact_force = kit_contact_force,
    .step = kit_step,
    .body_state = kit_body_state,
    .world_free = kit_world_free,
    .contact_rows = 1,
    .friction = 1,
};
