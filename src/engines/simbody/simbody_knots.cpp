// The integrator's steps of the Simbody scene and their end states, the
// knots (simbody_scene.cpp says how they are used): each step's end realized
// through accelerations with its loads (the mobilizer reactions, the drive's
// motion force, the Ball's or the contact's force at the cut joint), the contact
// episodes updated at every step end, a failure kept for the sample it
// stops, and a state realized exactly as Simbody realizes an interpolated
// report.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

#include "simbody_internal.h"

extern "C" {
#include "clock.h"
}

namespace fb_simbody {

namespace {

// loads in a state realized through accelerations: drive torque, then the
// reactions at joints 0..3 (x, y). The four-bar: A, D and C the mobilizers'
// (C on the follower from the coupler), B the cut. The slider-crank: the
// ground-crank and crank-coupler mobilizers' (on the crank from the ground,
// on the rod from the crank), the guide's the slider mobilizer's negated (on
// the ground from the slider, slider_crank_invdyn.h's -N along y), the
// piston pin the cut. At the cut joint cj: the Ball's reaction on the hole's
// body (ideal) or the contact force ce (clearance); *drift the Ball's
// violation
void loads_at(Scene *s, const State &state, const ContactEval *ce, double load[kLoads],
              double *drift) {
  s->matter.calcMobilizerReactionForces(state, s->mob_reactions);
  const Vec3 fa = s->mob_reactions[s->crank.getMobilizedBodyIndex()][1];
  const Vec3 fc = s->mob_reactions[s->coupler.getMobilizedBodyIndex()][1];
  s->matter.findMotionForces(state, s->motion_forces);
  load[0] = -s->motion_forces[s->crank.getFirstUIndex(state)];
  load[1 + 2 * FB_JOINT_A] = fa[0];
  load[2 + 2 * FB_JOINT_A] = fa[1];
  if (s->sc) {
    const Vec3 fs = s->mob_reactions[s->slider.getMobilizedBodyIndex()][1];
    load[1 + 2 * FB_JOINT_B] = fc[0]; // on the rod from the crank
    load[2 + 2 * FB_JOINT_B] = fc[1];
    load[1 + 2 * FB_JOINT_D] = -fs[0]; // on the ground from the slider
    load[2 + 2 * FB_JOINT_D] = -fs[1];
  } else {
    const Vec3 fd = s->mob_reactions[s->follower.getMobilizedBodyIndex()][1];
    load[1 + 2 * FB_JOINT_D] = fd[0];
    load[2 + 2 * FB_JOINT_D] = fd[1];
    load[1 + 2 * FB_JOINT_C] = -fc[0]; // on the follower from the coupler
    load[2 + 2 * FB_JOINT_C] = -fc[1];
  }
  *drift = 0.0;
  if (ce) {
    load[1 + 2 * s->cj] = ce->force * ce->n[0];
    load[2 + 2 * s->cj] = ce->force * ce->n[1];
  } else {
    const Vec3 fb = s->hole_body->getBodyRotation(state) * s->ball.getBallReactionForceOnBody2(state);
    load[1 + 2 * s->cj] = fb[0];
    load[2 + 2 * s->cj] = fb[1];
    const Vec3 pin = s->pin_body->findStationLocationInGround(state, s->pin_at);
    const Vec3 hole = s->hole_body->findStationLocationInGround(state, s->hole_at);
    *drift = (pin - hole).norm();
  }
}

} // namespace

// a knot from a state realized through accelerations, with the episodes ep
// (the scene's are used for the law)
Knot knot_of(Scene *s, const State &state) {
  s->system.realize(state, Stage::Acceleration);
  Knot kn;
  std::memset(&kn, 0, sizeof kn);
  kn.t = state.getTime();
  for (int i = 0; i < kMobilities; i++) {
    kn.q[i] = s->mob[i]->getOneQ(state, 0);
    kn.u[i] = s->mob[i]->getOneU(state, 0);
    kn.udot[i] = s->mob[i]->getOneUDot(state, 0);
  }
  kn.alpha[0] = kn.udot[s->parent] + kn.udot[kCoupler];
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

// the state at time t with mobilities q, u realized exactly, as Simbody
// realizes an interpolated report (createInterpolatedState): q and u set
// into the scratch State, the crank prescribed, projected onto the
// constraint manifold (the Ball at the cut: for the one-degree-of-freedom loop
// this sets the velocities the interpolation has only to O(dt^4), and it
// moves an integrator step's end by the constraint tolerance) and realized
// through accelerations, with the episodes ep (the law's v0 as the
// integration saw it)
Knot realize_state(Scene *s, double t, const double q[3], const double u[3],
                   const fb_episode &ep) {
  State &st = s->scratch;
  st.setTime(t);
  for (int i = 0; i < kMobilities; i++) {
    s->mob[i]->setOneQ(st, 0, q[i]);
    s->mob[i]->setOneU(st, 0, u[i]);
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

} // namespace fb_simbody
