// A planar mechanism in DART 6.12 (dart_world.h says what and why): the
// only code that includes DART.
#include "dart_world.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <new>
#include <numeric>
#include <vector>

#include <dart/constraint/BallJointConstraint.hpp>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/constraint/DynamicJointConstraint.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
#include <dart/constraint/ConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/Inertia.hpp>
#include <dart/dynamics/PlanarJoint.hpp>
#include <dart/dynamics/PrismaticJoint.hpp>
#include <dart/dynamics/RevoluteJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/simulation/World.hpp>

namespace {

using dart::dynamics::BodyNode;
using Eigen::Isometry3d;
using Eigen::Vector3d;

struct Body {
  double mass, inertia, pos[3], vel[3];
  BodyNode *node = nullptr;
  int parent_joint = -1; // the tree joint that holds it (-1: a PlanarJoint root)
};

// a loop's pin: DART's BallJointConstraint, keeping the impulse the
// constraint solver applies (its lambda, on body 1 along body 1's axes at
// the step's start [N s]; BallJointConstraint keeps it private)
class Pin : public dart::constraint::BallJointConstraint {
public:
  using BallJointConstraint::BallJointConstraint;
  double lambda[3] = {0.0, 0.0, 0.0};

protected:
  void applyImpulse(double *l) override {
    BallJointConstraint::applyImpulse(l);
    lambda[0] = l[0], lambda[1] = l[1], lambda[2] = l[2];
  }
};

struct Joint {
  int prismatic, b[2];
  double at[2], axis[2];
  int tree = 0;     // 1: a joint of the tree, 0: closes a loop
  int child = -1;   // the body it holds (a tree joint)
  dart::dynamics::Joint *dj = nullptr;
  std::shared_ptr<Pin> pin; // a loop's constraint
  int on = -1;              // the body whose point the moment is about: b[1], else b[0]
  double local[2] = {0.0, 0.0}; // that point in that body's frame [m]
  double sum[3] = {0.0, 0.0, 0.0}; // its reactions summed over the steps since the last clear
};

// a body's frame: at its centre of mass, turned by its angle
Isometry3d pose(const Body &b) {
  Isometry3d T = Isometry3d::Identity();
  T.translation() = Vector3d(b.pos[0], b.pos[1], 0.0);
  T.linear() = Eigen::AngleAxisd(b.pos[2], Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

Isometry3d at_point(const double at[2]) {
  Isometry3d T = Isometry3d::Identity();
  T.translation() = Vector3d(at[0], at[1], 0.0);
  return T;
}

// the velocity of body b's material point at p (the ground: zero)
void point_velocity(const std::vector<Body> &body, int b, const double p[2], double v[2]) {
  v[0] = v[1] = 0.0;
  if (b < 0) return;
  const Body &k = body[(size_t)b];
  v[0] = k.vel[0] - k.vel[2] * (p[1] - k.pos[1]);
  v[1] = k.vel[1] + k.vel[2] * (p[0] - k.pos[0]);
}

int fail(char *err, size_t size, const char *what) {
  if (err && size) std::snprintf(err, size, "%s", what);
  return -1;
}

} // namespace

struct fb_dart_world {
  dart::simulation::WorldPtr world;
  dart::dynamics::SkeletonPtr skel;
  std::vector<Body> body;
  std::vector<Joint> joint;
  int loops = 0;
  double fmax = 0.0;
  std::vector<double> start; // each body's pose at the last step's start (x, y, angle)
  int steps = 0;             // steps since the last fb_dart_reactions_clear
};

extern "C" fb_dart_world *fb_dart_world_new(double g, double h, double erp,
                                            double drive_torque_max) {
  try {
    fb_dart_world *w = new fb_dart_world;
    w->world = dart::simulation::World::create("fourbar");
    w->world->setGravity(Vector3d(0.0, -g, 0.0));
    w->world->setTimeStep(h);
    w->skel = dart::dynamics::Skeleton::create("mechanism");
    w->fmax = drive_torque_max;
    // the planar loop's out-of-plane rows (a BallJointConstraint's z row,
    // zero in every column of a tree of joints about +z) leave Dantzig's
    // factorisation a zero pivot: it returns NaN at every step and DART falls
    // back to its secondary PGS solver, whose default early stop (relative
    // change 1e-3 over at most 30 sweeps) leaves one-step spikes in alpha.
    // PGS is made the primary solver, run to convergence (dart_world.h)
    auto pgs = std::make_shared<dart::constraint::PgsBoxedLcpSolver>();
    pgs->setOption(dart::constraint::PgsBoxedLcpSolver::Option(
        FB_DART_PGS_SWEEPS, FB_DART_PGS_DX, FB_DART_PGS_REL_DX));
    auto *cs = dynamic_cast<dart::constraint::BoxedLcpConstraintSolver *>(
        w->world->getConstraintSolver());
    if (!cs) {
      delete w;
      return nullptr;
    }
    cs->setBoxedLcpSolver(pgs);
    cs->setSecondaryBoxedLcpSolver(nullptr);
    // the ideal joints' ERP is the case's ([solver] world_erp), a global of
    // DART's; its CFM is DART's own (1e-9 of each row's diagonal)
    dart::constraint::DynamicJointConstraint::setErrorReductionParameter(erp);
    return w;
  } catch (...) {
    return nullptr;
  }
}

extern "C" int fb_dart_add_body(fb_dart_world *w, double mass, double inertia, const double pos[3],
                                const double vel[3], char *err, size_t size) {
  try {
    Body b{mass, inertia, {pos[0], pos[1], pos[2]}, {vel[0], vel[1], vel[2]}};
    w->body.push_back(b);
    return 0;
  } catch (const std::exception &e) {
    return fail(err, size, e.what());
  }
}

extern "C" int fb_dart_add_joint(fb_dart_world *w, int prismatic, int b0, int b1,
                                 const double at[2], const double axis[2], char *err,
                                 size_t size) {
  try {
    Joint j;
    j.prismatic = prismatic;
    j.b[0] = b0, j.b[1] = b1;
    j.at[0] = at[0], j.at[1] = at[1];
    j.axis[0] = axis[0], j.axis[1] = axis[1];
    w->joint.push_back(j);
    return 0;
  } catch (const std::exception &e) {
    return fail(err, size, e.what());
  }
}

namespace {

// the joint properties common to every kind: its frame at world point at,
// aligned with the world at assembly, fixed in the parent and in the child
template <class P> void place(P &p, const Body *parent, const Body &child, const double at[2]) {
  p.mT_ParentBodyToJoint = (parent ? pose(*parent).inverse() : Isometry3d::Identity()) *
                           at_point(at);
  p.mT_ChildBodyToJoint = pose(child).inverse() * at_point(at);
}

// body c's node, held by tree joint j from its parent (-1: the world), or
// a PlanarJoint root when j < 0; its joint's start velocity
void add_node(fb_dart_world *w, int c, int j, int parent) {
  Body &b = w->body[(size_t)c];
  BodyNode *pn = parent < 0 ? nullptr : w->body[(size_t)parent].node;
  const Body *pb = parent < 0 ? nullptr : &w->body[(size_t)parent];
  const std::string name = "body" + std::to_string(c + 1);
  BodyNode::AspectProperties bp(name);
  dart::dynamics::Joint *dj;
  if (j < 0) {
    dart::dynamics::PlanarJoint::Properties p;
    p.mName = name + "-plane";
    p.mPlaneType = dart::dynamics::detail::PlaneType::XY;
    p.mTransAxis1 = Vector3d::UnitX();
    p.mTransAxis2 = Vector3d::UnitY();
    p.mRotAxis = Vector3d::UnitZ();
    place(p, nullptr, b, b.pos);
    auto pair = w->skel->createJointAndBodyNodePair<dart::dynamics::PlanarJoint>(pn, p, bp);
    dj = pair.first;
    b.node = pair.second;
    dj->setVelocity(0, b.vel[0]);
    dj->setVelocity(1, b.vel[1]);
    dj->setVelocity(2, b.vel[2]);
  } else {
    Joint &jt = w->joint[(size_t)j];
    const double omega_p = pb ? pb->vel[2] : 0.0;
    if (jt.prismatic) {
      dart::dynamics::PrismaticJoint::Properties p;
      p.mName = "joint" + std::to_string(j);
      p.mAxis = Vector3d(jt.axis[0], jt.axis[1], 0.0);
      place(p, pb, b, jt.at);
      auto pair = w->skel->createJointAndBodyNodePair<dart::dynamics::PrismaticJoint>(pn, p, bp);
      dj = pair.first;
      b.node = pair.second;
      double vc[2], vp[2];
      point_velocity(w->body, c, jt.at, vc);
      point_velocity(w->body, parent, jt.at, vp);
      dj->setVelocity(0, jt.axis[0] * (vc[0] - vp[0]) + jt.axis[1] * (vc[1] - vp[1]));
    } else {
      dart::dynamics::RevoluteJoint::Properties p;
      p.mName = "joint" + std::to_string(j);
      p.mAxis = Vector3d::UnitZ();
      place(p, pb, b, jt.at);
      auto pair = w->skel->createJointAndBodyNodePair<dart::dynamics::RevoluteJoint>(pn, p, bp);
      dj = pair.first;
      b.node = pair.second;
      dj->setVelocity(0, b.vel[2] - omega_p);
    }
    jt.dj = dj;
    jt.child = c;
  }
  b.parent_joint = j;
  b.node->setInertia(dart::dynamics::Inertia(
      b.mass, Vector3d::Zero(),
      Eigen::Vector3d(0.5 * b.inertia, 0.5 * b.inertia, b.inertia).asDiagonal()));
}

// the tree from the ground (then from each body no joint reaches, on a
// PlanarJoint), parents before children
void grow(fb_dart_world *w) {
  const int nb = (int)w->body.size();
  std::vector<int> queue{-1};
  std::vector<char> seen((size_t)nb, 0);
  for (size_t head = 0;; head++) {
    if (head == queue.size()) { // a body the tree has not reached: a root of its own
      int r = 0;
      while (r < nb && seen[(size_t)r]) r++;
      if (r == nb) break;
      seen[(size_t)r] = 1;
      add_node(w, r, -1, -1);
      queue.push_back(r);
      continue;
    }
    const int p = queue[head];
    for (size_t j = 0; j < w->joint.size(); j++) {
      const Joint &jt = w->joint[j];
      if (!jt.tree || (jt.b[0] != p && jt.b[1] != p)) continue;
      const int c = jt.b[0] == p ? jt.b[1] : jt.b[0];
      if (c < 0 || seen[(size_t)c]) continue;
      seen[(size_t)c] = 1;
      add_node(w, c, (int)j, p);
      queue.push_back(c);
    }
  }
}

} // namespace

extern "C" int fb_dart_build(fb_dart_world *w, const unsigned char *tree, char *err,
                             size_t size) {
  try {
    for (size_t j = 0; j < w->joint.size(); j++) {
      w->joint[j].tree = tree[j];
      if (!w->joint[j].tree && w->joint[j].prismatic) {
        char m[160];
        std::snprintf(m, sizeof m, "DART closes a loop at a revolute joint only "
                      "(BallJointConstraint), and joint %zu, which closes one, is prismatic", j);
        return fail(err, size, m);
      }
    }
    grow(w);
    w->world->addSkeleton(w->skel);
    w->start.assign(3 * w->body.size(), 0.0);
    // the point each joint's moment is about (kit.h's reactions), fixed in its body
    for (Joint &jt : w->joint) {
      jt.on = jt.b[1] >= 0 ? jt.b[1] : jt.b[0];
      const Vector3d p = pose(w->body[(size_t)jt.on]).inverse() * Vector3d(jt.at[0], jt.at[1], 0.0);
      jt.local[0] = p[0], jt.local[1] = p[1];
    }
    // every loop closed at its pin, as examples/rigid_loop closes its chain
    for (Joint &jt : w->joint) {
      if (jt.tree) continue;
      const Vector3d at(jt.at[0], jt.at[1], 0.0);
      BodyNode *a = jt.b[0] < 0 ? nullptr : w->body[(size_t)jt.b[0]].node;
      BodyNode *b = jt.b[1] < 0 ? nullptr : w->body[(size_t)jt.b[1]].node;
      jt.pin = a && b ? std::make_shared<Pin>(a, b, at) : std::make_shared<Pin>(a ? a : b, at);
      w->world->getConstraintSolver()->addConstraint(jt.pin);
      w->loops++;
    }
    return 0;
  } catch (const std::exception &e) {
    return fail(err, size, e.what());
  }
}

extern "C" int fb_dart_drive(fb_dart_world *w, int j, double rate, char *err, size_t size) {
  if (j < 0 || (size_t)j >= w->joint.size() || !w->joint[(size_t)j].tree ||
      w->joint[(size_t)j].prismatic)
    return fail(err, size, "DART drives a revolute joint of its tree only (a SERVO actuator)");
  const Joint &jt = w->joint[(size_t)j];
  dart::dynamics::Joint *dj = jt.dj;
  // the joint's coordinate turns its child relative to its parent
  const double command = jt.child == jt.b[1] ? rate : -rate;
  dj->setActuatorType(dart::dynamics::Joint::SERVO);
  dj->setForceLowerLimit(0, -w->fmax);
  dj->setForceUpperLimit(0, w->fmax);
  dj->setCommand(0, command);
  return 0;
}

extern "C" void fb_dart_add_force(fb_dart_world *w, int pin, int hole, const double p[2],
                                  const double f[2]) {
  const Vector3d at(p[0], p[1], 0.0), force(f[0], f[1], 0.0);
  if (pin >= 0) w->body[(size_t)pin].node->addExtForce(force, at, false, false);
  if (hole >= 0) w->body[(size_t)hole].node->addExtForce(-force, at, false, false);
}

extern "C" void fb_dart_add_wrench(fb_dart_world *w, int b, const double f[3]) {
  BodyNode *n = w->body[(size_t)b].node; // its frame's origin is its centre of mass
  n->addExtForce(Vector3d(f[0], f[1], 0.0), Vector3d::Zero(), false, true);
  n->addExtTorque(Vector3d(0.0, 0.0, f[2]), false);
}

namespace {

// body b's point at (x, y) in its frame, at pose q (x, y, angle) [m]
void at_pose(const double q[3], const double l[2], double p[2]) {
  const double c = std::cos(q[2]), s = std::sin(q[2]);
  p[0] = q[0] + c * l[0] - s * l[1];
  p[1] = q[1] + s * l[0] + c * l[1];
}

// joint jt's reaction over the step just taken (dart_world.h), from the
// poses at its start: a tree joint's, the wrench its child's BodyNode
// holds from its parent (getBodyForce: about the child's centre of mass
// along its axes, the constraint impulses over the step included); a
// pin's, its constraint's impulse on body 1 over the step
void reaction(const fb_dart_world *w, const Joint &jt, double h, double out[3]) {
  const double *q = w->start.data();
  double f[2], m = 0.0;
  int on; // the body the force (f, m) acts on
  if (jt.pin) {
    on = jt.b[0] >= 0 ? jt.b[0] : jt.b[1]; // body 1: body[0]'s node unless it is the ground
    const double *p = q + 3 * on, c = std::cos(p[2]), s = std::sin(p[2]);
    f[0] = (c * jt.pin->lambda[0] - s * jt.pin->lambda[1]) / h;
    f[1] = (s * jt.pin->lambda[0] + c * jt.pin->lambda[1]) / h;
  } else {
    on = jt.child;
    const Eigen::Vector6d &F = w->body[(size_t)on].node->getBodyForce(); // torque, force
    const double *p = q + 3 * on, c = std::cos(p[2]), s = std::sin(p[2]);
    f[0] = c * F[3] - s * F[4];
    f[1] = s * F[3] + c * F[4];
    double at[2]; // about the joint's point: M_P = M_G + (G - P) x f
    at_pose(q + 3 * jt.on, jt.local, at);
    m = F[2] + (p[0] - at[0]) * f[1] - (p[1] - at[1]) * f[0];
  }
  const double sign = on == jt.b[1] ? 1.0 : -1.0; // on body[1], from body[0]
  out[0] = sign * f[0];
  out[1] = sign * f[1];
  out[2] = sign * m;
}

} // namespace

extern "C" void fb_dart_reactions_clear(fb_dart_world *w) {
  for (Joint &jt : w->joint) jt.sum[0] = jt.sum[1] = jt.sum[2] = 0.0;
  w->steps = 0;
}

extern "C" void fb_dart_reaction(const fb_dart_world *w, int j, double out[3]) {
  const Joint &jt = w->joint[(size_t)j];
  for (int c = 0; c < 3; c++) out[c] = w->steps > 0 ? jt.sum[c] / w->steps : 0.0;
}

extern "C" void fb_dart_set_step(fb_dart_world *w, double h) { w->world->setTimeStep(h); }

extern "C" int fb_dart_step(fb_dart_world *w, char *err, size_t size) {
  try {
    for (size_t b = 0; b < w->body.size(); b++) { // the poses the reactions are read at
      double v[3];
      fb_dart_body_state(w, (int)b, &w->start[3 * b], v);
    }
    // false: keep the servo's command (World::step(true) resets every
    // command after the step); the external forces are this step's alone
    w->world->step(false);
    w->skel->clearExternalForces();
    const double h = w->world->getTimeStep();
    for (Joint &jt : w->joint) {
      double r[3];
      reaction(w, jt, h, r);
      for (int c = 0; c < 3; c++) jt.sum[c] += r[c];
    }
    w->steps++;
    const Eigen::VectorXd q = w->skel->getPositions(), v = w->skel->getVelocities();
    if (!q.allFinite() || !v.allFinite()) return fail(err, size, "DART's state is not finite");
    return 0;
  } catch (const std::exception &e) {
    return fail(err, size, e.what());
  }
}

extern "C" void fb_dart_body_state(const fb_dart_world *w, int b, double pos[3],
                                   double vel[3]) {
  const BodyNode *n = w->body[(size_t)b].node;
  const Isometry3d &T = n->getWorldTransform();
  const Vector3d v = n->getLinearVelocity(), om = n->getAngularVelocity();
  pos[0] = T.translation()[0];
  pos[1] = T.translation()[1];
  pos[2] = std::atan2(T.linear()(1, 0), T.linear()(0, 0));
  vel[0] = v[0];
  vel[1] = v[1];
  vel[2] = om[2];
}

extern "C" int fb_dart_loops(const fb_dart_world *w) { return w->loops; }

extern "C" void fb_dart_world_free(fb_dart_world *w) { delete w; }
