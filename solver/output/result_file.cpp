#include "output/result_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "io_errors/io_errors.hpp"
#include "output/xdmf_text.hpp"

namespace needlefem::output {
namespace {

constexpr double kMillimetresPerMetre = 1000.0;

// A failed HDF5 call: "cannot WHAT: REASON". The public operations prefix the file's path
// (with_path), so the user reads one line such as
// "out/result.h5: cannot write displacement: no space left on device".
struct Hdf5Failure : std::runtime_error {
  explicit Hdf5Failure(const std::string& what)
      : std::runtime_error(fmt::format("cannot {}: {}", what, io::hdf5_failure_reason())) {}
};

// Runs `body` with HDF5's own error printing off (io_errors.hpp); an HDF5 failure is reported under `path`.
template <class Body>
void with_path(const std::filesystem::path& path, Body&& body) {
  io::stop_hdf5_error_printing();
  try {
    body();
  } catch (const Hdf5Failure& failure) {
    throw std::runtime_error(fmt::format("{}: {}", path.string(), failure.what()));
  }
}

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw Hdf5Failure(what);
  }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  Handle& operator=(Handle&& other) noexcept {
    std::swap(id_, other.id_);
    std::swap(close_, other.close_);
    return *this;
  }
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  // Closes now so that errors surface (the destructor cannot report them).
  void close(const std::string& what) {
    if (id_ >= 0 && close_(std::exchange(id_, -1)) < 0) throw Hdf5Failure("close " + what);
  }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw Hdf5Failure(what);
}

// Object creation properties shared by groups and datasets: no time stamps, so that the
// same input gives the same bytes (and so that metadata never changes after creation).
Handle creation_properties(hid_t property_class) {
  Handle properties(H5Pcreate(property_class), H5Pclose, "create property list");
  check(H5Pset_obj_track_times(properties.get(), false), "disable time tracking");
  return properties;
}

Handle create_group(hid_t parent, const std::string& name) {
  Handle properties = creation_properties(H5P_GROUP_CREATE);
  return Handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                H5Gclose, "create group " + name);
}

// A contiguous dataset. `preallocate` allocates its file space now and never writes fill
// values (the space stays a hole in the file until data arrives).
Handle create_dataset(hid_t parent, const std::string& name, hid_t file_type,
                      const std::vector<hsize_t>& dims, bool preallocate) {
  Handle properties = creation_properties(H5P_DATASET_CREATE);
  check(H5Pset_layout(properties.get(), H5D_CONTIGUOUS), "set contiguous layout");
  if (preallocate) {
    check(H5Pset_alloc_time(properties.get(), H5D_ALLOC_TIME_EARLY), "set allocation time");
    check(H5Pset_fill_time(properties.get(), H5D_FILL_TIME_NEVER), "set fill time");
  }
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               "create dataspace for " + name);
  return Handle(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT, properties.get(),
                           H5P_DEFAULT),
                H5Dclose, "create dataset " + name);
}

// One time of a [capacity, n(, c)] dataset as its own [n(, c)] dataset: an HDF5 virtual
// dataset (no storage of its own) mapping onto slab `index` of `source` in this file.
void create_time_view(hid_t parent, const std::string& name, const std::string& source,
                      const std::vector<hsize_t>& source_dims, hsize_t index) {
  Handle properties = creation_properties(H5P_DATASET_CREATE);
  Handle source_space(H5Screate_simple(static_cast<int>(source_dims.size()), source_dims.data(), nullptr), H5Sclose,
                      "create dataspace for " + source);
  std::vector<hsize_t> start(source_dims.size(), 0), count = source_dims;
  start[0] = index;
  count[0] = 1;
  check(H5Sselect_hyperslab(source_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select slab of " + source);
  Handle view_space(H5Screate_simple(static_cast<int>(count.size()) - 1, count.data() + 1, nullptr), H5Sclose,
                    "create dataspace for " + name);
  check(H5Pset_virtual(properties.get(), view_space.get(), ".", source.c_str(), source_space.get()),
        "map " + name + " onto " + source);
  Handle(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, view_space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
         H5Dclose, "create virtual dataset " + name);
}

template <class T>
hid_t memory_type() {
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<T, int>) return H5T_NATIVE_INT;
  else return H5T_NATIVE_LLONG;
}

template <class T>
void write_dataset(hid_t parent, const std::string& name, hid_t file_type,
                   const std::vector<hsize_t>& dims, const std::vector<T>& values) {
  Handle dataset = create_dataset(parent, name, file_type, dims, false);
  check(H5Dwrite(dataset.get(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
        "write " + name);
}

Handle text_type() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "set string size");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "set string encoding");
  return type;
}

