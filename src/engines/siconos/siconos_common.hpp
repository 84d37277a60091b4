// What the Siconos scene (siconos_scene.cpp) and the Siconos binding of the
// engine kit (siconos_kit.cpp) share, private to this folder and included
// after SiconosKernel.hpp: numerics solver options without Siconos 4.4's
// leak, an MLCP one-step problem without its workspace growth, a Siconos
// exception's message, and the teardown that breaks the simulation's cycle
// of shared pointers.
#ifndef FB_SICONOS_COMMON_HPP
#define FB_SICONOS_COMMON_HPP

#include <cstdlib>
#include <exception>
#include <new>
#include <string>

namespace fb_siconos {

// A numerics solver's options, owned by the one-step problem. Built here,
// not by the problem's solver-id constructor: that one frees them with
// solver_options_delete, which in Siconos 4.4 frees what the struct holds
// but not the struct itself (its free is commented out), so each problem
// left 120 bytes behind (LeakSanitizer, tests/test_siconos.c)
inline SP::SolverOptions solver_options(int solver_id) {
  SolverOptions *o = solver_options_create(solver_id);
  if (!o) throw std::bad_alloc();
  return SP::SolverOptions(o, [](SolverOptions *p) {
    solver_options_delete(p);
    std::free(p);
  });
}

// An MLCP problem P (MLCP, MLCPProjectOnConstraints; the enumerative
// solver) without Siconos 4.4's growth per solve: MLCP::solve calls
// mlcp_driver_init before every solve, which callocs the solver's iWork and
// dWork again over the last ones (numerics/src/MLCP/mlcp_driver.c), and
// mlcp_driver_reset frees only the last. Freeing them before each solve
// changes nothing the solver sees (it gets freshly zeroed arrays either way).
// mlcp_enum's own EnumerationStruct, allocated each solve and never freed
// (mlcp_enum.c), is out of reach here (tests/lsan.supp). Build it from
// solver_options(SICONOS_MLCP_ENUM), as the solver-id constructor would,
// without its leaked struct.
template <class P>
class FreshWork : public P {
 public:
  using P::P;
  int compute(double time) override {
    SolverOptions &o = *this->numericsSolverOptions();
    std::free(o.iWork);
    std::free(o.dWork);
    o.iWork = nullptr;
    o.dWork = nullptr;
    o.iWorkSize = 0;
    o.dWorkSize = 0;
    return P::compute(time);
  }
};

// the message of a Siconos exception (its THROW_EXCEPTION text), else what()
inline std::string siconos_message(const std::exception &ex) {
  if (const boost::exception *be = dynamic_cast<const boost::exception *>(&ex))
    if (const std::string *msg = boost::get_error_info<Siconos::exception::extra_message>(*be))
      return *msg;
  return ex.what();
}

// The simulation and its integrator and one-step problems hold each other
// by shared pointers: Simulation::clear breaks that cycle (Siconos's own
// teardown), else the whole system outlives its owner. position may be null.
inline void teardown(const SP::Simulation &sim, const SP::OneStepIntegrator &osi,
                     const SP::OneStepNSProblem &osnspb, const SP::OneStepNSProblem &position,
                     const SP::NonSmoothDynamicalSystem &nsds) {
  sim->clear();
  osi->setSimulationPtr(SP::Simulation());
  osnspb->setSimulationPtr(SP::Simulation());
  if (position) position->setSimulationPtr(SP::Simulation());
  osi->setDynamicalSystemsGraph(SP::DynamicalSystemsGraph());
  nsds->clear();
}

// [siconos] scheme = combined-projection (TimeSteppingCombinedProjection):
// the index set whose interactions the positions' problem projects (the
// only level Siconos 4.4 implements: its constructor throws on another),
// the projection's iteration cap and its tolerance on each constraint's
// violation, |g| for a contact the step closed (projected as an equality,
// Siconos's default) and |h| for a loop closure [m]. Cap and tolerance are
// Siconos's slider-crank example's (a 1 mm clearance there); 1e-10 m is
// 7e-6 of the paper case's 14.5 um radial clearance. Each iteration is a
// Newton step on the linearised constraints: the tests' cases need 1 or 2
// (tests/test_siconos.c). At the cap Siconos 4.4 prints the violations on
// standard output and the step is refused (the model stops).
const unsigned kProjectionIndexSet = 2;
const unsigned kProjectionMaxIterations = 500;
const double kProjectionTolerance = 1e-10;

// The combined projection's position problem (MLCPProjectOnConstraints, the
// enumerative MLCP solver) without Siconos 4.4's growth per solve
inline SP::OneStepNSProblem projection_problem() {
  return SP::OneStepNSProblem(
      new FreshWork<MLCPProjectOnConstraints>(solver_options(SICONOS_MLCP_ENUM)));
}

// The combined projection's simulation of nsds with integrator osi, the
// velocity problem impact and the position problem position, its cap and
// tolerances (above)
inline SP::TimeSteppingCombinedProjection combined_projection(
    const SP::NonSmoothDynamicalSystem &nsds, const SP::TimeDiscretisation &td,
    const SP::OneStepIntegrator &osi, const SP::OneStepNSProblem &impact,
    const SP::OneStepNSProblem &position) {
  SP::TimeSteppingCombinedProjection p(
      new TimeSteppingCombinedProjection(nsds, td, osi, impact, position, kProjectionIndexSet));
  p->setProjectionMaxIteration(kProjectionMaxIterations);
  p->setConstraintTol(kProjectionTolerance);
  p->setConstraintTolUnilateral(kProjectionTolerance);
  return p;
}

} // namespace fb_siconos

#endif
