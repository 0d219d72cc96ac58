// The methods and policies: newton_matrix_factor.hpp.
#include "integration/newton_matrix_factor.hpp"

#include <exception>
#include <stdexcept>

#include "integration/ksp_solver.hpp"
#include "integration/machine_memory.hpp"
#include "integration/petsc_session.hpp"
#include "integration/sparse_cholesky.hpp"

namespace needlefem {

namespace {

// Near-incompressible tissue (K/mu up to 1e6) delays many pivots in MUMPS; its default 20 %
// workspace margin then runs out (INFOG(1) = -9). Give 100 % unless the user chose a value.
void widen_mumps_workspace(const std::string& prefix) {
  PetscBool given = PETSC_FALSE;
  petsc_check(PetscOptionsHasName(nullptr, prefix.c_str(), "-mat_mumps_icntl_14", &given), "PetscOptionsHasName");
  if (!given)
    petsc_check(PetscOptionsSetValue(nullptr, ("-" + prefix + "mat_mumps_icntl_14").c_str(), "100"),
                "PetscOptionsSetValue");
}

// The KSP's method for a linear-solver choice: "cholesky" keeps MUMPS LU for the setups that
// Cholesky does not factor.
KspMethod ksp_method(LinearSolver solver) {
  switch (solver) {
    case LinearSolver::cholesky:
    case LinearSolver::mumps:
      return KspMethod::mumps;
    case LinearSolver::gmres_gamg:
      return KspMethod::gmres_gamg;
    case LinearSolver::gmres_asm:
      return KspMethod::gmres_asm;
  }
  throw std::logic_error("ksp_method: a LinearSolver without a KspMethod");
}

NewtonMatrixFactor& factor_of(PC pc) {
  void* context = nullptr;
  petsc_check(PCShellGetContext(pc, &context), "PCShellGetContext");
  return *static_cast<NewtonMatrixFactor*>(context);
}

// PCSHELL callbacks: no exception may cross into PETSc.
PetscErrorCode set_up_shell(PC pc) noexcept {
  try {
    Mat op = nullptr, matrix = nullptr;
    petsc_check(PCGetOperators(pc, &op, &matrix), "PCGetOperators");
    if (!factor_of(pc).factor(matrix)) petsc_check(PCSetFailedReason(pc, PC_FACTOR_OTHER), "PCSetFailedReason");
    return 0;
  } catch (const std::exception&) {
    return PETSC_ERR_LIB;
  }
}

PetscErrorCode apply_shell(PC pc, Vec b, Vec x) noexcept {
  try {
    if (!factor_of(pc).solve(b, x)) petsc_check(PCSetFailedReason(pc, PC_SUBPC_ERROR), "PCSetFailedReason");
    return 0;
  } catch (const std::exception&) {
    return PETSC_ERR_LIB;
  }
}

}  // namespace

NewtonMatrixFactor::NewtonMatrixFactor(std::vector<char> prescribed, const NewtonMatrixOptions& options)
    : memory_bytes_(options.memory_bytes > 0 ? options.memory_bytes : usable_memory_bytes()),
      symmetric_preconditioner_(options.symmetric_preconditioner) {
  widen_mumps_workspace(options.prefix);
  const KspOptions ksp_options{.method = ksp_method(options.method),
                               .relative_tolerance = options.relative_tolerance,
                               .prefix = options.prefix};
  if (options.method == LinearSolver::cholesky)
    cholesky_ = std::make_unique<SparseCholesky>(
        std::move(prescribed),
        options.preconditioner_only ? SparseCholesky::Precision::single_precision
                                    : SparseCholesky::Precision::double_precision,
        options.symmetric_preconditioner ? SparseCholesky::Unsymmetric::symmetric_part
                                         : SparseCholesky::Unsymmetric::lu);
  ksp_ = std::make_unique<KspSolver>(PETSC_COMM_SELF, ksp_options);
}

NewtonMatrixFactor::~NewtonMatrixFactor() = default;

void NewtonMatrixFactor::weigh_lu_against_memory() {
  if (!cholesky_->single_precision() || symmetric_preconditioner_) return;  // no LU planned
  lu_beyond_memory_ = static_cast<double>(resident_bytes() + cholesky_->lu_extra_bytes()) >
                      kMemoryShare * static_cast<double>(memory_bytes_);
  if (lu_beyond_memory_) cholesky_->factor_symmetric_part_only();
}

bool NewtonMatrixFactor::factor_within_memory(Mat J) {
  cholesky_factored_ = cholesky_->factor(J);
  for (const double shift : kDiagonalShifts) {
    if (cholesky_factored_) break;
    ++shifted_;
    cholesky_factored_ = cholesky_->factor(J, shift);
  }
  return cholesky_factored_;
}

bool NewtonMatrixFactor::factor(Mat J) {
  if (cholesky_ && cholesky_->prepare(J)) weigh_lu_against_memory();
  if (lu_beyond_memory_) return factor_within_memory(J);
  const bool struggling = ++setups_since_accepted_step_ > kSinglePrecisionSetupsWithoutStep;
  const bool try_cholesky = cholesky_ && cholesky_skips_left_ == 0 && !(struggling && cholesky_->single_precision());
  if (cholesky_skips_left_ > 0) --cholesky_skips_left_;
  cholesky_factored_ = try_cholesky && cholesky_->factor(J);
  if (try_cholesky && !cholesky_factored_) cholesky_skips_left_ = kCholeskySkipsAfterIndefinite;
  return cholesky_factored_ || ksp_->factor(J);
}

bool NewtonMatrixFactor::solve(Vec b, Vec x) {
  if (!cholesky_factored_) return ksp_->solve(b, x);
  cholesky_->solve(b, x);
  return true;
}

void NewtonMatrixFactor::attach_to(PC pc) {
  petsc_check(PCSetType(pc, PCSHELL), "PCSetType");
  petsc_check(PCShellSetContext(pc, this), "PCShellSetContext");
  petsc_check(PCShellSetName(pc, "needlefem Newton-matrix factor"), "PCShellSetName");
  petsc_check(PCShellSetSetUp(pc, set_up_shell), "PCShellSetSetUp");
  petsc_check(PCShellSetApply(pc, apply_shell), "PCShellSetApply");
}

long NewtonMatrixFactor::iterations() const { return ksp_->iterations(); }

NewtonMatrixFactor::Factorisations NewtonMatrixFactor::factorisations() const {
  if (!cholesky_) return {.ksp = ksp_->factorizations()};
  const long lu = cholesky_->lu_factorizations();
  return {.cholesky = cholesky_->factorizations() - lu,
          .lu = lu,
          .ksp = ksp_->factorizations(),
          .shifted = shifted_,
          .lu_beyond_memory = lu_beyond_memory_,
          .factor_mb = static_cast<double>(cholesky_->cholesky_bytes() + (lu > 0 ? cholesky_->cholesky_bytes() : 0)) /
                       (1024.0 * 1024.0)};
}

}  // namespace needlefem
