// Interpolation between trajectory samples and the force clamp, against closed forms.
#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace needlefem::replay
