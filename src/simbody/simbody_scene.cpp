// The Simbody scene (simbody_scene.h): the only translation unit of the
// project that includes Simbody. C++ stays inside this file; the C side sees
// the extern "C" functions of simbody_scene.h only.
#include "Simbody.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <new>

extern "C" {
#include "contact.h"
#include "effective_mass.h"
#include "episode.h"
#include "simbody_scene.h"
}

using namespace SimTK;

namespace {

// Internal steps the integrator may take per output sample before the run
// stops with the named reason "step budget" (FB_STOP_STEP_BUDGET): the
// reference's FB_REFERENCE_STEPS_PER_SAMPLE budget is an average over the
// run; this one is per sample, so a collapsing step size stops the run
// within one sample interval instead of running on without end.
const long kStepsPerSampleMax = 200000;

// The contact at the crank-coupler joint in one state: the law's force at
// the exact pin-in-hole eccentricity.
struct ContactEval {
  double e[2];     // eccentricity pin - hole [m]
  double pen;      // penetration depth, >= 0 [m]
  double ddot;     // penetration rate (> 0 approaching) [m/s]
  double force;    // normal force on the coupler along +n [N]
  double n[2];     // unit normal (pin - hole)/|pin - hole|
  double mass_eff; // effective mass along n [kg] (restitution law), else NAN
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
  MultibodySystem system;
  SimbodyMatterSubsystem matter;
  GeneralForceSubsystem forces;
  MobilizedBody::Pin crank, follower, coupler;
  Constraint::Ball ball;  // ideal models only
  std::unique_ptr<Integrator> integ;
  double h;               // output step [s]
  size_t k;               // samples taken (time k h)
  fb_episode ep;          // contact episodes, updated at every internal step end
  // extremes over the internal step ends of the current sample interval
  int interval_contact;
  double max_force, max_pen, a3_ext, a4_ext;
  int interval_impacts;   // ep.impacts at the start of the interval
  // the last sample
  fb_sample x;
  double reaction[4][2], drive_torque, drift;
  double pen_now;
  Vector_<SpatialVec> mob_reactions; // per mobilized body, reused every sample
  Vector motion_forces;              // per mobility, reused every sample
  // provenance
  double me_min, me_max;
  size_t contact_steps;
  fb_stop stop;

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

ContactEval contact_at(const Scene *s, const State &state) {
  ContactEval ce;
  std::memset(&ce, 0, sizeof ce);
  ce.mass_eff = NAN;
  const Vec3 pin = s->crank.findStationLocationInGround(state, Vec3(s->a, 0, 0));
  const Vec3 hole = s->coupler.findStationLocationInGround(state, Vec3(0));
  ce.e[0] = pin[0] - hole[0];
  ce.e[1] = pin[1] - hole[1];
  const double ecc = std::hypot(ce.e[0], ce.e[1]);
  const double delta = ecc - s->sm.radial_clearance;
  if (!(delta > 0.0) || ecc == 0.0) return ce;
  ce.pen = delta;
  ce.n[0] = ce.e[0] / ecc;
  ce.n[1] = ce.e[1] / ecc;
  const Vec3 vp = s->crank.findStationVelocityInGround(state, Vec3(s->a, 0, 0));
  const Vec3 vh = s->coupler.findStationVelocityInGround(state, Vec3(0));
  ce.ddot = ce.n[0] * (vp[0] - vh[0]) + ce.n[1] * (vp[1] - vh[1]);
  fb_contact_law law = s->sm.law[FB_JOINT_B];
  if (law.kind == FB_LAW_RESTITUTION) {
    // the damper on the mechanism's effective mass along n (effective_mass.h)
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
    if (fb_effective_mass_tensor(w, &m, NULL) == FB_OK) {
      const double me = fb_effective_mass_along(w[FB_JOINT_B], ce.n);
      if (me > 0.0 && std::isfinite(me)) law.mass = ce.mass_eff = me;
    }
  }
  const double v0 = s->ep.in_contact ? s->ep.v0 : std::fmax(ce.ddot, s->sm.impact_velocity_min);
  ce.force = fb_contact_force(&law, delta, ce.ddot, v0);
  return ce;
}

void ClearanceForce::calcForce(const State &state, Vector_<SpatialVec> &bodyForces,
                               Vector_<Vec3> &, Vector &) const {
  const ContactEval ce = contact_at(s_, state);
  if (ce.force == 0.0) return;
  const Vec3 f(ce.force * ce.n[0], ce.force * ce.n[1], 0);
  s_->coupler.applyForceToBodyPoint(state, Vec3(0), f, bodyForces);
  s_->crank.applyForceToBodyPoint(state, Vec3(s_->a, 0, 0), -f, bodyForces);
}

// reads the sample (angles, rates, accelerations, contact, loads) from state
void read_sample(Scene *s, const State &state) {
  s->system.realize(state, Stage::Acceleration);
  fb_sample &x = s->x;
  std::memset(&x, 0, sizeof x);
  x.t = state.getTime();
  const double q2 = s->crank.getOneQ(state, 0), q4 = s->follower.getOneQ(state, 0);
  const double q3 = s->coupler.getOneQ(state, 0);
  const double u4 = s->follower.getOneU(state, 0), u3 = s->coupler.getOneU(state, 0);
  const double a4 = s->follower.getOneUDot(state, 0), a3 = s->coupler.getOneUDot(state, 0);
  x.crank_angle = q2;
  x.follower_angle = q4;
  x.follower_omega = u4;
  x.follower_alpha = a4;
  x.coupler_angle = q4 + q3;
  x.coupler_omega = u4 + u3;
  x.coupler_alpha = a4 + a3;
  // loads: reactions of the mobilizers (parent on child), of the ball or
  // the contact at B, and the drive torque the Motion applies
  s->matter.calcMobilizerReactionForces(state, s->mob_reactions);
  const Vec3 fa = s->mob_reactions[s->crank.getMobilizedBodyIndex()][1];
  const Vec3 fd = s->mob_reactions[s->follower.getMobilizedBodyIndex()][1];
  const Vec3 fc = s->mob_reactions[s->coupler.getMobilizedBodyIndex()][1];
  s->reaction[FB_JOINT_A][0] = fa[0];
  s->reaction[FB_JOINT_A][1] = fa[1];
  s->reaction[FB_JOINT_D][0] = fd[0];
  s->reaction[FB_JOINT_D][1] = fd[1];
  s->reaction[FB_JOINT_C][0] = -fc[0]; // on the follower from the coupler
  s->reaction[FB_JOINT_C][1] = -fc[1];
  s->matter.findMotionForces(state, s->motion_forces);
  s->drive_torque = -s->motion_forces[s->crank.getFirstUIndex(state)];
  s->pen_now = 0.0;
  s->drift = 0.0;
  if (s->clearance) {
    const ContactEval ce = contact_at(s, state);
    s->pen_now = ce.pen;
    s->reaction[FB_JOINT_B][0] = ce.force * ce.n[0];
    s->reaction[FB_JOINT_B][1] = ce.force * ce.n[1];
    double *col = x.contact[FB_JOINT_B];
    col[FB_C_FORCE] = ce.force;
    col[FB_C_PEN] = ce.pen;
    col[FB_C_EX] = ce.e[0];
    col[FB_C_EY] = ce.e[1];
    col[FB_C_STATE] = s->ep.state;
  } else {
    const Vec3 fb = s->coupler.getBodyRotation(state) * s->ball.getBallReactionForceOnBody2(state);
    s->reaction[FB_JOINT_B][0] = fb[0];
    s->reaction[FB_JOINT_B][1] = fb[1];
    const Vec3 pin = s->crank.findStationLocationInGround(state, Vec3(s->a, 0, 0));
    const Vec3 hole = s->coupler.findStationLocationInGround(state, Vec3(0));
    s->drift = (pin - hole).norm();
  }
}

// bookkeeping at one internal step end: episodes, interval extremes, provenance
void note_step_end(Scene *s, const State &state) {
  s->system.realize(state, Stage::Acceleration);
  const ContactEval ce = contact_at(s, state);
  fb_episode_update(&s->ep, ce.pen > 0.0, ce.ddot, s->sm.impact_velocity_min);
  if (ce.pen > 0.0) {
    s->interval_contact = 1;
    if (std::isfinite(ce.mass_eff)) {
      if (s->contact_steps == 0 || ce.mass_eff < s->me_min) s->me_min = ce.mass_eff;
      if (s->contact_steps == 0 || ce.mass_eff > s->me_max) s->me_max = ce.mass_eff;
    }
    s->contact_steps++;
  }
  s->max_force = std::fmax(s->max_force, ce.force);
  s->max_pen = std::fmax(s->max_pen, ce.pen);
  const double u4 = s->follower.getOneUDot(state, 0);
  const double a3 = u4 + s->coupler.getOneUDot(state, 0);
  if (std::fabs(a3) > std::fabs(s->a3_ext)) s->a3_ext = a3;
  if (std::fabs(u4) > std::fabs(s->a4_ext)) s->a4_ext = u4;
}

void reset_interval(Scene *s) {
  s->interval_contact = 0;
  s->max_force = s->max_pen = 0.0;
  s->a3_ext = s->a4_ext = 0.0;
  s->interval_impacts = s->ep.impacts;
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

fb_status set_stop(Scene *s, fb_stop_kind kind, const char *detail, fb_diag *diag) {
  std::memset(&s->stop, 0, sizeof s->stop);
  s->stop.kind = kind;
  s->stop.engine = "simbody";
  s->stop.joint = -1;
  s->stop.t = (double)s->k * s->h;
  if (kind == FB_STOP_STEP_BUDGET) {
    s->stop.value = (double)kStepsPerSampleMax;
    s->stop.limit = (double)kStepsPerSampleMax;
    s->stop.t_end = s->sm.def->duration;
  }
  std::snprintf(s->stop.detail, sizeof s->stop.detail, "%.150s", detail ? detail : "");
  return fb_diag_set(diag, FB_ERR_NUMERIC, "simbody: %s at t = %g s",
                     detail && *detail ? detail : "integration failed", s->stop.t);
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
    s->h = sm->solver.h;
    s->k = 0;
    std::memset(&s->ep, 0, sizeof s->ep);
    s->me_min = s->me_max = NAN;
    s->contact_steps = 0;
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
    s->integ->setReturnEveryInternalStep(true);
    s->integ->initialize(state);
    reset_interval(s);
    note_step_end(s, s->integ->getState());
    read_sample(s, s->integ->getState());
  } catch (const std::bad_alloc &) {
    fb_simbody_scene_destroy(h);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Simbody scene");
  } catch (const std::exception &ex) {
    fb_simbody_scene_destroy(h);
    return fb_diag_set(diag, FB_ERR_NUMERIC, "model '%s': Simbody refused the system: %.600s",
                       sm->model->name, ex.what());
  }
  *out = h;
  return FB_OK;
}

extern "C" fb_status fb_simbody_scene_step(fb_simbody_scene *h, fb_diag *diag) {
  Scene *s = h->s;
  const double t_next = (double)(s->k + 1) * s->h;
  reset_interval(s);
  try {
    long taken = 0;
    for (;;) {
      const Integrator::SuccessfulStepStatus r = s->integ->stepTo(t_next);
      if (r == Integrator::ReachedReportTime) break;
      if (r == Integrator::EndOfSimulation)
        return set_stop(s, FB_STOP_SOLVER, "the integrator ended the simulation", diag);
      if (r == Integrator::TimeHasAdvanced) {
        note_step_end(s, s->integ->getState());
        if (++taken > kStepsPerSampleMax) return set_stop(s, FB_STOP_STEP_BUDGET, "step budget", diag);
      }
    }
  } catch (const std::exception &ex) {
    return set_stop(s, FB_STOP_SOLVER, ex.what(), diag);
  }
  s->k++;
  read_sample(s, s->integ->getState());
  if (s->clearance) {
    double *col = s->x.contact[FB_JOINT_B];
    // peaks between samples: the interval's extremes at its internal step ends
    if (s->interval_contact || col[FB_C_PEN] > 0.0) {
      col[FB_C_FORCE] = std::fmax(col[FB_C_FORCE], s->max_force);
      col[FB_C_PEN] = std::fmax(col[FB_C_PEN], s->max_pen);
      if (std::fabs(s->a3_ext) > std::fabs(s->x.coupler_alpha)) s->x.coupler_alpha = s->a3_ext;
      if (std::fabs(s->a4_ext) > std::fabs(s->x.follower_alpha)) s->x.follower_alpha = s->a4_ext;
    }
    // an impact that began inside the interval is marked at this sample
    col[FB_C_STATE] = s->ep.impacts > s->interval_impacts ? FB_STATE_IMPACT : s->ep.state;
  }
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

extern "C" void fb_simbody_scene_sample(const fb_simbody_scene *h, fb_sample *x) {
  *x = h->s->x;
  x->t = (double)h->s->k * h->s->h; // on the grid exactly
}

extern "C" void fb_simbody_scene_contact(const fb_simbody_scene *h, fb_engine_contact *out) {
  std::memset(out, 0, sizeof *out);
  out->joint = h->s->clearance ? FB_JOINT_B : -1;
  out->penetration = h->s->pen_now;
  out->impacts[FB_JOINT_B] = h->s->ep.impacts;
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
  std::memcpy(force, h->s->reaction, sizeof h->s->reaction);
  *drive_torque = h->s->drive_torque;
}

extern "C" double fb_simbody_scene_drift(const fb_simbody_scene *h) { return h->s->drift; }

extern "C" size_t fb_simbody_scene_steps(const fb_simbody_scene *h) {
  return (size_t)h->s->integ->getNumStepsTaken();
}

extern "C" void fb_simbody_scene_destroy(fb_simbody_scene *h) {
  if (!h) return;
  delete h->s;
  delete h;
}
