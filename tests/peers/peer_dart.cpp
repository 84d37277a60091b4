// The ideal four-bar in DART 6.12, bare: one Skeleton, a tree of
// RevoluteJoints about +z (world -> crank at A, crank -> coupler at B,
// coupler -> follower at C), each BodyNode's frame at its centre of mass,
// the loop closed at D by a BallJointConstraint of the constraint solver
// (as DART's examples/rigid_loop closes its chain), the crank driven by its
// joint's SERVO actuator (a velocity command the constraint solver holds
// within the torque limit fmax), gravity along -y; World::step(false) at a
// fixed h (false: the servo keeps its command). The boxed LCP is PGS, made
// the primary solver with the given sweeps and stop tolerances (Dantzig,
// DART's default, meets a zero pivot on the ball constraint's out-of-plane
// row, which every joint about +z leaves empty), and the joints' global ERP
// the one given. Every step's angles (the joints' coordinates summed),
// angular velocities and accelerations (the omega change over the step)
// kept; no drive torque or reactions, which the harness's DART model keeps
// neither (the engine kit reads bodies only). DART's API only (dartsim 6.12:
// Skeleton::createJointAndBodyNodePair, constraint::BallJointConstraint,
// constraint::PgsBoxedLcpSolver, DynamicJointConstraint's ERP); settings
// and output: peer.h. Extra arguments: erp fmax pgs_sweeps pgs_dx
// pgs_rel_dx.
#include <dart/constraint/BallJointConstraint.hpp>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/constraint/DynamicJointConstraint.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/Inertia.hpp>
#include <dart/dynamics/RevoluteJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/simulation/World.hpp>

#include <memory>
#include <string>

#include "peer.h"

using dart::dynamics::BodyNode;
using dart::dynamics::RevoluteJoint;
using Eigen::Isometry3d;
using Eigen::Vector3d;

