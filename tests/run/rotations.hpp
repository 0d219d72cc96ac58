// A rotation about a coordinate axis, for the closed-form tests of quantities that rotations must
// leave alone (objectivity).
#pragma once

#include <cmath>

#include "physics/material/tensor.hpp"

namespace needlefem::fields {

// About axis 0 (x), 1 (y) or 2 (z), by `angle` radians, right-handed.
inline material::Mat3d rotation_about(int axis, double angle) {
  const int j = (axis + 1) % 3, k = (axis + 2) % 3;
  material::Mat3d R = material::Mat3d::identity();
  R(j, j) = R(k, k) = std::cos(angle);
  R(j, k) = -std::sin(angle);
  R(k, j) = std::sin(angle);
  return R;
}

}  // namespace needlefem::fields
