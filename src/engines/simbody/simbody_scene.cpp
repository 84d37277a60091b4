// The Simbody scene (simbody_scene.h): the only translation unit of the
// project that includes Simbody. C++ stays inside this file; the C side sees
// the extern "C" functions of simbody_scene.h only.
//
// How Simbody is driven (docs/engines.md, "How each engine is driven"): the
// integrator runs to the run's end on its own error-controlled steps
// (Integrator::stepTo(final time) with setReturnEveryInternalStep, so that
// control comes back after every step it takes); each step's end state is a
// knot, realized by the integrator through accelerations. The output grid
// k h is filled between two knots by cubic Hermite interpolation, the
// interpolant Simbody's own interpolated reports use
// (AbstractIntegratorRep::createInterpolatedState: positions from q and
// qdot, velocities from u and udot at both ends); the accelerations are the
// derivative of that velocity cubic, so they equal the realized udot at the
// knots; the loads a cubic through their knot values. No State is copied
// per sample.
//
// Exact samples only where a peak needs them: a local extreme of a velocity,
// acceleration or load of the interpolated series that leads its
// neighbourhood has its knot interval refined (kRefine - 1 samples realized
// exactly, the others corrected by the exact-minus-interpolated difference
// interpolated between those) and the extreme found on the refined series,
// it and its neighbours realized exactly. An exact sample is what Simbody
// makes of an interpolated report: the interpolated q and u set into one
// scratch State, projected onto the constraints at the integrator's
// constraint tolerance, realized through accelerations.
#include "Simbody.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <memory>
#include <new>
#include <vector>
#include <algorithm>

extern "C" {
#include "clock.h"
#include "contact.h"
#include "effective_mass.h"
#include "episode.h"
#include "simbody_scene.h"
}

using namespace SimTK;

namespace {

// Internal steps the integrator may take between two output samples before
// the run stops with the named reason "step budget" (FB_STOP_STEP_BUDGET):
// the reference's FB_REFERENCE_STEPS_PER_SAMPLE budget is an average over
// the run; this one is per sample, so a collapsing step size stops the run
// within one sample interval instead of running on without end.
const long kStepsPerSampleMax = 200000;

// Mobilities, in the knots' arrays: the crank (angle prescribed), the
// follower (about D), the coupler (about C, relative to the follower).
enum { kCrank = 0, kFollower = 1, kCoupler = 2, kMobilities = 3 };

// Load components, in the knots' and samples' order: the drive torque, then
// the reaction at A, B, C, D (x, y; invdyn.h's convention).
const int kLoads = 9;

// Columns whose local extremes call for an exact realization: the coupler's
// and follower's angular accelerations, the drive torque, the four reaction
// magnitudes and the two angular velocities (the peaks summary.json, check
// and the tests take).
const int kTracked = 9;
// the columns whose minimum no metric takes: the reaction magnitudes
const int kMaxOnly[kTracked] = {0, 0, 0, 1, 1, 1, 1, 0, 0};

// Exact states a knot interval holding a peak is refined with: the interval
// is cut into kRefine pieces at grid samples realized exactly, and the
// interpolation's error there (exact - interpolated, a smooth function over
// the interval) is interpolated between them and taken off the others. On
// the paper case (1 ms steps, errors up to 1.5e-3 rad/s in omega, 5 rad/s^2
// in alpha, 2e-3 of the loads) the refined samples lie within the
// projection's own scatter of the exact ones. Exact samples of the ideal
// model over 2 revolutions: 3 pieces 2.4 % of the grid, 4: 1.7 %, 6: 1.4 %,
// 8: 1.5 %, 12: 1.8 % (fewer pieces leave more refined samples above a
// peak, each then realized; more cost more nodes).
const int kRefine = 6;

// Knot intervals a peak's search may refine, at most: the exact peak lies in
// the interval of the interpolated one or a neighbour, and the samples an
// interpolation error lifts above it in one or two more.
const int kRefineMaxIntervals = 6;

// A local extreme of the interpolated series is made exact only when no
// record within kDominanceTurn of a crank turn on either side passes it by
// more than kDominanceMargin (relative): the peaks the metrics take lead
// their neighbourhood, and the margin is 5 times the interpolation's largest
// error (loads 2e-3 of their peak on the paper case), so that an extreme
// the interpolation has put a little low is still made exact. A clearance
// model's ringing in contact has thousands of local extremes per
// revolution; this keeps the few that lead.
const double kDominanceTurn = 0.02;
const double kDominanceMargin = 1e-2;

// How far below a peak (relative) the series must have fallen for the
// search to stop looking beside it for interpolated samples above it: 10
// times the largest interpolation error measured between the knots on the
// paper case (loads 2.3e-3 of their peak, accelerations 4e-4, velocities
// 2e-5).
const double kPeakClearance = 2.5e-2;

// Knot intervals the records are generated ahead of the one handed out (a
// peak's search reaches this far each way), and the most records that
// makes (memory, when the integrator takes long steps on a fine grid).
const double kLookaheadIntervals = 3.0;
const size_t kLookaheadMax = 100000;

// The contact at the crank-coupler joint in one state: the law's force at
// the exact pin-in-hole eccentricity.
struct ContactEval {
  double e[2];     // eccentricity pin - hole [m]
  double edot[2];  // its rate [m/s]
  double pen;      // penetration depth, >= 0 [m]
  double ddot;     // penetration rate (> 0 approaching) [m/s]
  double force;    // normal force on the coupler along +n [N]
  double n[2];     // unit normal (pin - hole)/|pin - hole|
  double mass_eff; // effective mass along n [kg] (restitution law), else NAN
};

// Values a sample is filled from: mobilities q (3) and u (3), the coupler's
// and follower's angular accelerations (2), the loads (kLoads).
const int kVals = 2 * 3 + 2 + 9;

// One integrator step's end: the state the integrator advanced to,
// realized through accelerations.
struct Knot {
  double t;
  double q[kMobilities], u[kMobilities], udot[kMobilities];
  double load[kLoads];  // drive torque [N m], reactions [N]
  double drift;         // the Ball constraint's violation (ideal) [m]
  double e[2], edot[2]; // eccentricity and its rate (clearance) [m, m/s]
  double w[2][2];       // inverse effective-mass tensor at B (restitution law) [1/kg]
  int w_ok;             // 1: w holds the tensor
  double force, pen;    // the law's force [N] and the penetration [m] here
  double alpha[2];      // coupler and follower angular accelerations [rad/s^2]
  fb_episode ep;        // the contact episodes after this knot's update
  long id;              // serial number (-1: an exact state inside an interval)
  int refined;          // 1: the interval from this knot on was refined (kRefine)
};

// One output sample on the grid k h.
struct Record {
  int valid;            // 0: not generated (past the run's end, or a failed step)
  int at_knot;          // 1: the sample is a knot (already exact)
  int exact;            // 1: realized exactly (realize_exact)
  int refined;          // 1: corrected by the exact states of a refined interval
  double v[kVals];      // the values the sample is filled from (fill_sample)
  ContactEval ce;       // the contact it is filled from (clearance)
  double t;
  double q[kMobilities], u[kMobilities]; // the state as first interpolated
  fb_sample x;          // with drive_torque and reaction filled
  double drift, pen;
  double track[kTracked];
  fb_episode ep;        // the episodes the integration over this sample's interval saw
  // the knots in ((k-1) h, k h]: contact, their extremes, a new impact
  int knot_contact, new_impact;
  double kmax_force, kmax_pen, ka3, ka4;
};

// A local extreme of tracked column m of the interpolated series at record
// j: sign +1 a maximum, -1 a minimum.
struct Peak {
  size_t j;
  int m;
  int sign;
};

struct Scene;

// The crank drive: the crank angle prescribed at position level,
// theta2(t) = theta0 + omega2 t, so the crank follows the analytic angle
// exactly (a velocity-level Motion::Steady leaves the angle to the
// integrator and to the constraint projection, which moved it by 7e-6 rad
// over 3 revolutions at accuracy 1e-6). The drive torque is the Motion's
// multiplier (SimbodyMatterSubsystem::findMotionForces).
class SteadyAngle : public Motion::Custom::Implementation {
 public:
  SteadyAngle(double theta0, double omega) : theta0_(theta0), omega_(omega) {}
  Motion::Level getLevel(const State &) const override { return Motion::Position; }
  void calcPrescribedPosition(const State &s, int, Real *q) const override {
    q[0] = theta0_ + omega_ * s.getTime();
  }
  void calcPrescribedPositionDot(const State &, int, Real *qdot) const override { qdot[0] = omega_; }
  void calcPrescribedPositionDotDot(const State &, int, Real *qdotdot) const override {
    qdotdot[0] = 0.0;
  }
  Implementation *clone() const override { return new SteadyAngle(*this); }

