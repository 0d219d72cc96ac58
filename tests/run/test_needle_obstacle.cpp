// The rigid needle obstacle (physics/contact/needle_obstacle.hpp) against independent
// references: gaps of points placed at known distances from each face of the tip (cylinder,
// bevel plane, fillet, the rounded bevel-cylinder edge, hemisphere), a normal continuous across
// the edge, n = ∂g/∂x and G = ∂n/∂x by central
// differences, the rigid velocity field against the time derivative of the pose
// (∂g/∂t = -n·w at a fixed point, and w = d/dt of the material point), and W = ∂w/∂x.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "../contact/obstacle_derivatives.hpp"
#include "physics/contact/needle_obstacle.hpp"

namespace needlefem::contact {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double r = 0.5e-3, shaft = 0.1e-3, tau = 0.25e-3;
const double alpha = 20.0 * kPi / 180.0;

BevelTip bevel_tip() { return {r, alpha, tau, shaft}; }
BevelTip rounded_tip() { return {r, alpha, r, shaft}; }
const NeedleMotion kMotion{1e-3, kPi, 0.1, 0.0};  // 1 mm/s, 180 deg/s for 0.1 s
constexpr double kEdgeRadius = 100e-6;              // m, the case default needle.edge_radius_um

Point3 add(const Point3& a, const Point3& b, double s = 1.0) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }
Point3 unit(const Point3& a) {
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / n, a[1] / n, a[2] / n};
}

// Points on the bevel tip's faces with their outward normals (needle frame).
struct SurfacePoint {
  const char* face;
  Point3 x, normal;
};
// The tip with every face moved inwards by the edge radius rho: its edges are the centres of the
// needle's rounded edges.
BevelTip core(double rho) { return {r - rho, alpha, tau - rho, shaft - rho * std::tan(alpha / 2)}; }

std::vector<SurfacePoint> bevel_surface_points(double rho) {
  const BevelTip tip = bevel_tip(), inner = core(rho);
  const double phi = 2.0;  // rad, on the shaft cylinder
  const double xb = 0.2 * r, yb = 0.3 * r;  // on the bevel plane
  const double psi = 0.6 * kPi;             // on the fillet arc, angle from +x in the x-z plane
  const double xf = tip.fillet_centre_x() + tau * std::cos(psi), zf = tip.fillet_centre_z() + tau * std::sin(psi);
  const double theta = 0.4;  // on the heel side of the bevel-cylinder edge
  const double re = r - rho, xe = re * std::cos(theta);
  const Point3 edge_centre{xe, re * std::sin(theta), inner.profile_top(xe)};
  const Point3 bevel_normal{std::cos(alpha), 0.0, std::sin(alpha)};
  const Point3 cylinder_normal{std::cos(theta), std::sin(theta), 0.0};
  return {{"cylinder", {r * std::cos(phi), r * std::sin(phi), 0.5 * shaft}, {std::cos(phi), std::sin(phi), 0.0}},
          {"bevel", {xb, yb, tip.profile_top(xb)}, bevel_normal},
          {"fillet", {xf, 0.1 * r, zf}, {std::cos(psi), 0.0, std::sin(psi)}},
          // On the rounded edge: rho from the core's edge along the bisector of the face normals.
          {"edge", add(edge_centre, unit(add(bevel_normal, cylinder_normal)), rho),
           unit(add(bevel_normal, cylinder_normal))}};
}

// The edge radius is the case's length, capped by the fillet (the core's fillet would go
// negative); the rounded tip has no edge, and a radius <= 0 leaves the edge sharp (an error).
TEST(NeedleObstacle, EdgeRadiusIsTheCaseLengthCappedByTheFillet) {
  EXPECT_DOUBLE_EQ(RigidNeedle(bevel_tip(), kMotion, 30e-6).edge_radius(), 30e-6);
  EXPECT_DOUBLE_EQ(RigidNeedle(bevel_tip(), kMotion, 0.4e-3).edge_radius(), tau);
  EXPECT_DOUBLE_EQ(RigidNeedle(rounded_tip(), kMotion, kEdgeRadius).edge_radius(), 0.0);
  EXPECT_THROW(RigidNeedle(bevel_tip(), kMotion, 0.0), std::invalid_argument);
  EXPECT_THROW(RigidNeedle(bevel_tip(), kMotion, -1e-6), std::invalid_argument);
}

