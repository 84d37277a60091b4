// Simbody as a binding of the engine kit (kit.h): any planar description
// built as Simbody's users build a closed chain, and as the Simbody four-bar
// (simbody_scene.cpp) builds its own: a tree of mobilizers with the loops
// closed by constraints, one of Simbody's error-controlled integrators.
//
// Bodies: each a Body::Rigid, its frame at its centre of mass at the
// assembly angle, its moment about +z the description's (the same about
// the in-plane axes, a physical inertia no planar motion excites). Joints:
// close_loop picks a spanning tree (the prismatic joints first, a cut slide
// would need two constraints; then the joints at the ground, where a
// drive usually is; then the rest, in the description's order) and makes
// each tree joint a mobilizer from the body nearer the ground: a revolute
// one a MobilizedBody::Pin about +z, a prismatic one a MobilizedBody::Slider
// along its axis, both frames at the joint's assembly position (q = 0 at
// assembly). Every other revolute joint closes its loop as a
// Constraint::Ball between the two bodies' points at the joint (as the
// four-bar's cut at B: its out-of-plane row is redundant, which Simbody's
// constraint solver takes). A body no ideal joint holds (a clearance joint
// only) rides a MobilizedBody::Planar on the ground. The drive is the
// four-bar's: the driven Pin's angle prescribed at position level
// (SteadyAngle, simbody_internal.h). The integrator and its accuracy are
// the case's [simbody] keys, as for the four-bar; gravity along -y.
//
// Stepping: the kit steps a fixed h and samples after each step; Simbody's
// integrator takes its own error-controlled steps inside each h
// (Integrator::stepTo(t + h) with interpolation off, so that it stops at
// t + h exactly and the state the kit reads is an integrated one, not an
// interpolant).
//
// A clearance joint is a force element evaluated inside the integrator, as
// the four-bar's clearance models apply theirs (ClearanceForce): the pin's
// and the hole's centres fixed in their bodies (add_clearance), at every
// evaluation the exact eccentricity, the penetration |e| - c and its rate,
// the law's force (fb_contact_force) applied +F n on the hole, -F n on the
// pin (apply_contact); the restitution law's damper on the effective mass
// along n at that state (planar_mass.h, as the pipeline and the reference
// take it: held over h from the step's start it was 3 times off at an
// onset inside a step, the peaks 7 % low). From the kit's contact
// (add_contact) it holds over the step the episode's onset rate v0; an
// episode that begins inside a step takes its rate there (the four-bar's
// contact_law). The force element changes at a step's start when v0 or the
// hand-over does, and the integrator is restarted there
// (Integrator::reinitialize at Stage::Dynamics), so it never steps across
// the change. A slider in its guide (a prismatic clearance joint) is four
// contact slots (kit.h) in the same force element: each corner on the
// slider against its wall on the guide (planar_guide.h's layout at the
// start), penetration n . (corner - wall point), rate n . (v_corner -
// v_guide under it), n the wall's normal now, the restitution law's damper
// on the corner's face's share of the effective mass at every evaluation
// (fb_planar_guide_masses, as the reference takes it).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <vector>

#include "simbody_internal.h"

extern "C" {
#include "contact_mass.h"
#include "effective_mass.h"
#include "planar_loads.h"
#include "planar_mass.h"
#include "simbody_kit.h"
}

namespace fb_simbody {

namespace {

// one joint of the description as the walk added it
struct KitJoint {
  int b0, b1;            // kit handles (FB_KIT_GROUND: the ground)
  int prismatic;         // 1: a slide along axis
  double at[2], axis[2]; // assembly position [m]; the slide's unit axis in the world
  int tree;              // 1: a mobilizer of the tree; 0: a loop's cut (a constraint)
};

// a contact slot (kit.h: a pin in its hole, or a slider's corner against
// its guide's wall; add_clearance) and its contact, held over the step
// (add_contact's fb_kit_contact)
struct Held {
  int joint;             // 1: a clearance joint's slot
  int on, on_last;       // add_contact handed it for this step, for the last
  int pin, hole;         // kit handles
  Vec3 pin_at, hole_at;  // the pin's and the hole's centres in their bodies' frames [m]
  double clearance;      // radial clearance c [m]
  double v_min;          // an onset slower than this takes it as v0 (episode.h) [m/s]
  double v0;             // the episode's onset rate [m/s]
  fb_contact_law base;   // the joint's law (cj->law)
  int wall;              // 1: a slider's corner (pin_at, on the slider) against its wall
                         // (hole_at, a point of it, on the guide), else a pin in its hole
  Vec3 wall_n;           // a wall's unit normal, towards the wall, in the guide's frame [-]
  int jn, corner;         // a corner's joint (the description's) and its number (0 .. 3)
  fb_planar_guide guide; // a corner's slider in its guide: a, b, c [m]
};

struct Kit;

// every held contact as a force element (evaluated at each of the
// integrator's stages inside the step)
class KitContact : public Force::Custom::Implementation {
 public:
  explicit KitContact(const Kit *k) : k_(k) {}
  void calcForce(const State &state, Vector_<SpatialVec> &bodyForces, Vector_<Vec3> &,
                 Vector &) const override;
  Real calcPotentialEnergy(const State &) const override { return 0.0; }

