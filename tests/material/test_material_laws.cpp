// Material laws at a point: stress = ∂W/∂F and consistent tangent = ∂P/∂F by central finite
// differences, objectivity, zero stress at rest, the mixed-element API (p(J), U''(J), S_vol,
// ∂S_iso/∂E) and the Prony ODE form against the one-step recursion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "material_test_support.hpp"
#include <vector>

#include "physics/material/material.hpp"

namespace needlefem::material {
namespace {

Mat3d rotation(double angle, int axis) {
  Mat3d Q = Mat3d::identity();
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  Q(i, i) = Q(j, j) = std::cos(angle);
  Q(i, j) = -std::sin(angle);
  Q(j, i) = std::sin(angle);
  return Q;
}

double max_abs(const Mat3d& x) {
  double m = 0.0;
  for (double v : x.a) m = std::max(m, std::abs(v));
  return m;
}

std::vector<Material> all_laws() {
  PolynomialTissue full;  // every coefficient non-zero, soft bulk so U(J) matters too
  full.isochoric.elastic = {.c10 = 263.0, .c01 = 120.0, .c20 = 491.0, .c11 = 77.0, .c02 = 300.0};
  full.isochoric.terms = {{0.45, 0.5}, {0.365, 50.0}};
  full.volumetric.bulk_modulus = 5.0e3;
  return {material_preset("miller-brain"), material_preset("miller-brain-c10-c20"), Material("all-coefficients", full),
          Material("corotational", CorotationalLinear{.youngs_modulus = 3050.0, .poisson_ratio = 0.45})};
}

// A state with non-zero viscous stresses: a loading step, then part of a relaxation.
ViscousState loaded_state(const Material& material) {
  Mat3d F1 = Mat3d::diagonal(1.2, 0.95, 0.9);
  F1(0, 2) = 0.1;
  ViscousState state = material.update(F1, material.initial_state(), 0.05).state;
  return material.update(F1, state, 0.3).state;
}

TEST(MaterialLaws, StressIsEnergyGradient) {
  const Mat3d F = general_deformation();
  for (const auto& material : all_laws()) {
    const Mat3d P = material.update(F, material.initial_state(), 0.0).first_pk;
    double error = 0.0;
    const double h = 1e-6;
    for (int n = 0; n < 9; ++n) {
      Mat3d plus = F, minus = F;
      plus.a[n] += h;
      minus.a[n] -= h;
      const double dw = (material.instantaneous_energy(plus) - material.instantaneous_energy(minus)) / (2 * h);
      error = std::max(error, std::abs(dw - P.a[n]));
    }
    const double relative = error / max_abs(P);
    RecordProperty(material.name() + "_dW_dF_rel_error", scientific(relative));
    EXPECT_LT(relative, 1e-6) << material.name();
  }
}

TEST(MaterialLaws, TangentMatchesFiniteDifferences) {
  const Mat3d F = general_deformation();
  for (const auto& material : all_laws())
    for (double dt : {0.0, 0.2, 1e30}) {
      const ViscousState old = loaded_state(material);
      const Tensor4 A = material.tangent(F, old, dt);
      double error = 0.0, size = 0.0;
      const double h = 1e-6;
      for (int kl = 0; kl < 9; ++kl) {
        Mat3d plus = F, minus = F;
        plus.a[kl] += h;
        minus.a[kl] -= h;
        const Mat3d dP = (1.0 / (2 * h)) * (material.update(plus, old, dt).first_pk - material.update(minus, old, dt).first_pk);
        for (int ij = 0; ij < 9; ++ij) {
          error = std::max(error, std::abs(dP.a[ij] - A.a[ij * 9 + kl]));
          size = std::max(size, std::abs(A.a[ij * 9 + kl]));
        }
      }
      RecordProperty(material.name() + "_tangent_rel_error_dt_" + scientific(dt), scientific(error / size));
      EXPECT_LT(error / size, 1e-6) << material.name() << " dt " << dt;
    }
}

// ∂S/∂E of the stepped stress, by differences of S along dF = F^-T dE (for which dC = 2 dE).
TEST(MaterialLaws, GreenStrainTangentMatchesFiniteDifferences) {
  const Mat3d F = general_deformation();
  const Mat3d F_inverse_transpose = transpose(inverse(F));
  for (const auto& material : all_laws()) {
    const ViscousState old = loaded_state(material);
    const Tensor4 A = material.tangent_green_strain(F, old, 0.2);
    double error = 0.0, size = 0.0;
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        Mat3d dE;
        dE(k, l) += 0.5;
        dE(l, k) += 0.5;
        const Mat3d dF = h * (F_inverse_transpose * dE);
        const Mat3d dS = (1.0 / (2 * h)) * (material.update(F + dF, old, 0.2).second_pk -
                                            material.update(F - dF, old, 0.2).second_pk);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            error = std::max(error, std::abs(dS(i, j) - A(i, j, k, l)));
            size = std::max(size, std::abs(A(i, j, k, l)));
          }
      }
    RecordProperty(material.name() + "_dS_dE_rel_error", scientific(error / size));
    EXPECT_LT(error / size, 1e-6) << material.name();
  }
}

