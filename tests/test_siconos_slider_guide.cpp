// Siconos's own slider-crank with a slider in its guide (translational
// clearance), reproduced from its equations, against the example's reference
// output (issue 61, its first "Done when" item).
//
//            y
//            |        guide wall  y = +(b + c)     ___________________
//    crank   |  rod                               | 1             2 |
//   A --l1-- B ---------l2------------------------|--------P------- |  slider
//   (theta1)   (theta2)                           | 3             4 |  2a x 2b,
//                                                  -------------------  tilt theta3
//                                  guide wall  y = -(b + c)
//
// The example: siconos-tutorials, examples/mechanics/SliderCrank,
// SliderCrankMoreauJeanCombinedProjectionOSI.cpp with its plugin and its
// reference output SliderCrankMoreauJeanCombinedProjectionOSI.ref (docs/
// models.md, "Siconos's slider in its guide", gives the repository, path and
// commit). The system is written here from its equations, no code copied:
//
//   q = (theta1, theta2, theta3): the crank's and the rod's absolute angles
//   and the slider's tilt. The crank turns about A = 0 (its centre of mass
//   at l1/2), the rod hangs from B = l1 u(theta1) (its centre at l2/2), the
//   slider's centre P = B + l2 u(theta2) is the rod's end (the piston pin,
//   ideal), u(x) = (cos x, sin x). No drive: the crank and rod start at
//   150 and -75 rad/s, which leave P's y still at t = 0.
//
//   Lagrange's equations M(q) q'' + F_gyr(q, q') + F_int(q) = p with
//     T = 1/2 (J1 + m1 l1^2 / 4) theta1'^2 + 1/2 m2 |r2'|^2 + 1/2 J2 theta2'^2
//         + 1/2 m3 |P'|^2 + 1/2 J3 theta3'^2,  r2 = B + l2/2 u(theta2)
//     V = g ((m1/2 + m2 + m3) l1 sin theta1 + (m2/2 + m3) l2 sin theta2)
//   so M = [[J1 + (m1/4 + m2 + m3) l1^2, K cos(theta1 - theta2), 0],
//           [K cos(theta1 - theta2), J2 + (m2/4 + m3) l2^2, 0], [0, 0, J3]],
//   K = (m2/2 + m3) l1 l2, F_gyr = K sin(theta1 - theta2) (theta2'^2,
//   -theta1'^2, 0) and F_int = dV/dq (gravity along -y).
//
//   The guide: no bilateral constraint; the slider's corners i = 1..4 at
//   (sx a, sy b) in its frame (1: (-a, b), 2: (a, b), 3: (-a, -b), 4: (a, -b))
//   stay between the walls y = +-(b + c): a gap g_N,i = (b + c) - sy y_i >= 0
//   each (y_i the corner's world y), its tangential coordinate the corner's
//   world x, Newton's impact law e_N = 0.4 and Coulomb's friction mu = 0.01
//   (NewtonImpactFrictionNSL, a 2-D friction contact problem).
//
// The scheme as the example's: MoreauJeanCombinedProjectionOSI(theta 0.5),
// TimeSteppingCombinedProjection with FrictionContact(2, the enumerative
// 2-D solver) for the impacts and MLCPProjectOnConstraints for the
// positions, h = 1e-4 s to 0.2 s. The 35 columns as the example writes them
// (time, crank revolutions, angles, rates, the corners' normalised y, the
// slider's normalised x and y, the gaps, their rates, the impulses of the
// velocity and position problems, the iteration counters).
//
// Oracle: the example's .ref, 2001 rows of 35 columns, read from the
// folder argv[1] (meson passes external/siconos_slider_crank in the clone,
// else ../shared/siconos beside it; $FOURBAR_SICONOS_REF_DIR overrides it): no value of it is in this
// repository. Absent: skipped (exit 77), never passed. Every column must
// agree to REF_TOL over every row; the column, row and values of the
// first departure are printed otherwise. With -o FILE the reproduction's
// rows are written to FILE (docs/models.md's figure). The last line is
// "N passed, M failed".
#include "SiconosKernel.hpp"
#include "SolverOptions.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

