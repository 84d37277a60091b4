// Siconos as a binding of the engine kit (kit.h, siconos_kit.h): any planar
// description as a Siconos nonsmooth dynamical system, built the way the
// four-bar's scene (siconos_scene.cpp) and Siconos's mechanism examples
// build theirs: Lagrangian dynamical systems, one Lagrangian relation per
// joint with its nonsmooth law, MoreauJeanOSI(theta) and TimeStepping with
// its Newton loop.
//
// Formulation (absolute coordinates, the kit's description as it is):
//   each moving body a LagrangianLinearTIDS, q = (x, y, theta) of its centre
//   of mass, M = diag(m, m, I), gravity m g along -y as its constant fExt;
//   the driven body, when the drive turns it about a ground pivot (the
//   four-bar's crank), is no coordinate: its motion theta(t) = theta0 +
//   omega t is prescribed exactly, as the four-bar scene's crank, and the
//   relations at its other joints are rheonomous (the pin moves with t);
//   a drive between two moving bodies is a rheonomous row theta1 - theta0 =
//   const + omega t;
//   a revolute joint: h = p0(q, t) - p1(q, t) = 0 (2 rows), a prismatic one:
//   the normal offset n0 . (p1 - p0) = 0 and the relative angle = const (2
//   rows), each with EqualityConditionNSL: the loops close through these
//   bilateral relations (no tree, no close_loop);
//   a clearance joint (add_clearance, the rigid limit the siconos-clearance
//   models stand for): the unilateral relation g = c - |p_pin - p_hole| >= 0
//   with Newton's impact law (NewtonImpactNSL, e_N the law's restitution),
//   the four-bar scene's ClearanceR on any two bodies.
// Every relation is a LagrangianRheonomousR h(q, t) with its Jacobian dh/dq
// and dh/dt (0 unless a side is the prescribed body). The one-step problem is
// an Equality problem for an ideal mechanism, an MLCP (the bilateral rows
// with the unilateral one, enumerative solver) with a clearance joint. The
// Newton loop also checks the relations' velocity residual at the last
// iterate (KitOSI): with constant mass matrices the dynamics' residual alone
// would stop it after one iteration, the relations' Jacobians one update old.
#include "SiconosKernel.hpp"
#include "SolverOptions.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

extern "C" {
#include "planar_loads.h"
#include "siconos_kit.h"
}
#include "siconos_angles.hpp"
#include "siconos_common.hpp"

namespace {

// Newton loop: tolerance on the dynamics' residual [kg m/s] and on the
// relations' velocity residual [m/s, rad/s], and its iteration cap (the
// four-bar scene's values, siconos_scene.cpp kNewtonTolerance).
const double kKitNewtonTolerance = 1e-12;
const unsigned kKitNewtonMaxIterations = 200;
// Below this eccentricity [m] a clearance joint's normal is taken along +x
// (the pin is a whole clearance from the wall: only the gap's sign matters).
const double kKitEccentricityMin = 1e-15;

enum Kind { REVOLUTE, PRISMATIC, DRIVE, GAP, CORNER };

struct Body {
  double m, inertia, pos0[3], vel0[3];
};

// a joint as the walk gave it, its points in each body's frame
struct Joint {
  Kind kind;
  int b[2];            // kit handles (FB_KIT_GROUND: the ground)
  double r[2][2];      // the joint's point in each body's frame (the ground's: world)
  double nl[2];        // prismatic: the normal to the axis in body b[0]'s frame
  double d0;           // prismatic, drive: theta_b1 - theta_b0 at assembly [rad]
  double rate;         // drive: d(theta_b1 - theta_b0)/dt [rad/s]
  double c, e_n;       // clearance: radial clearance [m] (corner: b + c [m]), Newton's e_N [-]
  int k;               // clearance: the description's joint index
  double ul[2];        // corner: the slide's direction in body b[0]'s frame (nl its normal)
  double o1[2];        // corner: the joint's point on body b[1] (the slider) in its frame
  double tau;          // corner: +1 the wall along +n, -1 the one along -n (planar_guide.h)
  double mu;           // corner: Coulomb's coefficient (0: frictionless, one row)
  int desc;            // the description's index of the joint
};

// a unilateral relation (a pin in its hole, a slider's corner)
bool unilateral(const Joint &j) { return j.kind == GAP || j.kind == CORNER; }

struct World;

// the coordinates (x, y, theta) of a relation's two sides (0: none)
struct Sides {
  double q[2][3];
};

// a side of a relation at (q, t): the point's position p, its Jacobian
// J = dp/dq_side (2 x 3), its time derivative pt, the body's angle th and
// its time derivative tht, its centre of mass c (the ground's: 0)
struct Pt {
  double p[2], J[2][3], pt[2], th, tht, c[2];
};

// The kit's world
struct World {
  double h, grav, theta;
  double friction;          // [clearance] friction [-]: refused at a pin in its hole
  int scheme = FB_SICONOS_MOREAU_JEAN; // [siconos] scheme (opts_siconos.h)
  int coordinates = FB_SICONOS_ABSOLUTE; // [siconos] coordinates
  int newton = FB_SICONOS_NEWTON_CONVERGED; // [siconos] newton
  const fb_case *c = nullptr; // the case, for the joints' names (NULL: numbered)
  SP::TimeSteppingCombinedProjection proj; // the combined projection's sim (else null)
  SP::OneStepNSProblem position;           // its position problem (else null)
  fb_siconos::TreeData tree;               // coordinates = angles: the tree (else null)
  const fb_planar *m = nullptr;            // the description, from a clearance joint (names)
  int walked = 0;                          // the description's joints walked so far
  std::vector<Body> body;
  std::vector<Joint> joint;
  std::vector<int> ds_of;   // body handle -> index in ds (-1: the prescribed body)
  int presc = -1;           // the prescribed body's handle
  double pivot[2] = {0, 0}, omega = 0.0;
  std::vector<SP::LagrangianDS> ds;
  std::vector<SP::Interaction> inter;
  std::vector<int> inter_joint; // inter[i]'s joint
  SP::NonSmoothDynamicalSystem nsds;
  SP::MoreauJeanOSI osi;
  SP::OneStepNSProblem osnspb;
  SP::TimeStepping sim;
  size_t k = 0;
  int info = 0;
  double force[FB_PLANAR_SPEC_MAX_JOINTS] = {0};
  std::vector<double> react;   // (3 per joint entry) its reaction over the last step (reactions)
  double clr[3 * FB_PLANAR_SPEC_MAX_JOINTS] = {0}; // (3 per description joint) a clearance
                                                    // joint's, its relations' sum (reactions)
  double presc_load[3] = {0, 0, 0}; // the prescribed body's springs' and loads' (apply_wrench)
  bool built = false;

