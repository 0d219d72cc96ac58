#include "model/scene_model.hpp"

#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "case/case.hpp"
#include "case/schema.hpp"
#include "model/read_msh.hpp"

namespace needlefem {

namespace {

// The keys of the mesh scene that name surface groups of the mesh.
const std::vector<std::string> kGroupListKeys{"groups.fixed", "groups.roller", "groups.displaced", "groups.pressure"};

// Every group a mesh-scene key names must be a surface group (dimension 2) of the mesh.
void require_scene_groups(const Case& c, const TetMesh& mesh) {
  const auto require_surface = [&](const std::string& key, const std::string& group) {
    if (mesh.surface_faces.count(group)) return;
    if (mesh.region_index(group) >= 0)
      throw c.error(key, fmt::format("'{}' is a volume group (dimension 3) of {}; a condition needs a surface group "
                                     "(dimension 2)", group, c.path("scene.mesh_file").string()));
    std::vector<std::string> surfaces;
    for (const auto& [name, faces] : mesh.surface_faces) surfaces.push_back(name);
    throw c.error(key, fmt::format("{} has no surface group (dimension 2) named '{}'; its surface groups are: {}",
                                   c.path("scene.mesh_file").string(), group,
                                   surfaces.empty() ? std::string("none") : fmt::format("{}", fmt::join(surfaces, ", "))));
  };
  for (const auto& key : kGroupListKeys)
    for (const auto& group : c.texts(key)) require_surface(key, group);
  if (c.text("obstacle.kind") == "none") return;
  if (c.text("obstacle.group").empty())
    throw c.error("obstacle.group", fmt::format("obstacle.kind = \"{}\" needs the surface group it touches",
                                                c.text("obstacle.kind")));
  require_surface("obstacle.group", c.text("obstacle.group"));
}

// Keys that only the mesh scene reads: given in another scene, they would be ignored silently.
bool mesh_scene_key(const std::string& key) {
  for (const char* prefix : {"groups.", "displacement.", "pressure.", "obstacle.", "loading.history_"})
    if (key.rfind(prefix, 0) == 0) return true;
  return false;
}

void require_mesh_scene_keys_unused(const Case& c) {
  for (const auto& spec : case_schema())
    if (mesh_scene_key(spec.key) && c.given(spec.key))
      throw c.error(spec.key, fmt::format("applies to scene.kind = \"mesh\" only (this case's is \"{}\")",
                                          c.text("scene.kind")));
}

}  // namespace

SceneModel load_scene_model(const Case& c, const std::filesystem::path& out_dir, std::FILE* progress) {
  SceneModel scene;
  const auto user_file = c.path("scene.mesh_file");
  const bool mesh_scene = c.text("scene.kind") == "mesh";
  if (!mesh_scene) require_mesh_scene_keys_unused(c);
  if (mesh_scene && user_file.empty())
    throw c.error("scene.mesh_file", "scene.kind = \"mesh\" needs the user's gmsh mesh (.msh) or geometry (.geo)");
  if (!user_file.empty() && !std::filesystem::exists(user_file))
    throw c.error("scene.mesh_file", fmt::format("file '{}' not found", user_file.string()));
  const bool geometry_file = user_file.extension() == ".geo";
  if (geometry_file && !mesh_scene)
    throw c.error("scene.mesh_file", "a .geo is meshed for scene.kind = \"mesh\" only; give a .msh");
  if (!user_file.empty() && !geometry_file) {
    scene.msh_file = user_file;
    scene.user_mesh = true;
  } else {
    scene.msh_file = out_dir / "mesh.msh";
    scene.info = build_scene_mesh(c, scene.msh_file, progress);
  }
  if (scene.user_mesh) require_readable_msh(scene.msh_file);
  scene.mesh = read_msh(scene.msh_file);
  // The case's element order describes the run; a user mesh of the other order would silently
  // make it a run of that order instead.
  if (const long order = scene.mesh.nodes_per_tet == 10 ? 2 : 1; scene.user_mesh && order != c.integer("mesh.order"))
    throw c.error("scene.mesh_file", fmt::format("'{}' has {}-node (order {}) tetrahedra but mesh.order = {}",
                                                 scene.msh_file.string(), scene.mesh.nodes_per_tet, order,
                                                 c.integer("mesh.order")));
  if (mesh_scene) require_scene_groups(c, scene.mesh);
  scene.quality = measure_quality(scene.mesh);
  return scene;
}

void require_valid_elements(const SceneModel& scene) {
  const auto bad = scene.quality.inverted();
  if (!bad) return;
  std::string reason = fmt::format("{}: {} tetrahedra have a non-positive Jacobian determinant", scene.msh_file.string(), bad);
  // The rounding moves the cavity most at a point or edge sharper than its edge radius: that, not
  // the mesher, is then what the user can change.
  if (scene.cavity_rounding.moved_nodes > 0)
    reason += fmt::format(" after the cavity was rounded to the needle's edges (needle.edge_radius_um; it moved the "
                          "cavity by up to {:.3g} mm: a sharp point rounded with a smaller radius moves it less)",
                          scene.cavity_rounding.largest_move_m * 1e3);
  throw std::runtime_error(reason);
}

}  // namespace needlefem
