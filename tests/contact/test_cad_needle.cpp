// The triangulated-surface needle (physics/contact/triangle_surface.hpp, cad_needle.hpp) against
// independent references: distances to a sphere, a box and a cylinder in closed form, the grid
// search against brute force, the edge rounding against the distance to a rounded box, the
// normal's continuity across a rounded edge, and the gap spline (gap_spline.hpp): a cubic
// reproduced exactly (also with a node limit that grows its spacing), a sphere's distance, the shaft as a prism, and a curvature that does not see
// the facets.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <map>
#include <random>

#include "physics/contact/cad_needle.hpp"
#include "physics/contact/gap_spline.hpp"
#include "physics/contact/triangle_surface.hpp"

namespace needlefem::contact {
namespace {

constexpr double kPi = 3.14159265358979323846;

double norm(const Point3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// Sphere of radius R: an octahedron subdivided `levels` times, vertices pushed onto the sphere.
TriangleSoup sphere(double R, int levels) {
  TriangleSoup s;
  s.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, fresh] = mid.emplace(key, static_cast<int>(s.vertices.size()));
      if (fresh) {
        Point3 m{};
        for (int d = 0; d < 3; ++d) m[d] = 0.5 * (s.vertices[a][d] + s.vertices[b][d]);
        s.vertices.push_back(m);
      }
      return it->second;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& [a, b, c] : s.triangles) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
    }
    s.triangles = finer;
  }
  for (auto& v : s.vertices) {
    const double l = norm(v);
    for (auto& c : v) c *= R / l;
  }
  return s;
}

// Box [x0, x1] x [y0, y1] x [z0, z1], each face an n x n grid of squares split in two; shared
// vertices along the edges (a closed surface), outward triangles.
TriangleSoup box(const Point3& lo, const Point3& hi, int n) {
  TriangleSoup s;
  std::map<std::array<long, 3>, int> index;
  auto vertex = [&](const Point3& p) {
    const std::array<long, 3> key{std::lround(p[0] * 1e9), std::lround(p[1] * 1e9), std::lround(p[2] * 1e9)};
    auto [it, fresh] = index.emplace(key, static_cast<int>(s.vertices.size()));
    if (fresh) s.vertices.push_back(p);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      auto at = [&](int i, int j) {
        Point3 p{};
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = lo[u] + (hi[u] - lo[u]) * i / n;
        p[w] = lo[w] + (hi[w] - lo[w]) * j / n;
        return vertex(p);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          if (side) s.triangles.insert(s.triangles.end(), {{a, b, c}, {a, c, d}});
          else s.triangles.insert(s.triangles.end(), {{a, c, b}, {a, d, c}});
        }
    }
  return s;
}

// Closed cylinder of radius r along z from 0 to L: `m` segments round, `k` along, fan caps.
TriangleSoup cylinder(double r, double L, int m, int k) {
  TriangleSoup s;
  for (int j = 0; j <= k; ++j)
    for (int i = 0; i < m; ++i)
      s.vertices.push_back({r * std::cos(2 * kPi * i / m), r * std::sin(2 * kPi * i / m), L * j / k});
  const int bottom = static_cast<int>(s.vertices.size()), top = bottom + 1;
  s.vertices.push_back({0, 0, 0});
  s.vertices.push_back({0, 0, L});
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < m; ++i) {
      const int a = j * m + i, b = j * m + (i + 1) % m, c = a + m, d = b + m;
      s.triangles.insert(s.triangles.end(), {{a, b, d}, {a, d, c}});
    }
  for (int i = 0; i < m; ++i) {
    s.triangles.push_back({bottom, (i + 1) % m, i});
    s.triangles.push_back({top, k * m + i, k * m + (i + 1) % m});
  }
  return s;
}

Point3 random_point(std::mt19937& rng, double extent) {
  std::uniform_real_distribution<double> u(-extent, extent);
  return {u(rng), u(rng), u(rng)};
}