 private:
  double theta0_, omega_;
};

// The project's contact law (contact.h) as a Simbody custom force: +F n on
// the coupler's hole centre, -F n on the crank's pin centre.
class ClearanceForce : public Force::Custom::Implementation {
 public:
  explicit ClearanceForce(const Scene *s) : s_(s) {}
  void calcForce(const State &state, Vector_<SpatialVec> &bodyForces, Vector_<Vec3> &,
                 Vector &) const override;
  Real calcPotentialEnergy(const State &) const override { return 0.0; }

 private:
  const Scene *s_;
};

struct Scene {
  fb_scene_model sm;
  int clearance;          // 1: the crank-coupler joint is a pin in a hole
  double a, b, c, g;      // crank, coupler, follower, ground lengths [m]
  double theta0, omega2;  // the prescribed crank angle theta0 + omega2 t
  MultibodySystem system;
  SimbodyMatterSubsystem matter;
  GeneralForceSubsystem forces;
  MobilizedBody::Pin crank, follower, coupler;
  Constraint::Ball ball;  // ideal models only
  std::unique_ptr<Integrator> integ;
  State scratch;          // the one State exact samples are realized in
  double h;               // output step [s]
  size_t n_grid;          // the grid ends at n_grid h (the run's last sample)
  fb_episode ep;          // contact episodes, updated at every step end (the law's v0)
  std::deque<Knot> knots; // from the knot before the oldest open record's interval on
  long knot_ids;          // knots made so far
  long knot_done;         // id of the newest knot whose bookkeeping a record took
  fb_episode ep_done;     // the episodes after that knot
  std::vector<Record> recs; // records rec_base .. gen_next - 1, record k at k mod size
                            // (a power of two, grown when the lookahead needs more)
  size_t rec_base;
  double gap_max;         // the longest knot interval held [s]
  std::deque<Peak> pending; // extremes of the interpolated series not yet made exact
  size_t k;               // the sample now (time k h)
  size_t k_open;          // the first record not handed out yet
  size_t gen_next;        // the next record to generate
  size_t dominance;       // records kDominanceTurn of a crank turn spans
  int failed;             // a record could not be generated: the integrator failed
  size_t fail_k;          // the first record that could not be
  fb_stop fail_stop;
  char fail_msg[400];
  // the sample now
  fb_sample x;
  double drift, pen_now;
  int impacts_now;
  Vector_<SpatialVec> mob_reactions; // per mobilized body, reused
  Vector motion_forces;              // per mobility, reused
  // provenance
  double me_min, me_max;
  size_t contact_steps;
  fb_stop stop;
  size_t exact_samples;   // samples realized exactly
  double stepping_s;      // wall time in the integrator's steps (stepTo) [s]

