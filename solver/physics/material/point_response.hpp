// What a material law gives the element kernel at one quadrature point, and the Voigt form the
// kernel works in. Every law (polynomial_tissue.hpp, corotational.hpp) provides
//
//   static constexpr bool kVolumetricSplit;   // W = W_iso(C̄) + U(J) with U handled apart
//   const std::vector<PronyTerm>& prony() const;   // empty for laws without internal variables
//   PointResponse respond(const Mat3d& F, const ViscousStress* viscous, VoigtTangent* tangent) const;
//   VolumetricResponse volumetric_response(double J) const;   // split laws only
//
// `viscous` is the Prony part of a step's stress at the point (ViscousStress, below), or nullptr
// for the elastic response S⁰_iso. The optional `tangent` receives ∂S⁰_iso/∂E for a split law
// (the part a step scales by its elastic_fraction, viscoelastic.hpp), ∂S/∂E for the others, and
// is skipped for nullptr (a residual, the hot loop, wants none).
// The element kernel calls nothing else of a law, so a new law is a new file with these members
// plus its entry in material.hpp's MaterialLaw (which checks them with PointwiseLaw, below).
//
// Voigt order (11, 22, 33, 23, 13, 12); strains carry ENGINEERING shear, so S:δE = S_v·δE_v and
// the tangent's shear columns are ∂S/∂γ.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <vector>

#include "physics/material/tensor.hpp"
#include "physics/material/viscoelastic.hpp"

namespace needlefem::material {

constexpr int kVoigt = 6;  // components of a symmetric tensor in Voigt form
using Voigt = std::array<double, kVoigt>;
using VoigtTangent = std::array<double, kVoigt * kVoigt>;  // row-major, D(m, n) = ∂S_m/∂E_n

inline constexpr std::array<int, kVoigt> kVoigtRow{0, 1, 2, 1, 0, 0};
inline constexpr std::array<int, kVoigt> kVoigtColumn{0, 1, 2, 2, 2, 1};

inline Voigt to_voigt(const Mat3d& s) {
  Voigt v{};
  for (int m = 0; m < kVoigt; ++m) v[m] = s(kVoigtRow[m], kVoigtColumn[m]);
  return v;
}

inline Mat3d from_voigt(const double* v) {
  Mat3d s;
  for (int m = 0; m < kVoigt; ++m) {
    s(kVoigtRow[m], kVoigtColumn[m]) = v[m];
    s(kVoigtColumn[m], kVoigtRow[m]) = v[m];
  }
  return s;
}

// D(m, n) = ∂S_m/∂E_n with engineering shear columns: the Tensor4 of a symmetric-direction
// jacobian already holds ∂S_ij/∂γ_kl in its (k, l) slot for k != l (direction E_kl = E_lk = 1/2).
inline VoigtTangent to_voigt(const Tensor4& d) {
  VoigtTangent v{};
  for (int m = 0; m < kVoigt; ++m)
    for (int n = 0; n < kVoigt; ++n)
      v[m * kVoigt + n] = d(kVoigtRow[m], kVoigtColumn[m], kVoigtRow[n], kVoigtColumn[n]);
  return v;
}

// ∂S_IJ/∂E_KL of a stress given as a function of F (minor symmetric in KL). A symmetric strain
// direction dE is produced by dF = F^-T dE (then dC = 2 dE), so the derivative of S(F) along
// F^-T dE is ∂S/∂E : dE. The jacobian is seeded at C (its value part is unused) only to
// generate the symmetric directions dE.
template <class StressOfF>
Tensor4 green_strain_tangent(const Mat3d& F, StressOfF&& stress_of_f) {
  const Mat3d F_inverse_transpose = transpose(inverse(F));
  return directional_jacobian(right_cauchy_green(F), true, [&](const Mat3<Dual>& seeded_c) {
    return stress_of_f(seeded(F, F_inverse_transpose * derivative_of(seeded_c)));
  });
}

// U(J), p = U'(J) and U''(J) of a split law: p is the mean Cauchy stress of the volumetric part
// (tension positive), U'' its slope, which a mixed element needs for its pressure equation.
struct VolumetricResponse {
  double energy = 0.0;    // U, Pa
  double pressure = 0.0;  // U'(J), Pa
  double slope = 0.0;     // U''(J), Pa
};

// A material point's Prony history in Voigt form, the stored state of the tissue's viscous
// stresses: Q_1 ... Q_m, then the elastic stress S⁰_iso at the same time (the recursion needs
// its increment).
inline std::size_t prony_history_size(std::size_t terms) { return (terms + 1) * kVoigt; }

// The Prony part of a step's stress at a point: S_iso = elastic_fraction S⁰_iso - history.
struct ViscousStress {
  double elastic_fraction = 1.0;
  Mat3d history;
};

// What a step of `step` subtracts from elastic_fraction S⁰⁺ at a point whose history is `history`:
// Σ_i decay_i Q_i + old_gain S⁰ (PronyStep).
inline ViscousStress viscous_stress(const PronyStep& step, const double* history) {
  const std::size_t terms = step.terms.size();
  Voigt h{};
  for (int m = 0; m < kVoigt; ++m) h[m] = step.old_gain * history[terms * kVoigt + m];
  for (std::size_t i = 0; i < terms; ++i)
    for (int m = 0; m < kVoigt; ++m) h[m] += step.terms[i].decay * history[i * kVoigt + m];
  return {step.elastic_fraction, from_voigt(h.data())};
}

// The history after the step, from the elastic stress S⁰⁺ at its end.
inline void advance_history(const PronyStep& step, const Voigt& elastic_stress, double* history) {
  const std::size_t terms = step.terms.size();
  double* old_elastic = history + terms * kVoigt;
  for (std::size_t i = 0; i < terms; ++i)
    for (int m = 0; m < kVoigt; ++m) {
      double& q = history[i * kVoigt + m];
      q = step.terms[i].decay * q + step.terms[i].old_gain * old_elastic[m] + step.terms[i].new_gain * elastic_stress[m];
    }
  for (int m = 0; m < kVoigt; ++m) old_elastic[m] = elastic_stress[m];
}

struct PointResponse {
  // Second Piola-Kirchhoff stress carried by the strain operator: elastic_fraction S⁰_iso -
  // history for a split law (the volumetric part comes apart, below), all of S for the others.
  Mat3d stress;
  // Split laws: S⁰_iso, from which a step advances the point's history (advance_history).
  Mat3d elastic_stress;
  // Instantaneous strain-energy density, Pa: W_iso for a split law (Q not counted), else W.
  double energy = 0.0;
  // Split laws: U, U'(J), U''(J) at the point's J = det F.
  VolumetricResponse volumetric;
};

template <class Law>
concept PointwiseLaw = requires(const Law& law, const Mat3d& F, const ViscousStress* viscous, VoigtTangent* tangent) {
  { Law::kVolumetricSplit } -> std::convertible_to<bool>;
  { law.prony() } -> std::same_as<const std::vector<PronyTerm>&>;
  { law.respond(F, viscous, tangent) } -> std::same_as<PointResponse>;
} && (!Law::kVolumetricSplit || requires(const Law& law, double J) {
  { law.volumetric_response(J) } -> std::same_as<VolumetricResponse>;
});

}  // namespace needlefem::material
