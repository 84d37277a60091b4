// The Simbody scene (simbody_scene.h): building the system, handing out the
// samples, and the extern "C" functions the C side sees. C++ and Simbody stay
// inside src/engines/simbody (simbody_internal.h lists its files); the C side
// sees the extern "C" functions of simbody_scene.h only.
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
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>

#include "simbody_internal.h"

extern "C" {
#include "slider_crank_invdyn.h"
}

namespace fb_simbody {

namespace {

// inertia of a link about its origin: the link's in-plane inertia about +z
// through its centre of mass (only Izz acts in the plane; the other two
// axes are given the same value so that the inertia is physical)
Body::Rigid link_body(const fb_link_mass &m, double length) {
  const Vec3 com(m.com_fraction * length, 0, 0);
  const Inertia central(m.inertia, m.inertia, m.inertia);
  return Body::Rigid(MassProperties(m.mass, com, central.shiftFromMassCenter(com, m.mass)));
}

// the slider-crank's slider: its mass at its frame's origin, the hole
// centre on the guide (mechanism.h); its inertia, positive, does not enter
// the motion (the Slider mobilizer holds its rotation)
Body::Rigid slider_body(const fb_link_mass &m) {
  return Body::Rigid(MassProperties(m.mass, Vec3(0), Inertia(m.inertia, m.inertia, m.inertia)));
}

} // namespace

// the integrator of [simbody] integrator (simbody_internal.h)
Integrator *make_integrator(const System &sys, int kind) {
  switch (kind) {
    case FB_SIMBODY_RKFELDBERG: return new RungeKuttaFeldbergIntegrator(sys);
    case FB_SIMBODY_RK3: return new RungeKutta3Integrator(sys);
    case FB_SIMBODY_CPODES: return new CPodesIntegrator(sys, CPodes::BDF, CPodes::Newton);
    case FB_SIMBODY_VERLET: return new VerletIntegrator(sys);
    default: return new RungeKuttaMersonIntegrator(sys);
  }
}

namespace {

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
  // tells a peak there. Record k + 1, generated a lookahead ago, is invalid
  // exactly when generation failed at or before it (generate): asked of the
  // scene, not of the record, which has long left the cache
  if (!r->exact && !r->at_knot && (k + 1 >= s->gen_next || (s->failed && k + 1 >= s->fail_k)))
    realize_exact(s, r);
  s->x = r->x;
  s->x.t = t_open; // on the grid exactly
  s->drift = r->drift;
  s->pen_now = r->pen;
  s->impacts_now = r->ep.impacts;
  if (s->clearance) {
    double *col = s->x.contact[s->cj];
    // peaks between samples: the extremes at the knots of ((k-1) h, k h]
    if (r->knot_contact || col[FB_C_PEN] > 0.0) {
      col[FB_C_FORCE] = std::fmax(col[FB_C_FORCE], r->kmax_force);
      col[FB_C_PEN] = std::fmax(col[FB_C_PEN], r->kmax_pen);
      double *acc[2] = {&s->x.body[0][FB_Q_ACC], &s->x.body[1][FB_Q_ACC]};
      if (std::fabs(r->ka3) > std::fabs(*acc[0])) *acc[0] = r->ka3;
      if (std::fabs(r->ka4) > std::fabs(*acc[1])) *acc[1] = r->ka4;
    }
    // an impact that began inside the interval is marked at this sample
    col[FB_C_STATE] = r->new_impact ? FB_STATE_IMPACT : r->ep.state;
  }
  return FB_OK;
}

} // namespace

} // namespace fb_simbody

using namespace fb_simbody;

struct fb_simbody_scene {
  Scene *s;
};

