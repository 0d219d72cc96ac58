// The steering result file (HDF5, float64, SI units; written by `needlefem steer`):
//
//   /time_s [n], /depth_m [n]              time and insertion depth (length pushed in)
//   /tip_position_m [n,3]                  needle tip (world frame: entry at the origin, +z in)
//   /pivot_position_m [n,3]                PRBM pivot at the neck's centre (the shaft's end)
//   /head_direction [n,3], /shaft_direction [n,3], /pull_direction [n,3]   unit vectors
//                                          (pull_direction is zero without a magnet)
//   /turning_angle_rad [n]                 head turning angle theta (Eq. 2.7)
//   /flux_density_t [n]                    B at the head (Eq. 2.3)
//   /force_n [n,3]                         magnetic pull on the head (Eq. 2.1-2.2) along the pull
//   /magnet_distance_m [n]                 magnet pole face to head (0 without a magnet)
//   /scene/{block_min_m, block_max_m, obstacle_centre_m, target_m} [3],
//   /scene/{obstacle_radius_m, needle_radius_m} [1]
// Every dataset has a string attribute "units". Root attributes: "format" =
// "needlefem-steering-path", "case" = the resolved case (TOML), and the outcome
// "obstacle_clearance_tip_path_m", "obstacle_clearance_needle_m" (to the obstacle's surface),
// "target_miss_distance_m" (final tip to the target), "target_closest_approach_m" (tip path to the
// target).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "steering/steering_path.hpp"

namespace needlefem::steering {

// Writes (truncates) the file; throws std::runtime_error naming the file on failure.
void write_steering_path(const std::filesystem::path& file, const std::vector<PathSample>& path,
                         const ObstacleScene& scene, const SteeringOutcome& outcome,
                         const std::string& resolved_case_toml);

}  // namespace needlefem::steering