TEST(MaterialLaws, Objectivity) {
  const Mat3d F = general_deformation();
  const Mat3d Q = rotation(0.7, 0) * rotation(-1.3, 2);
  for (const auto& material : all_laws()) {
    const ViscousState old = loaded_state(material);
    const auto at_F = material.update(F, old, 0.2);
    const auto at_QF = material.update(Q * F, old, 0.2);
    // P(QF) = Q P(F); S(QF) = S(F); the energy is unchanged.
    EXPECT_LT(max_abs(at_QF.first_pk - Q * at_F.first_pk), 1e-11 * max_abs(at_F.first_pk)) << material.name();
    EXPECT_LT(max_abs(at_QF.second_pk - at_F.second_pk), 1e-11 * max_abs(at_F.second_pk)) << material.name();
    EXPECT_NEAR(material.instantaneous_energy(Q * F), material.instantaneous_energy(F),
                1e-12 * material.instantaneous_energy(F));
  }
}

TEST(MaterialLaws, ZeroStressAtRest) {
  for (const auto& material : all_laws()) {
    const auto rest = material.update(Mat3d::identity(), material.initial_state(), 0.1);
    EXPECT_LT(max_abs(rest.first_pk), 1e-12 * material.instantaneous_shear_modulus()) << material.name();
    EXPECT_NEAR(material.instantaneous_energy(Mat3d::identity()), 0.0, 1e-15);
  }
}

TEST(MaterialLaws, PresetsAreInstantaneousModuli) {
  const Material miller = material_preset("miller-brain");
  EXPECT_DOUBLE_EQ(miller.instantaneous_shear_modulus(), 1052.0);
  EXPECT_NEAR(miller.long_term_shear_modulus(), 0.185 * 1052.0, 1e-9);
  EXPECT_DOUBLE_EQ(material_preset("miller-brain-c10-c20").instantaneous_shear_modulus(), 526.0);
  EXPECT_NE(miller.description().find("INSTANTANEOUS"), std::string::npos);
}

