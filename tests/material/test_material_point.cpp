// Material-point driver against closed forms derived here:
//  * incompressible uniaxial tension/compression of the polynomial law (F = diag(λ, λ^-½, λ^-½),
//    Ī1 = λ² + 2/λ, Ī2 = 2λ + 1/λ²):  σ11 = 2 (λ² - 1/λ) (W1 + W2/λ);
//  * incompressible simple shear (Ī1 = Ī2 = 3 + γ²):  σ12 = 2 γ (W1 + W2);
//  * co-rotational uniaxial: lateral stretch 1 - ν(λ - 1), P11 = E (λ - 1); co-rotational
//    simple shear with the closed-form polar rotation (angle atan(γ/2) about e3);
//  * ramp-and-hold relaxation against the hereditary (convolution) integral
//      S_iso(t) = g∞ S⁰(t) + Σ_i H_i(t),
//      H_i(t) = g_i [S⁰(t) - (1/τ_i) ∫_0^t exp(-(t-s)/τ_i) S⁰(s) ds]   (t ≤ ramp, by parts),
//      H_i(t) = H_i(ramp) exp(-(t - ramp)/τ_i)                         (hold),
//    evaluated by composite Simpson quadrature, independent of the driver's recursion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "material_test_support.hpp"

#include "physics/material/material_point.hpp"

