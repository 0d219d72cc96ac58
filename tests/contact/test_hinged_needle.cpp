// The hinged compliant needle (physics/contact/hinged_needle.hpp) against independent references:
// gaps of points placed at known distances from the shaft, the neck, the head's cylinder and cone
// and the rounded point (closed forms); n = ∂g/∂x and G = ∂n/∂x by central differences; the head
// turned about the pivot by its tilt (the pivot stays, the head's axis turns towards the pull);
// the velocity field against the time derivative of the pose, W = ∂w/∂x, and ∂g/∂t = -n·w.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "obstacle_derivatives.hpp"
#include "physics/contact/hinged_needle.hpp"

namespace needlefem::contact {
namespace {

constexpr double kPi = std::numbers::pi;
// Paper 000's tip (cases/compliant): r 0.5, shaft 0.1, neck 1 x 0.2, head 3.5 with a 0.5 mm point.
constexpr double r = 0.5e-3, s = 0.1e-3, l = 1.0e-3, d = 0.2e-3, L = 3.5e-3, p = 0.5e-3;
constexpr double kEdgeRadius = 100e-6;
const CompliantTip kTip{r, s, l, d, L, p};
const NeedleMotion kMotion{1e-3, 0.0, 1.0, 0.0};  // 1 mm/s, no rotation, for 1 s

double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::shared_ptr<const HeadTilt> ramped_tilt(double angle, double azimuth) {
  // Tilt towards (cos ψ, sin ψ, 0): rotation vector angle · e_z × e = angle (-sin ψ, cos ψ).
  return std::make_shared<HeadTilt>(std::vector<double>{0.0, 0.5, 1.0},
                                    std::vector<std::array<double, 2>>{{0.0, 0.0},
                                                                       {-0.5 * angle * std::sin(azimuth), 0.5 * angle * std::cos(azimuth)},
                                                                       {-angle * std::sin(azimuth), angle * std::cos(azimuth)}});
}

TEST(HingedNeedle, GapsOfPointsAtKnownDistances) {
  const HingedNeedle needle(kTip, kMotion, kEdgeRadius, nullptr);
  const double delta = 30e-6;
  const double head_z = s + l + 1.0e-3, cone_start = s + l + L - p, tip_z = s + l + L;
  struct Case {
    const char* what;
    Point3 x;
    double gap;
    int body;
  };
  const double beta = std::atan(r / p);  // the cone's half-angle
  const Point3 cone_normal{std::cos(beta), 0.0, std::sin(beta)};
  const double on_cone_R = 0.5 * r, on_cone_z = cone_start + (r - on_cone_R) / std::tan(beta);
  const double rho = kEdgeRadius;
  const Case cases[] = {
      {"shaft side", {0.0, -(r + delta), -2e-3}, delta, HingedNeedle::stem},
      {"inside the shaft", {r - delta, 0.0, -2e-3}, -delta, HingedNeedle::stem},
      {"neck, stem half", {(d / 2 + delta) * std::cos(1.0), (d / 2 + delta) * std::sin(1.0), s + 0.2 * l}, delta,
       HingedNeedle::stem},
      {"neck, head half", {d / 2 + delta, 0.0, s + 0.8 * l}, delta, HingedNeedle::head},
      {"head cylinder", {0.0, r + delta, head_z}, delta, HingedNeedle::head},
      {"cone", {on_cone_R + delta * cone_normal[0], 0.0, on_cone_z + delta * cone_normal[2]}, delta,
       HingedNeedle::head},
      // Ahead of the point on the axis: the rounded point's centre lies ρ/sin β behind the sharp one.
      {"rounded point", {0.0, 0.0, tip_z + delta}, delta + rho / std::sin(beta) - rho, HingedNeedle::head},
  };
  for (const Case& c : cases) {
    const ObstacleProjection got = needle.project(c.x, 0.0);
    EXPECT_NEAR(got.gap, c.gap, 1e-15) << c.what;
    EXPECT_EQ(got.body, c.body) << c.what;
  }
}

void expect_derivatives(const HingedNeedle& needle, const Point3& x, double t, const char* what) {
  expect_gap_derivatives([&](const Point3& at) { return needle.project(at, t); }, x, 1.0 / r, 1e-5, what);
}

TEST(HingedNeedle, NormalAndItsGradientAreDerivativesOfTheGap) {
  const HingedNeedle needle(kTip, kMotion, kEdgeRadius, ramped_tilt(0.3, 0.7));
  const double t = 0.6;  // tilted, and moving
  const Point3 pivot = needle.pivot(t), axis = needle.head_axis(t);
  // Points on and off the surfaces of both bodies (neither on a body's boundary between solids).
  const Point3 across{-axis[2] * std::cos(0.7), -axis[2] * std::sin(0.7), std::hypot(axis[0], axis[1])};
  auto along_head = [&](double z, double radial) {
    return Point3{pivot[0] + z * axis[0] + radial * across[0], pivot[1] + z * axis[1] + radial * across[1],
                  pivot[2] + z * axis[2] + radial * across[2]};
  };
  expect_derivatives(needle, {0.2e-3, -0.5e-3, -1e-3 + 0.6e-3}, t, "shaft side");
  expect_derivatives(needle, {0.35e-3, 0.4e-3, 0.1e-3 + 0.6e-3}, t, "shaft front rim");
  expect_derivatives(needle, along_head(l / 2 + 1.5e-3, r + 20e-6), t, "head cylinder");
  expect_derivatives(needle, along_head(l / 2 + 1.5e-3, -(r - 20e-6)), t, "inside the head");
  expect_derivatives(needle, along_head(l / 2 + L - 0.2e-3, 0.25e-3), t, "cone");
  expect_derivatives(needle, along_head(l / 2 + L + 40e-6, 10e-6), t, "rounded point");
  expect_derivatives(needle, along_head(l / 2 + 1e-6, -(r + 50e-6)), t, "head's rear rim");
}

TEST(HingedNeedle, TheHeadTurnsAboutThePivotTowardsThePull) {
  const double angle = 0.4, azimuth = 0.7;
  const HingedNeedle needle(kTip, kMotion, kEdgeRadius, ramped_tilt(angle, azimuth));
  const double t = 1.0, travel = kMotion.insertion_speed * t;
  const Point3 axis = needle.head_axis(t);
  EXPECT_NEAR(axis[0], std::sin(angle) * std::cos(azimuth), 1e-15);
  EXPECT_NEAR(axis[1], std::sin(angle) * std::sin(azimuth), 1e-15);
  EXPECT_NEAR(axis[2], std::cos(angle), 1e-15);
  const Point3 pivot = needle.pivot(t);
  EXPECT_NEAR(pivot[2], s + l / 2 + travel, 1e-15);
  // The head's point: a = l/2 + L ahead of the pivot along the axis; the stem only translates.
  const Point3 point = needle.from_body({0.0, 0.0, s + l + L}, t);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(point[i], pivot[i] + (l / 2 + L) * axis[i], 1e-15);
  const Point3 shaft = needle.from_body({r, 0.0, 0.0}, t);
  EXPECT_NEAR(shaft[0], r, 1e-18);
  EXPECT_NEAR(shaft[2], travel, 1e-18);
  for (const Point3& xi : {Point3{0.1e-3, 0.2e-3, 3e-3}, Point3{0.3e-3, -0.1e-3, -1e-3}}) {
    const Point3 back = needle.to_body(needle.from_body(xi, t), t);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], xi[i], 1e-18);
  }
  // The head's gap moves with it: its point, moved along the axis, is as far from it as before.
  EXPECT_NEAR(needle.project({point[0] + 30e-6 * axis[0], point[1] + 30e-6 * axis[1], point[2] + 30e-6 * axis[2]}, t).gap,
              needle.project({0.0, 0.0, s + l + L + 30e-6}, 0.0).gap, 1e-15);
}