  Scene() : matter(system), forces(system) {}
};

// inertia of a link about its origin: the link's in-plane inertia about +z
// through its centre of mass (only Izz acts in the plane; the other two
// axes are given the same value so that the inertia is physical)
Body::Rigid link_body(const fb_link_mass &m, double length) {
  const Vec3 com(m.com_fraction * length, 0, 0);
  const Inertia central(m.inertia, m.inertia, m.inertia);
  return Body::Rigid(MassProperties(m.mass, com, central.shiftFromMassCenter(com, m.mass)));
}

// the inverse effective-mass tensor at B in state (effective_mass.h), for
// the restitution law's damper; 0 when it cannot be formed
int mass_tensor(const Scene *s, const State &state, double w_out[2][2]) {
  fb_mechanism m;
  std::memset(&m, 0, sizeof m);
  const MobilizedBody *body[3] = {&s->crank, &s->coupler, &s->follower};
  const double len[3] = {s->a, s->b, s->c};
  for (int i = 0; i < 3; i++) {
    m.mass[i] = s->sm.link[i].mass;
    m.inertia[i] = s->sm.link[i].inertia;
    const Vec3 com =
        body[i]->findStationLocationInGround(state, Vec3(s->sm.link[i].com_fraction * len[i], 0, 0));
    m.com[i][0] = com[0];
    m.com[i][1] = com[1];
  }
  const Vec3 pin = s->crank.findStationLocationInGround(state, Vec3(s->a, 0, 0));
  const Vec3 cj = s->coupler.findStationLocationInGround(state, Vec3(s->b, 0, 0));
  m.joint[FB_JOINT_A][0] = m.joint[FB_JOINT_A][1] = 0.0;
  m.joint[FB_JOINT_B][0] = pin[0];
  m.joint[FB_JOINT_B][1] = pin[1];
  m.joint[FB_JOINT_C][0] = cj[0];
  m.joint[FB_JOINT_C][1] = cj[1];
  m.joint[FB_JOINT_D][0] = s->g;
  m.joint[FB_JOINT_D][1] = 0.0;
  m.clearance_mask = 1 << FB_JOINT_B;
  m.crank_driven = 1;
  double w[4][2][2];
  if (fb_effective_mass_tensor(w, &m, NULL) != FB_OK) return 0;
  std::memcpy(w_out, w[FB_JOINT_B], sizeof w[FB_JOINT_B]);
  return 1;
}

// the law at eccentricity e and rate edot, with episodes ep; w the inverse
// effective-mass tensor (restitution law) or NULL
ContactEval contact_law(const Scene *s, const double e[2], const double edot[2],
                        const double (*w)[2], const fb_episode &ep) {
  ContactEval ce;
  std::memset(&ce, 0, sizeof ce);
  ce.mass_eff = NAN;
  ce.e[0] = e[0];
  ce.e[1] = e[1];
  ce.edot[0] = edot[0];
  ce.edot[1] = edot[1];
  const double ecc = std::hypot(e[0], e[1]);
  const double delta = ecc - s->sm.radial_clearance;
  if (!(delta > 0.0) || ecc == 0.0) return ce;
  ce.pen = delta;
  ce.n[0] = e[0] / ecc;
  ce.n[1] = e[1] / ecc;
  ce.ddot = ce.n[0] * edot[0] + ce.n[1] * edot[1];
  fb_contact_law law = s->sm.law[FB_JOINT_B];
  if (law.kind == FB_LAW_RESTITUTION && w) {
    // the damper on the mechanism's effective mass along n (effective_mass.h)
    double wm[2][2] = {{w[0][0], w[0][1]}, {w[1][0], w[1][1]}};
    const double me = fb_effective_mass_along(wm, ce.n);
    if (me > 0.0 && std::isfinite(me)) law.mass = ce.mass_eff = me;
  }
  const double v0 = ep.in_contact ? ep.v0 : std::fmax(ce.ddot, s->sm.impact_velocity_min);
  ce.force = fb_contact_force(&law, delta, ce.ddot, v0);
  return ce;
}

// the contact in a realized state, with the scene's episodes; *w_ok and w
// (when given) the inverse effective-mass tensor used
ContactEval contact_at(const Scene *s, const State &state, double (*w)[2] = NULL,
                       int *w_ok = NULL) {
  const Vec3 pin = s->crank.findStationLocationInGround(state, Vec3(s->a, 0, 0));
  const Vec3 hole = s->coupler.findStationLocationInGround(state, Vec3(0));
  const Vec3 vp = s->crank.findStationVelocityInGround(state, Vec3(s->a, 0, 0));
  const Vec3 vh = s->coupler.findStationVelocityInGround(state, Vec3(0));
  const double e[2] = {pin[0] - hole[0], pin[1] - hole[1]};
  const double edot[2] = {vp[0] - vh[0], vp[1] - vh[1]};
  double wl[2][2];
  double (*wp)[2] = w ? w : wl;
  // the tensor where the law needs it (in contact); everywhere when asked for
  const int ok = s->sm.law[FB_JOINT_B].kind == FB_LAW_RESTITUTION &&
                 (w || std::hypot(e[0], e[1]) > s->sm.radial_clearance) && mass_tensor(s, state, wp);
  if (w_ok) *w_ok = ok;
  return contact_law(s, e, edot, ok ? wp : NULL, s->ep);
}

void ClearanceForce::calcForce(const State &state, Vector_<SpatialVec> &bodyForces,
                               Vector_<Vec3> &, Vector &) const {
  const ContactEval ce = contact_at(s_, state);
  if (ce.force == 0.0) return;
  const Vec3 f(ce.force * ce.n[0], ce.force * ce.n[1], 0);
  s_->coupler.applyForceToBodyPoint(state, Vec3(0), f, bodyForces);
  s_->crank.applyForceToBodyPoint(state, Vec3(s_->a, 0, 0), -f, bodyForces);
}

// loads in a state realized through accelerations: drive torque, then the
// reactions at A, B, C, D (x, y); the reaction at B is the Ball's (ideal)
// or the contact force ce (clearance); *drift the Ball's violation
void loads_at(Scene *s, const State &state, const ContactEval *ce, double load[kLoads],
              double *drift) {
  s->matter.calcMobilizerReactionForces(state, s->mob_reactions);
  const Vec3 fa = s->mob_reactions[s->crank.getMobilizedBodyIndex()][1];
  const Vec3 fd = s->mob_reactions[s->follower.getMobilizedBodyIndex()][1];
  const Vec3 fc = s->mob_reactions[s->coupler.getMobilizedBodyIndex()][1];
  s->matter.findMotionForces(state, s->motion_forces);
  load[0] = -s->motion_forces[s->crank.getFirstUIndex(state)];
  load[1 + 2 * FB_JOINT_A] = fa[0];
  load[2 + 2 * FB_JOINT_A] = fa[1];
  load[1 + 2 * FB_JOINT_D] = fd[0];
  load[2 + 2 * FB_JOINT_D] = fd[1];
  load[1 + 2 * FB_JOINT_C] = -fc[0]; // on the follower from the coupler
  load[2 + 2 * FB_JOINT_C] = -fc[1];
  *drift = 0.0;
  if (ce) {
    load[1 + 2 * FB_JOINT_B] = ce->force * ce->n[0];
    load[2 + 2 * FB_JOINT_B] = ce->force * ce->n[1];
  } else {
    const Vec3 fb = s->coupler.getBodyRotation(state) * s->ball.getBallReactionForceOnBody2(state);
    load[1 + 2 * FB_JOINT_B] = fb[0];
    load[2 + 2 * FB_JOINT_B] = fb[1];
    const Vec3 pin = s->crank.findStationLocationInGround(state, Vec3(s->a, 0, 0));
    const Vec3 hole = s->coupler.findStationLocationInGround(state, Vec3(0));
    *drift = (pin - hole).norm();
  }
}

// the value of tracked column m in a sample
double sample_value(const fb_sample &x, int m) {
  switch (m) {
    case 0: return x.coupler_alpha;
    case 1: return x.follower_alpha;
    case 2: return x.drive_torque;
    case 7: return x.coupler_omega;
    case 8: return x.follower_omega;
    default: return std::hypot(x.reaction[m - 3][0], x.reaction[m - 3][1]);
  }
}

// the sample's columns from mobilities q, u, the angular accelerations
// (coupler, follower), loads and the contact; track from them unless keep
void fill_sample(Record *r, double t, const double q[3], const double u[3],
                 const double alpha[2], const double load[kLoads], const ContactEval *ce,
                 int keep_track) {
  fb_sample &x = r->x;
  std::memset(&x, 0, sizeof x);
  x.t = t;
  x.crank_angle = q[kCrank];
  x.follower_angle = q[kFollower];
  x.follower_omega = u[kFollower];
  x.follower_alpha = alpha[1];
  x.coupler_angle = q[kFollower] + q[kCoupler];
  x.coupler_omega = u[kFollower] + u[kCoupler];
  x.coupler_alpha = alpha[0];
  x.drive_torque = load[0];
  for (int j = 0; j < 4; j++) {
    x.reaction[j][0] = load[1 + 2 * j];
    x.reaction[j][1] = load[2 + 2 * j];
  }
  r->pen = 0.0;
  if (ce) {
    r->pen = ce->pen;
    double *col = x.contact[FB_JOINT_B];
    col[FB_C_FORCE] = ce->force;
    col[FB_C_PEN] = ce->pen;
    col[FB_C_EX] = ce->e[0];
    col[FB_C_EY] = ce->e[1];
  }
  std::memcpy(r->v, q, 3 * sizeof(double));
  std::memcpy(r->v + 3, u, 3 * sizeof(double));
  std::memcpy(r->v + 6, alpha, 2 * sizeof(double));
  std::memcpy(r->v + 8, load, kLoads * sizeof(double));
  if (ce) r->ce = *ce;
  // the peaks are looked for on the series as first interpolated, and an
  // exact sample starts from the state as first interpolated (Simbody's)
  if (!keep_track) {
    for (int m = 0; m < kTracked; m++) r->track[m] = sample_value(x, m);
    std::memcpy(r->q, q, sizeof r->q);
    std::memcpy(r->u, u, sizeof r->u);
  }
}

// a knot from a state realized through accelerations, with the episodes ep
// (the scene's are used for the law)
Knot knot_of(Scene *s, const State &state) {
  s->system.realize(state, Stage::Acceleration);
  Knot kn;
  std::memset(&kn, 0, sizeof kn);
  kn.t = state.getTime();
  const MobilizedBody *mb[kMobilities] = {&s->crank, &s->follower, &s->coupler};
  for (int i = 0; i < kMobilities; i++) {
    kn.q[i] = mb[i]->getOneQ(state, 0);
    kn.u[i] = mb[i]->getOneU(state, 0);
    kn.udot[i] = mb[i]->getOneUDot(state, 0);
  }
  kn.alpha[0] = kn.udot[kFollower] + kn.udot[kCoupler];
  kn.alpha[1] = kn.udot[kFollower];
  ContactEval ce;
  if (s->clearance) {
    ce = contact_at(s, state, kn.w, &kn.w_ok);
    kn.e[0] = ce.e[0];
    kn.e[1] = ce.e[1];
    kn.edot[0] = ce.edot[0];
    kn.edot[1] = ce.edot[1];
    kn.force = ce.force;
    kn.pen = ce.pen;
  }
  loads_at(s, state, s->clearance ? &ce : NULL, kn.load, &kn.drift);
  kn.ep = s->ep;
  kn.id = -1;
  return kn;
}

// the knot of a state the integrator advanced to: its values, the contact
// episodes' update (at every step end, as the law's v0 needs) and provenance
Knot make_knot(Scene *s, const State &state) {
  Knot kn = knot_of(s, state);
  if (s->clearance) {
    const ContactEval ce = contact_law(s, kn.e, kn.edot, kn.w_ok ? kn.w : NULL, s->ep);
    fb_episode_update(&s->ep, ce.pen > 0.0, ce.ddot, s->sm.impact_velocity_min);
    if (ce.pen > 0.0) {
      if (std::isfinite(ce.mass_eff)) {
        if (s->contact_steps == 0 || ce.mass_eff < s->me_min) s->me_min = ce.mass_eff;
        if (s->contact_steps == 0 || ce.mass_eff > s->me_max) s->me_max = ce.mass_eff;
      }
      s->contact_steps++;
    }
  }
  kn.ep = s->ep;
  kn.id = s->knot_ids++;
  return kn;
}

Integrator *make_integrator(const System &sys, int kind) {
  switch (kind) {
    case FB_SIMBODY_RKFELDBERG: return new RungeKuttaFeldbergIntegrator(sys);
    case FB_SIMBODY_RK3: return new RungeKutta3Integrator(sys);
    case FB_SIMBODY_CPODES: return new CPodesIntegrator(sys, CPodes::BDF, CPodes::Newton);
    case FB_SIMBODY_VERLET: return new VerletIntegrator(sys);
    default: return new RungeKuttaMersonIntegrator(sys);
  }
}

// a failure to generate record k: kept, and reported when the harness asks
// for sample k
void fail(Scene *s, size_t k, fb_stop_kind kind, const char *detail) {
  if (s->failed) return;
  s->failed = 1;
  s->fail_k = k;
  fb_stop &st = s->fail_stop;
  std::memset(&st, 0, sizeof st);
  st.kind = kind;
  st.engine = "simbody";
  st.joint = -1;
  st.t = k > 0 ? (double)(k - 1) * s->h : 0.0;
  if (kind == FB_STOP_STEP_BUDGET) {
    st.value = (double)kStepsPerSampleMax;
    st.limit = (double)kStepsPerSampleMax;
    st.t_end = s->sm.def->duration;
  }
  std::snprintf(st.detail, sizeof st.detail, "%.150s", detail ? detail : "");
  std::snprintf(s->fail_msg, sizeof s->fail_msg, "%.300s",
                detail && *detail ? detail : "integration failed");
}

// one more integrator step towards target (the run's end): appends its knot.
// 0 when the integrator failed or ended (fail() called for record k)
int advance(Scene *s, double target, size_t k) {
  try {
    for (;;) {
      const double t0 = fb_clock_s();
      const Integrator::SuccessfulStepStatus r = s->integ->stepTo(target);
      s->stepping_s += fb_clock_s() - t0;
      if (r == Integrator::StartOfContinuousInterval) continue;
      const State &adv = s->integ->getAdvancedState();
      if (adv.getTime() > s->knots.back().t) {
        s->gap_max = std::fmax(s->gap_max, adv.getTime() - s->knots.back().t);
        s->knots.push_back(make_knot(s, adv));
        return 1;
      }
      if (r == Integrator::EndOfSimulation) {
        fail(s, k, FB_STOP_SOLVER, "the integrator ended the simulation");
        return 0;
      }
      if (r == Integrator::ReachedReportTime) { // nothing new at the target: cannot happen
        fail(s, k, FB_STOP_SOLVER, "the integrator reached its report time without a step");
        return 0;
      }
    }
  } catch (const std::exception &ex) {
    fail(s, k, FB_STOP_SOLVER, ex.what());
    return 0;
  }
}

// cubic Hermite on [0, 1] (dt the interval's length): value and time
// derivative (dy may be NULL)
inline void hermite(double s, double dt, double y0, double d0, double y1, double d1, double *y,
                    double *dy) {
  const double s2 = s * s, s3 = s2 * s;
  *y = (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * dt * d0 + (-2 * s3 + 3 * s2) * y1 +
       (s3 - s2) * dt * d1;
  if (dy)
    *dy = ((6 * s2 - 6 * s) * y0 + (3 * s2 - 4 * s + 1) * dt * d0 + (-6 * s2 + 6 * s) * y1 +
           (3 * s2 - 2 * s) * dt * d1) / dt;
}

// the rate of load m at knot b from its neighbours a (before) and c (after),
// either NULL: the three-point derivative on uneven steps, one-sided at an
// end (the loads are known at the knots only)
double load_rate(const Knot *a, const Knot &b, const Knot *c, int m) {
  if (a && c) {
    const double d0 = b.t - a->t, d1 = c->t - b.t;
    return ((c->load[m] - b.load[m]) / d1 * d0 + (b.load[m] - a->load[m]) / d0 * d1) / (d0 + d1);
  }
  if (c) return (c->load[m] - b.load[m]) / (c->t - b.t);
  if (a) return (b.load[m] - a->load[m]) / (b.t - a->t);
  return 0.0;
}

// record r from knot kn's realized values
void record_from_knot(const Scene *s, Record *r, const Knot &kn, int keep_track) {
  ContactEval ce;
  if (s->clearance) {
    ce = contact_law(s, kn.e, kn.edot, kn.w_ok ? kn.w : NULL, kn.ep);
    ce.force = kn.force;
    ce.pen = kn.pen;
  }
  fill_sample(r, kn.t, kn.q, kn.u, kn.alpha, kn.load, s->clearance ? &ce : NULL, keep_track);
  r->drift = kn.drift;
}

// record r at t inside (k0.t, k1.t), interpolated: positions by the cubic
// Hermite of q and qdot (= u), velocities by that of u and udot, the
// angular accelerations its derivative (Simbody's own interpolant,
// createInterpolatedState); the loads by the cubic Hermite of their values
// with three-point rates; the contact by the law at the cubic Hermite of the
// eccentricity and its rate (the integration from k0 to k1 saw k0's
// episodes). before, after: the knots beside the interval, or NULL.
void record_between(const Scene *s, Record *r, double t, const Knot *before, const Knot &k0,
                    const Knot &k1, const Knot *after, int keep_track) {
  const double dt = k1.t - k0.t, sp = (t - k0.t) / dt;
  double q[kMobilities], u[kMobilities], udot[kMobilities];
  for (int i = 0; i < kMobilities; i++) {
    hermite(sp, dt, k0.q[i], k0.u[i], k1.q[i], k1.u[i], &q[i], NULL);
    hermite(sp, dt, k0.u[i], k0.udot[i], k1.u[i], k1.udot[i], &u[i], &udot[i]);
  }
  q[kCrank] = s->theta0 + s->omega2 * t; // prescribed (the Motion), as Simbody prescribes it
  u[kCrank] = s->omega2;
  udot[kCrank] = 0.0;
  const double alpha[2] = {udot[kFollower] + udot[kCoupler], udot[kFollower]};
  double load[kLoads];
  for (int m = 0; m < kLoads; m++)
    hermite(sp, dt, k0.load[m], load_rate(before, k0, &k1, m), k1.load[m],
            load_rate(&k0, k1, after, m), &load[m], NULL);
  ContactEval ce;
  if (s->clearance) {
    double e[2], edot[2], w[2][2];
    for (int i = 0; i < 2; i++)
      hermite(sp, dt, k0.e[i], k0.edot[i], k1.e[i], k1.edot[i], &e[i], &edot[i]);
    const int w_ok = k0.w_ok || k1.w_ok;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) {
        const double w0 = k0.w_ok ? k0.w[i][j] : k1.w[i][j], w1 = k1.w_ok ? k1.w[i][j] : k0.w[i][j];
        w[i][j] = w0 + sp * (w1 - w0);
      }
    ce = contact_law(s, e, edot, w_ok ? w : NULL, k0.ep);
    load[1 + 2 * FB_JOINT_B] = ce.force * ce.n[0];
    load[2 + 2 * FB_JOINT_B] = ce.force * ce.n[1];
  }
  fill_sample(r, t, q, u, alpha, load, s->clearance ? &ce : NULL, keep_track);
  r->drift = std::fmax(k0.drift, k1.drift);
}

Record *rec(Scene *s, size_t k) { return &s->recs[k & (s->recs.size() - 1)]; }

// room for record k in the ring of records rec_base .. k
void ring_reserve(Scene *s, size_t k) {
  const size_t need = k - s->rec_base + 1;
  if (need <= s->recs.size()) return;
  size_t size = s->recs.size() ? s->recs.size() : 1024;
  while (size < need) size *= 2;
  std::vector<Record> grown(size);
  for (size_t j = s->rec_base; j < k; j++) grown[j & (size - 1)] = *rec(s, j);
  s->recs.swap(grown);
}

// index in s->knots of the knot interval (i, i + 1) holding t: knots[i].t <
// t <= knots[i + 1].t; the first interval for t at or before the first knot
size_t interval_of(const Scene *s, double t) {
  size_t lo = 0, hi = s->knots.size() - 1; // knots[lo].t < t <= knots[hi].t, if inside
  if (t <= s->knots[0].t) return 0;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (s->knots[mid].t < t) lo = mid;
    else hi = mid;
  }
  return lo;
}