  // body handle b's point r (its frame) at time t, its coordinates q (DS only)
  void point(Pt &o, int b, const double r[2], double t, const double *q) const {
    std::memset(&o, 0, sizeof o);
    if (b == FB_KIT_GROUND) {
      o.p[0] = r[0], o.p[1] = r[1];
      return;
    }
    double c[2];
    if (b == presc) {
      const Body &B = body[b];
      o.th = B.pos0[2] + omega * t, o.tht = omega;
      const double s = std::sin(omega * t), co = std::cos(omega * t);
      const double d[2] = {B.pos0[0] - pivot[0], B.pos0[1] - pivot[1]};
      c[0] = pivot[0] + co * d[0] - s * d[1];
      c[1] = pivot[1] + s * d[0] + co * d[1];
    } else {
      c[0] = q[0], c[1] = q[1], o.th = q[2];
    }
    const double s = std::sin(o.th), co = std::cos(o.th);
    const double rr[2] = {co * r[0] - s * r[1], s * r[0] + co * r[1]};
    o.p[0] = c[0] + rr[0], o.p[1] = c[1] + rr[1];
    o.c[0] = c[0], o.c[1] = c[1];
    if (b == presc) {
      o.pt[0] = -omega * (o.p[1] - pivot[1]);
      o.pt[1] = omega * (o.p[0] - pivot[0]);
    }
    // dp/dq of the body's (x, y, theta), the prescribed body's too: its
    // relations' Jacobians leave its columns out (KitR), its reaction takes
    // them (kit_reactions)
    o.J[0][0] = 1.0, o.J[0][2] = -rr[1];
    o.J[1][1] = 1.0, o.J[1][2] = rr[0];
  }
};

// One joint as a rheonomous Lagrangian relation on the one or two
// dynamical systems it links (col[s]: side s's first column in the block q,
// -1 when side s is the ground or the prescribed body).
class KitR : public LagrangianRheonomousR {
 public:
  KitR(const World *w, int j, const int col[2]) : w_(w), j_(j) {
    col_[0] = col[0], col_[1] = col[1];
    _hDot.reset(new SiconosVector(rows()));
  }
  int rows() const {
    const Joint &jt = w_->joint[j_];
    if (jt.kind == CORNER) return jt.mu > 0.0 ? 2 : 1; // g, and the tangential coordinate
    return jt.kind == GAP || jt.kind == DRIVE ? 1 : 2;
  }
  void computeh(double t, const BlockVector &q, BlockVector &, SiconosVector &y) override {
    double f[2], G[2][2][3], ft[2];
    eval(t, sides(q), f, G, ft);
    for (int i = 0; i < rows(); i++) y.setValue(i, f[i]);
  }
  void computeJachq(double t, const BlockVector &q, BlockVector &) override {
    double f[2], G[2][2][3], ft[2];
    eval(t, sides(q), f, G, ft);
    for (int i = 0; i < rows(); i++)
      for (int k = 0; k < 2; k++)
        for (int c = 0; col_[k] >= 0 && c < 3; c++) _jachq->setValue(i, col_[k] + c, G[i][k][c]);
  }
  void computehDot(double t, const BlockVector &q, BlockVector &) override {
    double f[2], G[2][2][3], ft[2];
    eval(t, sides(q), f, G, ft);
    for (int i = 0; i < rows(); i++) _hDot->setValue(i, ft[i]);
  }
  // the generalized force (x, y [N], the moment about the centre of mass
  // [N m]) that multipliers lam (rows(), an impulse over the step h [N s])
  // exert on side k's body, the ground's and the prescribed body's too,
  // at side coordinates qs and time t; its side's point and centre in *at
  void side_force(double t, const Sides &qs, const double *lam, double h, int k, double out[3],
                  Pt *at) const {
    double f[2], G[2][2][3], ft[2];
    Pt s[2];
    eval(t, qs, f, G, ft, s);
    for (int c = 0; c < 3; c++) {
      out[c] = 0.0;
      for (int i = 0; i < rows(); i++) out[c] += G[i][k][c] * lam[i] / h;
    }
    *at = s[k];
  }

