// The pointwise response the element kernel calls (point_response.hpp), law by law:
//  * its tangent against central differences of its own stress, along symmetric strain
//    directions dE (dF = F^-T dE gives dC = 2 dE to first order; the second-order part cancels
//    in a central difference), elastic and at the end of a viscous step (whose tangent is the
//    step's elastic fraction times the elastic one);
//  * a point's history, stepped by Simo's recursion through respond(), against the Prony
//    closed form of relaxation under a strain applied at t = 0 and held:
//    S_iso(t) = S⁰ (g∞ + Σ_i g_i e^(-t/τ_i)), which the recursion gives exactly at any step;
//  * its volumetric response against differences of U.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "material_test_support.hpp"
#include "physics/material/material.hpp"

namespace needlefem::material {
namespace {

PolynomialTissue full_polynomial() {
  PolynomialTissue tissue;  // every coefficient non-zero
  tissue.isochoric.elastic = {.c10 = 263.0, .c01 = 120.0, .c20 = 491.0, .c11 = 77.0, .c02 = 300.0};
  tissue.isochoric.terms = {{0.45, 0.5}, {0.365, 50.0}};
  tissue.volumetric.bulk_modulus = 5.0e3;
  return tissue;
}

// The symmetric direction of Voigt strain component n (engineering shear: E_kl = E_lk = 1/2).
Mat3d voigt_direction(int n) {
  Mat3d d;
  d(kVoigtRow[n], kVoigtColumn[n]) += n < 3 ? 1.0 : 0.5;
  if (n >= 3) d(kVoigtColumn[n], kVoigtRow[n]) += 0.5;
  return d;
}

// max |a D - D_fd| / max |a D| of a law's respond() at F with the viscous part `viscous` (a its
// elastic fraction, 1 without).
template <class Law>
double tangent_error(const Law& law, const Mat3d& F, const ViscousStress* viscous) {
  VoigtTangent D{};
  law.respond(F, viscous, &D);
  const double a = viscous ? viscous->elastic_fraction : 1.0;
  for (double& d : D) d *= a;
  const Mat3d F_inverse_transpose = transpose(inverse(F));
  const double h = 1e-6;
  double error = 0.0, size = 0.0;
  for (int n = 0; n < kVoigt; ++n) {
    const Mat3d dF = h * (F_inverse_transpose * voigt_direction(n));
    const Voigt plus = to_voigt(law.respond(F + dF, viscous, nullptr).stress);
    const Voigt minus = to_voigt(law.respond(F - dF, viscous, nullptr).stress);
    for (int m = 0; m < kVoigt; ++m) {
      const double fd = (plus[m] - minus[m]) / (2 * h);
      error = std::max(error, std::abs(fd - D[m * kVoigt + n]));
      size = std::max(size, std::abs(D[m * kVoigt + n]));
    }
  }
  return error / size;
}

TEST(PointResponse, TangentMatchesFiniteDifferencesOfItsStressForEveryLaw) {
  const Mat3d F = general_deformation();
  const PolynomialTissue tissue = full_polynomial();
  const std::vector<double> history{40.0, -15.0, 7.0, 3.0, -9.0, 12.0, -6.0, 20.0, 5.0, -2.0, 8.0, 1.0,
                                    90.0, 30.0, -20.0, 4.0, 6.0, -11.0};  // Q_1, Q_2, S⁰
  const ViscousStress viscous = viscous_stress(prony_step(tissue.prony(), 0.2), history.data());
  const double tissue_elastic = tangent_error(tissue, F, nullptr);
  const double tissue_viscous = tangent_error(tissue, F, &viscous);
  const double corotational =
      tangent_error(CorotationalLinear{.youngs_modulus = 3050.0, .poisson_ratio = 0.45}, F, nullptr);
  RecordProperty("polynomial_rel_error", scientific(std::max(tissue_elastic, tissue_viscous)));
  RecordProperty("corotational_rel_error", scientific(corotational));
  EXPECT_LT(tissue_elastic, 1e-7);
  EXPECT_LT(tissue_viscous, 1e-7);
  EXPECT_LT(corotational, 1e-7);
}

TEST(PointResponse, StressAndEnergyAgreeWithTheStepForm) {
  // With Q = 0 the response is the instantaneous law: S_iso + S_vol = update(F, ·, 0).second_pk
  // and W_iso + U(J) = W(F); the co-rotational law gives all of S and W itself.
  const Mat3d F = general_deformation();
  const PolynomialTissue tissue = full_polynomial();
  const Material polynomial("all-coefficients", tissue);
  const PointResponse at = tissue.respond(F, nullptr, nullptr);
  const Mat3d C = right_cauchy_green(F);
  const Mat3d total = at.stress + tissue.volumetric.stress(C);
  const Mat3d S = polynomial.update(F, polynomial.initial_state(), 0.0).second_pk;
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(total.a[k], S.a[k], 1e-12 * std::abs(S(0, 0)));
  EXPECT_NEAR(at.energy + at.volumetric.energy, polynomial.instantaneous_energy(F), 1e-12 * at.energy);
  EXPECT_DOUBLE_EQ(at.volumetric.pressure, tissue.volumetric.pressure(det(F)));

  const CorotationalLinear law{.youngs_modulus = 3050.0, .poisson_ratio = 0.45};
  const Material corotational("corotational", law);
  const Mat3d S_law = law.respond(F, nullptr, nullptr).stress;
  const Mat3d S_step = corotational.update(F, corotational.initial_state(), 0.0).second_pk;
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(S_law.a[k], S_step.a[k], 1e-12 * std::abs(S_step(0, 0)));
  EXPECT_DOUBLE_EQ(law.respond(F, nullptr, nullptr).energy, corotational.instantaneous_energy(F));
}

TEST(PointResponse, VolumetricSlopesMatchDifferencesOfU) {
  const PolynomialTissue tissue = full_polynomial();
  const double h = 1e-6;
  for (double J : {0.8, 1.0, 1.15}) {
    const VolumetricResponse at = tissue.volumetric_response(J);
    const VolumetricResponse plus = tissue.volumetric_response(J + h), minus = tissue.volumetric_response(J - h);
    EXPECT_NEAR(at.pressure, (plus.energy - minus.energy) / (2 * h), 1e-6 * tissue.volumetric.bulk_modulus);
    EXPECT_NEAR(at.slope, (plus.pressure - minus.pressure) / (2 * h), 1e-6 * tissue.volumetric.bulk_modulus);
  }
}

// Relaxation under a stretch applied at t = 0 (a step of length 0: the instantaneous response)
// and held, stepped with growing steps: with S⁰ constant over each step the recursion is exact.
TEST(PointResponse, SteppedHistoryFollowsThePronyClosedFormUnderHeldStrain) {
  const PolynomialTissue tissue = full_polynomial();
  const auto& terms = tissue.prony();
  Mat3d F = Mat3d::diagonal(1.3, 1.0 / std::sqrt(1.3), 1.0 / std::sqrt(1.3));
  F(0, 1) = 0.15;
  const Voigt s0 = to_voigt(tissue.respond(F, nullptr, nullptr).stress);
  const double scale = std::abs(*std::max_element(s0.begin(), s0.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }));
  std::vector<double> history(prony_history_size(terms.size()), 0.0);
  double t = 0.0, stress_error = 0.0;
  for (double dt : {0.0, 1e-3, 0.01, 0.1, 0.4, 1.0, 3.0, 10.0, 30.0, 100.0}) {
    t += dt;
    const PronyStep step = prony_step(terms, dt);
    const ViscousStress viscous = viscous_stress(step, history.data());
    const PointResponse response = tissue.respond(F, &viscous, nullptr);
    const Voigt s = to_voigt(response.stress);
    double relaxed = tissue.isochoric.long_term_fraction();
    for (const auto& term : terms) relaxed += term.g * std::exp(-t / term.tau_s);
    for (int m = 0; m < kVoigt; ++m) stress_error = std::max(stress_error, std::abs(s[m] - relaxed * s0[m]));
    advance_history(step, to_voigt(response.elastic_stress), history.data());
  }
  RecordProperty("relaxation_rel_error", scientific(stress_error / scale));
  EXPECT_LT(stress_error, 1e-12 * scale);
}

}  // namespace
}  // namespace needlefem::material
