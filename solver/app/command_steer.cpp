// `needlefem steer CASE.toml [--out DIR]`: kinematic steering of paper 000's compliant needle
// under a magnet schedule (steering/steering_path.hpp). Writes DIR/<case>.h5 (the tip path,
// steering/path_file.hpp) and DIR/<case>.json (obstacle_* clearances of the needle and its tip
// path, target_* miss distance and closest approach of the tip path), and prints the summary.
// Plot with postprocess/plot_steering.py DIR/<case>.h5.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "steering/path_file.hpp"
#include "steering/steering_case.hpp"

namespace needlefem::app {

namespace {

nlohmann::json summary(const std::vector<steering::PathSample>& path, const steering::SteeringOutcome& outcome,
                       const steering::SteeringSetup& setup) {
  double max_angle = 0.0, max_flux = 0.0, max_force = 0.0;
  for (const auto& s : path) {
    max_angle = std::max(max_angle, s.turning_angle_rad);
    max_flux = std::max(max_flux, s.flux_density_t);
    max_force = std::max(max_force, s.force_n);
  }
  const auto& tip = path.back().tip_m;
  // obstacle_*: surface-to-surface distances to the obstacle; target_*: distances to the target.
  return {{"obstacle_clearance_tip_path_mm", outcome.tip_path_clearance_m * 1e3},
          {"obstacle_clearance_needle_mm", outcome.needle_clearance_m * 1e3},
          {"clears_obstacle", outcome.needle_clearance_m > 0.0},
          {"target_miss_distance_mm", outcome.miss_distance_m * 1e3},
          {"target_closest_approach_mm", outcome.target_closest_approach_m * 1e3},
          {"target_reached", outcome.miss_distance_m <= setup.target_tolerance_m},
          {"target_tolerance_mm", setup.target_tolerance_m * 1e3},
          {"tip_stays_in_block", outcome.tip_stays_in_block},
          {"final_tip_mm", {tip[0] * 1e3, tip[1] * 1e3, tip[2] * 1e3}},
          {"tip_lever_mm", setup.model.tip_lever_m() * 1e3},
          {"max_turning_angle_deg", max_angle * 180.0 / std::numbers::pi},
          {"max_flux_density_t", max_flux},
          {"max_force_n", max_force},
          {"samples", path.size()}};
}

void run_steer(const CaseOptions& options) {
  const Case input = Case::load(options.case_file, options.overrides);
  const steering::SteeringSetup setup = steering::steering_setup_from_case(input);
  std::vector<steering::PathSample> path;
  try {
    path = steering::simulate_steering(setup.model, setup.schedule, setup.run);
  } catch (const std::domain_error& e) {
    throw input.error("steering.pull_azimuth_deg", e.what());
  }
  const steering::SteeringOutcome outcome = steering::evaluate_scene(path, setup.scene);

  const std::filesystem::path out(options.out_dir);
  std::filesystem::create_directories(out);
  const std::string stem = std::filesystem::path(options.case_file).stem().string();
  const std::filesystem::path h5 = out / (stem + ".h5");
  steering::write_steering_path(h5, path, setup.scene, outcome, input.to_toml());

  nlohmann::json json = summary(path, outcome, setup);
  json["path_file"] = h5.string();
  json["case"] = input.to_json();
  std::ofstream(out / (stem + ".json")) << json.dump(2) << '\n';
  json.erase("case");
  fmt::print("{}\n", json.dump(2));
}

}  // namespace

void add_steer_command(CLI::App& app) {
  add_case_command(app, "steer",
                   "Steer paper 000's compliant needle with a magnet schedule ([steering] keys): tip path as HDF5, clearance to\n"
                   "the obstacle and miss distance to the target as JSON. Plot: postprocess/plot_steering.py OUT/CASE.h5",
                   "out/steer", run_steer);
}

}  // namespace needlefem::app
