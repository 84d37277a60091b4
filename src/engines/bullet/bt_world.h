/* C++, private to src/engines/bullet: the Bullet world every build of a
 * mechanism in this folder uses (the four-bar's and slider-crank's scene,
 * bullet_scene.cpp; the engine kit's binding, bullet_kit.cpp): the world
 * without collision pairs and its solver, a planar body, the rows of an
 * ideal pin, of the drive and of a clearance joint's soft contact, the
 * slider guide, and one step that says when the MLCP fell back. Included
 * only by the .cpp files of this folder. SI throughout. */
#ifndef FB_BT_WORLD_H
#define FB_BT_WORLD_H

#include <math.h>

#include "bt_rows.h"
extern "C" {
#include "opts_bullet.h"
}

/* the solver the options ask for: btMLCPSolver with btDantzigSolver
 * (FB_BULLET_MLCP_DANTZIG) or sequential impulse, both with soft rows */
struct FbBtSolver {
  btDantzigSolver dantzig;
  btConstraintSolver *s = nullptr;
  FbMlcp *mlcp = nullptr; /* s when it is the MLCP */
  explicit FbBtSolver(int kind) {
    if (kind == FB_BULLET_MLCP_DANTZIG)
      s = mlcp = new FbMlcp(&dantzig);
    else
      s = new FbSequentialImpulse();
  }
  ~FbBtSolver() { delete s; }
};

/* a world without collision pairs: gravity g [m/s^2] along -y, the
 * solver's iterations, global CFM 0, one island solved at once */
struct FbBtWorld {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  FbBtSolver solver;
  btDiscreteDynamicsWorld world;
  btEmptyShape shape;
  FbBtWorld(int kind, int iterations, double g)
      : solver(kind), world(&dispatcher, &broadphase, solver.s, &config) {
    world.setGravity(btVector3(0, -g, 0));
    btContactSolverInfo &info = world.getSolverInfo();
    info.m_numIterations = iterations;
    info.m_globalCfm = 0.0;
    info.m_minimumSolverBatchSize = 1; /* one island, one solve */
    info.m_leastSquaresResidualThreshold = 0.0;
  }
  /* a planar body of mass m [kg] and principal moments [kg m^2] on its (x,
   * y, z): linear factor (1, 1, 0), angular (0, 0, 1); planar 0: a body
   * free in 3-D (a slider, which its guide holds) */
  btRigidBody *body(double m, const btVector3 &inertia, bool planar = true) {
    btRigidBody::btRigidBodyConstructionInfo ci(m, nullptr, &shape, inertia);
    btRigidBody *b = new btRigidBody(ci);
    if (planar) {
      b->setLinearFactor(btVector3(1, 1, 0));
      b->setAngularFactor(btVector3(0, 0, 1));
    }
    b->setFlags(0); /* no gyroscopic term: planar rotation about a principal axis */
    b->setDamping(0, 0);
    b->setSleepingThresholds(0, 0);
    b->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(b, 0, 0); /* no collision group: never a contact pair */
    return b;
  }
  void add(btTypedConstraint *c) { world.addConstraint(c, true); }
  /* one step of exactly h [s]; returns 1 when btMLCPSolver's Dantzig solve
   * failed and it fell back to sequential impulse (the step is then not
   * the direct solver's) */
  int step(double h) {
    const int before = solver.mlcp ? solver.mlcp->getNumFallbacks() : 0;
    world.stepSimulation(h, 0, h);
    return solver.mlcp && solver.mlcp->getNumFallbacks() > before;
  }
};

/* a body's point in the world from its local one (b nullptr: the ground,
 * local is the world point) [m] */
static inline btVector3 fb_bt_world_point(const btRigidBody *b, const btVector3 &local) {
  return b ? b->getCenterOfMassTransform() * local : local;
}

/* the velocity of body b's point p (world) [m/s]; 0 for the ground */
static inline btVector3 fb_bt_point_velocity(const btRigidBody *b, const btVector3 &p) {
  if (!b) return btVector3(0, 0, 0);
  return b->getLinearVelocity() + b->getAngularVelocity().cross(p - b->getCenterOfMassPosition());
}

/* a planar body's frame angle about +z [rad] in (-pi, pi] */
static inline double fb_bt_body_angle(const btRigidBody *b) {
  const btMatrix3x3 &R = b->getCenterOfMassTransform().getBasis();
  return atan2(R[1][0], R[0][0]);
}

/* the two rows of an ideal pin at body A's point pa and body B's pb
 * (world) [m]: J v = d(pa - pb)/dt along x and y closes the gap at the
 * rate erp / h, hard (CFM 0), unbounded */
static inline void fb_bt_pin_rows(FbRows *rows, const btVector3 &pa, const btVector3 &pb,
                                  double erp, double h) {
  for (int k = 0; k < 2; k++) {
    FbRow &r = rows->row[k];
    r.n = btVector3(k == 0, k == 1, 0);
    r.p = pa;
    r.angular = 0;
    r.rhs = erp * (pb[k] - pa[k]) / h;
    r.cfm_h = 0.0;
    r.lo = -SIMD_INFINITY;
    r.hi = SIMD_INFINITY;
  }
  rows->nrows = 2;
}

/* the drive's row: A's angular velocity about +z relative to B's held at
 * rate [rad/s], its impulse limited to fmax h (fmax the torque limit
 * [N m]), as ODE's hinge velocity motor */
static inline void fb_bt_drive_row(FbRows *rows, double rate, double fmax, double h) {
  FbRow &r = rows->row[0];
  r.n = btVector3(0, 0, 1);
  r.angular = 1;
  r.rhs = rate;
  r.cfm_h = 0.0;
  r.lo = -fmax * h;
  r.hi = fmax * h;
  rows->nrows = 1;
}

/* a clearance contact's one unilateral soft row: normal N (unit, pushes
 * A) at world point p [m], target J v_{n+1} = erp depth / h - (cfm / h)
 * lambda (the law's row of the step, contact.h), lambda >= 0 */
static inline void fb_bt_contact_row(FbRows *rows, const btVector3 &N, const btVector3 &p,
                                     double erp, double depth, double cfm, double h) {
  FbRow &r = rows->row[0];
  r.n = N;
  r.p = p;
  r.angular = 0;
  r.rhs = erp * depth / h;
  r.cfm_h = cfm / h;
  r.lo = 0.0;
  r.hi = SIMD_INFINITY;
  rows->nrows = 1;
}

/* a slider guide holding body b along its frame's x axis (frame: in b's
 * own frame; the guide's line is where that axis lies now in the world):
 * btSliderConstraint, Bullet's prismatic joint, its ERP erp on every axis,
 * CFM 0. a non-null: the guide is on body a, frame_a its frame in a. */
static inline btSliderConstraint *fb_bt_slider(btRigidBody *a, const btTransform &frame_a,
                                               btRigidBody &b, const btTransform &frame,
                                               double erp) {
  btSliderConstraint *s = a ? new btSliderConstraint(*a, b, frame_a, frame, true)
                            : new btSliderConstraint(b, frame, true);
  for (int axis = 0; axis < 6; axis++) s->setParam(BT_CONSTRAINT_STOP_ERP, erp, axis);
  return s;
}

#endif
