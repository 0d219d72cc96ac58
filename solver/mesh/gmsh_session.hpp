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

 private:
  // gmsh's General.NumThreads sets the process's OpenMP thread count (omp_set_num_threads): the
  // solver's element loops get back what they had once the session ends.
  int solver_threads_ = 1;
};

}  // namespace needlefem
