#include "run/output_schedule.hpp"

#include <cmath>

#include <fmt/format.h>

#include "case/case.hpp"
#include "physics/mechanics/load_history.hpp"

namespace needlefem::run {

std::vector<double> output_times(const OutputSpec& output, const LoadingSpec& loading) {
  const double end = mechanics::history_end(loading), interval = output.interval_s;
  // Every output time writes every field: 1e4 of them is already gigabytes on a fine mesh, and
  // 1e-9 s over 0.1 s once wrote hundreds of MB of metadata alone.
  constexpr double max_output_times = 1e4;
  if (end / interval > max_output_times)
    throw case_error(output.origin, "output.interval_s",
                     fmt::format("{:.3g} s over the {:.3g} s history is {:.3g} output times, more than {:.0f} (use an "
                                 "interval of at least {:.3g} s)", interval, end, end / interval, max_output_times,
                                 end / max_output_times));
  // A last interval shorter than 1e-9 of the interval is merged into the one before.
  const auto intervals = static_cast<long>(std::ceil(end / interval - 1e-9));
  std::vector<double> times;
  for (long i = 0; i < intervals; ++i) times.push_back(static_cast<double>(i) * interval);
  times.push_back(end);
  return times;
}

}  // namespace needlefem::run
