// Paper 000's three-stage insertion force as a replay trajectory; the model is in force_trajectory.hpp.
#include "insertion_force/force_trajectory.hpp"

#include <hdf5.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <fmt/core.h>

namespace needlefem::insertion {

double InsertionForceParameters::fracture_force_n() const {
  return 2.0 * std::numbers::pi * fracture_toughness_j_per_m2 * needle_radius_m;
}

namespace {

void validate(const InsertionForceParameters& p) {
  auto require_positive = [](double value, const char* name) {
    if (!(value > 0.0) || !std::isfinite(value))
      throw std::invalid_argument(fmt::format("insertion force: {} must be positive, got {}", name, value));
  };
  require_positive(p.needle_radius_m, "needle radius");
  require_positive(p.fracture_toughness_j_per_m2, "fracture toughness");
  require_positive(p.rupture_force_n, "rupture force");
  require_positive(p.insertion_speed_m_per_s, "insertion speed");
  require_positive(p.travel_m, "travel");
  require_positive(p.sample_interval_s, "sample interval");
  if (!(p.shaft_friction_n_per_m >= 0.0))
    throw std::invalid_argument("insertion force: shaft friction must be >= 0");
  if (!(p.rupture_force_n > p.fracture_force_n()))
    throw std::invalid_argument(fmt::format(
        "insertion force: the rupture force {:.4g} N must exceed the fracture force 2 pi J_c r = {:.4g} N, "
        "or the crack could not stop after rupture",
        p.rupture_force_n, p.fracture_force_n()));
}

}  // namespace

InsertionForceTrajectory insertion_force_trajectory(const DeformationEnergy& deformation,
                                                    const InsertionForceParameters& p) {
  validate(p);
  InsertionForceTrajectory out;
  out.fracture_force_n = p.fracture_force_n();
  out.rupture_displacement_m = deformation.displacement_at_force_m(p.rupture_force_n);
  out.ruptured = out.rupture_displacement_m <= p.travel_m;
  out.rupture_time_s = out.rupture_displacement_m / p.insertion_speed_m_per_s;
  out.steady_deformation_m = deformation.displacement_at_force_m(out.fracture_force_n);

  auto add_sample = [&](double time, bool after_rupture) {
    const double x = p.insertion_speed_m_per_s * time;
    const double l = after_rupture ? x - out.steady_deformation_m : 0.0;
    const double force = after_rupture ? out.fracture_force_n + p.shaft_friction_n_per_m * l : deformation.force_n(x);
    auto& t = out.trajectory;
    t.time_s.push_back(time);
    t.position_m.push_back({0.0, 0.0, x});
    t.orientation.push_back({1.0, 0.0, 0.0, 0.0});
    t.force_n.push_back({0.0, 0.0, -force});
    t.torque_n_m.push_back({0.0, 0.0, 0.0});
    out.displacement_m.push_back(x);
    out.crack_length_m.push_back(l);
    out.stage.push_back(static_cast<int>(after_rupture ? Stage::penetration : Stage::deformation));
  };

  const double duration = p.travel_m / p.insertion_speed_m_per_s;
  const auto intervals = static_cast<long>(std::ceil(duration / p.sample_interval_s - 1e-9));
  // Grid times closer than this to the rupture instant are dropped (time must increase strictly).
  const double tolerance = 1e-9 * p.sample_interval_s;
  bool rupture_sampled = !out.ruptured;
  for (long k = 0; k <= intervals; ++k) {
    const double time = std::min(static_cast<double>(k) * p.sample_interval_s, duration);
    if (!rupture_sampled && time >= out.rupture_time_s - tolerance) {
      add_sample(out.rupture_time_s, false);  // the peak: F_def(x_r) = F_r
      rupture_sampled = true;
      if (std::abs(time - out.rupture_time_s) <= tolerance) continue;
    }
    add_sample(time, out.ruptured && time > out.rupture_time_s);
  }
  return out;
}

void append_insertion_datasets(const std::filesystem::path& file, const InsertionForceTrajectory& result) {
  const std::string name = file.string();
  const hid_t file_id = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file_id < 0) throw replay::TrajectoryError(fmt::format("{}: cannot reopen to add datasets", name));
  auto write = [&](const char* dataset, hid_t file_type, hid_t memory_type, const void* data, const char* units) {
    const hsize_t size = result.displacement_m.size();
    const hid_t space = H5Screate_simple(1, &size, nullptr);
    const hid_t set = H5Dcreate2(file_id, dataset, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    bool ok = set >= 0 && H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0;
    if (ok) {
      const hid_t text = H5Tcopy(H5T_C_S1);
      H5Tset_size(text, std::string(units).size());
      const hid_t scalar = H5Screate(H5S_SCALAR);
      const hid_t attribute = H5Acreate2(set, "units", text, scalar, H5P_DEFAULT, H5P_DEFAULT);
      ok = attribute >= 0 && H5Awrite(attribute, text, units) >= 0;
      if (attribute >= 0) H5Aclose(attribute);
      H5Sclose(scalar);
      H5Tclose(text);
    }
    if (set >= 0) H5Dclose(set);
    H5Sclose(space);
    if (!ok) {
      H5Fclose(file_id);
      throw replay::TrajectoryError(fmt::format("{}: dataset '{}': cannot write", name, dataset));
    }
  };
  write("displacement_m", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, result.displacement_m.data(), "m");
  write("crack_length_m", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, result.crack_length_m.data(), "m");
  write("stage", H5T_STD_I32LE, H5T_NATIVE_INT, result.stage.data(), "0 = deformation, 1 = penetration");
  H5Fclose(file_id);
}

}  // namespace needlefem::insertion
