// Kinematic steering of the compliant needle; the model and its sources are in steering_path.hpp.
#include "steering/steering_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace needlefem::steering {

namespace {

Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 scale(double c, const Vec3& a) { return {c * a[0], c * a[1], c * a[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

double distance_to_segment(const Vec3& point, const Vec3& a, const Vec3& b) {
  const Vec3 ab = sub(b, a);
  const double length2 = dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(dot(sub(point, a), ab) / length2, 0.0, 1.0) : 0.0;
  return norm(sub(point, add(a, scale(t, ab))));
}

// Piecewise-linear table lookup, held constant outside [x.front(), x.back()].
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const auto upper = std::upper_bound(x.begin(), x.end(), at);
  const std::size_t i = static_cast<std::size_t>(upper - x.begin());
  const double w = (at - x[i - 1]) / (x[i] - x[i - 1]);
  return (1.0 - w) * y[i - 1] + w * y[i];
}

// Head turning and pull at one depth for the current shaft direction.
struct HeadPose {
  SteeringModel::HeadLoad load;
  Vec3 pull_direction{0.0, 0.0, 0.0};  // unit, normal to the shaft; zero without a magnet
  double magnet_distance_m = 0.0;
};

HeadPose head_pose(const SteeringModel& model, const MagnetSchedule& schedule, double depth_m,
                   const Vec3& shaft_direction) {
  HeadPose pose;
  if (schedule.empty()) return pose;
  pose.magnet_distance_m = schedule.distance_at(depth_m);
  pose.load = model.head_load(pose.magnet_distance_m);
  const double azimuth = schedule.azimuth_at(depth_m);
  const Vec3 pull{std::cos(azimuth), std::sin(azimuth), 0.0};
  const Vec3 normal_part = sub(pull, scale(dot(pull, shaft_direction), shaft_direction));
  const double length = norm(normal_part);
  if (length < 1e-9)
    throw std::domain_error(
        fmt::format("at depth {:.4g} mm the pull is along the shaft and cannot turn the head", depth_m * 1e3));
  pose.pull_direction = scale(1.0 / length, normal_part);
  return pose;
}

}  // namespace

double MagnetSchedule::distance_at(double depth) const { return interpolate(depth_m, magnet_distance_m, depth); }
double MagnetSchedule::azimuth_at(double depth) const { return interpolate(depth_m, pull_azimuth_rad, depth); }

double SteeringModel::tip_lever_m() const { return 0.5 * hinge.neck_length_m + hinge.head_length_m; }

SteeringModel::HeadLoad SteeringModel::head_load(double magnet_distance_m) const {
  HeadLoad load;
  load.flux_density_t = axial_flux_density_t(magnet, magnet_distance_m);
  load.force_n = gap_force_n(load.flux_density_t, magnet.pole_area_m2());
  load.turning_angle_rad = turning_angle_rad(hinge, load.force_n, force_angle_rad);
  if (load.turning_angle_rad > max_turning_angle_rad)
    throw std::domain_error(fmt::format(
        "magnet at {:.4g} mm gives B = {:.4g} T and a turning angle of {:.3g} deg, above the {:.3g} deg limit of "
        "the small-rotation model (Eq. 2.7)",
        magnet_distance_m * 1e3, load.flux_density_t, load.turning_angle_rad * 180.0 / std::numbers::pi,
        max_turning_angle_rad * 180.0 / std::numbers::pi));
  return load;
}

std::vector<PathSample> simulate_steering(const SteeringModel& model, const MagnetSchedule& schedule,
                                          const SteeringRun& run) {
  if (!(run.depth_step_m > 0.0) || !(run.insertion_depth_m > 0.0) || !(run.insertion_speed_m_per_s > 0.0))
    throw std::invalid_argument("steering: depth step, insertion depth and speed must be positive");
  const double a = model.tip_lever_m();
  Vec3 shaft{0.0, 0.0, 1.0};
  Vec3 pivot = sub(run.entry_point_m, scale(a, shaft));  // the tip starts at the entry point

  std::vector<PathSample> path;
  auto record = [&](double depth) {
    const HeadPose pose = head_pose(model, schedule, depth, shaft);
    const double theta = pose.load.turning_angle_rad;
    PathSample s;
    s.depth_m = depth;
    s.time_s = depth / run.insertion_speed_m_per_s;
    s.pivot_m = pivot;
    s.shaft_direction = shaft;
    s.pull_direction = pose.pull_direction;
    s.head_direction = add(scale(std::cos(theta), shaft), scale(std::sin(theta), pose.pull_direction));
    s.tip_m = add(pivot, scale(a, s.head_direction));
    s.turning_angle_rad = theta;
    s.flux_density_t = pose.load.flux_density_t;
    s.force_n = pose.load.force_n;
    s.magnet_distance_m = pose.magnet_distance_m;
    path.push_back(s);
  };

  double depth = 0.0;
  record(depth);
  while (depth < run.insertion_depth_m * (1.0 - 1e-12)) {
    const double step = std::min(run.depth_step_m, run.insertion_depth_m - depth);
    const HeadPose pose = head_pose(model, schedule, depth + 0.5 * step, shaft);
    // Exact arc of the pivot for theta and n held over the step: curvature sin(theta)/a.
    const double curvature = std::sin(pose.load.turning_angle_rad) / a;
    const double swept = curvature * step;
    if (swept == 0.0) {
      pivot = add(pivot, scale(step, shaft));
    } else {
      const Vec3& n = pose.pull_direction;
      pivot = add(pivot, add(scale(std::sin(swept) / curvature, shaft), scale((1.0 - std::cos(swept)) / curvature, n)));
      shaft = add(scale(std::cos(swept), shaft), scale(std::sin(swept), n));
      shaft = scale(1.0 / norm(shaft), shaft);
    }
    depth += step;
    record(depth);
  }
  return path;
}

double tip_arc_radius_m(double tip_lever_m, double turning_angle_rad) {
  return tip_lever_m / std::tan(turning_angle_rad);
}

double pivot_arc_radius_m(double tip_lever_m, double turning_angle_rad) {
  return tip_lever_m / std::sin(turning_angle_rad);
}

SteeringOutcome evaluate_scene(const std::vector<PathSample>& path, const ObstacleScene& scene) {
  if (path.empty()) throw std::invalid_argument("steering: empty path");
  SteeringOutcome out;
  const Vec3& centre = scene.obstacle_centre_m;
  double tip_path = std::numeric_limits<double>::infinity();
  double needle = tip_path, target = tip_path;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const PathSample& s = path[i];
    const PathSample& next = path[std::min(i + 1, path.size() - 1)];
    tip_path = std::min(tip_path, distance_to_segment(centre, s.tip_m, next.tip_m));
    target = std::min(target, distance_to_segment(scene.target_m, s.tip_m, next.tip_m));
    needle = std::min({needle, distance_to_segment(centre, s.pivot_m, s.tip_m),
                       distance_to_segment(centre, s.pivot_m, next.pivot_m)});
    // The tolerance forgives round-off at the entry face, where the straight needle starts.
    constexpr double tolerance_m = 1e-9;
    for (int k = 0; k < 3; ++k)
      if (s.tip_m[k] < scene.block_min_m[k] - tolerance_m || s.tip_m[k] > scene.block_max_m[k] + tolerance_m)
        out.tip_stays_in_block = false;
  }
  out.tip_path_clearance_m = tip_path - scene.obstacle_radius_m;
  out.needle_clearance_m = needle - scene.obstacle_radius_m - scene.needle_radius_m;
  out.target_closest_approach_m = target;
  out.miss_distance_m = norm(sub(path.back().tip_m, scene.target_m));
  return out;
}

}  // namespace needlefem::steering