 private:
  // side k's coordinates (x, y, theta) from the block q (0 when it has none)
  Sides sides(const BlockVector &q) const {
    Sides qs = {};
    for (int k = 0; k < 2; k++)
      for (int i = 0; col_[k] >= 0 && i < 3; i++) qs.q[k][i] = q.getValue(col_[k] + i);
    return qs;
  }
  // f(q, t), G[i][k] = df_i/dq_k over side k's coordinates (every side's,
  // a side without a system's too), ft = df/dt; the sides' points in s
  void eval(double t, const Sides &qs, double f[2], double G[2][2][3], double ft[2],
            Pt *s_out = nullptr) const {
    const Joint &jt = w_->joint[j_];
    Pt s[2];
    for (int k = 0; k < 2; k++) w_->point(s[k], jt.b[k], jt.r[k], t, qs.q[k]);
    std::memset(G, 0, 2 * 2 * 3 * sizeof(double));
    // add sign * row vector g (over side k's 3 coordinates) into G's row i
    auto put = [&](int i, int k, double sign, const double g[3]) {
      for (int c = 0; c < 3; c++) G[i][k][c] += sign * g[c];
    };
    const double th_q[3] = {0, 0, 1};
    // row i = sign dir . (p1 - p0), dir (dl in body b[0]'s frame) turning with it
    auto along = [&](int i, const double dl[2], double sign) {
      const double sn = std::sin(s[0].th), cs = std::cos(s[0].th);
      const double n[2] = {cs * dl[0] - sn * dl[1], sn * dl[0] + cs * dl[1]};
      const double d[2] = {s[1].p[0] - s[0].p[0], s[1].p[1] - s[0].p[1]};
      const double dn = -n[1] * d[0] + n[0] * d[1]; // d dir/d theta0 . d
      f[i] = sign * (n[0] * d[0] + n[1] * d[1]);
      ft[i] = sign * (dn * s[0].tht + n[0] * (s[1].pt[0] - s[0].pt[0]) +
                      n[1] * (s[1].pt[1] - s[0].pt[1]));
      for (int k = 0; k < 2; k++) {
        const double g[3] = {n[0] * s[k].J[0][0] + n[1] * s[k].J[1][0],
                             n[0] * s[k].J[0][1] + n[1] * s[k].J[1][1],
                             n[0] * s[k].J[0][2] + n[1] * s[k].J[1][2]};
        put(i, k, k == 0 ? -sign : sign, g);
      }
      const double gd[3] = {0, 0, sign * dn};
      put(i, 0, 1.0, gd);
    };
    if (jt.kind == CORNER) { // g = (b + c) - tau n . (p - o); the tangential u . (p - o)
      along(0, jt.nl, -jt.tau);
      f[0] += jt.c;
      if (jt.mu > 0.0) along(1, jt.ul, 1.0);
    } else if (jt.kind == REVOLUTE) {
      for (int i = 0; i < 2; i++) {
        f[i] = s[0].p[i] - s[1].p[i];
        ft[i] = s[0].pt[i] - s[1].pt[i];
        put(i, 0, 1.0, s[0].J[i]);
        put(i, 1, -1.0, s[1].J[i]);
      }
    } else if (jt.kind == GAP) {
      const double e[2] = {s[0].p[0] - s[1].p[0], s[0].p[1] - s[1].p[1]}, ecc = std::hypot(e[0], e[1]);
      const double n[2] = {ecc > kKitEccentricityMin ? e[0] / ecc : 1.0,
                           ecc > kKitEccentricityMin ? e[1] / ecc : 0.0};
      f[0] = jt.c - ecc;
      ft[0] = -(n[0] * (s[0].pt[0] - s[1].pt[0]) + n[1] * (s[0].pt[1] - s[1].pt[1]));
      for (int k = 0; k < 2; k++) {
        const double g[3] = {n[0] * s[k].J[0][0] + n[1] * s[k].J[1][0],
                             n[0] * s[k].J[0][1] + n[1] * s[k].J[1][1],
                             n[0] * s[k].J[0][2] + n[1] * s[k].J[1][2]};
        put(0, k, k == 0 ? -1.0 : 1.0, g);
      }
    } else {
      // the relative angle row (a prismatic joint's second, a drive's only)
      const int i = jt.kind == PRISMATIC ? 1 : 0;
      const double rate = jt.kind == DRIVE ? jt.rate : 0.0;
      f[i] = s[1].th - s[0].th - jt.d0 - rate * t;
      ft[i] = s[1].tht - s[0].tht - rate;
      put(i, 1, 1.0, th_q);
      put(i, 0, -1.0, th_q);
      if (jt.kind == PRISMATIC) along(0, jt.nl, 1.0); // n0 . (p1 - p0), n0 turning with b[0]
    }
    if (s_out) s_out[0] = s[0], s_out[1] = s[1];
  }
  const World *w_;
  int j_, col_[2];
};

// Moreau-Jean with the relations' residual at the step's end (TimeStepping's
// Newton loop with setComputeResiduY): a bilateral row's velocity |y'|, and
// a clearance joint's Newton's law while it is in the step's problem
// (siconos_scene.cpp's LawChecked, the same test).
template <class Osi>
class KitOSI : public Osi {
 public:
  KitOSI(double theta, const World *w) : Osi(theta), w_(w) {}
  double computeResiduOutput(double, SP::InteractionsGraph) override {
    double r = 0.0;
    SP::InteractionsGraph active = w_->nsds->topology()->indexSet(1);
    for (size_t i = 0; i < w_->inter.size(); i++) {
      Interaction &in = *w_->inter[i];
      const Joint &jt = w_->joint[(size_t)w_->inter_joint[i]];
      if (!unilateral(jt)) {
        for (unsigned k = 0; k < in.y(1)->size(); k++) r = std::max(r, std::fabs(in.y(1)->getValue(k)));
        continue;
      }
      if (!active || !active->is_vertex(w_->inter[i])) continue;
      const double g = in.y(1)->getValue(0) + jt.e_n * in.y_k(1)->getValue(0);
      r = std::max(r, in.lambda(1)->getValue(0) > 0.0 ? std::fabs(g) : std::max(0.0, -g));
    }
    return r;
  }

