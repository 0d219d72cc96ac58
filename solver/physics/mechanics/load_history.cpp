// Equations: load_history.hpp.
#include "physics/mechanics/load_history.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "case/case.hpp"

namespace needlefem::mechanics {

namespace {

constexpr double kMetresPerMm = 1e-3;

// Piecewise-linear interpolation of values[k] at times[k], held beyond both ends.
template <class T>
T interpolate(const std::vector<double>& times, const std::vector<T>& values, double t) {
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const double w = (t - times[k - 1]) / (times[k] - times[k - 1]);
  if constexpr (std::is_same_v<T, double>) {
    return (1.0 - w) * values[k - 1] + w * values[k];
  } else {
    T out{};
    for (std::size_t c = 0; c < out.size(); ++c) out[c] = (1.0 - w) * values[k - 1][c] + w * values[k][c];
    return out;
  }
}

}  // namespace

double ramp_then_hold(double t, double ramp_s) {
  if (ramp_s <= 0.0) return t >= 0.0 ? 1.0 : 0.0;
  return std::clamp(t / ramp_s, 0.0, 1.0);
}

double history_end(const Case& input) {
  const std::string kind = input.text("scene.kind");
  if (kind == "brain-tip") return input.real("motion.duration_s");
  const double loading = kind == "mesh" && input.has("loading.history_time_s")
                             ? input.reals("loading.history_time_s").back()
                             : input.real("loading.ramp_s");
  return loading + input.real("loading.hold_s");
}

LoadHistory LoadHistory::from_case(const Case& input) {
  LoadHistory h;
  const std::vector<double> final_translation = input.reals("displacement.translation_mm");
  const auto scaled_translation = [&](double s) {
    return Point3{s * final_translation[0] * kMetresPerMm, s * final_translation[1] * kMetresPerMm,
                  s * final_translation[2] * kMetresPerMm};
  };
  if (!input.has("loading.history_time_s")) {
    for (const char* key : {"loading.history_factor", "displacement.translation_history_mm"})
      if (input.has(key)) throw input.error(key, "needs loading.history_time_s, the times of its entries");
    const double ramp_s = input.real("loading.ramp_s");
    h.times_ = ramp_s > 0.0 ? std::vector<double>{0.0, ramp_s} : std::vector<double>{0.0};
    h.factors_ = ramp_s > 0.0 ? std::vector<double>{0.0, 1.0} : std::vector<double>{1.0};
    for (double s : h.factors_) h.translations_.push_back(scaled_translation(s));
    return h;
  }
  h.times_ = input.reals("loading.history_time_s");
  if (h.times_.front() != 0.0) throw input.error("loading.history_time_s", "must start at 0");
  for (std::size_t k = 1; k < h.times_.size(); ++k)
    if (!(h.times_[k] > h.times_[k - 1]))
      throw input.error("loading.history_time_s",
                        fmt::format("must increase strictly ({} follows {})", h.times_[k], h.times_[k - 1]));
  const std::size_t n = h.times_.size();
  if (!input.has("loading.history_factor")) throw input.error("loading.history_factor", "required with loading.history_time_s");
  h.factors_ = input.reals("loading.history_factor");
  if (h.factors_.size() != n)
    throw input.error("loading.history_factor",
                      fmt::format("has {} entries but loading.history_time_s has {}", h.factors_.size(), n));
  if (!input.has("displacement.translation_history_mm")) {
    for (double s : h.factors_) h.translations_.push_back(scaled_translation(s));
    return h;
  }
  if (input.given("displacement.translation_mm"))
    throw input.error("displacement.translation_history_mm", "give either it or displacement.translation_mm, not both");
  const std::vector<double> table = input.reals("displacement.translation_history_mm");
  if (table.size() != 3 * n)
    throw input.error("displacement.translation_history_mm",
                      fmt::format("has {} entries; loading.history_time_s has {} times, so it needs {} (x, y, z per "
                                  "time)", table.size(), n, 3 * n));
  for (std::size_t k = 0; k < n; ++k)
    h.translations_.push_back(
        {table[3 * k] * kMetresPerMm, table[3 * k + 1] * kMetresPerMm, table[3 * k + 2] * kMetresPerMm});
  return h;
}

double LoadHistory::factor(double t) const { return interpolate(times_, factors_, t); }

Point3 LoadHistory::translation(double t) const { return interpolate(times_, translations_, t); }

}  // namespace needlefem::mechanics