TEST(TriangleSurface, TreeSearchEqualsBruteForce) {
  const TriangleSurface surface(sphere(1.0, 4));
  std::mt19937 rng(7);
  for (int q = 0; q < 2000; ++q) {
    const Point3 x = random_point(rng, 2.5);  // inside, near and far outside
    EXPECT_DOUBLE_EQ(surface.closest(x).distance, surface.closest_brute_force(x).distance);
  }
}

TEST(TriangleSurface, SphereDistanceWithinTheFacetSagitta) {
  const double R = 1.0;
  const TriangleSoup s = sphere(R, 5);  // 8192 facets, edges of at most 0.05 R
  const TriangleSurface surface(s);
  const double sagitta = std::pow(0.05 * R, 2) / (2 * R);  // a facet's depth below the sphere
  std::mt19937 rng(3);
  for (int q = 0; q < 500; ++q) {
    const Point3 x = random_point(rng, 1.6);
    const double exact = norm(x) - R;
    if (std::abs(exact) > 0.9 * R) continue;
    EXPECT_NEAR(surface.signed_distance(x), exact, sagitta) << x[0] << " " << x[1] << " " << x[2];
  }
}

TEST(TriangleSurface, BoxFacesAreExact) {
  const TriangleSurface surface(box({-1, -1, 0}, {1, 1, 3}, 8));
  // Points whose closest point is on a face: the distance to its plane, with the sign.
  EXPECT_NEAR(surface.signed_distance({0.3, 0.2, 3.5}), 0.5, 1e-12);
  EXPECT_NEAR(surface.signed_distance({0.3, -1.25, 1.0}), 0.25, 1e-12);
  EXPECT_NEAR(surface.signed_distance({0.9, 0.1, 1.5}), -0.1, 1e-12);
  // Outside an edge and a corner: the distance to the edge line and to the corner.
  EXPECT_NEAR(surface.signed_distance({1.3, 0.0, 3.4}), 0.5, 1e-12);
  EXPECT_NEAR(surface.signed_distance({2.0, 2.0, 4.0}), std::sqrt(3.0), 1e-12);
}

TEST(TriangleSurface, OrientsAnyClosedTriangulationOutward) {
  TriangleSoup s = box({0, 0, 0}, {1, 2, 3}, 3);
  for (std::size_t t = 0; t < s.triangles.size(); t += 3) std::swap(s.triangles[t][1], s.triangles[t][2]);
  EXPECT_EQ(orient_outward(s), 0u);
  EXPECT_NEAR(enclosed_volume(s), 6.0, 1e-12);
  s.triangles.pop_back();
  EXPECT_GT(orient_outward(s), 0u);  // an open surface is reported
}

// A cylinder needle (r = 1, rear face on z = 0) without rounding: the gap is the distance to
// the cylinder (mantle or front cap) within the facet sagitta; behind z = 0 the shaft continues.
TEST(CadNeedleShape, CylinderGapsAgainstClosedForm) {
  const double r = 1.0, L = 4.0;
  const int m = 256;
  const CadNeedleShape needle(cylinder(r, L, m, 16), 0.0);
  const double sagitta = r * (1 - std::cos(kPi / m));
  for (double z : {0.5, 2.0, 3.5})
    for (double radius : {0.8, 1.05, 1.5})
      for (double angle : {0.1, 1.0, 2.5}) {
        const Point3 x{radius * std::cos(angle), radius * std::sin(angle), z};
        EXPECT_NEAR(needle.project(x).gap, radius - r, sagitta + 1e-12);
      }
  EXPECT_NEAR(needle.project({0.2, 0.1, L + 0.3}).gap, 0.3, 1e-12);  // the front cap: a plane
  EXPECT_NEAR(needle.project({1.2, 0.0, -0.2}).gap, 0.2, sagitta);   // behind the rear face: the shaft
}