// The pieces a mixed displacement-pressure element uses.
TEST(MaterialLaws, MixedElementInterface) {
  const VolumetricQuadratic volumetric{.bulk_modulus = 2.0e4};
  const double h = 1e-6;
  for (double J : {0.8, 1.0, 1.15}) {
    EXPECT_NEAR(volumetric.pressure(J), (volumetric.energy(J + h) - volumetric.energy(J - h)) / (2 * h), 1e-6);
    EXPECT_NEAR(volumetric.pressure_derivative(),
                (volumetric.pressure(J + h) - volumetric.pressure(J - h)) / (2 * h), 1e-5);
  }
  // S_vol = 2 ∂U(J(C))/∂C, and ∂S_iso/∂E against differences of S_iso.
  const Mat3d C = right_cauchy_green(general_deformation());
  const Mat3d s_vol = volumetric.stress(C);
  const Material miller = material_preset("miller-brain");
  const auto& tissue = std::get<PolynomialTissue>(miller.law());
  const Tensor4 tangent = tissue.isochoric.elastic_tangent(C);
  double vol_error = 0.0, tangent_error = 0.0, tangent_size = 0.0;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      Mat3d dE;  // symmetric direction sym(e_k (x) e_l)
      dE(k, l) += 0.5;
      dE(l, k) += 0.5;
      const Mat3d plus = C + (2 * h) * dE, minus = C - (2 * h) * dE;
      const double dU = (volumetric.energy(std::sqrt(det(plus))) - volumetric.energy(std::sqrt(det(minus)))) / (2 * h);
      vol_error = std::max(vol_error, std::abs(dU - double_dot(s_vol, dE)));
      const Mat3d dS = (1.0 / (2 * h)) * (tissue.isochoric.elastic.stress(plus) - tissue.isochoric.elastic.stress(minus));
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          tangent_error = std::max(tangent_error, std::abs(dS(i, j) - tangent(i, j, k, l)));
          tangent_size = std::max(tangent_size, std::abs(tangent(i, j, k, l)));
        }
    }
  EXPECT_LT(vol_error, 1e-6 * max_abs(s_vol));
  EXPECT_LT(tangent_error, 1e-6 * tangent_size);

  // The viscoelastic isochoric block: the stepped tangent is [1 - Σ g_i (1 - h_i)] ∂S⁰_iso/∂E.
  const ViscousState old = tissue.isochoric.advance(C, tissue.isochoric.initial_state(), 0.1);
  const double dt = 0.3;
  double scale = 1.0;
  for (const auto& term : tissue.isochoric.terms) {
    const double x = dt / term.tau_s;
    scale -= term.g * (1.0 - (1.0 - std::exp(-x)) / x);
  }
  const Tensor4 stepped = tissue.isochoric.stepped_tangent(C, old, dt);
  double stepped_error = 0.0;
  for (int n = 0; n < 81; ++n) stepped_error = std::max(stepped_error, std::abs(stepped.a[n] - scale * tangent.a[n]));
  EXPECT_LT(stepped_error, 1e-12 * tangent_size);
}

// Right Cauchy-Green tensor of a smooth loading path (tension, shear, partial unloading).
Mat3d path(double t) {
  Mat3d F = Mat3d::diagonal(1.0 + 0.25 * std::sin(2.0 * t), 1.0, 1.0);
  F(1, 1) = F(2, 2) = 1.0 / std::sqrt(F(0, 0));
  F(0, 1) = 0.3 * t * std::exp(-t);
  return right_cauchy_green(F);
}

