// Helpers shared by the material tests.
#pragma once

#include <cstdio>
#include <string>

namespace needlefem::material {

// A measured error as "1.234e-09" for RecordProperty (std::to_string would print 0.000000).
inline std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

}  // namespace needlefem::material
