// Taylor test of the global Newton matrix J = ∂F/∂y + cj ∂F/∂y' at the end of a viscous step
// from non-zero histories, with the mixed element's pressures and their element-wise
// condensation: for dy = J⁻¹ b,
//   ||F(y + h dy, y' + cj h dy) - F(y, y') - h b|| = O(h²).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "block_cases.hpp"
#include "mechanics_fixtures.hpp"

namespace needlefem::mechanics::testing {
namespace {

void fill_random(Vec v, double amplitude, PetscInt begin, PetscInt end, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
  PetscScalar* values = nullptr;
  VecGetArray(v, &values);
  for (PetscInt i = begin; i < end; ++i) values[i] = uniform(generator);
  VecRestoreArray(v, &values);
}

double taylor_slope(const std::string& formulation, int order) {
  // Uniaxial block (default faces): a mix of prescribed and free dofs.
  Problem problem(block_case("", "[1.2, 0, 0, 0, 1, 0, 0, 0, 1]",
                             "preset = \"miller-brain\"\nbulk_modulus_pa = 1e5\n", 0.5, order, formulation));
  MechanicsSystem& system = *problem.system;
  const PetscInt nu = system.displacement_dofs(), n = system.local_size();
  EXPECT_GT(system.viscous_history_size(), 0u);
  EXPECT_EQ(system.pressure_dofs() > 0, formulation == "mixed");
  // Histories from an accepted step at 0.1 s, then a step of 0.2 s (elastic fraction 0.87: the
  // viscous and elastic parts both matter) to another state.
  const double t = 0.3, cj = 4.0;
  fill_random(problem.y, 2e-5, 0, nu, 6);
  system.accept_step(0.1, problem.y, problem.ydot);
  fill_random(problem.y, 2e-5, 0, nu, 1);      // displacements up to 20 µm on a 1 mm block
  fill_random(problem.y, 300.0, nu, n, 2);     // the element pressures up to 300 Pa
  fill_random(problem.ydot, 1e-4, 0, n, 3);
  Vec b, dy, base, shifted_y, shifted_ydot, value;
  VecDuplicate(problem.y, &b);
  VecDuplicate(b, &dy);
  VecDuplicate(b, &base);
  VecDuplicate(b, &shifted_y);
  VecDuplicate(b, &shifted_ydot);
  VecDuplicate(b, &value);
  VecSet(b, 0.0);
  fill_random(b, 1e-3, 0, nu, 4);
  fill_random(b, 100.0, nu, n, 5);
  EXPECT_EQ(system.residual(t, problem.y, problem.ydot, base), DaeStatus::ok);
  EXPECT_EQ(system.setup_jacobian(t, problem.y, problem.ydot, cj), DaeStatus::ok);
  EXPECT_EQ(system.solve_jacobian(b, dy), DaeStatus::ok);
  // Scale so that h = 1 moves displacements by ~50 µm (strains of order 0.1).
  double largest = 0.0;
  {
    const PetscScalar* d = nullptr;
    VecGetArrayRead(dy, &d);
    for (PetscInt i = 0; i < nu; ++i) largest = std::max(largest, std::abs(d[i]));
    VecRestoreArrayRead(dy, &d);
  }
  const double scale = 5e-5 / largest;
  std::vector<double> hs, errors;
  for (double h = 1.0; h > 1e-3; h /= 2.0) {
    const double step = h * scale;
    VecWAXPY(shifted_y, step, dy, problem.y);
    VecWAXPY(shifted_ydot, cj * step, dy, problem.ydot);
    EXPECT_EQ(system.residual(t, shifted_y, shifted_ydot, value), DaeStatus::ok);
    VecAXPY(value, -1.0, base);
    VecAXPY(value, -step, b);
    double error = 0.0;
    VecNorm(value, NORM_2, &error);
    hs.push_back(step);
    errors.push_back(error);
  }
  // Least-squares slope of log(error) vs log(h) over the asymptotic range (small h, above round-off).
  double slope_sum = 0.0;
  int count = 0;
  for (std::size_t k = 3; k + 1 < hs.size(); ++k) {
    slope_sum += std::log(errors[k] / errors[k + 1]) / std::log(hs[k] / hs[k + 1]);
    ++count;
  }
  for (Vec* v : {&b, &dy, &base, &shifted_y, &shifted_ydot, &value}) VecDestroy(v);
  return slope_sum / count;
}

// With no contact, the Newton matrix changes with the step only through the Prony step's elastic
// fraction a(Δt) = 1 - Σ g_i (1 - h_i), h_i = (1 - exp(-Δt/τ_i)) τ_i/Δt, asked at Δt = 1/c_j
// (IDA's first, order-1 step), and serves where a changes by less than 1e-3. Miller's brain
// (g = 0.450, 0.365; τ = 0.5, 50 s): a(1e-8 s) = 1 - 4.5e-9; a(1e-5 s) = 1 - 4.5e-6 (the probe
// step's matrix serves IDA's first step); a(2 ms) = 1 - 9.06e-4, just within; a(4 ms) =
// 1 - 1.80e-3 and a(0.5 s) = 0.833, outside.
TEST(MechanicsJacobian, NewtonMatrixServesAnotherCjWhereThePronyFactorStays) {
  Problem problem(block_case("", "[1.2, 0, 0, 0, 1, 0, 0, 0, 1]", "preset = \"miller-brain\"\n", 0.5, 2, "mixed"));
  const MechanicsSystem& system = *problem.system;
  EXPECT_TRUE(system.newton_matrix_serves(1e8, 1e5));
  EXPECT_TRUE(system.newton_matrix_serves(1e5, 1e8));
  EXPECT_TRUE(system.newton_matrix_serves(1e8, 500.0));
  EXPECT_FALSE(system.newton_matrix_serves(1e8, 250.0));
  EXPECT_FALSE(system.newton_matrix_serves(1e8, 2.0));
}

// Where the factor only preconditions (integration.newton = "krylov", the default) it is single
// precision, until IDA keeps failing: the third setup without an accepted step between goes to
// MUMPS's double-precision LU, and the next accepted step brings the single-precision one back.
TEST(MechanicsJacobian, SinglePrecisionFactorGivesWayToDoubleWhenStepsKeepFailing) {
  Problem problem(block_case("", "[1.2, 0, 0, 0, 1, 0, 0, 0, 1]", "preset = \"miller-brain\"\n", 0.5, 2, "mixed"),
                  {"integration.newton=krylov"});
  MechanicsSystem& system = *problem.system;
  const double t = 1e-3, cj = 1e3;
  for (int setup = 1; setup <= 4; ++setup)
    ASSERT_EQ(system.setup_jacobian(t, problem.y, problem.ydot, cj), DaeStatus::ok);
  EXPECT_EQ(system.factorisations().cholesky, 2);
  EXPECT_EQ(system.factorisations().ksp, 2);
  system.accept_step(t, problem.y, problem.ydot);
  ASSERT_EQ(system.setup_jacobian(t, problem.y, problem.ydot, cj), DaeStatus::ok);
  EXPECT_EQ(system.factorisations().cholesky, 3);
  EXPECT_EQ(system.factorisations().ksp, 2);
}

TEST(MechanicsJacobian, TaylorSlopeIsTwoAfterAViscousStepMixedTet10) {
  const double slope = taylor_slope("mixed", 2);
  std::printf("Taylor slope, mixed TET10 after a viscous step: %.4f\n", slope);
  EXPECT_NEAR(slope, 2.0, 0.1);
}

TEST(MechanicsJacobian, TaylorSlopeIsTwoAfterAViscousStepDisplacementTet10) {
  const double slope = taylor_slope("displacement", 2);
  std::printf("Taylor slope, displacement TET10 after a viscous step: %.4f\n", slope);
  EXPECT_NEAR(slope, 2.0, 0.1);
}

TEST(MechanicsJacobian, TaylorSlopeIsTwoAfterAViscousStepTet4) {
  const double slope = taylor_slope("displacement", 1);
  std::printf("Taylor slope, TET4 after a viscous step: %.4f\n", slope);
  EXPECT_NEAR(slope, 2.0, 0.1);
}

}  // namespace
}  // namespace needlefem::mechanics::testing
