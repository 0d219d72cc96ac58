// Trajectory interpolation (linear and slerp) and force clamping; formulas in sampling.hpp.
#include "replay/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace needlefem::replay {

namespace {

// Below this angle between the quaternions slerp's sin(w) loses digits; the normalised linear
// blend differs from slerp by O(w^2) ~ 1e-12 there.
constexpr double slerp_linear_threshold_rad = 1e-6;

// (1 - s) a + s b cannot form b - a, which overflows for samples of opposite sign near the
// largest double; the bracket by the samples catches the one rounding overflow left (to +-inf).
double lerp(double a, double b, double s) {
  const auto [low, high] = std::minmax(a, b);
  return std::clamp((1.0 - s) * a + s * b, low, high);
}

Vec3 lerp(const Vec3& a, const Vec3& b, double s) { return {lerp(a[0], b[0], s), lerp(a[1], b[1], s), lerp(a[2], b[2], s)}; }

// |v| without overflow or underflow in the squares (std::hypot scales by the largest component).
double magnitude(const Vec3& v) { return std::hypot(v[0], v[1], v[2]); }

}  // namespace

Quaternion slerp(const Quaternion& from, Quaternion to, double fraction) {
  double cos_angle = from[0] * to[0] + from[1] * to[1] + from[2] * to[2] + from[3] * to[3];
  if (cos_angle < 0.0) {
    for (double& c : to) c = -c;
    cos_angle = -cos_angle;
  }
  const double angle = std::acos(std::min(cos_angle, 1.0));
  double weight_from = 1.0 - fraction, weight_to = fraction;
  if (angle > slerp_linear_threshold_rad) {
    weight_from = std::sin((1.0 - fraction) * angle) / std::sin(angle);
    weight_to = std::sin(fraction * angle) / std::sin(angle);
  }
  Quaternion q;
  double norm2 = 0.0;
  for (int i = 0; i < 4; ++i) {
    q[i] = weight_from * from[i] + weight_to * to[i];
    norm2 += q[i] * q[i];
  }
  const double norm = std::sqrt(norm2);
  for (double& c : q) c /= norm;
  return q;
}

TrajectoryState sample(const Trajectory& t, double time_s) {
  const auto& times = t.time_s;
  auto state_at = [&t](std::size_t i) {
    return TrajectoryState{t.position_m[i], t.orientation[i], t.force_n[i], t.torque_n_m[i]};
  };
  if (time_s <= times.front()) return state_at(0);
  if (time_s >= times.back()) return state_at(times.size() - 1);
  const std::size_t next = std::upper_bound(times.begin(), times.end(), time_s) - times.begin();
  const std::size_t prev = next - 1;
  const double s = (time_s - times[prev]) / (times[next] - times[prev]);
  return TrajectoryState{lerp(t.position_m[prev], t.position_m[next], s),
                         slerp(t.orientation[prev], t.orientation[next], s),
                         lerp(t.force_n[prev], t.force_n[next], s), lerp(t.torque_n_m[prev], t.torque_n_m[next], s)};
}

bool clamp_magnitude(Vec3& v, double limit) {
  const double length = magnitude(v);
  if (!(length > limit)) return false;
  // Divide by the largest component first, so a huge vector becomes a unit-sized one with its
  // direction, then scale to the limit. Rounding can leave |v| an ulp or two above the limit:
  // the limit is a hard bound, so shrink by a few ulps until it holds (at most a few passes).
  const double largest = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
  for (double& c : v) c /= largest;
  const double scale = limit / magnitude(v);
  for (double& c : v) c *= scale;
  while (magnitude(v) > limit || std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) > limit)
    for (double& c : v) c *= 1.0 - 4.0 * std::numeric_limits<double>::epsilon();
  return true;
}

}  // namespace needlefem::replay
