#include "integration/petsc_session.hpp"

#include <cctype>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/core.h>

namespace needlefem {

namespace {

// PETSc's default handler prints a dozen lines (banner, configure options, stack) for every
// error; needlefem reports each as one line instead. This handler prints nothing, keeps the
// most specific message (the one given where the error arose, e.g. "Unable to find requested
// KSP type nonsense") for petsc_check, and returns the code up the stack.
thread_local std::string g_first_message;

PetscErrorCode record_error(MPI_Comm, int, const char*, const char*, PetscErrorCode code, PetscErrorType type,
                            const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL) g_first_message = message ? message : "";
  return code;
}

}  // namespace

PetscSession::PetscSession(const std::vector<std::string>& options) : options_(options) {
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
  petsc_check(PetscPushErrorHandler(record_error, nullptr), "PetscPushErrorHandler");
}

PetscSession::~PetscSession() {
  if (!owns_) return;
  PetscPopErrorHandler();
  PetscFinalize();
}

void PetscSession::require_options_used() const {
  for (const auto& word : options_) {
    // An option is "-name"; a word like "-1e-8" or "-.5" is the value of the one before it.
    if (word.size() < 2 || word[0] != '-' || std::isdigit(static_cast<unsigned char>(word[1])) || word[1] == '.')
      continue;
    PetscBool used = PETSC_FALSE;
    petsc_check(PetscOptionsUsed(nullptr, word.c_str(), &used), "PetscOptionsUsed");
    if (!used)
      throw std::runtime_error(fmt::format("PETSc option '{}' (after --) was not used by any solver; misspelt, or "
                                           "not for this solver?", word));
  }
}

void petsc_check(PetscErrorCode code, std::string_view what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::string detail = std::exchange(g_first_message, {});
  for (char& c : detail)
    if (c == '\n') c = ' ';  // one line
  if (!detail.empty())
    throw std::runtime_error(fmt::format("PETSc: {} failed: {} (error {})", what, detail, static_cast<int>(code)));
  throw std::runtime_error(fmt::format("PETSc: {} failed (error {}: {})", what, static_cast<int>(code),
                                       text ? text : "unknown"));
}

}  // namespace needlefem