 private:
  const World *w_;
};

thread_local int *tl_info = nullptr;

// TimeStepping's solver-status hook: the status kept for the step (no print)
void keep_info(int info, Simulation *) {
  if (tl_info && info != 0) *tl_info = info;
}

void simulation(World *w);

// the system from what the walk recorded (at add_drive, the walk's last call)
void build(World *w) {
  const size_t nb = w->body.size();
  w->ds_of.assign(nb, -1);
  w->nsds.reset(new NonSmoothDynamicalSystem(0.0, 1e30));
  for (size_t b = 0; b < nb; b++) {
    if ((int)b == w->presc) continue;
    const Body &B = w->body[b];
    SP::SiconosVector q0(new SiconosVector(3)), v0(new SiconosVector(3)), f(new SiconosVector(3));
    SP::SimpleMatrix M(new SimpleMatrix(3, 3));
    M->zero();
    M->setValue(0, 0, B.m), M->setValue(1, 1, B.m), M->setValue(2, 2, B.inertia);
    for (int i = 0; i < 3; i++) q0->setValue(i, B.pos0[i]), v0->setValue(i, B.vel0[i]);
    f->zero();
    f->setValue(1, -B.m * w->grav);
    SP::LagrangianLinearTIDS d(new LagrangianLinearTIDS(q0, v0, M));
    d->setFExtPtr(f);
    w->ds_of[b] = (int)w->ds.size();
    w->ds.push_back(d);
    w->nsds->insertDynamicalSystem(d);
  }
  // the bilateral rows first, then the unilateral ones (the MLCP's order)
  bool gap = false;
  for (int pass = 0; pass < 2; pass++)
    for (size_t j = 0; j < w->joint.size(); j++) {
      const Joint &jt = w->joint[j];
      if (unilateral(jt) != (pass == 1)) continue;
      const bool held = (jt.b[0] == w->presc && jt.b[1] == FB_KIT_GROUND) ||
                        (jt.b[1] == w->presc && jt.b[0] == FB_KIT_GROUND);
      if (held && jt.kind == REVOLUTE) continue; // the prescribed body's pivot: exact
      SP::DynamicalSystem d[2];
      int col[2] = {-1, -1}, n = 0;
      for (int k = 0; k < 2; k++)
        if (jt.b[k] != FB_KIT_GROUND && w->ds_of[(size_t)jt.b[k]] >= 0) {
          d[n] = w->ds[(size_t)w->ds_of[(size_t)jt.b[k]]];
          col[k] = 3 * n++;
        }
      if (n == 0) continue; // between the ground and the prescribed body: nothing moves
      std::shared_ptr<KitR> rel(new KitR(w, (int)j, col));
      SP::NonSmoothLaw nsl;
      if (jt.kind == CORNER && jt.mu > 0.0)
        nsl.reset(new NewtonImpactFrictionNSL(jt.e_n, 0.0, jt.mu, 2)), gap = true;
      else if (unilateral(jt)) nsl.reset(new NewtonImpactNSL(jt.e_n)), gap = true;
      else nsl.reset(new EqualityConditionNSL(rel->rows()));
      SP::Interaction in(new Interaction(nsl, rel));
      if (n == 2) w->nsds->link(in, d[0], d[1]);
      else w->nsds->link(in, d[0]);
      w->inter.push_back(in);
      w->inter_joint.push_back((int)j);
    }
  if (gap) w->osnspb.reset(new fb_siconos::FreshWork<MLCP>(fb_siconos::solver_options(SICONOS_MLCP_ENUM)));
  else w->osnspb.reset(new Equality());
  simulation(w);
}

// the scheme's integrator and simulation on w->nsds and w->osnspb
void simulation(World *w) {
  const bool projected = w->scheme == FB_SICONOS_COMBINED_PROJECTION;
  if (projected) w->osi.reset(new KitOSI<MoreauJeanCombinedProjectionOSI>(w->theta, w));
  else w->osi.reset(new KitOSI<MoreauJeanOSI>(w->theta, w));
  SP::TimeDiscretisation td(new TimeDiscretisation(0.0, w->h));
  if (projected) {
    w->position = fb_siconos::projection_problem();
    w->proj = fb_siconos::combined_projection(w->nsds, td, w->osi, w->osnspb, w->position);
    w->sim = w->proj;
  } else {
    w->sim.reset(new TimeStepping(w->nsds, td, w->osi, w->osnspb));
  }
  if (w->newton == FB_SICONOS_NEWTON_CONVERGED) { // else Siconos's own, as the example's
    w->sim->setNewtonTolerance(kKitNewtonTolerance);
    w->sim->setNewtonMaxIteration(kKitNewtonMaxIterations);
    w->sim->setComputeResiduY(true);
  }
  w->sim->setWarnOnNonConvergence(false);
  w->sim->setCheckSolverFunction(keep_info);
  w->sim->initialize();
  w->built = true;
}

// a point given in the world at assembly, in body b's frame
void local(const World *w, int b, const double at[2], double r[2]) {
  if (b == FB_KIT_GROUND) {
    r[0] = at[0], r[1] = at[1];
    return;
  }
  const Body &B = w->body[(size_t)b];
  const double s = std::sin(B.pos0[2]), c = std::cos(B.pos0[2]);
  const double d[2] = {at[0] - B.pos0[0], at[1] - B.pos0[1]};
  r[0] = c * d[0] + s * d[1];
  r[1] = -s * d[0] + c * d[1];
}

// the joint (b0, b1) at `at`, its points in each frame
Joint joint_at(const World *w, Kind kind, int b0, int b1, const double at[2]) {
  Joint j;
  std::memset(&j, 0, sizeof j);
  j.kind = kind;
  j.desc = w->walked; // the walk's joints come in the description's order
  j.b[0] = b0, j.b[1] = b1;
  local(w, b0, at, j.r[0]);
  local(w, b1, at, j.r[1]);
  return j;
}

double angle0(const World *w, int b) { return b == FB_KIT_GROUND ? 0.0 : w->body[(size_t)b].pos0[2]; }

// joint jt's name for a message (the description's, when a clearance joint
// handed it; else the case's, whose joints are the description's in order)
std::string joint_name(const World *w, const Joint &jt) {
  if (w->m && jt.desc >= 0 && jt.desc < w->m->njoints)
    return std::string("'") + w->m->joint[jt.desc].name + "'";
  if (w->c && jt.desc >= 0 && jt.desc < w->c->planar.njoints)
    return std::string("'") + w->c->planar.joint[jt.desc].name + "'";
  return "number " + std::to_string(jt.desc + 1) + " of the description";
}

// The 2-D friction problem of the example's scheme: its enumerative solver
// with its tolerance and iteration cap (tests/test_siconos_slider_guide.cpp
// sets them as the example does), so that the same equations meet the same
// solver
const double kExampleFrictionTolerance = 1e-8;
const int kExampleFrictionMaxIterations = 100;

// coordinates = angles (siconos_angles.hpp): the tree of the walk's
// revolute joints, its one Lagrangian system, the corners' relations
fb_status build_angles(World *w, fb_diag *diag) {
  std::vector<fb_siconos::AngBody> body;
  for (const Body &B : w->body)
    body.push_back({B.m, B.inertia, {B.pos0[0], B.pos0[1], B.pos0[2]}, B.vel0[2]});
  std::vector<fb_siconos::AngPin> pin;
  std::vector<const Joint *> pin_joint;
  bool friction = false;
  for (const Joint &jt : w->joint) {
    if (jt.kind == PRISMATIC || jt.kind == GAP)
      return fb_diag_set(diag, FB_ERR_ARG, "[siconos] coordinates = angles: joint %s is %s; the "
                         "angle coordinates take a tree of revolute joints from the ground (the "
                         "clearance joints out) and a slider's guide as its corners; "
                         "coordinates = absolute takes any joint", joint_name(w, jt).c_str(),
                         jt.kind == PRISMATIC ? "an ideal prismatic joint"
                                              : "a pin in its hole with clearance");
    if (jt.kind == REVOLUTE) {
      pin.push_back({{jt.b[0], jt.b[1]}, {{jt.r[0][0], jt.r[0][1]}, {jt.r[1][0], jt.r[1][1]}}});
      pin_joint.push_back(&jt);
    }
    friction = friction || (jt.kind == CORNER && jt.mu > 0.0);
  }
  const std::string why = fb_siconos::angle_tree(&w->tree, body, pin, w->grav);
  if (why.rfind("pin ", 0) == 0)
    return fb_diag_set(diag, FB_ERR_ARG, "[siconos] coordinates = angles: joint %s closes a loop "
                       "of revolute joints; the angle coordinates take a tree from the ground "
                       "(coordinates = absolute takes loops)",
                       joint_name(w, *pin_joint[(size_t)std::stoi(why.substr(4))]).c_str());
  if (why.rfind("body ", 0) == 0) {
    const int b = std::stoi(why.substr(5));
    return fb_diag_set(diag, FB_ERR_ARG, "[siconos] coordinates = angles: body %s is not reached "
                       "from the ground by revolute joints", w->m ? w->m->body[b + 1].name
                                                                  : std::to_string(b + 1).c_str());
  }
  if (!why.empty()) return fb_diag_set(diag, FB_ERR_RANGE, "[siconos] coordinates = angles: %s",
                                       why.c_str());
  w->nsds.reset(new NonSmoothDynamicalSystem(0.0, 1e30));
  SP::LagrangianDS ds = fb_siconos::angle_ds(w->tree, body);
  w->ds.push_back(ds);
  w->nsds->insertDynamicalSystem(ds);
  for (size_t j = 0; j < w->joint.size(); j++) {
    const Joint &jt = w->joint[j];
    if (jt.kind != CORNER) continue;
    const fb_siconos::AngCorner k = {jt.b[0], jt.b[1], {jt.r[0][0], jt.r[0][1]},
                                     {jt.r[1][0], jt.r[1][1]}, {jt.nl[0], jt.nl[1]},
                                     {jt.ul[0], jt.ul[1]}, jt.tau, jt.c, jt.mu > 0.0};
    SP::NonSmoothLaw nsl;
    if (k.friction) nsl.reset(new NewtonImpactFrictionNSL(jt.e_n, 0.0, jt.mu, 2));
    else nsl.reset(new NewtonImpactNSL(jt.e_n));
    SP::Interaction in(new Interaction(nsl, fb_siconos::angle_corner(w->tree, k)));
    w->nsds->link(in, ds);
    w->inter.push_back(in);
    w->inter_joint.push_back((int)j);
  }
  if (friction) {
    SP::SolverOptions o = fb_siconos::solver_options(SICONOS_FRICTION_2D_ENUM);
    o->dparam[SICONOS_DPARAM_TOL] = kExampleFrictionTolerance;
    o->iparam[SICONOS_IPARAM_MAX_ITER] = kExampleFrictionMaxIterations;
    w->osnspb.reset(new FrictionContact(2, o));
  } else {
    w->osnspb.reset(new fb_siconos::FreshWork<MLCP>(fb_siconos::solver_options(SICONOS_MLCP_ENUM)));
  }
  simulation(w);
  return FB_OK;
}

// runs f, turning a Siconos exception into an error naming it
template <class F>
fb_status guarded(fb_diag *diag, const char *what, F f) {
  try {
    f();
  } catch (const std::bad_alloc &) {
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Siconos system");
  } catch (const std::exception &ex) {
    return fb_diag_set(diag, FB_ERR_NUMERIC, "siconos: %s: %.600s", what,
                       fb_siconos::siconos_message(ex).c_str());
  }
  return FB_OK;
}

// Every joint's reaction over the step just taken (kit.h reactions and
// clearance_reaction), its mean force, into w->react (an ideal joint's) and
// w->clr (a clearance joint's, its relations' sum: a guide's four corners):
// a relation's, the generalized force its multipliers (the step's impulse
// lambda(1), over h) exert on body[1] (on body[0], turned, when body[1] is
// the ground; KitR::side_force) through the relation's Jacobian at the
// step's end t, the state Moreau-Jean took it at (so the moments are those
// the step applied), its moment moved from the body's centre to the joint's
// point there (a corner's: the slider's point of the joint, not the corner);
// a drive row's couple added to its joint's; the prescribed body's pivot (no
// relation: its motion is exact) from that body's balance: the force, m
// (v_end - v_start) / h less the others on it (a clearance joint's contact
// too); the drive's torque, about the pivot, where the body's angular
// momentum is constant and the pivot's force has no moment.
void reactions(World *w, double t) {
  w->react.assign(3 * w->joint.size(), 0.0);
  std::fill(std::begin(w->clr), std::end(w->clr), 0.0);
  double on_presc[3] = {0, 0, 0}; // the relations' force and moment about its centre
  for (size_t i = 0; i < w->inter.size(); i++) {
    const int j = w->inter_joint[i];
    const Joint &jt = w->joint[(size_t)j];
    const KitR &rel = static_cast<const KitR &>(*w->inter[i]->relation());
    Sides qs = {};
    for (int k = 0; k < 2; k++) {
      const int d = jt.b[k] == FB_KIT_GROUND ? -1 : w->ds_of[(size_t)jt.b[k]];
      for (int c = 0; d >= 0 && c < 3; c++) qs.q[k][c] = w->ds[(size_t)d]->q()->getValue(c);
    }
    double lam[2] = {0, 0};
    for (int r = 0; r < rel.rows(); r++) lam[r] = w->inter[i]->lambda(1)->getValue(r);
    for (int k = 0; k < 2; k++) {
      if (jt.b[k] != w->presc) continue;
      double q[3];
      Pt at;
      rel.side_force(t, qs, lam, w->h, k, q, &at);
      for (int c = 0; c < 3; c++) on_presc[c] += q[c];
    }
    // the joint entry whose reaction it is: a drive row's, its revolute joint's
    size_t e = (size_t)j;
    for (size_t o = 0; jt.kind == DRIVE && o < w->joint.size(); o++)
      if (w->joint[o].kind == REVOLUTE && w->joint[o].desc == jt.desc) e = o;
    const int k = jt.b[1] != FB_KIT_GROUND ? 1 : 0;
    const double sign = k == 1 ? 1.0 : -1.0;
    double q[3];
    Pt at;
    rel.side_force(t, qs, lam, w->h, k, q, &at);
    if (jt.kind == CORNER && k == 1) w->point(at, jt.b[1], jt.o1, t, qs.q[1]);
    const double m = q[2] + (at.c[0] - at.p[0]) * q[1] - (at.c[1] - at.p[1]) * q[0];
    double *to = unilateral(jt) ? w->clr + 3 * jt.k : &w->react[3 * e];
    to[0] += sign * q[0];
    to[1] += sign * q[1];
    to[2] += sign * m;
  }
  if (w->presc < 0) return;
  for (size_t j = 0; j < w->joint.size(); j++) {
    const Joint &jt = w->joint[j];
    const int s = jt.b[0] == FB_KIT_GROUND ? 1 : 0; // the prescribed body's side
    if (jt.kind != REVOLUTE || jt.b[s] != w->presc || jt.b[1 - s] != FB_KIT_GROUND) continue;
    const Body &B = w->body[(size_t)w->presc];
    Pt g[2]; // its centre at the step's start and end
    const double zero[2] = {0, 0};
    w->point(g[0], w->presc, zero, t - w->h, nullptr);
    w->point(g[1], w->presc, zero, t, nullptr);
    // m (v_end - v_start) / h = F_pivot + the relations' + the weight + the loads'
    const double f[2] = {B.m * (g[1].pt[0] - g[0].pt[0]) / w->h - on_presc[0] - w->presc_load[0],
                         B.m * (g[1].pt[1] - g[0].pt[1]) / w->h - on_presc[1] + B.m * w->grav -
                             w->presc_load[1]};
    // about the pivot, its angular momentum (I + m r^2) omega constant: 0 = T + the
    // relations' moments + the weight's and the loads' (the pivot's force has none)
    const double r[2] = {g[1].p[0] - w->pivot[0], g[1].p[1] - w->pivot[1]}; // pivot to centre
    const double fa[2] = {on_presc[0] + w->presc_load[0],
                          on_presc[1] - B.m * w->grav + w->presc_load[1]};
    const double torque = -(on_presc[2] + w->presc_load[2] + r[0] * fa[1] - r[1] * fa[0]);
    const double sign = s == 1 ? 1.0 : -1.0; // on body[1] from body[0]
    w->react[3 * j] = sign * f[0];
    w->react[3 * j + 1] = sign * f[1];
    w->react[3 * j + 2] = sign * torque;
  }
}

} // namespace