// the bound: every column of every row within 1e-8 of the .ref
// (the example checks itself to 1e-10 absolute, over all columns: Siconos's
// ioMatrix::compareRefFile). Absolute for columns whose values are O(1) or
// below; relative to the value where it is larger (the angular rates reach
// 150 rad/s, the unilateral violation's "none" marker is 1e24)
const double REF_TOL = 1e-8;
// meson's exit code for a skipped test
const int EXIT_SKIP = 77;
const char *REF_NAME = "SliderCrankMoreauJeanCombinedProjectionOSI.ref";

// Table 1 of Flores, Leine and Glocker (2010) as the example's SCConst.h
// gives it [m, kg, kg m^2, m/s^2]
const double L1 = 0.1530, L2 = 0.3060;      // crank, rod
const double A_HALF = 0.05, B_HALF = 0.025; // slider half-length a, half-height b
const double C_GAP = 0.001;                 // clearance c, each side
const double M1 = 0.038, M2 = 0.038, M3 = 0.076;
const double J1 = 7.4e-5, J2 = 5.9e-4, J3 = 2.7e-6;
const double GRAV = 9.81;
// the example's contact law, start and scheme
const double E_N = 0.4, MU = 0.01;
const double OMEGA1_0 = 150.0, OMEGA2_0 = -75.0; // [rad/s]
const double THETA = 0.5, H = 1e-4, T_END = 0.2;
// the step run: H, or -h STEP's (then the rows are written with -o and not
// compared: docs/models.md's study of the scheme's step error)
double g_step = H;
// the friction coefficient run: MU, or -mu VALUE's (rows written, not compared)
double g_mu = MU;
const double FRICTION_TOL = 1e-8;
const int FRICTION_MAX_ITER = 100;
const unsigned PROJECTION_MAX_ITER = 500;
const double CONSTRAINT_TOL = 1e-10;
const unsigned N_COLS = 35;

// K = (m2/2 + m3) l1 l2: the crank-rod coupling of the mass matrix
double coupling() { return (0.5 * M2 + M3) * L1 * L2; }

// ---- the Lagrangian's terms, in LagrangianDS's function signatures
// (column-major matrices) ----

void mass(unsigned, double *q, double *m, unsigned, double *) {
  const double k = coupling() * std::cos(q[0] - q[1]);
  m[0] = J1 + (0.25 * M1 + M2 + M3) * L1 * L1;
  m[1] = k;
  m[2] = 0.0;
  m[3] = k;
  m[4] = J2 + (0.25 * M2 + M3) * L2 * L2;
  m[5] = 0.0;
  m[6] = 0.0;
  m[7] = 0.0;
  m[8] = J3;
}

void f_gyr(unsigned, double *q, double *v, double *f, unsigned, double *) {
  const double ks = coupling() * std::sin(q[0] - q[1]);
  f[0] = ks * v[1] * v[1];
  f[1] = -ks * v[0] * v[0];
  f[2] = 0.0;
}

void f_gyr_dq(unsigned, double *q, double *v, double *j, unsigned, double *) {
  const double kc = coupling() * std::cos(q[0] - q[1]);
  for (int i = 0; i < 9; i++) j[i] = 0.0;
  j[0] = kc * v[1] * v[1];  // d f0 / d theta1
  j[1] = -kc * v[0] * v[0]; // d f1 / d theta1
  j[3] = -kc * v[1] * v[1]; // d f0 / d theta2
  j[4] = kc * v[0] * v[0];  // d f1 / d theta2
}

void f_gyr_dv(unsigned, double *q, double *v, double *j, unsigned, double *) {
  const double ks = coupling() * std::sin(q[0] - q[1]);
  for (int i = 0; i < 9; i++) j[i] = 0.0;
  j[1] = -2.0 * ks * v[0]; // d f1 / d theta1'
  j[3] = 2.0 * ks * v[1];  // d f0 / d theta2'
}

// gravity's generalised force dV/dq
void f_int(double, unsigned, double *q, double *, double *f, unsigned, double *) {
  f[0] = (0.5 * M1 + M2 + M3) * GRAV * L1 * std::cos(q[0]);
  f[1] = (0.5 * M2 + M3) * GRAV * L2 * std::cos(q[1]);
  f[2] = 0.0;
}

void f_int_dq(double, unsigned, double *q, double *, double *j, unsigned, double *) {
  for (int i = 0; i < 9; i++) j[i] = 0.0;
  j[0] = -(0.5 * M1 + M2 + M3) * GRAV * L1 * std::sin(q[0]);
  j[4] = -(0.5 * M2 + M3) * GRAV * L2 * std::sin(q[1]);
}

