// Equations: needle_obstacle.hpp.
#include "physics/contact/needle_obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>


namespace needlefem::contact {

namespace {

constexpr double kPi = std::numbers::pi;
// Samples of the edge curve before the golden-section search: fine enough that the distance
// has one minimum between neighbouring samples for points near the needle.
constexpr int kEdgeSamples = 64;
constexpr int kGoldenIterations = 64;  // bracket 2 (2π/64) 0.618^64 ≈ 1e-14 rad
constexpr int kPolishIterations = 3;
// Edge parameters this close to ±π are the kink where the two edge branches meet.
constexpr double kKinkTolerance = 1e-6;
// Relative tolerance (of r) for "the projection onto one surface lies in the other set".
constexpr double kInsideTolerance = 1e-12;

double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

// (I - n nᵀ - extra)/distance, the normal gradient of a distance to a point (extra = 0), a line
// (extra = its direction's projector) or a curve.
Matrix3 normal_gradient(const Point3& n, double distance, const Matrix3& extra = {}) {
  Matrix3 G{};
  if (!(distance > 0.0)) return G;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) G[3 * i + j] = ((i == j ? 1.0 : 0.0) - n[i] * n[j] - extra[3 * i + j]) / distance;
  return G;
}

// Signed distance to the side profile P in the x-z plane: sd, 2-D normal, and the distance to
// the fillet centre when the closest point is on the arc (0 on the flat pieces).
struct ProfileDistance {
  double sd = 0.0;
  double nx = 0.0, nz = 0.0;
  double arc_distance = 0.0;
};

ProfileDistance profile_distance(const BevelProfile& tip, double x, double z) {
  const double ca = tip.cos_bevel, sa = tip.sin_bevel, tau = tip.fillet;
  const double dx = x - tip.centre_x, dz = z - tip.centre_z;
  // Wedge W': outward normals m_b = (cos α, sin α) (bevel), m_g = (-1, 0) (generator); its rays
  // leave the apex along d_b = (sin α, -cos α) and d_g = (0, -1).
  const double a = ca * dx + sa * dz, b = -dx;
  if (a <= 0.0 && b <= 0.0) return a >= b ? ProfileDistance{a - tau, ca, sa} : ProfileDistance{b - tau, -1.0, 0.0};
  if (a > 0.0 && sa * dx - ca * dz >= 0.0) return {a - tau, ca, sa};
  if (b > 0.0 && -dz >= 0.0) return {b - tau, -1.0, 0.0};
  const double d = std::hypot(dx, dz);
  if (!(d > 0.0)) return {-tau, ca, sa};  // sharp tip (τ = 0) exactly at its apex
  return {d - tau, dx / d, dz / d, d};
}

// The edge curve c(θ) = (r cos θ, r sin θ, h(r cos θ)) of the core's cylinder and profile, with
// c'(θ) and c''(θ) (h' and h'' of the bevel line or the arc).
struct CurvePoint {
  Point3 c, c1, c2;
};

CurvePoint edge_curve(const BevelProfile& core, double theta) {
  const double r = core.radius, tau = core.fillet, slope = -1.0 / core.tan_bevel;
  const double s = std::sin(theta), co = std::cos(theta), x = r * co;
  double h1 = slope, h2 = 0.0;
  if (x < core.tangent_x) {
    const double u = x - core.centre_x, root = std::sqrt(std::max(tau * tau - u * u, 0.0));
    h1 = -u / root;
    h2 = -tau * tau / (root * root * root);
  }
  return CurvePoint{{x, r * s, core.top(x)}, {-r * s, r * co, -h1 * r * s},
                    {-r * co, -r * s, h2 * r * r * s * s - h1 * r * co}};
}

// The samples of the edge curve that start its closest-point search, θ_k = -π + 2πk/kEdgeSamples.
double edge_sample_angle(int k) { return -kPi + 2.0 * kPi * k / kEdgeSamples; }

struct Candidate {
  double gap;
  Point3 normal;
  Matrix3 gradient;
};

ObstacleProjection from(const Candidate& c) {
  ObstacleProjection p;
  p.gap = c.gap;
  p.normal = c.normal;
  p.normal_gradient = c.gradient;
  return p;
}

}  // namespace

