// The Simbody scene's clearance contact (simbody_scene.h): the project's law
// (contact.h) at the exact pin-in-hole eccentricity of the clearance joint
// (the four-bar's crank-coupler, the slider-crank's piston pin), with the
// restitution law's damper on the mechanism's effective mass along the
// normal (effective_mass.h), and the custom force that applies it.
#include <cmath>
#include <cstring>

#include "simbody_internal.h"

extern "C" {
#include "contact_mass.h"
#include "effective_mass.h"
}

namespace fb_simbody {

namespace {

// the slider-crank in state (effective_mass.h, as fb_mechanism_from_slider_crank
// from the bodies): crank, rod and slider; joint centres A = 0, B, the rod's
// pin centre P and the slider's point on the guide, its hole centre H (the
// slider's centre of mass); the guide prismatic, the piston pin the clearance
void slider_crank_mechanism(const Scene *s, const State &state, fb_mechanism *m) {
  const MobilizedBody *body[2] = {&s->crank, &s->coupler};
  const double len[2] = {s->a, s->b};
  for (int i = 0; i < 3; i++) {
    m->mass[i] = s->sm.link[i].mass;
    m->inertia[i] = s->sm.link[i].inertia;
  }
  for (int i = 0; i < 2; i++) {
    const Vec3 com =
        body[i]->findStationLocationInGround(state, Vec3(s->sm.link[i].com_fraction * len[i], 0, 0));
    m->com[i][0] = com[0];
    m->com[i][1] = com[1];
  }
  const Vec3 b = s->crank.findStationLocationInGround(state, Vec3(s->a, 0, 0));
  const Vec3 pin = s->pin_body->findStationLocationInGround(state, s->pin_at);
  const Vec3 hole = s->hole_body->findStationLocationInGround(state, s->hole_at);
  m->com[2][0] = hole[0];
  m->com[2][1] = hole[1];
  m->joint[0][0] = m->joint[0][1] = 0.0;
  m->joint[1][0] = b[0];
  m->joint[1][1] = b[1];
  m->joint[2][0] = pin[0];
  m->joint[2][1] = pin[1];
  m->joint[3][0] = hole[0];
  m->joint[3][1] = hole[1];
  m->clearance_mask = 1 << s->cj;
  m->prismatic_mask = 1 << 3;
  m->crank_driven = 1;
}

// the inverse effective-mass tensor at the clearance joint in state
// (effective_mass.h), for the restitution law's damper; 0 when it cannot be
// formed
int mass_tensor(const Scene *s, const State &state, double w_out[2][2]) {
  fb_mechanism m;
  std::memset(&m, 0, sizeof m);
  if (s->sc) {
    slider_crank_mechanism(s, state, &m);
    double w[4][2][2];
    if (fb_effective_mass_tensor(w, &m, NULL) != FB_OK) return 0;
    std::memcpy(w_out, w[s->cj], sizeof w[s->cj]);
    return 1;
  }
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

} // namespace

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
  fb_contact_law law = s->sm.law[s->cj];
  if (fb_contact_law_wants_mass(&law) && w) {
    // the damper on the mechanism's effective mass along n (effective_mass.h)
    double wm[2][2] = {{w[0][0], w[0][1]}, {w[1][0], w[1][1]}};
    const double me = fb_effective_mass_along(wm, ce.n);
    if (me > 0.0 && std::isfinite(me)) law = fb_contact_law_on_mass(&law, ce.mass_eff = me);
  }
  const double v0 = ep.in_contact ? ep.v0 : std::fmax(ce.ddot, s->sm.impact_velocity_min);
  ce.force = fb_contact_force(&law, delta, ce.ddot, v0);
  return ce;
}

// the contact in a realized state, with the scene's episodes; *w_ok and w
// (when given) the inverse effective-mass tensor used
ContactEval contact_at(const Scene *s, const State &state, double (*w)[2], int *w_ok) {
  const Vec3 pin = s->pin_body->findStationLocationInGround(state, s->pin_at);
  const Vec3 hole = s->hole_body->findStationLocationInGround(state, s->hole_at);
  const Vec3 vp = s->pin_body->findStationVelocityInGround(state, s->pin_at);
  const Vec3 vh = s->hole_body->findStationVelocityInGround(state, s->hole_at);
  const double e[2] = {pin[0] - hole[0], pin[1] - hole[1]};
  const double edot[2] = {vp[0] - vh[0], vp[1] - vh[1]};
  double wl[2][2];
  double (*wp)[2] = w ? w : wl;
  // the tensor where the law needs it (in contact); everywhere when asked for
  const int ok = fb_contact_law_wants_mass(&s->sm.law[s->cj]) &&
                 (w || std::hypot(e[0], e[1]) > s->sm.radial_clearance) && mass_tensor(s, state, wp);
  if (w_ok) *w_ok = ok;
  return contact_law(s, e, edot, ok ? wp : NULL, s->ep);
}

void ClearanceForce::calcForce(const State &state, Vector_<SpatialVec> &bodyForces,
                               Vector_<Vec3> &, Vector &) const {
  const ContactEval ce = contact_at(s_, state);
  if (ce.force == 0.0) return;
  apply_contact(state, *s_->pin_body, s_->pin_at, *s_->hole_body, s_->hole_at, ce.force, ce.n,
                bodyForces);
}

} // namespace fb_simbody
