// The Siconos scene (siconos_scene.h): the only translation unit of the
// project that includes Siconos. C++ stays inside this file; the C side sees
// the extern "C" functions of siconos_scene.h only.
//
// Built as the Siconos examples of mechanisms build theirs (the slider-crank
// and four-bar clearance examples of siconos-tutorials): a LagrangianDS whose
// mass matrix and forces the user supplies with their Jacobians, Lagrangian
// relations for the joints, a nonsmooth law per relation, MoreauJeanOSI and
// TimeStepping with its Newton loop. The user's functions are supplied here
// by derived classes (as BouncingBall's BallR does for a relation) instead of
// plugins loaded from a shared library by name. The four-bar and the
// slider-crank each have their own dynamical system and relations
// (FourbarDS with ClosureR or ClearanceR; SliderCrankDS with PinClosureR or
// PinClearanceR), on the reference's coordinates of each.
#include "SiconosKernel.hpp"
#include "SolverOptions.h"
#include "siconos_common.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

extern "C" {
#include "episode.h"
#include "siconos_scene.h"
#include "slider_crank_invdyn.h"
}

namespace {

// Newton loop of TimeStepping: the residual of M(q)(v - v_k) - h F_theta - p
// [kg m^2/s] below which a step has converged, and the iterations allowed.
// The loop's test sees the dynamics' residual only, not the relation's: the
// contact normal of a pin in a 14.5 um clearance turns by a few percent over
// one step's sliding, so an iterate whose Jacobian is one Newton update old
// leaves Newton's law g'(k+1) = -e_N g'(k) off by up to 2.8e-3 at the
// experts' 1e-10 (their slider-crank's setting, with 200 iterations). At
// 1e-12 (a relative 2e-12 of the links' momenta, ~0.5 kg m^2/s) the
// worst impact of the paper case's first revolution is off by 2.6e-5 at no
// measurable cost (2 or 3 iterations a step; 1e-14: 5.3e-6). The
// slider-crank's clearance model has the relation's residual checked too
// (LawCheckedMoreauJeanOSI), to the same 1e-12, in m/s there: Newton's law
// holds to 2e-11 at its impacts.
const double kNewtonTolerance = 1e-12;
const unsigned kNewtonMaxIterations = 200;
// Tolerance and iteration cap of the friction problem's solver (the
// slider-crank example's settings). The solver is SICONOS_FRICTION_2D_LEMKE,
// a direct pivoting method (the 2-D friction problem as an LCP): the
// example's enumerative SICONOS_FRICTION_2D_ENUM returned info 1 at the
// paper case's first contact with friction 0.2.
const double kFrictionSolverTolerance = 1e-12;
const int kFrictionSolverMaxIterations = 100;
// [siconos] scheme = combined-projection: siconos_common.hpp's
// combined_projection (its cap and tolerances, shared with the kit)
using fb_siconos::kProjectionMaxIterations;
// Below this eccentricity [m] the normal e/|e| is undefined; the pin is then
// a whole clearance away from the wall, where only the sign of the gap
// matters, and the normal is taken along +x.
const double kEccentricityMin = 1e-15;

// The mechanism in the coordinates q = (theta3, theta4) (siconos_scene.h).
struct Mech {
  double a, b, cl, g;       // crank, coupler, follower, ground lengths [m]
  double m3, m4, i3, i4;    // coupler and follower masses [kg], central inertias [kg m^2]
  double f3, f4;            // centre-of-mass fractions (coupler from B, follower from D)
  double grav;              // along -y [m/s^2]
  double theta0, omega2;    // crank angle at t = 0 [rad], signed speed [rad/s]
  double c;                 // radial clearance [m]
  double r_pin, r_hole;     // pin and hole radii [m]