 private:
  const Kit *k_;
};

struct Kit {
  MultibodySystem system;
  SimbodyMatterSubsystem matter;
  GeneralForceSubsystem forces;
  std::vector<fb_kit_body> body;      // by handle, at assembly
  std::vector<KitJoint> joint;        // in the order added (add_drive's index)
  std::vector<MobilizedBody> mob;     // by handle
  std::vector<int> child;             // by joint: the handle its mobilizer moves (-1: a cut)
  std::vector<int> planar;            // handles on a Planar mobilizer
  Held held[FB_KIT_SLOTS];            // by the kit's contact slot
  fb_planar_cmass *cm;                // a slider's corners' effective masses (planar_mass.h)
  const fb_planar *m;                 // the description (add_clearance)
  unsigned char off[FB_PLANAR_SPEC_MAX_JOINTS]; // 1: a clearance joint
  int changed;                        // 1: a contact's law, v0 or hand-over changed
  mutable std::vector<double> lq;     // the springs' and loads' workspace (3 nq: q, q' and
                                      // their generalised forces, planar_loads.h); empty:
                                      // the description has none
  fb_kit_world o;                     // the walk's settings: names, drive (kit.h)
  std::vector<ConstraintIndex> cut;   // by joint: a loop's cut's Ball (invalid: a mobilizer)
  std::vector<double> react;          // by joint: its reaction at the last step's start (3 each,
                                      // kit.h's reactions)
  int drive_joint = -1;               // the driven joint (add_drive's index)
  Vector_<SpatialVec> mob_reactions;  // the mobilizers' reactions (workspace)
  Vector motion_forces;               // the prescribed motion's forces (workspace)
  std::unique_ptr<Integrator> integ;
  double h;
  int integrator;
  double accuracy;
  size_t steps;
  Kit() : matter(system), forces(system), held(), cm(NULL), m(NULL), off(), changed(0), o(), h(0),
          integrator(0), accuracy(FB_SIMBODY_ACCURACY_DEFAULT), steps(0) {}
  ~Kit() { fb_planar_cmass_free(cm); }
  MobilizedBody &of(int b) { return b == FB_KIT_GROUND ? matter.Ground() : mob[b]; }
  const MobilizedBody &of(int b) const {
    return b == FB_KIT_GROUND ? matter.getGround() : mob[b];
  }
};

// the law at state: its damper on the effective mass along n there when it
// wants one (planar_mass.h, as the pipeline and the reference take it), at
// every evaluation, as the four-bar's contact_at does
// the planar core's coordinates (x, y, theta per moving body) at state
std::vector<double> coordinates(const Kit *k, const State &state) {
  std::vector<double> q(3 * k->mob.size());
  for (size_t b = 0; b < k->mob.size(); b++) {
    const Vec3 p = k->mob[b].getBodyOriginLocation(state);
    const Rotation &R = k->mob[b].getBodyRotation(state);
    q[3 * b] = p[0];
    q[3 * b + 1] = p[1];
    q[3 * b + 2] = std::atan2(R[1][0], R[0][0]);
  }
  return q;
}

fb_contact_law law_at(const Kit *k, const State &state, const Held &c, const double n[2]) {
  if (!fb_contact_law_wants_mass(&c.base)) return c.base;
  const std::vector<double> q = coordinates(k, state);
  double w[2][2];
  fb_diag d;
  const int jn = (int)(&c - k->held);
  const double me = fb_planar_effective_mass_tensor(w, k->m, q.data(), k->off, jn, &d) == FB_OK
                        ? fb_effective_mass_along(w, n) : NAN;
  return fb_contact_law_on_mass(&c.base, std::isfinite(me) && me > 0.0 ? me : c.base.mass);
}

// a slider's four corners' effective masses at one evaluation, worked out
// once for the first of its corners in contact (jn -1: not yet)
struct CornerMasses {
  int jn = -1;
  double mass[FB_PLANAR_GUIDE_CORNERS] = {0.0};
};

// a corner's law at state: its damper on the corner's face's share of the
// effective mass there (planar_guide.h, as the reference takes it), at
// every evaluation, as law_at does a pin's
fb_contact_law corner_law(const Kit *k, const State &state, const Held &c, CornerMasses &cm) {
  if (!fb_contact_law_wants_mass(&c.base)) return c.base;
  if (cm.jn != c.jn) {
    const std::vector<double> q = coordinates(k, state), qd(q.size(), 0.0);
    fb_planar_guide_corner gc[FB_PLANAR_GUIDE_CORNERS];
    fb_planar_guide_corners(gc, NULL, k->m, c.jn, &c.guide, q.data(), qd.data());
    cm = CornerMasses();
    cm.jn = c.jn;
    fb_diag d;
    if (fb_planar_cmass_factor(k->cm, q.data(), FB_EFFECTIVE_MASS_REG, &d) == FB_OK)
      fb_planar_guide_masses(cm.mass, NULL, k->cm, k->m, c.jn, gc, q.data());
  }
  const double me = cm.mass[c.corner];
  return fb_contact_law_on_mass(&c.base, std::isfinite(me) && me > 0.0 ? me : c.base.mass);
}

// a slider's corner against its wall at state: the corner's penetration
// n . (corner - wall point) and rate n . (v_corner - v_guide under it), n
// the wall's normal now; its law at state (corner_law)
void corner_force(const Kit *k, const State &state, const Held &c, CornerMasses &cm,
                  Vector_<SpatialVec> &bodyForces) {
  const MobilizedBody &slider = k->of(c.pin), &guide = k->of(c.hole);
  const Vec3 x = slider.findStationLocationInGround(state, c.pin_at);
  const Vec3 nw = guide.getBodyRotation(state) * c.wall_n;
  const double n[2] = {nw[0], nw[1]};
  const Vec3 d = x - guide.findStationLocationInGround(state, c.hole_at);
  const double depth = n[0] * d[0] + n[1] * d[1];
  if (!(depth > 0.0)) return;
  const Vec3 under = guide.findStationAtGroundPoint(state, x);
  const Vec3 v = slider.findStationVelocityInGround(state, c.pin_at) -
                 guide.findStationVelocityInGround(state, under);
  const double rate = n[0] * v[0] + n[1] * v[1];
  const double v0 = c.on ? c.v0 : std::fmax(rate, c.v_min);
  const fb_contact_law law = corner_law(k, state, c, cm);
  const double f = fb_contact_force(&law, depth, rate, v0);
  if (f > 0.0) apply_contact(state, slider, c.pin_at, guide, under, f, n, bodyForces);
}

void KitContact::calcForce(const State &state, Vector_<SpatialVec> &bodyForces, Vector_<Vec3> &,
                           Vector &) const {
  CornerMasses cm; // this evaluation's
  for (const Held &c : k_->held) {
    if (!c.joint) continue;
    if (c.wall) {
      corner_force(k_, state, c, cm, bodyForces);
      continue;
    }
    const MobilizedBody &pin = k_->of(c.pin), &hole = k_->of(c.hole);
    const Vec3 e = pin.findStationLocationInGround(state, c.pin_at) -
                   hole.findStationLocationInGround(state, c.hole_at);
    const double ecc = std::hypot(e[0], e[1]), depth = ecc - c.clearance;
    if (!(depth > 0.0)) continue;
    const Vec3 v = pin.findStationVelocityInGround(state, c.pin_at) -
                   hole.findStationVelocityInGround(state, c.hole_at);
    const double n[2] = {e[0] / ecc, e[1] / ecc}, rate = n[0] * v[0] + n[1] * v[1];
    // an episode that begins inside the step: its onset rate here, as the
    // four-bar's contact_law takes it
    const double v0 = c.on ? c.v0 : std::fmax(rate, c.v_min);
    const fb_contact_law law = law_at(k_, state, c, n);
    const double f = fb_contact_force(&law, depth, rate, v0);
    if (f > 0.0) apply_contact(state, pin, c.pin_at, hole, c.hole_at, f, n, bodyForces);
  }
  if (k_->lq.empty()) return;
  // the springs', loads' and torque drive's forces at this evaluation's
  // state (kit.h loads_from_state): each body's pose and rates in the
  // description's coordinates (its mass centre and angle, as
  // kit_body_state reads them), their generalised forces (planar_loads.h,
  // gravity the engine's own) applied at the centre and as a torque
  const size_t nb = k_->body.size(), nq = 3 * nb;
  double *q = k_->lq.data(), *qd = q + nq, *f = qd + nq;
  for (size_t b = 0; b < nb; b++) {
    const MobilizedBody &mb = k_->mob[b];
    const Vec3 p = mb.getBodyOriginLocation(state), v = mb.getBodyOriginVelocity(state);
    const Rotation &R = mb.getBodyRotation(state);
    q[3 * b] = p[0];
    q[3 * b + 1] = p[1];
    q[3 * b + 2] = std::atan2(R[1][0], R[0][0]);
    qd[3 * b] = v[0];
    qd[3 * b + 1] = v[1];
    qd[3 * b + 2] = mb.getBodyAngularVelocity(state)[2];
  }
  fb_planar_applied(f, k_->o.mech, q, qd, 0.0);
  for (size_t b = 0; b < nb; b++) {
    const MobilizedBody &mb = k_->mob[b];
    mb.applyForceToBodyPoint(state, mb.getBodyMassCenterStation(state),
                             Vec3(f[3 * b], f[3 * b + 1], 0.0), bodyForces);
    mb.applyBodyTorque(state, Vec3(0.0, 0.0, f[3 * b + 2]), bodyForces);
  }
}

Kit *kit(void *w) { return static_cast<Kit *>(w); }
const Kit *kit(const void *w) { return static_cast<const Kit *>(w); }

// world vector x in the frame of body b at assembly (the ground's: x);
// point 1: a point [m] (from the body's origin), 0: a direction
Vec3 local(const Kit *k, int b, const double x[2], int point = 1) {
  if (b == FB_KIT_GROUND) return Vec3(x[0], x[1], 0);
  const double *p = k->body[b].pos, c = std::cos(p[2]), s = std::sin(p[2]);
  const double dx = x[0] - point * p[0], dy = x[1] - point * p[1];
  return Vec3(c * dx + s * dy, -s * dx + c * dy, 0);
}

// the frame of joint j on body b: at the joint, its x axis at world angle
// angle at assembly
Transform joint_frame(const Kit *k, int b, const KitJoint &j, double angle) {
  const double a = b == FB_KIT_GROUND ? 0.0 : k->body[b].pos[2];
  // the rotation about z written out (the values Rotation(angle, ZAxis) sets):
  // that constructor, inlined under the sanitizers' -O2, trips GCC 12's
  // -Warray-bounds inside Simbody's Row.h (a false positive)
  const double c = std::cos(angle - a), s = std::sin(angle - a);
  return Transform(Rotation(Mat33(c, -s, 0, s, c, 0, 0, 0, 1), true), local(k, b, j.at));
}

// the velocity at assembly of body b's point at world x [m/s]
void point_velocity(const Kit *k, int b, const double x[2], double v[2]) {
  v[0] = v[1] = 0.0;
  if (b == FB_KIT_GROUND) return;
  const fb_kit_body &kb = k->body[b];
  v[0] = kb.vel[0] - kb.vel[2] * (x[1] - kb.pos[1]);
  v[1] = kb.vel[1] + kb.vel[2] * (x[0] - kb.pos[0]);
}

// tree joint j a mobilizer from parent (built) to c (not yet)
void mobilize(Kit *k, int jn, int parent, int c) {
  const KitJoint &j = k->joint[jn];
  const fb_kit_body &kb = k->body[c];
  const Body::Rigid rigid(MassProperties(kb.mass, Vec3(0), Inertia(kb.inertia)));
  if (j.prismatic) {
    const double angle = std::atan2(j.axis[1], j.axis[0]);
    k->mob[c] = MobilizedBody::Slider(k->of(parent), joint_frame(k, parent, j, angle), rigid,
                                      joint_frame(k, c, j, angle));
  } else {
    k->mob[c] = MobilizedBody::Pin(k->of(parent), joint_frame(k, parent, j, 0.0), rigid,
                                   joint_frame(k, c, j, 0.0));
  }
  k->child[jn] = c;
}

// the tree's order of choice within fb_kit_tree's groups (the drive, the
// slides, the pins): joints at the ground, then the rest
int rank_of(const KitJoint &j) {
  return (j.b0 == FB_KIT_GROUND || j.b1 == FB_KIT_GROUND) ? 0 : 1;
}

// the initial mobilities from the bodies' assembly velocities (every q is 0
// at assembly but a Planar body's, its pose)
void start_state(const Kit *k, State &state) {
  for (size_t jn = 0; jn < k->joint.size(); jn++) {
    const int c = k->child[jn];
    if (c < 0) continue;
    const KitJoint &j = k->joint[jn];
    const int p = j.b0 == c ? j.b1 : j.b0;
    if (j.prismatic) {
      double vc[2], vp[2];
      point_velocity(k, c, j.at, vc);
      point_velocity(k, p, j.at, vp);
      k->mob[c].setOneU(state, 0, (vc[0] - vp[0]) * j.axis[0] + (vc[1] - vp[1]) * j.axis[1]);
    } else {
      k->mob[c].setOneU(state, 0,
                        k->body[c].vel[2] - (p == FB_KIT_GROUND ? 0.0 : k->body[p].vel[2]));
    }
  }
  for (int b : k->planar)
    for (int i = 0; i < 3; i++) {
      const int m = i == 0 ? 2 : i - 1; // Planar's q: angle, x, y
      k->mob[b].setOneQ(state, i, k->body[b].pos[m]);
      k->mob[b].setOneU(state, i, k->body[b].vel[m]);
    }
}

fb_status kit_world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  Kit *k = new (std::nothrow) Kit;
  if (!k) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Simbody world");
  Force::UniformGravity(k->forces, k->matter, Vec3(0, -o->gravity, 0));
  Force::Custom(k->forces, new KitContact(k));
  k->h = o->h;
  k->o = *o;
  if (o->c) {
    k->integrator = o->c->simbody.integrator;
    k->accuracy = o->c->simbody.accuracy;
  }
  k->body.reserve((size_t)o->nbodies);
  k->joint.reserve((size_t)o->njoints);
  try {
    if (o->mech && fb_planar_has_loads(o->mech))
      k->lq.assign(3 * (size_t)fb_planar_nq(o->mech), 0.0);
  } catch (const std::bad_alloc &) {
    delete k;
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the Simbody world");
  }
  *out = k;
  return FB_OK;
}

fb_status kit_add_body(void *w, const fb_kit_body *b, fb_diag *diag) {
  (void)diag;
  kit(w)->body.push_back(*b);
  return FB_OK;
}

fb_status kit_add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag) {
  (void)diag;
  kit(w)->joint.push_back(KitJoint{b0, b1, 0, {at[0], at[1]}, {1.0, 0.0}, 0});
  return FB_OK;
}

