// The paced replay loop with the in-process test device: frame count and sampling times,
// clamping, the final zero-force frame, stopping by flag and by SIGINT.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "fixtures.hpp"
#include "interrupt/interrupt_guard.hpp"
#include "replay/player.hpp"

namespace needlefem::replay {
namespace {

double magnitude(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

TEST(Player, OnePassSendsEverySlotThenZeroForce) {
  const Trajectory t = testing::ramp_trajectory(0.5, 5.0);
  RecordingDevice device;
  const std::atomic<bool> never{false};
  ReplayOptions options;
  options.rate_hz = 1000.0;
  options.force_limit_n = 2.0;
  const ReplayReport report = replay(t, device, options, never);

  // 0.5 s at 1 kHz: slots 0..500 (less any the shared machine made the loop oversleep), plus the
  // final frame.
  ASSERT_EQ(device.frames.size() + report.dropped_frames, 502u);
  EXPECT_EQ(report.frames_sent, device.frames.size());
  // A dropped slot is skipped, never sent late in a burst: the sampled times stay on the slot grid.
  std::uint64_t sent_slots = 0, clamped_seen = 0;
  for (std::size_t i = 0; i + 1 < device.frames.size(); ++i) {
    const auto& f = device.frames[i];
    EXPECT_EQ(f.sequence, i);
    const double slot = f.trajectory_time_s * 1000.0;
    EXPECT_NEAR(slot, std::round(slot), 1e-6);
    EXPECT_LE(magnitude(f.force_n), 2.0 + 1e-12);
    // Below the limit the sampled ramp passes through; above it the force is clamped along -z.
    const double ramp = 10.0 * f.trajectory_time_s;
    EXPECT_NEAR(f.force_n[2], -std::min(ramp, 2.0), 1e-12);
    if (std::abs(ramp - 2.0) > 1e-9) {
      EXPECT_EQ(f.force_clamped, ramp > 2.0);
    }
    clamped_seen += f.force_clamped;
    ++sent_slots;
  }
  EXPECT_EQ(sent_slots + report.dropped_frames, 501u);
  EXPECT_EQ(report.clamped_frames, clamped_seen);
  // Slots with t > 0.2 s of the 0.5 s ramp (the one at exactly 0.2 s is on the limit).
  EXPECT_NEAR(static_cast<double>(clamped_seen), 300.0, 1.0 + static_cast<double>(report.dropped_frames));
  const DeviceFrame& last = device.frames.back();
  EXPECT_TRUE(last.final_frame);
  EXPECT_EQ(last.sequence, device.frames.size() - 1);
  EXPECT_EQ(magnitude(last.force_n), 0.0);
  EXPECT_EQ(magnitude(last.torque_n_m), 0.0);
  EXPECT_EQ(last.position_m, device.frames[device.frames.size() - 2].position_m);  // holds the last pose
  EXPECT_FALSE(report.interrupted);
}

TEST(Player, HugeForcesAreSentFiniteAndClampedInTheirOwnDirection) {
  // A constant 1e200 N along +x, then a +-1e308 swing: every packet finite, at most the limit,
  // and a constant huge force arrives as the limit along +x (not 0 N, not NaN).
  Trajectory t = testing::ramp_trajectory(0.02, 1.0);
  for (std::size_t i = 0; i < t.size(); ++i) t.force_n[i] = {1e200, 0.0, 0.0};
  t.force_n.back() = {-1e308, 1e308, 0.0};
  t.torque_n_m.back() = {1e308, -1e308, 1e308};
  t.torque_n_m[t.size() - 2] = {-1e308, 1e308, -1e308};
  RecordingDevice device;
  const std::atomic<bool> never{false};
  ReplayOptions options;
  options.force_limit_n = 3.3;
  replay(t, device, options, never);
  ASSERT_GT(device.frames.size(), 2u);
  for (const DeviceFrame& f : device.frames) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(f.force_n[c])) << f.trajectory_time_s;
      ASSERT_TRUE(std::isfinite(f.torque_n_m[c])) << f.trajectory_time_s;
      ASSERT_TRUE(std::isfinite(f.position_m[c])) << f.trajectory_time_s;
    }
    EXPECT_LE(magnitude(f.force_n), 3.3);
  }
  const DeviceFrame& first = device.frames.front();
  EXPECT_TRUE(first.force_clamped);
  EXPECT_DOUBLE_EQ(first.force_n[0], 3.3);
}