void write_text_attribute(hid_t object, const std::string& name, const std::string& value) {
  Handle type = text_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar dataspace");
  Handle attribute(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "create attribute " + name);
  const char* text = value.c_str();
  check(H5Awrite(attribute.get(), type.get(), &text), "write attribute " + name);
}

void write_text_list_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values) {
  Handle type = text_type();
  const hsize_t count = values.size();
  Handle space(H5Screate_simple(1, &count, nullptr), H5Sclose, "create dataspace");
  Handle attribute(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "create attribute " + name);
  std::vector<const char*> texts;
  for (const std::string& value : values) texts.push_back(value.c_str());
  check(H5Awrite(attribute.get(), type.get(), texts.data()), "write attribute " + name);
}

std::string type_name(FieldType type) {
  switch (type) {
    case FieldType::scalar: return "scalar";
    case FieldType::vector: return "vector";
    case FieldType::symmetric_tensor: return "symmetric tensor, stored as 9 components xx xy xz yx yy yz zx zy zz";
    case FieldType::tensor: return "tensor, 9 components xx xy xz yx yy yz zx zy zz";
  }
  throw std::logic_error("unknown field type");
}

// Caller's values -> stored values: times spec.scale, symmetric tensors expanded from
// xx yy zz xy yz xz.
std::vector<double> stored_values(const FieldSpec& spec, std::span<const double> values) {
  std::vector<double> stored;
  if (spec.type != FieldType::symmetric_tensor) {
    stored.assign(values.begin(), values.end());
  } else {
    constexpr int kFullFromVoigt[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
    const std::size_t count = values.size() / 6;
    stored.resize(count * 9);
    for (std::size_t e = 0; e < count; ++e)
      for (int k = 0; k < 9; ++k) stored[e * 9 + k] = values[e * 6 + kFullFromVoigt[k]];
  }
  if (spec.scale != 1.0)
    for (double& v : stored) v *= spec.scale;
  return stored;
}

std::string checked_field_name(const std::string& name) {
  if (name.empty() || name.find_first_of("/<>&\"'.{}") != std::string::npos)
    throw std::invalid_argument(fmt::format("result field name '{}': empty or contains one of / < > & \" ' . {{ }}", name));
  return name;
}

}  // namespace

int input_components(FieldType type) {
  switch (type) {
    case FieldType::scalar: return 1;
    case FieldType::vector: return 3;
    case FieldType::symmetric_tensor: return 6;
    case FieldType::tensor: return 9;
  }
  throw std::logic_error("unknown field type");
}

int stored_components(FieldType type) { return type == FieldType::symmetric_tensor ? 9 : input_components(type); }

struct ResultFile::State {
  std::filesystem::path h5_path;
  Handle file;
  std::size_t node_count = 0;
  std::size_t cell_count = 0;
  std::set<std::string> field_names{"region"};
  std::vector<FieldSpec> series;
  std::vector<Handle> series_datasets;
  Handle time_dataset;
  Handle time_count_dataset;
  std::size_t capacity = 0;
  std::vector<double> times;
  XdmfDocument volume;    // the tetrahedra
  XdmfDocument surfaces;  // named boundary faces (no grids when the mesh has none)
  bool committed = false;

