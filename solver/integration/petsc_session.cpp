#include "integration/petsc_session.hpp"

#include <stdexcept>

#include <fmt/core.h>

namespace needlefem {

PetscSession::PetscSession(const std::vector<std::string>& options) {
  PetscBool running = PETSC_FALSE;
  petsc_check(PetscInitialized(&running), "PetscInitialized");
  if (running) {
    // Joining a running PETSc: the options still take effect for objects created later.
    std::string joined;
    for (const auto& word : options) joined += (joined.empty() ? "" : " ") + word;
    petsc_check(PetscOptionsInsertString(nullptr, joined.c_str()), "PetscOptionsInsertString");
    return;
  }
  words_.reserve(options.size() + 1);
  words_.push_back("needlefem");
  words_.insert(words_.end(), options.begin(), options.end());
  for (auto& word : words_) argv_.push_back(word.data());
  argv_.push_back(nullptr);
  argc_ = static_cast<int>(words_.size());
  argv_pointer_ = argv_.data();
  petsc_check(PetscInitialize(&argc_, &argv_pointer_, nullptr, nullptr), "PetscInitialize");
  owns_ = true;
}

PetscSession::~PetscSession() {
  if (owns_) PetscFinalize();
}

void petsc_check(PetscErrorCode code, std::string_view what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw std::runtime_error(fmt::format("PETSc: {} failed (error {}: {})", what, static_cast<int>(code),
                                       text ? text : "unknown"));
}

}  // namespace needlefem