void f_int_dv(double, unsigned, double *, double *, double *j, unsigned, double *) {
  for (int i = 0; i < 9; i++) j[i] = 0.0;
}

// ---- a corner against its wall ----

// Corner (sx a, sy b) of the slider: its world position and d/dq of it
struct Corner {
  double sx, sy; // +-1: which end (x), which face and wall (y)
  void at(const double *q, double p[2], double dx[3], double dy[3]) const {
    const double s1 = std::sin(q[0]), c1 = std::cos(q[0]);
    const double s2 = std::sin(q[1]), c2 = std::cos(q[1]);
    const double s3 = std::sin(q[2]), c3 = std::cos(q[2]);
    const double ax = sx * A_HALF, by = sy * B_HALF;
    p[0] = L1 * c1 + L2 * c2 + ax * c3 - by * s3;
    p[1] = L1 * s1 + L2 * s2 + ax * s3 + by * c3;
    dx[0] = -L1 * s1;
    dx[1] = -L2 * s2;
    dx[2] = -ax * s3 - by * c3;
    dy[0] = L1 * c1;
    dy[1] = L2 * c2;
    dy[2] = ax * c3 - by * s3;
  }
};

// The corner's relation: y = (g_N, x) with g_N = (b + c) - sy y_corner, its
// Jacobian rows d g_N / dq and d x / dq (a scleronomous relation: no time)
class CornerR : public LagrangianScleronomousR {
 public:
  explicit CornerR(Corner k) : k_(k) {}
  void computeh(const BlockVector &q, BlockVector &, SiconosVector &y) override {
    double qq[3], p[2], dx[3], dy[3];
    for (int i = 0; i < 3; i++) qq[i] = q.getValue(i);
    k_.at(qq, p, dx, dy);
    y.setValue(0, (B_HALF + C_GAP) - k_.sy * p[1]);
    if (y.size() > 1) y.setValue(1, p[0]);
  }
  void computeJachq(const BlockVector &q, BlockVector &) override {
    double qq[3], p[2], dx[3], dy[3];
    for (int i = 0; i < 3; i++) qq[i] = q.getValue(i);
    k_.at(qq, p, dx, dy);
    for (unsigned j = 0; j < 3; j++) {
      _jachq->setValue(0, j, -k_.sy * dy[j]);
      if (_jachq->size(0) > 1) _jachq->setValue(1, j, dx[j]);
    }
  }

 private:
  Corner k_;
};

// A numerics solver's options owned by the problem, freed whole (Siconos
// 4.4's solver_options_delete leaves the struct itself: siconos_scene.cpp)
SP::SolverOptions solver_options(int id) {
  SolverOptions *o = solver_options_create(id);
  return SP::SolverOptions(o, [](SolverOptions *p) {
    solver_options_delete(p);
    std::free(p);
  });
}

// ---- the run ----

typedef std::vector<double> Row;

struct Model {
  SP::LagrangianDS ds;
  SP::Interaction inter[4];
  SP::NonSmoothDynamicalSystem nsds;
  SP::TimeSteppingCombinedProjection sim;
  SP::MoreauJeanCombinedProjectionOSI osi;
  SP::OneStepNSProblem impact, position;
};

