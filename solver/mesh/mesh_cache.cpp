#include "mesh/mesh_cache.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fmt/core.h>
#include <gmsh.h>
#include <nlohmann/json.hpp>

#include "case/specs/mesh_spec.hpp"
#include "mesh/gmsh_session.hpp"
#include "wall_clock/seconds_since.hpp"

namespace needlefem {

namespace fs = std::filesystem;

namespace {

constexpr const char* kInfoSection = "$NeedlefemMeshInfo\n";
constexpr const char* kInfoSectionEnd = "\n$EndNeedlefemMeshInfo\n";

// 64-bit FNV-1a: a cache key, not a defence against chosen collisions.
class Fnv1a {
 public:
  void add(const char* data, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
  }
  void add(const std::string& text) { add(text.data(), text.size()); }
  std::string hex() const { return fmt::format("{:016x}", hash_); }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

// The hash of a file's bytes; "unreadable" when it cannot be read.
std::string file_hash(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "unreadable";
  Fnv1a hash;
  std::string buffer(1 << 20, '\0');
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
    hash.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  return hash.hex();
}

const std::string& executable_hash() {
  static const std::string hash = file_hash("/proc/self/exe");
  return hash;
}

// The gmsh library's own version (a library update without a rebuild changes it).
const std::string& gmsh_version() {
  static const std::string version = [] {
    std::string v;
    GmshSession session("needlefem-version");
    GmshSession::guarded([&] { gmsh::option::getString("General.Version", v); });
    return v;
  }();
  return version;
}

nlohmann::json to_json(const ElementSizeStats& s) {
  return {{"tets", s.tets}, {"min", s.min}, {"median", s.median}, {"max", s.max}};
}

ElementSizeStats sizes_from_json(const nlohmann::json& j) {
  return {j.at("tets").get<std::size_t>(), j.at("min").get<double>(), j.at("median").get<double>(),
          j.at("max").get<double>()};
}

// What the cache entry keeps of a meshing besides the mesh: its SceneMeshInfo.
std::string info_section(const SceneMeshInfo& info) {
  const nlohmann::json j = {{"needle_description", info.needle_description},
                            {"needle_cad_volume_m3", info.needle_cad_volume_m3},
                            {"needle_analytic_volume_m3", info.needle_analytic_volume_m3},
                            {"domain_volume_m3", info.domain_volume_m3},
                            {"seconds", info.seconds},
                            {"high_order_optimisation", info.high_order_optimisation},
                            {"grading", to_json(info.grading)}};
  // gmsh skips an unknown section line by line up to the next line starting with '$': one line
  // of JSON without a '$' (escaped inside strings, the only place one can be).
  std::string text = j.dump();
  for (std::size_t at = text.find('$'); at != std::string::npos; at = text.find('$', at))
    text.replace(at, 1, "\\u0024");
  return kInfoSection + text + kInfoSectionEnd;
}

// The SceneMeshInfo of an entry; nullopt when it has none (not written by this cache).
std::optional<SceneMeshInfo> read_info_section(const fs::path& entry) {
  std::ifstream in(entry, std::ios::binary | std::ios::ate);
  if (!in) return std::nullopt;
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 1 << 16);
  std::string text(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  if (!in.read(text.data(), tail)) return std::nullopt;
  const std::size_t begin = text.rfind(kInfoSection);
  if (begin == std::string::npos || !text.ends_with(kInfoSectionEnd)) return std::nullopt;
  const std::size_t from = begin + std::strlen(kInfoSection);
  const auto j = nlohmann::json::parse(text.substr(from, text.size() - std::strlen(kInfoSectionEnd) - from), nullptr,
                                       /*allow_exceptions=*/false);
  if (j.is_discarded()) return std::nullopt;
  SceneMeshInfo info;
  try {
    info.needle_description = j.at("needle_description").get<std::string>();
    info.needle_cad_volume_m3 = j.at("needle_cad_volume_m3").get<double>();
    info.needle_analytic_volume_m3 = j.at("needle_analytic_volume_m3").get<double>();
    info.domain_volume_m3 = j.at("domain_volume_m3").get<double>();
    info.seconds = j.at("seconds").get<double>();
    info.high_order_optimisation = j.at("high_order_optimisation").get<std::string>();
    info.grading = grading_from_json(j.at("grading"));
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
  return info;
}

// Whether gmsh wrote the file to its end (its last line closes a section, "$End..."): gmsh does
// not report a failed write, and a disk that fills up leaves the file cut short.
bool ends_a_section(const fs::path& file) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 256);
  std::string text(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  if (!in.read(text.data(), tail) || !text.ends_with("\n")) return false;
  const std::size_t line = text.rfind('\n', text.size() - 2);
  return line != std::string::npos && text.compare(line + 1, 4, "$End") == 0;
}

// write(2) all of `text` to fd; false on an error (ENOSPC, EIO, ...), errno set.
bool write_all(int fd, const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

std::string system_reason(int error) { return std::error_code(error, std::generic_category()).message(); }

// A temporary file of this process in the cache directory (removed when it goes).
class CacheTemporary {
 public:
  explicit CacheTemporary(const fs::path& entry) {
    static std::atomic<int> counter{0};
    path_ = entry.parent_path() /
            fmt::format(".{}.{}-{}.partial.msh", entry.stem().string(), ::getpid(), counter.fetch_add(1));
  }
  ~CacheTemporary() {
    std::error_code ignored;
    fs::remove(path_, ignored);
    fs::remove(path_.string() + ".partial.msh", ignored);  // gmsh's own partial file (scene_mesher.cpp)
  }
  CacheTemporary(const CacheTemporary&) = delete;
  CacheTemporary& operator=(const CacheTemporary&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Removes the temporaries that writers killed while meshing left in the directory: those older
// than a day (a meshing takes minutes) are nobody's.
void remove_stale_temporaries(const fs::path& directory) {
  const auto limit = fs::file_time_type::clock::now() - std::chrono::hours(24);
  std::error_code error;
  const fs::directory_iterator end;
  for (auto it = fs::directory_iterator(directory, error); !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    std::error_code ignored;
    if (name.starts_with(".") && name.ends_with(".partial.msh") && it->last_write_time(ignored) < limit && !ignored)
      fs::remove(it->path(), ignored);
  }
}

// Meshes the scene into a temporary file in the cache directory and publishes it as `entry`:
// "" when the entry exists afterwards (this run's or a concurrent run's: the first link wins),
// else why the directory could not take it. Errors of the case and of gmsh propagate.
std::string mesh_and_publish(const MeshSpec& spec, const fs::path& entry, std::FILE* progress) {
  std::error_code error;
  fs::create_directories(entry.parent_path(), error);
  if (error) return error.message();
  remove_stale_temporaries(entry.parent_path());
  const CacheTemporary temporary(entry);
  // Whether the directory takes a file at all, before meshing.
  if (const int probe = ::open(temporary.path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644); probe < 0)
    return system_reason(errno);
  else
    ::close(probe);
  const SceneMeshInfo info = generate_scene_mesh(spec, temporary.path(), progress);
  // gmsh does not report a failed write: the entry is published only if the mesh ends where gmsh
  // ends it and the info section that follows reached the disk.
  if (!ends_a_section(temporary.path())) return "the mesh gmsh wrote there is cut short; disk full?";
  const int fd = ::open(temporary.path().c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) return system_reason(errno);
  const bool written = write_all(fd, info_section(info)) && ::fsync(fd) == 0;
  const int write_error = errno;
  ::close(fd);
  if (!written) return system_reason(write_error);
  if (::link(temporary.path().c_str(), entry.c_str()) != 0 && errno != EEXIST) return system_reason(errno);
  return "";
}

// Copies the entry to msh_file (beside, then renamed, like the mesher's own write).
void copy_entry(const fs::path& entry, const fs::path& msh_file) {
  fs::create_directories(msh_file.parent_path().empty() ? "." : msh_file.parent_path());
  const fs::path partial = msh_file.string() + ".partial.msh";
  fs::copy_file(entry, partial, fs::copy_options::overwrite_existing);
  fs::rename(partial, msh_file);
}

void say(std::FILE* progress, const std::string& line) {
  if (!progress) return;
  fmt::print(progress, "{}\n", line);
  std::fflush(progress);
}

// Without the cache: the mesh written straight to msh_file.
SceneMeshInfo mesh_uncached(const MeshSpec& spec, const fs::path& msh_file, std::FILE* progress, const std::string& cache,
                            const std::string& key, const std::string& note) {
  SceneMeshInfo info = generate_scene_mesh(spec, msh_file, progress);
  info.cache = cache;
  info.cache_key = key;
  info.cache_note = note;
  say(progress, fmt::format("mesh: meshed in {:.1f} s: {}", info.seconds, msh_file.string()));
  return info;
}

// The canonical text the key hashes: a "key = value" line for each key of the mesh spec (every
// key the scene mesher reads) but the files handled otherwise: scene.mesh_file and
// needle.export_file bypass the cache, needle.cad_file is keyed by its bytes, and the CAD tip's
// facet keys shape the contact needle, not the scene mesh. A key the spec starts to hold must be
// added here, or a changed value would find the mesh of the old one
// (tests/mesh/check_mesh_cache_keys.py).
std::string mesh_cache_key_text(const MeshSpec& spec) {
  const NeedleTipSpec& tip = spec.needle_tip;
  const TissueCubeSpec& tissue = spec.tissue;
  std::string text;
  const auto line = [&text](const char* key, const auto& value) { text += fmt::format("{} = {}\n", key, value); };
  line("scene.kind", scene_kind_name(spec.scene_kind));
  line("tissue.cube_edge_mm", tissue.cube_edge_mm);
  line("tissue.core_width_mm", tissue.core_width_mm);
  line("tissue.core_element_mm", tissue.core_element_mm);
  line("tissue.outer_element_mm", tissue.outer_element_mm);
  line("tissue.curvature_elements", spec.curvature_elements);
  line("needle.kind", static_cast<int>(tip.kind));  // the enumerator
  line("needle.radius_mm", tip.radius_mm);
  line("needle.bevel_deg", tip.bevel_deg);
  line("needle.fillet_mm", tip.fillet_mm);
  line("needle.edge_radius_um", spec.needle_edge_radius_um);
  line("needle.shaft_mm", tip.shaft_mm);
  line("needle.head_length_mm", tip.head_length_mm);
  line("needle.neck_length_mm", tip.neck_length_mm);
  line("needle.neck_diameter_mm", tip.neck_diameter_mm);
  line("needle.point_length_mm", tip.point_length_mm);
  line("needle.mesh_volume", spec.needle_mesh_volume);
  const auto& block = spec.block_size_mm;
  line("block.size_mm", fmt::format("[{}, {}, {}]", block[0], block[1], block[2]));
  line("block.element_mm", spec.block_element_mm);
  line("mesh.order", spec.order);
  line("mesh.optimize_high_order", spec.optimize_high_order);
  line("mesh.seed", spec.seed);
  line("mesh.refinement_level", spec.refinement_level);
  // Not given, n follows the tip's keys above by a rule of this executable, both in the key.
  line("mesh.edge_elements_per_radius",
       spec.edge_elements_per_radius ? std::to_string(*spec.edge_elements_per_radius) : "by the tip");
  if (!tip.cad_file.empty()) text += fmt::format("needle.cad_file bytes = {}\n", file_hash(tip.cad_file));
  text += fmt::format("gmsh = {}\nexecutable = {}\n", gmsh_version(), executable_hash());
  return text;
}

}  // namespace

fs::path mesh_cache_directory() {
  if (const char* dir = std::getenv("NEEDLEFEM_MESH_CACHE"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/')
    return fs::path(xdg) / "needlefem" / "meshes";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "needlefem" / "meshes";
  return {};
}

std::string mesh_cache_key(const MeshSpec& spec) {
  Fnv1a hash;
  hash.add(mesh_cache_key_text(spec));
  return hash.hex();
}

SceneMeshInfo build_scene_mesh(const MeshSpec& spec, const fs::path& msh_file, std::FILE* progress) {
  const std::pair<const char*, const fs::path*> bypassing[] = {{"scene.mesh_file", &spec.scene_mesh_file},
                                                               {"needle.export_file", &spec.needle_export_file}};
  for (const auto& [key, file] : bypassing)
    if (!file->empty()) return mesh_uncached(spec, msh_file, progress, "bypassed", "", fmt::format("{} is given", key));
  const auto start = WallClock::now();
  const std::string key = mesh_cache_key(spec);
  const fs::path directory = mesh_cache_directory();
  if (directory.empty())
    return mesh_uncached(spec, msh_file, progress, "off", key,
                         "no cache directory (neither NEEDLEFEM_MESH_CACHE nor HOME set)");
  const fs::path entry = directory / (key + ".msh");
  std::error_code error;
  const bool hit = fs::exists(entry, error);
  if (!hit) {
    if (const std::string why = mesh_and_publish(spec, entry, progress); !why.empty()) {
      const std::string note = fmt::format("mesh cache {} cannot be written ({}): meshed into the output directory, "
                                           "not cached", directory.string(), why);
      say(progress, "mesh: " + note);
      return mesh_uncached(spec, msh_file, progress, "off", key, note);
    }
  }
  std::optional<SceneMeshInfo> info = read_info_section(entry);
  if (!info) {
    const std::string note = fmt::format("mesh cache entry {} has no mesh information: meshed into the output "
                                         "directory (delete the entry to cache this scene again)", entry.string());
    say(progress, "mesh: " + note);
    return mesh_uncached(spec, msh_file, progress, "off", key, note);
  }
  copy_entry(entry, msh_file);
  info->seconds = seconds_since(start);
  info->cache = hit ? "hit" : "miss";
  info->cache_key = key;
  info->cache_file = entry.string();
  say(progress, hit ? fmt::format("mesh: from the mesh cache: {} ({})", msh_file.string(), entry.string())
                    : fmt::format("mesh: meshed in {:.1f} s: {} (new in the mesh cache: {})", info->seconds,
                                  msh_file.string(), entry.string()));
  return *info;
}

nlohmann::json mesh_cache_json(const SceneMeshInfo& info) {
  // A user's .msh is read as it is: build_scene_mesh never saw it.
  if (info.cache.empty())
    return {{"source", "bypassed"}, {"key", ""}, {"file", ""}, {"note", "scene.mesh_file is given"}};
  nlohmann::json j = {{"source", info.cache}, {"key", info.cache_key}, {"file", info.cache_file}};
  if (!info.cache_note.empty()) j["note"] = info.cache_note;
  return j;
}

nlohmann::json to_json(const NeedleGrading& g) {
  return {{"refinement_level", g.refinement_level},
          {"edge_radius_mm", g.edge_radius_mm},
          {"edge_elements_per_radius", g.edge_elements_per_radius},
          {"target_mm", {{"edge", g.edge_target_mm}, {"surface", g.surface_target_mm}, {"core", g.core_mm}}},
          {"grading_distance_mm", g.grading_distance_mm},
          {"edge_curves", g.edge_curves},
          {"needle_edge_element_mm", to_json(g.edge_elements)},
          {"cavity_element_mm", to_json(g.cavity_elements)}};
}

NeedleGrading grading_from_json(const nlohmann::json& j) {
  NeedleGrading g;
  g.refinement_level = j.at("refinement_level").get<int>();
  g.edge_radius_mm = j.at("edge_radius_mm").get<double>();
  g.edge_target_mm = j.at("target_mm").at("edge").get<double>();
  g.edge_elements_per_radius = j.at("edge_elements_per_radius").get<long>();
  g.surface_target_mm = j.at("target_mm").at("surface").get<double>();
  g.core_mm = j.at("target_mm").at("core").get<double>();
  g.grading_distance_mm = j.at("grading_distance_mm").get<double>();
  g.edge_curves = j.at("edge_curves").get<int>();
  g.edge_elements = sizes_from_json(j.at("needle_edge_element_mm"));
  g.cavity_elements = sizes_from_json(j.at("cavity_element_mm"));
  return g;
}

}  // namespace needlefem
