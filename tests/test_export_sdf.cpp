// fourbar export --format sdf: the exported world as a Gazebo user's
// libsdformat loads it (sdf::Root::Load from disk), for the paper case with
// its clearance joint and for the ideal mechanism: no error, the names the
// issue gives (links crank, coupler, follower, ground fixed; the joints;
// frames <joint>_pin and <joint>_hole), the case's masses, and each
// clearance joint's contact under surface/contact/ode with a spring Gazebo
// turns into a valid ODE row (h kp + kd > 0).
//
/*        coupler
 *     B o-------o C
 *      /         \   follower
 * crank           \
 *    /             \
 *  A o==== ground ==o D                                                    */
//
// Usage: test_export_sdf FOURBAR_BINARY CASE_FILE (tests/meson.build).
// C++ only because libsdformat is C++; the export itself is C
// (src/report/export_sdf.c).
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <sdf/sdf.hh>

extern char **environ;

// masses are written with %.17g: read back exactly up to the parse
static const double MASS_REL_TOL = 1e-12;
// the paper case's link masses (cases/paper_crank_rocker.ini, [mass])
static const double CRANK_KG = 0.12, COUPLER_KG = 0.29, FOLLOWER_KG = 0.28;

static int failures = 0;
#define CHECK(cond, ...)                                   \
  do {                                                     \
    if (!(cond)) {                                         \
      std::fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__); \
      std::fprintf(stderr, __VA_ARGS__);                   \
      std::fputc('\n', stderr);                            \
      failures++;                                          \
    }                                                      \
  } while (0)

