// The deformable-needle check's solver (physics/contact/needle_elasticity.hpp) on a slender steel
// bar clamped at z = 0 and loaded by a uniform transverse traction on its free end: the end's
// mean deflection against Timoshenko's cantilever,
//   δ = F L³/(3 E I) + F L/(κ G A),   I = b h³/12,  κ = 10(1+ν)/(12+11ν) (rectangle, Cowper 1966),
// within 2 % (the clamp also holds the root's Poisson contraction and warping, which stiffens the
// 3-D bar by O(h/L) of the shear part; measured below). Also: ½ fᵀu = ½ F δ̄ for this load, and
// the result is linear in the load.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics/contact/needle_elasticity.hpp"
#include "structured_block.hpp"

namespace needlefem::contact::testing {
namespace {

constexpr double kWidth = 0.5e-3, kLength = 5e-3, kYoungs = 200e9, kPoisson = 0.29, kForce = 1e-3;

std::vector<double> uniform(double length, int cells) {
  std::vector<double> x;
  for (int i = 0; i <= cells; ++i) x.push_back(length * i / cells);
  return x;
}

// Consistent nodal forces of a uniform traction on TRI6 faces: corners 0, edge nodes A/3 each.
std::vector<Point3> end_load(const TetMesh& mesh, double force_x) {
  const auto& faces = mesh.surface_faces.at("z_max");
  std::vector<Point3> forces(mesh.nodes.size(), Point3{});
  const double traction = force_x / (kWidth * kWidth);
  for (std::size_t f = 0; f < faces.size(); f += 6) {
    const Point3 &a = mesh.nodes[faces[f]], &b = mesh.nodes[faces[f + 1]], &c = mesh.nodes[faces[f + 2]];
    const double area = 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    for (int k = 3; k < 6; ++k) forces[faces[f + k]][0] += traction * area / 3.0;
  }
  return forces;
}

TEST(NeedleElasticity, ClampedBarDeflectsAsTimoshenkosCantilever) {
  TetMesh mesh = structured_block(uniform(kWidth, 4), uniform(kWidth, 4), uniform(kLength, 40));
  mesh.region_names = {"needle"};
  mesh.surface_faces["needle_rear"] = mesh.surface_faces.at("z_min");
  const NeedleElasticity needle(mesh, kYoungs, kPoisson);
  EXPECT_EQ(needle.dofs(), 3 * mesh.nodes.size());

  const auto forces = end_load(mesh, kForce);
  const NeedleElasticity::Deflection deflection = needle.deflection(forces);
  // Mean end deflection from the energy: ½ fᵀu = ½ F δ̄ for a uniform traction.
  const double mean_end = 2.0 * deflection.elastic_energy_j / kForce;
  const double inertia = std::pow(kWidth, 4) / 12.0, area = kWidth * kWidth;
  const double shear_modulus = kYoungs / (2.0 * (1.0 + kPoisson));
  const double kappa = 10.0 * (1.0 + kPoisson) / (12.0 + 11.0 * kPoisson);
  const double bending = kForce * std::pow(kLength, 3) / (3.0 * kYoungs * inertia);
  const double shear = kForce * kLength / (kappa * shear_modulus * area);
  const double timoshenko = bending + shear;
  std::printf("end deflection %.6e m (largest %.6e m at z = %.3f mm), Timoshenko %.6e m (shear part %.2f %%): "
              "%+.3f %%\n",
              mean_end, deflection.max_m, deflection.where[2] * 1e3, timoshenko, 100.0 * shear / timoshenko,
              100.0 * (mean_end / timoshenko - 1.0));
  EXPECT_NEAR(mean_end / timoshenko, 1.0, 0.02);
  EXPECT_NEAR(deflection.where[2], kLength, 1e-12);  // the largest deflection is at the free end
  EXPECT_GT(deflection.max_m, mean_end);             // the corners bend a little more than the mean

  std::vector<Point3> doubled = forces;
  for (auto& f : doubled)
    for (double& c : f) c *= 2.0;
  EXPECT_NEAR(needle.deflection(doubled).max_m / deflection.max_m, 2.0, 1e-9);
}

TEST(NeedleElasticity, MissingNeedleRegionOrRearFaceIsAClearError) {
  TetMesh mesh = structured_block(uniform(kWidth, 1), uniform(kWidth, 1), uniform(kLength, 2));
  EXPECT_THROW(NeedleElasticity(mesh, kYoungs, kPoisson), std::runtime_error);  // region "tissue" only
  mesh.region_names = {"needle"};
  EXPECT_THROW(NeedleElasticity(mesh, kYoungs, kPoisson), std::runtime_error);  // no needle_rear
  mesh.surface_faces["needle_rear"] = mesh.surface_faces.at("z_min");
  EXPECT_THROW(NeedleElasticity(mesh, kYoungs, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace needlefem::contact::testing
