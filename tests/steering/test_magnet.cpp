// Block magnet (paper 000, Eq. 2.1-2.3) against references that do not use Eq. 2.3's closed form:
// a numerical integration of the equivalent magnetic-charge model, the far-field dipole, the
// long-magnet limit at the face, and the root finder's round trip.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "steering/magnet.hpp"

namespace needlefem::steering {
namespace {

// N42-like magnet with the paper's 50 x 60 mm pole.
BlockMagnet paper_pole_magnet(double correction = 1.0) { return {1.3, 0.05, 0.06, 0.02, correction}; }

// Axial field of a magnet magnetised along z, as surface magnetic charge +-Br/mu0 on its two pole
// faces: B_z(x) = Br/(4 pi) [ I(x) - I(x + T) ],  I(z) = integral over the face of z / r^3 dA.
// Integrated with composite 4-point Gauss-Legendre on a panel grid graded toward the axis.
double charge_model_axial_field(const BlockMagnet& m, double x) {
  constexpr std::array<double, 4> nodes = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                           0.8611363115940526};
  constexpr std::array<double, 4> weights = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                             0.3478548451374538};
  auto face_integral = [&](double z) {
    // Integrate over one quadrant [0, W/2] x [0, L/2] (the integrand is even) and multiply by 4;
    // geometric panel edges resolve the z-wide peak at the axis.
    auto edges = [z](double half) {
      std::vector<double> e = {0.0};
      for (double h = z / 64.0; h < half; h *= 1.25) e.push_back(h);
      e.push_back(half);
      return e;
    };
    const auto ex = edges(0.5 * m.pole_width_m), ey = edges(0.5 * m.pole_length_m);
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < ex.size(); ++i)
      for (std::size_t j = 0; j + 1 < ey.size(); ++j) {
        const double hx = 0.5 * (ex[i + 1] - ex[i]), cx = 0.5 * (ex[i + 1] + ex[i]);
        const double hy = 0.5 * (ey[j + 1] - ey[j]), cy = 0.5 * (ey[j + 1] + ey[j]);
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b) {
            const double u = cx + hx * nodes[a], v = cy + hy * nodes[b];
            sum += weights[a] * weights[b] * hx * hy * z / std::pow(u * u + v * v + z * z, 1.5);
          }
      }
    return 4.0 * sum;
  };
  return m.correction_factor * m.residual_flux_density_t / (4.0 * std::numbers::pi) *
         (face_integral(x) - face_integral(x + m.thickness_m));
}

TEST(BlockMagnet, MatchesNumericallyIntegratedChargeModel) {
  const BlockMagnet magnet = paper_pole_magnet(0.85);
  for (double x : {0.001, 0.005, 0.02, 0.05, 0.1, 0.3}) {
    const double closed_form = axial_flux_density_t(magnet, x);
    const double integrated = charge_model_axial_field(magnet, x);
    EXPECT_NEAR(closed_form, integrated, 1e-9 * magnet.residual_flux_density_t) << "x = " << x;
  }
}

TEST(BlockMagnet, FarFieldIsTheDipoleField) {
  // On the axis of a dipole m = (Br/mu0) W L T: B = mu0 m / (2 pi x^3) = Br W L T / (2 pi x^3),
  // up to O((size/x)^2) corrections.
  const BlockMagnet magnet = paper_pole_magnet();
  const double x = 10.0;  // 10 m, 100x the magnet's size
  const double dipole = magnet.residual_flux_density_t * magnet.pole_area_m2() * magnet.thickness_m /
                        (2.0 * std::numbers::pi * std::pow(x + 0.5 * magnet.thickness_m, 3));
  EXPECT_NEAR(axial_flux_density_t(magnet, x) / dipole, 1.0, 1e-4);
}

TEST(BlockMagnet, LongMagnetGivesHalfTheRemanenceAtItsFace) {
  // A semi-infinite magnet's face sees half its remanence on the axis: Br/2 (times correction).
  BlockMagnet magnet = paper_pole_magnet(0.9);
  magnet.thickness_m = 1e4;
  EXPECT_NEAR(axial_flux_density_t(magnet, 0.0), 0.5 * 0.9 * magnet.residual_flux_density_t, 1e-9);
  // An infinitely wide thin slab has no field outside it.
  BlockMagnet slab = paper_pole_magnet();
  slab.pole_width_m = slab.pole_length_m = 1e5;
  EXPECT_NEAR(axial_flux_density_t(slab, 0.01), 0.0, 1e-6);
}

TEST(BlockMagnet, FieldDecreasesMonotonically) {
  const BlockMagnet magnet = paper_pole_magnet();
  double previous = axial_flux_density_t(magnet, 0.0);
  for (double x = 1e-4; x < 1.0; x *= 1.1) {
    const double b = axial_flux_density_t(magnet, x);
    EXPECT_LT(b, previous) << "x = " << x;
    previous = b;
  }
}

TEST(BlockMagnet, DistanceRootGivesBackTheFluxDensity) {
  const BlockMagnet magnet = paper_pole_magnet(0.85);
  for (double wanted : {0.0391, 0.0553, 0.2, 0.3}) {
    const double x = distance_for_flux_density_m(magnet, wanted);
    EXPECT_NEAR(axial_flux_density_t(magnet, x), wanted, 1e-12 * wanted) << "B = " << wanted;
  }
  EXPECT_THROW(distance_for_flux_density_m(magnet, 0.9 * magnet.residual_flux_density_t), std::domain_error);
  EXPECT_THROW(distance_for_flux_density_m(magnet, 0.0), std::domain_error);
}

TEST(BlockMagnet, GapForceIsThePapersSiForm) {
  // Paper: F = B^2 A_g / (8 pi 1e-7), i.e. B^2 A_g / (2 mu0); 1 T on 1 m^2 pulls 397.9 kN.
  EXPECT_NEAR(gap_force_n(1.0, 1.0), 1.0 / (8.0 * std::numbers::pi * 1e-7), 1e-6);
  EXPECT_NEAR(gap_force_n(0.0391, 0.003), 0.0391 * 0.0391 * 0.003 / (8.0 * std::numbers::pi * 1e-7), 1e-12);
  // Eq. 2.2 in a medium of susceptibility chi: B = mu0 (1 + chi) H halves H at chi = 1.
  EXPECT_NEAR(gap_force_n(0.5, 0.01, 1.0), 0.5 * gap_force_n(0.5, 0.01), 1e-12);
}

}  // namespace
}  // namespace needlefem::steering