// generates record k (time k h): runs the integrator until a knot lies at
// or past k h and one more (the loads' rate there), unless that knot ends
// the run; takes the bookkeeping of the knots in ((k-1) h, k h] and fills
// the record
void generate(Scene *s, size_t k) {
  ring_reserve(s, k);
  Record *r = rec(s, k);
  std::memset(r, 0, sizeof *r);
  if (s->failed && k >= s->fail_k) return;
  const double t = (double)k * s->h;
  const double target = std::fmax((double)s->n_grid * s->h, t);
  long taken = 0;
  while (!(s->knots.back().t >= t &&
           (s->knots.back().t >= target ||
            (s->knots.size() >= 2 && s->knots[s->knots.size() - 2].t >= t)))) {
    if (++taken > kStepsPerSampleMax) {
      fail(s, k, FB_STOP_STEP_BUDGET, "step budget");
      return;
    }
    if (!advance(s, target, k)) return;
  }
  // bookkeeping of the knots in ((k-1) h, k h] (the knots' ids count up by one)
  const long from = s->knot_done + 1 - s->knots.front().id;
  for (size_t i = from > 0 ? (size_t)from : 0; i < s->knots.size() && s->knots[i].t <= t; i++) {
    const Knot &kn = s->knots[i];
    if (kn.pen > 0.0) r->knot_contact = 1;
    r->kmax_force = std::fmax(r->kmax_force, kn.force);
    r->kmax_pen = std::fmax(r->kmax_pen, kn.pen);
    if (std::fabs(kn.alpha[0]) > std::fabs(r->ka3)) r->ka3 = kn.alpha[0];
    if (std::fabs(kn.alpha[1]) > std::fabs(r->ka4)) r->ka4 = kn.alpha[1];
    if (kn.ep.impacts > s->ep_done.impacts) r->new_impact = 1;
    s->ep_done = kn.ep;
    s->knot_done = kn.id;
  }
  // the episodes after the last knot at or before t: those the integration
  // past it saw (the law's v0), and the sample's contact state
  r->ep = s->ep_done;
  const size_t i = interval_of(s, t);
  if (t <= s->knots[i].t) {
    record_from_knot(s, r, s->knots[i], 0);
    r->at_knot = 1;
  } else if (t == s->knots[i + 1].t) {
    record_from_knot(s, r, s->knots[i + 1], 0);
    r->at_knot = 1;
  } else {
    record_between(s, r, t, i > 0 ? &s->knots[i - 1] : NULL, s->knots[i], s->knots[i + 1],
                   i + 2 < s->knots.size() ? &s->knots[i + 2] : NULL, 0);
  }
  r->t = t;
  r->valid = 1;
}

