/* The ideal four-bar in ODE, bare: three bodies, four hinges about +z, a
 * velocity motor on the ground-crank hinge, dWorldStep at a fixed h; every
 * step's angles, angular velocities, angular accelerations (omega change
 * over the step), the drive torque and the joint reactions (dJointFeedback)
 * kept. ODE's API only (manual: "Joint feedback", "Hinge", dWorldStep);
 * settings and output: peer.h. Extra arguments: erp cfm fmax stepper (world,
 * quick) iterations. */
#include <ode/ode.h>

#include "peer.h"

/* a link body from joint point p along angle th, turning at w, the joint
 * point moving at vp */
static dBodyID link_body(dWorldID w, const peer_fourbar *f, int k, const double p[2], double th,
                         double om, const double vp[2]) {
  dBodyID b = dBodyCreate(w);
  dMass m;
  dMassSetParameters(&m, f->mass[k], 0, 0, 0, f->inertia_long[k], f->inertia_transverse[k],
                     f->inertia[k], 0, 0, 0);
  dBodySetMass(b, &m);
  const double len = f->len[k];
  const double rx = f->com[k] * len * cos(th), ry = f->com[k] * len * sin(th);
  dBodySetPosition(b, p[0] + rx, p[1] + ry, 0);
  dMatrix3 R;
  dRFromAxisAndAngle(R, 0, 0, 1, th);
  dBodySetRotation(b, R);
  dBodySetLinearVel(b, vp[0] - om * ry, vp[1] + om * rx, 0);
  dBodySetAngularVel(b, 0, 0, om);
  return b;
}

static double angle_of(dBodyID b) {
  const dReal *R = dBodyGetRotation(b);
  return atan2(R[4], R[0]);
}

int main(int argc, char **argv) {
  peer_args a;
  peer_fourbar f;
  peer_start(&a, &f, argc, argv);
  const double erp = peer_num(&a, "erp"), cfm = peer_num(&a, "cfm"), fmax = peer_num(&a, "fmax");
  const int quick = strcmp(peer_str(&a, "stepper"), "quick") == 0;
  const int iterations = (int)peer_num(&a, "iterations");
  const double t0 = peer_clock();
  dInitODE2(0);
  dWorldID w = dWorldCreate();
  dWorldSetGravity(w, 0, -f.gravity, 0);
  dWorldSetERP(w, erp);
  dWorldSetCFM(w, cfm);
  dWorldSetQuickStepNumIterations(w, iterations);
  const double A[2] = {0, 0}, D[2] = {f.len[3], 0};
  const double B[2] = {f.len[0] * cos(f.th2), f.len[0] * sin(f.th2)};
  const double C[2] = {D[0] + f.len[2] * cos(f.th4), D[1] + f.len[2] * sin(f.th4)};
  const double zero[2] = {0, 0}, vb[2] = {-f.omega2 * B[1], f.omega2 * B[0]};
  dBodyID body[3];
  body[0] = link_body(w, &f, 0, A, f.th2, f.omega2, zero);
  body[1] = link_body(w, &f, 1, B, f.th3, f.w3, vb);
  body[2] = link_body(w, &f, 2, D, f.th4, f.w4, zero);
  const double *anchor[4] = {A, B, C, D};
  dBodyID b1[4] = {body[0], body[0], body[1], body[2]}, b2[4] = {0, body[1], body[2], 0};
  dJointID hinge[4];
  dJointFeedback fb[4];
  for (int j = 0; j < 4; j++) {
    hinge[j] = dJointCreateHinge(w, 0);
    dJointAttach(hinge[j], b1[j], b2[j]);
    dJointSetHingeAnchor(hinge[j], anchor[j][0], anchor[j][1], 0);
    dJointSetHingeAxis(hinge[j], 0, 0, 1);
    dJointSetFeedback(hinge[j], &fb[j]);
  }
  dJointSetHingeParam(hinge[0], dParamVel, f.omega2);
  dJointSetHingeParam(hinge[0], dParamFMax, fmax);
  peer_series s;
  peer_series_init(&s, f.steps + 1);
  double ang[3], om[3];
  for (int i = 0; i < 3; i++) ang[i] = angle_of(body[i]), om[i] = dBodyGetAngularVel(body[i])[2];
  double v[P_COLS] = {0};
  peer_bodies(v, 0.0, ang, om, NULL);
  peer_push(&s, v);
  const double t1 = peer_clock();
  for (long k = 1; k <= f.steps; k++) {
    const dReal *g = dBodyGetPosition(body[0]);
    const double ax = -g[0], ay = -g[1]; /* A - crank's centre of mass, before the step */
    if (quick) dWorldQuickStep(w, f.h);
    else dWorldStep(w, f.h);
    double al[3];
    for (int i = 0; i < 3; i++)
      peer_body_step(&ang[i], &om[i], &al[i], angle_of(body[i]), dBodyGetAngularVel(body[i])[2], f.h);
    peer_bodies(v, (double)k * f.h, ang, om, al);
    /* reactions on the second-named body; the motor's torque about the pivot */
    const int on2[4] = {0, 1, 1, 0};
    for (int j = 0; j < 4; j++) {
      const dReal *fj = on2[j] ? fb[j].f2 : fb[j].f1;
      v[P_RX + 2 * j] = fj[0];
      v[P_RX + 2 * j + 1] = fj[1];
    }
    v[P_TORQUE] = fb[0].t1[2] - (ax * v[P_RX + 1] - ay * v[P_RX]);
    peer_push(&s, v);
  }
  const double t2 = peer_clock();
  peer_report("ode", &s, f.steps, t1 - t0, t2 - t1, f.window);
  peer_series_free(&s);
  dWorldDestroy(w);
  dCloseODE();
  return 0;
}
