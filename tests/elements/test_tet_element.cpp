// Element kernels: consistent tangent vs central finite differences of the residual, residual
// vs finite differences of the element energy, rigid-motion invariance.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "case/case.hpp"
#include "physics/elements/tet_element.hpp"
#include "physics/material/material.hpp"

namespace needlefem::elements {
namespace {

constexpr double kSize = 1e-3;  // element edge ~ 1 mm

// A curved element: unit-ish tetrahedron scaled to 1 mm with mid-edge nodes moved off the chords.
std::vector<double> element_coordinates(int nodes) {
  const std::vector<std::array<double, 3>> vertices{{0, 0, 0}, {1.1, 0.1, 0}, {0.2, 0.9, 0.1}, {0.1, 0.2, 1.2}};
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  std::vector<double> x;
  for (const auto& v : vertices)
    for (double c : v) x.push_back(c * kSize);
  if (nodes == 10)
    for (int e = 0; e < 6; ++e)
      for (int c = 0; c < 3; ++c)
        x.push_back(0.5 * (vertices[edges[e][0]][c] + vertices[edges[e][1]][c]) * kSize + 0.03 * kSize * ((e + c) % 3 - 1));
  return x;
}

material::Material tissue_material(double bulk_modulus_pa, bool viscous) {
  std::string toml = "[material]\npreset = \"custom\"\nc10_instantaneous_pa = 263\nc01_instantaneous_pa = 180\n"
                     "c20_instantaneous_pa = 491\nc11_instantaneous_pa = 120\nc02_instantaneous_pa = 300\n"
                     "bulk_modulus_pa = " + std::to_string(bulk_modulus_pa) + "\n";
  if (viscous) toml += "prony_g = [0.45, 0.365]\nprony_tau_s = [0.5, 50.0]\n";
  return material::material_from_spec(parse_material_spec(Case::parse(toml, "test")));
}

std::vector<double> random_values(std::size_t count, double amplitude, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
  std::vector<double> v(count);
  for (auto& x : v) x = uniform(generator);
  return v;
}

// ||K - K_fd||_F / ||K||_F with central differences of the residual.
double tangent_error(const TetElementKernel& kernel, const ElementGeometry& geometry, std::vector<double> u,
                     const ViscousStep* viscous) {
  const ElementResult at = kernel.evaluate(geometry, u.data(), viscous, true);
  EXPECT_FALSE(at.inverted);
  const int dofs = 3 * geometry.nodes;
  const double h = 1e-6 * kSize;
  double difference = 0.0, size = 0.0;
  for (int col = 0; col < dofs; ++col) {
    const double saved = u[col];
    u[col] = saved + h;
    const auto plus = kernel.evaluate(geometry, u.data(), viscous, false).residual;
    u[col] = saved - h;
    const auto minus = kernel.evaluate(geometry, u.data(), viscous, false).residual;
    u[col] = saved;
    for (int row = 0; row < dofs; ++row) {
      const double fd = (plus[row] - minus[row]) / (2 * h);
      const double exact = at.stiffness[static_cast<std::size_t>(row) * dofs + col];
      difference += (fd - exact) * (fd - exact);
      size += exact * exact;
    }
  }
  return std::sqrt(difference / size);
}

struct Variant {
  int nodes;
  Formulation formulation;
  const char* name;
};
const Variant kVariants[] = {{4, Formulation::displacement, "TET4"},
                             {10, Formulation::displacement, "TET10 displacement"},
                             {10, Formulation::mean_dilatation, "TET10 mean-dilatation"}};

TEST(TetElement, TangentMatchesFiniteDifferencesElasticAndViscous) {
  for (const auto& variant : kVariants) {
    const auto x = element_coordinates(variant.nodes);
    const ElementGeometry geometry = element_geometry(variant.nodes, x.data());
    const TetElementKernel kernel(tissue_material(1e5, true), variant.formulation);
    const auto u = random_values(3 * variant.nodes, 0.08 * kSize, 7);
    // A step of 0.2 s (elastic fraction 0.87) from histories of Q_i and S⁰ up to 150 Pa.
    const auto history = random_values(geometry.points * material::prony_history_size(kernel.prony().size()), 150.0, 11);
    const material::PronyStep step = material::prony_step(kernel.prony(), 0.2);
    const ViscousStep viscous_step{&step, history.data()};
    const double elastic = tangent_error(kernel, geometry, u, nullptr);
    const double viscous = tangent_error(kernel, geometry, u, &viscous_step);
    std::printf("%-24s tangent rel. error: elastic %.2e, viscous step %.2e\n", variant.name, elastic, viscous);
    EXPECT_LT(elastic, 1e-6) << variant.name;
    EXPECT_LT(viscous, 1e-6) << variant.name;
  }
}

TEST(TetElement, CorotationalLawTangentMatchesFiniteDifferences) {
  const auto material = material::material_from_spec(parse_material_spec(
      Case::parse("[material]\nmodel = \"corotational-linear\"\npoisson_ratio = 0.3\n", "test")));
  for (int nodes : {4, 10}) {
    const auto x = element_coordinates(nodes);
    const ElementGeometry geometry = element_geometry(nodes, x.data());
    const TetElementKernel kernel(material, Formulation::displacement);
    const double error = tangent_error(kernel, geometry, random_values(3 * nodes, 0.08 * kSize, 3), nullptr);
    std::printf("co-rotational TET%d tangent rel. error %.2e\n", nodes, error);
    EXPECT_LT(error, 1e-6);
  }
  EXPECT_THROW(TetElementKernel(material, Formulation::mean_dilatation), std::invalid_argument);
}

// With Q = 0 the residual is the gradient of the element energy (both formulations are
// energy-based), which checks the residual independently of the tangent.
TEST(TetElement, ResidualIsEnergyGradient) {
  for (const auto& variant : kVariants) {
    const auto x = element_coordinates(variant.nodes);
    const ElementGeometry geometry = element_geometry(variant.nodes, x.data());
    const TetElementKernel kernel(tissue_material(1e5, false), variant.formulation);
    auto u = random_values(3 * variant.nodes, 0.08 * kSize, 5);
    const auto residual = kernel.evaluate(geometry, u.data(), nullptr, false).residual;
    const double h = 1e-6 * kSize;
    double difference = 0.0, size = 0.0;
    for (std::size_t c = 0; c < u.size(); ++c) {
      const double saved = u[c];
      u[c] = saved + h;
      const double plus = kernel.evaluate(geometry, u.data(), nullptr, false).energy;
      u[c] = saved - h;
      const double minus = kernel.evaluate(geometry, u.data(), nullptr, false).energy;
      u[c] = saved;
      const double fd = (plus - minus) / (2 * h);
      difference += (fd - residual[c]) * (fd - residual[c]);
      size += residual[c] * residual[c];
    }
    EXPECT_LT(std::sqrt(difference / size), 1e-6) << variant.name;
  }
}

// A rigid rotation plus translation produces no internal force and keeps v_e = V_e.
TEST(TetElement, RigidMotionIsStressFree) {
  const double angle = 0.7, c = std::cos(angle), s = std::sin(angle);
  for (const auto& variant : kVariants) {
    const auto x = element_coordinates(variant.nodes);
    const ElementGeometry geometry = element_geometry(variant.nodes, x.data());
    const TetElementKernel kernel(tissue_material(1e7, false), variant.formulation);
    std::vector<double> u(x.size());
    for (int a = 0; a < variant.nodes; ++a) {
      const double* p = &x[3 * a];
      u[3 * a + 0] = c * p[0] - s * p[1] - p[0] + 2e-4;
      u[3 * a + 1] = s * p[0] + c * p[1] - p[1] - 1e-4;
      u[3 * a + 2] = 3e-4;
    }
    const ElementResult result = kernel.evaluate(geometry, u.data(), nullptr, false);
    double largest = 0.0;
    for (double r : result.residual) largest = std::max(largest, std::abs(r));
    // Force scale: mu * area = 1e3 Pa * 1e-6 m^2.
    EXPECT_LT(largest, 1e-12 * 1e-3) << variant.name;
  }
}

// TET4 has one point, so its mean dilatation equals the point's J: both forms coincide.
TEST(TetElement, MeanDilatationOnTet4IsTheDisplacementElement) {
  const auto x = element_coordinates(4);
  const ElementGeometry geometry = element_geometry(4, x.data());
  const auto material = tissue_material(1e6, false);
  const auto u = random_values(12, 0.05 * kSize, 9);
  const auto mixed = TetElementKernel(material, Formulation::mean_dilatation).evaluate(geometry, u.data(), nullptr, true);
  const auto plain = TetElementKernel(material, Formulation::displacement).evaluate(geometry, u.data(), nullptr, true);
  for (std::size_t c = 0; c < mixed.stiffness.size(); ++c)
    EXPECT_NEAR(mixed.stiffness[c], plain.stiffness[c], 1e-9 * std::abs(plain.stiffness[0]));
}

// The B-free products of the hot loops against products with the explicit B (6 x 30).
TEST(TetElement, GreenStrainProductsWithoutBMatchTheOperator) {
  const auto x = element_coordinates(10);
  const ElementGeometry geometry = element_geometry(10, x.data());
  const auto f = random_values(9, 0.4, 11), u = random_values(30, 1e-4, 12), stress = random_values(6, 500.0, 13);
  std::array<double, 9> F{};
  for (int k = 0; k < 9; ++k) F[k] = f[k] + (k % 4 == 0 ? 1.0 : 0.0);
  const std::array<double, kVoigt> s{stress[0], stress[1], stress[2], stress[3], stress[4], stress[5]};
  for (int q = 0; q < geometry.points; ++q) {
    std::vector<double> B(kVoigt * 30);
    green_strain_operator(F, geometry.gradient_at(q), 10, B.data());
    std::vector<double> work(30, 1.0), expected_work(30, 1.0);  // both add to a nonzero start
    add_green_strain_transpose(F, geometry.gradient_at(q), 10, s, 0.3, work.data());
    const auto strain = green_strain_variation(F, geometry.gradient_at(q), 10, u.data());
    for (int m = 0; m < kVoigt; ++m) {
      double expected_strain = 0.0;
      for (int c = 0; c < 30; ++c) {
        expected_strain += B[m * 30 + c] * u[c];
        expected_work[c] += 0.3 * B[m * 30 + c] * s[m];
      }
      EXPECT_NEAR(strain[m], expected_strain, 1e-12 * std::abs(expected_strain) + 1e-18) << "point " << q << " m " << m;
    }
    for (int c = 0; c < 30; ++c) EXPECT_NEAR(work[c], expected_work[c], 1e-12 * std::abs(expected_work[c])) << c;
  }
}

}  // namespace
}  // namespace needlefem::elements
