// Equations: hinged_needle.hpp.
#include "physics/contact/hinged_needle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace needlefem::contact {

namespace {

using Vec2 = std::array<double, 2>;

// How far behind the entry face the shaft reaches: far enough that nothing sees its end.
constexpr double kShaftBehind = 1.0;  // m
// A solid's edge radius is at most this fraction of its radius.
constexpr double kMaxEdgeRadiusPerRadius = 0.25;
// Vertices whose edges turn by less than this (sine of the angle) are not corners.
constexpr double kCollinear = 1e-12;
// Below this radius (fraction of the solid's size) a point is on the axis: no hoop curvature.
constexpr double kOnAxis = 1e-12;

double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Point3 rotate(const Matrix3& A, const Point3& x) {
  return {A[0] * x[0] + A[1] * x[1] + A[2] * x[2], A[3] * x[0] + A[4] * x[1] + A[5] * x[2],
          A[6] * x[0] + A[7] * x[1] + A[8] * x[2]};
}
Point3 rotate_back(const Matrix3& A, const Point3& x) {
  return {A[0] * x[0] + A[3] * x[1] + A[6] * x[2], A[1] * x[0] + A[4] * x[1] + A[7] * x[2],
          A[2] * x[0] + A[5] * x[1] + A[8] * x[2]};
}
Matrix3 multiply(const Matrix3& A, const Matrix3& B) {
  Matrix3 C{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) C[3 * i + j] += A[3 * i + k] * B[3 * k + j];
  return C;
}
Matrix3 skew(const Point3& w) { return {0.0, -w[2], w[1], w[2], 0.0, -w[0], -w[1], w[0], 0.0}; }

// exp([θ]×) (Rodrigues) and the left Jacobian J(θ) of SO(3) (hinged_needle.hpp); series near 0.
void rotation_and_jacobian(const Point3& theta, Matrix3& R, Matrix3& J) {
  const double a2 = dot(theta, theta), a = std::sqrt(a2);
  double s1, c1, c2;  // sin a / a, (1 - cos a)/a², (a - sin a)/a³
  if (a < 1e-4) {
    s1 = 1.0 - a2 / 6.0;
    c1 = 0.5 - a2 / 24.0;
    c2 = 1.0 / 6.0 - a2 / 120.0;
  } else {
    s1 = std::sin(a) / a;
    c1 = (1.0 - std::cos(a)) / a2;
    c2 = (a - std::sin(a)) / (a2 * a);
  }
  const Matrix3 K = skew(theta), K2 = multiply(K, K);
  for (int i = 0; i < 9; ++i) {
    const double identity = (i % 4 == 0) ? 1.0 : 0.0;
    R[i] = identity + s1 * K[i] + c1 * K2[i];
    J[i] = identity + c1 * K[i] + c2 * K2[i];
  }
}

// The full section polygon from its half meridian, collinear vertices dropped.
std::vector<Vec2> full_polygon(const std::vector<Vec2>& half) {
  std::vector<Vec2> all(half);
  for (std::size_t i = half.size() - 1; i-- > 1;) all.push_back({-half[i][0], half[i][1]});
  std::vector<Vec2> corners;
  const std::size_t n = all.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = all[(i + n - 1) % n], &b = all[i], &c = all[(i + 1) % n];
    const Vec2 u{b[0] - a[0], b[1] - a[1]}, v{c[0] - b[0], c[1] - b[1]};
    const double turn = u[0] * v[1] - u[1] * v[0];
    if (turn > kCollinear * std::hypot(u[0], u[1]) * std::hypot(v[0], v[1])) corners.push_back(b);
  }
  return corners;
}

Vec2 outward_normal(const Vec2& a, const Vec2& b) {
  const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
  return {(b[1] - a[1]) / length, -(b[0] - a[0]) / length};
}

}  // namespace