namespace {

// a frame at world point (x, y) turned by th about +z
Isometry3d frame(double x, double y, double th) {
  Isometry3d T = Isometry3d::Identity();
  T.translation() = Vector3d(x, y, 0.0);
  T.linear() = Eigen::AngleAxisd(th, Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

// link k's body, frame body (at its centre of mass, turned by the link's
// angle), from parent (nullptr: the world) whose frame is parent_frame, by
// a revolute joint about +z at world point p (its frame there, aligned with
// the world) turning at rate relative to the parent
std::pair<RevoluteJoint *, BodyNode *> link(const dart::dynamics::SkeletonPtr &skel,
                                            BodyNode *parent, const Isometry3d &parent_frame,
                                            const Isometry3d &body, const peer_fourbar &f, int k,
                                            const double p[2], double rate) {
  const Isometry3d at = frame(p[0], p[1], 0.0);
  RevoluteJoint::Properties jp;
  jp.mName = "joint" + std::to_string(k);
  jp.mAxis = Vector3d::UnitZ();
  jp.mT_ParentBodyToJoint = parent_frame.inverse() * at;
  jp.mT_ChildBodyToJoint = body.inverse() * at;
  auto pair = skel->createJointAndBodyNodePair<RevoluteJoint>(
      parent, jp, BodyNode::AspectProperties("link" + std::to_string(k)));
  // the moment about +z the case's; in the plane half of it each (a plate)
  pair.second->setInertia(dart::dynamics::Inertia(
      f.mass[k], Vector3d::Zero(),
      Vector3d(0.5 * f.inertia[k], 0.5 * f.inertia[k], f.inertia[k]).asDiagonal()));
  pair.first->setVelocity(0, rate);
  return pair;
}

// link k's frame: its centre of mass a fraction com of its length from its
// first joint point p along th
Isometry3d link_frame(const peer_fourbar &f, int k, const double p[2], double th) {
  const double r = f.com[k] * f.len[k];
  return frame(p[0] + r * std::cos(th), p[1] + r * std::sin(th), th);
}

}  // namespace

int main(int argc, char **argv) {
  peer_args a;
  peer_fourbar f;
  peer_start(&a, &f, argc, argv);
  const double erp = peer_num(&a, "erp"), fmax = peer_num(&a, "fmax");
  const int sweeps = (int)peer_num(&a, "pgs_sweeps");
  const double dx = peer_num(&a, "pgs_dx"), rel_dx = peer_num(&a, "pgs_rel_dx");
  const double t0 = peer_clock();
  auto world = dart::simulation::World::create("fourbar");
  world->setGravity(Vector3d(0.0, -f.gravity, 0.0));
  world->setTimeStep(f.h);
  auto *cs = dynamic_cast<dart::constraint::BoxedLcpConstraintSolver *>(world->getConstraintSolver());
  if (!cs) {
    std::fprintf(stderr, "peer_dart: the world's constraint solver is not a boxed LCP solver\n");
    return 1;
  }
  auto pgs = std::make_shared<dart::constraint::PgsBoxedLcpSolver>();
  pgs->setOption(dart::constraint::PgsBoxedLcpSolver::Option(sweeps, dx, rel_dx));
  cs->setBoxedLcpSolver(pgs);
  cs->setSecondaryBoxedLcpSolver(nullptr);
  dart::constraint::DynamicJointConstraint::setErrorReductionParameter(erp);
  auto skel = dart::dynamics::Skeleton::create("fourbar");
  const double A[2] = {0.0, 0.0}, D[2] = {f.len[3], 0.0};
  const double B[2] = {f.len[0] * std::cos(f.th2), f.len[0] * std::sin(f.th2)};
  const double C[2] = {B[0] + f.len[1] * std::cos(f.th3), B[1] + f.len[1] * std::sin(f.th3)};
  const Isometry3d crank_f = link_frame(f, 0, A, f.th2), coupler_f = link_frame(f, 1, B, f.th3);
  const Isometry3d follower_f = link_frame(f, 2, D, f.th4); // from D towards C
  auto crank = link(skel, nullptr, Isometry3d::Identity(), crank_f, f, 0, A, f.omega2);
  auto coupler = link(skel, crank.second, crank_f, coupler_f, f, 1, B, f.w3 - f.omega2);
  auto follower = link(skel, coupler.second, coupler_f, follower_f, f, 2, C, f.w4 - f.w3);
  world->addSkeleton(skel);
  world->getConstraintSolver()->addConstraint(
      std::make_shared<dart::constraint::BallJointConstraint>(follower.second,
                                                              Vector3d(D[0], D[1], 0.0)));
  RevoluteJoint *drive = crank.first;
  drive->setActuatorType(dart::dynamics::Joint::SERVO);
  drive->setForceLowerLimit(0, -fmax);
  drive->setForceUpperLimit(0, fmax);
  drive->setCommand(0, f.omega2);
  RevoluteJoint *joint[3] = {crank.first, coupler.first, follower.first};
  peer_series s;
  peer_series_init(&s, f.steps + 1);
  // body angles and rates: the joints' coordinates summed along the tree
  // from each body's start angle
  const double start[3] = {f.th2, f.th3, f.th4};
  double ang[3] = {f.th2, f.th3, f.th4}, om[3] = {f.omega2, f.w3, f.w4}, al[3];
  double v[P_COLS] = {0};
  peer_bodies(v, 0.0, ang, om, nullptr);
  peer_push(&s, v);
  const double t1 = peer_clock();
  for (long k = 1; k <= f.steps; k++) {
    world->step(false);
    double q = 0.0, w = 0.0;
    for (int i = 0; i < 3; i++) {
      q += joint[i]->getPosition(0);
      w += joint[i]->getVelocity(0);
      ang[i] = start[i] + q;
      al[i] = (w - om[i]) / f.h;
      om[i] = w;
    }
    peer_bodies(v, (double)k * f.h, ang, om, al);
    peer_push(&s, v);
  }
  const double t2 = peer_clock();
  peer_report("dart", &s, f.steps, t1 - t0, t2 - t1, f.window);
  peer_series_free(&s);
  return 0;
}