RigidNeedle::RigidNeedle(const BevelTip& tip, const NeedleMotion& motion, double edge_radius)
    : tip_(tip), motion_(motion), edge_radius_(tip.rounded() ? 0.0 : std::min(tip.fillet, edge_radius)) {
  if (!(tip.radius > 0.0) || !(tip.shaft >= 0.0) || !(tip.fillet >= 0.0) ||
      (!tip.rounded() && !(tip.bevel_rad > 0.0 && tip.bevel_rad <= kPi / 2)))
    throw std::invalid_argument("RigidNeedle: needs radius > 0, shaft >= 0, fillet >= 0, bevel in (0, 90] deg");
  if (!(edge_radius > 0.0)) throw std::invalid_argument("RigidNeedle: the edge radius must be positive");
  const auto violations = tip.violations();
  if (!violations.empty()) throw std::invalid_argument("RigidNeedle: " + violations.front().message);
  // Every face moved inwards by the edge radius ρ: radius and fillet shrink by ρ, the bevel line
  // moves by ρ along its normal (heel lower by ρ tan(α/2)); the fillet centre stays put.
  core_ = BevelProfile(BevelTip{tip.radius - edge_radius_, tip.bevel_rad, tip.fillet - edge_radius_,
                                tip.shaft - edge_radius_ * std::tan(0.5 * tip.bevel_rad)});
  if (tip.rounded()) return;
  edge_samples_.resize(kEdgeSamples + 1);
  for (int k = 0; k <= kEdgeSamples; ++k) edge_samples_[k] = edge_curve(core_, edge_sample_angle(k)).c;
}

ObstacleProjection RigidNeedle::project_rounded(const Point3& xi) const {
  const bool on_shaft = xi[2] < tip_.shaft;
  const Point3 offset{xi[0], xi[1], on_shaft ? 0.0 : xi[2] - tip_.shaft};
  const double d = norm(offset);
  const Point3 n = d > 0.0 ? Point3{offset[0] / d, offset[1] / d, offset[2] / d} : Point3{0.0, 0.0, 1.0};
  Matrix3 axis{};
  if (on_shaft) axis[8] = 1.0;  // the closest point slides along the axis with x
  return from({d - tip_.radius, n, normal_gradient(n, d, axis)});
}

ObstacleProjection RigidNeedle::project_bevel(const Point3& xi) const {
  const double r = core_.radius;
  // A: the cylinder.
  const double rho = std::hypot(xi[0], xi[1]);
  Candidate cylinder{rho - r, {1.0, 0.0, 0.0}, {}};
  if (rho > 0.0) {
    cylinder.normal = {xi[0] / rho, xi[1] / rho, 0.0};
    Matrix3 axis{};
    axis[8] = 1.0;
    cylinder.gradient = normal_gradient(cylinder.normal, rho, axis);
  }
  // B: the extruded profile.
  const ProfileDistance pd = profile_distance(core_, xi[0], xi[2]);
  Candidate profile{pd.sd, {pd.nx, 0.0, pd.nz}, {}};
  if (pd.arc_distance > 0.0) {
    Matrix3 across{};
    across[4] = 1.0;  // the fillet is a cylinder along y
    profile.gradient = normal_gradient(profile.normal, pd.arc_distance, across);
  }
  // Inside, or on the surface to round-off (where an edge point has no unique normal).
  const double tolerance = kInsideTolerance * r;
  if (cylinder.gap <= tolerance && profile.gap <= tolerance)
    return from(cylinder.gap >= profile.gap ? cylinder : profile);

  const Candidate* best = nullptr;
  if (cylinder.gap > 0.0 && profile_distance(core_, r * xi[0] / rho, xi[2]).sd <= tolerance) best = &cylinder;
  if (profile.gap > 0.0) {
    const double px = xi[0] - profile.gap * profile.normal[0];
    if (std::hypot(px, xi[1]) <= r + tolerance && (!best || profile.gap > best->gap)) best = &profile;
  }
  if (best) return from(*best);
  return project_on_edge(xi);
}

