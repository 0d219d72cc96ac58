// The contact Newton-matrix terms of one curved TRI6 face against central finite differences of
// its residual, separately in positions (∂r/∂x) and velocities (∂r/∂v, the c_j part): a
// frictional sphere (curvature terms) and a moving frictional plane (obstacle velocity), for
// both friction laws. The return map's anchors sit where the face points were at t = 0, so the
// jittered points at t stick or slip depending on how far the obstacle and the jitter moved them;
// the test checks both branches occur and that the law has no velocity block. Last, the Newton
// matrix GMRES is preconditioned with (NewtonMatrix::symmetric_preconditioner):
// positive semidefinite where the exact one is indefinite, with the same residual.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "physics/contact/penalty_contact.hpp"
#include "structured_block.hpp"

namespace needlefem::contact::testing {
namespace {

struct FdErrors {
  double position = 0.0, velocity = 0.0;  // max |J - J_fd| / max |J|
  double contact_area = 0.0;
  double slipping_area = 0.0;
  double velocity_block = 0.0;  // max |c_j ∂r/∂v| at c_j = 1
};

// Positions of a face's nodes jittered by ±20 µm about the mesh's and velocities of ±0.1 mm/s.
void jittered_face_state(const TetMesh& mesh, const PenaltyContact& contact, std::size_t face, std::mt19937& generator,
                         std::vector<double>& x, std::vector<double>& v) {
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  const int m = contact.nodes_per_face();
  x.resize(3 * m);
  v.resize(3 * m);
  for (int a = 0; a < m; ++a)
    for (int c = 0; c < 3; ++c) {
      x[3 * a + c] = mesh.nodes[contact.face_nodes(face)[a]][c] + 2e-5 * jitter(generator);
      v[3 * a + c] = 1e-4 * jitter(generator);
    }
}

// A 1 mm block's top face; the contact surface is "z_max". Its faces are perturbed so points
// penetrate the obstacle by various depths and slide in various directions.
FdErrors compare_with_finite_differences(std::shared_ptr<const RigidObstacle> obstacle, double t, FrictionLaw law,
                                         double rate_strengthening = 0.0) {
  const TetMesh mesh = structured_block({0.0, 1e-3}, {0.0, 1e-3}, {0.0, 1e-3});
  ContactParameters parameters;
  parameters.reference_modulus = 1000.0;
  parameters.slip_velocity_regularisation = 2e-5;
  parameters.friction_law = law;
  parameters.friction_tangent = FrictionTangent::consistent;
  // Return map: an elastic slip s0 of 5 µm (0.005 of the 1 mm faces), so that the tangential slips
  // the ±20 µm node jitter below gives the quadrature points fall on both sides of 2 s0: some stick
  // on the falling stick stiffness, some slide.
  parameters.elastic_slip = 0.005;
  parameters.rate_strengthening = rate_strengthening;
  const PenaltyContact contact(mesh, "z_max", obstacle, parameters);
  EXPECT_EQ(contact.face_count(), 2u);
  std::mt19937 generator(7);
  FdErrors errors;
  for (std::size_t face = 0; face < contact.face_count(); ++face) {
    const int n = 3 * contact.nodes_per_face();
    std::vector<double> x, v;
    jittered_face_state(mesh, contact, face, generator, x, v);
    const double cj = 1.0;  // the velocity part checked on its own below
    const FaceTerms exact_x = contact.face_terms(face, x.data(), v.data(), t, 0.0, true);
    const FaceTerms with_v = contact.face_terms(face, x.data(), v.data(), t, cj, true);
    errors.contact_area += exact_x.contact_area;
    errors.slipping_area += exact_x.slipping_area;
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
    // The return map has no velocity block: there the error is absolute, and must be 0.
    errors.velocity = std::max(errors.velocity, largest_v > 0.0 ? error_v / largest_v : error_v);
    errors.velocity_block = std::max(errors.velocity_block, largest_v);
  }
  std::printf("contact Jacobian vs central differences (%s law): position %.2e, velocity %.2e (relative to max "
              "entry); contact area %.3e m^2, of which slipping %.3e\n",
              law == FrictionLaw::return_map ? "return-map" : "velocity", errors.position, errors.velocity,
              errors.contact_area, errors.slipping_area);
  return errors;
}

std::shared_ptr<const RigidObstacle> pressed_sphere() {
  // Ball of radius 2 mm pressed 30 µm into the top face near one corner, moving sideways.
  return std::make_shared<TranslatingSphere>(Point3{0.3e-3, 0.4e-3, 3e-3 - 30e-6}, 2e-3, Point3{2e-4, -1e-4, 0});
}

std::shared_ptr<const RigidObstacle> tilted_moving_plane() {
  return std::make_shared<TranslatingPlane>(Point3{0, 0, 1e-3 + 5e-6}, Point3{0.1, -0.2, -1.0},
                                            Point3{3e-4, 1e-4, -2e-5});
}

TEST(ContactJacobian, VelocityLawSphereMatchesFiniteDifferences) {
  const FdErrors errors = compare_with_finite_differences(pressed_sphere(), 0.0, FrictionLaw::velocity);
  EXPECT_GT(errors.contact_area, 0.0);
  EXPECT_LT(errors.position, 1e-6);
  EXPECT_LT(errors.velocity, 1e-6);
}

TEST(ContactJacobian, VelocityLawMovingPlaneMatchesFiniteDifferences) {
  const FdErrors errors = compare_with_finite_differences(tilted_moving_plane(), 0.5, FrictionLaw::velocity);
  EXPECT_GT(errors.contact_area, 0.0);
  EXPECT_LT(errors.position, 1e-6);
  EXPECT_LT(errors.velocity, 1e-6);
}

// At t = 0 the anchors are where the points were, so the jitter alone loads them: some stick,
// some slip.
TEST(ContactJacobian, ReturnMapSphereSticksAndSlipsAndMatchesFiniteDifferences) {
  const FdErrors errors = compare_with_finite_differences(pressed_sphere(), 0.0, FrictionLaw::return_map);
  EXPECT_GT(errors.slipping_area, 0.0);
  EXPECT_LT(errors.slipping_area, errors.contact_area);
  EXPECT_LT(errors.position, 1e-6);
  EXPECT_EQ(errors.velocity_block, 0.0);
  EXPECT_EQ(errors.velocity, 0.0);
}

// By t = 0.5 s the plane has carried the anchors 0.16 mm away: every point slips.
TEST(ContactJacobian, ReturnMapMovingPlaneSlipsAndMatchesFiniteDifferences) {
  const FdErrors errors = compare_with_finite_differences(tilted_moving_plane(), 0.5, FrictionLaw::return_map);
  EXPECT_GT(errors.contact_area, 0.0);
  EXPECT_EQ(errors.slipping_area, errors.contact_area);
  EXPECT_LT(errors.position, 1e-6);
  EXPECT_EQ(errors.velocity_block, 0.0);
}

// With rate strengthening (-β p v_T added to the Coulomb traction) the return map gains a velocity
// block and a position part through P(x), w(x) and p(x): both against central differences.
TEST(ContactJacobian, ReturnMapWithRateStrengtheningMatchesFiniteDifferences) {
  for (const auto& [obstacle, t] : {std::pair{pressed_sphere(), 0.0}, std::pair{tilted_moving_plane(), 0.5}}) {
    const FdErrors errors = compare_with_finite_differences(obstacle, t, FrictionLaw::return_map, 5.0);
    EXPECT_GT(errors.contact_area, 0.0);
    EXPECT_GT(errors.velocity_block, 0.0);
    EXPECT_LT(errors.position, 1e-6);
    EXPECT_LT(errors.velocity, 1e-6);
  }
}

extern "C" void dsyev_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w,
                       double* work, const int* lwork, int* info);

// Smallest and largest eigenvalue of the symmetric part of an n x n row-major matrix (LAPACK).
std::pair<double, double> symmetric_part_eigenvalue_range(const std::vector<double>& matrix, int n) {
  std::vector<double> sym(matrix.size()), eigenvalues(n), work(static_cast<std::size_t>(34 * n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sym[i * n + j] = 0.5 * (matrix[i * n + j] + matrix[j * n + i]);
  const int lwork = static_cast<int>(work.size());
  int info = 0;
  dsyev_("N", "U", &n, sym.data(), &n, eigenvalues.data(), work.data(), &lwork, &info);
  EXPECT_EQ(info, 0);
  return {eigenvalues.front(), eigenvalues.back()};
}

// Every point of the face slides on the flat translating plane (no curvature, no rotation): the
// exact Newton matrix's symmetric part is indefinite through the unsymmetric μ p' ĝ nᵀ coupling
// (the slip direction has no stiffness), which defeats a Cholesky factor; without the coupling
// the matrix is a sum of positive semidefinite point terms. The residual does not change.
TEST(ContactJacobian, PreconditioningMatrixWithoutPressureCouplingIsSemidefiniteWhereTheExactOneIsNot) {
  const TetMesh mesh = structured_block({0.0, 1e-3}, {0.0, 1e-3}, {0.0, 1e-3});
  ContactParameters parameters;
  parameters.reference_modulus = 1000.0;
  parameters.elastic_slip = 0.008;
  parameters.rate_strengthening = 5.0;
  const PenaltyContact contact(mesh, "z_max", tilted_moving_plane(), parameters);
  std::mt19937 generator(11);
  for (std::size_t face = 0; face < contact.face_count(); ++face) {
    const int n = 3 * contact.nodes_per_face();
    std::vector<double> x, v;
    jittered_face_state(mesh, contact, face, generator, x, v);
    const FaceTerms with_coupling = contact.face_terms(face, x.data(), v.data(), 0.5, 1.0, true);
    const FaceTerms without = contact.face_terms(face, x.data(), v.data(), 0.5, 1.0, true, {},
                                                 NewtonMatrix::symmetric_preconditioner);
    ASSERT_GT(with_coupling.contact_area, 0.0);
    EXPECT_EQ(with_coupling.slipping_area, with_coupling.contact_area);
    EXPECT_EQ(with_coupling.residual, without.residual);
    const auto [exact_min, exact_max] = symmetric_part_eigenvalue_range(with_coupling.jacobian, n);
    const auto [min, max] = symmetric_part_eigenvalue_range(without.jacobian, n);
    std::printf("face %zu, symmetric part's eigenvalues: exact [%.3e, %.3e], without coupling [%.3e, %.3e]\n", face,
                exact_min, exact_max, min, max);
    EXPECT_LT(exact_min, -1e-2 * exact_max);
    EXPECT_GT(min, -1e-12 * max);
  }
}

// depends_on_rates() tells the integrator whether the Newton matrix changes with c_j through the
// contact (DaeSystem::newton_matrix_serves): checked against the matrix itself, the difference of
// the face terms at c_j = 1 and c_j = 0 on sliding points, for each friction law.
TEST(ContactJacobian, RateDependenceIsReportedExactlyWhereTheMatrixHasAVelocityPart) {
  const TetMesh mesh = structured_block({0.0, 1e-3}, {0.0, 1e-3}, {0.0, 1e-3});
  struct Law {
    FrictionLaw law;
    double friction, rate_strengthening;
    bool depends;
  };
  for (const Law& law : {Law{FrictionLaw::return_map, 0.5, 0.0, false}, Law{FrictionLaw::return_map, 0.5, 2.0, true},
                         Law{FrictionLaw::velocity, 0.5, 0.0, true}, Law{FrictionLaw::velocity, 0.0, 0.0, false}}) {
    ContactParameters parameters;
    parameters.reference_modulus = 1000.0;
    parameters.elastic_slip = 0.008;
    parameters.friction_law = law.law;
    parameters.friction_coefficient = law.friction;
    parameters.rate_strengthening = law.rate_strengthening;
    const PenaltyContact contact(mesh, "z_max", tilted_moving_plane(), parameters);
    EXPECT_EQ(contact.depends_on_rates(), law.depends);
    std::mt19937 generator(5);
    double largest_rate_part = 0.0, largest_entry = 0.0;
    for (std::size_t face = 0; face < contact.face_count(); ++face) {
      std::vector<double> x, v;
      jittered_face_state(mesh, contact, face, generator, x, v);
      const FaceTerms with_rates = contact.face_terms(face, x.data(), v.data(), 0.5, 1.0, true);
      const FaceTerms without = contact.face_terms(face, x.data(), v.data(), 0.5, 0.0, true);
      ASSERT_GT(with_rates.contact_area, 0.0);
      for (std::size_t k = 0; k < without.jacobian.size(); ++k) {
        largest_rate_part = std::max(largest_rate_part, std::abs(with_rates.jacobian[k] - without.jacobian[k]));
        largest_entry = std::max(largest_entry, std::abs(without.jacobian[k]));
      }
    }
    std::printf("law %d, mu %.1f, beta %.1f: largest c_j part %.3e (largest entry %.3e)\n", static_cast<int>(law.law),
                law.friction, law.rate_strengthening, largest_rate_part, largest_entry);
    if (law.depends)
      EXPECT_GT(largest_rate_part, 0.0);
    else
      EXPECT_EQ(largest_rate_part, 0.0);
  }
}

}  // namespace
}  // namespace needlefem::contact::testing