// the state at time t with mobilities q, u realized exactly, as Simbody
// realizes an interpolated report (createInterpolatedState): q and u set
// into the scratch State, the crank prescribed, projected onto the
// constraint manifold (the Ball at B: for the one-degree-of-freedom loop
// this sets the velocities the interpolation has only to O(dt^4), and it
// moves an integrator step's end by the constraint tolerance) and realized
// through accelerations, with the episodes ep (the law's v0 as the
// integration saw it)
Knot realize_state(Scene *s, double t, const double q[3], const double u[3],
                   const fb_episode &ep) {
  State &st = s->scratch;
  st.setTime(t);
  const MobilizedBody *mb[kMobilities] = {&s->crank, &s->follower, &s->coupler};
  for (int i = 0; i < kMobilities; i++) {
    mb[i]->setOneQ(st, 0, q[i]);
    mb[i]->setOneU(st, 0, u[i]);
  }
  const fb_episode keep = s->ep;
  s->ep = ep;
  // Simbody's own projection of an interpolated report (the integrator's
  // realizeAndProjectKinematicsWithThrow with ProjectOptions::LocalOnly)
  ProjectOptions options;
  options.setRequiredAccuracy(s->integ->getConstraintToleranceInUse());
  options.setOption(ProjectOptions::LocalOnly);
  ProjectResults results;
  Vector none;
  s->system.realize(st, Stage::Time);
  s->system.prescribeQ(st);
  s->system.realize(st, Stage::Position);
  s->system.projectQ(st, none, options, results);
  s->system.prescribeU(st);
  s->system.realize(st, Stage::Velocity);
  results.clear();
  s->system.projectU(st, none, options, results);
  Knot kn = knot_of(s, st);
  s->ep = keep;
  kn.ep = ep;
  return kn;
}