extern "C" {

static fb_status kit_world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  World *w = new (std::nothrow) World;
  if (!w) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Siconos world");
  w->h = o->h;
  w->grav = o->gravity;
  w->theta = o->c ? o->c->siconos.theta : 0.5;
  w->scheme = o->c ? o->c->siconos.scheme : FB_SICONOS_MOREAU_JEAN;
  w->coordinates = o->c ? o->c->siconos.coordinates : FB_SICONOS_ABSOLUTE;
  w->newton = o->c ? o->c->siconos.newton : FB_SICONOS_NEWTON_CONVERGED;
  w->c = o->c;
  w->friction = o->c ? o->c->clearance.friction : 0.0;
  if (w->coordinates == FB_SICONOS_ANGLES && o->mech && fb_planar_has_loads(o->mech)) {
    delete w;
    return fb_diag_set(diag, FB_ERR_ARG, "[siconos] coordinates = angles: springs, loads and a "
                       "torque drive are applied in the absolute coordinates only (each body's "
                       "external force); give [siconos] coordinates = absolute");
  }
  *out = w;
  return FB_OK;
}

static fb_status kit_add_body(void *vw, const fb_kit_body *b, fb_diag *diag) {
  (void)diag;
  World *w = static_cast<World *>(vw);
  Body B;
  B.m = b->mass, B.inertia = b->inertia;
  for (int i = 0; i < 3; i++) B.pos0[i] = b->pos[i], B.vel0[i] = b->vel[i];
  w->body.push_back(B);
  return FB_OK;
}