  std::filesystem::path xdmf_path() const {
    std::filesystem::path path = h5_path;
    return path.replace_extension(".xdmf");
  }
  std::filesystem::path surfaces_xdmf_path() const {
    std::filesystem::path path = h5_path;
    return path.replace_filename(h5_path.stem().string() + "_surfaces.xdmf");
  }
  std::size_t entities(FieldCentre centre) const { return centre == FieldCentre::node ? node_count : cell_count; }

  void add_attribute(const FieldSpec& spec, const std::string& path, bool per_time) {
    const XdmfAttribute attribute{spec.name, spec.centre == FieldCentre::node,
                                  {path, entities(spec.centre), stored_components(spec.type), false, per_time}};
    volume.grids.front().attributes.push_back(attribute);
    volume.grids.front().information.emplace_back("unit:" + spec.name, spec.unit);
    // Boundary faces share the volume's node numbering, so node fields apply to them as is.
    if (spec.centre == FieldCentre::node)
      for (XdmfTopology& surface : surfaces.grids) surface.attributes.push_back(attribute);
  }

  // Both XDMF files or neither (replace_files_atomically).
  void write_xdmf() const {
    std::vector<std::pair<std::filesystem::path, std::string>> files{{xdmf_path(), xdmf_text(volume, times)}};
    if (!surfaces.grids.empty()) files.emplace_back(surfaces_xdmf_path(), xdmf_text(surfaces, times));
    replace_files_atomically(files);
  }

  // Everything structural is on disk from here on; afterwards only raw data is written.
  void commit() {
    if (committed) return;
    check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flush");
    write_xdmf();
    committed = true;
  }

  void check_count(const FieldSpec& spec, std::size_t count) const {
    const std::size_t expected = entities(spec.centre) * static_cast<std::size_t>(input_components(spec.type));
    if (count != expected)
      throw std::invalid_argument(fmt::format("result field '{}': {} values given, {} expected", spec.name, count, expected));
  }

  // The constructor's work: the file, the mesh, the case and every time-series dataset.
  void create(const TetMesh& mesh, const std::string& resolved_case_toml, std::vector<FieldSpec> time_series,
              std::size_t output_capacity);
  // create()'s parts, in the order their objects go into the file: /mesh with the volume's XDMF
  // grid, /mesh/surfaces with one XDMF grid each, /series at full capacity.
  void write_mesh(const TetMesh& mesh);
  void write_surfaces(hid_t mesh_group, const TetMesh& mesh);
  void create_time_series(std::vector<FieldSpec> time_series);
  // append_time's work on the file (see there).
  void append(double time_s, const std::vector<std::span<const double>>& values);
  void set_time_count(long long count);
};

ResultFile::ResultFile(const std::filesystem::path& h5_path, const TetMesh& mesh,
                       const std::string& resolved_case_toml, std::vector<FieldSpec> time_series,
                       std::size_t output_capacity)
    : state_(std::make_unique<State>()) {
  state_->h5_path = h5_path;
  with_path(h5_path, [&] { state_->create(mesh, resolved_case_toml, std::move(time_series), output_capacity); });
}

void ResultFile::State::create(const TetMesh& mesh, const std::string& resolved_case_toml,
                               std::vector<FieldSpec> time_series, std::size_t output_capacity) {
  State& s = *this;
  const std::filesystem::path& h5_path = s.h5_path;
  s.node_count = mesh.nodes.size();
  s.cell_count = mesh.tet_count();
  s.capacity = output_capacity;
  if (!time_series.empty() && output_capacity == 0)
    throw std::invalid_argument("result file: time-series fields declared with an output capacity of 0");
  if (mesh.nodes_per_tet != 10 && mesh.nodes_per_tet != 4)
    throw std::invalid_argument(fmt::format("result file: {} nodes per tet (10 or 4 expected)", mesh.nodes_per_tet));

  // A stale XDMF must never point into the file about to be truncated.
  std::filesystem::remove(s.xdmf_path());
  std::filesystem::remove(s.surfaces_xdmf_path());

  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create file access list");
  // No sieve buffer: raw writes go to the OS when H5Dwrite returns.
  check(H5Pset_sieve_buf_size(access.get(), 0), "disable sieve buffer");
  s.file = Handle(H5Fcreate(h5_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), H5Fclose,
                  "create the file");
  write_text_attribute(s.file.get(), "case", resolved_case_toml);

  write_mesh(mesh);
  // Time series: all datasets at full capacity now, so that appending never changes metadata.
  if (!time_series.empty()) create_time_series(std::move(time_series));
}