void build(Model &m) {
  SP::SiconosVector q0(new SiconosVector(3)), v0(new SiconosVector(3));
  q0->zero();
  v0->zero();
  v0->setValue(0, OMEGA1_0);
  v0->setValue(1, OMEGA2_0);
  m.ds.reset(new LagrangianDS(q0, v0));
  m.ds->setComputeMassFunction(mass);
  m.ds->setComputeFGyrFunction(f_gyr);
  m.ds->setComputeJacobianFGyrqFunction(f_gyr_dq);
  m.ds->setComputeJacobianFGyrqDotFunction(f_gyr_dv);
  m.ds->setComputeFIntFunction(f_int);
  m.ds->setComputeJacobianFIntqFunction(f_int_dq);
  m.ds->setComputeJacobianFIntqDotFunction(f_int_dv);
  m.nsds.reset(new NonSmoothDynamicalSystem(0.0, T_END));
  m.nsds->insertDynamicalSystem(m.ds);
  const Corner corners[4] = {{-1, 1}, {1, 1}, {-1, -1}, {1, -1}};
  for (int i = 0; i < 4; i++) {
    SP::NonSmoothLaw law(new NewtonImpactFrictionNSL(E_N, 0.0, g_mu, 2));
    SP::Relation rel(new CornerR(corners[i]));
    m.inter[i].reset(new Interaction(law, rel));
    m.nsds->link(m.inter[i], m.ds);
  }
  m.osi.reset(new MoreauJeanCombinedProjectionOSI(THETA));
  SP::TimeDiscretisation td(new TimeDiscretisation(0.0, g_step));
  SP::SolverOptions opts = solver_options(SICONOS_FRICTION_2D_ENUM);
  opts->dparam[SICONOS_DPARAM_TOL] = FRICTION_TOL;
  opts->iparam[SICONOS_IPARAM_MAX_ITER] = FRICTION_MAX_ITER;
  opts->iparam[2] = 1; // as the example sets it
  m.impact.reset(new FrictionContact(2, opts));
  m.position.reset(new MLCPProjectOnConstraints());
  m.sim.reset(new TimeSteppingCombinedProjection(m.nsds, td, m.osi, m.impact, m.position, 2));
  m.sim->setProjectionMaxIteration(PROJECTION_MAX_ITER);
  m.sim->setConstraintTolUnilateral(CONSTRAINT_TOL);
  m.sim->setConstraintTol(CONSTRAINT_TOL);
}

// the example's 35 columns at time t
Row sample(Model &m, double t, bool first) {
  const SiconosVector &q = *m.ds->q(), &v = *m.ds->velocity();
  const double qq[3] = {q.getValue(0), q.getValue(1), q.getValue(2)};
  Row r(N_COLS, 0.0);
  r[0] = t;
  r[1] = qq[0] / (2.0 * M_PI);
  for (int i = 0; i < 3; i++) {
    if (i > 0) r[1 + i] = qq[i];
    r[4 + i] = v.getValue(i);
  }
  // each corner's y displacement from its centred place, over c (the
  // lower corners' sign turned: towards their wall positive)
  const Corner corners[4] = {{-1, 1}, {1, 1}, {-1, -1}, {1, -1}};
  for (int i = 0; i < 4; i++) {
    double p[2], dx[3], dy[3];
    corners[i].at(qq, p, dx, dy);
    r[7 + i] = corners[i].sy * (p[1] - corners[i].sy * B_HALF) / C_GAP;
  }
  const double px = L1 * std::cos(qq[0]) + L2 * std::cos(qq[1]);
  const double py = L1 * std::sin(qq[0]) + L2 * std::sin(qq[1]);
  r[11] = (px - L2) / L1;
  r[12] = py / C_GAP;
  for (int i = 0; i < 4; i++) {
    r[13 + i] = m.inter[i]->y(0)->getValue(0);
    r[17 + i] = m.inter[i]->y(1)->getValue(0);
    r[21 + i] = m.inter[i]->lambda(1)->getValue(0);
    r[25 + i] = m.inter[i]->lambda(0)->getValue(0);
  }
  if (first) {
    r[29] = 1.0;
    return r;
  }
  TimeSteppingCombinedProjection &s = *m.sim;
  r[29] = s.getNewtonNbIterations();
  r[30] = s.nbProjectionIteration();
  r[31] = s.maxViolationUnilateral();
  r[32] = s.nbIndexSetsIteration();
  r[33] = s.cumulatedNewtonNbIterations();
  r[34] = s.nbCumulatedProjectionIteration();
  return r;
}

std::vector<Row> run(Model &m) {
  std::vector<Row> rows;
  for (int i = 0; i < 4; i++) m.inter[i]->computeOutput(0.0, 0);
  rows.push_back(sample(m, m.nsds->t0(), true));
  while (m.sim->hasNextEvent()) {
    m.sim->advanceToEvent();
    rows.push_back(sample(m, m.sim->nextTime(), false));
    m.sim->processEvents();
  }
  return rows;
}