  double crank_angle(double t) const { return theta0 + omega2 * t; }
  // pin centre B_pin(t) and its velocity
  void pin(double t, double p[2], double v[2]) const {
    const double th = crank_angle(t);
    p[0] = a * std::cos(th);
    p[1] = a * std::sin(th);
    v[0] = -a * omega2 * std::sin(th);
    v[1] = a * omega2 * std::cos(th);
  }
  // hole centre B_hole(q) and its Jacobian JB (row-major 2 x 2: d B / d (theta3, theta4))
  void hole(double th3, double th4, double p[2], double J[2][2]) const {
    const double s3 = std::sin(th3), c3 = std::cos(th3), s4 = std::sin(th4), c4 = std::cos(th4);
    p[0] = g + cl * c4 - b * c3;
    p[1] = cl * s4 - b * s3;
    J[0][0] = b * s3;
    J[0][1] = -cl * s4;
    J[1][0] = -b * c3;
    J[1][1] = cl * c4;
  }
  // M(q), the reference's mass matrix (reference.c)
  void mass(double th3, double th4, double M[2][2]) const {
    const double s = (1.0 - f3) * b;
    M[0][0] = m3 * s * s + i3;
    M[0][1] = M[1][0] = -m3 * cl * s * std::cos(th4 - th3);
    M[1][1] = m3 * cl * cl + m4 * f4 * f4 * cl * cl + i4;
  }
  // PlanarDS's interface: M(q), and F with its Jacobians (time-free here)
  void dsMass(const double q[2], double M[2][2]) const { mass(q[0], q[1], M); }
  void dsForces(double, const double q[2], const double v[2], double F[2], double Fq[2][2],
                double Fv[2][2]) const {
    forces(q, v, F, Fq, Fv);
  }
  // F(q, v) of M q'' + F = p: the coupler's quadratic velocity terms and
  // gravity, and its Jacobians dF/dq, dF/dv (row-major)
  void forces(const double q[2], const double v[2], double F[2], double Fq[2][2],
              double Fv[2][2]) const {
    const double s = (1.0 - f3) * b, K = m3 * s * cl;
    const double S = std::sin(q[1] - q[0]), C = std::cos(q[1] - q[0]);
    const double w3 = v[0], w4 = v[1], gm = (m3 + m4 * f4) * grav * cl;
    F[0] = K * S * w4 * w4 - m3 * grav * s * std::cos(q[0]);
    F[1] = -K * S * w3 * w3 + gm * std::cos(q[1]);
    Fq[0][0] = -K * C * w4 * w4 + m3 * grav * s * std::sin(q[0]);
    Fq[0][1] = K * C * w4 * w4;
    Fq[1][0] = K * C * w3 * w3;
    Fq[1][1] = -K * C * w3 * w3 - gm * std::sin(q[1]);
    Fv[0][0] = 0.0;
    Fv[0][1] = 2.0 * K * S * w4;
    Fv[1][0] = -2.0 * K * S * w3;
    Fv[1][1] = 0.0;
  }
  // eccentricity e = B_pin - B_hole, |e|, unit normal n (pin - hole), and the
  // rows of the contact's velocity map: g' = wn . q' + wn_t, u_T = wt . q' + wt_t
  struct Contact {
    double e[2], ecc, n[2], wn[2], wn_t, wt[2], wt_t;
  };
  Contact contact(double t, double th3, double th4) const {
    Contact k;
    double bp[2], vp[2], bh[2], J[2][2];
    pin(t, bp, vp);
    hole(th3, th4, bh, J);
    k.e[0] = bp[0] - bh[0];
    k.e[1] = bp[1] - bh[1];
    k.ecc = std::hypot(k.e[0], k.e[1]);
    if (k.ecc > kEccentricityMin) {
      k.n[0] = k.e[0] / k.ecc;
      k.n[1] = k.e[1] / k.ecc;
    } else {
      k.n[0] = 1.0;
      k.n[1] = 0.0;
    }
    // g = c - |e|: dg/dq = n^T JB, dg/dt = -n . v_pin
    k.wn[0] = k.n[0] * J[0][0] + k.n[1] * J[1][0];
    k.wn[1] = k.n[0] * J[0][1] + k.n[1] * J[1][1];
    k.wn_t = -(k.n[0] * vp[0] + k.n[1] * vp[1]);
    // sliding velocity of the hole's surface on the pin's at the contact
    // point, along t = z x n: t . (JB q' - v_pin) + r_hole w3 - r_pin omega2
    const double tn[2] = {-k.n[1], k.n[0]};
    k.wt[0] = tn[0] * J[0][0] + tn[1] * J[1][0] + r_hole;
    k.wt[1] = tn[0] * J[0][1] + tn[1] * J[1][1];
    k.wt_t = -(tn[0] * vp[0] + tn[1] * vp[1]) - r_pin * omega2;
    return k;
  }
};

// The coupler and the follower as one LagrangianDS, M(q) q'' + F(q, q') = p,
// with the Jacobians of F that MoreauJeanOSI's iteration matrix
// W = M - h theta dF/dv - h^2 theta^2 dF/dq needs (all of F is carried as
// LagrangianDS's fInt: Siconos subtracts fInt from the forces).
// M gives the mass matrix and the forces with their Jacobians at (t, q,
// q'): dsMass, dsForces (Mech: the coupler and follower's; ScMech: the rod
// and slider's).
template <class M>
class PlanarDS : public LagrangianDS {
 public:
  PlanarDS(SP::SiconosVector q0, SP::SiconosVector v0, const M &m)
      : LagrangianDS(q0, v0), m_(m) {
    _hasConstantMass = false;
    allocateMass();
    allocateFInt();
    allocateJacobianFIntq();
    allocateJacobianFIntqDot();
    init_forces();
    computeMass();
  }
  void computeMass() override { computeMass(_q[0]); }
  void computeMass(SP::SiconosVector q) override {
    double Mq[2][2];
    const double qq[2] = {q->getValue(0), q->getValue(1)};
    m_.dsMass(qq, Mq);
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) _mass->setValue(i, j, Mq[i][j]);
    _mass->resetFactorizationFlags();
  }
  void computeFInt(double time) override { computeFInt(time, _q[0], _q[1]); }
  void computeFInt(double time, SP::SiconosVector q, SP::SiconosVector v) override {
    double F[2], Fq[2][2], Fv[2][2];
    eval(time, *q, *v, F, Fq, Fv);
    _fInt->setValue(0, F[0]);
    _fInt->setValue(1, F[1]);
  }
  void computeJacobianFIntq(double time) override { computeJacobianFIntq(time, _q[0], _q[1]); }
  void computeJacobianFIntq(double time, SP::SiconosVector q, SP::SiconosVector v) override {
    double F[2], Fq[2][2], Fv[2][2];
    eval(time, *q, *v, F, Fq, Fv);
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) _jacobianFIntq->setValue(i, j, Fq[i][j]);
  }
  void computeJacobianFIntqDot(double time) override {
    computeJacobianFIntqDot(time, _q[0], _q[1]);
  }
  void computeJacobianFIntqDot(double time, SP::SiconosVector q, SP::SiconosVector v) override {
    double F[2], Fq[2][2], Fv[2][2];
    eval(time, *q, *v, F, Fq, Fv);
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) _jacobianFIntqDot->setValue(i, j, Fv[i][j]);
  }

 private:
  void eval(double time, const SiconosVector &q, const SiconosVector &v, double F[2],
            double Fq[2][2], double Fv[2][2]) const {
    const double qq[2] = {q.getValue(0), q.getValue(1)}, vv[2] = {v.getValue(0), v.getValue(1)};
    m_.dsForces(time, qq, vv, F, Fq, Fv);
  }
  M m_;
};
using FourbarDS = PlanarDS<Mech>;

