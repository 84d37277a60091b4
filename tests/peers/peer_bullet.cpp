// The ideal four-bar in Bullet 3.24 (double precision), bare: three rigid
// bodies kept in the plane (linear factor (1, 1, 0), angular (0, 0, 1)),
// each joint a planar pin of two rows (a btTypedConstraint: the joint points
// coincide in x and y, the position error closed at erp / h; the hinge's
// other three rows would act on nothing the bodies can move and make the
// direct solver's system singular), the crank's speed held by one angular
// row with its impulse limited to fmax h; btDiscreteDynamicsWorld with the
// MLCP (btDantzigSolver) or sequential impulse, stepSimulation(h, 0, h); the
// reactions from the rows' btJointFeedback, the drive torque from the
// drive row's applied impulse. Bullet's API only (Bullet user manual,
// "Constraints"; btTypedConstraint getInfo1/getInfo2); settings and output:
// peer.h. Extra arguments: solver (mlcp, si) iterations erp fmax.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>
#include <btBulletDynamicsCommon.h>
#pragma GCC diagnostic pop

#include "peer.h"

namespace {

// two rows (x, y) holding point pa of body A on point pb of body B (or a
// fixed world point), or one angular row holding A's speed about +z
class Rows : public btTypedConstraint {
 public:
  btVector3 pa, pb;   // the joint point in A's and in B's frame (world for the ground)
  bool ground = false, drive = false;
  double erp = 0.2, speed = 0.0, limit = 0.0;
  Rows(btRigidBody &a) : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, a) {}
  Rows(btRigidBody &a, btRigidBody &b) : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, a, b) {}
  void getInfo1(btConstraintInfo1 *info) override {
    info->m_numConstraintRows = drive ? 1 : 2;
    info->nub = 0;
  }
  void getInfo2(btConstraintInfo2 *info) override {
    const int s = info->rowskip;
    if (drive) {
      for (int k = 0; k < 3; k++) info->m_J1angularAxis[k] = k == 2;
      info->m_constraintError[0] = speed;
      info->m_lowerLimit[0] = -limit;
      info->m_upperLimit[0] = limit;
      return;
    }
    const btVector3 wa = m_rbA.getCenterOfMassTransform() * pa;
    const btVector3 wb = ground ? pb : m_rbB.getCenterOfMassTransform() * pb;
    const btVector3 ra = wa - m_rbA.getCenterOfMassPosition();
    const btVector3 rb = wa - m_rbB.getCenterOfMassPosition();
    for (int r = 0; r < 2; r++) {
      const btVector3 n(r == 0, r == 1, 0);
      const btVector3 a1 = ra.cross(n), a2 = -(rb.cross(n));
      for (int k = 0; k < 3; k++) {
        info->m_J1linearAxis[r * s + k] = n[k];
        info->m_J1angularAxis[r * s + k] = a1[k];
        info->m_J2linearAxis[r * s + k] = -n[k];
        info->m_J2angularAxis[r * s + k] = a2[k];
      }
      info->m_constraintError[r * s] = erp * info->fps * (wb[r] - wa[r]);
      info->m_lowerLimit[r * s] = -SIMD_INFINITY;
      info->m_upperLimit[r * s] = SIMD_INFINITY;
    }
  }
  void setParam(int, btScalar, int) override {}
  btScalar getParam(int, int) const override { return 0; }
};

double angle_of(const btRigidBody *b) {
  const btMatrix3x3 &R = b->getCenterOfMassTransform().getBasis();
  return atan2(R[1][0], R[0][0]);
}

}  // namespace

