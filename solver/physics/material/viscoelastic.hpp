// Prony-series viscoelasticity on the isochoric second Piola-Kirchhoff stress, as a decorator
// around any isochoric elastic law (one with `stress(C)` giving S⁰_iso = 2 ∂W_iso/∂C).
// Internal-variable form (Simo 1987, CMAME 60:153; Holzapfel 2000 §6.10):
//
//   S_iso = S⁰_iso(C) - Σ_i Q_i,     dQ_i/dt = (g_i S⁰_iso - Q_i) / τ_i,   Q_i(0) = 0.
//
// The g_i are fractions of the INSTANTANEOUS modulus: a sudden load gives S⁰_iso, a held one
// relaxes to g∞ S⁰_iso with g∞ = 1 - Σ g_i (so the long-term shear modulus is g∞ mu0).
//
// Two ways to integrate, which tests check against each other:
//  * The ODE right-hand side and its derivatives, for an integrator (IDA) that keeps Q_i in its
//    state vector:  ∂(dQ_i/dt)/∂Q_i = -1/τ_i,  ∂(dQ_i/dt)/∂E = (g_i/τ_i) ∂S⁰_iso/∂E.
//  * One step of length Δt (Simo's exponential recursion): exact when S⁰_iso varies linearly in
//    time over the step. With x = Δt/τ_i, e_i = exp(-x), h_i = (1 - e_i)/x,
//      Q_i⁺ = e_i Q_i + g_i [(1 - h_i) S⁰⁺ + (h_i - e_i) S⁰],
//    derived from Q_i = g_i S⁰ - H_i, H_i(t) = g_i ∫ exp(-(t-s)/τ_i) dS⁰/ds ds, whose update
//    for linear S⁰ is H_i⁺ = e_i H_i + g_i h_i (S⁰⁺ - S⁰). Δt → 0 gives the instantaneous
//    (elastic) response, Δt = +inf the fully relaxed one; both are valid arguments.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "physics/material/tensor.hpp"

namespace needlefem::material {

// One term of the series and its rate equation, the only place it is written: the DAE
// residual, the Newton matrix and its condensation all take it from here.
struct PronyTerm {
  double g = 0.0;      // relative modulus (fraction of the instantaneous one)
  double tau_s = 1.0;  // relaxation time, s

  // dQ_i/dt = (g_i S⁰_iso - Q_i)/τ_i, for one component of S⁰_iso and Q_i.
  double rate(double elastic_stress, double q) const { return (g * elastic_stress - q) / tau_s; }
  // ∂(dQ_i/dt)/∂Q_i = -1/τ_i (times the identity: no coupling between terms or components).
  double rate_slope() const { return -1.0 / tau_s; }
  // ∂(dQ_i/dt)/∂S⁰_iso = g_i/τ_i, so ∂(dQ_i/dt)/∂E = (g_i/τ_i) ∂S⁰_iso/∂E.
  double rate_gain() const { return g / tau_s; }
};

// The factor of ∂S⁰_iso/∂E left in a Newton matrix J = ∂F/∂y + c_j ∂F/∂y' once the Q_i are
// condensed out: with J_QQ = c_j - rate_slope and J_Qu = -rate_gain ∂S⁰_iso/∂E B,
//   1 - Σ_i rate_gain_i / (c_j - rate_slope_i) = 1 - Σ_i g_i/(1 + c_j τ_i)
// (c_j = +inf: 1, the instantaneous response; c_j = 0: g∞, the relaxed one).
inline double condensed_fraction(const std::vector<PronyTerm>& terms, double cj) {
  double fraction = 1.0;
  if (std::isinf(cj)) return fraction;
  for (const auto& term : terms) fraction -= term.g / (1.0 + cj * term.tau_s);
  return fraction;
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

  // --- ODE form ------------------------------------------------------------------------------
  // S_iso = S⁰_iso - Σ Q_i for given internal variables.
  template <class T>
  Mat3<T> stress(const Mat3<T>& C, const std::vector<Mat3d>& q) const {
    Mat3<T> s = elastic.stress(C);
    for (const auto& q_i : q) s -= lift<T>(q_i);
    return s;
  }
  // dQ_i/dt for all terms (PronyTerm::rate, component by component).
  std::vector<Mat3d> viscous_rate(const Mat3d& C, const std::vector<Mat3d>& q) const {
    const Mat3d s0 = elastic.stress(C);
    std::vector<Mat3d> rate(terms.size());
    for (std::size_t i = 0; i < terms.size(); ++i)
      for (int n = 0; n < 9; ++n) rate[i].a[n] = terms[i].rate(s0.a[n], q[i].a[n]);
    return rate;
  }
  // ∂(dQ_i/dt)/∂Q_i, times the identity.
  double viscous_rate_dq(std::size_t i) const { return terms[i].rate_slope(); }
  // ∂(dQ_i/dt)/∂E = (g_i/τ_i) ∂S⁰_iso/∂E.
  Tensor4 viscous_rate_de(const Mat3d& C, std::size_t i) const {
    Tensor4 d = elastic_tangent(C);
    for (auto& v : d.a) v *= terms[i].rate_gain();
    return d;
  }
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
    Mat3<T> s = s0;
    for (std::size_t i = 0; i < terms.size(); ++i) s -= stepped_q(i, s0, old, dt);
    return s;
  }
  // Consistent tangent ∂S_iso/∂E of stepped_stress (the isochoric block of a mixed element):
  // [1 - Σ g_i (1 - h_i)] ∂S⁰_iso/∂E, computed as the exact derivative of the update.
  Tensor4 stepped_tangent(const Mat3d& C, const ViscousState& old, double dt) const {
    return green_strain_jacobian(C, [&](const Mat3<Dual>& c) { return stepped_stress(c, old, dt); });
  }
  ViscousState advance(const Mat3d& C, const ViscousState& old, double dt) const {
    ViscousState next{std::vector<Mat3d>(terms.size()), elastic.stress(C)};
    for (std::size_t i = 0; i < terms.size(); ++i) next.q[i] = stepped_q(i, next.elastic_stress, old, dt);
    return next;
  }

 private:
  template <class T>
  Mat3<T> stepped_q(std::size_t i, const Mat3<T>& s0_new, const ViscousState& old, double dt) const {
    const double x = dt / terms[i].tau_s;
    const double e = std::exp(-x);
    const double h = x > 0.0 ? -std::expm1(-x) / x : 1.0;  // (1 - e)/x -> 1 as x -> 0, 0 as x -> inf
    return lift<T>(e * old.q[i] + terms[i].g * (h - e) * old.elastic_stress) + (terms[i].g * (1.0 - h)) * s0_new;
  }
};

}  // namespace needlefem::material