// Near the rounded bevel-cylinder edge the needle is the core's edge point p swept by a ball of
// radius rho: a point p + s u with u in the edge's normal cone (u = unit(a n_bevel + b n_cylinder),
// a, b >= 0) has p as its closest core point, so its gap is the closed form s - rho and its normal
// u, for every edge radius.
TEST(NeedleObstacle, GapNearTheEdgeIsTheRoundedEdgesClosedForm) {
  const Point3 bevel_normal{std::cos(alpha), 0.0, std::sin(alpha)};
  const double theta = 0.4;  // the edge point of bevel_surface_points
  const Point3 cylinder_normal{std::cos(theta), std::sin(theta), 0.0};
  for (double rho : {10e-6, 25e-6, 50e-6, 100e-6}) {
    const RigidNeedle needle(bevel_tip(), kMotion, rho);
    const double re = r - rho, xe = re * std::cos(theta);
    const Point3 p{xe, re * std::sin(theta), core(rho).profile_top(xe)};
    for (double a : {0.0, 0.3, 1.0, 3.0})
      for (double s : {0.5 * rho, rho, 1.2 * rho, rho + 20e-6}) {
        const Point3 u = unit(add(add({0.0, 0.0, 0.0}, bevel_normal, a), cylinder_normal));
        const ObstacleProjection g = needle.project_in_needle_frame(add(p, u, s));
        EXPECT_NEAR(g.gap, s - rho, 1e-14) << "rho " << rho << " a " << a << " s " << s;
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(g.normal[i], u[i], 1e-8) << "rho " << rho << " a " << a << " s " << s;
      }
  }
}

TEST(NeedleObstacle, GapOfPointsAtKnownDistancesFromEachFace) {
  const RigidNeedle needle(bevel_tip(), kMotion, kEdgeRadius);
  EXPECT_DOUBLE_EQ(needle.edge_radius(), kEdgeRadius);
  for (const auto& s : bevel_surface_points(needle.edge_radius()))
    for (double d : {-2e-6, 0.0, 1e-6, 2e-5}) {
      const ObstacleProjection p = needle.project_in_needle_frame(add(s.x, s.normal, d));
      EXPECT_NEAR(p.gap, d, 1e-15) << s.face << " d = " << d;
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(p.normal[i], s.normal[i], 1e-9) << s.face << " d = " << d;
    }
  // Deeper than the edge radius: minus the distance to the nearer face (bevel plane or cylinder).
  const auto edge = bevel_surface_points(needle.edge_radius())[3];
  const Point3 inside = add(edge.x, edge.normal, -1.5 * needle.edge_radius());
  const double to_bevel = (inside[0] - r) * std::cos(alpha) + (inside[2] - shaft) * std::sin(alpha);
  const double to_cylinder = std::hypot(inside[0], inside[1]) - r;
  EXPECT_NEAR(needle.project_in_needle_frame(inside).gap, std::max(to_bevel, to_cylinder), 1e-15);
  EXPECT_LT(std::max(to_bevel, to_cylinder), 0.0);
  EXPECT_NEAR(bevel_tip().profile_top(r), shaft, 1e-18);  // the bevel plane passes through (r, ., shaft)
}

