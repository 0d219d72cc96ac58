// Interpolation between trajectory samples and the force clamp, against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "fixtures.hpp"
#include "replay/sampling.hpp"

namespace needlefem::replay {
namespace {

Quaternion about_z(double angle) { return {std::cos(angle / 2), 0.0, 0.0, std::sin(angle / 2)}; }

TEST(Sampling, SlerpFollowsTheGreatCircleAtConstantRate) {
  // Rotations about one axis: slerp between angles a and b at s is the rotation by a + s (b - a).
  const double a = 0.3, b = 2.2;
  for (double s : {0.0, 0.1, 0.5, 0.77, 1.0}) {
    const Quaternion q = slerp(about_z(a), about_z(b), s);
    const Quaternion expected = about_z(a + s * (b - a));
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(q[c], expected[c], 1e-14) << "s = " << s;
  }
}

TEST(Sampling, SlerpTakesTheShorterArc) {
  // -q is the same rotation as q: interpolating toward -about_z(0.4) must still turn by 0.4 rad.
  Quaternion negated = about_z(0.4);
  for (double& c : negated) c = -c;
  const Quaternion half = slerp(about_z(0.0), negated, 0.5);
  const Quaternion expected = about_z(0.2);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(half[c], expected[c], 1e-14);
}

TEST(Sampling, SlerpOfNearlyEqualQuaternionsIsStable) {
  const Quaternion q = slerp(about_z(1.0), about_z(1.0 + 1e-9), 0.5);
  const Quaternion expected = about_z(1.0 + 0.5e-9);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(q[c], expected[c], 1e-15);
}

TEST(Sampling, VectorsAreLinearBetweenSamplesAndHeldOutside) {
  const Trajectory t = testing::ramp_trajectory(2.0, 5.0);
  // The ramp is linear in time, so linear interpolation reproduces it exactly between samples.
  for (double time : {0.0, 0.0042, 0.5, 1.23456, 1.999}) {
    const TrajectoryState s = sample(t, time);
    EXPECT_NEAR(s.position_m[2], 1e-3 * time, 1e-16);
    EXPECT_NEAR(s.force_n[2], -2.5 * time, 1e-13);
    EXPECT_NEAR(s.torque_n_m[2], -1e-4 * time, 1e-18);
    const Quaternion expected = about_z(std::numbers::pi / 10.0 * time);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(s.orientation[c], expected[c], 1e-14) << time;
  }
  EXPECT_EQ(sample(t, -1.0).force_n, t.force_n.front());
  EXPECT_EQ(sample(t, 7.0).force_n, t.force_n.back());
}

TEST(Sampling, ClampKeepsDirectionAndLimitsMagnitude) {
  Vec3 large{3.0, 4.0, 0.0};  // |f| = 5
  EXPECT_TRUE(clamp_magnitude(large, 3.3));
  EXPECT_NEAR(large[0], 3.0 * 3.3 / 5.0, 1e-15);
  EXPECT_NEAR(large[1], 4.0 * 3.3 / 5.0, 1e-15);
  EXPECT_NEAR(std::hypot(large[0], large[1], large[2]), 3.3, 1e-15);
  Vec3 small{1.0, -1.0, 0.5};
  const Vec3 unchanged = small;
  EXPECT_FALSE(clamp_magnitude(small, 3.3));
  EXPECT_EQ(small, unchanged);
}

// Finite but huge samples (a hostile trajectory file): interpolation stays finite and between
// the samples, and the clamp brings any length to the limit along the vector's own direction.
TEST(Sampling, HugeFiniteSamplesInterpolateToFiniteValues) {
  Trajectory t = testing::ramp_trajectory(0.02, 1.0);
  t.force_n = {{-1e308, 1e308, 0.0}, {1e308, -1e308, 0.0}, {1e308, 1e308, -1e308}};
  t.torque_n_m = t.force_n;
  t.position_m = t.force_n;
  for (double time : {0.0, 0.0025, 0.005, 0.0137, 0.02}) {
    const TrajectoryState s = sample(t, time);
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(s.force_n[c])) << time;
      EXPECT_TRUE(std::isfinite(s.torque_n_m[c])) << time;
      EXPECT_TRUE(std::isfinite(s.position_m[c])) << time;
    }
  }
}

TEST(Sampling, ClampOfAHugeVectorIsTheLimitInItsOwnDirection) {
  for (const Vec3& huge : {Vec3{0.0, 0.0, 1e200}, Vec3{-1e308, 1e308, 0.0}, Vec3{1e308, 1e308, -1e308},
                           Vec3{1.7e308, -3.0, 1e-300}}) {
    Vec3 v = huge;
    EXPECT_TRUE(clamp_magnitude(v, 3.3));
    const double largest = std::max({std::abs(huge[0]), std::abs(huge[1]), std::abs(huge[2])});
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(v[c]));
      EXPECT_NEAR(v[c] / 3.3, (huge[c] / largest) / std::hypot(huge[0] / largest, huge[1] / largest, huge[2] / largest),
                  1e-12);
    }
  }
}

TEST(Sampling, ClampedMagnitudeNeverExceedsTheLimitUnderRounding) {
  // The limit is a hard bound: over many directions and limits, |clamped| <= limit exactly.
  std::uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (int trial = 0; trial < 100000; ++trial) {
    const double limit = 0.1 + 10.0 * uniform();
    const double scale = std::pow(10.0, 300.0 * uniform() - 100.0);
    Vec3 v{scale * (uniform() - 0.5), scale * (uniform() - 0.5), scale * (uniform() - 0.5)};
    clamp_magnitude(v, limit);
    ASSERT_LE(std::hypot(v[0], v[1], v[2]), limit) << "trial " << trial;
    ASSERT_LE(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), limit) << "trial " << trial;
  }
}

}  // namespace
}  // namespace needlefem::replay