// record r realized exactly (realize_state): r takes its values; returns
// them as a knot
Knot realize_exact(Scene *s, Record *r) {
  const Knot kn = realize_state(s, r->t, r->q, r->u, r->ep);
  record_from_knot(s, r, kn, 1);
  r->exact = 1;
  s->exact_samples++;
  return kn;
}

// refines knot interval i (knots[i], knots[i + 1]): kRefine - 1 of its
// records, spread over it, are realized exactly, and every other record of
// it is corrected by the difference exact - interpolated, interpolated
// between those records (cubic through the four nearest, the difference
// zero at the knots). The difference is the interpolation's own smooth
// error; interpolating it, rather than the exact states themselves, keeps
// the projection's scatter at the constraint tolerance out of the
// differentiated velocities (realized exactly, or all records when the
// interval holds few). Only records not handed out and generated are
// touched.
void refine_interval(Scene *s, size_t i) {
  if (i + 1 >= s->knots.size() || s->knots[i].refined) return;
  s->knots[i].refined = 1;
  const double t0 = s->knots[i].t, t1 = s->knots[i + 1].t;
  size_t j0 = (size_t)std::ceil(t0 / s->h), j1 = (size_t)std::floor(t1 / s->h);
  while ((double)j0 * s->h <= t0) j0++;
  while (j0 > 0 && (double)(j0 - 1) * s->h > t0) j0--;
  while (j1 > 0 && (double)j1 * s->h >= t1) j1--;
  while ((double)(j1 + 1) * s->h < t1) j1++;
  j0 = std::max(j0, s->k_open);
  j1 = std::min(j1, s->gen_next - 1);
  if (j1 < j0) return;
  const size_t count = j1 - j0 + 1;
  if (count <= (size_t)(2 * kRefine)) {
    for (size_t j = j0; j <= j1; j++)
      if (rec(s, j)->valid && !rec(s, j)->exact && !rec(s, j)->at_knot) realize_exact(s, rec(s, j));
    return;
  }
  // the corrections at the knots (zero) and at kRefine - 1 exact records
  double nt[kRefine + 1], nd[kRefine + 1][kVals];
  int nn = 0;
  nt[nn] = t0;
  std::memset(nd[nn], 0, sizeof nd[nn]);
  nn++;
  for (int p = 1; p < kRefine; p++) {
    Record *r = rec(s, j0 + (count - 1) * (size_t)p / kRefine);
    if (!r->valid || r->exact || r->at_knot) continue;
    double coarse[kVals];
    std::memcpy(coarse, r->v, sizeof coarse);
    realize_exact(s, r);
    nt[nn] = r->t;
    for (int m = 0; m < kVals; m++) nd[nn][m] = r->v[m] - coarse[m];
    nn++;
  }
  nt[nn] = t1;
  std::memset(nd[nn], 0, sizeof nd[nn]);
  nn++;
  int n = 0;
  for (size_t j = j0; j <= j1; j++) {
    Record *r = rec(s, j);
    if (!r->valid || r->exact || r->at_knot) continue;
    while (n + 2 < nn && nt[n + 1] < r->t) n++;
    // the four nodes nearest to the piece (n, n + 1), fewer at the ends
    const int a = std::max(0, n - 1), b = std::min(nn - 1, n + 2);
    for (int m = 0; m < kVals; m++) {
      double c = 0.0;
      for (int p = a; p <= b; p++) {
        double l = 1.0;
        for (int q = a; q <= b; q++)
          if (q != p) l *= (r->t - nt[q]) / (nt[p] - nt[q]);
        c += l * nd[p][m];
      }
      r->v[m] += c;
    }
    double v[kVals];
    std::memcpy(v, r->v, sizeof v);
    fill_sample(r, r->t, v, v + 3, v + 6, v + 8, s->clearance ? &r->ce : NULL, 1);
    r->refined = 1;
  }
}

// refines the knot interval holding record j (both beside it when j is a knot)
void refine_at(Scene *s, size_t j) {
  const Record *r = rec(s, j);
  if (r->exact || r->refined) return;
  const size_t i = interval_of(s, r->t);
  refine_interval(s, i);
  if (r->at_knot && i + 1 < s->knots.size() && s->knots[i + 1].t == r->t) refine_interval(s, i + 1);
}

// after record k is generated: a local extreme of a tracked column of the
// interpolated series at k - 1 joins the peaks to make exact
void find_peaks(Scene *s, size_t k) {
  if (k < 2 || k - 2 < s->rec_base) return;
  const Record &a = *rec(s, k - 2), &b = *rec(s, k - 1), &c = *rec(s, k);
  if (!a.valid || !b.valid || !c.valid) return;
  for (int m = 0; m < kTracked; m++) {
    const double y0 = a.track[m], y1 = b.track[m], y2 = c.track[m];
    const int sign = (y1 > y0 && y1 >= y2) ? 1 : (y1 < y0 && y1 <= y2) ? -1 : 0;
    // a reaction's magnitude is taken at its largest only
    if (sign > 0 || (sign < 0 && !kMaxOnly[m])) s->pending.push_back(Peak{k - 1, m, sign});
  }
}

// makes peak p exact: refines the knot interval of the interpolated
// extreme, climbs to the local extreme of the refined series, realizes it
// and its two neighbours exactly, then looks beside it, until the series
// has fallen clear of it, for records at or beyond it: an interpolated one
// has its interval refined, a refined one is realized exactly (a refined
// value is right to the projection's scatter, an interpolated one only to
// the interpolation's error), and one beyond it becomes the extreme. At most
// kRefineMaxIntervals intervals are refined per peak.
void make_peak_exact(Scene *s, const Peak &p) {
  const size_t lo = s->k_open, hi = s->gen_next - 1;
  if (p.j < lo || p.j > hi || !rec(s, p.j)->valid) return;
  const int m = p.m;
  const double sg = p.sign;
  int budget = kRefineMaxIntervals;
  auto val = [&](size_t i) { return sg * sample_value(rec(s, i)->x, m); };
  auto accurate = [&](size_t i) {
    const Record *r = rec(s, i);
    if (r->exact || r->refined || r->at_knot) return true;
    if (budget <= 0) return false;
    refine_at(s, i);
    budget--;
    return true;
  };
  auto usable = [&](size_t j, int d) {
    return (d < 0 ? j > lo : j < hi) && rec(s, d < 0 ? j - 1 : j + 1)->valid;
  };
  // only an extreme that leads its neighbourhood (the peaks the metrics
  // take lead theirs; a contact's ringing has many that do not)
  const size_t w = s->dominance;
  const double lead = sg * rec(s, p.j)->track[m] + kDominanceMargin * std::fabs(rec(s, p.j)->track[m]);
  for (size_t i = p.j > lo + w ? p.j - w : lo; i <= hi && i <= p.j + w; i++)
    if (rec(s, i)->valid && sg * rec(s, i)->track[m] > lead) return;
  size_t j = p.j;
  accurate(j);
  for (int guard = 0; guard < 8 * kRefineMaxIntervals; guard++) {
    // climb over the accurate records
    for (;;) {
      size_t best = j;
      for (int d = -1; d <= 1; d += 2)
        if (usable(j, d) && accurate(j + d) && val(j + d) > val(best)) best = j + d;
      if (best == j) break;
      j = best;
    }
    // the extreme and its neighbours realized exactly
    for (int d = -1; d <= 1; d++) {
      if (d != 0 && !usable(j, d)) continue;
      Record *r = rec(s, j + d);
      if (!r->exact && !r->at_knot) realize_exact(s, r);
    }
    size_t next = j;
    for (int d = -1; d <= 1; d += 2)
      if (usable(j, d) && val(j + d) > val(next)) next = j + d;
    if (next != j) {
      j = next;
      continue;
    }
    // records beside it at or beyond it
    const double peak = val(j), clear = kPeakClearance * std::fabs(peak);
    int moved = 0;
    for (int d = -1; d <= 1 && !moved; d += 2)
      for (size_t i = j; usable(i, d);) {
        i = d < 0 ? i - 1 : i + 1;
        Record *r = rec(s, i);
        if (val(i) >= peak && !r->exact && !r->at_knot) {
          if (!r->refined && !accurate(i)) break;
          if (!r->exact && !r->at_knot && val(i) >= peak) realize_exact(s, r);
          if (val(i) > peak) {
            j = i;
            moved = 1;
            break;
          }
        }
        if (val(i) < peak - clear) break;
      }
    if (!moved) return;
  }
}

