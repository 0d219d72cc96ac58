#include "model/scene_model.hpp"

#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "case/case_error.hpp"
#include "case/specs/boundary_spec.hpp"
#include "case/specs/contact_spec.hpp"
#include "case/specs/mesh_spec.hpp"
#include "case/specs/pressure_spec.hpp"
#include "model/read_msh.hpp"

namespace needlefem {

namespace {

// Every group a mesh-scene key names must be a surface group (dimension 2) of the mesh.
void require_scene_groups(const MeshSpec& spec, const MeshSceneGroupsSpec& groups, const PressureSpec& pressure,
                          const ObstacleSpec& obstacle, const TetMesh& mesh) {
  const std::filesystem::path& mesh_file = spec.scene_mesh_file;
  const auto require_surface = [&](const std::string& key, const std::string& group) {
    if (mesh.surface_faces.count(group)) return;
    if (mesh.region_index(group) >= 0)
      throw case_error(spec.origin, key,
                       fmt::format("'{}' is a volume group (dimension 3) of {}; a condition needs a surface group "
                                   "(dimension 2)", group, mesh_file.string()));
    std::vector<std::string> surfaces;
    for (const auto& [name, faces] : mesh.surface_faces) surfaces.push_back(name);
    throw case_error(spec.origin, key,
                     fmt::format("{} has no surface group (dimension 2) named '{}'; its surface groups are: {}",
                                 mesh_file.string(), group,
                                 surfaces.empty() ? std::string("none") : fmt::format("{}", fmt::join(surfaces, ", "))));
  };
  // The keys that name lists of surface groups, in the order their errors are reported.
  const std::pair<const char*, const std::vector<std::string>*> group_lists[] = {
      {"groups.fixed", &groups.fixed},
      {"groups.roller", &groups.roller},
      {"groups.displaced", &groups.displaced},
      {"groups.pressure", &pressure.groups}};
  for (const auto& [key, names] : group_lists)
    for (const auto& group : *names) require_surface(key, group);
  if (obstacle.kind == ObstacleKind::none) return;
  if (obstacle.group.empty())
    throw case_error(spec.origin, "obstacle.group",
                     fmt::format("obstacle.kind = \"{}\" needs the surface group it touches",
                                 obstacle_kind_name(obstacle.kind)));
  require_surface("obstacle.group", obstacle.group);
}

// The keys only a mesh scene reads, given in another scene, would be ignored silently.
void require_mesh_scene_keys_unused(const MeshSpec& spec) {
  if (spec.mesh_scene_keys_given.empty()) return;
  throw case_error(spec.origin, spec.mesh_scene_keys_given.front(),
                   fmt::format("applies to scene.kind = \"mesh\" only (this case's is \"{}\")",
                               scene_kind_name(spec.scene_kind)));
}

}  // namespace

SceneModel load_scene_model(const MeshSpec& spec, const MeshSceneGroupsSpec& groups, const PressureSpec& pressure,
                            const ObstacleSpec& obstacle, const std::filesystem::path& out_dir, std::FILE* progress) {
  SceneModel scene;
  const std::filesystem::path& user_file = spec.scene_mesh_file;
  const bool mesh_scene = spec.scene_kind == SceneKind::mesh;
  const auto file_error = [&](const std::string& reason) { return case_error(spec.origin, "scene.mesh_file", reason); };
  if (!mesh_scene) require_mesh_scene_keys_unused(spec);
  if (mesh_scene && user_file.empty())
    throw file_error("scene.kind = \"mesh\" needs the user's gmsh mesh (.msh) or geometry (.geo)");
  if (!user_file.empty() && !std::filesystem::exists(user_file))
    throw file_error(fmt::format("file '{}' not found", user_file.string()));
  const bool geometry_file = user_file.extension() == ".geo";
  if (geometry_file && !mesh_scene) throw file_error("a .geo is meshed for scene.kind = \"mesh\" only; give a .msh");
  if (!user_file.empty() && !geometry_file) {
    scene.msh_file = user_file;
    scene.user_mesh = true;
  } else {
    scene.msh_file = out_dir / "mesh.msh";
    scene.info = build_scene_mesh(spec, scene.msh_file, progress);
  }
  if (scene.user_mesh) require_readable_msh(scene.msh_file);
  scene.mesh = read_msh(scene.msh_file);
  // The case's element order describes the run; a user mesh of the other order would silently
  // make it a run of that order instead.
  if (const long order = scene.mesh.nodes_per_tet == 10 ? 2 : 1; scene.user_mesh && order != spec.order)
    throw file_error(fmt::format("'{}' has {}-node (order {}) tetrahedra but mesh.order = {}", scene.msh_file.string(),
                                 scene.mesh.nodes_per_tet, order, spec.order));
  if (mesh_scene) require_scene_groups(spec, groups, pressure, obstacle, scene.mesh);
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