void ResultFile::State::write_mesh(const TetMesh& mesh) {
  State& s = *this;
  Handle mesh_group = create_group(s.file.get(), "mesh");
  std::vector<double> coordinates_mm;
  coordinates_mm.reserve(s.node_count * 3);
  for (const Point3& node : mesh.nodes)
    for (double x : node) coordinates_mm.push_back(x * kMillimetresPerMetre);
  write_dataset(mesh_group.get(), "coordinates_mm", H5T_IEEE_F64LE, {s.node_count, 3}, coordinates_mm);
  {
    Handle coordinates(H5Dopen2(mesh_group.get(), "coordinates_mm", H5P_DEFAULT), H5Dclose, "open coordinates");
    write_text_attribute(coordinates.get(), "unit", "mm");
    write_text_attribute(coordinates.get(), "note", "converted from the solver's metres for viewing");
  }
  const int per_tet = mesh.nodes_per_tet;
  std::vector<int> tets(mesh.tet_nodes.size());
  for (std::size_t e = 0; e < s.cell_count; ++e)
    for (int k = 0; k < per_tet; ++k)
      tets[e * per_tet + k] = mesh.tet(e)[per_tet == 10 ? kTet10GmshOfVtk[k] : k];
  write_dataset(mesh_group.get(), "tets", H5T_STD_I32LE, {s.cell_count, static_cast<hsize_t>(per_tet)}, tets);
  write_dataset(mesh_group.get(), "region", H5T_STD_I32LE, {s.cell_count}, mesh.tet_region);
  {
    Handle region(H5Dopen2(mesh_group.get(), "region", H5P_DEFAULT), H5Dclose, "open region");
    write_text_list_attribute(region.get(), "names", mesh.region_names);
  }
  std::string region_list;
  for (std::size_t r = 0; r < mesh.region_names.size(); ++r)
    region_list += fmt::format("{}{}={}", r ? ", " : "", r, mesh.region_names[r]);

  s.volume.h5_file_name = s.h5_path.filename().string();
  s.volume.coordinates = {"/mesh/coordinates_mm", s.node_count, 3, false, false};
  XdmfTopology tetrahedra;
  tetrahedra.name = "mesh";
  tetrahedra.topology_type = per_tet == 10 ? "Tetrahedron_10" : "Tetrahedron";
  tetrahedra.connectivity = {"/mesh/tets", s.cell_count, per_tet, true, false};
  tetrahedra.attributes.push_back({"region", false, {"/mesh/region", s.cell_count, 1, true, false}});
  tetrahedra.information = {{"region_names", region_list}, {"length_unit", "mm"}, {"time_unit", "s"}};
  s.volume.grids.push_back(std::move(tetrahedra));

  s.surfaces.h5_file_name = s.volume.h5_file_name;
  s.surfaces.coordinates = s.volume.coordinates;
  write_surfaces(mesh_group.get(), mesh);
}

void ResultFile::State::write_surfaces(hid_t mesh_group, const TetMesh& mesh) {
  State& s = *this;
  if (mesh.surface_faces.empty()) return;
  Handle surfaces_group = create_group(mesh_group, "surfaces");
  const int per_face = mesh.nodes_per_face();
  for (const auto& [name, faces] : mesh.surface_faces) {
    const std::size_t face_count = faces.size() / per_face;
    write_dataset(surfaces_group.get(), checked_field_name(name), H5T_STD_I32LE,
                  {face_count, static_cast<hsize_t>(per_face)}, faces);
    XdmfTopology surface;
    surface.name = name;
    surface.topology_type = per_face == 6 ? "Triangle_6" : "Triangle";
    surface.connectivity = {"/mesh/surfaces/" + name, face_count, per_face, true, false};
    surface.information = {{"length_unit", "mm"}};
    s.surfaces.grids.push_back(std::move(surface));
  }
}