fb_status kit_add_prismatic(void *w, int b0, int b1, const double at[2], const double axis[2],
                            fb_diag *diag) {
  (void)diag;
  kit(w)->joint.push_back(KitJoint{b0, b1, 1, {at[0], at[1]}, {axis[0], axis[1]}, 0});
  return FB_OK;
}

// the tree, its mobilizers, and the loops' cuts as Ball constraints
fb_status kit_close_loop(void *w, fb_diag *diag) {
  Kit *k = kit(w);
  const int nb = (int)k->body.size(), nj = (int)k->joint.size();
  if (nj > FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_RANGE, "the Simbody kit takes %d joints at most",
                       FB_PLANAR_SPEC_MAX_JOINTS);
  int order[FB_PLANAR_SPEC_MAX_JOINTS] = {0}, ends[FB_PLANAR_SPEC_MAX_JOINTS][2] = {{0}}, n = 0;
  unsigned char slide[FB_PLANAR_SPEC_MAX_JOINTS] = {0}, tree[FB_PLANAR_SPEC_MAX_JOINTS] = {0};
  for (int rank = 0; rank < 2; rank++)
    for (int jn = 0; jn < nj; jn++)
      if (rank_of(k->joint[(size_t)jn]) == rank) order[n++] = jn;
  for (int jn = 0; jn < nj; jn++) {
    const KitJoint &j = k->joint[(size_t)jn];
    ends[jn][0] = j.b0, ends[jn][1] = j.b1, slide[jn] = (unsigned char)j.prismatic;
  }
  const int cut = fb_kit_tree(&k->o, nj, ends, slide, order, tree);
  if (cut >= 0)
    return fb_diag_set(diag, FB_ERR_ARG, "Simbody cannot close a loop at prismatic joint '%s': "
                       "the Simbody kit cuts a loop at a pin (a Ball constraint), and the "
                       "description's prismatic joints (with the drive) form a loop, so one of "
                       "them must close it; make one of that loop's joints revolute",
                       fb_kit_joint_name(&k->o, cut));
  for (int jn = 0; jn < nj; jn++) k->joint[(size_t)jn].tree = tree[jn];
  try {
    k->mob.assign((size_t)nb, MobilizedBody());
    k->child.assign((size_t)nj, -1);
    std::vector<char> built((size_t)nb + 1, 0); // by node
    built[0] = 1;
    for (int grew = 1; grew;) { // outwards from the ground
      grew = 0;
      for (int jn = 0; jn < nj; jn++) {
        const KitJoint &j = k->joint[(size_t)jn];
        if (!j.tree || k->child[(size_t)jn] >= 0) continue;
        const int n0 = j.b0 + 1, n1 = j.b1 + 1;
        if (built[(size_t)n0] == built[(size_t)n1]) continue;
        const int parent = built[(size_t)n0] ? j.b0 : j.b1, c = parent == j.b0 ? j.b1 : j.b0;
        mobilize(k, jn, parent, c);
        built[(size_t)c + 1] = 1;
        grew = 1;
      }
    }
    for (int b = 0; b < nb; b++) {
      if (built[(size_t)b + 1]) continue;
      const fb_kit_body &kb = k->body[(size_t)b];
      k->mob[(size_t)b] = MobilizedBody::Planar(
          k->matter.Ground(), Transform(),
          Body::Rigid(MassProperties(kb.mass, Vec3(0), Inertia(kb.inertia))), Transform());
      k->planar.push_back(b);
    }
    k->cut.assign((size_t)nj, ConstraintIndex());
    for (int jn = 0; jn < nj; jn++) {
      const KitJoint &j = k->joint[(size_t)jn];
      if (j.tree) continue;
      k->cut[(size_t)jn] = Constraint::Ball(k->of(j.b0), local(k, j.b0, j.at), k->of(j.b1),
                                            local(k, j.b1, j.at)).getConstraintIndex();
    }
  } catch (const std::exception &ex) {
    return fb_diag_set(diag, FB_ERR_NUMERIC, "Simbody refused the tree: %.600s", ex.what());
  }
  return FB_OK;
}

