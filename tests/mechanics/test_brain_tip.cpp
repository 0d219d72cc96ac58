// Brain-tip scene (paper 001 cube, coarse mesh) under IDA with contact.mode = "tied": the cavity
// nodes follow the needle's rigid motion, and the tissue is in global equilibrium (reaction on
// the skull faces balances the force the needle exerts: their sum vanishes relative to either).
// Reactions are the forces the supports exert on the tissue. (Frictional contact, the default:
// tests/run.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "integration/ida_integrator.hpp"
#include "mechanics_fixtures.hpp"

namespace needlefem::mechanics::testing {
namespace {

TEST(MechanicsBrainTip, CavityFollowsNeedleAndTissueIsInEquilibrium) {
  Problem problem(
      "[tissue]\ncore_element_mm = 1.5\nouter_element_mm = 3.0\n[needle]\nradius_mm = 0.5\nbevel_deg = 20\n"
      "fillet_mm = 0.25\n[motion]\ninsertion_speed_mm_per_s = 1.0\n"
      "rotation_speed_deg_per_s = 180\nduration_s = 0.1\n[contact]\nmode = \"tied\"\n");
  IdaOptions options;
  options.relative_tolerance = 1e-5;
  options.absolute_tolerance = 1e-12;
  options.suppress_algebraic_error = true;
  IdaIntegrator integrator(*problem.system, options, 0.0, PETSC_COMM_SELF);
  const double t = 0.01;
  integrator.advance_to(t);

  // Rigid motion of the cavity: rotation π t about z and 1 mm/s t along +z.
  const auto& mesh = problem.scene.mesh;
  const double angle = std::numbers::pi * t, c = std::cos(angle), s = std::sin(angle);
  double worst = 0.0;
  Vec saved = problem.y;
  problem.y = integrator.state();
  for (int node : mesh.surface_faces.at("cavity")) {
    const auto& X = mesh.nodes[node];
    const double expected[3] = {c * X[0] - s * X[1] - X[0], s * X[0] + c * X[1] - X[1], 1e-3 * t};
    for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(problem.displacement(node, i) - expected[i]));
  }
  problem.y = saved;
  EXPECT_LT(worst, 1e-15);

  const Point3 needle = problem.system->reaction_force(integrator.state(), "cavity");
  const Point3 skull = problem.system->reaction_force(integrator.state(), "fixed");
  const Point3 entry = problem.system->reaction_force(integrator.state(), "entry");
  const double needle_size = std::hypot(needle[0], needle[1], needle[2]);
  std::printf("brain tip t = %.2f s: cavity force (%.3e, %.3e, %.3e) N, skull (%.3e, %.3e, %.3e) N, "
              "entry face (free) (%.1e, %.1e, %.1e) N\n",
              t, needle[0], needle[1], needle[2], skull[0], skull[1], skull[2], entry[0], entry[1], entry[2]);
  EXPECT_GT(needle_size, 0.0);
  EXPECT_GT(needle[2], 0.0);  // the needle pushes the tissue along +z
  // Free nodes are in equilibrium to IDA's Newton tolerance (rtol 1e-5), not to round-off.
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(needle[i] + skull[i]), 1e-4 * needle_size);
  const auto counters = integrator.counters();
  std::printf("IDA: %ld steps, %ld Newton iterations, %ld Jacobian setups, %d dofs\n", counters.steps,
              counters.newton_iterations, counters.jacobian_setups, static_cast<int>(problem.system->local_size()));
}

}  // namespace
}  // namespace needlefem::mechanics::testing
