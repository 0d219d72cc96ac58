// The memory this process may fill and the memory it holds: what the Newton-matrix factor weighs
// an LU against before it grows its factor (newton_matrix_factor.hpp).
#pragma once

#include <cstddef>

namespace needlefem {

// The machine's physical memory, or the control group's limit where that is lower (a container
// or a batch job's allocation; cgroup v2, else v1).
std::size_t usable_memory_bytes();
// This process's resident set now (/proc/self/statm).
std::size_t resident_bytes();

}  // namespace needlefem
