// Total-Lagrangian tetrahedral elements (TET4, TET10) for the decoupled hyper-viscoelastic
// tissue of physics/material, in two formulations.
//
// Notation: X reference, F = I + Σ_a u_a ⊗ G_a with G_a = ∂N_a/∂X, J = det F, C = FᵀF,
// E = (C - I)/2. Voigt order (11, 22, 33, 23, 13, 12) with ENGINEERING shear for strains, so
// S:δE = S_v·δE_v. B_q (6 x 3n) maps nodal displacement variations to δE_v at point q:
//   δE_v(a,i) = [F_i1 G_a1, F_i2 G_a2, F_i3 G_a3, F_i2 G_a3 + F_i3 G_a2, F_i1 G_a3 + F_i3 G_a1,
//                F_i1 G_a2 + F_i2 G_a1].
//
// Stress (physics/material/polynomial.hpp, viscoelastic.hpp; Holzapfel 2000 §6.4, §6.10):
//   S = S⁰_iso(C) - Σ_i Q_i + S_vol,   the Q_i (Prony internal variables) at the end of a step
//   from the points' histories, which are element inputs (ViscousStep, below):
//   S_iso = a S⁰_iso(C) - H,   a = PronyStep::elastic_fraction, H from the history.
//
// DISPLACEMENT formulation (TET4/TET10, locks as K/mu grows):
//   Π_e = ∫ W_iso(C) dV + ∫ U(J) dV,  U = K/2 (J - 1)².
// MEAN-DILATATION formulation (Simo, Taylor & Pister 1985, CMAME 51:177; Bonet & Wood,
//   Nonlinear Continuum Mechanics for FEA, 2nd ed. §8.6): three fields u, element-constant
//   dilatation θ and pressure p; the Hu-Washizu stationarity conditions in θ and p give
//   θ = v_e/V_e (current over reference element volume) and p = U'(θ), condensed exactly at
//   element level. Equivalently F̄ = (θ/J)^(1/3) F in the energy, and because W_iso depends only
//   on C̄ = J^(-2/3) C, which F̄ and F share,
//     Π_e = ∫ W_iso(C) dV + V_e U(v_e/V_e),    v_e = ∫ J dV.
//   This is the tetrahedral analogue of Abaqus C3D10H (hybrid, constant pressure) and is free of
//   volumetric locking on TET10 up to incompressibility (one constraint per element against 30
//   displacement dofs); on TET4 it is the displacement element (1 quadrature point).
//   The pressure may also be given (`given_pressure`, the two-field u-p form: p_e an unknown of
//   its own with the equation p_e = U'(θ), mechanics/mechanics_system.hpp): the residual and the
//   tangent's p ∂²v_e/∂u² term then use the given p, and ElementResult reports U'(θ), ∂v_e/∂u
//   and U''(θ)/V_e for that equation.
//
// Residual (r_a = ∂Π_e/∂u_a for the elastic part; the history enters through S):
//   r = Σ_q w_q B_qᵀ S_iso,v(q) + volumetric part,
//   volumetric part  displacement: Σ_q w_q U'(J_q) ∂J_q/∂u,   mixed: U'(θ) ∂v_e/∂u,
//   with ∂J/∂u_ai = J n_ai, n_ai = G_aJ F⁻¹_Ji (= ∂N_a/∂x_i), v_e = Σ_q w_q J_q.
// Tangent (consistent with the step's recursion):
//   K = Σ_q w_q [ a B_qᵀ D⁰ B_q + δ_ik G_a·S_iso G_b ] + volumetric part,
//   D⁰ = ∂S⁰_iso/∂E (6 x 6, exact via dual numbers), a = 1 without a ViscousStep,
//   ∂²J/∂u_ai∂u_bk = J (n_ai n_bk - n_ak n_bi),
//   displacement: Σ_q w_q [U''(J) J² n n + U'(J) J (n_ai n_bk - n_ak n_bi)],
//   mixed: U'(θ) ∂²v_e/∂u² + U''(θ)/V_e (∂v_e/∂u)(∂v_e/∂u)ᵀ.
//
// The kernel asks the law for nothing but its pointwise response (physics/material/
// point_response.hpp): S, S⁰_iso, D⁰, W_iso, U(J) with its slopes. Laws without the isochoric/volumetric split (co-rotational linear) give
// all of S and ∂S/∂E there and use the displacement formulation only; they carry no internal
// variables. The kernel is instantiated per law (std::visit once per element, not per point).
//
// Quadrature: TET10 the 4-point degree-2 rule (Keast; Abaqus' C3D10/C3D10H rule), exact for the
// stiffness of straight-sided elements and enough for optimal convergence of quadratic elements;
// TET4 the centroid. Fewer points than tet_geometry's degree-5 rule keep the viscous state small.
#pragma once

#include <array>
#include <vector>

#include "case/specs/mechanics_spec.hpp"
#include "model/tet_geometry.hpp"
#include "physics/material/material.hpp"