RevolvedSolid::RevolvedSolid(const std::vector<std::array<double, 2>>& meridian, double edge_radius)
    : edge_radius_(edge_radius) {
  if (!(edge_radius >= 0.0)) throw std::invalid_argument("revolved solid: negative edge radius");
  const std::vector<Vec2> polygon = full_polygon(meridian);
  const std::size_t n = polygon.size();
  if (n < 3) throw std::invalid_argument("revolved solid: the meridian encloses no area");
  // Vertex i of P_ρ: where the lines of edges i-1 and i, moved inwards by ρ, cross.
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = polygon[(i + n - 1) % n], &b = polygon[i], &c = polygon[(i + 1) % n];
    const Vec2 m1 = outward_normal(a, b), m2 = outward_normal(b, c);
    const double k1 = m1[0] * b[0] + m1[1] * b[1] - edge_radius, k2 = m2[0] * b[0] + m2[1] * b[1] - edge_radius;
    const double det = m1[0] * m2[1] - m1[1] * m2[0];
    core_.push_back({(k1 * m2[1] - k2 * m1[1]) / det, (m1[0] * k2 - m2[0] * k1) / det});
  }
  for (std::size_t i = 0; i < n; ++i) {  // every moved edge keeps its direction
    const Vec2 &a = polygon[i], &b = polygon[(i + 1) % n], &p = core_[i], &q = core_[(i + 1) % n];
    if ((b[0] - a[0]) * (q[0] - p[0]) + (b[1] - a[1]) * (q[1] - p[1]) <= 0.0)
      throw std::invalid_argument("revolved solid: the edge radius is larger than the solid allows");
  }
}

ObstacleProjection RevolvedSolid::project(const Point3& xi) const {
  const double R = std::hypot(xi[0], xi[1]);
  const Vec2 q{R, xi[2]};
  const std::size_t n = core_.size();
  // Inside P_ρ: the largest signed distance to an edge's line; outside: the nearest edge point.
  double deepest = -std::numeric_limits<double>::infinity(), nearest = std::numeric_limits<double>::infinity();
  Vec2 normal{}, nearest_normal{};
  double curvature = 0.0;  // 1/|q - c| at a nearest vertex c, 0 on an edge
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = core_[i], &b = core_[(i + 1) % n];
    const Vec2 m = outward_normal(a, b);
    const double s = m[0] * (q[0] - a[0]) + m[1] * (q[1] - a[1]);
    if (s > deepest) deepest = s, normal = m;
    const Vec2 e{b[0] - a[0], b[1] - a[1]};
    const double along = ((q[0] - a[0]) * e[0] + (q[1] - a[1]) * e[1]) / (e[0] * e[0] + e[1] * e[1]);
    const double f = std::clamp(along, 0.0, 1.0);
    const Vec2 c{a[0] + f * e[0], a[1] + f * e[1]};
    const double d = std::hypot(q[0] - c[0], q[1] - c[1]);
    if (d < nearest) {
      nearest = d;
      const bool on_edge = along > 0.0 && along < 1.0;
      nearest_normal = on_edge || d == 0.0 ? m : Vec2{(q[0] - c[0]) / d, (q[1] - c[1]) / d};
      curvature = on_edge || d == 0.0 ? 0.0 : 1.0 / d;
    }
  }
  ObstacleProjection p;
  double H[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  if (deepest <= 0.0) {
    p.gap = deepest - edge_radius_;
  } else {
    p.gap = nearest - edge_radius_;
    normal = nearest_normal;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) H[i][j] = curvature * ((i == j ? 1.0 : 0.0) - normal[i] * normal[j]);
  }
  const double size = std::abs(core_.front()[1]) + std::abs(core_.front()[0]) + edge_radius_;
  const bool on_axis = R <= kOnAxis * size;
  const Point3 eR = on_axis ? Point3{1.0, 0.0, 0.0} : Point3{xi[0] / R, xi[1] / R, 0.0}, ez{0.0, 0.0, 1.0};
  for (int i = 0; i < 3; ++i) p.normal[i] = normal[0] * eR[i] + normal[1] * ez[i];
  const double hoop = on_axis ? 0.0 : normal[0] / R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      p.normal_gradient[3 * i + j] = H[0][0] * eR[i] * eR[j] + H[0][1] * (eR[i] * ez[j] + ez[i] * eR[j]) +
                                     H[1][1] * ez[i] * ez[j] +
                                     hoop * ((i == j ? 1.0 : 0.0) - eR[i] * eR[j] - ez[i] * ez[j]);
  return p;
}

