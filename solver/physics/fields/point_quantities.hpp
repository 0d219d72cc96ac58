// What needle designers read off the tissue at one material point (quadrature point), from the
// deformation gradient F, its rate Ḟ and the stress.
//
//   Cauchy stress      σ = J⁻¹ F S Fᵀ, J = det F, with the total second Piola-Kirchhoff stress
//                      S = S⁰_iso - Σ_i Q_i + J p C⁻¹  (physics/elements/tet_element.hpp), so
//                      σ = J⁻¹ F (S⁰_iso - Σ Q_i) Fᵀ + p I (mixed element: the element's
//                      pressure unknown, U'(θ) at convergence; displacement element: U'(J) at
//                      the point).
//                      Laws without the split give σ = J⁻¹ P Fᵀ from their P(F).
//   von Mises          σ_vM = sqrt(3/2 s:s), s = σ - tr(σ)/3 I.
//   pressure           -tr(σ)/3 (positive in compression).
//   log strain         ln V = 1/2 ln b, b = F Fᵀ (Hencky strain, spatial); its principal values
//                      are ln λ_i with λ_i² the eigenvalues of b.
//   strain rate        D = sym(L), L = Ḟ F⁻¹ (rate of deformation; Holzapfel 2000 §2.7);
//                      reported as its largest eigenvalue and the equivalent rate
//                      sqrt(2/3 D:D) (= |rate| in incompressible uniaxial stretching).
// Principal values of symmetric 3x3 tensors come from the trigonometric closed form of the
// cubic's roots (Smith 1961, Comm. ACM 4:168).
#pragma once

#include <array>

#include "physics/material/tensor.hpp"

namespace needlefem::fields {

using material::Mat3d;

// Eigenvalues of a symmetric tensor, ascending.
std::array<double, 3> symmetric_eigenvalues(const Mat3d& symmetric);

struct PointQuantities {
  Mat3d cauchy_stress;            // Pa
  double von_mises = 0.0;         // Pa
  double max_principal_stress = 0.0;  // Pa
  double pressure = 0.0;          // Pa, -tr(σ)/3
  double max_log_strain = 0.0;    // largest principal value of ln V
  double max_strain_rate = 0.0;   // 1/s, largest eigenvalue of D
  double equivalent_strain_rate = 0.0;  // 1/s, sqrt(2/3 D:D)
};

// From F, Ḟ and the Cauchy stress σ already formed by the caller.
PointQuantities point_quantities(const Mat3d& F, const Mat3d& F_rate, const Mat3d& cauchy_stress);

// σ = J⁻¹ F S Fᵀ for a second Piola-Kirchhoff stress S (J = det F).
Mat3d push_forward(const Mat3d& F, const Mat3d& second_pk);

}  // namespace needlefem::fields