// Across the edge's bisector, at a penetration shallower than the edge radius, the normal turns
// smoothly from one face's to the other's (a sharp edge would switch it in one jump).
TEST(NeedleObstacle, NormalIsContinuousAcrossTheEdge) {
  const RigidNeedle needle(bevel_tip(), kMotion, kEdgeRadius);
  const double rho = needle.edge_radius();
  const auto edge = bevel_surface_points(rho)[3];
  const Point3 bevel_normal{std::cos(alpha), 0.0, std::sin(alpha)}, cylinder_normal{std::cos(0.4), std::sin(0.4), 0.0};
  const Point3 across = unit(add(bevel_normal, cylinder_normal, -1.0));
  const Point3 centre = add(edge.x, edge.normal, -0.5 * rho);  // half the edge radius deep
  Point3 previous = needle.project_in_needle_frame(add(centre, across, -0.2 * rho)).normal;
  for (int k = -19; k <= 20; ++k) {
    const Point3 n = needle.project_in_needle_frame(add(centre, across, 0.01 * k * rho)).normal;
    const double turn = std::acos(std::min(1.0, n[0] * previous[0] + n[1] * previous[1] + n[2] * previous[2]));
    EXPECT_LT(turn, 0.05) << "step " << k;  // ~0.02 rad per step; a sharp edge jumps by 0.52 rad
    previous = n;
  }
}

TEST(NeedleObstacle, RoundedTipIsCapsule) {
  const RigidNeedle needle(rounded_tip(), kMotion, kEdgeRadius);
  const Point3 dir = unit({0.3, -0.4, 0.8});
  for (double d : {-1e-5, 0.0, 3e-5}) {
    const ObstacleProjection cap = needle.project_in_needle_frame(add({0.0, 0.0, shaft}, dir, r + d));
    EXPECT_NEAR(cap.gap, d, 1e-15);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(cap.normal[i], dir[i], 1e-12);
    const ObstacleProjection side = needle.project_in_needle_frame({0.0, -(r + d), -0.2e-3});
    EXPECT_NEAR(side.gap, d, 1e-15);
    EXPECT_NEAR(side.normal[1], -1.0, 1e-12);
  }
}

void expect_derivatives(const RigidNeedle& needle, const Point3& x, const char* what) {
  expect_gap_derivatives([&](const Point3& at) { return needle.project_in_needle_frame(at); }, x, 1.0 / r, 1e-6, what);
}

TEST(NeedleObstacle, NormalAndItsGradientAreDerivativesOfTheGap) {
  const RigidNeedle needle(bevel_tip(), kMotion, kEdgeRadius);
  for (const auto& s : bevel_surface_points(needle.edge_radius()))
    for (double d : {-3e-6, 4e-6, 5e-5}) expect_derivatives(needle, add(s.x, s.normal, d), s.face);
  // Outside the edge off the bisector (still in its normal wedge): the closest point slides along
  // the curved edge, which G must include.
  const auto edge = bevel_surface_points(needle.edge_radius())[3];
  expect_derivatives(needle, add(add(edge.x, edge.normal, 4e-5), {0.0, 0.0, 1.0}, 5e-6), "edge off-bisector");
  // On the fillet's side of the edge (h'' of the arc enters G), along the bisector of the
  // cylinder's and the fillet's normals, then shifted along z.
  const double rho = needle.edge_radius();
  const BevelTip inner = core(rho);
  const double theta = 2.6, x = (r - rho) * std::cos(theta), z = inner.profile_top(x);
  const Point3 fillet_normal{(x - inner.fillet_centre_x()) / (tau - rho), 0.0, (z - inner.fillet_centre_z()) / (tau - rho)};
  const Point3 bisector = unit(add({std::cos(theta), std::sin(theta), 0.0}, fillet_normal));
  const Point3 fillet_edge{x, (r - rho) * std::sin(theta), z};
  EXPECT_NEAR(needle.project_in_needle_frame(add(fillet_edge, bisector, 3e-5)).gap, 3e-5 - rho, 1e-15);
  expect_derivatives(needle, add(add(fillet_edge, bisector, 3e-5), {0.0, 0.0, 1.0}, 3e-6), "fillet edge");
  const RigidNeedle rounded(rounded_tip(), kMotion, kEdgeRadius);
  expect_derivatives(rounded, {1e-4, -2e-4, shaft + 0.5e-3}, "hemisphere");
  expect_derivatives(rounded, {1e-4, -5.5e-4, -0.1e-3}, "rounded shaft");
}