HeadTilt::HeadTilt(std::vector<double> times, std::vector<std::array<double, 2>> tilt)
    : times_(std::move(times)), tilt_(std::move(tilt)) {
  if (times_.size() != tilt_.size()) throw std::invalid_argument("head tilt: as many times as tilts are needed");
  for (std::size_t i = 1; i < times_.size(); ++i)
    if (!(times_[i] > times_[i - 1])) throw std::invalid_argument("head tilt: the times must increase strictly");
}

std::array<double, 2> HeadTilt::at(double t) const {
  if (times_.empty()) return {0.0, 0.0};
  if (t <= times_.front()) return tilt_.front();
  if (t >= times_.back()) return tilt_.back();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
  const double f = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
  return {tilt_[i - 1][0] + f * (tilt_[i][0] - tilt_[i - 1][0]), tilt_[i - 1][1] + f * (tilt_[i][1] - tilt_[i - 1][1])};
}

std::array<double, 2> HeadTilt::rate(double t) const {
  if (times_.size() < 2 || t < times_.front() || t >= times_.back()) return {0.0, 0.0};
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
  const double dt = times_[i] - times_[i - 1];
  return {(tilt_[i][0] - tilt_[i - 1][0]) / dt, (tilt_[i][1] - tilt_[i - 1][1]) / dt};
}

HingedNeedle::HingedNeedle(const CompliantTip& tip, const NeedleMotion& motion, double edge_radius,
                           std::shared_ptr<const HeadTilt> tilt)
    : motion_(motion), edge_radius_(edge_radius), tilt_(tilt ? std::move(tilt) : std::make_shared<HeadTilt>()) {
  if (const auto broken = tip.violations(); !broken.empty()) throw std::invalid_argument(broken.front().message);
  if (!(edge_radius > 0.0)) throw std::invalid_argument("the edge radius must be positive");
  const double r = tip.radius, s = tip.shaft, l = tip.neck_length, neck = tip.neck_diameter / 2;
  const double L = tip.head_length, point = tip.point_length;
  const double rho = std::min(edge_radius, kMaxEdgeRadiusPerRadius * r);
  const double rho_neck = std::min(edge_radius, kMaxEdgeRadiusPerRadius * neck);
  pivot_z_ = s + l / 2;
  // The neck's halves reach into the shaft and the head by a neck diameter (their rounded ends
  // buried), and the stem's half 2ρ past the pivot over the head's rounded rear end, so that the
  // untilted neck is one smooth cylinder.
  stem_.emplace_back(std::vector<Vec2>{{0.0, -kShaftBehind}, {r, -kShaftBehind}, {r, s}, {0.0, s}}, rho);
  stem_.emplace_back(std::vector<Vec2>{{0.0, s - 2 * neck}, {neck, s - 2 * neck}, {neck, pivot_z_ + 2 * rho_neck},
                                       {0.0, pivot_z_ + 2 * rho_neck}},
                     rho_neck);
  head_.emplace_back(std::vector<Vec2>{{0.0, pivot_z_}, {neck, pivot_z_}, {neck, s + l + 2 * neck}, {0.0, s + l + 2 * neck}},
                     rho_neck);
  head_.emplace_back(std::vector<Vec2>{{0.0, s + l}, {r, s + l}, {r, s + l + L - point}, {0.0, s + l + L}}, rho);
}

ObstacleProjection HingedNeedle::project_body(Body body, const Point3& xi) const {
  ObstacleProjection best;
  best.gap = std::numeric_limits<double>::infinity();
  for (const RevolvedSolid& solid : body == stem ? stem_ : head_) {
    const ObstacleProjection p = solid.project(xi);
    if (p.gap < best.gap) best = p;
  }
  best.body = body;
  return best;
}

