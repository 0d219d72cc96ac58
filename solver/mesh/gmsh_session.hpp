// RAII guard for the gmsh library state: initialise quietly, finalise on scope exit, and turn
// gmsh's std::string exceptions into std::runtime_error.
#pragma once

#include <functional>
#include <string>

namespace needlefem {

class GmshSession {
 public:
  explicit GmshSession(const std::string& model_name);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // Runs `body`, rethrowing gmsh's std::string errors as std::runtime_error("gmsh: ...").
  static void guarded(const std::function<void()>& body);

  // Runs `body` (which opens its session) on a fresh thread and rethrows what it throws. Why:
  // gmsh's high-order optimiser works in the order of its elements' memory addresses. A new thread
  // allocates from a fresh malloc arena, laid out by the meshing alone and not by what the process
  // allocated before (paths, options), so the objects in it keep their relative order from run
  // to run; large blocks mapped on their own land where address-space randomisation puts them, so
  // this alone does not make a meshing repeat bit for bit. The scene mesh does not rely on it: it
  // is meshed once and read from the mesh cache (mesh/mesh_cache.hpp).
  static void on_fresh_thread(const std::function<void()>& body);

 private:
  // gmsh's General.NumThreads sets the process's OpenMP thread count (omp_set_num_threads): the
  // solver's element loops get back what they had once the session ends.
  int solver_threads_ = 1;
};

}  // namespace needlefem
