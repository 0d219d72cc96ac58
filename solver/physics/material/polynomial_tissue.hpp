// The brain tissue law of paper 001: the decoupled polynomial (N = 2) isochoric energy wrapped
// in a Prony series, plus a quadratic volumetric energy,
//
//   S = S_iso + S_vol,   S_iso = S⁰_iso(C) - Σ_i Q_i   (viscoelastic.hpp; Holzapfel 2000 §6.10),
//   S⁰_iso = 2 ∂W_iso/∂C (polynomial.hpp),   S_vol = J U'(J) C⁻¹,   U = K/2 (J - 1)².
//
// Its hyperelastic constants are INSTANTANEOUS moduli; the long-term shear modulus is
// g∞ · 2 (C10 + C01). The law answers in two forms:
//  * the pointwise response of point_response.hpp, for the element kernel, whose caller keeps
//    the points' histories: elastic_fraction S⁰_iso - history, S⁰_iso, ∂S⁰_iso/∂E, W_iso, U and
//    its slopes;
//  * one step of length dt from a stored state (Simo's recursion), for the material-point
//    driver: second_pk, advance.
// Tangents are exact derivatives on Dual numbers (tensor.hpp).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "physics/material/point_response.hpp"
#include "physics/material/polynomial.hpp"
#include "physics/material/viscoelastic.hpp"

namespace needlefem::material {

struct PolynomialTissue {
  static constexpr bool kVolumetricSplit = true;

  Viscoelastic<PolynomialIsochoric> isochoric;
  VolumetricQuadratic volumetric;

  // --- pointwise response (point_response.hpp) -----------------------------------------------
  const std::vector<PronyTerm>& prony() const { return isochoric.terms; }
  PointResponse respond(const Mat3d& F, const ViscousStress* viscous, VoigtTangent* tangent) const;
  VolumetricResponse volumetric_response(double J) const {
    return {volumetric.energy(J), volumetric.pressure(J), volumetric.pressure_derivative()};
  }

  // --- one step from a stored state --------------------------------------------------------------
  ViscousState initial_state() const { return isochoric.initial_state(); }
  // S_iso after a step of dt from `old` (templated so tangents are its exact derivative).
  template <class T>
  Mat3<T> isochoric_second_pk(const Mat3<T>& F, const ViscousState& old, double dt) const {
    return isochoric.stepped_stress(right_cauchy_green(F), old, dt);
  }
  template <class T>
  Mat3<T> second_pk(const Mat3<T>& F, const ViscousState& old, double dt) const {
    const Mat3<T> C = right_cauchy_green(F);
    return isochoric.stepped_stress(C, old, dt) + volumetric.stress(C);
  }
  ViscousState advance(const Mat3d& F, const ViscousState& old, double dt) const {
    return isochoric.advance(right_cauchy_green(F), old, dt);
  }
  // Instantaneous W(F) = W_iso + U(J).
  double energy(const Mat3d& F) const {
    const Mat3d C = right_cauchy_green(F);
    return isochoric.elastic.energy(C) + volumetric.energy(std::sqrt(det(C)));
  }
  double instantaneous_shear_modulus() const { return isochoric.elastic.initial_shear_modulus(); }
  double long_term_shear_modulus() const {
    return isochoric.long_term_fraction() * isochoric.elastic.initial_shear_modulus();
  }
  // The law and all its constants, for logs and output headers.
  std::string description() const;
};

}  // namespace needlefem::material