// the .ref: a line "rows cols", then the rows
bool read_ref(const std::string &path, std::vector<Row> &rows) {
  FILE *fp = std::fopen(path.c_str(), "r");
  if (!fp) return false;
  unsigned nr = 0, nc = 0;
  bool ok = std::fscanf(fp, "%u %u", &nr, &nc) == 2 && nc == N_COLS;
  for (unsigned i = 0; ok && i < nr; i++) {
    Row r(nc);
    for (unsigned j = 0; ok && j < nc; j++) ok = std::fscanf(fp, "%lf", &r[j]) == 1;
    rows.push_back(r);
  }
  std::fclose(fp);
  return ok;
}

const char *COL_NAME[N_COLS] = {
    "time", "crank_rev", "rod_angle", "slider_tilt", "crank_omega", "rod_omega",
    "slider_omega", "y1/c", "y2/c", "y3/c", "y4/c", "x_slider/l1", "y_slider/c", "g1", "g2",
    "g3", "g4", "g1'", "g2'", "g3'", "g4'", "impulse1", "impulse2", "impulse3", "impulse4",
    "proj_impulse1", "proj_impulse2", "proj_impulse3", "proj_impulse4", "newton_iter",
    "proj_iter", "max_violation", "index_set_iter", "newton_iter_cum", "proj_iter_cum"};

void write_rows(const char *path, const std::vector<Row> &rows) {
  FILE *fp = std::fopen(path, "w");
  if (!fp) {
    std::printf("cannot write %s\n", path);
    return;
  }
  for (const Row &r : rows) {
    for (unsigned j = 0; j < r.size(); j++) std::fprintf(fp, "%s%.16e", j ? " " : "", r[j]);
    std::fputc('\n', fp);
  }
  std::fclose(fp);
}

} // namespace

int main(int argc, char **argv) {
  const char *env = std::getenv("FOURBAR_SICONOS_REF_DIR");
  const char *out = NULL;
  const char *dir = NULL;
  for (int i = 1; i < argc; i++) {
    if (std::strcmp(argv[i], "-o") == 0 && i + 1 < argc)
      out = argv[++i];
    else if (std::strcmp(argv[i], "-h") == 0 && i + 1 < argc)
      g_step = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "-mu") == 0 && i + 1 < argc)
      g_mu = std::atof(argv[++i]);
    else
      dir = argv[i];
  }
  if (env && *env) dir = env;
  std::vector<Row> ref;
  const std::string path = dir ? std::string(dir) + "/" + REF_NAME : std::string(REF_NAME);
  if (!dir || !read_ref(path, ref)) {
    std::printf("SKIP: no readable %s (the steering folder's siconos_slider_crank/, or "
                "$FOURBAR_SICONOS_REF_DIR; docs/models.md says where to fetch it)\n",
                path.c_str());
    if (!out) return EXIT_SKIP;
  }
  Model m;
  std::vector<Row> rows;
  try {
    build(m);
    rows = run(m);
  } catch (...) {
    Siconos::exception::process();
    std::printf("FAIL: Siconos threw\n0 passed, 1 failed\n");
    return 1;
  }
  if (out) write_rows(out, rows);
  if (ref.empty() || g_step != H || g_mu != MU) return EXIT_SKIP;
  int passed = 0, failed = 0;
  if (rows.size() != ref.size()) {
    std::printf("FAIL: %zu rows, the .ref has %zu\n", rows.size(), ref.size());
    failed++;
  }
  const size_t n = rows.size() < ref.size() ? rows.size() : ref.size();
  for (unsigned j = 0; j < N_COLS; j++) {
    double worst = 0.0;
    long first = -1;
    for (size_t i = 0; i < n; i++) {
      const double d = std::fabs(rows[i][j] - ref[i][j]);
      const double bound = REF_TOL * std::fmax(1.0, std::fabs(ref[i][j]));
      if (d > worst) worst = d;
      if (!(d <= bound) && first < 0) first = (long)i;
    }
    if (first < 0) {
      passed++;
      if (std::getenv("FB_TEST_VERBOSE"))
        std::printf("ok   column %2u %-15s max |diff| %.3e\n", j + 1, COL_NAME[j], worst);
    } else {
      failed++;
      std::printf("FAIL column %2u %-15s max |diff| %.3e; first beyond %.0e at row %ld "
                  "(t = %.4f s): ours %.16e, .ref %.16e\n",
                  j + 1, COL_NAME[j], worst, REF_TOL, first, ref[first][0], rows[first][j],
                  ref[first][j]);
    }
  }
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
