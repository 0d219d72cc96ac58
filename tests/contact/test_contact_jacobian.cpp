// The contact Newton-matrix terms of one curved TRI6 face against central finite differences of
// its residual, separately in positions (∂r/∂x) and velocities (∂r/∂v, the c_j part): a
// frictional sphere (curvature terms) and a moving frictional plane (obstacle velocity).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "physics/contact/penalty_contact.hpp"
#include "structured_block.hpp"

namespace needlefem::contact::testing {
namespace {

struct FdErrors {
  double position = 0.0, velocity = 0.0;  // max |J - J_fd| / max |J|
  double contact_area = 0.0;
};

// A 1 mm block's top face; the contact surface is "z_max". Its faces are perturbed so points
// penetrate the obstacle by various depths and slide in various directions.
FdErrors compare_with_finite_differences(std::shared_ptr<const RigidObstacle> obstacle, double t) {
  const TetMesh mesh = structured_block({0.0, 1e-3}, {0.0, 1e-3}, {0.0, 1e-3});
  ContactParameters parameters;
  parameters.reference_modulus = 1000.0;
  parameters.slip_velocity_regularisation = 2e-5;
  parameters.friction_tangent = FrictionTangent::consistent;
  const PenaltyContact contact(mesh, "z_max", obstacle, parameters);
  EXPECT_EQ(contact.face_count(), 2u);
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  FdErrors errors;
  for (std::size_t face = 0; face < contact.face_count(); ++face) {
    const int m = contact.nodes_per_face(), n = 3 * m;
    std::vector<double> x(n), v(n);
    for (int a = 0; a < m; ++a)
      for (int c = 0; c < 3; ++c) {
        x[3 * a + c] = mesh.nodes[contact.face_nodes(face)[a]][c] + 2e-5 * jitter(generator);
        v[3 * a + c] = 1e-4 * jitter(generator);
      }
    const double cj = 1.0;  // the velocity part checked on its own below
    const FaceTerms exact_x = contact.face_terms(face, x.data(), v.data(), t, 0.0, true);
    const FaceTerms with_v = contact.face_terms(face, x.data(), v.data(), t, cj, true);
    errors.contact_area += exact_x.contact_area;
    double largest = 0.0, error_x = 0.0, error_v = 0.0;
    for (double value : exact_x.jacobian) largest = std::max(largest, std::abs(value));
    const double hx = 1e-9, hv = 1e-9;
    for (int col = 0; col < n; ++col) {
      std::vector<double> xp = x, xm = x, vp = v, vm = v;
      xp[col] += hx, xm[col] -= hx, vp[col] += hv, vm[col] -= hv;
      const auto rxp = contact.face_terms(face, xp.data(), v.data(), t, 0.0, false).residual;
      const auto rxm = contact.face_terms(face, xm.data(), v.data(), t, 0.0, false).residual;
      const auto rvp = contact.face_terms(face, x.data(), vp.data(), t, 0.0, false).residual;
      const auto rvm = contact.face_terms(face, x.data(), vm.data(), t, 0.0, false).residual;
      for (int row = 0; row < n; ++row) {
        const std::size_t k = static_cast<std::size_t>(row) * n + col;
        error_x = std::max(error_x, std::abs(exact_x.jacobian[k] - (rxp[row] - rxm[row]) / (2 * hx)));
        const double exact_v = (with_v.jacobian[k] - exact_x.jacobian[k]) / cj;
        error_v = std::max(error_v, std::abs(exact_v - (rvp[row] - rvm[row]) / (2 * hv)));
      }
    }
    // The velocity block carries 1/ε_v: compare it with its own scale.
    double largest_v = 0.0;
    for (std::size_t k = 0; k < with_v.jacobian.size(); ++k)
      largest_v = std::max(largest_v, std::abs(with_v.jacobian[k] - exact_x.jacobian[k]));
    errors.position = std::max(errors.position, error_x / largest);
    errors.velocity = std::max(errors.velocity, error_v / largest_v);
  }
  std::printf("contact Jacobian vs central differences: position %.2e, velocity %.2e (relative to max entry)\n",
              errors.position, errors.velocity);
  return errors;
}

TEST(ContactJacobian, FrictionalSphereMatchesFiniteDifferences) {
  // Ball of radius 2 mm pressed 30 µm into the top face near one corner, moving sideways.
  auto sphere = std::make_shared<TranslatingSphere>(Point3{0.3e-3, 0.4e-3, 3e-3 - 30e-6}, 2e-3, Point3{2e-4, -1e-4, 0});
  const FdErrors errors = compare_with_finite_differences(sphere, 0.0);
  EXPECT_GT(errors.contact_area, 0.0);
  EXPECT_LT(errors.position, 1e-6);
  EXPECT_LT(errors.velocity, 1e-6);
}

TEST(ContactJacobian, MovingFrictionalPlaneMatchesFiniteDifferences) {
  auto plane = std::make_shared<TranslatingPlane>(Point3{0, 0, 1e-3 + 5e-6}, Point3{0.1, -0.2, -1.0},
                                                  Point3{3e-4, 1e-4, -2e-5});
  const FdErrors errors = compare_with_finite_differences(plane, 0.5);
  EXPECT_GT(errors.contact_area, 0.0);
  EXPECT_LT(errors.position, 1e-6);
  EXPECT_LT(errors.velocity, 1e-6);
}

}  // namespace
}  // namespace needlefem::contact::testing
