// Steering result file writer; the layout is documented in path_file.hpp. Uses HDF5's
// high-level Lite API (H5LT): every dataset is written whole, once.
#include "steering/path_file.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <stdexcept>

#include <fmt/format.h>

#include "io_errors/io_errors.hpp"

namespace needlefem::steering {

namespace {

class PathFileWriter {
 public:
  explicit PathFileWriter(const std::filesystem::path& file) : name_(file.string()) {
    io::stop_hdf5_error_printing();  // every call below is checked and reported in one line
    id_ = H5Fcreate(name_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (id_ < 0) throw std::runtime_error(fmt::format("{}: cannot create HDF5 file", name_));
  }
  PathFileWriter(const PathFileWriter&) = delete;
  PathFileWriter& operator=(const PathFileWriter&) = delete;
  ~PathFileWriter() { H5Fclose(id_); }

  void group(const char* name) {
    const hid_t g = H5Gcreate2(id_, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) throw std::runtime_error(fmt::format("{}: cannot create group '{}'", name_, name));
    H5Gclose(g);
  }
  // rows x columns doubles (columns 0 = a one-dimensional dataset).
  void dataset(const std::string& name, const std::vector<double>& values, std::size_t columns, const char* units) {
    const hsize_t dims[2] = {columns ? values.size() / columns : values.size(), columns};
    if (H5LTmake_dataset_double(id_, name.c_str(), columns ? 2 : 1, dims, values.data()) < 0 ||
        H5LTset_attribute_string(id_, name.c_str(), "units", units) < 0)
      throw std::runtime_error(fmt::format("{}: cannot write dataset '{}'", name_, name));
  }
  void root_text(const char* name, const std::string& value) {
    if (H5LTset_attribute_string(id_, "/", name, value.c_str()) < 0)
      throw std::runtime_error(fmt::format("{}: cannot write attribute '{}'", name_, name));
  }
  void root_real(const char* name, double value) {
    if (H5LTset_attribute_double(id_, "/", name, &value, 1) < 0)
      throw std::runtime_error(fmt::format("{}: cannot write attribute '{}'", name_, name));
  }
  void close() {
    if (H5Fflush(id_, H5F_SCOPE_GLOBAL) < 0) throw std::runtime_error(fmt::format("{}: cannot flush", name_));
  }

 private:
  std::string name_;
  hid_t id_ = -1;
};

template <class Field>
std::vector<double> column(const std::vector<PathSample>& path, Field field) {
  std::vector<double> out;
  out.reserve(path.size());
  for (const PathSample& s : path) out.push_back(field(s));
  return out;
}

template <class Field>
std::vector<double> vectors(const std::vector<PathSample>& path, Field field) {
  std::vector<double> out;
  out.reserve(3 * path.size());
  for (const PathSample& s : path) {
    const Vec3 v = field(s);
    out.insert(out.end(), v.begin(), v.end());
  }
  return out;
}

}  // namespace

void write_steering_path(const std::filesystem::path& file, const std::vector<PathSample>& path,
                         const ObstacleScene& scene, const SteeringOutcome& outcome,
                         const std::string& resolved_case_toml) {
  PathFileWriter out(file);
  out.root_text("format", "needlefem-steering-path");
  out.root_text("case", resolved_case_toml);
  out.root_real("obstacle_clearance_tip_path_m", outcome.tip_path_clearance_m);
  out.root_real("obstacle_clearance_needle_m", outcome.needle_clearance_m);
  out.root_real("target_miss_distance_m", outcome.miss_distance_m);
  out.root_real("target_closest_approach_m", outcome.target_closest_approach_m);

  out.dataset("time_s", column(path, [](const PathSample& s) { return s.time_s; }), 0, "s");
  out.dataset("depth_m", column(path, [](const PathSample& s) { return s.depth_m; }), 0, "m");
  out.dataset("tip_position_m", vectors(path, [](const PathSample& s) { return s.tip_m; }), 3, "m");
  out.dataset("pivot_position_m", vectors(path, [](const PathSample& s) { return s.pivot_m; }), 3, "m");
  out.dataset("head_direction", vectors(path, [](const PathSample& s) { return s.head_direction; }), 3, "1");
  out.dataset("shaft_direction", vectors(path, [](const PathSample& s) { return s.shaft_direction; }), 3, "1");
  out.dataset("pull_direction", vectors(path, [](const PathSample& s) { return s.pull_direction; }), 3, "1");
  out.dataset("turning_angle_rad", column(path, [](const PathSample& s) { return s.turning_angle_rad; }), 0, "rad");
  out.dataset("flux_density_t", column(path, [](const PathSample& s) { return s.flux_density_t; }), 0, "T");
  out.dataset("force_n",
              vectors(path,
                      [](const PathSample& s) {
                        return Vec3{s.force_n * s.pull_direction[0], s.force_n * s.pull_direction[1],
                                    s.force_n * s.pull_direction[2]};
                      }),
              3, "N");
  out.dataset("magnet_distance_m", column(path, [](const PathSample& s) { return s.magnet_distance_m; }), 0, "m");

  out.group("scene");
  auto point = [&](const char* name, const Vec3& v) { out.dataset(fmt::format("scene/{}", name), {v[0], v[1], v[2]}, 0, "m"); };
  point("block_min_m", scene.block_min_m);
  point("block_max_m", scene.block_max_m);
  point("obstacle_centre_m", scene.obstacle_centre_m);
  point("target_m", scene.target_m);
  out.dataset("scene/obstacle_radius_m", {scene.obstacle_radius_m}, 0, "m");
  out.dataset("scene/needle_radius_m", {scene.needle_radius_m}, 0, "m");
  out.close();
}

}  // namespace needlefem::steering