ObstacleProjection RigidNeedle::project_on_edge(const Point3& xi) const {
  auto curve = [&](double theta) { return edge_curve(core_, theta); };
  auto distance2_to = [&](const Point3& c) {
    const Point3 d{xi[0] - c[0], xi[1] - c[1], xi[2] - c[2]};
    return dot(d, d);
  };
  auto distance2 = [&](double theta) { return distance2_to(curve(theta).c); };
  int best = 0;
  double best_d2 = distance2_to(edge_samples_[0]);
  for (int k = 1; k <= kEdgeSamples; ++k) {
    const double d2 = distance2_to(edge_samples_[k]);
    if (d2 < best_d2) best = k, best_d2 = d2;
  }
  const double step = 2.0 * kPi / kEdgeSamples;
  double lo = std::max(-kPi, -kPi + step * (best - 1)), hi = std::min(kPi, -kPi + step * (best + 1));
  const double bracket_lo = lo, bracket_hi = hi;
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo), fa = distance2(a), fb = distance2(b);
  for (int i = 0; i < kGoldenIterations; ++i) {
    if (fa < fb) {
      hi = b, b = a, fb = fa, a = hi - golden * (hi - lo), fa = distance2(a);
    } else {
      lo = a, a = b, fa = fb, b = lo + golden * (hi - lo), fb = distance2(b);
    }
  }
  double theta = 0.5 * (lo + hi);
  const bool kink = kPi - std::abs(theta) < kKinkTolerance;
  // Golden section locates a minimum only to ~sqrt(machine epsilon); Newton on
  // (x - c)·c' = 0 then makes the closest point (and so n) accurate to round-off.
  for (int i = 0; i < kPolishIterations && !kink; ++i) {
    const CurvePoint p = curve(theta);
    const Point3 offset{xi[0] - p.c[0], xi[1] - p.c[1], xi[2] - p.c[2]};
    const double slope_of_distance = dot(offset, p.c1), curvature = dot(p.c1, p.c1) - dot(offset, p.c2);
    if (!(curvature > 0.0)) break;
    theta = std::clamp(theta + slope_of_distance / curvature, bracket_lo, bracket_hi);
  }
  const CurvePoint p = curve(theta);
  const Point3 offset{xi[0] - p.c[0], xi[1] - p.c[1], xi[2] - p.c[2]};
  const double d = norm(offset);
  const Point3 n{offset[0] / d, offset[1] / d, offset[2] / d};
  if (kink) return from({d, n, normal_gradient(n, d)});
  const double denominator = dot(p.c1, p.c1) - dot(offset, p.c2);
  Matrix3 slide{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) slide[3 * i + j] = p.c1[i] * p.c1[j] / denominator;
  return from({d, n, normal_gradient(n, d, slide)});
}

RigidNeedle::RigidNeedle(std::shared_ptr<const NeedleShape> shape, const NeedleMotion& motion)
    : shape_(std::move(shape)), motion_(motion), edge_radius_(shape_->edge_radius()) {}

ObstacleProjection RigidNeedle::project_in_needle_frame(const Point3& xi) const {
  if (shape_) return shape_->project(xi);
  if (tip_.rounded()) return project_rounded(xi);
  ObstacleProjection p = project_bevel(xi);  // against the core
  p.gap -= edge_radius_;
  return p;
}

Point3 RigidNeedle::rear_face_centre(double t) const { return pose(t).d; }

RigidNeedle::Pose RigidNeedle::pose(double t) const {
  const double elapsed = motion_.elapsed(t), angle = motion_.rotation_speed * elapsed;
  return {std::cos(angle), std::sin(angle), {0.0, 0.0, motion_.insertion_speed * elapsed}};
}

Point3 RigidNeedle::Pose::from_body(const Point3& xi) const {
  return {c * xi[0] - s * xi[1] + d[0], s * xi[0] + c * xi[1] + d[1], xi[2] + d[2]};
}

Point3 RigidNeedle::Pose::to_body(const Point3& x) const {
  const Point3 relative{x[0] - d[0], x[1] - d[1], x[2] - d[2]};
  return {c * relative[0] + s * relative[1], -s * relative[0] + c * relative[1], relative[2]};
}

Point3 RigidNeedle::from_body(const Point3& xi, double t) const { return pose(t).from_body(xi); }
Point3 RigidNeedle::to_body(const Point3& x, double t) const { return pose(t).to_body(x); }

ObstacleProjection RigidNeedle::project(const Point3& x, double t) const {
  const Pose now = pose(t);
  const double c = now.c, s = now.s;
  const Point3 relative{x[0] - now.d[0], x[1] - now.d[1], x[2] - now.d[2]};
  // ξ = R_z(-angle)(x - d); rotate n and G back: n = R n_ξ, G = R G_ξ Rᵀ.
  const Point3 xi = now.to_body(x);
  const ObstacleProjection local = project_in_needle_frame(xi);
  const Matrix3 R{c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0};
  ObstacleProjection p;
  p.gap = local.gap;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) p.normal[i] += R[3 * i + k] * local.normal[k];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          p.normal_gradient[3 * i + j] += R[3 * i + k] * local.normal_gradient[3 * k + l] * R[3 * j + l];
  if (const double fraction = motion_.speed_fraction(t); fraction > 0.0) {
    const double v = fraction * motion_.insertion_speed, omega = fraction * motion_.rotation_speed;
    p.velocity = {-omega * relative[1], omega * relative[0], v};
    p.velocity_gradient = {0.0, -omega, 0.0, omega, 0.0, 0.0, 0.0, 0.0, 0.0};
  }
  return p;
}

}  // namespace needlefem::contact
