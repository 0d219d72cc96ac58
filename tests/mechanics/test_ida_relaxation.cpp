// The mechanics system under the real integrator (IDA): ramp-and-hold relaxation of a block in
// uniaxial tension against the material-point Prony recursion (physics/material, exact for
// stress varying linearly over a step, run here with fine steps), within 0.5 % over 100 s.
// Block: rollers on x_min, y_min, z_min, x_max pulled to stretch 1.1 in 0.1 s, then held; the
// reaction over the undeformed face area is the nominal stress P11. K = 1e9 Pa (K/mu ≈ 1e6) so
// the block matches the reference's exact incompressibility to ~1e-6.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "block_cases.hpp"
#include "integration/ida_integrator.hpp"
#include "mechanics_fixtures.hpp"
#include "physics/material/material_point.hpp"

namespace needlefem::mechanics::testing {
namespace {

TEST(MechanicsIda, RampAndHoldRelaxationMatchesPronyRecursion) {
  const std::string toml =
      "[scene]\nkind = \"block\"\n[block]\nelement_mm = 0.5\napplied_gradient = [1.1, 0, 0, 0, 1, 0, 0, 0, 1]\n"
      "[loading]\nramp_s = 0.1\nhold_s = 100\n[material]\npreset = \"miller-brain\"\nbulk_modulus_pa = 1e9\n";
  Problem problem(toml);
  IdaOptions options;
  options.relative_tolerance = 1e-6;
  options.absolute_tolerance = 1e-12;
  options.suppress_algebraic_error = true;
  IdaIntegrator integrator(*problem.system, options, 0.0, PETSC_COMM_SELF);

  material::LoadProgram program;
  program.history = material::LoadHistory::Relaxation;
  program.target = 1.1;
  program.steps = 400;
  program.ramp_s = 0.1;
  program.hold_s = 100.0;
  const auto reference =
      material::run_material_point(material::material_from_spec(parse_material_spec(problem.input)), program);
  auto reference_at = [&](double t) {
    for (const auto& row : reference)
      if (std::abs(row.time_s - t) < 1e-9 * std::max(1.0, t)) return row.nominal_stress_pa;
    ADD_FAILURE() << "no reference row at t = " << t;
    return 0.0;
  };
  for (double t : {0.05, 0.1, 0.6, 5.0, 50.0, 100.0}) {
    integrator.advance_to(t);
    const double nominal = problem.system->reaction_force(integrator.state(), "x_max")[0] / 1e-6;
    const double expected = reference_at(t);
    const double error = std::abs(nominal / expected - 1);
    std::printf("relaxation t = %6.2f s: block %.6f Pa, Prony recursion %.6f Pa, rel. error %.2e\n", t, nominal,
                expected, error);
    EXPECT_LT(error, 5e-3);
  }
  const auto counters = integrator.counters();
  std::printf("IDA: %ld steps, %ld Newton iterations, %ld Jacobian setups\n", counters.steps, counters.newton_iterations,
              counters.jacobian_setups);
}

}  // namespace
}  // namespace needlefem::mechanics::testing