TEST(Prony, OdeRightHandSideAgreesWithRecursion) {
  const Material miller = material_preset("miller-brain");
  const auto& law = std::get<PolynomialTissue>(miller.law()).isochoric;
  const double dt = 1e-3, end = 3.0;
  // Classical RK4 on the internal-variable ODE dQ_i/dt = (g_i S⁰(C(t)) - Q_i)/τ_i.
  auto rate = [&](const Mat3d& C, const std::vector<Mat3d>& q) {
    const Mat3d s0 = law.elastic.stress(C);
    std::vector<Mat3d> r(q.size());
    for (std::size_t i = 0; i < q.size(); ++i) r[i] = (1.0 / law.terms[i].tau_s) * (law.terms[i].g * s0 - q[i]);
    return r;
  };
  // S_iso = S⁰_iso - Σ Q_i for given internal variables.
  auto stress = [&](const Mat3d& C, const std::vector<Mat3d>& q) {
    Mat3d s = law.elastic.stress(C);
    for (const auto& q_i : q) s -= q_i;
    return s;
  };
  std::vector<Mat3d> q(law.terms.size());
  auto add = [](const std::vector<Mat3d>& x, double a, const std::vector<Mat3d>& y) {
    std::vector<Mat3d> r = x;
    for (std::size_t i = 0; i < r.size(); ++i) r[i] += a * y[i];
    return r;
  };
  ViscousState recursion = law.initial_state();
  double max_difference = 0.0, max_stress = 0.0;
  for (int n = 0; n < static_cast<int>(std::lround(end / dt)); ++n) {
    const double t = n * dt;
    const auto k1 = rate(path(t), q);
    const auto k2 = rate(path(t + dt / 2), add(q, dt / 2, k1));
    const auto k3 = rate(path(t + dt / 2), add(q, dt / 2, k2));
    const auto k4 = rate(path(t + dt), add(q, dt, k3));
    q = add(add(add(add(q, dt / 6, k1), dt / 3, k2), dt / 3, k3), dt / 6, k4);
    const Mat3d s_recursion = law.stepped_stress(path(t + dt), recursion, dt);
    recursion = law.advance(path(t + dt), recursion, dt);
    // The stepped stress is S⁰ - Σ Q_i of the advanced state.
    EXPECT_LT(max_abs(s_recursion - stress(path(t + dt), recursion.q)), 1e-12 * (1.0 + max_abs(s_recursion)));
    const Mat3d s_ode = stress(path(t + dt), q);
    max_difference = std::max(max_difference, max_abs(s_ode - s_recursion));
    max_stress = std::max(max_stress, max_abs(s_ode));
  }
  RecordProperty("ode_vs_recursion_rel", scientific(max_difference / max_stress));
  EXPECT_LT(max_difference / max_stress, 1e-6);
}

// The element kernel's form of the recursion (a point's Voigt history, point_response.hpp)
// against the material-point form (ViscousState, viscoelastic.hpp), over a loading path with
// steps of growing length: the same stresses and the same advanced state.
TEST(Prony, VoigtHistoryFollowsTheRecursionOfTheMaterialPoint) {
  const Material miller = material_preset("miller-brain");
  const auto& law = std::get<PolynomialTissue>(miller.law()).isochoric;
  ViscousState state = law.initial_state();
  std::vector<double> history(prony_history_size(law.terms.size()), 0.0);
  double t = 0.0, largest_difference = 0.0, largest_stress = 0.0;
  for (double dt : {1e-4, 1e-3, 0.01, 0.1, 0.5, 2.0, 20.0}) {
    t += dt;
    const Mat3d C = path(t);
    const PronyStep step = prony_step(law.terms, dt);
    const ViscousStress viscous = viscous_stress(step, history.data());
    const Mat3d voigt_form = step.elastic_fraction * law.elastic.stress(C) - viscous.history;
    const Mat3d point_form = law.stepped_stress(C, state, dt);
    largest_difference = std::max(largest_difference, max_abs(voigt_form - point_form));
    largest_stress = std::max(largest_stress, max_abs(point_form));
    advance_history(step, to_voigt(law.elastic.stress(C)), history.data());
    state = law.advance(C, state, dt);
    for (std::size_t i = 0; i < law.terms.size(); ++i)
      EXPECT_LT(max_abs(from_voigt(history.data() + i * kVoigt) - state.q[i]), 1e-12 * largest_stress) << dt;
  }
  EXPECT_LT(largest_difference, 1e-12 * largest_stress);
  // Δt = 0 is the stored state's own stress; Δt -> inf relaxes to g∞.
  EXPECT_DOUBLE_EQ(prony_step(law.terms, 0.0).elastic_fraction, 1.0);
  EXPECT_NEAR(prony_step(law.terms, 1e9).elastic_fraction, law.long_term_fraction(), 1e-6);
}

}  // namespace
}  // namespace needlefem::material