int main(int argc, char **argv) {
  peer_args a;
  peer_fourbar f;
  peer_start(&a, &f, argc, argv);
  const bool mlcp = strcmp(peer_str(&a, "solver"), "mlcp") == 0;
  const int iterations = (int)peer_num(&a, "iterations");
  const double erp = peer_num(&a, "erp"), fmax = peer_num(&a, "fmax");
  const double t0 = peer_clock();
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btDantzigSolver dantzig;
  btMLCPSolver mlcp_solver(&dantzig);
  btSequentialImpulseConstraintSolver si_solver;
  btConstraintSolver *solver = mlcp ? static_cast<btConstraintSolver *>(&mlcp_solver) : &si_solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, solver, &config);
  world.setGravity(btVector3(0, -f.gravity, 0));
  btContactSolverInfo &info = world.getSolverInfo();
  info.m_numIterations = iterations;
  info.m_globalCfm = 0.0;
  info.m_minimumSolverBatchSize = 1;
  info.m_leastSquaresResidualThreshold = 0.0;
  btEmptyShape shape;
  const double A[2] = {0, 0}, D[2] = {f.len[3], 0};
  const double B[2] = {f.len[0] * cos(f.th2), f.len[0] * sin(f.th2)};
  const double C[2] = {D[0] + f.len[2] * cos(f.th4), D[1] + f.len[2] * sin(f.th4)};
  const double at[3][2] = {{A[0], A[1]}, {B[0], B[1]}, {D[0], D[1]}};
  const double th[3] = {f.th2, f.th3, f.th4}, om[3] = {f.omega2, f.w3, f.w4};
  const double vjoint[3][2] = {{0, 0}, {-f.omega2 * B[1], f.omega2 * B[0]}, {0, 0}};
  btRigidBody *body[3];
  for (int i = 0; i < 3; i++) {
    btRigidBody::btRigidBodyConstructionInfo ci(
        f.mass[i], nullptr, &shape,
        btVector3(f.inertia_long[i], f.inertia_transverse[i], f.inertia[i]));
    body[i] = new btRigidBody(ci);
    body[i]->setLinearFactor(btVector3(1, 1, 0));
    body[i]->setAngularFactor(btVector3(0, 0, 1));
    body[i]->setFlags(0);
    body[i]->setDamping(0, 0);
    body[i]->setSleepingThresholds(0, 0);
    body[i]->setActivationState(DISABLE_DEACTIVATION);
    const double rx = f.com[i] * f.len[i] * cos(th[i]), ry = f.com[i] * f.len[i] * sin(th[i]);
    btTransform t;
    t.setIdentity();
    t.setOrigin(btVector3(at[i][0] + rx, at[i][1] + ry, 0));
    t.setRotation(btQuaternion(btVector3(0, 0, 1), th[i]));
    body[i]->setCenterOfMassTransform(t);
    body[i]->setLinearVelocity(btVector3(vjoint[i][0] - om[i] * ry, vjoint[i][1] + om[i] * rx, 0));
    body[i]->setAngularVelocity(btVector3(0, 0, om[i]));
    world.addRigidBody(body[i], 0, 0);
  }
  const double *pt[4] = {A, B, C, D};
  btRigidBody *b1[4] = {body[0], body[0], body[1], body[2]}, *b2[4] = {nullptr, body[1], body[2], nullptr};
  Rows *pin[4];
  btJointFeedback fb[4];
  for (int j = 0; j < 4; j++) {
    const btVector3 p(pt[j][0], pt[j][1], 0);
    pin[j] = b2[j] ? new Rows(*b1[j], *b2[j]) : new Rows(*b1[j]);
    pin[j]->ground = !b2[j];
    pin[j]->pa = b1[j]->getCenterOfMassTransform().inverse() * p;
    pin[j]->pb = b2[j] ? b2[j]->getCenterOfMassTransform().inverse() * p : p;
    pin[j]->erp = erp;
    pin[j]->setJointFeedback(&fb[j]);
    pin[j]->enableFeedback(true);
    world.addConstraint(pin[j], true);
  }
  Rows drive(*body[0]);
  drive.drive = true;
  drive.speed = f.omega2;
  drive.limit = fmax * f.h;
  world.addConstraint(&drive, true);
  peer_series s;
  peer_series_init(&s, f.steps + 1);
  double v[P_COLS] = {0}, ang[3], w[3];
  for (int i = 0; i < 3; i++) ang[i] = angle_of(body[i]), w[i] = body[i]->getAngularVelocity()[2];
  peer_bodies(v, 0.0, ang, w, nullptr);
  peer_push(&s, v);
  const double t1 = peer_clock();
  const int on2[4] = {0, 1, 1, 0};
  for (long k = 1; k <= f.steps; k++) {
    world.stepSimulation(f.h, 0, f.h);
    double al[3];
    for (int i = 0; i < 3; i++)
      peer_body_step(&ang[i], &w[i], &al[i], angle_of(body[i]), body[i]->getAngularVelocity()[2], f.h);
    peer_bodies(v, (double)k * f.h, ang, w, al);
    for (int j = 0; j < 4; j++) {
      const btVector3 &fj = on2[j] ? fb[j].m_appliedForceBodyB : fb[j].m_appliedForceBodyA;
      v[P_RX + 2 * j] = fj[0];
      v[P_RX + 2 * j + 1] = fj[1];
    }
    v[P_TORQUE] = drive.getAppliedImpulse() / f.h;
    peer_push(&s, v);
  }
  const double t2 = peer_clock();
  peer_report("bullet", &s, f.steps, t1 - t0, t2 - t1, f.window);
  peer_series_free(&s);
  world.removeConstraint(&drive);
  for (int j = 0; j < 4; j++) world.removeConstraint(pin[j]), delete pin[j];
  for (int i = 0; i < 3; i++) world.removeRigidBody(body[i]), delete body[i];
  return 0;
}