static fb_status kit_add_revolute(void *vw, int b0, int b1, const double at[2], fb_diag *diag) {
  (void)diag;
  World *w = static_cast<World *>(vw);
  w->joint.push_back(joint_at(w, REVOLUTE, b0, b1, at));
  w->walked++;
  return FB_OK;
}

static fb_status kit_add_prismatic(void *vw, int b0, int b1, const double at[2],
                                   const double axis[2], fb_diag *diag) {
  (void)diag;
  World *w = static_cast<World *>(vw);
  Joint j = joint_at(w, PRISMATIC, b0, b1, at);
  const double a = angle0(w, b0), s = std::sin(a), c = std::cos(a);
  const double nw[2] = {-axis[1], axis[0]}; // the axis's normal in the world
  j.nl[0] = c * nw[0] + s * nw[1];
  j.nl[1] = -s * nw[0] + c * nw[1];
  j.d0 = angle0(w, b1) - a;
  w->joint.push_back(j);
  w->walked++;
  return FB_OK;
}

// a slider in its guide (planar_guide.h): its four corners (sigma, tau) as
// unilateral relations g = (b + c) - tau n . (p - o) >= 0, o the joint's
// point on the guide (c->pin), p the corner on the slider (c->hole), n the
// slide's normal turning with the guide; Newton's law, Coulomb's friction
// on the tangential coordinate u . (p - o) when mu > 0
static fb_status add_corners(World *w, int k, const fb_kit_clearance_joint *c, fb_diag *diag) {
  if (w->friction > 0.0 && w->coordinates == FB_SICONOS_ABSOLUTE)
    return fb_diag_set(diag, FB_ERR_ARG, "[clearance] friction = %g at prismatic joint '%s': "
                       "Siconos's 2-D friction problem takes no bilateral row, and absolute "
                       "coordinates hold the joints by bilateral rows; give [siconos] coordinates "
                       "= angles, or friction = 0", w->friction, c->m->joint[k].name);
  const fb_planar_guide &g = c->guide;
  const double *u = c->axis, n[2] = {-c->axis[1], c->axis[0]};
  const double a0 = angle0(w, c->pin), s0 = std::sin(a0), c0 = std::cos(a0);
  for (int i = 0; i < FB_PLANAR_GUIDE_CORNERS; i++) {
    const double sigma = i % 2 ? 1.0 : -1.0, tau = i < 2 ? 1.0 : -1.0; // planar_guide.h's order
    const double p[2] = {c->at[0] + sigma * g.half_length * u[0] + tau * g.half_height * n[0],
                         c->at[1] + sigma * g.half_length * u[1] + tau * g.half_height * n[1]};
    Joint j = joint_at(w, CORNER, c->pin, c->hole, c->at);
    j.o1[0] = j.r[1][0], j.o1[1] = j.r[1][1];
    local(w, c->hole, p, j.r[1]);
    j.nl[0] = c0 * n[0] + s0 * n[1], j.nl[1] = -s0 * n[0] + c0 * n[1];
    j.ul[0] = c0 * u[0] + s0 * u[1], j.ul[1] = -s0 * u[0] + c0 * u[1];
    j.tau = tau;
    j.c = g.half_height + g.clearance;
    j.mu = w->friction;
    j.e_n = c->restitution, j.k = k;
    w->joint.push_back(j);
  }
  return FB_OK;
}

