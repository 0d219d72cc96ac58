// Kinematic steering (steering/steering_path.hpp) against closed forms: a straight insertion
// without a magnet, the circular arcs of a constant turning angle, and the obstacle/target metrics.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "case/case.hpp"
#include "steering/steering_case.hpp"
#include "steering/steering_path.hpp"

namespace needlefem::steering {
namespace {

// Paper 000's worked example: l = 1 mm, L = 3.5 mm, d = 0.2 mm, steel; block magnet 50 x 60 mm.
SteeringModel paper_model() {
  SteeringModel model;
  model.hinge = {1e-3, 0.2e-3, 3.5e-3, 200e9, 0.0};
  model.magnet = {1.3, 0.05, 0.06, 0.02, 0.85};
  model.max_turning_angle_rad = 60.0 * std::numbers::pi / 180.0;
  return model;
}

SteeringRun run_to(double depth_m, double step_m) {
  SteeringRun run;
  run.insertion_depth_m = depth_m;
  run.depth_step_m = step_m;
  run.insertion_speed_m_per_s = 2e-3;
  return run;
}

MagnetSchedule constant_magnet(double distance_m, double azimuth_rad) {
  return {{0.0}, {distance_m}, {azimuth_rad}};
}

double distance(const Vec3& a, const Vec3& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

TEST(SteeringPath, StraightAlongTheAxisWithoutMagnet) {
  const auto path = simulate_steering(paper_model(), {}, run_to(0.02, 3e-4));
  ASSERT_GT(path.size(), 60u);
  EXPECT_NEAR(path.back().depth_m, 0.02, 1e-15);
  EXPECT_NEAR(path.back().time_s, 10.0, 1e-12);
  for (const auto& s : path) {
    EXPECT_EQ(s.turning_angle_rad, 0.0);
    EXPECT_EQ(s.flux_density_t, 0.0);
    EXPECT_NEAR(s.tip_m[0], 0.0, 1e-15);
    EXPECT_NEAR(s.tip_m[1], 0.0, 1e-15);
    EXPECT_NEAR(s.tip_m[2], s.depth_m, 1e-15);
    EXPECT_NEAR(s.head_direction[2], 1.0, 1e-15);
  }
}

// Constant theta: tip on a circle of radius a/tan(theta), pivot on the concentric circle of
// radius a/sin(theta), the shaft turned by depth * sin(theta)/a; in the plane of the pull.
TEST(SteeringPath, ConstantTurningAngleGivesTheClosedFormArc) {
  const SteeringModel model = paper_model();
  const double azimuth = 30.0 * std::numbers::pi / 180.0;
  const MagnetSchedule schedule = constant_magnet(0.045, azimuth);
  const double theta = model.head_load(0.045).turning_angle_rad;
  ASSERT_GT(theta, 10.0 * std::numbers::pi / 180.0);
  ASSERT_LT(theta, 30.0 * std::numbers::pi / 180.0);
  const double a = model.tip_lever_m();
  EXPECT_NEAR(a, 4.0e-3, 1e-15);
  const double tip_radius = tip_arc_radius_m(a, theta), pivot_radius = pivot_arc_radius_m(a, theta);

  // Start: the straight needle's pivot at (0, 0, -a), the head turned at once towards the pull
  // e = (cos psi, sin psi, 0): tip p0 = a (sin(theta) e + (cos(theta) - 1) z), heading
  // h0 = sin(theta) e + cos(theta) z. The centre lies tip_radius from p0, normal to h0 towards e.
  const Vec3 e{std::cos(azimuth), std::sin(azimuth), 0.0};
  const double p0_lateral = a * std::sin(theta), p0_z = a * (std::cos(theta) - 1.0);
  const Vec3 centre{(p0_lateral + tip_radius * std::cos(theta)) * e[0],
                    (p0_lateral + tip_radius * std::cos(theta)) * e[1], p0_z - tip_radius * std::sin(theta)};
  const double depth = 0.02;  // the shaft turns by depth sin(theta)/a, about 1.5 rad
  const auto path = simulate_steering(model, schedule, run_to(depth, 0.5e-3));
  EXPECT_NEAR(path.front().tip_m[2], p0_z, 1e-15);
  for (const auto& s : path) {
    EXPECT_NEAR(s.turning_angle_rad, theta, 1e-15);
    EXPECT_NEAR(distance(s.tip_m, centre), tip_radius, 1e-12);
    EXPECT_NEAR(distance(s.pivot_m, centre), pivot_radius, 1e-12);
    // Out-of-plane component (normal e x z) stays zero: the path lies in the pull's plane.
    EXPECT_NEAR(s.tip_m[0] * e[1] - s.tip_m[1] * e[0], 0.0, 1e-15);
  }
  const double shaft_turn = std::acos(path.back().shaft_direction[2]);
  EXPECT_NEAR(shaft_turn, depth * std::sin(theta) / a, 1e-12);
  // A coarser step lands on the same arc end (steps follow the arc exactly).
  const auto coarse = simulate_steering(model, schedule, run_to(depth, 3e-3));
  EXPECT_NEAR(distance(coarse.back().tip_m, path.back().tip_m), 0.0, 1e-14);
}

TEST(SteeringPath, TooCloseMagnetExceedsTheSmallRotationLimit) {
  EXPECT_THROW(paper_model().head_load(0.02), std::domain_error);  // ~180 deg by Eq. 2.7
}

TEST(SteeringScene, StraightPathThroughTheObstacleCentre) {
  const auto path = simulate_steering(paper_model(), {}, run_to(0.036, 1e-3));
  ObstacleScene scene;
  scene.block_min_m = {-0.015, -0.015, 0.0};
  scene.block_max_m = {0.015, 0.015, 0.04};
  scene.obstacle_centre_m = {0.0, 0.0, 0.02};
  scene.obstacle_radius_m = 0.004;
  scene.needle_radius_m = 0.0005;
  scene.target_m = {0.003, 0.0, 0.034};
  const SteeringOutcome outcome = evaluate_scene(path, scene);
  EXPECT_NEAR(outcome.tip_path_clearance_m, -0.004, 1e-15);
  EXPECT_NEAR(outcome.needle_clearance_m, -0.0045, 1e-15);
  EXPECT_NEAR(outcome.target_closest_approach_m, 0.003, 1e-15);
  EXPECT_NEAR(outcome.miss_distance_m, std::hypot(0.003, 0.002), 1e-15);
  EXPECT_TRUE(outcome.tip_stays_in_block);
}

// A schedule against time is the same schedule against depth = speed * time.
TEST(SteeringCase, TimeScheduleMapsToDepthThroughTheInsertionSpeed) {
  const Case input = Case::parse(R"([needle]
kind = "compliant"
[steering]
insertion_speed_mm_per_s = 2.0
schedule_time_s = [0.0, 5.0, 7.5]
magnet_distance_mm = [300.0, 50.0, 60.0]
pull_azimuth_deg = [0.0, 90.0, 90.0]
)",
                                 "time_schedule.toml");
  const SteeringSetup setup = steering_setup_from_case(input);
  ASSERT_EQ(setup.schedule.depth_m.size(), 3u);
  EXPECT_NEAR(setup.schedule.depth_m[1], 0.010, 1e-15);
  EXPECT_NEAR(setup.schedule.depth_m[2], 0.015, 1e-15);
  EXPECT_NEAR(setup.schedule.distance_at(0.0125), 0.055, 1e-15);
  EXPECT_NEAR(setup.schedule.azimuth_at(0.005), std::numbers::pi / 4, 1e-15);
  EXPECT_NEAR(setup.model.tip_lever_m(), 4.0e-3, 1e-15);
  EXPECT_NEAR(setup.scene.obstacle_centre_m[2], 0.020, 1e-15);
}

}  // namespace
}  // namespace needlefem::steering