// the drive (the four-bar's SteadyAngle on the driven Pin), then the
// system's topology, the start and the integrator
fb_status kit_add_drive(void *w, int jn, double rate, fb_diag *diag) {
  Kit *k = kit(w);
  const bool driven = jn >= 0; /* -1: undriven (kit.h), the walk's end only */
  const int c = driven ? k->child[(size_t)jn] : -1;
  const bool prismatic = driven && k->joint[(size_t)jn].prismatic;
  if (driven && (prismatic || c < 0))
    return fb_diag_set(diag, FB_ERR_ARG, "the Simbody kit drives a revolute joint of its tree; "
                       "the driven joint '%s' is %s", fb_kit_joint_name(&k->o, jn),
                       prismatic ? "prismatic" : "a loop's cut");
  try {
    if (driven)
      Motion::Custom(k->mob[(size_t)c],
                     new SteadyAngle(0.0, c == k->joint[(size_t)jn].b1 ? rate : -rate));
    k->drive_joint = jn;
    k->react.assign(3 * k->joint.size(), 0.0);
    State state = k->system.realizeTopology();
    start_state(k, state);
    state.setTime(0.0);
    k->integ.reset(make_integrator(k->system, k->integrator));
    k->integ->setAccuracy(k->accuracy);
    k->integ->setAllowInterpolation(false); // stop at each t + h: the kit reads integrated states
    k->integ->setInternalStepLimit((int)kStepsPerSampleMax);
    k->integ->initialize(state);
  } catch (const std::exception &ex) {
    return fb_diag_set(diag, FB_ERR_NUMERIC, "Simbody refused the system: %.600s", ex.what());
  }
  return FB_OK;
}

