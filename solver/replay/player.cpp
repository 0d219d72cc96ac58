// The paced replay loop and its statistics; the pacing rules are in player.hpp.
#include <algorithm>
#include "replay/player.hpp"

#include <sys/prctl.h>
#include <time.h>

#include <cerrno>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "replay/sampling.hpp"

namespace needlefem::replay {

namespace {

using Nanoseconds = std::int64_t;

Nanoseconds monotonic_now_ns() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return Nanoseconds{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

// Sleeps until the absolute CLOCK_MONOTONIC deadline. Returns false when a signal woke it and
// the stop flag is raised; other signals resume the sleep.
bool sleep_until(Nanoseconds deadline_ns, const std::atomic<bool>& stop) {
  const timespec deadline{static_cast<time_t>(deadline_ns / 1'000'000'000), static_cast<long>(deadline_ns % 1'000'000'000)};
  for (;;) {
    const int status = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr);
    if (status == 0) return true;
    if (status != EINTR) throw std::system_error(status, std::generic_category(), "clock_nanosleep");
    if (stop.load()) return false;
  }
}

// Fixed-bin histogram of non-negative durations: constant memory however long a --loop replay
// runs, percentiles to one bin (100 ns), exact maximum.
class DurationHistogram {
 public:
  void add(Nanoseconds value) {
    const auto magnitude = static_cast<std::uint64_t>(value < 0 ? -value : value);
    ++bins_[std::min<std::uint64_t>(magnitude / bin_ns, bins_.size() - 1)];
    ++count_;
    max_ns_ = std::max(max_ns_, magnitude);
  }
  double quantile_s(double q) const {
    if (count_ == 0) return 0.0;
    const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_)));
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < bins_.size(); ++i) {
      seen += bins_[i];
      if (seen >= std::max<std::uint64_t>(rank, 1))
        return 1e-9 * static_cast<double>(std::min<std::uint64_t>((i + 1) * bin_ns, max_ns_));
    }
    return 1e-9 * static_cast<double>(max_ns_);
  }
  Percentiles percentiles() const { return {quantile_s(0.50), quantile_s(0.99), 1e-9 * static_cast<double>(max_ns_)}; }

 private:
  static constexpr std::uint64_t bin_ns = 100;
  std::vector<std::uint32_t> bins_ = std::vector<std::uint32_t>(200'000);  // up to 20 ms
  std::uint64_t count_ = 0;
  std::uint64_t max_ns_ = 0;
};

// Linux delays a normal thread's timer wake-ups by up to its timer slack (50 us by default) to
// batch them; at a 1 ms period that is 5 % jitter for nothing. Slack 1 ns while replaying.
class MinimalTimerSlack {
 public:
  MinimalTimerSlack() : previous_ns_(prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0)) { prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0); }
  MinimalTimerSlack(const MinimalTimerSlack&) = delete;
  MinimalTimerSlack& operator=(const MinimalTimerSlack&) = delete;
  ~MinimalTimerSlack() {
    if (previous_ns_ > 0) prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(previous_ns_), 0, 0, 0);
  }

 private:
  long previous_ns_;
};

nlohmann::json percentiles_us(const Percentiles& p) {
  return {{"p50", 1e6 * p.p50}, {"p99", 1e6 * p.p99}, {"max", 1e6 * p.max}};
}

}  // namespace