// Rounding: a box needle with edge radius ρ is the box shrunk by ρ plus a ball of radius ρ. Gaps
// against that closed form, at points around the front edges and corner, within and outside it.
TEST(CadNeedleShape, RoundedEdgesMatchTheRoundedBox) {
  const double a = 1.0, L = 3.0, rho = 0.2;
  const CadNeedleShape needle(box({-a, -a, 0}, {a, a, L}, 40), rho);
  auto rounded_box_gap = [&](const Point3& x) {
    // Distance to the core [-a+ρ, a-ρ]² x [-inf, L-ρ] (the shaft goes on behind z = 0), minus ρ.
    const double hi[3] = {a - rho, a - rho, L - rho};
    double out2 = 0, inside = -1e300;
    for (int d = 0; d < 3; ++d) {
      const double e = d < 2 ? std::abs(x[d]) - hi[d] : x[d] - hi[d];
      out2 += std::pow(std::max(e, 0.0), 2);
      inside = std::max(inside, e);
    }
    return (out2 > 0 ? std::sqrt(out2) : inside) - rho;
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.5, 1.3), w(2.6, 3.3);
  for (int q = 0; q < 400; ++q) {
    const Point3 x{u(rng), (q % 2 ? 1 : -1) * u(rng) * 0.9, w(rng)};
    const double exact = rounded_box_gap(x);
    if (exact < -0.9 * rho) continue;  // deep inside: outside the rounding's reach
    EXPECT_NEAR(needle.project(x).gap, exact, 2e-3 * rho) << x[0] << " " << x[1] << " " << x[2];
  }
}

// Along a path that crosses the bisector of the front edge at a depth below ρ, the normal turns
// smoothly: no jump between neighbouring samples larger than the arc the path sweeps, and the
// normal is the gap's gradient (central differences).
TEST(CadNeedleShape, NormalIsContinuousAcrossARoundedEdge) {
  const double a = 1.0, L = 3.0, rho = 0.2;
  const CadNeedleShape needle(box({-a, -a, 0}, {a, a, L}, 40), rho);
  const int samples = 400;
  const double depth = 0.3 * rho, radius = rho - depth;  // an arc around the rounded edge's axis
  Point3 previous{};
  double largest_jump = 0;
  for (int i = 0; i <= samples; ++i) {
    const double phi = -0.2 + (kPi / 2 + 0.4) * i / samples;  // from the side face to the front face
    const Point3 x{a - rho + radius * std::cos(phi), 0.1, L - rho + radius * std::sin(phi)};
    const ObstacleProjection p = needle.project(x);
    if (i > 0) {
      Point3 d{p.normal[0] - previous[0], p.normal[1] - previous[1], p.normal[2] - previous[2]};
      largest_jump = std::max(largest_jump, norm(d));
    }
    previous = p.normal;
    const double h = 1e-7;
    for (int k = 0; k < 3; ++k) {
      Point3 plus = x, minus = x;
      plus[k] += h;
      minus[k] -= h;
      EXPECT_NEAR((needle.project(plus).gap - needle.project(minus).gap) / (2 * h), p.normal[k], 1e-5);
    }
  }
  const double step = (kPi / 2 + 0.4) / samples;
  EXPECT_LT(largest_jump, 3 * step);  // the sweep turns the normal by `step` per sample
  // Without rounding the normal jumps by |n1 - n2| = sqrt(2) at the bisector.
  const CadNeedleShape sharp(box({-a, -a, 0}, {a, a, L}, 40), 0.0);
  const double before = sharp.project({a - 0.1, 0.1, L - 0.1 - 1e-6}).normal[0];
  const double after = sharp.project({a - 0.1 - 1e-6, 0.1, L - 0.1}).normal[0];
  EXPECT_GT(std::abs(before - after), 0.9);
}