// runs fourbar export CASE --format sdf [--ideal] --out path; its exit status
static int run_export(const char *bin, const char *cs, bool ideal, const std::string &path) {
  std::vector<std::string> args = {bin, "export", cs, "--format", "sdf", "--out", path};
  if (ideal) args.push_back("--ideal");
  std::vector<char *> argv;
  for (auto &a : args) argv.push_back(&a[0]);
  argv.push_back(nullptr);
  pid_t pid;
  if (posix_spawn(&pid, bin, nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static const sdf::Model *load(sdf::Root &root, const std::string &path) {
  const sdf::Errors errors = root.Load(path);
  for (const auto &e : errors) std::fprintf(stderr, "  sdformat: %s\n", e.Message().c_str());
  CHECK(errors.empty(), "%s: %zu errors from sdf::Root::Load", path.c_str(), errors.size());
  CHECK(root.WorldCount() == 1, "worlds: %lu", (unsigned long)root.WorldCount());
  if (root.WorldCount() != 1) return nullptr;
  const sdf::World *w = root.WorldByIndex(0);
  CHECK(w->PhysicsCount() >= 1 && w->PhysicsByIndex(0)->MaxStepSize() > 0.0,
        "the world has no physics with a positive step");
  const sdf::Model *m = w->ModelByName("fourbar");
  CHECK(m != nullptr, "no model \"fourbar\"");
  return m;
}

static void check_mechanism(const sdf::Model *m) {
  const char *links[] = {"ground", "crank", "coupler", "follower"};
  for (const char *l : links) CHECK(m->LinkNameExists(l), "no link %s", l);
  const struct {
    const char *name;
    double kg;
  } masses[] = {{"crank", CRANK_KG}, {"coupler", COUPLER_KG}, {"follower", FOLLOWER_KG}};
  for (const auto &x : masses) {
    const sdf::Link *l = m->LinkByName(x.name);
    if (!l) continue;
    const double got = l->Inertial().MassMatrix().Mass();
    CHECK(std::fabs(got - x.kg) <= MASS_REL_TOL * x.kg, "%s mass %.17g kg, case %.17g kg", x.name,
          got, x.kg);
  }
  // ground welded to the world
  const sdf::Joint *weld = m->JointByName("ground_weld");
  CHECK(weld && weld->Type() == sdf::JointType::FIXED && weld->ParentLinkName() == "world" &&
            weld->ChildLinkName() == "ground",
        "ground is not fixed to the world by joint ground_weld");
  const char *joints[] = {"ground-crank", "crank-coupler", "coupler-follower", "follower-ground"};
  const char *ends[] = {"pin", "hole"};
  for (const char *j : joints)
    for (const char *e : ends) {
      const std::string f = std::string(j) + "_" + e;
      CHECK(m->FrameNameExists(f), "no frame %s", f.c_str());
    }
}

int main(int argc, char **argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: test_export_sdf FOURBAR_BINARY CASE_FILE\n");
    return 2;
  }
  char dir[] = "/tmp/fourbar_export_sdf_XXXXXX";
  if (!mkdtemp(dir)) return 2;
  const std::string clearance = std::string(dir) + "/paper.sdf";
  const std::string ideal = std::string(dir) + "/paper_ideal.sdf";

  // the clearance export: crank-coupler as a contact, the other three revolute
  CHECK(run_export(argv[1], argv[2], false, clearance) == 0, "export --format sdf failed");
  {
    sdf::Root root;
    const sdf::Model *m = load(root, clearance);
    if (m) {
      check_mechanism(m);
      const double h = root.WorldByIndex(0)->PhysicsByIndex(0)->MaxStepSize();
      const char *revolute[] = {"ground-crank", "coupler-follower", "follower-ground"};
      for (const char *j : revolute) {
        const sdf::Joint *jt = m->JointByName(j);
        CHECK(jt && jt->Type() == sdf::JointType::REVOLUTE, "joint %s is not revolute", j);
      }
      CHECK(!m->JointNameExists("crank-coupler"), "the clearance joint is also a hinge");
      const sdf::Link *crank = m->LinkByName("crank");
      const sdf::Collision *pin = crank ? crank->CollisionByName("crank-coupler_pin") : nullptr;
      CHECK(pin != nullptr, "crank has no collision crank-coupler_pin");
      const sdf::Link *coupler = m->LinkByName("coupler");
      CHECK(coupler && coupler->CollisionByName("crank-coupler_hole_0"),
            "coupler has no collision crank-coupler_hole_0");
      if (pin) {
        sdf::ElementPtr ode =
            pin->Element()->GetElement("surface")->GetElement("contact")->GetElement("ode");
        const double kp = ode->Get<double>("kp"), kd = ode->Get<double>("kd");
        const double max_vel = ode->Get<double>("max_vel"), min_depth = ode->Get<double>("min_depth");
        std::fprintf(stderr, "  crank-coupler: kp %.6g N/m, kd %.6g N s/m, max_vel %.6g m/s, "
                     "h %.6g s\n", kp, kd, max_vel, h);
        CHECK(std::isfinite(kp) && kp > 0.0, "kp = %g", kp);
        CHECK(std::isfinite(kd) && h * kp + kd > 0.0, "h kp + kd = %g: no ODE row", h * kp + kd);
        CHECK(std::isfinite(max_vel) && max_vel > 0.0, "max_vel = %g", max_vel);
        CHECK(min_depth == 0.0, "min_depth = %g (the exact mapping needs 0)", min_depth);
        CHECK(!ode->HasElement("soft_erp") && !ode->HasElement("soft_cfm"),
              "soft_erp/soft_cfm written (Gazebo Classic ignores them)");
      }
    }
  }

  // the ideal export: four revolute joints, the loop closed by the fourth
  CHECK(run_export(argv[1], argv[2], true, ideal) == 0, "export --format sdf --ideal failed");
  {
    sdf::Root root;
    const sdf::Model *m = load(root, ideal);
    if (m) {
      check_mechanism(m);
      const char *revolute[] = {"ground-crank", "crank-coupler", "coupler-follower",
                                "follower-ground"};
      for (const char *j : revolute) {
        const sdf::Joint *jt = m->JointByName(j);
        CHECK(jt && jt->Type() == sdf::JointType::REVOLUTE, "joint %s is not revolute", j);
      }
    }
  }
  std::remove(clearance.c_str());
  std::remove(ideal.c_str());
  rmdir(dir);
  if (failures) std::fprintf(stderr, "%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