// records to generate ahead of the one handed out: kLookaheadIntervals of
// the longest knot interval held
size_t lookahead(const Scene *s) {
  const double gap = s->gap_max;
  const double n = std::fmax(std::ceil(kLookaheadIntervals * gap / s->h), (double)s->dominance) + 2.0;
  return n < (double)kLookaheadMax ? (size_t)n : kLookaheadMax;
}

// makes sample k the current one: the records ahead of it generated, the
// peaks within reach of k made exact, the run's last sample realized
// exactly, the knots' extremes of k's interval kept
fb_status emit(Scene *s, size_t k, fb_diag *diag) {
  s->k_open = k;
  if (s->rec_base < k) s->rec_base = k;
  const double t_open = (double)k * s->h;
  if (s->knots.size() > 3 && s->knots[2].t < t_open) {
    while (s->knots.size() > 3 && s->knots[2].t < t_open) s->knots.pop_front();
    s->gap_max = 0.0; /* of the knots still held */
    for (size_t i = 1; i < s->knots.size(); i++)
      s->gap_max = std::fmax(s->gap_max, s->knots[i].t - s->knots[i - 1].t);
  }
  int ended = 0;
  size_t reach = lookahead(s);
  for (;;) {
    const size_t frontier = k >= s->n_grid ? k : std::min(s->n_grid, k + 2 * reach);
    while (s->gen_next <= frontier) {
      generate(s, s->gen_next);
      s->gen_next++;
      if (!rec(s, s->gen_next - 1)->valid) {
        ended = 1;
        break;
      }
      find_peaks(s, s->gen_next - 1);
    }
    if (ended || frontier == s->n_grid || frontier == k) ended = 1;
    const size_t again = lookahead(s);
    if (ended || again <= reach) break;
    reach = again;
  }
  while (!s->pending.empty() && (ended || s->pending.front().j + reach < s->gen_next)) {
    make_peak_exact(s, s->pending.front());
    s->pending.pop_front();
  }
  Record *r = rec(s, k);
  if (!r->valid) {
    s->stop = s->fail_stop;
    return fb_diag_set(diag, FB_ERR_NUMERIC, "simbody: %s at t = %g s", s->fail_msg, s->stop.t);
  }
  // the run's last sample (and the one before a failed step): no neighbour
  // tells a peak there
  if (!r->exact && !r->at_knot && (k + 1 >= s->gen_next || !rec(s, k + 1)->valid))
    realize_exact(s, r);
  s->x = r->x;
  s->x.t = t_open; // on the grid exactly
  s->drift = r->drift;
  s->pen_now = r->pen;
  s->impacts_now = r->ep.impacts;
  if (s->clearance) {
    double *col = s->x.contact[FB_JOINT_B];
    // peaks between samples: the extremes at the knots of ((k-1) h, k h]
    if (r->knot_contact || col[FB_C_PEN] > 0.0) {
      col[FB_C_FORCE] = std::fmax(col[FB_C_FORCE], r->kmax_force);
      col[FB_C_PEN] = std::fmax(col[FB_C_PEN], r->kmax_pen);
      if (std::fabs(r->ka3) > std::fabs(s->x.coupler_alpha)) s->x.coupler_alpha = r->ka3;
      if (std::fabs(r->ka4) > std::fabs(s->x.follower_alpha)) s->x.follower_alpha = r->ka4;
    }
    // an impact that began inside the interval is marked at this sample
    col[FB_C_STATE] = r->new_impact ? FB_STATE_IMPACT : r->ep.state;
  }
  return FB_OK;
}

} // namespace

struct fb_simbody_scene {
  Scene *s;
};