namespace needlefem::material {
namespace {

struct InvariantDerivatives {
  double w1, w2;
};
InvariantDerivatives derivatives(const PolynomialIsochoric& c, double i1_bar, double i2_bar) {
  const double a = i1_bar - 3.0, b = i2_bar - 3.0;
  return {c.c10 + 2 * c.c20 * a + c.c11 * b, c.c01 + c.c11 * a + 2 * c.c02 * b};
}

PolynomialTissue full_polynomial() {
  PolynomialTissue tissue;
  tissue.isochoric.elastic = {.c10 = 263.0, .c01 = 120.0, .c20 = 491.0, .c11 = 77.0, .c02 = 300.0};
  tissue.isochoric.terms = {{0.45, 0.5}, {0.365, 50.0}};
  tissue.volumetric.bulk_modulus = 1.0e7;
  return tissue;
}

TEST(MaterialPoint, IncompressibleUniaxialClosedForm) {
  for (const Material& material : {material_preset("miller-brain"), material_preset("miller-brain-c10-c20"),
                                   Material("all-coefficients", full_polynomial())}) {
    const auto& c = std::get<PolynomialTissue>(material.law()).isochoric.elastic;
    double worst = 0.0;
    for (double target : {1.5, 0.7}) {
      const auto rows = run_material_point(material, {.history = LoadHistory::Uniaxial, .target = target, .steps = 8});
      ASSERT_EQ(rows.size(), 9u);
      for (const auto& row : rows) {
        const double l = row.stretch;
        const auto w = derivatives(c, l * l + 2 / l, 2 * l + 1 / (l * l));
        const double sigma = 2 * (l * l - 1 / l) * (w.w1 + w.w2 / l);
        EXPECT_NEAR(row.log_strain, std::log(l), 1e-15);
        if (l == 1.0) {
          EXPECT_NEAR(row.cauchy_stress_pa, 0.0, 1e-12);
          continue;
        }
        worst = std::max({worst, std::abs(row.cauchy_stress_pa / sigma - 1), std::abs(row.nominal_stress_pa / (sigma / l) - 1)});
      }
      EXPECT_DOUBLE_EQ(rows.back().stretch, target);
    }
    RecordProperty(material.name() + "_uniaxial_rel_error", scientific(worst));
    EXPECT_LT(worst, 1e-6) << material.name();
  }
}

TEST(MaterialPoint, IncompressibleSimpleShearClosedForm) {
  for (const Material& material : {material_preset("miller-brain"), Material("all-coefficients", full_polynomial())}) {
    const auto& c = std::get<PolynomialTissue>(material.law()).isochoric.elastic;
    const auto rows = run_material_point(material, {.history = LoadHistory::Shear, .target = 1.0, .steps = 10});
    ASSERT_EQ(rows.size(), 11u);
    double worst = 0.0;
    for (std::size_t k = 1; k < rows.size(); ++k) {
      const double g = rows[k].shear;
      const auto w = derivatives(c, 3 + g * g, 3 + g * g);
      const double tau = 2 * g * (w.w1 + w.w2);
      worst = std::max({worst, std::abs(rows[k].cauchy_stress_pa / tau - 1), std::abs(rows[k].nominal_stress_pa / tau - 1)});
      EXPECT_NEAR(rows[k].log_strain, std::asinh(g / 2), 1e-15);
    }
    RecordProperty(material.name() + "_shear_rel_error", scientific(worst));
    EXPECT_LT(worst, 1e-6) << material.name();
  }
}

TEST(MaterialPoint, LongTermIsRelaxedFractionOfInstantaneous) {
  const Material miller = material_preset("miller-brain");
  const auto fast = run_material_point(miller, {.history = LoadHistory::Uniaxial, .target = 1.3, .steps = 3});
  const auto slow =
      run_material_point(miller, {.history = LoadHistory::Uniaxial, .target = 1.3, .steps = 3, .long_term = true});
  EXPECT_NEAR(slow.back().cauchy_stress_pa / fast.back().cauchy_stress_pa, 0.185, 1e-12);
}

TEST(MaterialPoint, CorotationalClosedForms) {
  const CorotationalLinear law{.youngs_modulus = 3050.0, .poisson_ratio = 0.45};
  const Material material("corotational", law);
  double worst = 0.0;
  for (double target : {1.5, 0.7}) {
    for (const auto& row : run_material_point(material, {.history = LoadHistory::Uniaxial, .target = target, .steps = 4})) {
      const double strain = row.stretch - 1, lateral = 1 - law.poisson_ratio * strain;
      const double nominal = law.youngs_modulus * strain;
      worst = std::max(worst, std::abs(row.nominal_stress_pa - nominal) / (law.youngs_modulus * 0.5));
      worst = std::max(worst, std::abs(row.cauchy_stress_pa - nominal / (lateral * lateral)) / (law.youngs_modulus * 0.5));
    }
  }
  for (const auto& row : run_material_point(material, {.history = LoadHistory::Shear, .target = 1.0, .steps = 5})) {
    // Polar decomposition of simple shear: R rotates by θ = atan(γ/2) about e3.
    const double g = row.shear, theta = std::atan(g / 2), c = std::cos(theta), s = std::sin(theta);
    Mat3d R = Mat3d::identity(), F = Mat3d::identity();
    R(0, 0) = R(1, 1) = c;
    R(0, 1) = s;
    R(1, 0) = -s;
    F(0, 1) = g;
    const Mat3d strain = transpose(R) * F - Mat3d::identity();
    const Mat3d P = R * (2 * law.shear_modulus() * strain + law.lame_lambda() * trace(strain) * Mat3d::identity());
    const double sigma = (P * transpose(F))(0, 1);
    worst = std::max(worst, std::abs(row.cauchy_stress_pa - sigma) / law.youngs_modulus);
  }
  RecordProperty("corotational_rel_error", scientific(worst));
  EXPECT_LT(worst, 1e-9);
}

// σ11(t) of ramp-and-hold from the hereditary integral (see the file header).
double hereditary_cauchy_stress(const Viscoelastic<PolynomialIsochoric>& law, double target, double ramp, double t) {
  auto stretch_at = [&](double time) { return 1 + (target - 1) * std::min(time / ramp, 1.0); };
  auto elastic_stress = [&](double time) {
    const double l = stretch_at(time);
    return law.elastic.stress(right_cauchy_green(Mat3d::diagonal(l, 1 / std::sqrt(l), 1 / std::sqrt(l))));
  };
  const double loaded = std::min(t, ramp);
  Mat3d S = law.long_term_fraction() * elastic_stress(t);
  for (const auto& term : law.terms) {
    const int intervals = 2000;  // Simpson on [0, loaded]; the integrand is smooth
    const double h = loaded / intervals;
    Mat3d integral;
    for (int k = 0; k <= intervals; ++k) {
      const double weight = (k == 0 || k == intervals) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      integral += (weight * h / 3 * std::exp(-(loaded - k * h) / term.tau_s)) * elastic_stress(k * h);
    }
    const Mat3d h_loaded = term.g * (elastic_stress(loaded) - (1 / term.tau_s) * integral);
    S += std::exp(-(t - loaded) / term.tau_s) * h_loaded;
  }
  const double l = stretch_at(t);
  return l * l * S(0, 0) - S(1, 1) / l;  // (F S Fᵀ)11 - (F S Fᵀ)22, the lateral pressure removed
}

TEST(MaterialPoint, RampAndHoldRelaxationMatchesHereditaryIntegral) {
  for (const Material& material : {material_preset("miller-brain"), material_preset("miller-brain-c10-c20")}) {
    const auto& law = std::get<PolynomialTissue>(material.law()).isochoric;
    for (double target : {1.1, 0.9}) {
      const auto rows = run_material_point(
          material, {.history = LoadHistory::Relaxation, .target = target, .steps = 20, .ramp_s = 0.1, .hold_s = 100});
      double worst = 0.0;
      for (double required : {0.05, 0.1, 0.6, 5.0, 50.0, 100.0})
        EXPECT_TRUE(std::any_of(rows.begin(), rows.end(),
                                [&](const auto& row) { return std::abs(row.time_s - required) < 1e-9; }))
            << "no row at t = " << required;
      for (const auto& row : rows) {
        if (row.time_s == 0.0) continue;
        const double reference = hereditary_cauchy_stress(law, target, 0.1, row.time_s);
        worst = std::max(worst, std::abs(row.cauchy_stress_pa / reference - 1));
      }
      EXPECT_NEAR(rows.back().time_s, 100.1, 1e-9);
      // Relaxation is real and large: at 100 s less than 40 % of the peak stress remains.
      const auto peak = std::max_element(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
        return std::abs(a.cauchy_stress_pa) < std::abs(b.cauchy_stress_pa);
      });
      EXPECT_LT(rows.back().cauchy_stress_pa / peak->cauchy_stress_pa, 0.4);
      RecordProperty(material.name() + "_relaxation_rel_error_to_" + scientific(target), scientific(worst));
      EXPECT_LT(worst, 0.005) << material.name() << " to " << target;
    }
  }
}

TEST(MaterialPoint, ConstantRateHistory) {
  const auto rows = run_material_point(material_preset("miller-brain"),
                                       {.history = LoadHistory::ConstantRate, .target = 0.7, .steps = 20, .rate_per_s = 0.64});
  ASSERT_EQ(rows.size(), 21u);
  EXPECT_NEAR(rows.back().time_s, 0.3 / 0.64, 1e-12);
  EXPECT_NEAR(rows.back().stretch, 0.7, 1e-12);
  EXPECT_NEAR(rows.back().strain_rate_per_s, -0.64 / 0.7, 1e-12);
  EXPECT_LT(rows.back().cauchy_stress_pa, 0.0);
  // Slower than instantaneous loading: relaxation during the 0.47 s ramp lowers the stress.
  const auto instantaneous =
      run_material_point(material_preset("miller-brain"), {.history = LoadHistory::Uniaxial, .target = 0.7, .steps = 1});
  EXPECT_LT(std::abs(rows.back().cauchy_stress_pa), std::abs(instantaneous.back().cauchy_stress_pa));
}

}  // namespace
}  // namespace needlefem::material