// clearance joint jn of m: the pin and the hole, their centres where the
// start puts them (kit.h: at, at_hole; together at the assembly)
fb_status kit_add_clearance(void *w, int jn, const fb_kit_clearance_joint *cj, fb_diag *diag) {
  const fb_planar *m = cj->m;
  const fb_kit_clearance *cl = cj->cl;
  Kit *k = kit(w);
  k->m = m;
  for (int i = 0; i < m->njoints && i < FB_PLANAR_SPEC_MAX_JOINTS; i++)
    k->off[i] = (cl->mask >> i) & 1u;
  if (cj->kind == FB_KIND_PRISMATIC) { // a slider in its guide: its four corners
    if (!k->cm) {
      const fb_status st = fb_planar_cmass_new(&k->cm, m, k->off, diag);
      if (st != FB_OK) return st;
    }
    for (int r = 0; r < FB_PLANAR_GUIDE_CORNERS; r++) {
      double corner[2], wall[2], normal[2];
      fb_planar_guide_layout(corner, wall, normal, cj->at, cj->axis, &cj->guide, r);
      Held &hc = k->held[fb_kit_slot(jn, r)];
      hc.joint = hc.wall = 1;
      hc.pin = cj->hole; // the slider (kit.h: the joint's body[1])
      hc.hole = cj->pin; // the guide
      hc.pin_at = local(k, hc.pin, corner);
      hc.hole_at = local(k, hc.hole, wall);
      hc.wall_n = local(k, hc.hole, normal, 0);
      hc.v_min = cl->impact_velocity_min;
      hc.base = cj->law;
      hc.jn = jn;
      hc.corner = r;
      hc.guide = cj->guide;
    }
    return FB_OK;
  }
  const fb_planar_joint &j = m->joint[jn];
  Held &hd = k->held[jn];
  hd.joint = 1;
  hd.pin = j.body[0] - 1; // kit.h's handles
  hd.hole = j.body[1] == FB_PLANAR_GROUND ? FB_KIT_GROUND : j.body[1] - 1;
  hd.pin_at = local(k, hd.pin, cj->at); // where the start puts each side (kit.h)
  hd.hole_at = local(k, hd.hole, cj->at_hole);
  hd.clearance = cl->radial_clearance;
  hd.v_min = cl->impact_velocity_min;
  hd.base = cj->law;
  return FB_OK;
}

