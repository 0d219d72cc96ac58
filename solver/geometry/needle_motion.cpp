// Equations: needle_motion.hpp.
#include "geometry/needle_motion.hpp"

#include <algorithm>
#include <numbers>

#include <fmt/format.h>

#include "case/case.hpp"

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

NeedleMotion needle_motion_from_case(const Case& input) {
  constexpr double kMetresPerMm = 1e-3;
  const NeedleMotion motion{input.real("motion.insertion_speed_mm_per_s") * kMetresPerMm,
                            input.real("motion.rotation_speed_deg_per_s") * std::numbers::pi / 180.0,
                            input.real("motion.duration_s"), input.real("motion.ramp_s")};
  if (motion.ramp > motion.duration)
    throw input.error("motion.ramp_s", fmt::format("the start ramp ({:.6g} s) is longer than motion.duration_s ({:.6g} s)",
                                                   motion.ramp, motion.duration));
  return motion;
}

}  // namespace needlefem
