// The ideal four-bar in Simbody 3.7, bare: a tree of Pin mobilizers (ground
// -> crank at A, ground -> follower at D, follower -> coupler at C), the
// loop closed at B by a Constraint::Ball, the crank angle prescribed as
// theta2 + omega2 t (Motion::Custom), gravity along -y; an error-controlled
// integrator (RungeKuttaMerson, or the one named) at the given accuracy runs
// to the end on its own steps (stepTo the final time, returning after every
// step: Integrator::setReturnEveryInternalStep). The output grid k h is
// filled between its steps by the cubic Hermite interpolant Simbody's
// interpolated reports use (q from q and qdot, u from u and udot; the
// accelerations its derivative; the loads, known at the steps, linear), and
// over t >= window each kept column's largest and smallest sample is made
// exact: the sample realized from its interpolated q and u with Simbody's
// own projection of an interpolated report (LocalOnly, at the constraint
// tolerance), its neighbours too, climbing to the exact extreme. Simbody's
// API only (Simbody User's Guide, "Integrators", "TimeStepper"; Integrator,
// System::projectQ/projectU); settings and output: peer.h. Extra
// arguments: integrator (rkmerson, rkfeldberg, rk3, cpodes, verlet)
// accuracy.
#include "Simbody.h"

#include <vector>

#include "peer.h"

using namespace SimTK;

namespace {

class SteadyAngle : public Motion::Custom::Implementation {
 public:
  SteadyAngle(double th, double w) : th_(th), w_(w) {}
  Motion::Level getLevel(const State &) const override { return Motion::Position; }
  void calcPrescribedPosition(const State &s, int, Real *q) const override { q[0] = th_ + w_ * s.getTime(); }
  void calcPrescribedPositionDot(const State &, int, Real *qd) const override { qd[0] = w_; }
  void calcPrescribedPositionDotDot(const State &, int, Real *qdd) const override { qdd[0] = 0; }
  Implementation *clone() const override { return new SteadyAngle(*this); }