// the kit's law and episode for the coming step (the header says how)
fb_status kit_add_contact(void *w, int jn, const fb_kit_contact *c, fb_diag *diag) {
  (void)diag;
  Kit *k = kit(w);
  Held &hd = k->held[jn];
  if (!hd.on_last || hd.v0 != c->v0) k->changed = 1;
  hd.on = 1;
  hd.v0 = c->v0;
  return FB_OK;
}

// every ideal joint's reaction at the integrator's state (the step's
// start; kit.h's convention: the force on body[1] from body[0], the moment
// about the joint's point on body[1], body[0]'s when body[1] is the ground)
// into k->react. A mobilizer's: Simbody's reaction on its child from its
// parent at the child's M frame, the joint's point
// (calcMobilizerReactionForces), turned to body[1]'s side; a Pin's moment
// is the drive's torque on the driven joint (the prescribed motion's force,
// findMotionForces, as the Simbody four-bar reads it), a Slider's the
// reaction's couple, moved to the parent's point when body[1] is the
// parent. A cut's: the Ball's on its body 2, body[1], negated
// (getBallReactionForceOnBody2 is the reaction body 2 exerts; the
// analytic model's reactions, tests/test_planar_loads.py, fix the sign),
// no moment.
void note_reactions(Kit *k) {
  const State &state = k->integ->getState();
  k->system.realize(state, Stage::Acceleration);
  k->matter.calcMobilizerReactionForces(state, k->mob_reactions);
  k->matter.findMotionForces(state, k->motion_forces);
  for (size_t jn = 0; jn < k->joint.size(); jn++) {
    const KitJoint &j = k->joint[jn];
    double *r = &k->react[3 * jn];
    r[0] = r[1] = r[2] = 0.0;
    if (!j.tree) {
      const Constraint::Ball &ball = Constraint::Ball::downcast(k->matter.getConstraint(k->cut[jn]));
      const Vec3 f = k->of(j.b1).getBodyRotation(state) * ball.getBallReactionForceOnBody2(state);
      r[0] = -f[0], r[1] = -f[1]; /* Simbody's reaction is body 2's on the constraint */
      continue;
    }
    const int c = k->child[jn];
    const MobilizedBody &mc = k->mob[(size_t)c];
    const SpatialVec &sv = k->mob_reactions[mc.getMobilizedBodyIndex()];
    const double s = c == j.b1 ? 1.0 : -1.0;
    r[0] = s * sv[1][0], r[1] = s * sv[1][1];
    if (j.prismatic) {
      double moment = sv[0][2]; // on the child about its point
      if (c != j.b1 && j.b1 != FB_KIT_GROUND) { // about the parent's point instead
        const Vec3 d = mc.findStationLocationInGround(state, local(k, c, j.at)) -
                       k->of(j.b1).findStationLocationInGround(state, local(k, j.b1, j.at));
        moment += d[0] * sv[1][1] - d[1] * sv[1][0];
      }
      r[2] = s * moment;
    } else if ((int)jn == k->drive_joint) {
      r[2] = s * -k->motion_forces[mc.getFirstUIndex(state)];
    }
  }
}

