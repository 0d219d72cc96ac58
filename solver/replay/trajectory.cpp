// Trajectory HDF5 writer and validating reader; the file format is documented in trajectory.hpp.
#include "replay/trajectory.hpp"

#include <hdf5.h>

#include <cmath>
#include <system_error>

#include <fmt/core.h>

#include "io_errors/io_errors.hpp"

namespace needlefem::replay {

namespace {

// One HDF5 identifier, closed with its matching H5?close when it goes out of scope.
class Hid {
 public:
  Hid(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  ~Hid() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

struct DatasetSpec {
  const char* name;
  std::size_t columns;  // 0 = one-dimensional [n]
  const char* units;
};

constexpr DatasetSpec time_spec{"time_s", 0, "s"};
constexpr DatasetSpec position_spec{"position_m", 3, "m"};
constexpr DatasetSpec orientation_spec{"orientation", 4, "1"};
constexpr DatasetSpec force_spec{"force_n", 3, "N"};
constexpr DatasetSpec torque_spec{"torque_n_m", 3, "N m"};

constexpr double quaternion_norm_tolerance = 1e-3;

// ---------------------------------------------------------------- writing

void write_string_attribute(hid_t object, const char* name, const std::string& value, const std::string& file) {
  Hid type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.empty() ? 1 : value.size());
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  Hid space(H5Screate(H5S_SCALAR), H5Sclose);
  Hid attribute(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const std::string stored = value.empty() ? std::string(1, '\0') : value;
  if (!attribute.valid() || H5Awrite(attribute.get(), type.get(), stored.data()) < 0)
    throw TrajectoryError(fmt::format("{}: cannot write attribute '{}'", file, name));
}

void write_dataset(hid_t file_id, const DatasetSpec& spec, const double* data, std::size_t rows, const std::string& file) {
  const hsize_t dims[2] = {rows, spec.columns};
  Hid space(H5Screate_simple(spec.columns == 0 ? 1 : 2, dims, nullptr), H5Sclose);
  Hid dataset(H5Dcreate2(file_id, spec.name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose);
  if (!dataset.valid() || H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw TrajectoryError(fmt::format("{}: dataset '{}': cannot write", file, spec.name));
  write_string_attribute(dataset.get(), "units", spec.units, file);
}

// ---------------------------------------------------------------- reading

std::string read_string_attribute(hid_t object, const char* name, const std::string& where) {
  if (H5Aexists(object, name) <= 0) throw TrajectoryError(fmt::format("{}: missing attribute '{}'", where, name));
  Hid attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Hid file_type(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(file_type.get()) != H5T_STRING)
    throw TrajectoryError(fmt::format("{}: attribute '{}' is not a string", where, name));
  if (H5Tis_variable_str(file_type.get()) > 0) {  // as h5py writes str attributes
    Hid memory_type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memory_type.get(), H5T_VARIABLE);
    char* text = nullptr;
    if (H5Aread(attribute.get(), memory_type.get(), &text) < 0 || text == nullptr)
      throw TrajectoryError(fmt::format("{}: cannot read attribute '{}'", where, name));
    std::string value(text);
    H5free_memory(text);
    return value;
  }
  std::string value(H5Tget_size(file_type.get()), '\0');
  Hid memory_type(H5Tcopy(file_type.get()), H5Tclose);
  if (H5Aread(attribute.get(), memory_type.get(), value.data()) < 0)
    throw TrajectoryError(fmt::format("{}: cannot read attribute '{}'", where, name));
  return value.substr(0, value.find('\0'));
}

long read_integer_attribute(hid_t object, const char* name, const std::string& where) {
  if (H5Aexists(object, name) <= 0) throw TrajectoryError(fmt::format("{}: missing attribute '{}'", where, name));
  Hid attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  Hid file_type(H5Aget_type(attribute.get()), H5Tclose);
  long value = 0;
  if (H5Tget_class(file_type.get()) != H5T_INTEGER || H5Aread(attribute.get(), H5T_NATIVE_LONG, &value) < 0)
    throw TrajectoryError(fmt::format("{}: attribute '{}' is not an integer", where, name));
  return value;
}

// Reads an [n] or [n, columns] floating-point dataset as row-major doubles; returns n.
std::size_t read_dataset(hid_t file_id, const DatasetSpec& spec, std::vector<double>& values, const std::string& file) {
  const std::string where = fmt::format("{}: dataset '{}'", file, spec.name);
  if (H5Lexists(file_id, spec.name, H5P_DEFAULT) <= 0) throw TrajectoryError(where + ": missing");
  Hid dataset(H5Dopen2(file_id, spec.name, H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) throw TrajectoryError(where + ": not a dataset");
  Hid type(H5Dget_type(dataset.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_FLOAT) throw TrajectoryError(where + ": must hold floating-point numbers");
  Hid space(H5Dget_space(dataset.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  hsize_t dims[H5S_MAX_RANK] = {};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  const std::string wanted = spec.columns == 0 ? "[n]" : fmt::format("[n,{}]", spec.columns);
  std::string found = "[";
  for (int i = 0; i < rank; ++i) found += fmt::format("{}{}", i ? "," : "", dims[i]);
  found += "]";
  const int wanted_rank = spec.columns == 0 ? 1 : 2;
  if (rank != wanted_rank || (spec.columns != 0 && dims[1] != spec.columns))
    throw TrajectoryError(fmt::format("{}: shape {} but the format needs {}", where, found, wanted));
  values.resize(dims[0] * (spec.columns == 0 ? 1 : spec.columns));
  if (!values.empty() && H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw TrajectoryError(where + ": cannot read");
  return dims[0];
}

template <std::size_t N>
std::vector<std::array<double, N>> to_rows(const std::vector<double>& flat) {
  std::vector<std::array<double, N>> rows(flat.size() / N);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < N; ++j) rows[i][j] = flat[i * N + j];
  return rows;
}

template <std::size_t N>
std::vector<double> to_flat(const std::vector<std::array<double, N>>& rows) {
  std::vector<double> flat;
  flat.reserve(rows.size() * N);
  for (const auto& row : rows) flat.insert(flat.end(), row.begin(), row.end());
  return flat;
}

template <std::size_t N>
void require_finite(const std::vector<std::array<double, N>>& rows, const std::string& origin, const char* name) {
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (double v : rows[i])
      if (!std::isfinite(v))
        throw TrajectoryError(fmt::format("{}: dataset '{}': non-finite value at sample {}", origin, name, i));
}

}  // namespace

void validate_trajectory(const Trajectory& t, const std::string& origin) {
  const std::size_t n = t.time_s.size();
  if (n < 2) throw TrajectoryError(fmt::format("{}: dataset 'time_s': {} samples, replay needs at least 2", origin, n));
  auto require_rows = [&](std::size_t rows, const char* name) {
    if (rows != n)
      throw TrajectoryError(fmt::format("{}: dataset '{}': {} samples but 'time_s' has {}", origin, name, rows, n));
  };
  require_rows(t.position_m.size(), position_spec.name);
  require_rows(t.orientation.size(), orientation_spec.name);
  require_rows(t.force_n.size(), force_spec.name);
  require_rows(t.torque_n_m.size(), torque_spec.name);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(t.time_s[i]))
      throw TrajectoryError(fmt::format("{}: dataset 'time_s': non-finite value at sample {}", origin, i));
    if (i > 0 && !(t.time_s[i] > t.time_s[i - 1]))
      throw TrajectoryError(fmt::format("{}: dataset 'time_s': not strictly increasing at sample {} ({} after {})",
                                        origin, i, t.time_s[i], t.time_s[i - 1]));
  }
  require_finite(t.position_m, origin, position_spec.name);
  require_finite(t.orientation, origin, orientation_spec.name);
  require_finite(t.force_n, origin, force_spec.name);
  require_finite(t.torque_n_m, origin, torque_spec.name);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& q = t.orientation[i];
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (std::abs(norm - 1.0) > quaternion_norm_tolerance)
      throw TrajectoryError(fmt::format("{}: dataset 'orientation': quaternion at sample {} has norm {}, not 1",
                                        origin, i, norm));
  }
}

void write_trajectory(const std::filesystem::path& file, const Trajectory& t) {
  const std::string name = file.string();
  validate_trajectory(t, name);
  const std::filesystem::path partial = file.string() + ".tmp";
  {
    io::stop_hdf5_error_printing();
    Hid file_id(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    if (!file_id.valid()) throw TrajectoryError(fmt::format("{}: cannot create file", partial.string()));
    write_string_attribute(file_id.get(), "format", trajectory_format_name, name);
    {
      Hid space(H5Screate(H5S_SCALAR), H5Sclose);
      Hid version(H5Acreate2(file_id.get(), "format_version", H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                  H5Aclose);
      const int value = trajectory_format_version;
      if (!version.valid() || H5Awrite(version.get(), H5T_NATIVE_INT, &value) < 0)
        throw TrajectoryError(fmt::format("{}: cannot write attribute 'format_version'", name));
    }
    write_string_attribute(file_id.get(), "source_case", t.source_case, name);
    write_dataset(file_id.get(), time_spec, t.time_s.data(), t.size(), name);
    write_dataset(file_id.get(), position_spec, to_flat(t.position_m).data(), t.size(), name);
    write_dataset(file_id.get(), orientation_spec, to_flat(t.orientation).data(), t.size(), name);
    {
      Hid dataset(H5Dopen2(file_id.get(), orientation_spec.name, H5P_DEFAULT), H5Dclose);
      write_string_attribute(dataset.get(), "order", "w,x,y,z", name);
    }
    write_dataset(file_id.get(), force_spec, to_flat(t.force_n).data(), t.size(), name);
    write_dataset(file_id.get(), torque_spec, to_flat(t.torque_n_m).data(), t.size(), name);
  }
  std::error_code error;
  std::filesystem::rename(partial, file, error);
  if (error) throw TrajectoryError(fmt::format("{}: cannot move finished file into place: {}", name, error.message()));
}

Trajectory read_trajectory(const std::filesystem::path& file) {
  const std::string name = file.string();
  io::stop_hdf5_error_printing();
  if (!std::filesystem::exists(file)) throw TrajectoryError(fmt::format("{}: no such file", name));
  if (H5Fis_hdf5(file.c_str()) <= 0) throw TrajectoryError(fmt::format("{}: not an HDF5 file", name));
  Hid file_id(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file_id.valid()) throw TrajectoryError(fmt::format("{}: cannot open", name));

  const std::string format = read_string_attribute(file_id.get(), "format", name);
  if (format != trajectory_format_name)
    throw TrajectoryError(fmt::format("{}: attribute 'format' is '{}', expected '{}'", name, format,
                                      trajectory_format_name));
  const long version = read_integer_attribute(file_id.get(), "format_version", name);
  if (version != trajectory_format_version)
    throw TrajectoryError(fmt::format("{}: format_version {} is not supported (this build reads {})", name, version,
                                      trajectory_format_version));

  Trajectory t;
  t.source_case = H5Aexists(file_id.get(), "source_case") > 0
                      ? read_string_attribute(file_id.get(), "source_case", name)
                      : std::string();
  std::vector<double> flat;
  read_dataset(file_id.get(), time_spec, t.time_s, name);
  read_dataset(file_id.get(), position_spec, flat, name);
  t.position_m = to_rows<3>(flat);
  read_dataset(file_id.get(), orientation_spec, flat, name);
  t.orientation = to_rows<4>(flat);
  read_dataset(file_id.get(), force_spec, flat, name);
  t.force_n = to_rows<3>(flat);
  read_dataset(file_id.get(), torque_spec, flat, name);
  t.torque_n_m = to_rows<3>(flat);

  validate_trajectory(t, name);
  for (auto& q : t.orientation) {
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= norm;
  }
  return t;
}

}  // namespace needlefem::replay