TEST(HingedNeedle, VelocityFieldIsTheRateOfThePose) {
  const HingedNeedle needle(kTip, kMotion, kEdgeRadius, ramped_tilt(0.3, 2.0));
  const double t = 0.7, dt = 1e-7;
  for (const Point3& X : {Point3{0.45e-3, 0.1e-3, 3e-3}, Point3{0.1e-3, 0.5e-3, -0.5e-3}}) {
    const Point3 x = needle.from_body(X, t);
    const ObstacleProjection pr = needle.project(x, t);
    const Point3 ahead = needle.from_body(X, t + dt), behind = needle.from_body(X, t - dt);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR((ahead[i] - behind[i]) / (2 * dt), pr.velocity[i], 1e-11);
    const double rate = (needle.project(x, t + dt).gap - needle.project(x, t - dt).gap) / (2 * dt);
    EXPECT_NEAR(rate, -dot(pr.normal, pr.velocity), 1e-9);
    expect_velocity_gradient(needle, x, t);
  }
}

TEST(HingedNeedle, RejectsImpossibleTipsAndTilts) {
  EXPECT_THROW(HingedNeedle(CompliantTip{r, s, l, 2 * r, L, p}, kMotion, kEdgeRadius, nullptr), std::invalid_argument);
  EXPECT_THROW(HingedNeedle(kTip, kMotion, 0.0, nullptr), std::invalid_argument);
  EXPECT_THROW(HeadTilt({0.0, 0.0}, {{0.0, 0.0}, {0.1, 0.0}}), std::invalid_argument);
  EXPECT_THROW(HeadTilt({0.0}, {}), std::invalid_argument);
  const HeadTilt none;
  EXPECT_EQ(none.at(3.0)[0], 0.0);
}

}  // namespace
}  // namespace needlefem::contact