void kit_reactions(const void *w, int jn, double out[3]) {
  const double *r = &kit(w)->react[3 * (size_t)jn];
  out[0] = r[0], out[1] = r[1], out[2] = r[2];
}

fb_status kit_step(void *w, fb_diag *diag) {
  Kit *k = kit(w);
  for (const Held &c : k->held) k->changed |= c.on != c.on_last;
  const double t1 = (double)(k->steps + 1) * k->h;
  try {
    // the force element changed at this step's start: the integrator's
    // derivative there is evaluated again
    if (k->changed) k->integ->reinitialize(Stage::Dynamics, false);
    k->changed = 0;
    note_reactions(k);
    for (int tries = 0; k->integ->getTime() < t1 && tries < 3; tries++) {
      const Integrator::SuccessfulStepStatus st = k->integ->stepTo(t1);
      if (st == Integrator::ReachedStepLimit)
        return fb_diag_set(diag, FB_ERR_NUMERIC, "simbody: step budget (%ld steps within h) at "
                           "t = %g s", kStepsPerSampleMax, k->integ->getTime());
      if (st == Integrator::EndOfSimulation)
        return fb_diag_set(diag, FB_ERR_NUMERIC, "simbody: the integrator ended at t = %g s (%s)",
                           k->integ->getTime(),
                           Integrator::getTerminationReasonString(
                               k->integ->getTerminationReason()).c_str());
    }
  } catch (const std::bad_alloc &) {
    return fb_diag_set(diag, FB_ERR_NOMEM, "simbody: out of memory at t = %g s", t1 - k->h);
  } catch (const std::exception &ex) {
    return fb_diag_set(diag, FB_ERR_NUMERIC, "simbody: %.300s at t = %g s", ex.what(), t1 - k->h);
  }
  for (Held &c : k->held) c.on_last = c.on, c.on = 0;
  k->steps++;
  return FB_OK;
}

