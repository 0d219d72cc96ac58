// Needle trajectories for haptic replay, and their HDF5 file format.
//
// File format "needlefem-trajectory", version 1 (one HDF5 file, all datasets float64, n >= 2):
//
//   /time_s          [n]     s     strictly increasing sample times (need not start at 0)
//   /position_m      [n,3]   m     needle reference point (centre of its rear face) in the world
//                                  (tissue block) frame
//   /orientation     [n,4]   1     unit quaternion (w, x, y, z) rotating the needle body frame
//                                  into the world frame
//   /force_n         [n,3]   N     force the tissue exerts on the needle, world frame; this is
//                                  the force rendered at the haptic handle (paper 000, Eq. 3.2:
//                                  F_h = -F_t)
//   /torque_n_m      [n,3]   N m   torque the tissue exerts on the needle about position_m,
//                                  world frame
//
//   Every dataset carries a string attribute "units" ("s", "m", "1", "N", "N m"); /orientation
//   also carries "order" = "w,x,y,z". Root attributes: "format" = "needlefem-trajectory",
//   "format_version" = 1 (integer), "source_case" = the fully resolved case (TOML text) or
//   description the trajectory was computed from ("" when none).
//
// Producers (e.g. the insertion-force model of paper 000, Eq. 3.2) fill a Trajectory and call
// write_trajectory; they may add further datasets (insertion depth, stage, ...), which replay
// ignores. Files written by other tools are accepted when they follow this layout; float32
// datasets are converted on reading. The reader checks the format tag, every dataset's presence and shape,
// finite values, strictly increasing time and unit quaternions (|q| within 1e-3 of 1, then
// renormalised), and reports the first failure in one line naming the file, dataset and reason.
#pragma once

#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace needlefem::replay {

using Vec3 = std::array<double, 3>;
using Quaternion = std::array<double, 4>;  // (w, x, y, z)

inline constexpr const char* trajectory_format_name = "needlefem-trajectory";
inline constexpr int trajectory_format_version = 1;

struct Trajectory {
  std::vector<double> time_s;
  std::vector<Vec3> position_m;
  std::vector<Quaternion> orientation;
  std::vector<Vec3> force_n;
  std::vector<Vec3> torque_n_m;
  std::string source_case;

  std::size_t size() const { return time_s.size(); }
  double duration_s() const { return time_s.back() - time_s.front(); }
};

// "FILE: dataset 'NAME': REASON" (or "FILE: REASON" for file-level problems).
class TrajectoryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Checks the in-memory invariants the file format promises; `origin` names the source in errors.
void validate_trajectory(const Trajectory& trajectory, const std::string& origin);

// Writes atomically (to FILE.tmp, then renamed), so a failed write never leaves a partial file.
void write_trajectory(const std::filesystem::path& file, const Trajectory& trajectory);

Trajectory read_trajectory(const std::filesystem::path& file);

}  // namespace needlefem::replay
