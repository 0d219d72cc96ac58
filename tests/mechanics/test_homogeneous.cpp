// Homogeneous deformations of a meshed block against closed forms, and the patch test.
//
// Closed forms for the incompressible polynomial (N = 2) law, Miller's constants
// (C10 = C01 = 263 Pa, C20 = C02 = 491 Pa, C11 = 0; instantaneous response):
//   W1 = C10 + 2 C20 (I1 - 3) + C11 (I2 - 3),  W2 = C01 + C11 (I1 - 3) + 2 C02 (I2 - 3).
//   Uniaxial stretch λ, lateral λ^(-1/2): I1 = λ² + 2/λ, I2 = 2λ + 1/λ²,
//     nominal stress P11 = 2 (λ - λ⁻²)(W1 + W2/λ)          (Holzapfel 2000 §6.3, Ogden 1984).
//   Simple shear γ: I1 = I2 = 3 + γ²,  P12 = σ12 = 2γ (W1 + W2).
// The block is near-incompressible with the stated K = 1e9 Pa (K/mu0 ≈ 1e6), so the
// compressible solution differs from the closed form by O(mu/K) ≈ 1e-6 relative. The
// instantaneous response is reached by loading in 1 µs (Prony times 0.5 s and 50 s).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "block_cases.hpp"
#include "mechanics_fixtures.hpp"

