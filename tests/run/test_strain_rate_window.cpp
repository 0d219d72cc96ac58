// The strain rate sustained over a window (physics/fields/strain_rate_window.hpp) against closed
// forms: steady stretching, the same stretching on rotating axes, a burst, rest before the first
// snapshot, a deformation gradient linear in time between snapshots, and snapshots dropped.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "physics/fields/strain_rate_window.hpp"
#include "rotations.hpp"

namespace needlefem::fields {
namespace {

using material::Mat3d;

constexpr double kRate = 7.0;       // 1/s
constexpr double kWindow = 0.019;   // s

// Isochoric uniaxial stretching along x at a steady log-strain rate d from t = 0.
Mat3d uniaxial(double log_strain) {
  const double l = std::exp(log_strain);
  return Mat3d::diagonal(l, 1.0 / std::sqrt(l), 1.0 / std::sqrt(l));
}

// Snapshots of one point's F(t) every `spacing` from 0 to `end` (inclusive).
template <class F>
StrainRateWindow sampled(F deformation, double spacing, double end, double longest = 2 * kWindow) {
  StrainRateWindow window(longest, spacing);
  const int count = static_cast<int>(std::lround(end / spacing));
  for (int i = 0; i <= count; ++i) window.add_snapshot(i * spacing, {deformation(i * spacing)});
  return window;
}

TEST(StrainRateWindow, SteadyStretchingGivesItsRate) {
  // Windows that start on a snapshot (F is not linear in t: between snapshots it is interpolated).
  const auto window = sampled([](double t) { return uniaxial(kRate * t); }, 0.0005, 0.05);
  for (double w : {kWindow / 2, kWindow, 2 * kWindow})
    EXPECT_NEAR(window.rate(w)[0], kRate, 1e-9 * kRate) << "window " << w;
}

TEST(StrainRateWindow, RotatingAxesDoNotCount) {
  // F = R(ωt) U(t): the stretch rotates with the tissue at 30 rad/s; the window's stretch is the
  // same as without the rotation (the window starts on a snapshot: F is not linear in t here).
  const auto window =
      sampled([](double t) { return rotation_about(2, 30.0 * t) * uniaxial(kRate * t); }, 0.001, 0.05);
  EXPECT_NEAR(window.rate(kWindow)[0], kRate, 1e-9 * kRate);
}

TEST(StrainRateWindow, ABurstCountsByTheStrainItDelivers) {
  // Steady stretching plus a log strain of 0.02 delivered in 0.5 ms at t = 0.030 s (a slip burst
  // at 40 1/s): a window that holds the burst gives d + 0.02 / τ, one that does not gives d.
  const double burst = 0.02, start = 0.030, length = 0.0005;
  const auto strain = [&](double t) {
    return kRate * t + burst * std::clamp((t - start) / length, 0.0, 1.0);
  };
  const auto at = [&](double end) {
    return sampled([&](double t) { return uniaxial(strain(t)); }, 0.0005, end).rate(kWindow)[0];
  };
  EXPECT_NEAR(at(0.040), kRate + burst / kWindow, 1e-9);
  EXPECT_NEAR(at(0.0295), kRate, 1e-9);
  EXPECT_NEAR(at(0.060), kRate, 1e-9);
}

TEST(StrainRateWindow, TissueRestsBeforeTheFirstSnapshot) {
  // At t = 0.01 s a 0.019 s window reaches back before the start: the strain delivered since the
  // start, 0.01 d, spread over the window.
  const auto window = sampled([](double t) { return uniaxial(kRate * t); }, 0.001, 0.01);
  EXPECT_NEAR(window.rate(kWindow)[0], kRate * 0.01 / kWindow, 1e-9);
}

TEST(StrainRateWindow, InterpolatesBetweenSnapshots) {
  // F(t) = I + t A is linear in t: the window's start, between two snapshots 4 ms apart, is
  // interpolated exactly; the rate is that of F(t) F(t - τ)⁻¹ in closed form.
  Mat3d A;
  A(0, 0) = 3.0;
  A(0, 1) = 1.5;
  A(1, 0) = -0.5;
  A(2, 2) = -1.0;
  const auto F = [&](double t) { return Mat3d::identity() + t * A; };
  const double end = 0.048;
  const auto window = sampled(F, 0.004, end);
  const Mat3d relative = F(end) * material::inverse(F(end - kWindow));
  const Mat3d b = relative * material::transpose(relative);
  // The largest eigenvalue of b by power iteration (b is symmetric positive definite).
  std::array<double, 3> v{1.0, 1.0, 1.0};
  double largest = 0.0;
  for (int k = 0; k < 200; ++k) {
    std::array<double, 3> w{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) w[i] += b(i, j) * v[j];
    largest = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int i = 0; i < 3; ++i) v[i] = w[i] / largest;
  }
  EXPECT_NEAR(window.rate(kWindow)[0], 0.5 * std::log(largest) / kWindow, 1e-9);
}

TEST(StrainRateWindow, KeepsOnlyWhatTheLongestWindowNeeds) {
  // A thousand snapshots: the rates over every window up to the longest stay exact, and a
  // snapshot closer than the spacing to the last is not due.
  StrainRateWindow window(2 * kWindow, 0.001);
  for (int i = 0; i <= 1000; ++i) {
    const double t = i * 0.001;
    EXPECT_TRUE(window.wants_snapshot(t));
    window.add_snapshot(t, {uniaxial(kRate * t), uniaxial(-kRate * t)});
    EXPECT_FALSE(window.wants_snapshot(t + 0.0009));
  }
  for (double w : {0.001, kWindow, 2 * kWindow}) {
    const std::vector<double> rates = window.rate(w);
    EXPECT_NEAR(rates[0], kRate, 1e-9);
    // Compressed along x: the lateral stretch leads, a double eigenvalue the closed-form
    // eigensolver resolves to about 1e-8 of its size.
    EXPECT_NEAR(rates[1], kRate / 2, 1e-6);
  }
  EXPECT_THROW(window.rate(3 * kWindow), std::invalid_argument);
  EXPECT_THROW(window.add_snapshot(0.5, {Mat3d::identity(), Mat3d::identity()}), std::invalid_argument);
}

}  // namespace
}  // namespace needlefem::fields
