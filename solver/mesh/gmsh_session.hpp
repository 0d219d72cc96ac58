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
  // gmsh's high-order optimiser works in the order of its elements' memory addresses, so where
  // the allocator puts them decides the last digits of the curved nodes (up to 6e-6 mm on ~1200
  // nodes of the default brain tip, which frictional runs turn into other step sequences). A new thread allocates from a fresh malloc arena, laid
  // out by the meshing alone and not by what the process allocated before (paths, options); with
  // the address space not randomised (app/main.cpp) the same input then gives the same mesh bit
  // for bit, whatever the output or case path, the environment, or the command; not whatever
  // the build or the executable's path (gmsh keeps that path, whose length shifts the layout).
  static void on_fresh_thread(const std::function<void()>& body);

 private:
  // gmsh's General.NumThreads sets the process's OpenMP thread count (omp_set_num_threads): the
  // solver's element loops get back what they had once the session ends.
  int solver_threads_ = 1;
};

}  // namespace needlefem