ReplayReport replay(const Trajectory& trajectory, HapticDevice& device, const ReplayOptions& options,
                    const std::atomic<bool>& stop) {
  if (!(options.rate_hz > 0.0) || !(options.rate_hz <= max_rate_hz))
    throw std::invalid_argument(fmt::format("replay: --rate {:.6g} Hz is outside (0, {:.6g}] Hz, the rates this loop "
                                            "can pace", options.rate_hz, max_rate_hz));
  if (!(options.force_limit_n > 0.0) || !std::isfinite(options.force_limit_n))
    throw std::invalid_argument("replay: force limit must be positive and finite");
  if (!(options.duration_s >= 0.0)) throw std::invalid_argument("replay: duration must be >= 0");
  validate_trajectory(trajectory, "replay trajectory");

  const Nanoseconds period_ns = std::llround(1e9 / options.rate_hz);
  const double period_s = 1e-9 * static_cast<double>(period_ns);
  const double length_s = trajectory.duration_s();
  const std::uint64_t one_pass_frames = static_cast<std::uint64_t>(std::floor(length_s / period_s + 1e-9)) + 1;
  std::uint64_t frame_count = options.loop ? std::numeric_limits<std::uint64_t>::max() : one_pass_frames;
  if (options.duration_s > 0.0)
    frame_count = std::min<std::uint64_t>(frame_count, static_cast<std::uint64_t>(std::floor(options.duration_s / period_s + 1e-9)));

  ReplayReport report;
  DurationHistogram period_error, lateness;
  DeviceFrame frame;
  frame.position_m = trajectory.position_m.front();
  frame.orientation = trajectory.orientation.front();
  Nanoseconds first_send = 0, previous_send = 0;
  std::uint64_t paced_frames = 0;

  const MinimalTimerSlack precise_wakeups;
  const Nanoseconds start = monotonic_now_ns();
  for (std::uint64_t k = 0; k < frame_count && !stop.load();) {
    const Nanoseconds deadline = start + static_cast<Nanoseconds>(k) * period_ns;
    if (!sleep_until(deadline, stop)) break;
    const double offset_s = static_cast<double>(k) * period_s;
    frame.trajectory_time_s = trajectory.time_s.front() + (options.loop ? std::fmod(offset_s, length_s) : offset_s);
    const TrajectoryState state = sample(trajectory, frame.trajectory_time_s);
    frame.timestamp_ns = static_cast<std::uint64_t>(deadline);
    frame.position_m = state.position_m;
    frame.orientation = state.orientation;
    frame.force_n = state.force_n;
    frame.torque_n_m = state.torque_n_m;
    frame.force_clamped = clamp_magnitude(frame.force_n, options.force_limit_n);

    const Nanoseconds sent_at = monotonic_now_ns();
    if (!device.send(frame)) ++report.failed_sends;
    ++frame.sequence;
    report.clamped_frames += frame.force_clamped;
    lateness.add(sent_at - deadline);
    if (sent_at - deadline > period_ns / 2) ++report.late_frames;
    if (paced_frames++ == 0)
      first_send = sent_at;
    else
      period_error.add(sent_at - previous_send - period_ns);
    previous_send = sent_at;

    ++k;
    // Overslept past further deadlines: resume at the newest one instead of bursting.
    // Slots past the last frame are not frames: cap at frame_count.
    const auto newest_due =
        std::min<std::uint64_t>(frame_count, static_cast<std::uint64_t>((monotonic_now_ns() - start) / period_ns));
    if (newest_due > k) {
      report.dropped_frames += newest_due - k;
      k = newest_due;
    }
  }
  report.interrupted = stop.load();

  frame.final_frame = true;
  frame.force_clamped = false;
  frame.force_n = {0.0, 0.0, 0.0};
  frame.torque_n_m = {0.0, 0.0, 0.0};
  frame.timestamp_ns = static_cast<std::uint64_t>(monotonic_now_ns());
  if (!device.send(frame)) ++report.failed_sends;

  report.frames_sent = paced_frames + 1;
  report.elapsed_s = 1e-9 * static_cast<double>(previous_send - first_send);
  report.achieved_rate_hz = report.elapsed_s > 0.0 ? static_cast<double>(paced_frames - 1) / report.elapsed_s : 0.0;
  report.period_error_s = period_error.percentiles();
  report.lateness_s = lateness.percentiles();
  return report;
}

nlohmann::json ReplayReport::to_json(const ReplayOptions& options) const {
  return {{"rate_hz", options.rate_hz},
          {"force_limit_n", options.force_limit_n},
          {"loop", options.loop},
          {"frames_sent", frames_sent},
          {"final_zero_force_frame", true},
          {"late_frames", late_frames},
          {"dropped_frames", dropped_frames},
          {"clamped_frames", clamped_frames},
          {"failed_sends", failed_sends},
          {"elapsed_s", elapsed_s},
          {"achieved_rate_hz", achieved_rate_hz},
          {"period_error_us", percentiles_us(period_error_s)},
          {"lateness_us", percentiles_us(lateness_s)},
          {"interrupted", interrupted}};
}

}  // namespace needlefem::replay
