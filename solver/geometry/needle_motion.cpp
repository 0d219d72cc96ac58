// Equations: needle_motion.hpp.
#include "geometry/needle_motion.hpp"

#include <algorithm>
#include <numbers>

namespace needlefem {

double NeedleMotion::elapsed(double t) const {
  const double clamped = std::clamp(t, 0.0, duration);
  if (clamped >= ramp) return clamped - 0.5 * ramp;
  const double sigma = clamped / ramp;
  return ramp * sigma * sigma * sigma * (1.0 - 0.5 * sigma);
}

double NeedleMotion::speed_fraction(double t) const {
  if (t < 0.0 || t > duration) return 0.0;
  if (t >= ramp) return 1.0;
  const double sigma = t / ramp;
  return sigma * sigma * (3.0 - 2.0 * sigma);
}

NeedleMotion needle_motion_from_spec(const MotionSpec& spec) {
  constexpr double kMetresPerMm = 1e-3;
  return {spec.insertion_speed_mm_per_s * kMetresPerMm, spec.rotation_speed_deg_per_s * std::numbers::pi / 180.0,
          spec.duration_s, spec.ramp_s};
}

}  // namespace needlefem
