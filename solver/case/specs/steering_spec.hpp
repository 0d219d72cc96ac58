// The magnet steering keys ([steering]), parsed: paper 000's compliant needle under a block
// magnet's schedule, its insertion and the obstacle scene it steers through. The input of
// steering_setup_from_case (steering/steering_case.hpp), which converts them to SI and checks the
// schedule's cross-key rules; prbm-check takes the neck's modulus from here. Values are in the
// units their keys name.
#pragma once

#include <array>
#include <optional>
#include <vector>

namespace needlefem {

class Case;

struct SteeringSpec {
  // The hinged head (Eq. 2.4-2.7).
  double neck_youngs_modulus_gpa;
  double tissue_spring_constant_n_per_m2;  // mu_t per unit length; 0: none
  double force_angle_deg;                  // phi, between the pull and the head's normal
  double max_turning_angle_deg;            // the largest a schedule may give
  // The block magnet (Eq. 2.3).
  double magnet_residual_flux_density_t;
  double magnet_pole_width_mm;
  double magnet_pole_length_mm;
  double magnet_thickness_mm;
  double magnet_correction_factor;
  // The magnet schedule, as given (absent: not given): one axis, against depth or time, and the
  // magnet's distance and pull azimuth at each of its entries; no axis: no magnet.
  std::optional<std::vector<double>> schedule_depth_mm;
  std::optional<std::vector<double>> schedule_time_s;
  std::optional<std::vector<double>> magnet_distance_mm;
  std::optional<std::vector<double>> pull_azimuth_deg;
  // The insertion.
  double insertion_depth_mm;
  double insertion_speed_mm_per_s;
  double depth_step_mm;  // of the path integration
  // The scene: a tissue block (x, y centred on the insertion axis, z from the entry face) with a
  // sphere at its centre, and the target the tip should reach.
  std::array<double, 3> block_size_mm;
  double obstacle_radius_mm;
  std::array<double, 3> target_mm;
  double target_tolerance_mm;  // miss distance below which the target counts as reached
};

SteeringSpec parse_steering_spec(const Case& c);

}  // namespace needlefem
