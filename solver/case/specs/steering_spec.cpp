#include "case/specs/steering_spec.hpp"

#include "case/case.hpp"

namespace needlefem {

SteeringSpec parse_steering_spec(const Case& c) {
  // The schema gives these keys three entries.
  const std::vector<double> block = c.reals("steering.block_size_mm"), target = c.reals("steering.target_mm");
  return {.neck_youngs_modulus_gpa = c.real("steering.neck_youngs_modulus_gpa"),
          .tissue_spring_constant_n_per_m2 = c.real("steering.tissue_spring_constant_n_per_m2"),
          .force_angle_deg = c.real("steering.force_angle_deg"),
          .max_turning_angle_deg = c.real("steering.max_turning_angle_deg"),
          .magnet_residual_flux_density_t = c.real("steering.magnet_residual_flux_density_t"),
          .magnet_pole_width_mm = c.real("steering.magnet_pole_width_mm"),
          .magnet_pole_length_mm = c.real("steering.magnet_pole_length_mm"),
          .magnet_thickness_mm = c.real("steering.magnet_thickness_mm"),
          .magnet_correction_factor = c.real("steering.magnet_correction_factor"),
          .schedule_depth_mm = c.maybe_reals("steering.schedule_depth_mm"),
          .schedule_time_s = c.maybe_reals("steering.schedule_time_s"),
          .magnet_distance_mm = c.maybe_reals("steering.magnet_distance_mm"),
          .pull_azimuth_deg = c.maybe_reals("steering.pull_azimuth_deg"),
          .insertion_depth_mm = c.real("steering.insertion_depth_mm"),
          .insertion_speed_mm_per_s = c.real("steering.insertion_speed_mm_per_s"),
          .depth_step_mm = c.real("steering.depth_step_mm"),
          .block_size_mm = {block[0], block[1], block[2]},
          .obstacle_radius_mm = c.real("steering.obstacle_radius_mm"),
          .target_mm = {target[0], target[1], target[2]},
          .target_tolerance_mm = c.real("steering.target_tolerance_mm")};
}

}  // namespace needlefem
