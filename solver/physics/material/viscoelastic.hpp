// Prony-series viscoelasticity on the isochoric second Piola-Kirchhoff stress, as a decorator
// around any isochoric elastic law (one with `stress(C)` giving S⁰_iso = 2 ∂W_iso/∂C).
// Internal-variable form (Simo 1987, CMAME 60:153; Holzapfel 2000 §6.10):
//
//   S_iso = S⁰_iso(C) - Σ_i Q_i,     dQ_i/dt = (g_i S⁰_iso - Q_i) / τ_i,   Q_i(0) = 0.
//
// The g_i are fractions of the INSTANTANEOUS modulus: a sudden load gives S⁰_iso, a held one
// relaxes to g∞ S⁰_iso with g∞ = 1 - Σ g_i (so the long-term shear modulus is g∞ mu0).
//
// Integrated by Simo's exponential recursion over each step of length Δt, exact when S⁰_iso
// varies linearly in time over the step. With x = Δt/τ_i, e_i = exp(-x), h_i = (1 - e_i)/x,
//   Q_i⁺ = e_i Q_i + g_i [(1 - h_i) S⁰⁺ + (h_i - e_i) S⁰],
// derived from Q_i = g_i S⁰ - H_i, H_i(t) = g_i ∫ exp(-(t-s)/τ_i) dS⁰/ds ds, whose update for
// linear S⁰ is H_i⁺ = e_i H_i + g_i h_i (S⁰⁺ - S⁰). Δt → 0 gives the instantaneous (elastic)
// response, Δt = +inf the fully relaxed one; both are valid arguments. The stress after a step
// is linear in S⁰⁺ (PronyStep), which is what lets the tissue's DAE keep only displacements and
// pressures as unknowns, the Q_i advanced at each accepted step (mechanics_system.hpp), as
// Abaqus and FEBio do.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "physics/material/tensor.hpp"

namespace needlefem::material {

struct PronyTerm {
  double g = 0.0;      // relative modulus (fraction of the instantaneous one)
  double tau_s = 1.0;  // relaxation time, s
};

// Simo's recursion over one step of length dt as the coefficients every point shares, the only
// place they are computed:
//   Q_i⁺ = decay_i Q_i + old_gain_i S⁰ + new_gain_i S⁰⁺,
//   decay_i = e_i,  old_gain_i = g_i (h_i - e_i),  new_gain_i = g_i (1 - h_i),
// so the stress after the step, S_iso⁺ = S⁰⁺ - Σ_i Q_i⁺, is
//   elastic_fraction S⁰⁺ - (Σ_i decay_i Q_i + old_gain S⁰),
// elastic_fraction = 1 - Σ_i new_gain_i (1 at dt = 0, g∞ at dt = inf), old_gain = Σ_i old_gain_i.
// ∂S_iso⁺/∂E = elastic_fraction ∂S⁰_iso/∂E: the consistent tangent of a step.
struct PronyStep {
  struct Term {
    double decay = 1.0, old_gain = 0.0, new_gain = 0.0;
  };
  std::vector<Term> terms;
  double elastic_fraction = 1.0;
  double old_gain = 0.0;
};

inline PronyStep prony_step(const std::vector<PronyTerm>& terms, double dt) {
  PronyStep step;
  for (const auto& term : terms) {
    const double x = dt / term.tau_s;
    const double e = std::exp(-x);
    const double h = x > 0.0 ? -std::expm1(-x) / x : 1.0;  // (1 - e)/x -> 1 as x -> 0, 0 as x -> inf
    step.terms.push_back({e, term.g * (h - e), term.g * (1.0 - h)});
    step.elastic_fraction -= step.terms.back().new_gain;
    step.old_gain += step.terms.back().old_gain;
  }
  return step;
}

// Internal state of a viscoelastic material point: one Q_i per Prony term, and the elastic
// isochoric stress S⁰_iso at the time of the state (the recursion needs its increment).
struct ViscousState {
  std::vector<Mat3d> q;
  Mat3d elastic_stress;
};

template <class Elastic>
struct Viscoelastic {
  Elastic elastic;
  std::vector<PronyTerm> terms;

  double long_term_fraction() const {
    double g_infinity = 1.0;
    for (const auto& term : terms) g_infinity -= term.g;
    return g_infinity;
  }

  ViscousState initial_state() const { return {std::vector<Mat3d>(terms.size()), Mat3d{}}; }

  // ∂S⁰_iso/∂E (E = (C - I)/2, so dC = 2 dE).
  Tensor4 elastic_tangent(const Mat3d& C) const {
    return green_strain_jacobian(C, [&](const Mat3<Dual>& c) { return elastic.stress(c); });
  }

  // --- one-step form ---------------------------------------------------------------------------
  // S_iso after a step of length dt from `old` to right Cauchy-Green C (templated so the
  // consistent tangent is its exact derivative).
  template <class T>
  Mat3<T> stepped_stress(const Mat3<T>& C, const ViscousState& old, double dt) const {
    const Mat3<T> s0 = elastic.stress(C);
    const PronyStep step = prony_step(terms, dt);
    Mat3<T> s = s0;
    for (std::size_t i = 0; i < terms.size(); ++i) s -= stepped_q(step.terms[i], s0, old, i);
    return s;
  }
  // Consistent tangent ∂S_iso/∂E of stepped_stress (the isochoric block of a mixed element):
  // [1 - Σ g_i (1 - h_i)] ∂S⁰_iso/∂E, computed as the exact derivative of the update.
  Tensor4 stepped_tangent(const Mat3d& C, const ViscousState& old, double dt) const {
    return green_strain_jacobian(C, [&](const Mat3<Dual>& c) { return stepped_stress(c, old, dt); });
  }
  ViscousState advance(const Mat3d& C, const ViscousState& old, double dt) const {
    ViscousState next{std::vector<Mat3d>(terms.size()), elastic.stress(C)};
    const PronyStep step = prony_step(terms, dt);
    for (std::size_t i = 0; i < terms.size(); ++i) next.q[i] = stepped_q(step.terms[i], next.elastic_stress, old, i);
    return next;
  }

 private:
  template <class T>
  Mat3<T> stepped_q(const PronyStep::Term& step, const Mat3<T>& s0_new, const ViscousState& old, std::size_t i) const {
    return lift<T>(step.decay * old.q[i] + step.old_gain * old.elastic_stress) + step.new_gain * s0_new;
  }
};

}  // namespace needlefem::material
