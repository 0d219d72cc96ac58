// Small dense tensors for material points, templated on the scalar so the same law code runs
// on double (stress) and on Dual (exact directional derivatives, hence consistent tangents).
//
//   Mat3<T>   3x3 second-order tensor, row-major, (i, j) indexing.
//   Tensor4   fourth-order tensor A_ijkl (double), stored at ((i*3 + j)*3 + k)*3 + l.
//   Dual      forward-mode dual number v + d*eps (eps^2 = 0): f(x + eps dx) = f(x) + eps f'(x) dx,
//             so evaluating a law once on Dual inputs seeded with a direction gives the exact
//             directional derivative of its output (no truncation error, unlike finite differences).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace needlefem::material {

// --- dual numbers ---------------------------------------------------------------------------
struct Dual {
  double v = 0.0;  // value
  double d = 0.0;  // derivative along the seeded direction
  constexpr Dual() = default;
  constexpr Dual(double value, double derivative = 0.0) : v(value), d(derivative) {}
};

constexpr Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.d + b.d}; }
constexpr Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.d - b.d}; }
constexpr Dual operator-(Dual a) { return {-a.v, -a.d}; }
constexpr Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.d * b.v + a.v * b.d}; }
constexpr Dual operator/(Dual a, Dual b) { return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)}; }
inline Dual& operator+=(Dual& a, Dual b) { return a = a + b; }
inline Dual& operator-=(Dual& a, Dual b) { return a = a - b; }
inline Dual& operator*=(Dual& a, Dual b) { return a = a * b; }
inline Dual sqrt(Dual a) {
  const double r = std::sqrt(a.v);
  return {r, a.d / (2.0 * r)};
}
inline Dual pow(Dual a, double p) {
  const double r = std::pow(a.v, p);
  return {r, p * std::pow(a.v, p - 1.0) * a.d};
}
inline Dual cbrt(Dual a) {
  const double r = std::cbrt(a.v);
  return {r, a.d / (3.0 * r * r)};
}
inline Dual log(Dual a) { return {std::log(a.v), a.d / a.v}; }
inline Dual exp(Dual a) {
  const double e = std::exp(a.v);
  return {e, e * a.d};
}

inline double value_of(double x) { return x; }
inline double value_of(Dual x) { return x.v; }
// Size of a number including its derivative part: iterations on Dual must converge in both.
inline double magnitude(double x) { return std::abs(x); }
inline double magnitude(Dual x) { return std::abs(x.v) + std::abs(x.d); }

// --- second-order tensors -------------------------------------------------------------------
template <class T>
struct Mat3 {
  std::array<T, 9> a{};
  T& operator()(int i, int j) { return a[3 * i + j]; }
  const T& operator()(int i, int j) const { return a[3 * i + j]; }

  static Mat3 identity() {
    Mat3 m;
    m(0, 0) = m(1, 1) = m(2, 2) = T(1.0);
    return m;
  }
  static Mat3 diagonal(T x, T y, T z) {
    Mat3 m;
    m(0, 0) = x;
    m(1, 1) = y;
    m(2, 2) = z;
    return m;
  }
};
using Mat3d = Mat3<double>;

template <class T>
Mat3<T> operator+(const Mat3<T>& x, const Mat3<T>& y) {
  Mat3<T> r;
  for (int n = 0; n < 9; ++n) r.a[n] = x.a[n] + y.a[n];
  return r;
}
template <class T>
Mat3<T> operator-(const Mat3<T>& x, const Mat3<T>& y) {
  Mat3<T> r;
  for (int n = 0; n < 9; ++n) r.a[n] = x.a[n] - y.a[n];
  return r;
}
template <class T, class S>
  requires std::is_arithmetic_v<S> || std::is_same_v<S, T>
Mat3<T> operator*(S s, const Mat3<T>& x) {
  Mat3<T> r;
  for (int n = 0; n < 9; ++n) r.a[n] = T(s) * x.a[n];
  return r;
}
template <class T>
Mat3<T>& operator+=(Mat3<T>& x, const Mat3<T>& y) { return x = x + y; }
template <class T>
Mat3<T>& operator-=(Mat3<T>& x, const Mat3<T>& y) { return x = x - y; }

template <class T>
Mat3<T> operator*(const Mat3<T>& x, const Mat3<T>& y) {
  Mat3<T> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      T s(0.0);
      for (int k = 0; k < 3; ++k) s += x(i, k) * y(k, j);
      r(i, j) = s;
    }
  return r;
}

