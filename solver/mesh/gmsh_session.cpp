#include "mesh/gmsh_session.hpp"

#include <exception>
#include <stdexcept>
#include <thread>

#include <gmsh.h>
#include <omp.h>

namespace needlefem {

GmshSession::GmshSession(const std::string& model_name) : solver_threads_(omp_get_max_threads()) {
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
  // One thread and a fixed seed: the same case gives the same mesh up to the last digits of the
  // curved nodes (on_fresh_thread and mesh/mesh_cache.hpp: why and what makes runs repeat).
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

void GmshSession::on_fresh_thread(const std::function<void()>& body) {
  std::exception_ptr failure;
  std::thread mesher([&] {
    try {
      body();
    } catch (...) {
      failure = std::current_exception();
    }
  });
  mesher.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace needlefem
