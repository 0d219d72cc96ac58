#include "model/scene_model.hpp"

#include <exception>
#include <thread>

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
    // gmsh's high-order optimiser works in the order of its elements' memory addresses, so where
    // the allocator puts them decides the last digits of the curved nodes (up to 6e-6 mm on ~1200
    // nodes of the default tip, which frictional runs turn into other step sequences). On a
    // thread of its own gmsh allocates from a fresh malloc arena, laid out by the case alone and
    // not by what the process allocated before (paths, options); with the address space not
    // randomised (app/main.cpp) the same case then gives the same mesh bit for bit, whatever the
    // output or case path, the environment, or the command (`mesh`, `run`).
    std::exception_ptr failure;
    std::thread mesher([&] {
      try {
        scene.info = build_scene_mesh(c, scene.msh_file);
      } catch (...) {
        failure = std::current_exception();
      }
    });
    mesher.join();
    if (failure) std::rethrow_exception(failure);
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
