// Decoupled (isochoric/volumetric) polynomial hyperelasticity, N = 2.
//
//   W(C) = W_iso(Ī1, Ī2) + U(J),   J = det F = sqrt(det C),  C̄ = J^(-2/3) C,
//   Ī1 = tr C̄ = J^(-2/3) I1,       Ī2 = ½[(tr C̄)² - tr(C̄²)] = J^(-4/3) I2.
//
//   W_iso = C10 (Ī1-3) + C01 (Ī2-3) + C20 (Ī1-3)² + C11 (Ī1-3)(Ī2-3) + C02 (Ī2-3)²
//   (Mooney-Rivlin: C20 = C11 = C02 = 0; neo-Hookean: also C01 = 0; initial shear modulus
//   mu0 = 2 (C10 + C01)).  Abaqus "POLYNOMIAL, N=2"; Holzapfel 2000 §6.5.
//
//   Isochoric second Piola-Kirchhoff stress (Holzapfel 2000 eq. 6.89 written out):
//     S_iso = 2 ∂W_iso/∂C = 2 [W1 ∂Ī1/∂C + W2 ∂Ī2/∂C],  Wa = ∂W_iso/∂Īa,
//     ∂Ī1/∂C = J^(-2/3) [I - (I1/3) C⁻¹],
//     ∂Ī2/∂C = J^(-4/3) [I1 I - C - (2/3) I2 C⁻¹].
//   Volumetric part, U(J) = K/2 (J - 1)²  (Abaqus' form with D1 = 2/K):
//     p(J) = U'(J) = K (J - 1)   (mean Cauchy stress of the volumetric part, tension positive),
//     U''(J) = K,   S_vol = J p C⁻¹.
//   A mixed displacement-pressure element uses S_iso (and its tangent) with its own pressure
//   field and p(J), U''(J) for the constraint; a displacement element uses S_iso + S_vol.
//
// Tangents are not hand-coded: the laws are templates on the scalar and are differentiated
// exactly with Dual numbers (tensor.hpp); tests check them against finite differences.
#pragma once

#include <utility>

#include "physics/material/tensor.hpp"

namespace needlefem::material {

struct PolynomialIsochoric {
  double c10 = 0.0, c01 = 0.0, c20 = 0.0, c11 = 0.0, c02 = 0.0;  // Pa

  double initial_shear_modulus() const { return 2.0 * (c10 + c01); }

  template <class T>
  T energy(const Mat3<T>& C) const {
    return energy(Invariants<T>(C));
  }

  // S_iso = 2 ∂W_iso/∂C.
  template <class T>
  Mat3<T> stress(const Mat3<T>& C) const {
    return stress(C, Invariants<T>(C));
  }

  // Both from one evaluation of the invariants (the residual needs both at every point).
  template <class T>
  std::pair<Mat3<T>, T> stress_and_energy(const Mat3<T>& C) const {
    const Invariants<T> inv(C);
    return {stress(C, inv), energy(inv)};
  }

 private:
  template <class T>
  struct Invariants {
    T i1, i2, j_m23, j_m43, i1_bar, i2_bar;
    explicit Invariants(const Mat3<T>& C) {
      i1 = trace(C);
      i2 = T(0.5) * (i1 * i1 - double_dot(C, transpose(C)));
      using std::cbrt;
      j_m23 = T(1.0) / cbrt(det(C));  // J^(-2/3) = (det C)^(-1/3); cbrt costs half of pow
      j_m43 = j_m23 * j_m23;
      i1_bar = j_m23 * i1;
      i2_bar = j_m43 * i2;
    }
  };

  template <class T>
  T energy(const Invariants<T>& inv) const {
    const T a = inv.i1_bar - T(3.0), b = inv.i2_bar - T(3.0);
    return T(c10) * a + T(c01) * b + T(c20) * a * a + T(c11) * a * b + T(c02) * b * b;
  }

  template <class T>
  Mat3<T> stress(const Mat3<T>& C, const Invariants<T>& inv) const {
    const T a = inv.i1_bar - T(3.0), b = inv.i2_bar - T(3.0);
    const T w1 = T(c10) + T(2.0 * c20) * a + T(c11) * b;
    const T w2 = T(c01) + T(c11) * a + T(2.0 * c02) * b;
    const Mat3<T> identity = Mat3<T>::identity();
    const Mat3<T> c_inv = inverse(C);
    const Mat3<T> d_i1_bar = inv.j_m23 * (identity - (inv.i1 / T(3.0)) * c_inv);
    const Mat3<T> d_i2_bar = inv.j_m43 * (inv.i1 * identity - C - (T(2.0) / T(3.0) * inv.i2) * c_inv);
    return T(2.0) * (w1 * d_i1_bar + w2 * d_i2_bar);
  }
};

struct VolumetricQuadratic {
  double bulk_modulus = 0.0;  // K, Pa

  template <class T>
  T energy(T J) const { return T(0.5 * bulk_modulus) * (J - T(1.0)) * (J - T(1.0)); }
  template <class T>
  T pressure(T J) const { return T(bulk_modulus) * (J - T(1.0)); }
  double pressure_derivative() const { return bulk_modulus; }  // U''(J)

  // S_vol = J p(J) C⁻¹.
  template <class T>
  Mat3<T> stress(const Mat3<T>& C) const {
    using std::sqrt;
    const T J = sqrt(det(C));
    return (J * pressure(J)) * inverse(C);
  }
};

}  // namespace needlefem::material
