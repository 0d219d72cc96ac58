#include "case/specs/insertion_force_spec.hpp"

#include "case/case.hpp"

namespace needlefem {

InsertionForceSpec parse_insertion_force_spec(const Case& c) {
  return {.energy_history = c.path("insertion_force.energy_history"),
          .energy_case = c.path("insertion_force.energy_case"),
          .extrapolation_warn_factor = c.real("insertion_force.extrapolation_warn_factor"),
          .extrapolation_limit_factor = c.real("insertion_force.extrapolation_limit_factor"),
          .fracture_toughness_j_per_m2 = c.real("insertion_force.fracture_toughness_j_per_m2"),
          .rupture_force_n = c.maybe_real("insertion_force.rupture_force_n"),
          .shaft_friction_n_per_mm = c.real("insertion_force.shaft_friction_n_per_mm"),
          .travel_mm = c.real("insertion_force.travel_mm"),
          .sample_interval_s = c.real("insertion_force.sample_interval_s"),
          .insertion_speed_mm_per_s = c.real("motion.insertion_speed_mm_per_s")};
}

}  // namespace needlefem
