// Pseudo-rigid-body model of the compliant needle (paper 000, Eq. 2.4-2.8); equations in hinge.hpp.
#include "steering/hinge.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "steering/magnet.hpp"

namespace needlefem::steering {

void CompliantNeedleHinge::validate() const {
  auto require = [](bool ok, const char* what, double value, const char* unit) {
    if (!ok || !std::isfinite(value))
      throw std::invalid_argument(fmt::format("compliant needle: {}, got {:.6g} {}", what, value, unit));
  };
  require(neck_length_m > 0.0, "neck length must be positive", neck_length_m, "m");
  require(neck_diameter_m > 0.0, "neck diameter must be positive", neck_diameter_m, "m");
  require(head_length_m > 0.0, "head length must be positive", head_length_m, "m");
  require(youngs_modulus_pa > 0.0, "Young's modulus must be positive", youngs_modulus_pa, "Pa");
  require(tissue_spring_constant_n_per_m2 >= 0.0, "tissue spring constant must be >= 0",
          tissue_spring_constant_n_per_m2, "N/m^2");
}

double CompliantNeedleHinge::neck_second_moment_m4() const {
  return std::numbers::pi * std::pow(neck_diameter_m, 4) / 64.0;
}

double CompliantNeedleHinge::hinge_stiffness_n_m_per_rad() const {
  return youngs_modulus_pa * neck_second_moment_m4() / neck_length_m;
}

double CompliantNeedleHinge::tissue_stiffness_n_m_per_rad() const {
  return tissue_spring_constant_n_per_m2 / 3.0 * std::pow(0.5 * neck_length_m + head_length_m, 3);
}

double CompliantNeedleHinge::lever_arm_m() const { return 0.5 * (head_length_m + neck_length_m); }

double turning_angle_rad(const CompliantNeedleHinge& hinge, double force_n, double force_angle_rad) {
  hinge.validate();
  return force_n * std::cos(force_angle_rad) * hinge.lever_arm_m() /
         (hinge.hinge_stiffness_n_m_per_rad() + hinge.tissue_stiffness_n_m_per_rad());
}

double turning_angle_for_flux_density_rad(const CompliantNeedleHinge& hinge, double flux_density_t,
                                          double gap_area_m2, double force_angle_rad) {
  return turning_angle_rad(hinge, gap_force_n(flux_density_t, gap_area_m2), force_angle_rad);
}

double flux_density_for_turning_angle_t(const CompliantNeedleHinge& hinge, double turning_angle_rad,
                                        double gap_area_m2, double force_angle_rad) {
  hinge.validate();
  if (!(turning_angle_rad >= 0.0))
    throw std::domain_error("compliant needle: wanted turning angle must be >= 0");
  // cos(90 deg) evaluates to 6e-17, not 0: treat pulls within 1e-9 of perpendicular as perpendicular.
  const double cos_phi = std::cos(force_angle_rad);
  if (!(cos_phi > 1e-9))
    throw std::domain_error(fmt::format("compliant needle: a pull at {:.6g} deg to the head has no turning component "
                                        "(cos(phi) <= 0)", force_angle_rad * 180.0 / std::numbers::pi));
  if (!(gap_area_m2 > 0.0)) throw std::domain_error("compliant needle: gap area must be positive");
  // Eq. 2.7 solved for F, then F = B^2 A_g / (2 mu0) solved for B.
  const double force_n = turning_angle_rad *
                         (hinge.hinge_stiffness_n_m_per_rad() + hinge.tissue_stiffness_n_m_per_rad()) /
                         (cos_phi * hinge.lever_arm_m());
  return std::sqrt(2.0 * vacuum_permeability_h_per_m * force_n / gap_area_m2);
}

}  // namespace needlefem::steering
