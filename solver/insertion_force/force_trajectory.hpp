// Insertion-force trajectory of paper 000 (Section 3.2, Eq. 3.2), for haptic replay:
//
//   F_t = ΔU/Δx + 2 pi J_c r Δl/Δx (+ f_s l, optional shaft friction)
//
// x: needle (haptic handle) displacement from first contact, x = v t; l: crack (penetration)
// length; U: elastic energy of the tissue (deformation_energy.hpp, U = c x^p from a mechanics run).
//  1. Deformation (l = 0): the tip presses the entry face, which follows it;
//     F_t = dU/dx = F_def(x), until F_def reaches the tissue rupture force F_r at
//     x_r = F_def^-1(F_r).
//  2. Rupture: the crack runs until the tissue deformation force at the tip falls to the fracture
//     force F_c = 2 pi J_c r (the stable crack: a further Δl would release less energy than
//     2 pi J_c r Δl costs), i.e. the tissue springs back to the steady deformation
//     δ_ss = F_def^-1(F_c) and l jumps to x_r - δ_ss. Needs F_r > F_c.
//  3. Penetration: l = x - δ_ss, Δl/Δx = 1 and U = U(δ_ss) stays constant (ΔU = 0), so
//     F_t = F_c + f_s l: the steady fracture force 2 pi J_c r plus the shaft friction.
// The trajectory (replay/trajectory.hpp): the needle moves along +z (position (0, 0, x), identity
// orientation); the tissue's force on it is (0, 0, -F_t) (the force rendered at the handle,
// F_h = -F_t); no torque (axisymmetric). Samples every sample_interval, plus the rupture instant.
#pragma once

#include <vector>

#include "insertion_force/deformation_energy.hpp"
#include "replay/trajectory.hpp"

namespace needlefem::insertion {

struct InsertionForceParameters {
  double needle_radius_m = 0.0;             // r
  double fracture_toughness_j_per_m2 = 0.0; // J_c
  double rupture_force_n = 0.0;             // F_r
  double shaft_friction_n_per_m = 0.0;      // f_s
  double insertion_speed_m_per_s = 0.0;     // v
  double travel_m = 0.0;                    // total needle displacement
  double sample_interval_s = 0.0;

  double fracture_force_n() const;          // F_c = 2 pi J_c r
};

enum class Stage { deformation = 0, penetration = 1 };

struct InsertionForceTrajectory {
  replay::Trajectory trajectory;
  std::vector<double> displacement_m;  // x per sample
  std::vector<double> crack_length_m;  // l per sample
  std::vector<int> stage;              // Stage per sample
  bool ruptured = false;               // F_r reached within the travel
  double rupture_time_s = 0.0, rupture_displacement_m = 0.0;
  double steady_deformation_m = 0.0;   // δ_ss
  double fracture_force_n = 0.0;       // F_c
};

// Throws std::invalid_argument naming the parameter for non-positive values or F_r <= F_c.
InsertionForceTrajectory insertion_force_trajectory(const DeformationEnergy& deformation,
                                                    const InsertionForceParameters& parameters);

// Adds /displacement_m, /crack_length_m and /stage (datasets replay ignores) to a trajectory file
// write_trajectory has written. Throws replay::TrajectoryError on HDF5 failures.
void append_insertion_datasets(const std::filesystem::path& file, const InsertionForceTrajectory& result);

}  // namespace needlefem::insertion
