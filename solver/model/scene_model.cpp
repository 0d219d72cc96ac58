#include "model/scene_model.hpp"

#include <fmt/format.h>

#include "case/case.hpp"
#include "model/read_msh.hpp"

namespace needlefem {

SceneModel load_scene_model(const Case& c, const std::filesystem::path& out_dir, std::FILE* progress) {
  SceneModel scene;
  const auto user_file = c.path("scene.mesh_file");
  if (!user_file.empty()) {
    if (!std::filesystem::exists(user_file))
      throw c.error("scene.mesh_file", fmt::format("file '{}' not found", user_file.string()));
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
  scene.quality = measure_quality(scene.mesh);
  return scene;
}

void require_valid_elements(const SceneModel& scene) {
  if (const auto bad = scene.quality.inverted())
    throw std::runtime_error(fmt::format("{}: {} tetrahedra have a non-positive Jacobian determinant",
                                         scene.msh_file.string(), bad));
}

}  // namespace needlefem
