#include "scene.h"

#include <math.h>
#include <ode/ode.h>
#include <stdio.h>
#include <stdlib.h>

#include "ode_env.h"

struct fb_scene {
  fb_scene_def def;
  dWorldID world;
  dBodyID body[3];   /* crank, coupler, follower */
  dJointID hinge[4]; /* A (ground-crank, driven), B, C, D */
  dJointFeedback feedback[4];
  double crank_com_before[2]; /* crank centre of mass at the start of the last step */
  size_t steps;
  double angle[3];     /* unwrapped angles [rad] */
  double omega_prev[3];
  double alpha[3];
};

/* sets a link body between joint points p and q, COM at fraction f */
static void place_body(dBodyID b, const fb_link_mass *lm, const double p[2], const double q[2],
                       double omega, const double vp[2]) {
  double dx = q[0] - p[0], dy = q[1] - p[1];
  double phi = atan2(dy, dx);
  double rx = lm->com_fraction * dx, ry = lm->com_fraction * dy;
  dMass m;
  /* body frame: x along the link, z the hinge axis */
  dMassSetParameters(&m, lm->mass, 0, 0, 0, lm->inertia_long, lm->inertia_transverse,
                     lm->inertia, 0, 0, 0);
  dBodySetMass(b, &m);
  dBodySetPosition(b, p[0] + rx, p[1] + ry, 0.0);
  dMatrix3 R;
  dRFromAxisAndAngle(R, 0, 0, 1, phi);
  dBodySetRotation(b, R);
  dBodySetLinearVel(b, vp[0] - omega * ry, vp[1] + omega * rx, 0.0);
  dBodySetAngularVel(b, 0, 0, omega);
}

static double body_angle(dBodyID b) {
  const dReal *R = dBodyGetRotation(b);
  return atan2(R[4], R[0]);
}

fb_status fb_scene_create(fb_scene **out, const fb_scene_def *def, fb_diag *diag) {
  fb_linkage_state st;
  fb_status rc = fb_linkage_solve(&st, &def->lengths, def->branch, def->crank_angle0,
                                  def->omega2, 0.0, diag);
  if (rc != FB_OK) return rc;
  fb_scene *s = calloc(1, sizeof *s);
  if (!s) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the scene");
  fb_ode_acquire();
  s->def = *def;
  s->world = dWorldCreate();
  dWorldSetGravity(s->world, 0, -def->gravity, 0);
  dWorldSetERP(s->world, def->solver.world_erp);
  dWorldSetCFM(s->world, def->solver.world_cfm);
  dWorldSetQuickStepNumIterations(s->world, def->solver.quick_iterations);
  dRandSetSeed(def->solver.seed);

  const double a0[2] = {0, 0};
  const double d0[2] = {def->lengths.length[FB_GROUND], 0};
  const double zero[2] = {0, 0};
  const double vb[2] = {-def->omega2 * st.b[1], def->omega2 * st.b[0]};
  for (int i = 0; i < 3; i++) s->body[i] = dBodyCreate(s->world);
  place_body(s->body[FB_CRANK], &def->link[FB_CRANK], a0, st.b, def->omega2, zero);
  place_body(s->body[FB_COUPLER], &def->link[FB_COUPLER], st.b, st.c, st.coupler_omega, vb);
  place_body(s->body[FB_FOLLOWER], &def->link[FB_FOLLOWER], d0, st.c, st.follower_omega, zero);

  const dBodyID b1[4] = {s->body[FB_CRANK], s->body[FB_CRANK], s->body[FB_COUPLER],
                         s->body[FB_FOLLOWER]};
  const dBodyID b2[4] = {0, s->body[FB_COUPLER], s->body[FB_FOLLOWER], 0};
  const double *anchor[4] = {a0, st.b, st.c, d0};
  for (int j = 0; j < 4; j++) {
    s->hinge[j] = dJointCreateHinge(s->world, 0);
    dJointAttach(s->hinge[j], b1[j], b2[j]);
    dJointSetHingeAnchor(s->hinge[j], anchor[j][0], anchor[j][1], 0.0);
    dJointSetHingeAxis(s->hinge[j], 0, 0, 1);
    dJointSetFeedback(s->hinge[j], &s->feedback[j]);
  }
  /* the drive: velocity motor on the ground-crank hinge */
  dJointSetHingeParam(s->hinge[0], dParamVel, def->omega2);
  dJointSetHingeParam(s->hinge[0], dParamFMax, def->solver.drive_torque_max);

  for (int i = 0; i < 3; i++) {
    s->angle[i] = body_angle(s->body[i]);
    s->omega_prev[i] = dBodyGetAngularVel(s->body[i])[2];
    s->alpha[i] = 0.0;
  }
  *out = s;
  return FB_OK;
}