// The loop closed at B (ideal models): h(q, t) = B_hole(q) - B_pin(t) = 0.
class ClosureR : public LagrangianRheonomousR {
 public:
  explicit ClosureR(const Mech &m) : m_(m) { _hDot.reset(new SiconosVector(2)); }
  void computeh(double time, const BlockVector &q, BlockVector &, SiconosVector &y) override {
    double bp[2], vp[2], bh[2], J[2][2];
    m_.pin(time, bp, vp);
    m_.hole(q.getValue(0), q.getValue(1), bh, J);
    y.setValue(0, bh[0] - bp[0]);
    y.setValue(1, bh[1] - bp[1]);
  }
  void computeJachq(double, const BlockVector &q, BlockVector &) override {
    double bh[2], J[2][2];
    m_.hole(q.getValue(0), q.getValue(1), bh, J);
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) _jachq->setValue(i, j, J[i][j]);
  }
  void computehDot(double time, const BlockVector &, BlockVector &) override {
    double bp[2], vp[2];
    m_.pin(time, bp, vp);
    _hDot->setValue(0, -vp[0]);
    _hDot->setValue(1, -vp[1]);
  }

 private:
  Mech m_;
};

// The clearance at a pin: g(q, t) = c - |e| >= 0, and with friction a second
// row, the sliding velocity at the contact point (its position row is 0:
// only its velocity enters Moreau-Jean's velocity-level problem). M is the
// mechanism's coordinates: Mech (the four-bar's clearance at B) or ScMech
// (the slider-crank's at the piston pin), each with contact(t, q0, q1) and
// the radial clearance c.
template <class M>
class ClearanceRT : public LagrangianRheonomousR {
 public:
  ClearanceRT(const M &m, int rows) : m_(m), rows_(rows) {
    _hDot.reset(new SiconosVector(rows));
  }
  void computeh(double time, const BlockVector &q, BlockVector &, SiconosVector &y) override {
    const Mech::Contact k = m_.contact(time, q.getValue(0), q.getValue(1));
    y.setValue(0, m_.c - k.ecc);
    if (rows_ > 1) y.setValue(1, 0.0);
  }
  void computeJachq(double time, const BlockVector &q, BlockVector &) override {
    const Mech::Contact k = m_.contact(time, q.getValue(0), q.getValue(1));
    _jachq->setValue(0, 0, k.wn[0]);
    _jachq->setValue(0, 1, k.wn[1]);
    if (rows_ > 1) {
      _jachq->setValue(1, 0, k.wt[0]);
      _jachq->setValue(1, 1, k.wt[1]);
    }
  }
  void computehDot(double time, const BlockVector &q, BlockVector &) override {
    const Mech::Contact k = m_.contact(time, q.getValue(0), q.getValue(1));
    _hDot->setValue(0, k.wn_t);
    if (rows_ > 1) _hDot->setValue(1, k.wt_t);
  }

 private:
  M m_;
  int rows_;
};
using ClearanceR = ClearanceRT<Mech>;

// ---- the slider-crank ------------------------------------------------------
//
// The slider-crank in the coordinates q = (theta3, x): the rod's angle
// (direction B -> P) and the slider's hole centre's x along the guide, the
// reference's minimal coordinates (slider_crank_dynamics.h). The crank is
// prescribed, B(t) = a u(theta2(t)); the rod turns about the moving B, the
// slider's hole centre is H = (x, offset): the guide is in the coordinates,
// as the Siconos slider-crank example keeps its ideal joints in its
// coordinates and writes a relation only where its clearance is. The loop's
// one joint that is no hinge of those coordinates is the piston pin, the
// rod's pin P = B(t) + b u(theta3) in the slider's hole H: one rheonomous
// relation closes it (ideal) or carries the clearance.
struct ScMech {
  double a, b, off;         // crank, rod [m], the guide's offset along +y [m]
  double m3, i3, f3;        // rod mass [kg], central inertia [kg m^2], com fraction from B
  double m4;                // slider mass [kg]
  double grav;              // along -y [m/s^2]
  double theta0, omega2;    // crank angle at t = 0 [rad], signed speed [rad/s]
  double c;                 // radial clearance [m]
  double r_pin;             // pin radius [m]

