#include "case/specs/motion_spec.hpp"

#include <fmt/format.h>

#include "case/case.hpp"

namespace needlefem {

MotionSpec parse_motion_spec(const Case& c) {
  const MotionSpec spec{.insertion_speed_mm_per_s = c.real("motion.insertion_speed_mm_per_s"),
                        .rotation_speed_deg_per_s = c.real("motion.rotation_speed_deg_per_s"),
                        .duration_s = c.real("motion.duration_s"),
                        .ramp_s = c.real("motion.ramp_s")};
  if (spec.ramp_s > spec.duration_s)
    throw c.error("motion.ramp_s", fmt::format("the start ramp ({:.6g} s) is longer than motion.duration_s ({:.6g} s)",
                                               spec.ramp_s, spec.duration_s));
  return spec;
}

}  // namespace needlefem
