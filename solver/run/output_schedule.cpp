#include "run/output_schedule.hpp"

#include <cmath>

#include "case/case.hpp"

namespace needlefem::run {

double history_end(const Case& c) {
  if (c.text("scene.kind") == "block") return c.real("loading.ramp_s") + c.real("loading.hold_s");
  return c.real("motion.duration_s");
}

std::vector<double> output_times(const Case& c) {
  const double end = history_end(c), interval = c.real("output.interval_s");
  // A last interval shorter than 1e-9 of the interval is merged into the one before.
  const auto intervals = static_cast<long>(std::ceil(end / interval - 1e-9));
  std::vector<double> times;
  for (long i = 0; i < intervals; ++i) times.push_back(static_cast<double>(i) * interval);
  times.push_back(end);
  return times;
}

}  // namespace needlefem::run