HingedNeedle::Pose HingedNeedle::stem_pose(double t) const {
  const double elapsed = motion_.elapsed(t), angle = motion_.rotation_speed * elapsed;
  const double c = std::cos(angle), s = std::sin(angle), fraction = motion_.speed_fraction(t);
  Pose pose;
  pose.Q = {c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0};
  pose.d = {0.0, 0.0, motion_.insertion_speed * elapsed};
  pose.d_rate = {0.0, 0.0, fraction * motion_.insertion_speed};
  pose.spin = {0.0, 0.0, fraction * motion_.rotation_speed};
  return pose;
}

HingedNeedle::Pose HingedNeedle::head_pose(double t) const {
  const Pose s = stem_pose(t);
  const auto tilt = tilt_->at(t), tilt_rate = tilt_->rate(t);
  Matrix3 R, J;
  rotation_and_jacobian({tilt[0], tilt[1], 0.0}, R, J);
  const Point3 turn = rotate(J, {tilt_rate[0], tilt_rate[1], 0.0});  // Ω_R
  const Point3 p{0.0, 0.0, pivot_z_}, Rp = rotate(R, p), spin = rotate(R, s.spin), swing = cross(turn, Rp);
  Pose pose;
  pose.Q = multiply(R, s.Q);
  for (int i = 0; i < 3; ++i) {
    pose.d[i] = s.d[i] + p[i] - Rp[i];
    pose.d_rate[i] = s.d_rate[i] - swing[i];
    pose.spin[i] = turn[i] + spin[i];
  }
  return pose;
}

Point3 HingedNeedle::Pose::from_body(const Point3& xi) const {
  const Point3 x = rotate(Q, xi);
  return {x[0] + d[0], x[1] + d[1], x[2] + d[2]};
}

Point3 HingedNeedle::Pose::to_body(const Point3& x) const {
  return rotate_back(Q, {x[0] - d[0], x[1] - d[1], x[2] - d[2]});
}

Point3 HingedNeedle::from_body(const Point3& xi, double t) const {
  return (xi[2] > pivot_z_ ? head_pose(t) : stem_pose(t)).from_body(xi);
}

Point3 HingedNeedle::to_body(const Point3& x, double t) const {
  const Point3 on_head = head_pose(t).to_body(x);
  return on_head[2] > pivot_z_ ? on_head : stem_pose(t).to_body(x);
}

Point3 HingedNeedle::rear_face_centre(double t) const { return stem_pose(t).d; }

Point3 HingedNeedle::pivot(double t) const {
  const Point3 d = stem_pose(t).d;
  return {d[0], d[1], d[2] + pivot_z_};
}

Point3 HingedNeedle::head_axis(double t) const { return rotate(head_pose(t).Q, {0.0, 0.0, 1.0}); }

ObstacleProjection HingedNeedle::project(const Point3& x, double t) const {
  ObstacleProjection best;
  best.gap = std::numeric_limits<double>::infinity();
  Pose chosen;
  for (const Body body : {stem, head}) {
    const Pose pose = body == stem ? stem_pose(t) : head_pose(t);
    const ObstacleProjection local = project_body(body, pose.to_body(x));
    if (local.gap >= best.gap) continue;
    best = local;
    chosen = pose;
  }
  // n = Q n_ξ, G = Q G_ξ Qᵀ, w = ḋ + Ω × (x - d), W = [Ω]×.
  const Point3 n = rotate(chosen.Q, best.normal);
  const Matrix3 G = multiply(multiply(chosen.Q, best.normal_gradient),
                             {chosen.Q[0], chosen.Q[3], chosen.Q[6], chosen.Q[1], chosen.Q[4], chosen.Q[7], chosen.Q[2],
                              chosen.Q[5], chosen.Q[8]});
  const Point3 arm{x[0] - chosen.d[0], x[1] - chosen.d[1], x[2] - chosen.d[2]};
  const Point3 swirl = cross(chosen.spin, arm);
  best.normal = n;
  best.normal_gradient = G;
  for (int i = 0; i < 3; ++i) best.velocity[i] = chosen.d_rate[i] + swirl[i];
  best.velocity_gradient = skew(chosen.spin);
  return best;
}

}  // namespace needlefem::contact