// The quasi-interpolant reproduces cubics: a cubic with a gradient below 1 (so that the coarse pass
// may skip nodes by the Lipschitz bound) comes back with its value, gradient and Hessian to
// rounding wherever the spline answers.
TEST(GapSpline, ReproducesACubicExactly) {
  auto p = [](const Point3& x) {
    return 0.3 * (x[0] - 0.5) + 0.02 * std::pow(x[1] - 0.5, 3) + 0.01 * x[0] * x[1] * x[2] - 0.02 * x[2] * x[2];
  };
  const double h = 0.1;
  const GapSpline spline({0, 0, 0}, {1, 1, 1}, h, 0.0, false, 1e9, p);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int answered = 0;
  for (int q = 0; q < 500; ++q) {
    const Point3 x{u(rng), u(rng), u(rng)};
    const auto s = spline.project(x);
    if (!s) {
      EXPECT_GT(std::abs(p(x)), GapSpline::kTrustCells * h * 0.99);  // declined only outside the band
      continue;
    }
    ++answered;
    const Point3 gradient{0.3 + 0.01 * x[1] * x[2], 0.06 * std::pow(x[1] - 0.5, 2) + 0.01 * x[0] * x[2],
                          0.01 * x[0] * x[1] - 0.04 * x[2]};
    const double hessian[9] = {0, 0.01 * x[2], 0.01 * x[1], 0.01 * x[2], 0.12 * (x[1] - 0.5), 0.01 * x[0],
                               0.01 * x[1], 0.01 * x[0], -0.04};
    EXPECT_NEAR(s->gap, p(x), 1e-13);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(s->normal[i], gradient[i], 1e-12);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(s->normal_gradient[i], hessian[i], 1e-10);
  }
  EXPECT_GT(answered, 200);
}

// A node limit that binds: the spacing grows until the grid fits, so the spline queries the gap
// at no more nodes than the limit (and the coarse pass), still reproduces a cubic, and answers
// farther from the surface (kTrustCells times the grown spacing); a limit below kMinNodeLimit is
// refused.
TEST(GapSpline, NodeLimitGrowsTheSpacing) {
  auto p = [](const Point3& x) {
    return 0.3 * (x[0] - 0.5) + 0.02 * std::pow(x[1] - 0.5, 3) + 0.01 * x[0] * x[1] * x[2] - 0.02 * x[2] * x[2];
  };
  const double h = 0.03;  // on the unit cube grown by the band and the stencil: 59³ = 205k nodes
  std::atomic<long> queries{0};
  auto counted = [&](const Point3& x) {
    ++queries;
    return p(x);
  };
  const GapSpline free_grid({0, 0, 0}, {1, 1, 1}, h, 0.0, false, 1e9, counted);
  const long free_queries = queries.exchange(0);
  const double limit = GapSpline::kMinNodeLimit;
  const GapSpline capped({0, 0, 0}, {1, 1, 1}, h, 0.0, false, limit, counted);
  EXPECT_GT(free_queries, 2 * limit);
  EXPECT_LE(queries.load(), 1.05 * limit) << "every node and the coarse pass's every fourth";
  // p = 0.087 here: beyond kTrustCells h = 0.075 of the requested spacing, within that of the
  // grown one (the grid fits 1e5 nodes only from h = 0.047 on).
  const Point3 x{0.8, 0.5, 0.5};
  EXPECT_FALSE(free_grid.project(x).has_value());
  const auto s = capped.project(x);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->gap, p(x), 1e-13);
  EXPECT_NEAR(s->normal[0], 0.3 + 0.01 * x[1] * x[2], 1e-12);
  EXPECT_THROW(GapSpline({0, 0, 0}, {1, 1, 1}, h, 0.0, false, 0.5 * limit, p), std::invalid_argument);
}