  double crank_angle(double t) const { return theta0 + omega2 * t; }
  // crank pin B(t) and its velocity
  void crank_pin(double t, double p[2], double v[2]) const {
    const double th = crank_angle(t);
    p[0] = a * std::cos(th);
    p[1] = a * std::sin(th);
    v[0] = -a * omega2 * std::sin(th);
    v[1] = a * omega2 * std::cos(th);
  }
  // eccentricity e = P - H (rod's pin minus slider's hole) and its Jacobian
  // J = de/dq (row-major 2 x 2: d e / d (theta3, x)); B'(t) in bv
  void ecc(double t, double th3, double x, double e[2], double J[2][2], double bv[2]) const {
    double bp[2];
    crank_pin(t, bp, bv);
    const double s3 = std::sin(th3), c3 = std::cos(th3);
    e[0] = bp[0] + b * c3 - x;
    e[1] = bp[1] + b * s3 - off;
    J[0][0] = -b * s3;
    J[0][1] = -1.0;
    J[1][0] = b * c3;
    J[1][1] = 0.0;
  }
  // M(q) = diag(m3 (f3 b)^2 + I3, m4): the rod about the moving B, the slider
  void mass(double M[2][2]) const {
    M[0][0] = m3 * f3 * b * f3 * b + i3;
    M[0][1] = M[1][0] = 0.0;
    M[1][1] = m4;
  }
  // PlanarDS's interface: the constant M, and F with dF/dq (dF/dq' = 0)
  void dsMass(const double[2], double M[2][2]) const { mass(M); }
  void dsForces(double t, const double q[2], const double[2], double F[2], double Fq[2][2],
                double Fv[2][2]) const {
    forces(t, q, F, Fq);
    Fv[0][0] = Fv[0][1] = Fv[1][0] = Fv[1][1] = 0.0;
  }
  // F(t, q) of M q'' + F = p: the crank pin's acceleration and gravity on
  // the rod, m3 f3 b u'(theta3).(B''(t) + g y) (the slider's weight is the
  // guide's), and dF/dq (dF/dq' = 0)
  void forces(double t, const double q[2], double F[2], double Fq[2][2]) const {
    const double d = crank_angle(t) - q[0], K = m3 * f3 * b;
    const double w2 = omega2 * omega2;
    F[0] = K * (-a * w2 * std::sin(d) + grav * std::cos(q[0]));
    F[1] = 0.0;
    Fq[0][0] = K * (a * w2 * std::cos(d) - grav * std::sin(q[0]));
    Fq[0][1] = Fq[1][0] = Fq[1][1] = 0.0;
  }
  // the contact at the piston pin: e, |e|, n = e / |e| (hole -> pin) and the
  // rows of its velocity map, g' = wn . q' + wn_t (g = c - |e|) and the
  // sliding velocity of the hole's surface on the pin's at the contact
  // point, u_T = wt . q' + wt_t (the slider does not turn; the pin turns
  // with the rod: t . (H' - P') - r_pin theta3', t = z x n)
  Mech::Contact contact(double t, double th3, double x) const {
    Mech::Contact k;
    double J[2][2], bv[2];
    ecc(t, th3, x, k.e, J, bv);
    k.ecc = std::hypot(k.e[0], k.e[1]);
    if (k.ecc > kEccentricityMin) {
      k.n[0] = k.e[0] / k.ecc;
      k.n[1] = k.e[1] / k.ecc;
    } else {
      k.n[0] = 1.0;
      k.n[1] = 0.0;
    }
    // g = c - |e|: dg/dq = -n^T J, dg/dt = -n . B'
    k.wn[0] = -(k.n[0] * J[0][0] + k.n[1] * J[1][0]);
    k.wn[1] = -(k.n[0] * J[0][1] + k.n[1] * J[1][1]);
    k.wn_t = -(k.n[0] * bv[0] + k.n[1] * bv[1]);
    const double tn[2] = {-k.n[1], k.n[0]};
    k.wt[0] = -(tn[0] * J[0][0] + tn[1] * J[1][0]) - r_pin;
    k.wt[1] = -(tn[0] * J[0][1] + tn[1] * J[1][1]);
    k.wt_t = -(tn[0] * bv[0] + tn[1] * bv[1]);
    return k;
  }
};

// The rod and the slider as one LagrangianDS, M q'' + F(t, q) = p (the
// reference's equations; F carried as fInt, with its Jacobians for
// MoreauJeanOSI's iteration matrix): PlanarDS on ScMech
using SliderCrankDS = PlanarDS<ScMech>;

// The piston pin closed (ideal models): h(q, t) = P(q, t) - H(q) = 0
class PinClosureR : public LagrangianRheonomousR {
 public:
  explicit PinClosureR(const ScMech &m) : m_(m) { _hDot.reset(new SiconosVector(2)); }
  void computeh(double time, const BlockVector &q, BlockVector &, SiconosVector &y) override {
    double e[2], J[2][2], bv[2];
    m_.ecc(time, q.getValue(0), q.getValue(1), e, J, bv);
    y.setValue(0, e[0]);
    y.setValue(1, e[1]);
  }
  void computeJachq(double time, const BlockVector &q, BlockVector &) override {
    double e[2], J[2][2], bv[2];
    m_.ecc(time, q.getValue(0), q.getValue(1), e, J, bv);
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) _jachq->setValue(i, j, J[i][j]);
  }
  void computehDot(double time, const BlockVector &q, BlockVector &) override {
    double e[2], J[2][2], bv[2];
    m_.ecc(time, q.getValue(0), q.getValue(1), e, J, bv);
    _hDot->setValue(0, bv[0]);
    _hDot->setValue(1, bv[1]);
  }

 private:
  ScMech m_;
};

// The clearance at the piston pin (ClearanceR's rows on the slider-crank's
// coordinates)
using PinClearanceR = ClearanceRT<ScMech>;

