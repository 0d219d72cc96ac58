// Locking study and convergence under refinement on a bending problem.
//
// Beam 6 x 1 x 1 mm: x_min clamped, x_max guided (u_x = u_y = 0) and moved by u_z = γ x
// = 0.03 mm (block.applied_gradient with F_zx = γ = 0.005), other faces free: a clamped-guided
// beam in bending. Quantity: the transverse reaction on x_max. Elastic neo-Hookean tissue
// (C10 = 500 Pa, no Prony), K/mu from 10 to 1e6.
// For a beam in bending the exact reaction scales with Young's modulus E = 9 K mu/(3K + mu),
// which itself changes by 3.4 % between K/mu = 10 and incompressibility; the locking measure is
// therefore the reaction divided by E/(3 mu), normalised to its value at K/mu = 10. What remains
// for a locking-free element is the small physical effect of the clamps on lateral contraction
// (concentrated between K/mu = 10 and 100).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "block_cases.hpp"
#include "mechanics_fixtures.hpp"

namespace needlefem::mechanics::testing {
namespace {

constexpr double kMu = 1000.0;  // 2 C10
const std::string kBeamFaces = "x_min = \"fixed\"\nx_max = \"displacement\"\ny_min = \"free\"\ny_max = \"free\"\n"
                               "z_min = \"free\"\nz_max = \"free\"\n";
const std::string kBeamGradient = "[1, 0, 0, 0, 1, 0, 0.005, 0, 1]";

double beam_reaction(double bulk_ratio, int order, const std::string& formulation, double element_mm) {
  const std::string material = "preset = \"custom\"\nc10_instantaneous_pa = 500\nbulk_modulus_pa = " +
                               std::to_string(bulk_ratio * kMu) + "\n";
  Problem problem(block_case(kBeamFaces, kBeamGradient, material, element_mm, order, formulation, "[6.0, 1.0, 1.0]"));
  EXPECT_TRUE(problem.advance(0.0, 1e-6, 1));
  return problem.system->reaction_force(problem.y, "x_max")[2];
}

double youngs_modulus_ratio(double bulk_ratio) {  // E / (3 mu)
  return 9 * bulk_ratio / (3 * bulk_ratio + 1) / 3;
}

TEST(MechanicsLocking, MixedTet10DoesNotLockDisplacementElementsDo) {
  struct Element {
    int order;
    const char* formulation;
    const char* name;
  };
  const Element elements[] = {{1, "displacement", "TET4"},
                              {2, "displacement", "TET10 displacement"},
                              {2, "mixed", "TET10 mixed"}};
  const double ratios[] = {10, 1e2, 1e3, 1e4, 1e5, 1e6};
  std::printf("locking study: beam reaction / (E/3mu), relative to K/mu = 10 (element 0.5 mm)\n%-20s", "K/mu");
  for (double ratio : ratios) std::printf("%10.0e", ratio);
  std::printf("\n");
  for (const auto& element : elements) {
    std::printf("%-20s", element.name);
    double first = 0.0, second = 0.0, last = 0.0;
    for (double ratio : ratios) {
      const double normalised = beam_reaction(ratio, element.order, element.formulation, 0.5) / youngs_modulus_ratio(ratio);
      if (first == 0.0) first = normalised;
      if (ratio == 1e2) second = normalised;
      last = normalised;
      std::printf("%10.4f", normalised / first);
    }
    std::printf("\n");
    const double change = std::abs(last / first - 1);
    if (std::string(element.formulation) == "mixed") {
      EXPECT_LT(change, 0.02) << element.name;
      EXPECT_LT(std::abs(last / second - 1), 0.005) << element.name << " from K/mu = 100";
    } else {
      EXPECT_GT(change, element.order == 1 ? 1.0 : 0.05) << element.name << " should lock";
    }
  }
}

// Reference refinement: reaction of the near-incompressible beam (K/mu = 1e4) on meshes of
// 1, 0.5 and 0.25 mm; observed order p = log2(|R1 - R½| / |R½ - R¼|). The reaction converges
// like the energy, O(h^(2 λ)), limited here not by the quadratic element (h⁴ for smooth
// solutions) but by the stress singularities along the edges where the clamped ends meet the
// free faces (Williams-type exponent λ < 1): expect p between 1 and 2.
TEST(MechanicsConvergence, MixedTet10ReactionConvergesUnderRefinement) {
  const double coarse = beam_reaction(1e4, 2, "mixed", 1.0);
  const double medium = beam_reaction(1e4, 2, "mixed", 0.5);
  const double fine = beam_reaction(1e4, 2, "mixed", 0.25);
  const double rate = std::log2(std::abs(coarse - medium) / std::abs(medium - fine));
  std::printf("refinement, mixed TET10, K/mu = 1e4: R(1 mm) %.8e, R(0.5 mm) %.8e, R(0.25 mm) %.8e N; observed order %.2f\n",
              coarse, medium, fine, rate);
  EXPECT_GT(rate, 1.0);
  EXPECT_LT(rate, 2.5);
}

}  // namespace
}  // namespace needlefem::mechanics::testing