// a pin in its hole: g = c - |p_pin - p_hole| >= 0, frictionless
static fb_status add_gap(World *w, int k, const fb_kit_clearance_joint *c, fb_diag *diag) {
  if (w->friction > 0.0)
    return fb_diag_set(diag, FB_ERR_ARG, "[clearance] friction = %g: the Siconos binding of the "
                       "engine kit builds a frictionless clearance joint (friction = 0)",
                       w->friction);
  Joint j = joint_at(w, GAP, c->pin, c->hole, c->at);
  j.c = c->radial_clearance;
  j.e_n = c->restitution, j.k = k;
  w->joint.push_back(j);
  return FB_OK;
}

static fb_status kit_add_clearance(void *vw, int k, const fb_kit_clearance_joint *c,
                                   fb_diag *diag) {
  World *w = static_cast<World *>(vw);
  if (k < 0 || k >= FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_ARG, "clearance joint %d out of range", k);
  const fb_status st = c->kind == FB_KIND_PRISMATIC ? add_corners(w, k, c, diag)
                                                    : add_gap(w, k, c, diag);
  w->m = c->m; // the description, for the joints' names
  w->walked++;
  return st;
}

// the drive: a revolute joint to the ground prescribes its body (the
// four-bar scene's crank); between two moving bodies, a rheonomous row
static fb_status kit_add_drive(void *vw, int joint, double rate, fb_diag *diag) {
  World *w = static_cast<World *>(vw);
  const bool angles = w->coordinates == FB_SICONOS_ANGLES;
  if (joint < 0) { // undriven: the walk's end
    fb_status st = FB_OK;
    const fb_status g = guarded(diag, "the system was refused", [&] {
      if (angles) st = build_angles(w, diag);
      else build(w);
    });
    return g != FB_OK ? g : st;
  }
  if (angles)
    return fb_diag_set(diag, FB_ERR_ARG, "[siconos] coordinates = angles: an undriven "
                       "description only ([drive] joint = none); coordinates = absolute drives");
  int n = -1;
  size_t j = 0;
  for (; j < w->joint.size(); j++)
    if (!unilateral(w->joint[j]) && ++n == joint) break;
  if (j == w->joint.size() || w->joint[j].kind != REVOLUTE)
    return fb_diag_set(diag, FB_ERR_ARG, "the Siconos kit drives a revolute joint only");
  Joint &jt = w->joint[j];
  if (jt.b[0] == FB_KIT_GROUND || jt.b[1] == FB_KIT_GROUND) {
    const int s = jt.b[0] == FB_KIT_GROUND ? 1 : 0;
    w->presc = jt.b[s];
    w->omega = s == 1 ? rate : -rate;
    w->pivot[0] = jt.r[1 - s][0], w->pivot[1] = jt.r[1 - s][1];
  } else {
    Joint d = jt;
    d.kind = DRIVE;
    d.rate = rate;
    d.d0 = angle0(w, jt.b[1]) - angle0(w, jt.b[0]);
    w->joint.push_back(d);
  }
  return guarded(diag, "the system was refused", [w] { build(w); });
}

static fb_status kit_step(void *vw, fb_diag *diag) {
  World *w = static_cast<World *>(vw);
  w->info = 0;
  tl_info = &w->info;
  const fb_status st = guarded(diag, "step failed", [w] { w->sim->computeOneStep(); });
  tl_info = nullptr;
  const double t = (double)(w->k + 1) * w->h;
  if (st != FB_OK) return st;
  if (w->newton == FB_SICONOS_NEWTON_CONVERGED && !w->sim->isNewtonConverge()) // the example goes on
    return fb_diag_set(diag, FB_ERR_NUMERIC, "siconos: Newton loop not converged in %u iterations "
                       "at t = %g s", kKitNewtonMaxIterations, t);
  if (w->info != 0)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "siconos: one-step nonsmooth problem not solved "
                       "(numerics info %d) at t = %g s", w->info, t);
  if (w->proj && w->proj->nbProjectionIteration() >= fb_siconos::kProjectionMaxIterations)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "siconos: position projection not converged in %u "
                       "iterations at t = %g s (violation %g m)",
                       fb_siconos::kProjectionMaxIterations, t,
                       std::max(w->proj->maxViolationUnilateral(), w->proj->maxViolationEquality()));
  for (const Joint &jt : w->joint)
    if (unilateral(jt)) w->force[jt.k] = 0.0;
  for (size_t i = 0; i < w->inter.size(); i++) { // a guide's: its corners' sum
    const Joint &jt = w->joint[(size_t)w->inter_joint[i]];
    if (unilateral(jt)) w->force[jt.k] += w->inter[i]->lambda(1)->getValue(0) / w->h;
  }
  if (!w->tree) reactions(w, (double)(w->k + 1) * w->h);
  const fb_status nx = guarded(diag, "step failed", [w] { w->sim->nextStep(); });
  w->k++;
  return nx;
}

