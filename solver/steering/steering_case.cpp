// The steering spec -> steering problem (SI); the rules are listed in steering_case.hpp.
#include "steering/steering_case.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "case/case.hpp"
#include "case/specs/needle_tip_spec.hpp"
#include "case/specs/steering_spec.hpp"

namespace needlefem::steering {

namespace {

constexpr double mm = 1e-3;
constexpr double deg = std::numbers::pi / 180.0;

template <class Values>
Values scaled(Values values, double factor) {
  for (double& v : values) v *= factor;
  return values;
}

MagnetSchedule schedule_from_spec(const Case& input, const SteeringSpec& spec, const SteeringModel& model,
                                  double speed_m_per_s) {
  const bool by_depth = spec.schedule_depth_mm.has_value();
  const bool by_time = spec.schedule_time_s.has_value();
  const bool tables = spec.magnet_distance_mm || spec.pull_azimuth_deg;
  if (by_depth && by_time)
    throw input.error("steering.schedule_time_s", "give the schedule against depth or against time, not both");
  if (!by_depth && !by_time) {
    if (tables)
      throw input.error("steering.schedule_depth_mm",
                        "magnet tables need a schedule axis (schedule_depth_mm or schedule_time_s)");
    return {};
  }
  const std::string axis_key = by_depth ? "steering.schedule_depth_mm" : "steering.schedule_time_s";
  const std::vector<double>& axis = by_depth ? *spec.schedule_depth_mm : *spec.schedule_time_s;
  for (const auto& [key, table] : {std::pair{"steering.magnet_distance_mm", &spec.magnet_distance_mm},
                                   std::pair{"steering.pull_azimuth_deg", &spec.pull_azimuth_deg}}) {
    if (!*table) throw input.error(key, fmt::format("required with {}", axis_key));
    if ((*table)->size() != axis.size())
      throw input.error(key, fmt::format("has {} entries but {} has {}", (*table)->size(), axis_key, axis.size()));
  }
  for (std::size_t i = 1; i < axis.size(); ++i)
    if (!(axis[i] > axis[i - 1]))
      throw input.error(axis_key, fmt::format("must increase strictly: entry {} ({}) follows {}", i + 1, axis[i],
                                              axis[i - 1]));

  MagnetSchedule schedule;
  schedule.depth_m = by_depth ? scaled(axis, mm) : scaled(axis, speed_m_per_s);
  schedule.magnet_distance_m = scaled(*spec.magnet_distance_mm, mm);
  schedule.pull_azimuth_rad = scaled(*spec.pull_azimuth_deg, deg);
  // B(x) falls monotonically with x, so between entries the angle lies between the entries' angles.
  for (std::size_t i = 0; i < axis.size(); ++i) {
    try {
      model.head_load(schedule.magnet_distance_m[i]);
    } catch (const std::domain_error& e) {
      throw input.error("steering.magnet_distance_mm", fmt::format("entry {}: {}", i + 1, e.what()));
    }
  }
  return schedule;
}

}  // namespace

SteeringSetup steering_setup_from_case(const Case& input) {
  const NeedleTipSpec needle = parse_needle_tip_spec(input);
  if (needle.kind != NeedleKind::compliant)
    throw input.error("needle.kind", "steering needs the compliant (hinged, magnetised) needle: set \"compliant\"");
  const SteeringSpec spec = parse_steering_spec(input);
  SteeringSetup setup;
  SteeringModel& model = setup.model;
  model.hinge = {needle.neck_length_mm * mm, needle.neck_diameter_mm * mm, needle.head_length_mm * mm,
                 spec.neck_youngs_modulus_gpa * 1e9, spec.tissue_spring_constant_n_per_m2};
  model.magnet = {spec.magnet_residual_flux_density_t, spec.magnet_pole_width_mm * mm, spec.magnet_pole_length_mm * mm,
                  spec.magnet_thickness_mm * mm, spec.magnet_correction_factor};
  model.force_angle_rad = spec.force_angle_deg * deg;
  model.max_turning_angle_rad = spec.max_turning_angle_deg * deg;

  SteeringRun& run = setup.run;
  run.insertion_depth_m = spec.insertion_depth_mm * mm;
  run.depth_step_m = spec.depth_step_mm * mm;
  // One path sample (~160 bytes) and one magnet solve per step: 1e5 steps is far finer than the
  // kinematic model resolves; 1e-7 mm over 40 mm once asked for tens of GB.
  constexpr double max_steps = 1e5;
  if (const double steps = run.insertion_depth_m / run.depth_step_m; steps > max_steps)
    throw input.error("steering.depth_step_mm",
                      fmt::format("{:.3g} mm over the {:.3g} mm insertion is {:.3g} steps, more than {:.0f} (use a "
                                  "step of at least {:.3g} mm)", run.depth_step_m / mm, run.insertion_depth_m / mm,
                                  steps, max_steps, run.insertion_depth_m / max_steps / mm));
  run.insertion_speed_m_per_s = spec.insertion_speed_mm_per_s * mm;
  setup.schedule = schedule_from_spec(input, spec, model, run.insertion_speed_m_per_s);

  const Vec3 block = scaled(spec.block_size_mm, mm);
  ObstacleScene& scene = setup.scene;
  scene.block_min_m = {-0.5 * block[0], -0.5 * block[1], 0.0};
  scene.block_max_m = {0.5 * block[0], 0.5 * block[1], block[2]};
  scene.obstacle_centre_m = {0.0, 0.0, 0.5 * block[2]};
  scene.obstacle_radius_m = spec.obstacle_radius_mm * mm;
  scene.target_m = scaled(spec.target_mm, mm);
  scene.needle_radius_m = needle.radius_mm * mm;
  if (2.0 * scene.obstacle_radius_m >= std::min({block[0], block[1], block[2]}))
    throw input.error("steering.obstacle_radius_mm", "the obstacle does not fit inside the block");
  setup.target_tolerance_m = spec.target_tolerance_mm * mm;
  setup.origin = input.origin();
  return setup;
}

}  // namespace needlefem::steering
