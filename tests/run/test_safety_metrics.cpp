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

template <class Points, class F>
std::vector<double> sample(const Points& c, F f) {
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
  // A zero field (every field at rest): every ball ties exactly, and the tie goes to the first
  // centre in lattice order, the corner voxel's (the search stops after the first block, which
  // no later block can beat, and nor can it tie in an earlier slot).
  const LocatedValue at_rest = averager.maximum(std::vector<double>(c.positions.size(), 0.0));
  EXPECT_EQ(at_rest.value, 0.0);
  const double s = 0.2e-3 / 4;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(at_rest.position[i], s / 2, 1e-15) << i;
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
  // A rough field, where the rims' bounds are loose, and a smooth peak, where they are tight and
  // skip most rims next to the best ball.
  std::vector<double> rough, peak;
  for (const Point3& x : c.positions) {
    rough.push_back(uniform(random));
    const double dx = x[0] - 0.37e-3, dy = x[1] - 0.52e-3, dz = x[2] - 0.61e-3;
    peak.push_back(std::exp(-(dx * dx + dy * dy + dz * dz) / (0.2e-3 * 0.2e-3)));
  }
  for (const auto& field : {rough, peak})
    for (double l : {0.15e-3, 0.4e-3}) {
      const BallAverager averager = averager_of(c, l);
      const double s = l / 4;
      const int centres = static_cast<int>(kSide / s);
      LocatedValue brute{-1e300, {}};
      for (int i = 0; i < centres; ++i)
        for (int j = 0; j < centres; ++j)
          for (int k = 0; k < centres; ++k) {
            const LocatedValue v = averager.average_around({(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s}, field);
            if (v.value > brute.value) brute = v;
          }
      const LocatedValue max = averager.maximum(field);
      EXPECT_DOUBLE_EQ(max.value, brute.value) << l;
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(max.position[i], brute.position[i], 1e-15) << l;
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

// The cube [0, side]³ in n³ cells of six Kuhn tetrahedra each, with `barycentric` points per
// tetrahedron (their positions and reference volumes, tetrahedron by tetrahedron).
struct TetCloud {
  std::vector<Tetrahedron> tetrahedra;
  std::vector<std::array<double, 4>> barycentric;
  std::vector<Point3> positions;
  std::vector<double> volumes;
  TissueElements elements() const { return {tetrahedra, barycentric}; }
  VolumeAbove above(const std::vector<double>& field, double t, std::span<const char> mask = {}) const {
    const TissueElements e = elements();
    return volume_above(e, e.vertex_values(field), e.selected_volumes(volumes, mask), t);
  }
  double percentile(const std::vector<double>& field, double percent, std::span<const char> mask = {}) const {
    const TissueElements e = elements();
    return volume_percentile(e.vertex_values(field), e.selected_volumes(volumes, mask), percent);
  }
};

TetCloud kuhn_cube(int n, std::vector<std::array<double, 4>> barycentric) {
  TetCloud c;
  c.barycentric = std::move(barycentric);
  const double h = kSide / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        std::array<int, 3> axes{0, 1, 2};
        do {
          Tetrahedron t;
          t[0] = {i * h, j * h, k * h};
          for (int v = 1; v < 4; ++v) {
            t[v] = t[v - 1];
            t[v][axes[v - 1]] += h;
          }
          c.tetrahedra.push_back(t);
          for (const auto& l : c.barycentric) {
            Point3 x{};
            for (int v = 0; v < 4; ++v)
              for (int d = 0; d < 3; ++d) x[d] += l[v] * t[v][d];
            c.positions.push_back(x);
            c.volumes.push_back(h * h * h / 6.0 / c.barycentric.size());
          }
        } while (std::next_permutation(axes.begin(), axes.end()));
      }
  return c;
}

// TET10's 4-point rule (Keast): barycentric (a, b, b, b) and permutations.
std::vector<std::array<double, 4>> keast_points() {
  const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
  return {{a, b, b, b}, {b, a, b, b}, {b, b, a, b}, {b, b, b, a}};
}

TEST(SafetyMetrics, TetrahedronPartAboveALinearField) {
  // The share of a tetrahedron where a linear field with distinct vertex values c_i exceeds t is
  // the divided difference Σ_i (c_i - t)₊³ / Π_{j≠i} (c_i - c_j) (the field's distribution over
  // the tetrahedron is the quadratic B-spline on the knots c_i); the centroid against Monte Carlo
  // samples of the uniform distribution on the tetrahedron.
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::array<int, 5> cases{};  // by the number of vertices above
  for (int trial = 0; trial < 60; ++trial) {
    std::array<double, 4> c;
    for (double& x : c) x = uniform(random);
    const double t = 0.1 + 0.8 * uniform(random);
    double share = 0.0;
    int above = 0;
    for (int i = 0; i < 4; ++i) {
      if (c[i] <= t) continue;
      ++above;
      double product = 1.0;
      for (int j = 0; j < 4; ++j)
        if (j != i) product *= c[i] - c[j];
      share += std::pow(c[i] - t, 3) / product;
    }
    ++cases[above];
    const TetrahedronPart part = part_above(c, t);
    EXPECT_NEAR(part.fraction, share, 1e-9) << trial;
    if (trial % 6 != 0 || part.fraction < 0.05) continue;
    std::array<double, 4> centroid{};
    int inside = 0;
    for (int s = 0; s < 200000; ++s) {
      std::array<double, 4> l;
      double sum = 0.0;
      for (double& x : l) sum += x = -std::log(1.0 - uniform(random));
      double f = 0.0;
      for (int i = 0; i < 4; ++i) f += (l[i] /= sum) * c[i];
      if (f <= t) continue;
      ++inside;
      for (int i = 0; i < 4; ++i) centroid[i] += l[i];
    }
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(part.centroid[i], centroid[i] / inside, 5e-3) << trial << " " << i;
  }
  EXPECT_GT(cases[1] * cases[2] * cases[3], 0);  // every cut: a corner, a prism, all but a corner
  EXPECT_EQ(part_above({0.0, 1.0, 2.0, 3.0}, 3.0).fraction, 0.0);
  EXPECT_EQ(part_above({0.0, 1.0, 2.0, 3.0}, -1.0).fraction, 1.0);
}

TEST(SafetyMetrics, VolumeAboveALimitAndItsCentroid) {
  // A linear field: its volume above t = 0.713 is (1 - t) side³ on any mesh, with centroid
  // x = (1 + t)/2 side. The points' own volumes above t (a whole w_q per point above) miss it by
  // part of a cell layer, the error the cut removes.
  const TetCloud c = kuhn_cube(10, keast_points());
  const auto field = sample(c, [](const Point3& x) { return x[0] / kSide; });
  const double t = 0.713, cube = std::pow(kSide, 3);
  const VolumeAbove above = c.above(field, t);
  EXPECT_NEAR(above.volume, (1.0 - t) * cube, 1e-12 * cube);
  EXPECT_NEAR(above.centroid[0], (1.0 + t) / 2 * kSide, 1e-12 * kSide);
  EXPECT_NEAR(above.centroid[1], 0.5 * kSide, 1e-12 * kSide);
  double points_above = 0.0;
  for (std::size_t q = 0; q < field.size(); ++q)
    if (field[q] > t) points_above += c.volumes[q];
  EXPECT_GT(std::abs(points_above - (1.0 - t) * cube), 0.01 * cube);  // what the test tells apart
  // Inside the region y < 0.5 mm only: half of it.
  std::vector<char> lower_half;
  for (const Point3& x : c.positions) lower_half.push_back(x[1] < 0.5e-3);
  const VolumeAbove half = c.above(field, t, lower_half);
  EXPECT_NEAR(half.volume, (1.0 - t) / 2 * cube, 1e-12 * cube);
  EXPECT_NEAR(half.centroid[1], 0.25e-3, 1e-12 * kSide);
  EXPECT_EQ(c.above(field, 2.0).volume, 0.0);
  // One point per element (TET4): a constant field per element, counted whole or not at all.
  const TetCloud centroids = kuhn_cube(10, {{0.25, 0.25, 0.25, 0.25}});
  const auto constant = sample(centroids, [](const Point3& x) { return x[0] / kSide; });
  double whole = 0.0;
  for (std::size_t q = 0; q < constant.size(); ++q)
    if (constant[q] > t) whole += centroids.volumes[q];
  EXPECT_NEAR(centroids.above(constant, t).volume, whole, 1e-12 * cube);
}

TEST(SafetyMetrics, VolumeAboveASmoothFieldConvergesAtSecondOrder) {
  // f = |x|²/side² over the cube is above t = 1/2 outside the sphere octant of radius side/√2:
  // volume (1 - π/6 (1/2)^(3/2)) side³. The linear field per element misses it by O(h²) (here
  // faster: the level surface's errors partly cancel), 27–120 times less than the points' own
  // volumes above t do on these meshes.
  const double t = 0.5, exact = 1.0 - M_PI / 6.0 * std::pow(0.5, 1.5);
  std::vector<double> errors, point_errors;
  for (int n : {8, 16, 32}) {
    const TetCloud c = kuhn_cube(n, keast_points());
    const auto field =
        sample(c, [](const Point3& x) { return (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) / (kSide * kSide); });
    errors.push_back(std::abs(c.above(field, t).volume / std::pow(kSide, 3) - exact));
    double points_above = 0.0;
    for (std::size_t q = 0; q < field.size(); ++q)
      if (field[q] > t) points_above += c.volumes[q];
    point_errors.push_back(std::abs(points_above / std::pow(kSide, 3) - exact));
  }
  for (int k : {0, 1}) EXPECT_GT(std::log2(errors[k] / errors[k + 1]), 1.9) << k;
  EXPECT_LT(errors[2], 1e-6);
  EXPECT_GT(point_errors[2], 50 * errors[2]);  // what the test tells apart
}

TEST(SafetyMetrics, VolumePercentileOfAUniformlyDistributedField) {
  // f = x/side is uniform on (0, 1) by volume: its P-th percentile is P/100, exactly for the
  // linear field per element.
  const TetCloud c = kuhn_cube(10, keast_points());
  const auto field = sample(c, [](const Point3& x) { return x[0] / kSide; });
  for (double percent : {50.0, 90.0, 99.0, 99.9})
    EXPECT_NEAR(c.percentile(field, percent), percent / 100.0, 1e-9) << percent;
  // Over the region x > 0.5 mm, f is uniform on (0.5, 1).
  std::vector<char> right;
  for (const Point3& x : c.positions) right.push_back(x[0] > 0.5e-3);
  EXPECT_NEAR(c.percentile(field, 90.0, right), 0.95, 1e-9);
  EXPECT_THROW(c.percentile(field, 100.0), std::invalid_argument);
  // A homogeneous field up to round-off (its range a few ulps, below any relative tolerance).
  std::vector<double> homogeneous(field.size(), 0.3);
  for (std::size_t q = 0; q < homogeneous.size(); q += 7) homogeneous[q] = std::nextafter(0.3, 1.0);
  EXPECT_NEAR(c.percentile(homogeneous, 99.0), 0.3, 1e-15);
  // f = |x|²/side²: the volume above v <= 1 is (1 - π/6 v^(3/2)) side³, so the median is (3/π)^(2/3),
  // to the volume's error at n = 16 (7e-6 above) over the slope π/4 v^(1/2).
  const TetCloud fine = kuhn_cube(16, keast_points());
  const auto square =
      sample(fine, [](const Point3& x) { return (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) / (kSide * kSide); });
  EXPECT_NEAR(fine.percentile(square, 50.0), std::pow(3.0 / M_PI, 2.0 / 3.0), 2e-5);
  // One point per element: the value of the element whose volume, hottest first, passes the share.
  const TetCloud centroids = kuhn_cube(10, {{0.25, 0.25, 0.25, 0.25}});
  auto constant = sample(centroids, [](const Point3& x) { return x[0] / kSide + 0.1 * x[1] / kSide; });
  std::vector<double> sorted = constant;
  std::sort(sorted.begin(), sorted.end(), std::greater<>());
  const double percentile = centroids.percentile(constant, 90.0);
  const std::size_t hottest = static_cast<std::size_t>(0.1 * sorted.size());  // equal volumes
  EXPECT_NEAR(percentile, sorted[hottest], 1e-9);
}

}  // namespace
}  // namespace needlefem::fields