// A Moreau-Jean integrator (MoreauJeanOSI, or MoreauJeanCombinedProjectionOSI
// for [siconos] scheme = combined-projection) with the relation's residual
// that Siconos 4.4 leaves to the integrator
// (OneStepIntegrator::computeResiduOutput, which TimeStepping's Newton loop
// checks with setComputeResiduY(true), as EulerMoreauOSI implements it):
// Newton's law at the step's end, g'(k+1) + e_N g'(k) = 0 while the impulse
// is positive (>= 0 without one), g'(k+1) from the output the loop has just
// updated at the last iterate's positions. The slider-crank's clearance
// model needs it: its mass matrix is constant and its forces nearly linear
// over a step, so the dynamics' residual reaches round-off after one
// iteration, with the contact's Jacobian still at the positions the
// iteration started from (the normal of a pin sliding in a 100 um clearance
// turns by a few percent over a step: Newton's law was off by up to 1.3e-2
// on tests/test_siconos.c's mild case). The four-bar's mass matrix moves
// with q, and its loop iterates on.
template <class Osi>
class LawChecked : public Osi {
 public:
  LawChecked(double theta, double e_n) : Osi(theta), e_n_(e_n) {}
  // the interaction whose normal row is checked, and the system whose
  // active set (index set 1) says whether it entered the step's problem
  void watch(Interaction *inter, NonSmoothDynamicalSystem *nsds) {
    inter_ = inter;
    nsds_ = nsds;
  }
  double computeResiduOutput(double, SP::InteractionsGraph) override {
    if (!inter_ || !nsds_) return 0.0;
    SP::InteractionsGraph active = nsds_->topology()->indexSet(1);
    if (!active || !active->is_vertex(inter_->shared_from_this())) return 0.0;
    const double w = inter_->y(1)->getValue(0) + e_n_ * inter_->y_k(1)->getValue(0);
    return inter_->lambda(1)->getValue(0) > 0.0 ? std::fabs(w) : std::max(0.0, -w);
  }

 private:
  double e_n_;
  Interaction *inter_ = nullptr;
  NonSmoothDynamicalSystem *nsds_ = nullptr;
};

using fb_siconos::siconos_message;
using fb_siconos::solver_options;

// The scheme's integrator at theta: MoreauJeanOSI, or for the combined
// projection MoreauJeanCombinedProjectionOSI; law-checked (LawChecked) on
// interaction `checked` with restitution e_n when it is given
SP::MoreauJeanOSI make_osi(double theta, int projected, Interaction *checked,
                           NonSmoothDynamicalSystem *nsds, double e_n) {
  if (checked && projected) {
    auto osi = std::make_shared<LawChecked<MoreauJeanCombinedProjectionOSI>>(theta, e_n);
    osi->watch(checked, nsds);
    return osi;
  }
  if (checked) {
    auto osi = std::make_shared<LawChecked<MoreauJeanOSI>>(theta, e_n);
    osi->watch(checked, nsds);
    return osi;
  }
  if (projected) return std::make_shared<MoreauJeanCombinedProjectionOSI>(theta);
  return std::make_shared<MoreauJeanOSI>(theta);
}

struct Scene {
  fb_model_scene sm;
  int sc;          // 1: the slider-crank (ScMech msc), 0: the four-bar (Mech m)
  int cj;          // the joint the relation is written at: crank-coupler, or the piston pin
  Mech m;
  ScMech msc;
  int clearance;   // 1: joint cj is a pin in a hole
  int friction;    // 1: Coulomb friction at it (a second relation row)
  double h;        // step [s]
  size_t k;        // steps taken (time k h)
  SP::LagrangianDS ds;
  SP::Interaction inter;
  SP::NonSmoothDynamicalSystem nsds;
  SP::MoreauJeanOSI osi;
  SP::OneStepNSProblem osnspb;
  SP::OneStepNSProblem position;             // combined projection: the positions' problem
  SP::TimeSteppingCombinedProjection proj;   // combined projection: sim as itself (else null)
  SP::TimeStepping sim;
  int solver_info; // the last one-step problem's status (0: solved)
  fb_episode ep;
  double gdot;     // g' at the last step's end [m/s] (clearance)
  fb_sample x;
  double pen_now, drift;
  double me_min, me_max;
  size_t contact_steps;
  fb_stop stop;
};

// the scene whose step runs now, for the solver-status hook below (one step
// at a time per thread)
thread_local Scene *tl_stepping = nullptr;

// TimeStepping's solver-status hook: keeps the status for the step to act on
// instead of Siconos's default, which prints a warning to standard output
void keep_solver_status(int info, Simulation *) {
  if (tl_stepping && info != 0) tl_stepping->solver_info = info;
}

fb_status set_stop(Scene *s, fb_stop_kind kind, const char *detail, fb_diag *diag) {
  std::memset(&s->stop, 0, sizeof s->stop);
  s->stop.kind = kind;
  s->stop.engine = "siconos";
  s->stop.joint = -1;
  s->stop.t = (double)s->k * s->h;
  s->stop.step = s->k;
  std::snprintf(s->stop.detail, sizeof s->stop.detail, "%.150s", detail ? detail : "");
  return fb_diag_set(diag, FB_ERR_NUMERIC, "siconos: %s at t = %g s",
                     detail && *detail ? detail : "step failed", s->stop.t);
}

// 1 / (w^T M^-1 w), w = J_hole^T n: the mechanism's effective mass along n [kg]
double effective_mass(const Mech &m, double th3, double th4, const double w[2]) {
  double M[2][2];
  m.mass(th3, th4, M);
  const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
  const double wmw = (w[0] * (M[1][1] * w[0] - M[0][1] * w[1]) +
                      w[1] * (M[0][0] * w[1] - M[1][0] * w[0])) / det;
  return 1.0 / wmw;
}

