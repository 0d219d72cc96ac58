// Wall time since a moment, in seconds: the timings a run, a sweep, the mesher and the prbm check
// report (summary.json, the progress lines, prbm_check.json).
#pragma once

#include <chrono>

namespace needlefem {

using WallClock = std::chrono::steady_clock;

inline double seconds_since(WallClock::time_point start) {
  return std::chrono::duration<double>(WallClock::now() - start).count();
}

}  // namespace needlefem