extern "C" fb_status fb_simbody_scene_create(fb_simbody_scene **out, const fb_model_scene *sm,
                                             fb_diag *diag) {
  *out = NULL;
  fb_status st = fb_scene_check(sm->def, diag);
  if (st != FB_OK) return st;
  const int sc = sm->def->source.mechanism == FB_MECH_SLIDER_CRANK;
  if (sm->def->source.mechanism != FB_MECH_FOURBAR && !sc)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': the Simbody scene builds the four-bar and the slider-crank only",
                       sm->model->name);
  // the joint the tree is cut at: the four-bar's crank-coupler, the
  // slider-crank's piston pin (the case refuses clearance elsewhere for it)
  const int cj = sc ? (int)FB_SC_JOINT_COUPLER_SLIDER : (int)FB_JOINT_B;
  const char *cut = sc ? "coupler-slider" : "crank-coupler";
  if (sm->clearance_mask & ~(1 << cj))
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': the Simbody tree is cut at the %s joint only; "
                       "[clearance] joints names others: set [solver] builder = auto or kit "
                       "(the engine kit takes any pins), joints = %s, or drop the "
                       "simbody-clearance-* models", sm->model->name, cut, cut);
  fb_start_state start;
  st = fb_model_scene_start(&start, sm, diag);
  if (st != FB_OK) return st;
  fb_simbody_scene *h = new (std::nothrow) fb_simbody_scene;
  if (!h) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Simbody scene");
  h->s = NULL;
  try {
    Scene *s = new Scene;
    h->s = s;
    s->sm = *sm;
    s->sc = sc;
    s->cj = cj;
    s->clearance = (sm->clearance_mask & (1 << cj)) != 0;
    s->parent = sc ? kCrank : kFollower;
    s->a = sm->lengths.length[FB_CRANK];
    s->b = sm->lengths.length[FB_COUPLER];
    s->c = sc ? 0.0 : sm->lengths.length[FB_FOLLOWER];
    s->g = sc ? 0.0 : sm->lengths.length[FB_GROUND];
    s->offset = sc ? sm->lengths.length[FB_LENGTH_OFFSET] : 0.0;
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
    // the tree; each link's frame at its first joint, x along the link
    s->crank = MobilizedBody::Pin(s->matter.Ground(), Transform(), link_body(sm->link[0], s->a),
                                  Transform());
    if (sc) {
      // ground -> crank (A), crank -> rod (B), ground -> slider (Slider along
      // x on the guide line y = offset, its frame at its hole centre H, its
      // centre of mass there); the loop cut at the piston pin
      s->coupler = MobilizedBody::Pin(s->crank, Transform(Vec3(s->a, 0, 0)),
                                      link_body(sm->link[1], s->b), Transform());
      s->slider = MobilizedBody::Slider(s->matter.Ground(), Transform(Vec3(0, s->offset, 0)),
                                        slider_body(sm->link[2]), Transform());
      s->mob[kFollower] = &s->slider;
      s->pin_body = &s->coupler;
      s->pin_at = Vec3(s->b, 0, 0);
      s->hole_body = &s->slider;
      s->hole_at = Vec3(0);
    } else {
      // ground -> crank (A), ground -> follower (D), follower -> coupler (C);
      // the loop cut at B
      s->follower = MobilizedBody::Pin(s->matter.Ground(), Transform(Vec3(s->g, 0, 0)),
                                       link_body(sm->link[2], s->c), Transform());
      s->coupler = MobilizedBody::Pin(s->follower, Transform(Vec3(s->c, 0, 0)),
                                      link_body(sm->link[1], s->b), Transform(Vec3(s->b, 0, 0)));
      s->mob[kFollower] = &s->follower;
      s->pin_body = &s->crank;
      s->pin_at = Vec3(s->a, 0, 0);
      s->hole_body = &s->coupler;
      s->hole_at = Vec3(0);
    }
    s->mob[kCrank] = &s->crank;
    s->mob[kCoupler] = &s->coupler;
    Motion::Custom(s->crank, new SteadyAngle(start.crank_angle, sm->omega2));
    if (s->clearance)
      Force::Custom(s->forces, new ClearanceForce(s));
    else
      s->ball = Constraint::Ball(*s->pin_body, s->pin_at, *s->hole_body, s->hole_at);
    State state = s->system.realizeTopology();
    s->crank.setOneQ(state, 0, start.crank_angle);
    s->crank.setOneU(state, 0, sm->omega2);
    if (sc) {
      // the rod relative to the crank; the slider's hole centre x along the guide
      s->coupler.setOneQ(state, 0, start.coupler_angle - start.crank_angle);
      s->coupler.setOneU(state, 0, start.coupler_omega - sm->omega2);
      s->slider.setOneQ(state, 0, start.body[1][FB_Q_POS]);
      s->slider.setOneU(state, 0, start.body[1][FB_Q_VEL]);
    } else {
      s->follower.setOneQ(state, 0, start.follower_angle);
      s->coupler.setOneQ(state, 0, start.coupler_angle - start.follower_angle);
      s->follower.setOneU(state, 0, start.follower_omega);
      s->coupler.setOneU(state, 0, start.coupler_omega - start.follower_omega);
    }
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
  if (s->clearance) s->x.contact[s->cj][FB_C_STATE] = s->ep.state;
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
  out->joint = h->s->clearance ? h->s->cj : -1;
  out->penetration = h->s->pen_now;
  out->impacts[h->s->cj] = h->s->impacts_now;
}

extern "C" void fb_simbody_scene_provenance(const fb_simbody_scene *h, int joint,
                                            fb_contact_provenance *out) {
  const Scene *s = h->s;
  out->mass_eff_min = joint == s->cj ? s->me_min : NAN;
  out->mass_eff_max = joint == s->cj ? s->me_max : NAN;
  out->erp_max = NAN;
  out->cfm_min = NAN;
  out->h_omega_max = NAN;
  out->contact_steps = joint == s->cj ? s->contact_steps : 0;
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
