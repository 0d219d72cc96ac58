// Block magnet field and force (paper 000, Eq. 2.1-2.3); equations in magnet.hpp.
#include "steering/magnet.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace needlefem::steering {

namespace {

// A quarter of the solid angle subtended by the W x L pole rectangle from distance z on its axis.
double quarter_solid_angle(double width, double length, double z) {
  return std::atan(width * length / (2.0 * z * std::sqrt(length * length + width * width + 4.0 * z * z)));
}

}  // namespace

void BlockMagnet::validate() const {
  auto require_positive = [](double value, const char* name, const char* unit) {
    if (!(value > 0.0) || !std::isfinite(value))
      throw std::invalid_argument(fmt::format("block magnet: {} must be positive and finite, got {:.6g}{}", name, value,
                                              unit));
  };
  require_positive(residual_flux_density_t, "residual flux density", " T");
  require_positive(pole_width_m, "pole width", " m");
  require_positive(pole_length_m, "pole length", " m");
  require_positive(thickness_m, "thickness", " m");
  require_positive(correction_factor, "correction factor", "");
}

double axial_flux_density_t(const BlockMagnet& m, double distance_m) {
  if (!(distance_m >= 0.0)) throw std::domain_error("block magnet: distance must be >= 0");
  // At the face itself the arctangent's argument LW/0 is infinite: atan -> pi/2.
  const double near = distance_m > 0.0 ? quarter_solid_angle(m.pole_width_m, m.pole_length_m, distance_m)
                                       : 0.5 * std::numbers::pi;
  const double far = quarter_solid_angle(m.pole_width_m, m.pole_length_m, distance_m + m.thickness_m);
  return m.correction_factor * m.residual_flux_density_t / std::numbers::pi * (near - far);
}

double distance_for_flux_density_m(const BlockMagnet& m, double flux_density_t) {
  m.validate();
  const double at_face = axial_flux_density_t(m, 0.0);
  if (!(flux_density_t > 0.0) || flux_density_t >= at_face)
    throw std::domain_error(fmt::format("block magnet: wanted flux density {:.6g} T is outside (0, {:.6g} T), the range "
                                        "this magnet gives", flux_density_t, at_face));
  // Bracket: grow the far end until B has dropped below the target, then bisect to round-off.
  const double size = m.pole_width_m + m.pole_length_m + m.thickness_m;
  double near = 0.0, far = size;
  while (axial_flux_density_t(m, far) > flux_density_t) {
    near = far;
    far *= 2.0;
  }
  for (int i = 0; i < 200 && far - near > 1e-15 * far; ++i) {
    const double mid = 0.5 * (near + far);
    (axial_flux_density_t(m, mid) > flux_density_t ? near : far) = mid;
  }
  return 0.5 * (near + far);
}

double gap_force_n(double flux_density_t, double gap_area_m2, double susceptibility) {
  return flux_density_t * flux_density_t * gap_area_m2 / (2.0 * vacuum_permeability_h_per_m * (1.0 + susceptibility));
}

}  // namespace needlefem::steering