TEST(Player, RateBeyondWhatCanBePacedIsRefusedBeforeSending) {
  // 1e10 Hz rounds to a zero period: once it sent nothing and reported success.
  RecordingDevice device;
  const std::atomic<bool> never{false};
  ReplayOptions options;
  options.rate_hz = 1e10;
  EXPECT_THROW(replay(testing::ramp_trajectory(0.1), device, options, never), std::invalid_argument);
  EXPECT_TRUE(device.frames.empty());
  options.rate_hz = max_rate_hz;
  options.duration_s = 0.001;
  replay(testing::ramp_trajectory(0.1), device, options, never);
  EXPECT_FALSE(device.frames.empty());
}

TEST(Player, DeadlinesAreAbsolute) {
  // Timestamps are start + k * period exactly: no drift however long the replay runs.
  const Trajectory t = testing::ramp_trajectory(0.2);
  RecordingDevice device;
  const std::atomic<bool> never{false};
  ReplayOptions options;
  options.rate_hz = 800.0;  // 1.25 ms
  replay(t, device, options, never);
  const auto start = device.frames.front().timestamp_ns;
  for (std::size_t i = 0; i + 1 < device.frames.size(); ++i) {
    const double slot = std::round(device.frames[i].trajectory_time_s * 800.0);
    EXPECT_EQ(device.frames[i].timestamp_ns - start, static_cast<std::uint64_t>(slot) * 1'250'000u);
  }
}

TEST(Player, LoopStopsAfterDurationWrappingTrajectoryTime) {
  const Trajectory t = testing::ramp_trajectory(0.1);
  RecordingDevice device;
  const std::atomic<bool> never{false};
  ReplayOptions options;
  options.loop = true;
  options.duration_s = 0.35;
  const ReplayReport report = replay(t, device, options, never);
  EXPECT_EQ(device.frames.size() + report.dropped_frames, 351u);
  for (const auto& f : device.frames) EXPECT_LT(f.trajectory_time_s, 0.1 + 1e-12);
}

TEST(Player, StopFlagEndsWithZeroForce) {
  const Trajectory t = testing::ramp_trajectory(2.0, 1.0);
  RecordingDevice device;
  std::atomic<bool> stop{false};
  ReplayOptions options;
  options.loop = true;
  std::thread stopper([&stop] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    stop = true;
  });
  const ReplayReport report = replay(t, device, options, stop);
  stopper.join();
  EXPECT_TRUE(report.interrupted);
  ASSERT_GE(device.frames.size(), 2u);
  EXPECT_TRUE(device.frames.back().final_frame);
  EXPECT_EQ(magnitude(device.frames.back().force_n), 0.0);
  EXPECT_LT(device.frames.size(), 1000u);
}

TEST(Player, SigintStopsTheLoopThroughTheGuard) {
  const Trajectory t = testing::ramp_trajectory(2.0, 1.0);
  RecordingDevice device;
  ReplayOptions options;
  options.loop = true;
  ReplayReport report;
  {
    InterruptGuard guard;
    std::thread interrupter([] {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      ::kill(::getpid(), SIGINT);
    });
    report = replay(t, device, options, InterruptGuard::stop_flag());
    interrupter.join();
    EXPECT_EQ(InterruptGuard::signal_number(), SIGINT);
  }
  EXPECT_TRUE(report.interrupted);
  EXPECT_TRUE(device.frames.back().final_frame);
  EXPECT_EQ(magnitude(device.frames.back().force_n), 0.0);
  EXPECT_NEAR(static_cast<double>(device.frames.size()), 200.0, 150.0);
}

}  // namespace
}  // namespace needlefem::replay
