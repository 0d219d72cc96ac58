// Co-rotational linear elasticity: paper 000's tissue model (Müller's co-rotational FEM, where
// element forces are f = R K (Rᵀ x - x0)), written as a continuum law at a point.
//
//   F = R U (polar decomposition),  ε = U - I (the strain seen in the co-rotated frame),
//   W(F) = mu |U - I|² + (lambda/2) tr(U - I)²,
//   P = ∂W/∂F = R [2 mu (U - I) + lambda tr(U - I) I] = R σ_lin(U - I),
// i.e. small-strain Hooke stress on U - I, rotated back. The derivative of R drops out because
// ∂tr(RᵀF)/∂F = R (Rᵀ dR is skew and U symmetric); McAdams et al. 2011, Stomakhin et al. 2012.
// mu = E / (2(1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu)). Exact for rigid rotations, it is
// not a finite-strain model: its stress-stretch curve departs from the hyperelastic tissue's
// at large stretch, which is the point of offering it for comparison.
//
// For the element kernel (point_response.hpp) the law answers with S = F⁻¹P = U⁻¹ σ_lin(U - I)
// (symmetric: σ_lin is a polynomial in U) and its exact ∂S/∂E on Dual numbers. It has no
// volumetric split and no internal variables.
#pragma once

#include <string>
#include <vector>

#include "physics/material/point_response.hpp"
#include "physics/material/tensor.hpp"
#include "physics/material/viscoelastic.hpp"

namespace needlefem::material {

struct CorotationalLinear {
  static constexpr bool kVolumetricSplit = false;

  double youngs_modulus = 0.0;  // E, Pa
  double poisson_ratio = 0.0;   // nu < 0.5

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double lame_lambda() const {
    return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }

  template <class T>
  T energy(const Mat3<T>& F) const {
    const Mat3<T> strain = transpose(rotation_of(F)) * F - Mat3<T>::identity();
    const T tr = trace(strain);
    return T(shear_modulus()) * double_dot(strain, strain) + T(0.5 * lame_lambda()) * tr * tr;
  }

  // First Piola-Kirchhoff stress P = R σ_lin(U - I).
  template <class T>
  Mat3<T> first_piola_kirchhoff(const Mat3<T>& F) const {
    const Mat3<T> R = rotation_of(F);
    const Mat3<T> strain = transpose(R) * F - Mat3<T>::identity();
    const Mat3<T> rotated_stress =
        T(2.0 * shear_modulus()) * strain + (T(lame_lambda()) * trace(strain)) * Mat3<T>::identity();
    return R * rotated_stress;
  }

  // --- pointwise response (point_response.hpp) -----------------------------------------------
  const std::vector<PronyTerm>& prony() const {
    static const std::vector<PronyTerm> none;
    return none;
  }
  // `viscous` is unused: the law has no internal variables.
  PointResponse respond(const Mat3d& F, const ViscousStress* viscous, VoigtTangent* tangent) const;

  // --- one step from a stored state: elastic, so the state passes through ---------------------
  ViscousState initial_state() const { return {}; }
  template <class T>
  Mat3<T> second_pk(const Mat3<T>& F, const ViscousState&, double) const {
    return inverse(F) * first_piola_kirchhoff(F);
  }
  ViscousState advance(const Mat3d&, const ViscousState& old, double) const { return old; }
  double instantaneous_shear_modulus() const { return shear_modulus(); }
  double long_term_shear_modulus() const { return shear_modulus(); }
  // The law and its constants, for logs and output headers.
  std::string description() const;
};

}  // namespace needlefem::material
