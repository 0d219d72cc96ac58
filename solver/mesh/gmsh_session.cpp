#include "mesh/gmsh_session.hpp"

#include <stdexcept>

#include <gmsh.h>
#include <omp.h>

namespace needlefem {

GmshSession::GmshSession(const std::string& model_name) : solver_threads_(omp_get_max_threads()) {
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
  // One thread and a fixed seed: the same case gives the same mesh up to the last digits of the
  // curved nodes, which gmsh's high-order optimiser takes in the order of the elements' memory
  // addresses; runs repeat bit for bit because the scene is meshed once and read from the mesh
  // cache (mesh/mesh_cache.hpp).
  gmsh::option::setNumber("General.NumThreads", 1);
  gmsh::model::add(model_name);
}

GmshSession::~GmshSession() {
  gmsh::finalize();
  omp_set_num_threads(solver_threads_);
}

void GmshSession::guarded(const std::function<void()>& body) {
  try {
    body();
  } catch (const std::string& message) {
    throw std::runtime_error("gmsh: " + message);
  }
}

}  // namespace needlefem