fb_status fb_scene_step(fb_scene *s, fb_diag *diag) {
  const double h = s->def.solver.h;
  const dReal *g1 = dBodyGetPosition(s->body[FB_CRANK]);
  s->crank_com_before[0] = g1[0];
  s->crank_com_before[1] = g1[1];
  int ok = s->def.solver.stepper == FB_STEPPER_WORLD ? dWorldStep(s->world, h)
                                                     : dWorldQuickStep(s->world, h);
  if (!ok)
    return fb_diag_set(diag, FB_ERR_NOMEM, "ODE could not allocate memory for step %zu",
                       s->steps + 1);
  s->steps++;
  for (int i = 0; i < 3; i++) {
    double w = dBodyGetAngularVel(s->body[i])[2];
    s->alpha[i] = (w - s->omega_prev[i]) / h;
    s->omega_prev[i] = w;
    double a = body_angle(s->body[i]);
    double prev = s->angle[i];
    double d = remainder(a - prev, 2.0 * M_PI);
    s->angle[i] = prev + d;
  }
  return FB_OK;
}

void fb_scene_sample(const fb_scene *s, fb_sample *x) {
  x->t = (double)s->steps * s->def.solver.h;
  x->crank_angle = s->angle[FB_CRANK];
  x->coupler_angle = s->angle[FB_COUPLER];
  x->coupler_omega = s->omega_prev[FB_COUPLER];
  x->coupler_alpha = s->alpha[FB_COUPLER];
  x->follower_angle = s->angle[FB_FOLLOWER];
  x->follower_omega = s->omega_prev[FB_FOLLOWER];
  x->follower_alpha = s->alpha[FB_FOLLOWER];
}

double fb_scene_joint_drift(const fb_scene *s) {
  double worst = 0.0;
  for (int j = 0; j < 4; j++) {
    dVector3 p1, p2;
    dJointGetHingeAnchor(s->hinge[j], p1);
    dJointGetHingeAnchor2(s->hinge[j], p2);
    double d = sqrt((p1[0] - p2[0]) * (p1[0] - p2[0]) + (p1[1] - p2[1]) * (p1[1] - p2[1]) +
                    (p1[2] - p2[2]) * (p1[2] - p2[2]));
    if (d > worst) worst = d;
  }
  return worst;
}

void fb_scene_reactions(const fb_scene *s, double force[4][2], double *drive_torque) {
  if (s->steps == 0) {
    for (int j = 0; j < 4; j++) force[j][0] = force[j][1] = 0.0;
    *drive_torque = 0.0;
    return;
  }
  /* A: on the crank (body 1); B: on the coupler (body 2); C: on the follower
   * (body 2); D: on the follower (body 1) */
  const int on_body2[4] = {0, 1, 1, 0};
  for (int j = 0; j < 4; j++) {
    const dReal *f = on_body2[j] ? s->feedback[j].f2 : s->feedback[j].f1;
    force[j][0] = f[0];
    force[j][1] = f[1];
  }
  /* ODE's torque is about the crank's centre of mass; move it to the pivot */
  const double r[2] = {-s->crank_com_before[0], -s->crank_com_before[1]}; /* A - G */
  *drive_torque = s->feedback[0].t1[2] - (r[0] * force[0][1] - r[1] * force[0][0]);
}

size_t fb_scene_steps(const fb_scene *s) { return s->steps; }

void fb_scene_destroy(fb_scene *s) {
  if (!s) return;
  dWorldDestroy(s->world);
  free(s);
  fb_ode_release();
}