 private:
  double th_, w_;
};

Body::Rigid link(double m, double izz, double com) {
  const Vec3 c(com, 0, 0);
  return Body::Rigid(MassProperties(m, c, Inertia(izz, izz, izz).shiftFromMassCenter(c, m)));
}

struct Knot {
  double t, q[3], u[3], udot[3], load[9];
};

struct Model {
  MultibodySystem system;
  SimbodyMatterSubsystem matter;
  GeneralForceSubsystem forces;
  MobilizedBody::Pin crank, follower, coupler;
  Constraint::Ball ball;
  double a = 0;
  Model() : matter(system), forces(system) {}
  // q, u, udot and the loads (drive torque, reactions at A, B, C, D) of a realized state
  void read(const State &s, Knot &k) {
    const MobilizedBody *mb[3] = {&crank, &follower, &coupler};
    k.t = s.getTime();
    for (int i = 0; i < 3; i++) {
      k.q[i] = mb[i]->getOneQ(s, 0);
      k.u[i] = mb[i]->getOneU(s, 0);
      k.udot[i] = mb[i]->getOneUDot(s, 0);
    }
    Vector_<SpatialVec> r;
    matter.calcMobilizerReactionForces(s, r);
    Vector mf;
    matter.findMotionForces(s, mf);
    const Vec3 fa = r[crank.getMobilizedBodyIndex()][1], fd = r[follower.getMobilizedBodyIndex()][1];
    const Vec3 fc = r[coupler.getMobilizedBodyIndex()][1];
    const Vec3 fb = coupler.getBodyRotation(s) * ball.getBallReactionForceOnBody2(s);
    const double l[9] = {-mf[crank.getFirstUIndex(s)], fa[0], fa[1], fb[0], fb[1], -fc[0], -fc[1],
                         fd[0], fd[1]};
    for (int i = 0; i < 9; i++) k.load[i] = l[i];
  }
};

void hermite(double s, double dt, double y0, double d0, double y1, double d1, double *y, double *dy) {
  const double s2 = s * s, s3 = s2 * s;
  *y = (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * dt * d0 + (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * dt * d1;
  if (dy)
    *dy = ((6 * s2 - 6 * s) * y0 + (3 * s2 - 4 * s + 1) * dt * d0 + (-6 * s2 + 6 * s) * y1 +
           (3 * s2 - 2 * s) * dt * d1) / dt;
}

// a grid sample's columns from q, u, accelerations and loads
void columns(double t, const double q[3], const double u[3], const double ud[3], const double l[9],
             double v[P_COLS]) {
  v[P_T] = t;
  v[P_CRANK] = q[0];
  v[P_COUPLER] = q[1] + q[2];
  v[P_COUPLER_W] = u[1] + u[2];
  v[P_COUPLER_A] = ud[1] + ud[2];
  v[P_FOLLOWER] = q[1];
  v[P_FOLLOWER_W] = u[1];
  v[P_FOLLOWER_A] = ud[1];
  v[P_TORQUE] = l[0];
  for (int i = 0; i < 8; i++) v[P_RX + i] = l[1 + i];
}

}  // namespace

int main(int argc, char **argv) {
  peer_args args;
  peer_fourbar f;
  peer_start(&args, &f, argc, argv);
  const char *integ = peer_str(&args, "integrator");
  const double accuracy = peer_num(&args, "accuracy");
  const double t0 = peer_clock();
  Model m;
  m.a = f.len[0];
  Force::UniformGravity(m.forces, m.matter, Vec3(0, -f.gravity, 0));
  m.crank = MobilizedBody::Pin(m.matter.Ground(), Transform(), link(f.mass[0], f.inertia[0], f.com[0] * f.len[0]), Transform());
  m.follower = MobilizedBody::Pin(m.matter.Ground(), Transform(Vec3(f.len[3], 0, 0)),
                                  link(f.mass[2], f.inertia[2], f.com[2] * f.len[2]), Transform());
  m.coupler = MobilizedBody::Pin(m.follower, Transform(Vec3(f.len[2], 0, 0)),
                                 link(f.mass[1], f.inertia[1], f.com[1] * f.len[1]), Transform(Vec3(f.len[1], 0, 0)));
  Motion::Custom(m.crank, new SteadyAngle(f.th2, f.omega2));
  m.ball = Constraint::Ball(m.crank, Vec3(f.len[0], 0, 0), m.coupler, Vec3(0));
  State state = m.system.realizeTopology();
  m.crank.setOneQ(state, 0, f.th2);
  m.follower.setOneQ(state, 0, f.th4);
  m.coupler.setOneQ(state, 0, f.th3 - f.th4);
  m.crank.setOneU(state, 0, f.omega2);
  m.follower.setOneU(state, 0, f.w4);
  m.coupler.setOneU(state, 0, f.w3 - f.w4);
  Integrator *in;
  if (strcmp(integ, "rkfeldberg") == 0) in = new RungeKuttaFeldbergIntegrator(m.system);
  else if (strcmp(integ, "rk3") == 0) in = new RungeKutta3Integrator(m.system);
  else if (strcmp(integ, "cpodes") == 0) in = new CPodesIntegrator(m.system, CPodes::BDF, CPodes::Newton);
  else if (strcmp(integ, "verlet") == 0) in = new VerletIntegrator(m.system);
  else in = new RungeKuttaMersonIntegrator(m.system);
  in->setAccuracy(accuracy);
  in->setReturnEveryInternalStep(true);
  in->initialize(state);
  State scratch = in->getState();
  peer_series s;
  peer_series_init(&s, f.steps + 1);
  std::vector<Knot> knots;
  knots.reserve(4096);
  const double t1 = peer_clock();
  // the integrator's own steps to the end
  const double t_end = (double)f.steps * f.h;
  Knot k;
  m.system.realize(in->getState(), Stage::Acceleration);
  m.read(in->getState(), k);
  knots.push_back(k);
  while (knots.back().t < t_end) {
    const Integrator::SuccessfulStepStatus st = in->stepTo(t_end);
    if (st == Integrator::StartOfContinuousInterval) continue;
    const State &adv = in->getAdvancedState();
    if (adv.getTime() <= knots.back().t) break;
    m.system.realize(adv, Stage::Acceleration);
    m.read(adv, k);
    knots.push_back(k);
  }
  // the grid between the steps
  size_t i = 0;
  for (long n = 0; n <= f.steps; n++) {
    const double t = (double)n * f.h;
    while (i + 2 < knots.size() && knots[i + 1].t < t) i++;
    const Knot &a = knots[i], &b = knots[i + 1];
    const double dt = b.t - a.t, sp = (t - a.t) / dt;
    double q[3], u[3], ud[3], l[9], v[P_COLS];
    for (int j = 0; j < 3; j++) {
      hermite(sp, dt, a.q[j], a.u[j], b.q[j], b.u[j], &q[j], nullptr);
      hermite(sp, dt, a.u[j], a.udot[j], b.u[j], b.udot[j], &u[j], &ud[j]);
    }
    for (int j = 0; j < 9; j++) l[j] = a.load[j] + sp * (b.load[j] - a.load[j]);
    columns(t, q, u, ud, l, v);
    peer_push(&s, v);
  }
  // the extremes over the window made exact: sample n realized as Simbody
  // realizes an interpolated report, climbing to the exact extreme
  ProjectOptions opt;
  opt.setRequiredAccuracy(in->getConstraintToleranceInUse());
  opt.setOption(ProjectOptions::LocalOnly);
  std::vector<char> exact((size_t)s.n, 0);
  auto realize = [&](long n) {
    if (exact[(size_t)n]) return;
    exact[(size_t)n] = 1;
    const double t = s.col[P_T][n];
    size_t j = 0;
    while (j + 2 < knots.size() && knots[j + 1].t < t) j++;
    const Knot &a = knots[j], &b = knots[j + 1];
    const double dt = b.t - a.t, sp = (t - a.t) / dt;
    scratch.setTime(t);
    const MobilizedBody *mb[3] = {&m.crank, &m.follower, &m.coupler};
    for (int c = 0; c < 3; c++) {
      double q, u;
      hermite(sp, dt, a.q[c], a.u[c], b.q[c], b.u[c], &q, nullptr);
      hermite(sp, dt, a.u[c], a.udot[c], b.u[c], b.udot[c], &u, nullptr);
      mb[c]->setOneQ(scratch, 0, q);
      mb[c]->setOneU(scratch, 0, u);
    }
    ProjectResults res;
    Vector none;
    m.system.realize(scratch, Stage::Time);
    m.system.prescribeQ(scratch);
    m.system.realize(scratch, Stage::Position);
    m.system.projectQ(scratch, none, opt, res);
    m.system.prescribeU(scratch);
    m.system.realize(scratch, Stage::Velocity);
    res.clear();
    m.system.projectU(scratch, none, opt, res);
    m.system.realize(scratch, Stage::Acceleration);
    Knot e;
    m.read(scratch, e);
    double v[P_COLS];
    columns(t, e.q, e.u, e.udot, e.load, v);
    for (int c = 0; c < P_COLS; c++) s.col[c][n] = v[c];
  };
  const int cols[5] = {P_COUPLER_W, P_FOLLOWER_W, P_COUPLER_A, P_FOLLOWER_A, P_TORQUE};
  long first = 0;
  while (first < s.n && s.col[P_T][first] < f.window) first++;
  auto climb = [&](int c, int sign, long n, double (*val)(const peer_series &, int, long)) {
    for (;;) {
      realize(n);
      if (n > first) realize(n - 1);
      if (n + 1 < s.n) realize(n + 1);
      long best = n;
      if (n > first && sign * val(s, c, n - 1) > sign * val(s, c, best)) best = n - 1;
      if (n + 1 < s.n && sign * val(s, c, n + 1) > sign * val(s, c, best)) best = n + 1;
      if (best == n) return;
      n = best;
    }
  };
  auto column = [](const peer_series &ps, int c, long n) { return ps.col[c][n]; };
  auto magnitude = [](const peer_series &ps, int j, long n) {
    return std::hypot(ps.col[P_RX + 2 * j][n], ps.col[P_RX + 2 * j + 1][n]);
  };
  for (int c : cols)
    for (int sign = -1; sign <= 1; sign += 2) {
      long best = first;
      for (long n = first; n < s.n; n++)
        if (sign * s.col[c][n] > sign * s.col[c][best]) best = n;
      if (first < s.n) climb(c, sign, best, column);
    }
  for (int j = 0; j < 4; j++) {
    long best = first;
    for (long n = first; n < s.n; n++)
      if (magnitude(s, j, n) > magnitude(s, j, best)) best = n;
    if (first < s.n) climb(j, 1, best, magnitude);
  }
  const double t2 = peer_clock();
  peer_report("simbody", &s, (long)in->getNumStepsTaken(), t1 - t0, t2 - t1, f.window);
  peer_series_free(&s);
  delete in;
  return 0;
}
