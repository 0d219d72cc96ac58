// The needle's prescribed motion ([motion] keys), parsed and checked: the input of
// needle_motion_from_spec (geometry/needle_motion.hpp).
#pragma once

namespace needlefem {

class Case;

struct MotionSpec {
  double insertion_speed_mm_per_s;
  double rotation_speed_deg_per_s;
  double duration_s;  // resolved by Case::parse from motion.insertion_travel_mm or rotation_deg if given
  double ramp_s;      // the smooth start's length
};

// The case's [motion] table. Throws CaseError (motion.ramp_s) if the ramp is longer than the motion.
MotionSpec parse_motion_spec(const Case& c);

}  // namespace needlefem