template <class T>
Mat3<T> transpose(const Mat3<T>& x) {
  Mat3<T> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = x(j, i);
  return r;
}
template <class T>
T trace(const Mat3<T>& x) { return x(0, 0) + x(1, 1) + x(2, 2); }
template <class T>
T det(const Mat3<T>& x) {
  return x(0, 0) * (x(1, 1) * x(2, 2) - x(1, 2) * x(2, 1)) - x(0, 1) * (x(1, 0) * x(2, 2) - x(1, 2) * x(2, 0)) +
         x(0, 2) * (x(1, 0) * x(2, 1) - x(1, 1) * x(2, 0));
}
template <class T>
Mat3<T> inverse(const Mat3<T>& x) {
  Mat3<T> r;
  r(0, 0) = x(1, 1) * x(2, 2) - x(1, 2) * x(2, 1);
  r(0, 1) = x(0, 2) * x(2, 1) - x(0, 1) * x(2, 2);
  r(0, 2) = x(0, 1) * x(1, 2) - x(0, 2) * x(1, 1);
  r(1, 0) = x(1, 2) * x(2, 0) - x(1, 0) * x(2, 2);
  r(1, 1) = x(0, 0) * x(2, 2) - x(0, 2) * x(2, 0);
  r(1, 2) = x(0, 2) * x(1, 0) - x(0, 0) * x(1, 2);
  r(2, 0) = x(1, 0) * x(2, 1) - x(1, 1) * x(2, 0);
  r(2, 1) = x(0, 1) * x(2, 0) - x(0, 0) * x(2, 1);
  r(2, 2) = x(0, 0) * x(1, 1) - x(0, 1) * x(1, 0);
  const T inv_det = T(1.0) / det(x);
  for (auto& v : r.a) v = v * inv_det;
  return r;
}
template <class T>
T double_dot(const Mat3<T>& x, const Mat3<T>& y) {
  T s(0.0);
  for (int n = 0; n < 9; ++n) s += x.a[n] * y.a[n];
  return s;
}
// Right Cauchy-Green tensor C = F^T F.
template <class T>
Mat3<T> right_cauchy_green(const Mat3<T>& F) { return transpose(F) * F; }

// Polar decomposition F = R U (det F > 0) by Higham's Newton iteration R <- (R + R^-T)/2,
// which converges quadratically to the rotation; on Dual input the derivative part converges
// with it (its update is the projection onto R·skew, exact one step after R has converged).
template <class T>
Mat3<T> rotation_of(const Mat3<T>& F) {
  Mat3<T> R = F;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Mat3<T> next = 0.5 * (R + transpose(inverse(R)));
    double change = 0.0, size = 0.0;
    for (int n = 0; n < 9; ++n) {
      change += magnitude(next.a[n] - R.a[n]);
      size += magnitude(next.a[n]);
    }
    R = next;
    if (change <= 1e-15 * size) break;
  }
  return R;
}

// Lift a double tensor into the scalar type of a computation (no derivative part).
template <class T>
Mat3<T> lift(const Mat3d& x) {
  Mat3<T> r;
  for (int n = 0; n < 9; ++n) r.a[n] = T(x.a[n]);
  return r;
}
inline Mat3d value_of(const Mat3<Dual>& x) {
  Mat3d r;
  for (int n = 0; n < 9; ++n) r.a[n] = x.a[n].v;
  return r;
}
inline Mat3d derivative_of(const Mat3<Dual>& x) {
  Mat3d r;
  for (int n = 0; n < 9; ++n) r.a[n] = x.a[n].d;
  return r;
}
// x + eps * direction.
inline Mat3<Dual> seeded(const Mat3d& x, const Mat3d& direction) {
  Mat3<Dual> r;
  for (int n = 0; n < 9; ++n) r.a[n] = Dual(x.a[n], direction.a[n]);
  return r;
}

// --- fourth-order tensors -------------------------------------------------------------------
struct Tensor4 {
  std::array<double, 81> a{};
  double& operator()(int i, int j, int k, int l) { return a[((i * 3 + j) * 3 + k) * 3 + l]; }
  double operator()(int i, int j, int k, int l) const { return a[((i * 3 + j) * 3 + k) * 3 + l]; }
};

// A_ijkl = d out_ij / d in_kl of a tensor function, from one Dual evaluation per direction.
// `symmetric_input`: the argument is symmetric (C or E); then direction kl is sym(e_k (x) e_l)
// and the result has minor symmetry in kl, the usual convention for dS/dE.
template <class Function>
Tensor4 directional_jacobian(const Mat3d& at, bool symmetric_input, Function&& function) {
  Tensor4 jacobian;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      if (symmetric_input && l < k) {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) jacobian(i, j, k, l) = jacobian(i, j, l, k);
        continue;
      }
      Mat3d direction;
      if (symmetric_input) {
        direction(k, l) += 0.5;
        direction(l, k) += 0.5;
      } else {
        direction(k, l) = 1.0;
      }
      const Mat3d derivative = derivative_of(function(seeded(at, direction)));
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) jacobian(i, j, k, l) = derivative(i, j);
    }
  return jacobian;
}

// A_ijkl = d out_ij / d E_kl of a function of C = I + 2E (minor symmetric in kl).
template <class Function>
Tensor4 green_strain_jacobian(const Mat3d& C, Function&& function_of_c) {
  return directional_jacobian(C, true, [&](Mat3<Dual> c) {
    for (auto& entry : c.a) entry.d *= 2.0;  // dC = 2 dE
    return function_of_c(c);
  });
}

}  // namespace needlefem::material
