// Reading a trajectory between its samples, and the device's force limit.
//
// Between samples i and i+1 (s = (t - t_i)/(t_{i+1} - t_i) in [0, 1]):
//   position, force, torque: linear,  v(s) = (1 - s) v_i + s v_{i+1}
//   orientation: spherical linear interpolation on the shorter arc (Shoemake 1985),
//     q(s) = sin((1 - s) w)/sin(w) q_i + sin(s w)/sin(w) q_{i+1},  cos(w) = |q_i . q_{i+1}|,
//     with q_{i+1} negated when q_i . q_{i+1} < 0 (q and -q are the same rotation), and the
//     normalised linear blend when w is tiny (sin(w) -> 0), where both agree to O(w^2).
// Times outside [t_0, t_n] hold the end samples.
// The force limit clamps the magnitude, keeping the direction: f -> f * min(1, F_max/|f|).
// Any finite samples give finite values (the interpolation never forms v_{i+1} - v_i, and
// |f| is computed without squaring overflow), and the clamped |f| never exceeds F_max, also
// after rounding: F_max is a hard bound for the device.
#pragma once

#include "replay/trajectory.hpp"

namespace needlefem::replay {

struct TrajectoryState {
  Vec3 position_m{};
  Quaternion orientation{1.0, 0.0, 0.0, 0.0};
  Vec3 force_n{};
  Vec3 torque_n_m{};
};

Quaternion slerp(const Quaternion& from, Quaternion to, double fraction);

// The trajectory's state at time_s (binary search for the bracketing samples).
TrajectoryState sample(const Trajectory& trajectory, double time_s);

// Scales vector down to magnitude <= limit (a hard bound) if it is longer, keeping its
// direction; returns true when it did. vector must be finite, limit finite and > 0.
bool clamp_magnitude(Vec3& vector, double limit);

}  // namespace needlefem::replay