namespace needlefem::mechanics::testing {
namespace {

constexpr double kC10 = 263.0, kC01 = 263.0, kC20 = 491.0, kC11 = 0.0, kC02 = 491.0;
const std::string kMiller = "preset = \"miller-brain\"\nbulk_modulus_pa = 1e9\n";
constexpr double kFaceArea = 1e-6;  // 1 mm x 1 mm block faces, m²

double w1(double i1, double i2) { return kC10 + 2 * kC20 * (i1 - 3) + kC11 * (i2 - 3); }
double w2(double i1, double i2) { return kC01 + kC11 * (i1 - 3) + 2 * kC02 * (i2 - 3); }

double uniaxial_nominal_stress(double stretch) {
  const double i1 = stretch * stretch + 2 / stretch, i2 = 2 * stretch + 1 / (stretch * stretch);
  return 2 * (stretch - 1 / (stretch * stretch)) * (w1(i1, i2) + w2(i1, i2) / stretch);
}

double shear_stress(double gamma) {
  const double i = 3 + gamma * gamma;
  return 2 * gamma * (w1(i, i) + w2(i, i));
}

std::string diagonal_gradient(double stretch) {
  return "[" + std::to_string(stretch) + ", 0, 0, 0, 1, 0, 0, 0, 1]";
}

TEST(MechanicsHomogeneous, UniaxialTensionAndCompressionMatchClosedForm) {
  for (const std::string formulation : {"mixed", "displacement"})
    for (double stretch : {0.7, 0.85, 1.2, 1.5}) {
      // Default block faces: rollers on x_min, y_min, z_min; x_max pulled; y_max, z_max free.
      Problem problem(block_case("", diagonal_gradient(stretch), kMiller, 0.5, 2, formulation));
      ASSERT_TRUE(problem.advance(0.0, 1e-6, 5));
      const double force = problem.system->reaction_force(problem.y, "x_max")[0];
      const double expected = uniaxial_nominal_stress(stretch) * kFaceArea;
      const double error = std::abs(force / expected - 1);
      std::printf("uniaxial %-12s stretch %.2f: reaction %.6e N, closed form %.6e N, rel. error %.2e\n",
                  formulation.c_str(), stretch, force, expected, error);
      EXPECT_LT(error, 1e-4);
    }
}

TEST(MechanicsHomogeneous, SimpleShearMatchesClosedForm) {
  for (double gamma : {0.3, 1.0}) {
    const std::string gradient = "[1, " + std::to_string(gamma) + ", 0, 0, 1, 0, 0, 0, 1]";
    Problem problem(block_case(kAllFacesDisplaced, gradient, kMiller));
    ASSERT_TRUE(problem.advance(0.0, 1e-6, 5));
    const double force = problem.system->reaction_force(problem.y, "y_max")[0];
    const double expected = shear_stress(gamma) * kFaceArea;
    const double error = std::abs(force / expected - 1);
    std::printf("simple shear gamma %.2f: reaction %.6e N, closed form %.6e N, rel. error %.2e\n", gamma, force,
                expected, error);
    EXPECT_LT(error, 1e-4);
  }
}

// Patch test: an affine displacement on the whole boundary of an unstructured mesh is
// reproduced exactly at every interior node (the element represents homogeneous states).
TEST(MechanicsHomogeneous, PatchTestReproducesAffineField) {
  const double F[9] = {1.1, 0.2, -0.05, 0.1, 0.95, 0.15, -0.1, 0.05, 1.05};
  const std::string gradient = "[1.1, 0.2, -0.05, 0.1, 0.95, 0.15, -0.1, 0.05, 1.05]";
  for (int order : {1, 2})
    for (const std::string formulation : {"mixed", "displacement"}) {
      Problem problem(block_case(kAllFacesDisplaced, gradient, kMiller, 0.3, order, formulation));
      ASSERT_TRUE(problem.advance(0.0, 1e-6, 3));
      const auto& mesh = problem.scene.mesh;
      double worst = 0.0;
      int interior = 0;
      std::vector<bool> prescribed(problem.system->displacement_dofs(), false);
      for (const auto& d : problem.system->conditions().dofs) prescribed[d.dof] = true;
      for (std::size_t node = 0; node < mesh.nodes.size(); ++node) {
        if (prescribed[problem.system->dof_map().dof(static_cast<int>(node), 0)]) continue;
        ++interior;
        for (int i = 0; i < 3; ++i) {
          double exact = 0.0;
          for (int J = 0; J < 3; ++J) exact += (F[3 * i + J] - (i == J)) * mesh.nodes[node][J];
          worst = std::max(worst, std::abs(problem.displacement(static_cast<int>(node), i) - exact));
        }
      }
      std::printf("patch test TET%d %-12s: %d interior nodes, max error %.2e m (field ~2e-4 m)\n", order == 2 ? 10 : 4,
                  formulation.c_str(), interior, worst);
      EXPECT_GT(interior, 0);
      EXPECT_LT(worst, 1e-12);
    }
}

// The mixed element's pressures are unknowns of the state with the equation p_e = U'(θ_e)
// (mechanics_system.hpp): under an affine field with a volume change every element has
// θ = det F, so every converged p_e is U'(det F) = K (det F - 1), here 1e9 Pa x 0.06.
TEST(MechanicsHomogeneous, ElementPressuresConvergeToTheVolumetricPressure) {
  const double F[9] = {1.1, 0.2, -0.05, 0.1, 0.95, 0.15, -0.1, 0.05, 1.05};
  const double det_f = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
                       F[2] * (F[3] * F[7] - F[4] * F[6]);
  const double expected = 1e9 * (det_f - 1.0);  // kMiller's bulk modulus
  Problem problem(block_case(kAllFacesDisplaced, "[1.1, 0.2, -0.05, 0.1, 0.95, 0.15, -0.1, 0.05, 1.05]", kMiller,
                             0.3, 2, "mixed"));
  ASSERT_TRUE(problem.advance(0.0, 1e-6, 3));
  const MechanicsSystem& system = *problem.system;
  ASSERT_EQ(system.pressure_dofs(), static_cast<PetscInt>(system.dof_map().tissue_tets.size()));
  const PetscScalar* y = nullptr;
  VecGetArrayRead(problem.y, &y);
  double worst = 0.0;
  for (PetscInt k = 0; k < system.pressure_dofs(); ++k)
    worst = std::max(worst, std::abs(y[system.pressure_offset() + k] / expected - 1.0));
  VecRestoreArrayRead(problem.y, &y);
  std::printf("element pressures: %d elements, expected %.6e Pa, largest relative error %.2e\n",
              static_cast<int>(system.pressure_dofs()), expected, worst);
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace needlefem::mechanics::testing
