// Mesh-objective safety metrics (physics/fields/safety_metrics.hpp) against closed forms, on a
// cube of side 1 mm sampled at the centres of n³ cubic cells (midpoint rule, volume h³ each).
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "physics/fields/safety_metrics.hpp"

namespace needlefem::fields {
namespace {

constexpr double kSide = 1e-3;  // m

struct Cloud {
  std::vector<Point3> positions;
  std::vector<double> volumes;
  std::vector<Tetrahedron> tissue;  // the cube as six tetrahedra
  double h = 0.0;
};

// The cube [x0, x0 + side] x [0, side]²: its cell centres and its Kuhn tetrahedra (one per
// ordering of the axes, from the corner nearest the origin to the farthest).
Cloud cube(int n, double x0 = 0.0) {
  Cloud c;
  c.h = kSide / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        c.positions.push_back({x0 + (i + 0.5) * c.h, (j + 0.5) * c.h, (k + 0.5) * c.h});
        c.volumes.push_back(c.h * c.h * c.h);
      }
  std::array<int, 3> axes{0, 1, 2};
  do {
    Tetrahedron t;
    t[0] = {x0, 0.0, 0.0};
    for (int v = 1; v < 4; ++v) {
      t[v] = t[v - 1];
      t[v][axes[v - 1]] += kSide;
    }
    c.tissue.push_back(t);
  } while (std::next_permutation(axes.begin(), axes.end()));
  return c;
}

BallAverager averager_of(const Cloud& c, double radius) { return BallAverager(c.positions, c.volumes, c.tissue, radius); }

template <class F>
std::vector<double> sample(const Cloud& c, F f) {
  std::vector<double> v;
  for (const Point3& x : c.positions) v.push_back(f(x));
  return v;
}

// The average of x over the part x' >= -d of a ball of radius l around x = d (the ball's centre at
// height d over the face x = 0), in closed form.
double truncated_ball_mean(double d, double l) {
  const double volume = l * l * (l + d) - (l * l * l - d * d * d) / 3.0;  // ∫_{-d}^{l} (l² - x²) dx
  const double moment = l * l * l * l / 4.0 - (l * l * d * d / 2.0 - d * d * d * d / 4.0);
  return d + moment / volume;
}

TEST(SafetyMetrics, HomogeneousFieldAveragesToItsValue) {
  const Cloud c = cube(20);
  const std::vector<double> field(c.positions.size(), 0.137);
  const BallAverager averager = averager_of(c, 0.2e-3);
  EXPECT_NEAR(averager.maximum(field).value, 0.137, 1e-14);
  EXPECT_NEAR(averager.average_around({0.0, 0.0, 0.0}, field).value, 0.137, 1e-14);  // an eighth of a ball
}

TEST(SafetyMetrics, LinearFieldInAFullBallAveragesToTheCentreValue) {
  // The ball's centre lies midway between grid points, so the points inside it are symmetric
  // about it and the average is exact.
  const Cloud c = cube(40);
  const auto f = [](const Point3& x) { return 2.0 + 300.0 * x[0] - 100.0 * x[1] + 50.0 * x[2]; };
  const auto field = sample(c, f);
  const BallAverager averager = averager_of(c, 0.2e-3);
  const LocatedValue around = averager.average_around({0.5e-3, 0.45e-3, 0.52e-3}, field);
  EXPECT_NEAR(around.value, f(around.position), 1e-12);
  EXPECT_NEAR(around.position[0], 0.525e-3, 1e-15);  // the centre of the voxel [0.50, 0.55) mm
}

TEST(SafetyMetrics, QuadraticFieldAveragesToThreeFifthsOfTheRadiusSquared) {
  // f = |X - c|²/ℓ² over a full ball of radius ℓ: 3/5, to the sampling of the ball's rim.
  const Cloud c = cube(60);
  const double l = 0.3e-3;
  const Point3 centre{0.4875e-3, 0.4875e-3, 0.4875e-3};  // a lattice voxel's centre (s = 75 µm)
  const auto field = sample(c, [&](const Point3& x) {
    return (std::pow(x[0] - centre[0], 2) + std::pow(x[1] - centre[1], 2) + std::pow(x[2] - centre[2], 2)) / (l * l);
  });
  const BallAverager averager = averager_of(c, l);
  EXPECT_NEAR(averager.average_around(centre, field).value, 0.6, 0.6 * 0.01);
}

TEST(SafetyMetrics, LinearFieldAtAFaceAveragesOverTheTruncatedBall) {
  // f = x/ℓ: a ball centred s/2 inside the face x = 0 averages x over its tissue part only; the
  // largest average over the cube is the mirror image at the face x = 1 mm.
  for (int n : {40, 80}) {
    const Cloud c = cube(n);
    const double l = 0.2e-3, s = l / 4;
    const auto field = sample(c, [&](const Point3& x) { return x[0] / l; });
    const BallAverager averager = averager_of(c, l);
    const double near_face = truncated_ball_mean(s / 2, l) / l;
    EXPECT_NEAR(averager.average_around({0.0, 0.5e-3, 0.5e-3}, field).value, near_face, 0.01 * near_face) << n;
    const LocatedValue max = averager.maximum(field);
    const double expected = (kSide - truncated_ball_mean(s / 2, l)) / l;
    EXPECT_NEAR(max.value, expected, 0.01 * expected) << n;
    EXPECT_NEAR(max.position[0], kSide - s / 2, 1e-15) << n;
  }
}

TEST(SafetyMetrics, MaximumEqualsTheBruteForceMaximumOfEveryBall) {
  // Every lattice centre in the cube, one by one (a block's edge, ℓ, exceeds the points' spacing,
  // so each centre's block holds points).
  const Cloud c = cube(12);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> field;
  for (std::size_t q = 0; q < c.positions.size(); ++q) field.push_back(uniform(random));
  for (double l : {0.15e-3, 0.4e-3}) {
    const BallAverager averager = averager_of(c, l);
    const double s = l / 4;
    const int centres = static_cast<int>(kSide / s);
    double brute = -1e300;
    for (int i = 0; i < centres; ++i)
      for (int j = 0; j < centres; ++j)
        for (int k = 0; k < centres; ++k)
          brute = std::max(brute, averager.average_around({(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s}, field).value);
    EXPECT_DOUBLE_EQ(averager.maximum(field).value, brute) << l;
  }
}

TEST(SafetyMetrics, BallCentresLieInTheTissue) {
  // The face x = x0 = 0.7 s cuts the first voxel layer [0, s): that voxel holds tissue points but
  // its centre s/2 lies outside. f = 1 - (x - x0)/ℓ is largest at the face; the largest average
  // is the truncated ball centred at the first centre inside, x = 3s/2, 0.8 s from the face (a
  // centre at s/2, 0.2 s outside, would average a thinner shell to a value 21 % larger).
  const double l = 0.2e-3, s = l / 4, x0 = 0.7 * s;
  const Cloud c = cube(80, x0);
  const auto field = sample(c, [&](const Point3& x) { return 1.0 - (x[0] - x0) / l; });
  const LocatedValue max = averager_of(c, l).maximum(field);
  const double expected = 1.0 - truncated_ball_mean(0.8 * s, l) / l;
  EXPECT_NEAR(max.position[0], 1.5 * s, 1e-15);
  EXPECT_NEAR(max.value, expected, 0.01 * expected);
  EXPECT_GT(1.0 - truncated_ball_mean(-0.2 * s, l) / l, 1.2 * expected);  // what the test tells apart
}

TEST(SafetyMetrics, VolumeAboveALimitAndItsCentroid) {
  const Cloud c = cube(20);
  const auto field = sample(c, [](const Point3& x) { return x[0] / kSide; });
  const VolumeAbove above = volume_above(field, c.volumes, c.positions, 0.7);
  EXPECT_NEAR(above.volume, 0.3 * std::pow(kSide, 3), 1e-12 * std::pow(kSide, 3));
  EXPECT_NEAR(above.centroid[0], 0.85e-3, 1e-15);
  EXPECT_NEAR(above.centroid[1], 0.5e-3, 1e-15);
  // Inside the region y < 0.5 mm only: half of it.
  std::vector<char> lower_half;
  for (const Point3& x : c.positions) lower_half.push_back(x[1] < 0.5e-3);
  const VolumeAbove half = volume_above(field, c.volumes, c.positions, 0.7, lower_half);
  EXPECT_NEAR(half.volume, 0.15 * std::pow(kSide, 3), 1e-12 * std::pow(kSide, 3));
  EXPECT_NEAR(half.centroid[1], 0.25e-3, 1e-15);
  EXPECT_EQ(volume_above(field, c.volumes, c.positions, 2.0).volume, 0.0);
}

TEST(SafetyMetrics, VolumePercentileOfAUniformlyDistributedField) {
  // f = x/side is uniform on (0, 1) by volume: its P-th percentile is P/100, to a cell.
  const Cloud c = cube(50);
  const auto field = sample(c, [](const Point3& x) { return x[0] / kSide; });
  for (double percent : {50.0, 90.0, 99.0})
    EXPECT_NEAR(volume_percentile(field, c.volumes, percent), percent / 100.0, 1.0 / 50) << percent;
  // Over the region x > 0.5 mm, f is uniform on (0.5, 1).
  std::vector<char> right;
  for (const Point3& x : c.positions) right.push_back(x[0] > 0.5e-3);
  EXPECT_NEAR(volume_percentile(field, c.volumes, 90.0, right), 0.95, 1.0 / 50);
  EXPECT_THROW(volume_percentile(field, c.volumes, 100.0), std::invalid_argument);
}

}  // namespace
}  // namespace needlefem::fields