void ResultFile::State::create_time_series(std::vector<FieldSpec> time_series) {
  State& s = *this;
  Handle series_group = create_group(s.file.get(), "series");
  s.time_dataset = create_dataset(series_group.get(), "time", H5T_IEEE_F64LE, {s.capacity}, true);
  write_text_attribute(s.time_dataset.get(), "unit", "s");
  s.time_count_dataset = create_dataset(series_group.get(), "time_count", H5T_STD_I64LE, {1}, false);
  const long long zero = 0;
  check(H5Dwrite(s.time_count_dataset.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &zero),
        "write time_count");
  write_text_attribute(s.time_count_dataset.get(), "note",
                       "number of completed output times; later entries of /series are unwritten");
  Handle node_group = create_group(series_group.get(), "node");
  Handle cell_group = create_group(series_group.get(), "cell");
  Handle steps_group = create_group(series_group.get(), "steps");
  std::vector<Handle> step_groups;
  for (std::size_t i = 0; i < s.capacity; ++i) step_groups.push_back(create_group(steps_group.get(), std::to_string(i)));
  for (const FieldSpec& spec : time_series) {
    if (!s.field_names.insert(checked_field_name(spec.name)).second)
      throw std::invalid_argument(fmt::format("result field '{}' declared twice", spec.name));
    const bool at_nodes = spec.centre == FieldCentre::node;
    std::vector<hsize_t> dims{s.capacity, s.entities(spec.centre)};
    if (spec.type != FieldType::scalar) dims.push_back(stored_components(spec.type));
    Handle dataset = create_dataset(at_nodes ? node_group.get() : cell_group.get(), spec.name,
                                    H5T_IEEE_F64LE, dims, true);
    write_text_attribute(dataset.get(), "unit", spec.unit);
    write_text_attribute(dataset.get(), "type", type_name(spec.type));
    const std::string source = fmt::format("/series/{}/{}", at_nodes ? "node" : "cell", spec.name);
    for (std::size_t i = 0; i < s.capacity; ++i) create_time_view(step_groups[i].get(), spec.name, source, dims, i);
    s.add_attribute(spec, "/series/steps/{}/" + spec.name, true);
    s.series_datasets.push_back(std::move(dataset));
  }
  s.series = std::move(time_series);
}

ResultFile::~ResultFile() {
  try {
    close();
  } catch (...) {
    // A destructor cannot report; close() explicitly to see errors.
  }
}

void ResultFile::write_static_field(const FieldSpec& spec, std::span<const double> values) {
  State& s = *state_;
  if (s.committed)
    throw std::logic_error(fmt::format("result field '{}': static fields must precede the first output time", spec.name));
  s.check_count(spec, values.size());
  if (!s.field_names.insert(checked_field_name(spec.name)).second)
    throw std::invalid_argument(fmt::format("result field '{}' written twice", spec.name));
  const bool at_nodes = spec.centre == FieldCentre::node;
  const std::string group_path = at_nodes ? "static/node" : "static/cell";
  with_path(s.h5_path, [&] {
    if (H5Lexists(s.file.get(), "static", H5P_DEFAULT) <= 0) {
      Handle static_group = create_group(s.file.get(), "static");
      create_group(static_group.get(), "node");
      create_group(static_group.get(), "cell");
    }
    Handle group(H5Gopen2(s.file.get(), group_path.c_str(), H5P_DEFAULT), H5Gclose, "open " + group_path);
    std::vector<hsize_t> dims{s.entities(spec.centre)};
    if (spec.type != FieldType::scalar) dims.push_back(stored_components(spec.type));
    write_dataset(group.get(), spec.name, H5T_IEEE_F64LE, dims, stored_values(spec, values));
    Handle dataset(H5Dopen2(group.get(), spec.name.c_str(), H5P_DEFAULT), H5Dclose, "open " + spec.name);
    write_text_attribute(dataset.get(), "unit", spec.unit);
    write_text_attribute(dataset.get(), "type", type_name(spec.type));
  });
  s.add_attribute(spec, "/" + group_path + "/" + spec.name, false);
}

