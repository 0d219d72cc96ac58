#include "model/scene_model.hpp"

#include <fmt/format.h>

#include "case/case.hpp"
#include "model/read_msh.hpp"

namespace needlefem {

SceneModel load_scene_model(const Case& c, const std::filesystem::path& out_dir) {
  SceneModel scene;
  const auto user_file = c.path("scene.mesh_file");
  if (!user_file.empty()) {
    if (!std::filesystem::exists(user_file))
      throw c.error("scene.mesh_file", fmt::format("file '{}' not found", user_file.string()));
    scene.msh_file = user_file;
    scene.user_mesh = true;
  } else {
    scene.msh_file = out_dir / "mesh.msh";
    scene.info = build_scene_mesh(c, scene.msh_file);
  }
  scene.mesh = read_msh(scene.msh_file);
  scene.quality = measure_quality(scene.mesh);
  return scene;
}

void require_valid_elements(const SceneModel& scene) {
  if (const auto bad = scene.quality.inverted())
    throw std::runtime_error(fmt::format("{}: {} tetrahedra have a non-positive Jacobian determinant",
                                         scene.msh_file.string(), bad));
}

}  // namespace needlefem