// the slider-crank's sample at the state now (read_sample): the rod's
// angle, omega and alpha in body[0], the slider's x, v and a in body[1], the
// contact columns at the piston pin
void read_sample_sc(Scene *s, double impulse, const double v_old[2]) {
  fb_sample &x = s->x;
  const double t = x.t;
  const SiconosVector &q = *s->ds->q(), &v = *s->ds->velocity();
  x.crank_angle = s->msc.crank_angle(t);
  for (int b = 0; b < 2; b++) {
    x.body[b][FB_Q_POS] = q.getValue(b);
    x.body[b][FB_Q_VEL] = v.getValue(b);
    if (v_old) x.body[b][FB_Q_ACC] = (v.getValue(b) - v_old[b]) / s->h;
  }
  s->pen_now = 0.0;
  s->drift = 0.0;
  const Mech::Contact k = s->msc.contact(t, q.getValue(0), q.getValue(1));
  if (s->clearance) {
    s->pen_now = k.ecc > s->msc.c ? k.ecc - s->msc.c : 0.0;
    s->gdot = k.wn[0] * v.getValue(0) + k.wn[1] * v.getValue(1) + k.wn_t;
    double *col = x.contact[s->cj];
    col[FB_C_FORCE] = impulse / s->h;
    col[FB_C_PEN] = s->pen_now;
    col[FB_C_EX] = k.e[0];
    col[FB_C_EY] = k.e[1];
    col[FB_C_STATE] = s->ep.state;
  } else {
    s->drift = k.ecc;
  }
}

// the slider-crank's 1 / (w^T M^-1 w), M diagonal (ScMech::mass) [kg]
double effective_mass_sc(const ScMech &m, const double w[2]) {
  double M[2][2];
  m.mass(M);
  return 1.0 / (w[0] * w[0] / M[0][0] + w[1] * w[1] / M[1][1]);
}

// the sample at the state now; impulse the step's normal impulse [N s]
void read_sample(Scene *s, double impulse, const double v_old[2]) {
  fb_sample &x = s->x;
  std::memset(&x, 0, sizeof x);
  const double t = (double)s->k * s->h;
  const SiconosVector &q = *s->ds->q(), &v = *s->ds->velocity();
  x.t = t;
  if (s->sc) {
    read_sample_sc(s, impulse, v_old);
    return;
  }
  x.crank_angle = s->m.crank_angle(t);
  x.coupler_angle = q.getValue(0);
  x.coupler_omega = v.getValue(0);
  x.follower_angle = q.getValue(1);
  x.follower_omega = v.getValue(1);
  if (v_old) {
    x.coupler_alpha = (v.getValue(0) - v_old[0]) / s->h;
    x.follower_alpha = (v.getValue(1) - v_old[1]) / s->h;
  }
  s->pen_now = 0.0;
  s->drift = 0.0;
  const Mech::Contact k = s->m.contact(t, q.getValue(0), q.getValue(1));
  if (s->clearance) {
    s->pen_now = k.ecc > s->m.c ? k.ecc - s->m.c : 0.0;
    s->gdot = k.wn[0] * v.getValue(0) + k.wn[1] * v.getValue(1) + k.wn_t;
    double *col = x.contact[FB_JOINT_B];
    col[FB_C_FORCE] = impulse / s->h;
    col[FB_C_PEN] = s->pen_now;
    col[FB_C_EX] = k.e[0];
    col[FB_C_EY] = k.e[1];
    col[FB_C_STATE] = s->ep.state;
  } else {
    s->drift = k.ecc;
  }
}

} // namespace

struct fb_siconos_scene {
  Scene *s;
};

