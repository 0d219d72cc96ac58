// Wall time since `start`, in seconds: the prbm check's timings (meshing, the FEM's solves and its
// linear solves) in prbm_check.json.
#pragma once

#include <chrono>

namespace needlefem::prbm {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace needlefem::prbm
