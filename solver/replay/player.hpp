// The replay loop: streams a trajectory to a haptic device at the device rate.
//
// Pacing: frame k is due at the absolute deadline start + k * period on CLOCK_MONOTONIC and the
// loop sleeps with clock_nanosleep(TIMER_ABSTIME) until it. Deadlines come from k, never from
// the previous wake-up, so oversleeping one frame does not shift any later one (no drift).
// Frame k samples the trajectory at t_0 + k * period (modulo the duration with --loop).
//   late frame:    sent more than half a period after its deadline
//   dropped frame: a deadline the loop overslept completely; rather than bursting frames to
//                  catch up, the loop resumes at the newest deadline that has passed
//   period error:  (time between consecutive sends) - period; its |.| percentiles are reported
// When the trajectory ends, the stop flag is raised (SIGINT through interrupt/interrupt_guard.hpp), or the
// requested duration is reached, one last frame with the last pose and zero force and torque is
// sent, so the device is never left pushing.
#pragma once

#include <atomic>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "replay/device.hpp"
#include "replay/trajectory.hpp"

namespace needlefem::replay {

// The fastest rate the loop paces: a 10 us period, still 100 histogram bins (100 ns) and well
// above any haptic device's servo rate (1-10 kHz). A faster rate would round to a zero period.
inline constexpr double max_rate_hz = 100'000.0;

struct ReplayOptions {
  double rate_hz = 1000.0;       // device servo rate
  double force_limit_n = 3.3;    // device's maximum force
  bool loop = false;             // repeat the trajectory until stopped
  double duration_s = 0.0;       // stop after this long (0 = one pass, or forever with loop)
};

struct Percentiles {
  double p50 = 0.0, p99 = 0.0, max = 0.0;
};

struct ReplayReport {
  std::uint64_t frames_sent = 0;       // including the final zero-force frame
  std::uint64_t late_frames = 0;
  std::uint64_t dropped_frames = 0;
  std::uint64_t clamped_frames = 0;
  std::uint64_t failed_sends = 0;      // frames the back end could not deliver
  double elapsed_s = 0.0;              // first to last paced send
  double achieved_rate_hz = 0.0;       // paced sends over elapsed_s
  Percentiles period_error_s;          // |interval - period|
  Percentiles lateness_s;              // send time - deadline
  bool interrupted = false;
  nlohmann::json to_json(const ReplayOptions& options) const;
};

ReplayReport replay(const Trajectory& trajectory, HapticDevice& device, const ReplayOptions& options,
                    const std::atomic<bool>& stop);

}  // namespace needlefem::replay