extern "C" fb_status fb_siconos_scene_create(fb_siconos_scene **out, const fb_model_scene *sm,
                                             fb_diag *diag) {
  *out = NULL;
  fb_status st = fb_scene_check(sm->def, diag);
  if (st != FB_OK) return st;
  const int sc = sm->def->source.mechanism == FB_MECH_SLIDER_CRANK;
  if (!sc && sm->def->source.mechanism != FB_MECH_FOURBAR)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': the Siconos scene builds the four-bar and the slider-crank "
                       "only", sm->model->name);
  // the joint the relation is written at (the case refuses a slider-crank's
  // clearance anywhere but at its piston pin)
  const int cj = sc ? (int)FB_SC_JOINT_COUPLER_SLIDER : (int)FB_JOINT_B;
  if (sm->clearance_mask & ~(1 << cj)) {
    const char *joint = sc ? "coupler-slider" : "crank-coupler";
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': the Siconos model has clearance at the %s joint only; "
                       "[clearance] joints names others: set [solver] builder = auto or kit "
                       "(the engine kit takes any pins), joints = %s, or drop the "
                       "siconos-clearance-* models",
                       sm->model->name, joint, joint);
  }
  fb_start_state start;
  st = fb_model_scene_start(&start, sm, diag);
  if (st != FB_OK) return st;
  fb_siconos_scene *hd = new (std::nothrow) fb_siconos_scene;
  if (!hd) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Siconos scene");
  hd->s = NULL;
  try {
    Scene *s = new Scene;
    hd->s = s;
    s->sm = *sm;
    s->sc = sc;
    s->cj = cj;
    s->clearance = (sm->clearance_mask & (1 << cj)) != 0;
    s->friction = s->clearance && sm->friction > 0.0;
    s->h = sm->solver.h;
    s->k = 0;
    s->solver_info = 0;
    std::memset(&s->ep, 0, sizeof s->ep);
    s->gdot = 0.0;
    s->me_min = s->me_max = NAN;
    s->contact_steps = 0;
    std::memset(&s->stop, 0, sizeof s->stop);
    s->stop.engine = "siconos";
    s->stop.joint = -1;
    Mech &m = s->m;
    m.a = sm->lengths.length[FB_CRANK];
    m.b = sm->lengths.length[FB_COUPLER];
    m.cl = sm->lengths.length[FB_FOLLOWER];
    m.g = sm->lengths.length[FB_GROUND];
    m.m3 = sm->link[1].mass;
    m.m4 = sm->link[2].mass;
    m.i3 = sm->link[1].inertia;
    m.i4 = sm->link[2].inertia;
    m.f3 = sm->link[1].com_fraction;
    m.f4 = sm->link[2].com_fraction;
    m.grav = sm->gravity;
    m.theta0 = start.crank_angle;
    m.omega2 = sm->omega2;
    m.c = sm->radial_clearance;
    m.r_pin = sm->pin_radius;
    m.r_hole = sm->pin_radius + sm->radial_clearance;
    if (sc) {
      // the slider-crank: lengths and masses as the reference's
      // (fb_slider_crank_of, fb_slider_crank_mass_of)
      const fb_slider_crank g = fb_slider_crank_of(&sm->lengths);
      const fb_slider_crank_mass ms = fb_slider_crank_mass_of(sm->link);
      ScMech &n = s->msc;
      n.a = g.crank;
      n.b = g.coupler;
      n.off = g.offset;
      n.m3 = ms.coupler_mass;
      n.i3 = ms.coupler_inertia;
      n.f3 = ms.coupler_com_fraction;
      n.m4 = ms.slider_mass;
      n.grav = sm->gravity;
      n.theta0 = start.crank_angle;
      n.omega2 = sm->omega2;
      n.c = sm->radial_clearance;
      n.r_pin = sm->pin_radius;
    }

    // q = (theta3, theta4) for the four-bar, (theta3, x) for the slider-crank:
    // the start's output bodies, body[output][position / velocity]
    SP::SiconosVector q0(new SiconosVector(2)), v0(new SiconosVector(2));
    q0->setValue(0, start.body[0][0]);
    q0->setValue(1, start.body[1][0]);
    v0->setValue(0, start.body[0][1]);
    v0->setValue(1, start.body[1][1]);
    if (sc)
      s->ds.reset(new SliderCrankDS(q0, v0, s->msc));
    else
      s->ds.reset(new FourbarDS(q0, v0, m));
    SP::NonSmoothLaw nsl;
    SP::Relation rel;
    if (!s->clearance) {
      nsl.reset(new EqualityConditionNSL(2));
      if (sc)
        rel.reset(new PinClosureR(s->msc));
      else
        rel.reset(new ClosureR(m));
    } else {
      const double e_n = sm->law[cj].restitution;
      if (s->friction)
        nsl.reset(new NewtonImpactFrictionNSL(e_n, 0.0, sm->friction, 2));
      else
        nsl.reset(new NewtonImpactNSL(e_n));
      if (sc)
        rel.reset(new PinClearanceR(s->msc, s->friction ? 2 : 1));
      else
        rel.reset(new ClearanceR(m, s->friction ? 2 : 1));
    }
    s->inter.reset(new Interaction(nsl, rel));
    // the run's end lies past the harness's last step: it decides when to stop
    const double t_end = sm->def->duration + 16.0 * s->h;
    s->nsds.reset(new NonSmoothDynamicalSystem(0.0, t_end));
    s->nsds->insertDynamicalSystem(s->ds);
    s->nsds->link(s->inter, s->ds);
    const int projected = sm->siconos.scheme == FB_SICONOS_COMBINED_PROJECTION;
    s->osi = make_osi(sm->siconos.theta, projected,
                      sc && s->clearance ? s->inter.get() : nullptr, s->nsds.get(),
                      sm->law[cj].restitution);
    if (!s->clearance) {
      s->osnspb.reset(new Equality());
    } else if (s->friction) {
      SP::SolverOptions opts = solver_options(SICONOS_FRICTION_2D_LEMKE);
      opts->dparam[SICONOS_DPARAM_TOL] = kFrictionSolverTolerance;
      opts->iparam[SICONOS_IPARAM_MAX_ITER] = kFrictionSolverMaxIterations;
      s->osnspb.reset(new FrictionContact(2, opts));
    } else {
      s->osnspb.reset(new LCP(solver_options(SICONOS_LCP_LEMKE)));
    }
    SP::TimeDiscretisation td(new TimeDiscretisation(0.0, s->h));
    if (projected) {
      s->position = fb_siconos::projection_problem();
      s->proj = fb_siconos::combined_projection(s->nsds, td, s->osi, s->osnspb, s->position);
      s->sim = s->proj;
    } else {
      s->sim.reset(new TimeStepping(s->nsds, td, s->osi, s->osnspb));
    }
    s->sim->setNewtonTolerance(kNewtonTolerance);
    if (sc && s->clearance) s->sim->setComputeResiduY(true);
    s->sim->setNewtonMaxIteration(kNewtonMaxIterations);
    s->sim->setWarnOnNonConvergence(false);
    s->sim->setCheckSolverFunction(keep_solver_status);
    s->sim->initialize();
    read_sample(s, 0.0, NULL);
  } catch (const std::bad_alloc &) {
    fb_siconos_scene_destroy(hd);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Siconos scene");
  } catch (const std::exception &ex) {
    const std::string msg = siconos_message(ex);
    fb_siconos_scene_destroy(hd);
    return fb_diag_set(diag, FB_ERR_NUMERIC, "model '%s': Siconos refused the system: %.600s",
                       sm->model->name, msg.c_str());
  }
  *out = hd;
  return FB_OK;
}

