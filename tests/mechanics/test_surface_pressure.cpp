// The pressure load of the mesh scene (physics/mechanics/surface_pressure.hpp) on one face of a
// single 10-node tetrahedron: its resultant against the pressure times the area vector, on the
// undeformed face and, for the follower load, on the face deformed by an affine map F (Nanson:
// n da = J F⁻ᵀ N dA); and its Newton matrix against central differences of the residual on a
// randomly curved face.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include <petscmat.h>

#include "physics/mechanics/surface_pressure.hpp"

namespace needlefem::mechanics::testing {
namespace {

constexpr double kEdge = 1e-3;        // m
constexpr double kPressure = 250.0;   // Pa

// The tet with corners 0, e_x, e_y, e_z (times kEdge) and straight edges; its face on z = 0,
// outward normal -z, as the surface "bottom" (TRI6: corners 0, 2, 1, then edges (0,2) (2,1) (1,0)).
TetMesh one_tet() {
  TetMesh mesh;
  const std::array<Point3, 4> corner{{{0, 0, 0}, {kEdge, 0, 0}, {0, kEdge, 0}, {0, 0, kEdge}}};
  mesh.nodes.assign(corner.begin(), corner.end());
  const std::array<std::array<int, 2>, 6> edges{{{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};
  for (const auto& [a, b] : edges)
    mesh.nodes.push_back({0.5 * (corner[a][0] + corner[b][0]), 0.5 * (corner[a][1] + corner[b][1]),
                          0.5 * (corner[a][2] + corner[b][2])});
  mesh.tet_nodes = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  mesh.tet_region = {0};
  mesh.region_names = {"tissue"};
  mesh.surface_faces["bottom"] = {0, 2, 1, 6, 5, 4};
  return mesh;
}

// Force on the tissue, -Σ_a r_a, at displacements u.
Point3 force_on_tissue(const SurfacePressure& load, const DofMap& dofs, const std::vector<double>& u) {
  std::vector<double> residual(u.size(), 0.0);
  load.add_residual(0.0, u.data(), u.data(), dofs, residual.data());
  Point3 force{};
  for (std::size_t i = 0; i < residual.size(); ++i) force[i % 3] -= residual[i];
  return force;
}

TEST(SurfacePressure, ResultantIsThePressureTimesTheAreaVectorUndeformedAndUnderAnAffineMap) {
  const TetMesh mesh = one_tet();
  const DofMap dofs = tissue_dof_map(mesh);
  const auto pressure = [](double) { return kPressure; };
  const SurfacePressure follower(mesh, {"bottom"}, pressure, true), dead(mesh, {"bottom"}, pressure, false);
  const double area = 0.5 * kEdge * kEdge;
  std::vector<double> u(static_cast<std::size_t>(dofs.dof_count), 0.0);
  for (const SurfacePressure* load : {&follower, &dead}) {
    const Point3 f = force_on_tissue(*load, dofs, u);  // t = -p n, n = -e_z
    EXPECT_NEAR(f[0], 0.0, 1e-15);
    EXPECT_NEAR(f[1], 0.0, 1e-15);
    EXPECT_NEAR(f[2], kPressure * area, 1e-12 * kPressure * area);
  }
  const std::array<double, 9> F{1.2, 0.1, 0.0, 0.0, 0.9, 0.05, 0.02, 0.0, 1.1};
  for (std::size_t node = 0; node < mesh.nodes.size(); ++node)
    for (int i = 0; i < 3; ++i) {
      double x = 0.0;
      for (int j = 0; j < 3; ++j) x += F[3 * i + j] * mesh.nodes[node][j];
      u[dofs.dof(static_cast<int>(node), i)] = x - mesh.nodes[node][i];
    }
  // J F⁻ᵀ N with N = -e_z: minus the third column of the cofactor matrix J F⁻ᵀ.
  const Point3 cofactor_z{F[3] * F[7] - F[4] * F[6], F[1] * F[6] - F[0] * F[7], F[0] * F[4] - F[1] * F[3]};
  const Point3 moved = force_on_tissue(follower, dofs, u), unmoved = force_on_tissue(dead, dofs, u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(moved[i], kPressure * area * cofactor_z[i], 1e-12 * kPressure * area) << "component " << i;
    EXPECT_NEAR(unmoved[i], i == 2 ? kPressure * area : 0.0, 1e-12 * kPressure * area) << "component " << i;
  }
}

TEST(SurfacePressure, FollowerNewtonMatrixMatchesCentralDifferencesOnACurvedFace) {
  const TetMesh mesh = one_tet();
  const DofMap dofs = tissue_dof_map(mesh);
  const SurfacePressure load(mesh, {"bottom"}, [](double) { return kPressure; }, true);
  const int n = dofs.dof_count;
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> uniform(-0.1 * kEdge, 0.1 * kEdge);
  std::vector<double> u(n), direction(n);
  for (auto& value : u) value = uniform(generator);  // moves the mid-side nodes off the straight edges
  for (auto& value : direction) value = uniform(generator);

  Mat jacobian = nullptr;
  ASSERT_EQ(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, n, nullptr, &jacobian), 0);
  ASSERT_EQ(MatSetBlockSize(jacobian, 3), 0);
  load.add_jacobian(0.0, u.data(), u.data(), 0.0, dofs, jacobian, NewtonMatrix::exact);
  ASSERT_EQ(MatAssemblyBegin(jacobian, MAT_FINAL_ASSEMBLY), 0);
  ASSERT_EQ(MatAssemblyEnd(jacobian, MAT_FINAL_ASSEMBLY), 0);
  Vec d = nullptr, product = nullptr;
  VecCreateSeq(PETSC_COMM_SELF, n, &d);
  VecDuplicate(d, &product);
  for (int i = 0; i < n; ++i) VecSetValue(d, i, direction[i], INSERT_VALUES);
  VecAssemblyBegin(d);
  VecAssemblyEnd(d);
  MatMult(jacobian, d, product);

  const double h = 1e-4;  // the residual is a polynomial of degree 2 in u: central differences are exact
  std::vector<double> plus(u), minus(u), r_plus(n, 0.0), r_minus(n, 0.0);
  for (int i = 0; i < n; ++i) plus[i] += h * direction[i], minus[i] -= h * direction[i];
  load.add_residual(0.0, plus.data(), plus.data(), dofs, r_plus.data());
  load.add_residual(0.0, minus.data(), minus.data(), dofs, r_minus.data());
  const PetscScalar* exact = nullptr;
  VecGetArrayRead(product, &exact);
  double largest = 0.0, error = 0.0;
  for (int i = 0; i < n; ++i) {
    const double difference = (r_plus[i] - r_minus[i]) / (2.0 * h);
    largest = std::max(largest, std::abs(difference));
    error = std::max(error, std::abs(exact[i] - difference));
  }
  VecRestoreArrayRead(product, &exact);
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(error, 1e-9 * largest) << "largest entry " << largest;
  VecDestroy(&d);
  VecDestroy(&product);
  MatDestroy(&jacobian);
}

}  // namespace
}  // namespace needlefem::mechanics::testing
