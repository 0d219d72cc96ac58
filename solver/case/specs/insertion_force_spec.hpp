// The insertion force's keys ([insertion_force]), parsed, with the needle's insertion speed: the
// input of `needlefem force-trajectory` (app/command_force_trajectory.cpp, which checks them;
// insertion_force/force_trajectory.hpp). Values are in the units their keys name.
#pragma once

#include <filesystem>
#include <optional>

namespace needlefem {

class Case;

struct InsertionForceSpec {
  // history.csv of a brain-tip `needlefem run` (its elastic energy), resolved; empty: not given
  std::filesystem::path energy_history;
  std::filesystem::path energy_case;  // the case whose run writes energy_history, resolved; empty: none
  // Multiples of the energy run's last sample the deformation stage may reach: warned beyond the
  // first, refused beyond the second.
  double extrapolation_warn_factor;
  double extrapolation_limit_factor;
  double fracture_toughness_j_per_m2;     // J_c
  std::optional<double> rupture_force_n;  // F_r, ending the deformation stage; required, absent: not given
  double shaft_friction_n_per_mm;         // f_s per inserted length; 0: none
  double travel_mm;                       // the needle's (haptic handle's) total displacement
  double sample_interval_s;               // between trajectory samples
  double insertion_speed_mm_per_s;        // motion.insertion_speed_mm_per_s
};

InsertionForceSpec parse_insertion_force_spec(const Case& c);

}  // namespace needlefem
