// Equations: polynomial_tissue.hpp.
#include "physics/material/polynomial_tissue.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace needlefem::material {

PointResponse PolynomialTissue::respond(const Mat3d& F, const ViscousStress* viscous, VoigtTangent* tangent) const {
  const Mat3d C = right_cauchy_green(F);
  const auto [elastic_stress, elastic_energy] = isochoric.elastic.stress_and_energy(C);
  PointResponse response;
  response.elastic_stress = elastic_stress;
  response.stress = viscous ? viscous->elastic_fraction * elastic_stress - viscous->history : elastic_stress;
  response.energy = elastic_energy;
  if (tangent) *tangent = to_voigt(isochoric.elastic_tangent(C));
  response.volumetric = volumetric_response(det(F));
  return response;
}

std::string PolynomialTissue::description() const {
  const auto& c = isochoric.elastic;
  std::vector<double> g, tau;
  for (const auto& term : isochoric.terms) {
    g.push_back(term.g);
    tau.push_back(term.tau_s);
  }
  return fmt::format(
      "polynomial N=2, INSTANTANEOUS C10={} C01={} C20={} C11={} C02={} Pa, bulk modulus K={} Pa; "
      "Prony g=[{}] tau_s=[{}] (g_inf={:.4g}); shear modulus instantaneous {:.6g} Pa, long-term {:.6g} Pa",
      c.c10, c.c01, c.c20, c.c11, c.c02, volumetric.bulk_modulus, fmt::join(g, ", "), fmt::join(tau, ", "),
      isochoric.long_term_fraction(), instantaneous_shear_modulus(), long_term_shear_modulus());
}

}  // namespace needlefem::material
