// PETSc for the whole process: initialised once, with the options the user passed after `--`
// on the needlefem command line (e.g. -nf_ksp_type gmres -log_view), finalised when the
// owning session ends. A session created while PETSc is already running (a test harness, a
// second solver in the same process) joins it and leaves finalisation to the first owner.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <petscsys.h>

namespace needlefem {

class PetscSession {
 public:
  // `options` are PETSc options as separate words, e.g. {"-nf_ksp_type", "gmres"}.
  explicit PetscSession(const std::vector<std::string>& options = {});
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  // True if this session initialised PETSc (and will finalise it).
  bool owns_petsc() const { return owns_; }

  // Throws std::runtime_error naming the first of the user's options that no PETSc object has
  // read (a misspelt option is otherwise ignored without a word). Call once every solver has
  // been set up and used (PETSc reads some options only at the first solve).
  void require_options_used() const;

 private:
  bool owns_ = false;
  std::vector<std::string> options_;
  // PETSc keeps pointers to argc/argv for the whole run: they live here.
  std::vector<std::string> words_;
  std::vector<char*> argv_;
  int argc_ = 0;
  char** argv_pointer_ = nullptr;
};

// Throws std::runtime_error naming `what` and PETSc's message if `code` is an error.
void petsc_check(PetscErrorCode code, std::string_view what);

}  // namespace needlefem
