// Equations: corotational.hpp.
#include "physics/material/corotational.hpp"

#include <fmt/format.h>

namespace needlefem::material {

PointResponse CorotationalLinear::respond(const Mat3d& F, const ViscousStress*, VoigtTangent* tangent) const {
  PointResponse response;
  response.stress = second_pk(F, {}, 0.0);
  response.energy = energy(F);
  if (tangent) *tangent = to_voigt(green_strain_tangent(F, [&](const Mat3<Dual>& f) { return second_pk(f, {}, 0.0); }));
  return response;
}

std::string CorotationalLinear::description() const {
  return fmt::format("co-rotational linear elastic, E={} Pa, nu={}; shear modulus {:.6g} Pa (elastic)",
                     youngs_modulus, poisson_ratio, shear_modulus());
}

}  // namespace needlefem::material
