#include "physics/fields/point_quantities.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace needlefem::fields {

std::array<double, 3> symmetric_eigenvalues(const Mat3d& A) {
  const double off = A(0, 1) * A(0, 1) + A(0, 2) * A(0, 2) + A(1, 2) * A(1, 2);
  const double mean = material::trace(A) / 3.0;
  const double deviator_size =
      std::sqrt(((A(0, 0) - mean) * (A(0, 0) - mean) + (A(1, 1) - mean) * (A(1, 1) - mean) +
                 (A(2, 2) - mean) * (A(2, 2) - mean) + 2.0 * off) / 6.0);
  if (deviator_size <= 1e-300) return {mean, mean, mean};
  // B = (A - mean I)/deviator_size has eigenvalues 2 cos(φ + 2πk/3), det B = 2 cos 3φ.
  Mat3d B = A;
  for (int i = 0; i < 3; ++i) B(i, i) -= mean;
  B = (1.0 / deviator_size) * B;
  const double half_det = std::clamp(material::det(B) / 2.0, -1.0, 1.0);
  const double phi = std::acos(half_det) / 3.0;
  const double largest = mean + 2.0 * deviator_size * std::cos(phi);
  const double smallest = mean + 2.0 * deviator_size * std::cos(phi + 2.0 * std::numbers::pi / 3.0);
  const double middle = 3.0 * mean - largest - smallest;
  return {smallest, middle, largest};
}

Mat3d push_forward(const Mat3d& F, const Mat3d& second_pk) {
  return (1.0 / material::det(F)) * (F * second_pk * material::transpose(F));
}

PointQuantities point_quantities(const Mat3d& F, const Mat3d& F_rate, const Mat3d& cauchy_stress) {
  PointQuantities q;
  q.cauchy_stress = cauchy_stress;
  const double mean_stress = material::trace(cauchy_stress) / 3.0;
  Mat3d deviator = cauchy_stress;
  for (int i = 0; i < 3; ++i) deviator(i, i) -= mean_stress;
  q.von_mises = std::sqrt(1.5 * material::double_dot(deviator, deviator));
  q.pressure = -mean_stress;
  q.max_principal_stress = symmetric_eigenvalues(cauchy_stress)[2];

  const Mat3d b = F * material::transpose(F);
  q.max_log_strain = 0.5 * std::log(symmetric_eigenvalues(b)[2]);

  const Mat3d L = F_rate * material::inverse(F);
  const Mat3d D = 0.5 * (L + material::transpose(L));
  q.max_strain_rate = symmetric_eigenvalues(D)[2];
  q.equivalent_strain_rate = std::sqrt(2.0 / 3.0 * material::double_dot(D, D));
  return q;
}

}  // namespace needlefem::fields