extern "C" fb_status fb_siconos_scene_step(fb_siconos_scene *hd, fb_diag *diag) {
  Scene *s = hd->s;
  const SiconosVector &v = *s->ds->velocity();
  const double v_old[2] = {v.getValue(0), v.getValue(1)};
  const double gdot_old = s->gdot;
  double impulse = 0.0;
  s->solver_info = 0;
  tl_stepping = s;
  try {
    s->sim->computeOneStep();
    tl_stepping = nullptr;
    if (!s->sim->isNewtonConverge()) {
      char why[96];
      std::snprintf(why, sizeof why, "Newton loop not converged in %u iterations",
                    kNewtonMaxIterations);
      s->k++;
      return set_stop(s, FB_STOP_SOLVER, why, diag);
    }
    if (s->proj && s->proj->nbProjectionIteration() >= kProjectionMaxIterations) {
      char why[128];
      std::snprintf(why, sizeof why,
                    "position projection not converged in %u iterations (violation %g m)",
                    kProjectionMaxIterations,
                    std::max(s->proj->maxViolationUnilateral(), s->proj->maxViolationEquality()));
      s->k++;
      return set_stop(s, FB_STOP_SOLVER, why, diag);
    }
    if (s->solver_info != 0) {
      char why[96];
      std::snprintf(why, sizeof why, "one-step nonsmooth problem not solved (numerics info %d)",
                    s->solver_info);
      s->k++;
      return set_stop(s, FB_STOP_SOLVER, why, diag);
    }
    if (s->clearance) impulse = s->inter->lambda(1)->getValue(0);
    s->sim->nextStep();
  } catch (const std::exception &ex) {
    tl_stepping = nullptr;
    const std::string msg = siconos_message(ex);
    s->k++;
    return set_stop(s, FB_STOP_SOLVER, msg.c_str(), diag);
  }
  s->k++;
  if (s->clearance) {
    // an episode is a run of steps with a contact impulse; it begins as an
    // impact when the pin approached the wall at >= the impact speed
    // (g' < 0 before the step)
    const int in_contact = impulse > 0.0;
    fb_episode_update(&s->ep, in_contact, s->ep.in_contact ? -s->gdot : -gdot_old,
                      s->sm.impact_velocity_min);
    if (in_contact) {
      const SiconosVector &q = *s->ds->q();
      const double t = (double)s->k * s->h;
      double me;
      if (s->sc) {
        const Mech::Contact k = s->msc.contact(t, q.getValue(0), q.getValue(1));
        me = effective_mass_sc(s->msc, k.wn);
      } else {
        const Mech::Contact k = s->m.contact(t, q.getValue(0), q.getValue(1));
        me = effective_mass(s->m, q.getValue(0), q.getValue(1), k.wn);
      }
      if (s->contact_steps == 0 || me < s->me_min) s->me_min = me;
      if (s->contact_steps == 0 || me > s->me_max) s->me_max = me;
      s->contact_steps++;
    }
  }
  read_sample(s, impulse, v_old);
  if (!std::isfinite(s->x.coupler_angle) || !std::isfinite(s->x.coupler_alpha) ||
      !std::isfinite(s->x.follower_alpha)) {
    std::memset(&s->stop, 0, sizeof s->stop);
    s->stop.kind = FB_STOP_NONFINITE;
    s->stop.engine = "siconos";
    s->stop.joint = -1;
    s->stop.t = s->x.t;
    s->stop.step = s->k;
    return fb_diag_set(diag, FB_ERR_NUMERIC, "siconos: non-finite state at t = %g s", s->x.t);
  }
  return FB_OK;
}

extern "C" void fb_siconos_scene_stopped(const fb_siconos_scene *hd, fb_stop *out) {
  *out = hd->s->stop;
}

extern "C" void fb_siconos_scene_sample(const fb_siconos_scene *hd, fb_sample *x) {
  *x = hd->s->x;
}

extern "C" void fb_siconos_scene_contact(const fb_siconos_scene *hd, fb_engine_contact *out) {
  std::memset(out, 0, sizeof *out);
  out->joint = hd->s->clearance ? hd->s->cj : -1;
  out->penetration = hd->s->pen_now;
  out->impacts[hd->s->cj] = hd->s->ep.impacts;
}

extern "C" void fb_siconos_scene_provenance(const fb_siconos_scene *hd, int joint,
                                            fb_contact_provenance *out) {
  const Scene *s = hd->s;
  out->mass_eff_min = joint == s->cj ? s->me_min : NAN;
  out->mass_eff_max = joint == s->cj ? s->me_max : NAN;
  out->erp_max = NAN;
  out->cfm_min = NAN;
  out->h_omega_max = NAN;
  out->contact_steps = joint == s->cj ? s->contact_steps : 0;
}

extern "C" double fb_siconos_scene_drift(const fb_siconos_scene *hd) { return hd->s->drift; }

extern "C" size_t fb_siconos_scene_steps(const fb_siconos_scene *hd) { return hd->s->k; }

extern "C" void fb_siconos_scene_destroy(fb_siconos_scene *hd) {
  if (!hd) return;
  // the cycle of shared pointers broken (siconos_common.hpp)
  if (hd->s && hd->s->sim)
    fb_siconos::teardown(hd->s->sim, hd->s->osi, hd->s->osnspb, hd->s->position, hd->s->nsds);
  delete hd->s;
  delete hd;
}