namespace needlefem::elements {

using Formulation = ElementFormulation;  // element.formulation (case/specs/mechanics_spec.hpp)

using material::kVoigt;

const std::vector<QuadraturePoint>& element_quadrature(int nodes_per_tet);

// Reference-configuration data of one element.
struct ElementGeometry {
  int nodes = 0;                // 4 or 10
  int points = 0;               // quadrature points
  std::vector<double> gradient; // points x nodes x 3: G_a = ∂N_a/∂X at each point
  std::vector<double> weight;   // points: quadrature weight times det(∂X/∂ξ)
  double volume = 0.0;          // V_e
  const double* gradient_at(int q) const { return gradient.data() + static_cast<std::size_t>(q) * nodes * 3; }
};

// From node coordinates (nodes x 3, metres). Throws std::runtime_error for a degenerate or
// inverted reference element.
ElementGeometry element_geometry(int nodes_per_tet, const double* coordinates);

// sum += ∂v/∂X = Σ_a v_a ⊗ G_a at point q of an element whose node values are `values`
// (nodes x 3): F from the identity and the displacements, Ḟ from zero and the velocities.
void add_field_gradient(const ElementGeometry& geometry, int q, const double* values, material::Mat3d& sum);

// What an evaluation reports at each quadrature point, for output fields and the points'
// viscous histories.
struct PointResult {
  std::array<double, 9> deformation_gradient{};           // F, row-major
  material::Voigt stress{};                               // S carried by B_q (S_iso or all of S)
  material::Voigt elastic_stress{};                       // S⁰_iso (split laws), to advance a history
  material::VoigtTangent elastic_tangent{};               // D⁰ = ∂S⁰_iso,v/∂E_v (with tangent)
  double pressure = 0.0;                                  // split laws: U'(J) at the point
};

constexpr int kMaxElementDofs = 30;    // TET10
constexpr int kMaxElementPoints = 4;   // TET10's rule

// Fixed-size arrays, not vectors, for what every residual needs: four heap allocations per
// element and residual had cost a quarter of a residual's time.
struct ElementResult {
  bool inverted = false;                             // det F <= 0 at some point (or θ <= 0): nothing else is valid
  std::array<double, kMaxElementDofs> residual{};   // the first 3n: internal force
  std::vector<double> stiffness;                     // 3n x 3n row-major (when requested)
  std::array<PointResult, kMaxElementPoints> points{};    // the first geometry.points
  double pressure = 0.0;            // mixed: U'(θ); displacement: volume average of U'(J)
  double energy = 0.0;              // elastic energy of the element (instantaneous, Q not counted)
  // Mixed form only: U'(θ), ∂v_e/∂u (3n) and U''(θ)/V_e, for an element pressure that is an
  // unknown of its own.
  double volume_pressure = 0.0;
  std::array<double, kMaxElementDofs> volume_gradient{};
  double pressure_stiffness = 0.0;
};

// A Prony step for one element: the step's coefficients (material::prony_step) and the points'
// histories at its start, points x material::prony_history_size values.
struct ViscousStep {
  const material::PronyStep* step = nullptr;
  const double* history = nullptr;
};

class TetElementKernel {
 public:
  // Throws std::invalid_argument for the mean-dilatation form with a law that has no
  // isochoric/volumetric split.
  TetElementKernel(const material::Material& material, Formulation formulation);

  Formulation formulation() const { return formulation_; }
  // Prony terms of the material (0 for elastic laws).
  int prony_terms() const { return static_cast<int>(material_.prony().size()); }
  const std::vector<material::PronyTerm>& prony() const { return material_.prony(); }

  // displacement: 3n values; viscous: the step the stress is taken at the end of, or nullptr for
  // the elastic response (Q = 0); given_pressure: the mixed element's p, or nullptr for p = U'(θ).
  ElementResult evaluate(const ElementGeometry& geometry, const double* displacement, const ViscousStep* viscous,
                         bool with_tangent, const double* given_pressure = nullptr) const;

 private:
  template <class Law>
  ElementResult evaluate_law(const Law& law, const ElementGeometry& geometry, const double* displacement,
                             const ViscousStep* viscous, bool with_tangent, const double* given_pressure) const;

  material::Material material_;
  Formulation formulation_;
};

// B_q of the header comment (6 x 3n, row-major) at deformation gradient F and gradients G.
void green_strain_operator(const std::array<double, 9>& F, const double* gradient, int nodes, double* B);
// The two products with B_q that residuals and condensation need, without forming B_q (the
// hot loops of a Newton-Krylov solve call them for every point of every element); F and the
// gradients in double, sums in double:
//   out += w B_qᵀ s,  i.e. out_a += w F S G_a  (S the symmetric tensor of the Voigt stress s);
template <class Real>
void add_green_strain_transpose(const std::array<Real, 9>& F, const Real* gradient, int nodes,
                                const std::array<double, kVoigt>& s, double w, double* out) {
  const double S[9] = {s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2]};
  double FS[9];
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      FS[3 * i + J] = w * (F[3 * i] * S[J] + F[3 * i + 1] * S[3 + J] + F[3 * i + 2] * S[6 + J]);
  for (int a = 0; a < nodes; ++a) {
    const Real* G = gradient + 3 * a;
    for (int i = 0; i < 3; ++i) out[3 * a + i] += FS[3 * i] * G[0] + FS[3 * i + 1] * G[1] + FS[3 * i + 2] * G[2];
  }
}

//   B_q u = δE_v = Voigt of sym(Fᵀ H), H = Σ_a u_a ⊗ G_a (engineering shear).
template <class Real>
std::array<double, kVoigt> green_strain_variation(const std::array<Real, 9>& F, const Real* gradient, int nodes,
                                                  const double* u) {
  double H[9] = {};
  for (int a = 0; a < nodes; ++a) {
    const Real* G = gradient + 3 * a;
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) H[3 * i + J] += u[3 * a + i] * G[J];
  }
  double A[9];  // Fᵀ H
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J) A[3 * I + J] = F[I] * H[J] + F[3 + I] * H[3 + J] + F[6 + I] * H[6 + J];
  return {A[0], A[4], A[8], A[5] + A[7], A[2] + A[6], A[1] + A[3]};
}

}  // namespace needlefem::elements