void ResultFile::append_time(double time_s, const std::vector<std::span<const double>>& values) {
  State& s = *state_;
  if (!s.file.get()) throw std::logic_error("result file: append_time after close");
  if (values.size() != s.series.size())
    throw std::invalid_argument(fmt::format("result file: {} time-series arrays given, {} declared", values.size(), s.series.size()));
  if (s.times.size() == s.capacity)
    throw std::length_error(fmt::format("{}: output capacity of {} times exhausted", s.h5_path.string(), s.capacity));
  for (std::size_t f = 0; f < s.series.size(); ++f) s.check_count(s.series[f], values[f].size());
  with_path(s.h5_path, [&] {
    s.commit();
    s.append(time_s, values);
  });
}

void ResultFile::State::append(double time_s, const std::vector<std::span<const double>>& values) {
  const hsize_t index = times.size();
  for (std::size_t f = 0; f < series.size(); ++f) {
    const FieldSpec& spec = series[f];
    const std::vector<double> stored = stored_values(spec, values[f]);
    const hid_t dataset = series_datasets[f].get();
    Handle file_space(H5Dget_space(dataset), H5Sclose, "get dataspace of " + spec.name);
    std::vector<hsize_t> start{index, 0}, count{1, entities(spec.centre)};
    if (spec.type != FieldType::scalar) {
      start.push_back(0);
      count.push_back(stored_components(spec.type));
    }
    check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
          "select time slab of " + spec.name);
    Handle memory_space(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose,
                        "create memory dataspace");
    check(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT, stored.data()),
          "write " + spec.name);
  }
  // Fields before their time, the time before the count: a reader trusting time_count (or
  // the XDMF written last) never sees a partly written output time.
  check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flush");
  {
    Handle file_space(H5Dget_space(time_dataset.get()), H5Sclose, "get time dataspace");
    const hsize_t one = 1;
    check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &index, nullptr, &one, nullptr), "select time");
    Handle memory_space(H5Screate_simple(1, &one, nullptr), H5Sclose, "create memory dataspace");
    check(H5Dwrite(time_dataset.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT, &time_s),
          "write time");
  }
  check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flush");
  // The count and the XDMF say the same: when the XDMF cannot be written (a full disk), the
  // count goes back, so a reader of either sees the same completed times. time_count's bytes
  // were written when the file was made, so writing them again needs no new disk space.
  try {
    set_time_count(static_cast<long long>(index) + 1);
    times.push_back(time_s);
    write_xdmf();
  } catch (...) {
    times.resize(index);
    try {
      set_time_count(static_cast<long long>(index));
    } catch (...) {
      // The first failure is the one to report; the file then lists one time the XDMF does not.
    }
    throw;
  }
}

void ResultFile::State::set_time_count(long long count) {
  check(H5Dwrite(time_count_dataset.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &count),
        "write time_count");
  check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flush");
}

void ResultFile::close() {
  State& s = *state_;
  if (!s.file.get()) return;
  with_path(s.h5_path, [&] {
    s.commit();
    s.time_count_dataset.close("time_count");
    s.time_dataset.close("time");
    for (Handle& dataset : s.series_datasets) dataset.close("time-series dataset");
    s.file.close("the file");
  });
}

std::size_t ResultFile::completed_times() const { return state_->times.size(); }
const std::filesystem::path& ResultFile::h5_path() const { return state_->h5_path; }
std::filesystem::path ResultFile::xdmf_path() const { return state_->xdmf_path(); }

}  // namespace needlefem::output
