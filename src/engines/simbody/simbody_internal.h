// The Simbody scene's insides, shared by the C++ files that make it up
// (private to src/engines/simbody: it includes Simbody). simbody_scene.h is
// the C side's view; simbody_scene.cpp says how Simbody is driven. The files:
//   simbody_scene.cpp    building the system, handing out samples (emit), the
//                        extern "C" functions of simbody_scene.h
//   simbody_contact.cpp  the clearance contact: the law at the exact
//                        pin-in-hole eccentricity, the effective mass, the
//                        custom force
//   simbody_knots.cpp    the integrator's steps and their end states (knots):
//                        values, loads, contact episodes, failures, and a
//                        state realized exactly
//   simbody_grid.cpp     the records of the output grid: from a knot,
//                        interpolated between knots, realized exactly
//   simbody_peaks.cpp    the peaks: local extremes of the interpolated series
//                        made exact, knot intervals refined
// Calls run one way: scene -> peaks -> grid -> knots -> contact (and scene to
// each below it).
#ifndef FB_SIMBODY_INTERNAL_H
#define FB_SIMBODY_INTERNAL_H

#include "Simbody.h"

#include <cmath>
#include <cstdlib>
#include <deque>
#include <new>
#include <memory>
#include <vector>

extern "C" {
#include "contact.h"
#include "episode.h"
#include "simbody_scene.h"
}

namespace fb_simbody {

using namespace SimTK;

// Internal steps the integrator may take between two output samples before
// the run stops with the named reason "step budget" (FB_STOP_STEP_BUDGET):
// the reference's FB_REFERENCE_STEPS_PER_SAMPLE budget is an average over
// the run; this one is per sample, so a collapsing step size stops the run
// within one sample interval instead of running on without end.
const long kStepsPerSampleMax = 200000;

// Mobilities, in the knots' arrays: the crank (angle prescribed), the second
// output body (the four-bar's follower about D; the slider-crank's slider
// along the guide), the coupler (relative to its parent mobility,
// Scene::parent: the four-bar's about C on the follower, the slider-crank's
// connecting rod about B on the crank).
enum { kCrank = 0, kFollower = 1, kCoupler = 2, kMobilities = 3 };

// Load components, in the knots' and samples' order: the drive torque, then
// the reaction at the description's joints 0..3 (x, y; the four-bar's A, B,
// C, D in invdyn.h's convention; the slider-crank's ground-crank,
// crank-coupler, coupler-slider and slider-ground in slider_crank_invdyn.h's,
// the last the force on the ground from the slider).
const int kLoads = 9;

// Columns whose local extremes call for an exact realization: the two output
// bodies' accelerations (the coupler's angular one; the follower's angular
// one or the slider's), the drive torque, the four reaction magnitudes and
// the two output velocities (the peaks summary.json, check and the tests
// take).
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

// The contact at the clearance joint (Scene::cj) in one state: the law's
// force at the exact pin-in-hole eccentricity.
struct ContactEval {
  double e[2];     // eccentricity pin - hole [m]
  double edot[2];  // its rate [m/s]
  double pen;      // penetration depth, >= 0 [m]
  double ddot;     // penetration rate (> 0 approaching) [m/s]
  double force;    // normal force on the coupler along +n [N]
  double n[2];     // unit normal (pin - hole)/|pin - hole|
  double mass_eff; // effective mass along n [kg] (restitution law), else NAN
};

// Values a sample is filled from: mobilities q (3) and u (3), the two output
// bodies' accelerations (2), the loads (kLoads).
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
  double alpha[2];      // the output bodies' accelerations: the coupler's angular
                        // [rad/s^2], the follower's angular [rad/s^2] or the slider's [m/s^2]
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

// The drive (the four-bar's crank, the engine kit's driven joint): the
// mobility's angle prescribed at position level, q(t) = theta0 + omega t,
// so the driven body follows the analytic angle exactly (a velocity-level
// Motion::Steady leaves the angle to the integrator and to the constraint
// projection, which moved it by 7e-6 rad over 3 revolutions at accuracy
// 1e-6). The drive torque is the Motion's multiplier
// (SimbodyMatterSubsystem::findMotionForces).
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

// A clearance joint's normal force F [N] along unit n (hole towards pin) as
// a force element applies it: +F n on the hole's body at hole_at, -F n on
// the pin's body at pin_at (body frames) [m]
inline void apply_contact(const State &state, const MobilizedBody &pin, const Vec3 &pin_at,
                          const MobilizedBody &hole, const Vec3 &hole_at, double force,
                          const double n[2], Vector_<SpatialVec> &bodyForces) {
  const Vec3 f(force * n[0], force * n[1], 0);
  hole.applyForceToBodyPoint(state, hole_at, f, bodyForces);
  pin.applyForceToBodyPoint(state, pin_at, -f, bodyForces);
}

// ---- simbody_scene.cpp ----

// a new integrator of kind fb_simbody_integrator for sys (the case's
// [simbody] integrator)
Integrator *make_integrator(const System &sys, int kind);

struct Scene;

// The project's contact law (contact.h) as a Simbody custom force: +F n on
// the hole centre, -F n on the pin centre (the four-bar's crank pin in the
// coupler's hole at B; the slider-crank's rod pin in the slider's hole).
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
  fb_model_scene sm;
  int sc;                 // 1: the slider-crank (fb_mech_slider_crank); 0: the four-bar
  int cj;                 // the joint the tree is cut at, the one that may be a pin in a
                          // hole: FB_JOINT_B (crank-coupler), or the slider-crank's
                          // coupler-slider (FB_JOINT_C, index 2)
  int clearance;          // 1: joint cj is a pin in a hole
  int parent;             // the coupler's parent mobility: kFollower (four-bar), kCrank
  double a, b, c, g;      // crank, coupler, follower, ground lengths [m] (slider-crank: c, g 0)
  double offset;          // the slider-crank's guide line y = offset [m] (four-bar 0)
  double theta0, omega2;  // the prescribed crank angle theta0 + omega2 t
  MultibodySystem system;
  SimbodyMatterSubsystem matter;
  GeneralForceSubsystem forces;
  MobilizedBody::Pin crank, follower, coupler;
  MobilizedBody::Slider slider; // the slider-crank's slider (the four-bar's follower unused)
  const MobilizedBody *mob[kMobilities]; // crank, follower or slider, coupler
  MobilizedBody *pin_body, *hole_body; // the bodies of joint cj's pin and hole
  Vec3 pin_at, hole_at;   // the pin and hole centres on them (body frames) [m]
  Constraint::Ball ball;  // ideal models only: pin_body's pin_at on hole_body's hole_at
  std::unique_ptr<Integrator> integ;
  State scratch;          // the one State exact samples are realized in
  double h;               // output step [s]
  size_t n_grid;          // the grid ends at n_grid h (the run's last sample)
  fb_episode ep;          // contact episodes, updated at every step end (the law's v0)
  std::deque<Knot> knots; // from the knot before the oldest open record's interval on
  long knot_ids;          // knots made so far
  long knot_done;         // id of the newest knot whose bookkeeping a record took
  fb_episode ep_done;     // the episodes after that knot
  Record *recs;           // records rec_base .. gen_next - 1, record k at k mod nrecs
  size_t nrecs;           // (a power of two, grown in place when the lookahead needs more)
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
  // the loads' rates at the ends of the knot interval records were last
  // interpolated in (simbody_grid.cpp), computed once per interval: the key
  // is the first knot's id and which neighbours the rates saw
  long rate_id;           // -1: none held
  int rate_before, rate_after;
  double rate0[kLoads], rate1[kLoads];