// A sphere's gap |x| - R: the spline against the closed form within its h⁴ interpolation error,
// the normal, and the curvature (I - n nᵀ)/|x|.
TEST(GapSpline, SphereGapNormalAndCurvature) {
  const double R = 0.5, h = R / 6;
  const GapSpline spline({-R, -R, -R}, {R, R, R}, h, 0.0, false, 1e9, [&](const Point3& x) { return norm(x) - R; });
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> radial(R - h, R + 2 * h);
  for (int q = 0; q < 300; ++q) {
    Point3 x = random_point(rng, 1.0);
    const double r = radial(rng), scale = r / norm(x);
    for (auto& c : x) c *= scale;
    const auto s = spline.project(x);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(s->gap, r - R, 2e-4 * R);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(s->normal[i], x[i] / r, 2e-3);
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(s->normal_gradient[3 * i + j], ((i == j) - x[i] * x[j] / (r * r)) / r, 0.02 / r);
    }
  }
}

// Far behind the rear face (beyond the triangulated shaft tube, which ends one tip size back) the
// needle is read as a prism: the gap of the side face, as at the same x, y near the rear face.
TEST(CadNeedleShape, ShaftFarBehindTheRearFaceIsAPrism) {
  const double a = 1.0, L = 3.0, rho = 0.2;
  const CadNeedleShape needle(box({-a, -a, 0}, {a, a, L}, 40), rho);
  for (double z : {-0.5, -4.0, -30.0}) {
    const ObstacleProjection p = needle.project({a + 0.03, 0.2, z});
    EXPECT_NEAR(p.gap, 0.03, 1e-6) << z;
    EXPECT_NEAR(p.normal[0], 1.0, 1e-6) << z;
    EXPECT_NEAR(p.normal[2], 0.0, 1e-9) << z;
  }
}

// The smooth normal field: around a rounded cylinder of 512 facets (a sixth of the spline's spacing
// ρ/6 on the core) the exact projection's curvature across the mantle is 0 over each facet and 1/d
// over each facet edge's wedge; the spline's is close to the smooth cylinder's 1/|x| everywhere,
// and its gaps are the cylinder's within the facets' sagitta. (Facets as wide as the spacing would
// come through: the spline smooths below its spacing only.)
TEST(CadNeedleShape, CurvatureDoesNotSeeTheFacets) {
  const double r = 1.0, L = 3.0, rho = 0.3;
  const int m = 512;
  const CadNeedleShape needle(cylinder(r, L, m, 8), rho);
  const double radius = r + 0.02, sagitta = r * (1 - std::cos(kPi / m));
  double exact_lo = 1e300, exact_hi = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double phi = 2 * kPi * i / 200 + 0.01;
    const Point3 x{radius * std::cos(phi), radius * std::sin(phi), 1.5}, t{-std::sin(phi), std::cos(phi), 0};
    auto tangential = [&](const ObstacleProjection& p) {
      double v = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) v += t[a] * p.normal_gradient[3 * a + b] * t[b];
      return v;
    };
    const ObstacleProjection smooth = needle.project(x), exact = needle.project_exact(x);
    EXPECT_NEAR(smooth.gap, radius - r, sagitta);
    EXPECT_NEAR(tangential(smooth), 1 / radius, 0.1 / radius) << phi;
    exact_lo = std::min(exact_lo, tangential(exact));
    exact_hi = std::max(exact_hi, tangential(exact));
  }
  EXPECT_LT(exact_lo, 1e-9);  // the reference does see the facets
  EXPECT_GT(exact_hi, 1 / (radius - rho));
}

TEST(CadNeedleShape, RejectsOpenSurfacesAndMissingRearFaces) {
  TriangleSoup open = box({-1, -1, 0}, {1, 1, 2}, 2);
  open.triangles.pop_back();
  EXPECT_THROW(CadNeedleShape(open, 0.1), std::invalid_argument);
  EXPECT_THROW(CadNeedleShape(box({-1, -1, 0.5}, {1, 1, 2}, 2), 0.1), std::invalid_argument);  // no face on z = 0
}

}  // namespace
}  // namespace needlefem::contact