void kit_body_state(const void *w, int b, double pos[3], double vel[3]) {
  const Kit *k = kit(w);
  const State &state = k->integ->getState();
  k->system.realize(state, Stage::Velocity);
  const MobilizedBody &m = k->mob[(size_t)b];
  const Vec3 p = m.getBodyOriginLocation(state), v = m.getBodyOriginVelocity(state);
  const Rotation &R = m.getBodyRotation(state);
  pos[0] = p[0];
  pos[1] = p[1];
  pos[2] = std::atan2(R[1][0], R[0][0]);
  vel[0] = v[0];
  vel[1] = v[1];
  vel[2] = m.getBodyAngularVelocity(state)[2];
}

void kit_world_free(void *w) { delete kit(w); }

} // namespace

} // namespace fb_simbody

// the table (kit.h's order; no designated initializers in C++11)
extern "C" const fb_kit_binding fb_simbody_kit = {
    "simbody",
    fb_simbody::kit_world_new,
    fb_simbody::kit_add_body,
    fb_simbody::kit_add_revolute,
    fb_simbody::kit_add_prismatic,
    fb_simbody::kit_close_loop,
    fb_simbody::kit_add_drive,
    NULL, /* hold_in_plane: every mobilizer is planar; a body only a clearance joint holds
             rides a Planar mobilizer (close_loop) */
    fb_simbody::kit_add_contact,
    NULL, /* contact_force: the law's at the step's start, the force the element applies there */
    fb_simbody::kit_step,
    fb_simbody::kit_body_state,
    fb_simbody::kit_world_free,
    fb_simbody::kit_add_clearance,
    1, /* applied_force: a force element under the integrator's error control, no row to
          alias */
    NULL, /* model_text: no model file */
    NULL, /* contact_force_max: one force per step */
    0,    /* contact_rows: no constraint row */
    fb_simbody::kit_reactions,
    NULL, /* contact_force_vec: the normal force along the normal */
    0,    /* friction: a normal law only */
    NULL, /* body_accel: the step's difference */
    0,    /* explicit_law: an error-controlled integrator */
    NULL, /* apply_wrench: the force element evaluates them itself */
    1,    /* loads_from_state: at every stage of the integrator, from its state */
    NULL, /* reactions_in: every world reports them */
    NULL, /* clearance_reaction: the kit's contacts (add_contact) */
    NULL, /* collide: no collider of its own */
    NULL, /* collided */
    NULL, /* penetration: the exact one */
    0,    /* contact_always: the law's contact in contact only */
    NULL, /* step_by: its integrator controls its own steps inside each h */
    0,    /* persistent_rule: no adaptive step */
    0,    /* contact_speed_limit: no fixed row's world */
    NULL, /* body_rotation: from the angle */
};
