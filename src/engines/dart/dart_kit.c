/* DART as a binding of the engine kit (kit.h): any planar description in
 * DART 6.12 as its experts build a mechanism (dart_world.h): the bodies
 * and joints are collected as the kit walks them, and close_loop makes
 * the skeleton (a tree of RevoluteJoints about +z and PrismaticJoints,
 * each loop closed at a pin by a BallJointConstraint of DART's constraint
 * solver, whose out-of-plane row is redundant: DART's CFM, relative to
 * the row's diagonal, keeps the LCP solvable). DART's constraint settings
 * are its own defaults (global ERP 0.01, CFM 1e-9 of the diagonal, error
 * reduction velocity at most 10 m/s), not the case's ODE world ERP and
 * CFM. The drive is the driven joint's SERVO actuator, tracked by the
 * constraint solver within [solver] drive_torque_max_n_m. A clearance
 * joint's contact (the kit's pipeline, kit_contact.h) is the law's force,
 * fb_contact_force at the step's start, on the pin along -n and on the
 * hole along +n at the wall point, through DART's external force
 * (BodyNode::addExtForce), as MuJoCo's passive callback applies it. Each
 * step is World::step: semi-implicit Euler, the constraint impulses at
 * the velocity level. */
#include "dart_kit.h"

#include <stdlib.h>

#include "contact.h"
#include "dart_world.h"

static fb_status dart_error(fb_status st, const char *what, const char *err, fb_diag *diag) {
  return fb_diag_set(diag, st, "DART %s: %s", what, err);
}

static fb_status kit_world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  fb_dart_world *w = fb_dart_world_new(o->gravity, o->h, o->solver->world_erp,
                                       o->solver->drive_torque_max);
  if (!w) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the DART world");
  *out = w;
  return FB_OK;
}

static fb_status kit_add_body(void *w, const fb_kit_body *b, fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  if (fb_dart_add_body(w, b->mass, b->inertia, b->pos, b->vel, err, sizeof err) != 0)
    return dart_error(FB_ERR_NOMEM, "body", err, diag);
  return FB_OK;
}

static fb_status add_joint(void *w, int prismatic, int b0, int b1, const double at[2],
                           const double axis[2], fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  if (fb_dart_add_joint(w, prismatic, b0, b1, at, axis, err, sizeof err) != 0)
    return dart_error(FB_ERR_NOMEM, "joint", err, diag);
  return FB_OK;
}

static fb_status kit_add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag) {
  const double z[2] = {0.0, 0.0};
  return add_joint(w, 0, b0, b1, at, z, diag);
}

static fb_status kit_add_prismatic(void *w, int b0, int b1, const double at[2],
                                   const double axis[2], fb_diag *diag) {
  return add_joint(w, 1, b0, b1, at, axis, diag);
}

static fb_status kit_close_loop(void *w, fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  if (fb_dart_build(w, err, sizeof err) != 0) return dart_error(FB_ERR_ARG, "skeleton", err, diag);
  return FB_OK;
}

static fb_status kit_add_drive(void *w, int joint, double rate, fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  if (fb_dart_drive(w, joint, rate, err, sizeof err) != 0)
    return dart_error(FB_ERR_ARG, "drive", err, diag);
  return FB_OK;
}

/* the law's force at the step's start on the pin along -n, on the hole
 * along +n, at the hole wall's point */
static fb_status kit_add_contact(void *w, int k, const fb_kit_contact *c, fb_diag *diag) {
  (void)k;
  (void)diag;
  const double f = fb_contact_force(&c->law, c->depth, c->rate, c->v0);
  const double on_pin[2] = {-f * c->normal[0], -f * c->normal[1]};
  fb_dart_add_force(w, c->pin, c->hole, c->point, on_pin);
  return FB_OK;
}

static fb_status kit_step(void *w, fb_diag *diag) {
  char err[FB_DIAG_SIZE];
  if (fb_dart_step(w, err, sizeof err) != 0) return dart_error(FB_ERR_NUMERIC, "step", err, diag);
  return FB_OK;
}

static void kit_body_state(const void *w, int b, double pos[3], double vel[3]) {
  fb_dart_body_state(w, b, pos, vel);
}

static void kit_world_free(void *w) { fb_dart_world_free(w); }

const fb_kit_binding fb_dart_kit = {
    .engine = "dart",
    .world_new = kit_world_new,
    .add_body = kit_add_body,
    .add_revolute = kit_add_revolute,
    .add_prismatic = kit_add_prismatic,
    .close_loop = kit_close_loop,
    .add_drive = kit_add_drive,
    .hold_in_plane = NULL, /* DART's joints are planar: a free body is a PlanarJoint root */
    .add_contact = kit_add_contact,
    .contact_force = NULL, /* the law's force, as applied */
    .step = kit_step,
    .body_state = kit_body_state,
    .world_free = kit_world_free,
};