extern "C" fb_status fb_simbody_scene_create(fb_simbody_scene **out, const fb_scene_model *sm,
                                             fb_diag *diag) {
  *out = NULL;
  fb_status st = fb_scene_def_check(sm->def, diag);
  if (st != FB_OK) return st;
  if (sm->clearance_mask & ~(1 << FB_JOINT_B))
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': the Simbody tree is cut at the crank-coupler joint only; "
                       "[clearance] joints names others: set joints = crank-coupler or drop the "
                       "simbody-clearance-* models", sm->model->name);
  fb_start_state start;
  st = fb_scene_model_start(&start, sm, diag);
  if (st != FB_OK) return st;
  fb_simbody_scene *h = new (std::nothrow) fb_simbody_scene;
  if (!h) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Simbody scene");
  h->s = NULL;
  try {
    Scene *s = new Scene;
    h->s = s;
    s->sm = *sm;
    s->clearance = (sm->clearance_mask & (1 << FB_JOINT_B)) != 0;
    s->a = sm->lengths.length[FB_CRANK];
    s->b = sm->lengths.length[FB_COUPLER];
    s->c = sm->lengths.length[FB_FOLLOWER];
    s->g = sm->lengths.length[FB_GROUND];
    s->theta0 = start.crank_angle;
    s->omega2 = sm->omega2;
    s->h = sm->solver.h;
    s->n_grid = sm->def->steps;
    s->k = 0;
    s->gen_next = 0;
    s->k_open = 0;
    s->dominance = sm->omega2 != 0.0
                       ? (size_t)std::ceil(kDominanceTurn * 2.0 * M_PI / std::fabs(sm->omega2) / s->h)
                       : 0;
    if (s->dominance > kLookaheadMax / 2) s->dominance = kLookaheadMax / 2;
    s->failed = 0;
    s->knot_ids = 0;
    s->knot_done = -1;
    std::memset(&s->ep, 0, sizeof s->ep);
    std::memset(&s->ep_done, 0, sizeof s->ep_done);
    s->me_min = s->me_max = NAN;
    s->contact_steps = 0;
    s->exact_samples = 0;
    s->stepping_s = 0.0;
    std::memset(&s->stop, 0, sizeof s->stop);
    s->stop.engine = "simbody";
    s->stop.joint = -1;
    Force::UniformGravity(s->forces, s->matter, Vec3(0, -sm->gravity, 0));
    // the tree: ground -> crank (A), ground -> follower (D), follower -> coupler (C);
    // each body's frame at its first joint, x along the link
    s->crank = MobilizedBody::Pin(s->matter.Ground(), Transform(), link_body(sm->link[0], s->a),
                                  Transform());
    s->follower = MobilizedBody::Pin(s->matter.Ground(), Transform(Vec3(s->g, 0, 0)),
                                     link_body(sm->link[2], s->c), Transform());
    s->coupler = MobilizedBody::Pin(s->follower, Transform(Vec3(s->c, 0, 0)),
                                    link_body(sm->link[1], s->b), Transform(Vec3(s->b, 0, 0)));
    Motion::Custom(s->crank, new SteadyAngle(start.crank_angle, sm->omega2));
    if (s->clearance)
      Force::Custom(s->forces, new ClearanceForce(s));
    else
      s->ball = Constraint::Ball(s->crank, Vec3(s->a, 0, 0), s->coupler, Vec3(0));
    State state = s->system.realizeTopology();
    s->crank.setOneQ(state, 0, start.crank_angle);
    s->follower.setOneQ(state, 0, start.follower_angle);
    s->coupler.setOneQ(state, 0, start.coupler_angle - start.follower_angle);
    s->crank.setOneU(state, 0, sm->omega2);
    s->follower.setOneU(state, 0, start.follower_omega);
    s->coupler.setOneU(state, 0, start.coupler_omega - start.follower_omega);
    state.setTime(0.0);
    s->integ.reset(make_integrator(s->system, sm->simbody.integrator));
    s->integ->setAccuracy(sm->simbody.accuracy);
    // control back after every step the integrator takes: its steps are the knots
    s->integ->setReturnEveryInternalStep(true);
    s->integ->initialize(state);
    s->scratch = s->integ->getState(); // the one copy: exact samples are realized in it
    s->knots.push_back(make_knot(s, s->integ->getState()));
    // sample 0 is the initial knot (below); records are generated from 1 on
    s->rec_base = 1;
    s->gen_next = 1;
    s->knot_done = s->knots.front().id;
    s->ep_done = s->knots.front().ep;
    s->gap_max = 0.0;
  } catch (const std::bad_alloc &) {
    fb_simbody_scene_destroy(h);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Simbody scene");
  } catch (const std::exception &ex) {
    fb_simbody_scene_destroy(h);
    return fb_diag_set(diag, FB_ERR_NUMERIC, "model '%s': Simbody refused the system: %.600s",
                       sm->model->name, ex.what());
  }
  // the sample at t = 0 is the initial state (a knot): the integrator takes
  // its first step in the first fb_simbody_scene_step, not in the set-up
  Scene *s = h->s;
  Record r0;
  std::memset(&r0, 0, sizeof r0);
  record_from_knot(s, &r0, s->knots.front(), 0);
  s->x = r0.x;
  s->drift = r0.drift;
  s->pen_now = r0.pen;
  s->impacts_now = s->ep.impacts;
  if (s->clearance) s->x.contact[FB_JOINT_B][FB_C_STATE] = s->ep.state;
  *out = h;
  return FB_OK;
}

extern "C" fb_status fb_simbody_scene_step(fb_simbody_scene *h, fb_diag *diag) {
  Scene *s = h->s;
  fb_status st;
  try {
    st = emit(s, s->k + 1, diag);
  } catch (const std::bad_alloc &) {
    std::memset(&s->stop, 0, sizeof s->stop);
    s->stop.kind = FB_STOP_ALLOCATION;
    s->stop.engine = "simbody";
    s->stop.joint = -1;
    s->stop.t = (double)s->k * s->h;
    return fb_diag_set(diag, FB_ERR_NOMEM, "simbody: out of memory at t = %g s", s->stop.t);
  } catch (const std::exception &ex) {
    std::memset(&s->stop, 0, sizeof s->stop);
    s->stop.kind = FB_STOP_SOLVER;
    s->stop.engine = "simbody";
    s->stop.joint = -1;
    s->stop.t = (double)s->k * s->h;
    std::snprintf(s->stop.detail, sizeof s->stop.detail, "%.150s", ex.what());
    return fb_diag_set(diag, FB_ERR_NUMERIC, "simbody: %s at t = %g s", ex.what(), s->stop.t);
  }
  if (st != FB_OK) return st;
  s->k++;
  if (!std::isfinite(s->x.coupler_angle) || !std::isfinite(s->x.coupler_alpha)) {
    std::memset(&s->stop, 0, sizeof s->stop);
    s->stop.kind = FB_STOP_NONFINITE;
    s->stop.engine = "simbody";
    s->stop.joint = -1;
    s->stop.t = s->x.t;
    return fb_diag_set(diag, FB_ERR_NUMERIC, "simbody: non-finite state at t = %g s", s->x.t);
  }
  return FB_OK;
}

extern "C" void fb_simbody_scene_stopped(const fb_simbody_scene *h, fb_stop *out) {
  *out = h->s->stop;
}

extern "C" void fb_simbody_scene_sample(const fb_simbody_scene *h, fb_sample *x) { *x = h->s->x; }

extern "C" void fb_simbody_scene_contact(const fb_simbody_scene *h, fb_engine_contact *out) {
  std::memset(out, 0, sizeof *out);
  out->joint = h->s->clearance ? FB_JOINT_B : -1;
  out->penetration = h->s->pen_now;
  out->impacts[FB_JOINT_B] = h->s->impacts_now;
}

extern "C" void fb_simbody_scene_provenance(const fb_simbody_scene *h, int joint,
                                            fb_contact_provenance *out) {
  const Scene *s = h->s;
  out->mass_eff_min = joint == FB_JOINT_B ? s->me_min : NAN;
  out->mass_eff_max = joint == FB_JOINT_B ? s->me_max : NAN;
  out->erp_max = NAN;
  out->cfm_min = NAN;
  out->h_omega_max = NAN;
  out->contact_steps = joint == FB_JOINT_B ? s->contact_steps : 0;
}

extern "C" void fb_simbody_scene_reactions(const fb_simbody_scene *h, double force[4][2],
                                           double *drive_torque) {
  std::memcpy(force, h->s->x.reaction, sizeof h->s->x.reaction);
  *drive_torque = h->s->x.drive_torque;
}

extern "C" double fb_simbody_scene_drift(const fb_simbody_scene *h) { return h->s->drift; }

extern "C" size_t fb_simbody_scene_steps(const fb_simbody_scene *h) {
  return (size_t)h->s->integ->getNumStepsTaken();
}

extern "C" double fb_simbody_scene_stepping_s(const fb_simbody_scene *h) {
  return h->s->stepping_s;
}

extern "C" size_t fb_simbody_scene_exact_samples(const fb_simbody_scene *h) {
  return h->s->exact_samples;
}

extern "C" void fb_simbody_scene_destroy(fb_simbody_scene *h) {
  if (!h) return;
  delete h->s;
  delete h;
}
