// Quadrature-point output quantities against closed forms: eigenvalues of a rotated diagonal
// tensor, incompressible uniaxial stretching (ln V = ln λ, D = λ'/λ, equivalent rate λ'/λ),
// rigid spin (no strain, no strain rate), von Mises and pressure of a uniaxial stress.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/fields/point_quantities.hpp"
#include "rotations.hpp"

namespace needlefem::fields {
namespace {

TEST(PointQuantities, EigenvaluesOfRotatedDiagonalTensors) {
  const Mat3d R = rotation_about(2, 0.7) * rotation_about(0, -1.1);
  for (const auto& d : {std::array<double, 3>{-2.0, 1.0, 3.0}, std::array<double, 3>{2.0, 2.0, 5.0},
                        std::array<double, 3>{-1e-3, 4.0, 4.0}, std::array<double, 3>{7.0, 7.0, 7.0}}) {
    const Mat3d A = R * Mat3d::diagonal(d[0], d[1], d[2]) * material::transpose(R);
    const auto eigenvalues = symmetric_eigenvalues(A);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(eigenvalues[i], d[i], 1e-7 * (1.0 + std::abs(d[i])));
  }
}

TEST(PointQuantities, IncompressibleUniaxialStretching) {
  const double stretch = 1.3, stretch_rate = 0.4;  // λ, λ' (1/s)
  const double lateral = 1.0 / std::sqrt(stretch);
  const Mat3d F = Mat3d::diagonal(stretch, lateral, lateral);
  const double lateral_rate = -0.5 * stretch_rate * std::pow(stretch, -1.5);
  const Mat3d F_rate = Mat3d::diagonal(stretch_rate, lateral_rate, lateral_rate);
  const Mat3d R = rotation_about(2, 0.3);  // a rigid rotation changes none of the invariants
  const PointQuantities q = point_quantities(R * F, R * F_rate, Mat3d{});
  EXPECT_NEAR(q.max_log_strain, std::log(stretch), 1e-14);
  EXPECT_NEAR(q.max_strain_rate, stretch_rate / stretch, 1e-14);
  EXPECT_NEAR(q.equivalent_strain_rate, stretch_rate / stretch, 1e-14);
}

TEST(PointQuantities, RigidSpinHasNoStrainAndNoStrainRate) {
  const double angle = 0.9, spin = 3.0;  // rad, rad/s
  const Mat3d F = rotation_about(2, angle);
  const Mat3d F_rate = spin * (rotation_about(2, angle + std::numbers::pi / 2) - Mat3d::diagonal(0, 0, 1));
  const PointQuantities q = point_quantities(F, F_rate, Mat3d{});
  EXPECT_NEAR(q.max_log_strain, 0.0, 1e-15);
  EXPECT_NEAR(q.max_strain_rate, 0.0, 1e-14);
  EXPECT_NEAR(q.equivalent_strain_rate, 0.0, 1e-14);
}

TEST(PointQuantities, UniaxialStressInvariants) {
  const double s = 1234.0;
  const Mat3d R = rotation_about(0, 0.4);
  const PointQuantities q = point_quantities(Mat3d::identity(), Mat3d{}, R * Mat3d::diagonal(s, 0, 0) * material::transpose(R));
  EXPECT_NEAR(q.von_mises, s, 1e-10 * s);
  EXPECT_NEAR(q.max_principal_stress, s, 1e-10 * s);
  EXPECT_NEAR(q.pressure, -s / 3.0, 1e-10 * s);
}

TEST(PointQuantities, PushForwardOfSecondPiolaKirchhoff) {
  // σ = J⁻¹ F S Fᵀ: for F = diag(2, 1, 1), S = diag(1, 0, 0) gives σ_xx = 4 / 2.
  const Mat3d sigma = push_forward(Mat3d::diagonal(2, 1, 1), Mat3d::diagonal(1, 0, 0));
  EXPECT_DOUBLE_EQ(sigma(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(sigma(1, 1), 0.0);
}

}  // namespace
}  // namespace needlefem::fields
