// Equations: load_history.hpp.
#include "physics/mechanics/load_history.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "case/case.hpp"

namespace needlefem::mechanics {

namespace {

constexpr double kMetresPerMm = 1e-3;
constexpr const char* kNeedsHistoryTimes = "needs loading.history_time_s, the times of its entries";

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

double history_end(const LoadingSpec& spec) {
  if (spec.scene_kind == SceneKind::brain_tip) return spec.motion_duration_s;
  const double loading =
      spec.scene_kind == SceneKind::mesh && spec.history_time_s ? spec.history_time_s->back() : spec.ramp_s;
  return loading + spec.hold_s;
}

LoadHistory LoadHistory::from_spec(const LoadingSpec& spec) {
  const auto error = [&](const std::string& key, const std::string& reason) {
    return case_error(spec.origin, key, reason);
  };
  LoadHistory h;
  const auto scaled_translation = [&](double s) {
    return Point3{s * spec.translation_mm[0] * kMetresPerMm, s * spec.translation_mm[1] * kMetresPerMm,
                  s * spec.translation_mm[2] * kMetresPerMm};
  };
  if (!spec.history_time_s) {
    if (spec.history_factor) throw error("loading.history_factor", kNeedsHistoryTimes);
    if (spec.translation_history_mm) throw error("displacement.translation_history_mm", kNeedsHistoryTimes);
    h.times_ = spec.ramp_s > 0.0 ? std::vector<double>{0.0, spec.ramp_s} : std::vector<double>{0.0};
    h.factors_ = spec.ramp_s > 0.0 ? std::vector<double>{0.0, 1.0} : std::vector<double>{1.0};
    for (double s : h.factors_) h.translations_.push_back(scaled_translation(s));
    return h;
  }
  h.times_ = *spec.history_time_s;
  if (h.times_.front() != 0.0) throw error("loading.history_time_s", "must start at 0");
  for (std::size_t k = 1; k < h.times_.size(); ++k)
    if (!(h.times_[k] > h.times_[k - 1]))
      throw error("loading.history_time_s",
                  fmt::format("must increase strictly ({} follows {})", h.times_[k], h.times_[k - 1]));
  const std::size_t n = h.times_.size();
  if (!spec.history_factor) throw error("loading.history_factor", "required with loading.history_time_s");
  h.factors_ = *spec.history_factor;
  if (h.factors_.size() != n)
    throw error("loading.history_factor",
                fmt::format("has {} entries but loading.history_time_s has {}", h.factors_.size(), n));
  if (!spec.translation_history_mm) {
    for (double s : h.factors_) h.translations_.push_back(scaled_translation(s));
    return h;
  }
  if (spec.translation_mm_given)
    throw error("displacement.translation_history_mm", "give either it or displacement.translation_mm, not both");
  const std::vector<double>& table = *spec.translation_history_mm;
  if (table.size() != 3 * n)
    throw error("displacement.translation_history_mm",
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
