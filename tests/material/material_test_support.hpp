// Helpers shared by the material tests.
#pragma once

#include <cstdio>
#include <string>

#include "physics/material/tensor.hpp"

namespace needlefem::material {

// A measured error as "1.234e-09" for RecordProperty (std::to_string would print 0.000000).
inline std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

// A general deformation gradient: stretch, shear and rotation together, det F > 0.
inline Mat3d general_deformation() {
  Mat3d F;
  F.a = {1.12, 0.21, -0.05, 0.03, 0.91, 0.12, -0.08, 0.04, 1.05};
  return F;
}

}  // namespace needlefem::material
