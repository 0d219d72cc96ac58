// Kinematic steering of paper 000's compliant needle (Tang, Chen & He, Sections 2.2 and 3.3):
// a magnet schedule turns the hinged head, the needle is pushed on, and its tip path bends.
//
// Kinematic model (pseudo-rigid-body, quasi-static). The PRBM pivot sits at the centre of the
// neck; the tip is a = l/2 + L ahead of it along the head direction h. The shaft behind the
// pivot has direction s and is held by the tissue, so the pivot q slides along s (the shaft
// follows its own channel). The head is turned by theta towards the unit pull direction n,
// the magnet's pull projected on the plane normal to the shaft:
//
//   h = cos(theta) s + sin(theta) n,          tip p = q + a h.
//
// The tip cuts along the head direction (it moves parallel to h) while the pivot moves along s.
// With the insertion depth d (the length pushed in at the base, = pivot arc length) as the
// independent variable, the rigid pivot-to-tip link gives
//
//   dq/dd = s,   ds/dd = (sin(theta)/a) n,   dp/dd = cos(theta) h   (theta, n held),
//
// the kinematic bicycle with the rear wheel at the pivot and the steered front wheel at the tip
// (Webster et al., "Nonholonomic modeling of needle steering", IJRR 25(5-6), 2006, use the same
// model for bevel tips). For a constant theta and a pull fixed in the (s, n) plane the pivot runs
// on a circle of radius a/sin(theta) and the tip on a concentric circle of radius a/tan(theta);
// simulate_steering advances each depth step exactly along that arc, with theta and n taken at
// the step's mid-depth, so constant schedules are integrated without discretisation error.
//
// A change of theta turns the head about the pivot in place: the tip swings sideways by
// a (sin(theta_new) - sin(theta_old)), as the paper's static turning stage does (Section 2.1);
// with the PRBM spring the head also swings back when the magnet releases it. The recorded tip
// path contains these swings, and the obstacle clearance checks the head at every sample.
//
// theta comes from the magnet: the schedule gives the magnet distance x (pole axis through the
// head) and the pull direction; Eq. 2.3 gives B(x), Eq. 2.1-2.2 the pull F = B^2 A_g / (2 mu0)
// and Eq. 2.7 the turning angle with the neck stiffness (E I)_l / l and the tissue term mu_t.
// Eq. 2.7 is a small-rotation moment balance, so schedules are limited to a maximum angle.
#pragma once

#include <array>
#include <vector>

#include "steering/hinge.hpp"
#include "steering/magnet.hpp"

namespace needlefem::steering {

using Vec3 = std::array<double, 3>;

// Magnet position against insertion depth, linearly interpolated, held beyond its ends.
// The pull azimuth psi gives the pull as (cos psi, sin psi, 0) in the world frame (the needle
// enters along +z), projected on the plane normal to the shaft. An empty schedule = no magnet.
struct MagnetSchedule {
  std::vector<double> depth_m;            // strictly increasing
  std::vector<double> magnet_distance_m;  // from the pole face to the head, on the pole axis
  std::vector<double> pull_azimuth_rad;

  bool empty() const { return depth_m.empty(); }
  double distance_at(double depth_m) const;
  double azimuth_at(double depth_m) const;
};

struct SteeringModel {
  CompliantNeedleHinge hinge;
  BlockMagnet magnet;
  double force_angle_rad = 0.0;  // phi of Eq. 2.7, between the pull and the head's normal
  double max_turning_angle_rad = 0.0;

  double tip_lever_m() const;  // a = l/2 + L, pivot to tip
  // Eq. 2.3 -> Eq. 2.1-2.2 -> Eq. 2.7 at one magnet distance. Throws std::domain_error when
  // the angle exceeds max_turning_angle_rad.
  struct HeadLoad {
    double flux_density_t = 0.0;
    double force_n = 0.0;
    double turning_angle_rad = 0.0;
  };
  HeadLoad head_load(double magnet_distance_m) const;
};

struct SteeringRun {
  Vec3 entry_point_m{0.0, 0.0, 0.0};  // the tip's start; the needle points along +z
  double insertion_depth_m = 0.0;
  double depth_step_m = 0.0;
  double insertion_speed_m_per_s = 0.0;  // time = depth / speed
};

struct PathSample {
  double time_s = 0.0;
  double depth_m = 0.0;
  Vec3 tip_m{}, pivot_m{};
  Vec3 head_direction{}, shaft_direction{}, pull_direction{};
  double turning_angle_rad = 0.0;
  double flux_density_t = 0.0;
  double force_n = 0.0;  // magnitude; the pull acts along pull_direction
  double magnet_distance_m = 0.0;  // 0 when there is no magnet
};

// The path from depth 0 to run.insertion_depth_m, one sample per depth step (and the end).
std::vector<PathSample> simulate_steering(const SteeringModel& model, const MagnetSchedule& schedule,
                                          const SteeringRun& run);

// Closed forms of the kinematic model for a constant turning angle (0 < theta < pi/2).
double tip_arc_radius_m(double tip_lever_m, double turning_angle_rad);    // a / tan(theta)
double pivot_arc_radius_m(double tip_lever_m, double turning_angle_rad);  // a / sin(theta)

// Paper 000's scene (Fig. 9b, 10): a tissue block, an obstacle sphere at its centre and a target.
struct ObstacleScene {
  Vec3 block_min_m{}, block_max_m{};
  Vec3 obstacle_centre_m{};
  double obstacle_radius_m = 0.0;
  Vec3 target_m{};
  double needle_radius_m = 0.0;
};

struct SteeringOutcome {
  // Smallest distance from the tip path (a polyline through the samples) to the obstacle's
  // surface; negative = the path enters the obstacle.
  double tip_path_clearance_m = 0.0;
  // The same for the whole needle: shaft path, and the head/neck axis at every sample, less the
  // needle radius (surface to surface).
  double needle_clearance_m = 0.0;
  double miss_distance_m = 0.0;       // final tip position to the target
  double target_closest_approach_m = 0.0;  // tip path polyline to the target (not the obstacle)
  bool tip_stays_in_block = true;
};

SteeringOutcome evaluate_scene(const std::vector<PathSample>& path, const ObstacleScene& scene);

}  // namespace needlefem::steering