  Scene()
      : matter(system), forces(system), recs(NULL), nrecs(0), rate_id(-1), rate_before(0),
        rate_after(0) {}
  ~Scene() { std::free(recs); }
  Scene(const Scene &) = delete;
  Scene &operator=(const Scene &) = delete;
};

// ---- simbody_contact.cpp ----

// the law at eccentricity e [m] and rate edot [m/s], with episodes ep; w the
// inverse effective-mass tensor [1/kg] (restitution law) or NULL
ContactEval contact_law(const Scene *s, const double e[2], const double edot[2],
                        const double (*w)[2], const fb_episode &ep);

// the contact in a realized state, with the scene's episodes; *w_ok and w
// (when given) the inverse effective-mass tensor used
ContactEval contact_at(const Scene *s, const State &state, double (*w)[2] = NULL,
                       int *w_ok = NULL);

// ---- simbody_knots.cpp ----

// a knot from a state realized through accelerations (the scene's episodes)
Knot knot_of(Scene *s, const State &state);

// the knot of a state the integrator advanced to, with the episodes' update
Knot make_knot(Scene *s, const State &state);

// a failure to generate record k, kept for when sample k is asked for
void fail(Scene *s, size_t k, fb_stop_kind kind, const char *detail);

// one more integrator step towards target: appends its knot; 0 on failure
int advance(Scene *s, double target, size_t k);

// the state at t with mobilities q, u realized exactly, with episodes ep
Knot realize_state(Scene *s, double t, const double q[3], const double u[3],
                   const fb_episode &ep);

// ---- simbody_grid.cpp ----

// record k in the ring of records
inline Record *rec(Scene *s, size_t k) { return &s->recs[k & (s->nrecs - 1)]; }

// the value of tracked column m in a sample (inline: every record takes
// all kTracked)
inline double sample_value(const fb_sample &x, int m) {
  switch (m) {
    case 0: return x.body[0][FB_Q_ACC];
    case 1: return x.body[1][FB_Q_ACC];
    case 2: return x.drive_torque;
    case 7: return x.body[0][FB_Q_VEL];
    case 8: return x.body[1][FB_Q_VEL];
    default: { /* a reaction's magnitude (|F| ~ N: neither overflows) */
      const double fx = x.reaction[m - 3][0], fy = x.reaction[m - 3][1];
      return std::sqrt(fx * fx + fy * fy);
    }
  }
}

// the sample's columns and values from q, u, alpha, loads and the contact
void fill_sample(const Scene *s, Record *r, double t, const double q[3], const double u[3],
                 const double alpha[2], const double load[kLoads], const ContactEval *ce,
                 int keep_track);

// record r from knot kn's realized values
void record_from_knot(const Scene *s, Record *r, const Knot &kn, int keep_track);

// the knot interval (i, i + 1) holding t
size_t interval_of(const Scene *s, double t);

// generates record k (time k h), running the integrator as far as it needs
void generate(Scene *s, size_t k);

// record r realized exactly; returns its values as a knot
Knot realize_exact(Scene *s, Record *r);

// ---- simbody_peaks.cpp ----

// after record k is generated: a local extreme at k - 1 joins the pending peaks
void find_peaks(Scene *s, size_t k);

// makes peak p exact (and the records beside it that reach it)
void make_peak_exact(Scene *s, const Peak &p);

} // namespace fb_simbody

#endif