TEST(NeedleObstacle, PoseVelocityAndItsGradientMatchTheMotion) {
  const RigidNeedle needle(bevel_tip(), kMotion, kEdgeRadius);
  const Point3 x{0.3e-3, 0.45e-3, 0.4e-3};
  const double t = 0.03, dt = 1e-7;
  const ObstacleProjection p = needle.project(x, t);
  // A fixed point sees the gap shrink at the needle's normal speed there.
  const double rate = (needle.project(x, t + dt).gap - needle.project(x, t - dt).gap) / (2 * dt);
  EXPECT_NEAR(rate, -(p.normal[0] * p.velocity[0] + p.normal[1] * p.velocity[1] + p.normal[2] * p.velocity[2]), 1e-9);
  // The material point now at x moves with w(x).
  const double angle = kMotion.rotation_speed * t, c = std::cos(angle), s = std::sin(angle);
  const Point3 X{c * x[0] + s * x[1], -s * x[0] + c * x[1], x[2] - kMotion.insertion_speed * t};
  const Point3 ahead = needle.from_body(X, t + dt), behind = needle.from_body(X, t - dt);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(needle.from_body(X, t)[i], x[i], 1e-18);
    EXPECT_NEAR((ahead[i] - behind[i]) / (2 * dt), p.velocity[i], 1e-12);
  }
  // W = ∂w/∂x.
  expect_velocity_gradient(needle, x, t);
  // Rotating the point with the needle leaves its gap unchanged; past the duration the needle rests.
  EXPECT_NEAR(needle.project(x, t).gap, needle.project_in_needle_frame(X).gap, 1e-18);
  const ObstacleProjection after = needle.project(x, 0.2);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(after.velocity[i], 0.0);
  EXPECT_EQ(needle.rear_face_centre(0.2)[2], kMotion.insertion_speed * kMotion.duration);
}

// The start ramp (geometry/needle_motion.hpp): speed fraction = dτ/dt by central differences
// inside and across the ramp's end, 0 and its slope 0 at t = 0, the travel lost = v t_r / 2, and
// the obstacle's velocity field and to_body/from_body follow the ramped pose.
TEST(NeedleObstacle, StartRampIsSmoothAndTheVelocityFollowsIt) {
  const NeedleMotion ramped{1e-3, kPi, 0.1, 0.01};
  const double dt = 1e-7;
  for (double t : {0.001, 0.005, 0.0099, 0.01, 0.0101, 0.05}) {
    const double derivative = (ramped.elapsed(t + dt) - ramped.elapsed(t - dt)) / (2 * dt);
    EXPECT_NEAR(derivative, ramped.speed_fraction(t), 1e-7) << "t = " << t;
  }
  EXPECT_EQ(ramped.elapsed(0.0), 0.0);
  EXPECT_EQ(ramped.speed_fraction(0.0), 0.0);
  // Zero acceleration at the start: the speed grows as 3 (t/t_r)², so its slope over the first dt
  // is 3 dt/t_r², 1e-4 of the mid-ramp acceleration 1.5/t_r.
  EXPECT_LT(ramped.speed_fraction(dt) / dt, 1e-4 * 1.5 / ramped.ramp);
  EXPECT_NEAR(ramped.speed_fraction(0.01), 1.0, 1e-15);
  EXPECT_NEAR(ramped.elapsed(0.1), 0.1 - 0.005, 1e-15);
  EXPECT_EQ(ramped.speed_fraction(0.11), 0.0);

  const RigidNeedle needle(bevel_tip(), ramped, kEdgeRadius);
  const Point3 X{0.3e-3, 0.45e-3, 0.4e-3};
  const double t = 0.004;
  const Point3 x = needle.from_body(X, t);
  const Point3 back = needle.to_body(x, t);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], X[i], 1e-18);
  const Point3 ahead = needle.from_body(X, t + dt), behind = needle.from_body(X, t - dt);
  const ObstacleProjection p = needle.project(x, t);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR((ahead[i] - behind[i]) / (2 * dt), p.velocity[i], 1e-12);
}

}  // namespace
}  // namespace needlefem::contact