// the springs', loads' and torque drive's force at body handle b's centre
// of mass and torque for the coming step (kit.h apply_wrench): its
// Lagrangian system's external force, the weight beside it, held over the
// step as Moreau-Jean holds a constant fExt (coordinates = absolute; the
// angles' refuse a description with loads at kit_world_new)
static void kit_apply_wrench(void *vw, int b, const double f[3]) {
  World *w = static_cast<World *>(vw);
  if (!w->built || w->coordinates != FB_SICONOS_ABSOLUTE) return;
  const int d = w->ds_of[(size_t)b];
  if (d < 0) { // the prescribed body: its motion is given, its drive balances them (reactions)
    for (int i = 0; i < 3; i++) w->presc_load[i] = f[i];
    return;
  }
  SiconosVector &fe = *w->ds[(size_t)d]->fExt();
  fe.setValue(0, f[0]);
  fe.setValue(1, f[1] - w->body[(size_t)b].m * w->grav);
  fe.setValue(2, f[2]);
}

// ideal joint k's (its place among the joints added) reaction over the last
// step (kit.h): the walk's k-th bilateral joint entry (a drive row, added
// after the walk, is in its joint's)
static void kit_reactions(const void *vw, int k, double out[3]) {
  const World *w = static_cast<const World *>(vw);
  out[0] = out[1] = out[2] = 0.0;
  int n = -1;
  for (size_t j = 0; j < w->joint.size(); j++) {
    const Joint &jt = w->joint[j];
    if (unilateral(jt) || jt.kind == DRIVE || ++n != k) continue;
    for (int c = 0; c < 3 && 3 * j + 2 < w->react.size(); c++) out[c] = w->react[3 * j + c];
    return;
  }
}

// clearance joint j's (the description's index) reaction over the last
// step (kit.h clearance_reaction): its relations' (reactions)
static void kit_clearance_reaction(const void *vw, int j, double out[3]) {
  const World *w = static_cast<const World *>(vw);
  for (int c = 0; c < 3; c++)
    out[c] = j >= 0 && j < FB_PLANAR_SPEC_MAX_JOINTS ? w->clr[3 * j + c] : 0.0;
}

// reactions in absolute coordinates only: the angle coordinates' tree
// joints are no relations (siconos_angles.hpp), so no multiplier holds them
static int kit_reactions_in(const fb_kit_world *o) {
  return !o->c || o->c->siconos.coordinates == FB_SICONOS_ABSOLUTE;
}

// clearance joint k's normal force over the last step (kit.h contact_force;
// the kit asks at the joint's index, a guide's corners summed), 0 out of range
static double kit_contact_force(const void *vw, int k) {
  return k >= 0 && k < FB_PLANAR_SPEC_MAX_JOINTS ? static_cast<const World *>(vw)->force[k] : 0.0;
}

static void kit_body_state(const void *vw, int b, double pos[3], double vel[3]) {
  const World *w = static_cast<const World *>(vw);
  if (w->tree) { // coordinates = angles: the tree's one system
    const LagrangianDS &d = *w->ds[0];
    fb_siconos::angle_state(w->tree, b, &(*d.q())(0), &(*d.velocity())(0), pos, vel);
    return;
  }
  if (b == w->presc) {
    Pt o;
    const double zero[2] = {0, 0};
    const double t = (double)w->k * w->h;
    w->point(o, b, zero, t, nullptr);
    pos[0] = o.p[0], pos[1] = o.p[1], pos[2] = o.th;
    vel[0] = o.pt[0], vel[1] = o.pt[1], vel[2] = o.tht;
    return;
  }
  const LagrangianDS &d = *w->ds[(size_t)w->ds_of[(size_t)b]];
  for (int i = 0; i < 3; i++) pos[i] = d.q()->getValue(i), vel[i] = d.velocity()->getValue(i);
}

static void kit_world_free(void *vw) {
  World *w = static_cast<World *>(vw);
  if (w->built) fb_siconos::teardown(w->sim, w->osi, w->osnspb, w->position, w->nsds);
  delete w;
}

// the table in fb_kit_binding's order (kit.h; C++17 has no designated
// initialisers)
const fb_kit_binding fb_siconos_kit = {
    "siconos",          kit_world_new,     kit_add_body, kit_add_revolute,
    kit_add_prismatic,  NULL /* close_loop: the bilateral relations close the loops */,
    kit_add_drive,      NULL /* hold_in_plane: planar coordinates */,
    NULL /* add_contact: the clearance is a relation (add_clearance) */,
    kit_contact_force,  kit_step,          kit_body_state, kit_world_free,
    kit_add_clearance,  0 /* applied_force: no penalty row */,
    NULL /* model_text: Siconos reads no model file */,
    NULL /* contact_force_max: an impulse per step, no sub-steps */,
    0 /* contact_rows: a unilateral relation, no soft row */,
    kit_reactions,
    NULL /* contact_force_vec: the normal force along the normal */,
    0 /* friction: add_clearance reads [clearance] friction itself */,
    NULL /* body_accel: the step's difference */,
    0 /* explicit_law: no applied force */,
    kit_apply_wrench,
    0 /* loads_from_state: none */,
    kit_reactions_in,
    kit_clearance_reaction,
    NULL /* collide: no collider of its own */,
    NULL /* collided */,
    NULL /* penetration: the exact one */,
    0 /* contact_always: no add_contact */,
    NULL /* step_by: Moreau-Jean at a fixed h */,
    0 /* persistent_rule: no adaptive step */,
    0 /* contact_speed_limit: no fixed row's world */,
    NULL /* body_rotation: from the angle */,
};

} // extern "C"
